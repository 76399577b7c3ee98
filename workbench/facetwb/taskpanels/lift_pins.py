# SPDX-License-Identifier: LGPL-2.1-or-later
"""Pinned heights picked in the 3D view: the pin controls (:class:`PinEditor`, also in the
Lift plan panel) and the Pin heights panel of a Lifting (:class:`LiftPinsPanel`: Pin heights
command, or double-click the Lifting).

Click vertices of the plan or of the roof in the 3D view (Ctrl+click for more), type a
height, press *Pin selected vertices*: each vertex gets a pin (x, y of the vertex, the
height) in the table, where a height can be edited and a pin removed. The Pin heights
panel writes the Lifting's ``PinnedPoints`` at each change and re-solves the Lifting alone,
live, in one transaction: OK keeps the pins (and recomputes what is made from the roof),
Cancel puts the previous ones back. Wiring only: :mod:`facetwb.pins` resolves the selection.
"""

import FreeCAD as App
import FreeCADGui as Gui

from facetwb import pins as pin_logic
from facetwb.picked import gui_selection
from facetwb.recompute import Recomputes, cancel_live_edit, failure, up_to_date
from facetwb.taskpanels import forms
from facetwb.translation import QT_TRANSLATE_NOOP, translate

#: The open Pin heights panel, if any (for scripts and the GUI test).
active = None

TITLE = QT_TRANSLATE_NOOP("Facet", "Pin heights")

#: Colour of the markers of the pins being picked (the Lift plan panel's preview).
PREVIEW_COLOR = (0.85, 0.10, 0.55)


def _mm(value):
    """A length in mm for the table: "2500", "2437.5" (at most two decimals)."""
    return f"{float(value):.2f}".rstrip("0").rstrip(".")


def _length(value):
    from facetwb.viewproviders.markers import length_text

    return length_text(value)


