# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel of an existing Planarized object (double-click it, or Edit in its context menu).

The Planarize form, filled from the object's properties. Every change of a field is set on
the object at once, and :mod:`facetwb.live_parameters` re-solves it shortly after (debounced),
so the planar result follows while the designer types or spins a box. Below it, the held
vertices: click corners of the mesh in the 3D view (Ctrl+click for more) and press Hold
selected (FixedVertices; :mod:`facetwb.fixed_vertices`), Free selected or Free all; held
vertices show as magenta squares, the selected ones framed in black. All of it is one
transaction: OK keeps the changes as one undo step, Cancel puts the previous values and the
previous result back. Wiring only.
"""

import FreeCAD as App
import FreeCADGui as Gui

from facetwb import fixed_vertices
from facetwb.picked import gui_selection
from facetwb.taskpanels import forms
from facetwb.objects.planarized import METHODS, planarize_summary
from facetwb.recompute import Recomputes, cancel_live_edit, up_to_date
from facetwb.taskpanels.derive_panels import check_planarize
from facetwb.translation import QT_TRANSLATE_NOOP, translate

#: The open panel, if any (for scripts and the GUI test).
active = None

TITLE = QT_TRANSLATE_NOOP("Facet", "Planarize")

#: (field of planarize.ui = property of the object, choices of a combo box)
FIELDS = (("Method", METHODS), ("Tolerance", None), ("ToleranceAbs", None),
          ("MaxIterations", None))


def _property_value(obj, name):
    value = getattr(obj, name)
    return value.Value if hasattr(value, "Value") else value


class PlanarizeEditPanel:
    """The solver parameters of one Planarized object, applied live."""

    def __init__(self, obj):
        global active
        self.obj = obj
        self.doc = obj.Document
        self.form = forms.load("planarize")
        # the object's name in the note, which wraps: in the title (which does not) a label
        # such as "Control mesh planarized" widened the panel past the task pane, its
        # fields cut off at the right
        self.form.setWindowTitle(translate("Facet", TITLE))
        note = forms.widget(self.form, "note")
        note.setText(translate(
            "Facet", "{0}: every change re-solves it at once. OK keeps the changes in one "
                     "undo step; Cancel puts the previous values and result back.").format(
            forms.elided(note, obj.Label)))
        for name, choices in FIELDS:
            forms.set_value(self.form, name, _property_value(obj, name), choices)
        # what is made from the result (panels, cut sheets) and up to date now: a live
        # re-solve touches it, and Cancel, which puts the same result back, leaves it so
        self.fresh = up_to_date(obj.InListRecursive)
        self.recomputes = Recomputes(self.doc)  # what a Recompute pressed meanwhile rebuilt
        self.doc.openTransaction(f"Edit {obj.Label}")
        for name, _choices in FIELDS:
            forms.on_change(self.form, name, self.changed)
        self.form = self._with_held(self.form)
        self.show_held()
        self.observing = False
        try:
            Gui.Selection.addObserver(self)
            self.observing = True
        except Exception:  # noqa: BLE001 - no selection observer: the buttons still work
            pass
        self.show_selected()
        active = self

    def _with_held(self, planarize):
        """The panel's widget: the Planarize form, then the Held vertices group (a hint, the
        buttons, the count and a message line)."""
        from facetwb.compat import qt_gui

        qt = qt_gui()
        form = qt.QWidget()
        form.setObjectName("PlanarizeEdit")
        form.setWindowTitle(planarize.windowTitle())
        column = qt.QVBoxLayout(form)
        column.setContentsMargins(0, 0, 0, 0)
        column.addWidget(planarize)
        group = qt.QGroupBox(translate("Facet", "Held vertices"))
        group.setObjectName("HeldVertices")
        column.addWidget(group)
        layout = qt.QGridLayout(group)
        hint = qt.QLabel(translate(
            "Facet", "Click corners of the mesh in the 3D view (Ctrl+click for more) to hold "
                     "them in place while it is planarized (FixedVertices). Held: magenta "
                     "squares; selected: framed in black."))
        hint.setWordWrap(True)
        layout.addWidget(hint, 0, 0, 1, 2)
        self.buttons = {}
        for row, column, name, text, tip, action in (
                (1, 0, "HoldSelected", translate("Facet", "Hold selected"),
                 translate("Facet", "Hold the vertices selected in the 3D view in place"),
                 self.hold_selected),
                (1, 1, "FreeSelected", translate("Facet", "Free selected"),
                 translate("Facet", "Let the selected held vertices move again"),
                 self.free_selected),
                (2, 1, "FreeAll", translate("Facet", "Free all"),
                 translate("Facet", "Let every held vertex move again"), self.free_all)):
            button = qt.QPushButton(text)
            button.setObjectName(name)
            button.setToolTip(tip)
            button.clicked.connect(action)
            layout.addWidget(button, row, column)
            self.buttons[name] = button
        self.held_label = qt.QLabel()
        self.held_label.setObjectName("HeldCount")
        layout.addWidget(self.held_label, 2, 0)
        self.selected_label = qt.QLabel()
        self.selected_label.setObjectName("SelectedCount")
        layout.addWidget(self.selected_label, 3, 0, 1, 2)
        self.held_message = qt.QLabel()
        self.held_message.setObjectName("HeldMessage")
        self.held_message.setWordWrap(True)
        layout.addWidget(self.held_message, 4, 0, 1, 2)
        return form

    # --- held vertices --------------------------------------------------------------------

    def _selected(self):
        """The selected vertices' indices; a SelectionError says what else is selected."""
        return fixed_vertices.selected_vertices(self.obj, gui_selection())

    def _on_selected(self, act):
        """``act(vertices)`` on the selected vertices, its text in the panel's message line;
        False (the message says what else is selected) when they are not vertices."""
        try:
            vertices = self._selected()
        except fixed_vertices.SelectionError as error:
            self.held_message.setText(str(error))
            return False
        self.held_message.setText(act(vertices))
        self.show_held()
        return True

    def hold_selected(self):
        """Hold selected: FixedVertices gains the selected vertices (the result re-solves)."""
        def hold(vertices):
            added = fixed_vertices.hold(self.obj, vertices)
            return translate("Facet", "{0} of the {1} selected held now").format(
                added, len(vertices)) if added < len(vertices) else ""

        return self._on_selected(hold)

    def free_selected(self):
        """Free selected: the selected vertices leave FixedVertices."""
        def free(vertices):
            freed = fixed_vertices.free(self.obj, vertices)
            return "" if freed else translate("Facet", "None of the selected vertices was held")

        return self._on_selected(free)

    def free_all(self):
        fixed_vertices.free(self.obj)
        self.held_message.setText("")
        self.show_held()
        return True

    def show_held(self):
        self.held_label.setText(fixed_vertices.held_text(self.obj))

    def show_selected(self):
        """The count of selected vertices, and their markers."""
        try:
            vertices = self._selected()
        except fixed_vertices.SelectionError:
            vertices = []
        count = len(vertices)
        self.selected_label.setText(
            translate("Facet", "No vertex selected") if count == 0 else
            translate("Facet", "1 vertex selected") if count == 1 else
            translate("Facet", "{0} vertices selected").format(count))
        self._mark_selected(vertices)

    def _mark_selected(self, vertices):
        proxy = getattr(getattr(self.obj, "ViewObject", None), "Proxy", None)
        if hasattr(proxy, "redraw_markers"):
            proxy.redraw_markers(self.obj, selected=vertices)

    # Gui.Selection observer: the count and markers follow the selection
    def addSelection(self, *_args):  # noqa: N802 - FreeCAD's names
        self.show_selected()

    def removeSelection(self, *_args):  # noqa: N802
        self.show_selected()

    def setSelection(self, *_args):  # noqa: N802
        self.show_selected()

    def clearSelection(self, *_args):  # noqa: N802
        self.show_selected()

    def read(self):
        """{property: value} from the fields; a ValueError names a field that cannot work."""
        values = {name: forms.get_value(self.form, name, choices, name == "Tolerance")
                  for name, choices in FIELDS}
        check_planarize(values)
        return values

    def changed(self, *_args):
        """Set the fields' values on the object (the object then re-solves by itself)."""
        try:
            values = self.read()
        except ValueError as error:
            self.show_message(str(error))
            return False
        self.show_message("")
        for name, value in values.items():
            if _property_value(self.obj, name) != value:
                setattr(self.obj, name, value)
        return True

    def show_message(self, text):
        forms.widget(self.form, "message").setText(text)

    # --- Gui.Control ---------------------------------------------------------------------

    def accept(self):
        if not self.changed():
            return False
        if "Touched" in self.obj.State:
            self.doc.recompute([self.obj])
        self.doc.commitTransaction()
        # the result the edit ends with (the live re-solves said nothing in the report view)
        forms.report_summary(self.obj, planarize_summary(self.obj))
        self._close()
        return True

    def reject(self):
        # the previous values, points and planarity; what is made from the result is up
        # to date again, or rebuilt from it after a Recompute pressed while the panel was
        # open
        cancel_live_edit(self.doc, self.obj, self.fresh, self.recomputes)
        from facetwb import live_parameters

        live_parameters.forget(self.obj)  # the values put back are solved
        self._close()
        return True

    def _close(self):
        global active
        active = None
        self.recomputes.stop()
        if self.observing:
            Gui.Selection.removeObserver(self)
            self.observing = False
        try:
            self._mark_selected([])
        except Exception:  # noqa: BLE001 - the object was deleted with the panel open
            pass
        if Gui.ActiveDocument is not None:
            Gui.ActiveDocument.resetEdit()
        Gui.Control.closeDialog()

    def getStandardButtons(self):
        return forms.ok_cancel_buttons()


def edit(obj):
    """Open the panel of ``obj`` (a view provider's setEdit). True when it opened."""
    if Gui.Control.activeDialog():
        App.Console.PrintWarning(f"Facet: {obj.Label}: close the open task panel first\n")
        return False
    Gui.Control.showDialog(PlanarizeEditPanel(obj))
    return True