class PinEditor:
    """Height field, *Pin selected vertices*, the table of pins, *Remove*, a message.

    ``plan``: the plan the pins are for; ``pins``: the pins to start with ((x, y, z) mm);
    ``changed(pins)`` is called after each change; ``preview``: draw the pins in the 3D
    view while the editor is open (the Lift plan panel: there is no Lifting to draw them
    yet)."""

    COLUMNS = (QT_TRANSLATE_NOOP("Facet", "Vertex"), "x", "y",
               QT_TRANSLATE_NOOP("Facet", "Height"))

    def __init__(self, plan, pins=(), changed=None, snap=0.0, preview=False):
        from facetwb.compat import qt_gui
        from facetwb.objects.polymesh import get_mesh

        QtGui = qt_gui()
        self.plan = plan
        self.mesh = get_mesh(plan)
        self.snap = float(snap)
        self.pins = [tuple(float(c) for c in p) for p in pins]
        self.changed = changed
        self.widget = QtGui.QWidget()
        layout = QtGui.QGridLayout(self.widget)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.setColumnStretch(1, 1)  # the height field as wide as the pane allows
        label = QtGui.QLabel(translate("Facet", "Height"))
        tip = translate("Facet", "The height the selected vertices are pinned at")
        label.setToolTip(tip)
        self.height = Gui.UiLoader().createWidget("Gui::QuantitySpinBox")
        self.height.setProperty("unit", "mm")
        self.height.setProperty("minimum", -1.0e9)
        self.height.setProperty("maximum", 1.0e9)
        self.height.setToolTip(tip)
        layout.addWidget(label, 0, 0)
        layout.addWidget(self.height, 0, 1)
        self.pin_button = QtGui.QPushButton(translate("Facet", "Pin selected vertices"))
        self.pin_button.setToolTip(translate(
            "Facet", "Pin the vertices selected in the 3D view (click near a corner of the "
            "plan or of the roof; Ctrl+click for more) at the height"))
        layout.addWidget(self.pin_button, 1, 0, 1, 2)
        # what Pin selected vertices did or why it refused, right under it: under the table
        # it was below the task pane's fold
        self.message = QtGui.QLabel()
        self.message.setWordWrap(True)
        layout.addWidget(self.message, 2, 0, 1, 2)
        # the unit above the table: in each header ("Height (mm)") the task pane's narrow
        # table cut them off
        caption = QtGui.QLabel(translate("Facet", "Pins (lengths in mm):"))
        layout.addWidget(caption, 3, 0, 1, 2)
        self.table = QtGui.QTableWidget(0, len(self.COLUMNS))
        self.table.setHorizontalHeaderLabels([translate("Facet", c) for c in self.COLUMNS])
        self.table.setToolTip(translate(
            "Facet", "The pins: the plan vertex, its x and y, and the height (double-click "
            "a height to edit it)"))
        self.table.verticalHeader().setVisible(False)
        self.table.setSelectionBehavior(QtGui.QAbstractItemView.SelectRows)
        header = self.table.horizontalHeader()
        header.setSectionResizeMode(QtGui.QHeaderView.Stretch)
        header.setSectionResizeMode(0, QtGui.QHeaderView.ResizeToContents)
        self.table.verticalHeader().setDefaultSectionSize(self.table.fontMetrics().height() + 6)
        self.table.setMinimumHeight(120)
        layout.addWidget(self.table, 4, 0, 1, 2)
        self.remove_button = QtGui.QPushButton(translate("Facet", "Remove pin"))
        self.remove_button.setToolTip(translate("Facet", "Remove the pins selected in the "
                                                         "table"))
        layout.addWidget(self.remove_button, 5, 0, 1, 2)
        self.markers = None
        if preview:
            from facetwb.viewproviders.markers import Markers

            self.markers = Markers(PREVIEW_COLOR)
            view = getattr(Gui.ActiveDocument, "ActiveView", None)
            if view is not None and hasattr(view, "getSceneGraph"):
                self.markers.show_in(view)
        self._filling = False
        self.fill()
        self.pin_button.clicked.connect(self.pin_selection)
        self.remove_button.clicked.connect(self.remove_selected)
        self.table.itemChanged.connect(self.height_edited)

    # --- the table ------------------------------------------------------------------------

    def vertices(self):
        """The plan vertex of each pin (-1: at no vertex)."""
        return pin_logic.pins_vertices(self.mesh, self.pins, self.snap)

    def fill(self):
        """The table (and the preview markers) from ``self.pins``."""
        from PySide import QtCore

        from facetwb.compat import qt_gui

        QtGui = qt_gui()
        self._filling = True
        self.table.setRowCount(len(self.pins))
        for row, ((x, y, z), vertex) in enumerate(zip(self.pins, self.vertices())):
            # in mm, the unit in the header: "2500.00 mm" in each cell of the task pane's
            # narrow table was cut to "250..."
            # x and y to the mm, which tells the vertex: a plan drawn in metres has
            # "16000.17", cut to "160..." (in full in the tooltip)
            texts = (str(vertex) if vertex >= 0 else translate("Facet", "none"),
                     f"{x:.0f}", f"{y:.0f}", _mm(z))
            for column, text in enumerate(texts):
                item = QtGui.QTableWidgetItem(text)
                item.setToolTip(_mm((x, y, z)[column - 1]) if column else text)
                flags = QtCore.Qt.ItemIsSelectable | QtCore.Qt.ItemIsEnabled
                if column == 3:
                    flags |= QtCore.Qt.ItemIsEditable
                item.setFlags(flags)
                self.table.setItem(row, column, item)
        self._filling = False
        if self.markers is not None:
            # on the plan's vertices, where they were picked (at their heights they floated
            # above the flat plan, away from the vertices clicked)
            points = self.mesh.vertices
            at = [tuple(points[v]) if v >= 0 else (x, y, 0.0)
                  for (x, y, _z), v in zip(self.pins, self.vertices())]
            self.markers.set(at, [_length(p[2]) for p in self.pins])

    def show_message(self, text, error=False):
        self.message.setText(text)
        self.message.setStyleSheet("color: #b00000" if error else "")
        if text and error:
            App.Console.PrintError(f"Facet: {translate('Facet', TITLE)}: {text}\n")

    def _set(self, pins, text):
        self.pins = pins
        self.fill()
        self.show_message(text)
        if self.changed is not None:
            self.changed(list(self.pins))

    # --- actions --------------------------------------------------------------------------

    def pin_selection(self, entries=None):
        """Pin the selected vertices (``entries``: the selection, by default the GUI's) at
        the height field's value. False (message shown) when the selection is not plan
        vertices."""
        entries = gui_selection() if entries in (None, False) else entries
        try:
            vertices = pin_logic.selected_vertices(entries, self.plan)
            height = pin_logic.check_height(self.height.property("rawValue"))
            pins = pin_logic.pin(self.mesh, self.pins, vertices, height, self.snap)
        except pin_logic.PinError as error:
            self.show_message(str(error), error=True)
            return False
        names = ", ".join(str(v) for v in vertices)
        self._set(pins, translate("Facet", "Pinned {0} {1} at {2}").format(
            translate("Facet", "vertex") if len(vertices) == 1 else
            translate("Facet", "vertices"), names, _length(height)))
        return True

    def remove_selected(self, _checked=False):
        rows = sorted({index.row() for index in self.table.selectedIndexes()})
        if not rows:
            self.show_message(translate("Facet", "Select the pins to remove in the table "
                                                 "first"), error=True)
            return False
        pins = [p for k, p in enumerate(self.pins) if k not in rows]
        self._set(pins, translate("Facet", "Removed {0} pin(s)").format(len(rows)))
        return True

    def set_height(self, row, text):
        """Height of pin ``row`` from ``text`` (a length: "3.5 m", "3500 mm"; "3500": mm).
        False (message shown, the height as it was) when it is not one."""
        try:
            height = pin_logic.height_from_text(text, translate("Facet", "Height of pin "
                                                                         "{0}").format(row + 1))
        except pin_logic.PinError as error:
            self.fill()
            self.show_message(str(error), error=True)
            return False
        x, y, _z = self.pins[row]
        pins = list(self.pins)
        pins[row] = (x, y, height)
        self._set(pins, "")
        return True

    def height_edited(self, item):
        if self._filling or item.column() != 3:
            return
        self.set_height(item.row(), item.text())

    def close(self):
        if self.markers is not None:
            self.markers.remove()


class LiftPinsPanel:
    """The pinned heights of one Lifting, applied live."""

    def __init__(self, obj):
        from facetwb.compat import qt_gui

        global active
        QtGui = qt_gui()
        self.obj = obj
        self.doc = obj.Document
        self.original = [tuple(p) for p in obj.PinnedPoints]
        self.form = QtGui.QWidget()
        self.form.setWindowTitle(translate("Facet", TITLE))
        layout = QtGui.QVBoxLayout(self.form)
        intro = QtGui.QLabel()
        intro.setWordWrap(True)
        text = translate(
            "Facet", "{0}: click vertices of the roof or of its plan in the 3D view "
            "(Ctrl+click for more), type a height and press Pin selected vertices. The roof "
            "follows at once; the other vertices are free. OK keeps the pins in one undo "
            "step; Cancel puts the previous ones back.").format(
                forms.elided(intro, obj.Label))
        if obj.Targets is not None or obj.TargetFile:
            target = obj.Targets.Label if obj.Targets is not None else obj.TargetFile
            text += " " + translate(
                "Facet", "Pins are used only without other targets: the targets are now "
                "{0} (empty Targets and TargetFile to use the pins).").format(
                    forms.elided(intro, target))
        intro.setText(text)
        layout.addWidget(intro)
        from facetwb.objects.lifting import match_snap

        # (within the plan graph's Snap when the Lifting's is 0, as the Lifting matches them)
        self.editor = PinEditor(obj.Plan, self.original, changed=self.changed,
                                snap=match_snap(obj))
        if self.original:
            self.editor.height.setProperty("rawValue", self.original[-1][2])
        layout.addWidget(self.editor.widget)
        # what is made from the roof and up to date now: the live re-solves touch it, and
        # Cancel, which puts the same roof back, leaves it so
        self.fresh = up_to_date([obj] + list(obj.InListRecursive))
        self.recomputes = Recomputes(self.doc)  # what a Recompute pressed meanwhile rebuilt
        self.doc.openTransaction(translate("Facet", TITLE))
        active = self

    def changed(self, pins):
        """Write the pins and re-solve the Lifting alone (what is made from it waits for
        OK); a failure (no pin left: no targets) is said under the table."""
        from facetwb.taskpanels.lift_mix import resolve_alone

        self.obj.PinnedPoints = [App.Vector(*p) for p in pins]
        resolve_alone(self.obj)
        if not self.obj.isValid():
            self.editor.show_message(failure(self.obj), error=True)

    # --- Gui.Control ---------------------------------------------------------------------

    def accept(self):
        if any("Touched" in o.State for o in self.obj.InListRecursive):
            from facetwb import progress

            with progress.reporting(translate("Facet", TITLE) + " ...") as reporter:
                self.doc.recompute()
            if reporter.cancelled:
                App.Console.PrintWarning(
                    "Facet: Pin heights: the pins are kept; what is made from the roof was "
                    "not recomputed (cancelled): recompute the document to update it\n")
        self.doc.commitTransaction()
        self._close()
        return True

    def reject(self):
        def restore():  # (a document without undo: the transaction put nothing back)
            if [tuple(p) for p in self.obj.PinnedPoints] == self.original:
                return False
            self.obj.PinnedPoints = [App.Vector(*p) for p in self.original]
            return True

        # the previous pins and roof as the transaction puts them back (re-solved alone only
        # when it did not, or left the Lifting in error): what is made from the roof is up
        # to date again (rebuilt from it after a Recompute pressed while the panel was open)
        cancel_live_edit(self.doc, self.obj, self.fresh, self.recomputes, restore,
                         solve_again=False)
        self._close()
        return True

    def _close(self):
        global active
        self.recomputes.stop()
        self.editor.close()
        active = None
        if Gui.ActiveDocument is not None and Gui.ActiveDocument.getInEdit() is not None:
            Gui.ActiveDocument.resetEdit()
        Gui.Control.closeDialog()

    def getStandardButtons(self):
        return forms.ok_cancel_buttons()


def edit(obj):
    """Open the Pin heights panel of the Lifting ``obj`` (a view provider's setEdit). True
    when it opened."""
    if Gui.Control.activeDialog():
        App.Console.PrintWarning(f"Facet: {obj.Label}: close the open task panel first\n")
        return False
    if obj.Plan is None:
        App.Console.PrintError(f"Facet: {obj.Label}: Plan is empty: nothing to pin\n")
        return False
    Gui.Control.showDialog(LiftPinsPanel(obj))
    return True
