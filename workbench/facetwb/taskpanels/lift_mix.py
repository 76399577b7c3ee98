# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel of a Lifting: sliders that add the smoothest non-planar liftings (eigen-liftings)
to the optimal one, and a vertex whose height can be dragged (its fundamental lifting: the
rest of the roof follows), with the result following live. Every mix keeps every face exactly planar:
the liftings form a linear space. Wiring only: the basis comes from ``facet.lift``.

The sliders write the Lifting's ``Mix`` and ``Drags`` properties and recompute it; what is
made from it (panels, cut sheets) is recomputed at OK, which keeps the mix (one undo step).
Cancel restores the previous one.
"""

import FreeCAD as App
import FreeCADGui as Gui

from facetwb.recompute import Recomputes, cancel_live_edit, up_to_date
from facetwb.taskpanels import forms
from facetwb.translation import translate

#: Sliders shown (fewer when the plan has fewer non-planar liftings).
MAX_SLIDERS = 8
#: Slider positions each side of 0.
STEPS = 100

#: The open panel, if any (for scripts and the GUI test).
active = None

#: Colour of the marker on the vertex the Raise vertex row moves.
RAISE_COLOR = (1.00, 0.45, 0.00)


class LiftMixPanel:
    """Gui.Control task panel for one Lifting object."""

    def __init__(self, obj):
        from facetwb.compat import qt_gui
        from facetwb.objects.polymesh import get_mesh

        from PySide import QtCore  # FreeCAD's PySide shim, 0.20 and 1.x

        QtGui = qt_gui()
        self.obj = obj
        self.original = list(obj.Mix)
        #: Why there is nothing to shape (the Lifting failed or was never solved), or None.
        #: Such a Lifting's Dimension is 0, or that of its last good solve: the panel said
        #: "this plan admits only planes", or offered sliders that could only fail.
        self.failed = _not_lifted(obj)
        #: Full slider travel: a quarter of the plan's size, in mm.
        self.range = 1.0
        self.count = 0
        if self.failed is None:
            xy = get_mesh(obj.Plan).vertices[:, :2]
            self.range = 0.25 * (float((xy.max(axis=0) - xy.min(axis=0)).max()) or 1.0)
            self.count = max(0, min(MAX_SLIDERS, int(obj.Dimension) - 3))
        self.form = QtGui.QWidget()
        # the object's name in the intro, which wraps: in the title (which does not) a label
        # such as "Roof over the north wing lifted" widened the panel past the task pane,
        # OK's neighbour Cancel and the slider values cut off at the right
        self.form.setWindowTitle(translate("Facet", "Shape lifting"))
        layout = QtGui.QVBoxLayout(self.form)
        intro = QtGui.QLabel()
        name = forms.elided(intro, obj.Label)
        if self.failed is not None:
            intro.setText(translate(
                "Facet", "{0}: there is no lifting to shape: {1}. Fix it and recompute "
                "first.").format(name, self.failed))
        elif self.count == 0:
            intro.setText(translate(
                "Facet", "{0}: this plan admits only planes: there is nothing to mix. Change "
                "the drawing (or lift it with moved vertices) to get more shapes.").format(name))
        elif int(obj.Dimension) == 4:
            # ("the plan admits 1 non-planar liftings": liftings other than one plane, read
            # as faces that are not planar beside "every face stays exactly planar")
            intro.setText(translate(
                "Facet", "{0}: besides tilting it as one plane, the plan admits one other "
                "shape of the roof with planar faces. The slider adds it; every face stays "
                "exactly planar.").format(name))
        else:
            intro.setText(translate(
                "Facet", "{0}: besides tilting it as one plane, the plan admits {1} "
                "other shapes of the roof with planar faces. Each slider adds one "
                "(smoothest first); every face stays exactly planar.").format(
                    name, int(obj.Dimension) - 3))
        # wrapped: on one line it made the panel 479 px wide, and the task pane (258 px)
        # cut it and the value labels off (GUI review)
        intro.setWordWrap(True)
        layout.addWidget(intro)
        # how far the roof is from its targets: the pin markers stay at the pinned heights
        # while the sliders move the roof away from them, and nothing said how far
        self.distance = QtGui.QLabel()
        self.distance.setObjectName("distance")
        self.distance.setWordWrap(True)
        layout.addWidget(self.distance)
        self.sliders = []
        self.labels = []
        values = list(self.original) + [0.0] * self.count
        # each slider on a line of its own under its name and value: beside them it was 66
        # to 99 px long in the task pane, and shrank as its value label grew while dragged
        for k in range(self.count):
            row = QtGui.QHBoxLayout()
            row.addWidget(QtGui.QLabel(translate("Facet", "Lifting {0}").format(k + 1)))
            row.addStretch(1)
            label = self._value_label()
            row.addWidget(label)
            layout.addLayout(row)
            slider = QtGui.QSlider(QtCore.Qt.Horizontal)
            slider.setRange(-STEPS, STEPS)
            slider.setToolTip(translate(
                "Facet", "Height of this lifting at its peak; the faces stay planar"))
            slider.setValue(int(round(values[k] / self.range * STEPS)))
            layout.addWidget(slider)
            self.sliders.append(slider)
            self.labels.append(label)
            slider.valueChanged.connect(self.changed)
        # Dragging one vertex: its fundamental lifting (the rest of the roof follows).
        self.original_drags = list(obj.Drags)
        self.points = [] if self.failed else [(p.x, p.y) for p in obj.Plan.Points]
        drag_row = QtGui.QHBoxLayout()
        drag_row.addWidget(QtGui.QLabel(translate("Facet", "Raise vertex")))
        self.vertex = QtGui.QSpinBox()
        self.vertex.setToolTip(translate("Facet", "The plan vertex to raise or lower"))
        self.vertex.setRange(0, max(0, len(self.points) - 1))
        drag_row.addWidget(self.vertex)
        drag_row.addStretch(1)
        # (sized to its text: beside the label and the spin box, a width for the widest
        # value made the panel 3 px wider than the pane)
        self.drag_label = QtGui.QLabel()
        self.drag_label.setAlignment(QtCore.Qt.AlignRight | QtCore.Qt.AlignVCenter)
        drag_row.addWidget(self.drag_label)
        layout.addLayout(drag_row)
        # the height slider on a line of its own: beside the label and the vertex box it
        # was squeezed to 32 px in the task pane, too short to drag
        self.drag = QtGui.QSlider(QtCore.Qt.Horizontal)
        self.drag.setRange(-STEPS, STEPS)
        self.drag.setToolTip(translate(
            "Facet", "How far the vertex moves; the rest of the roof follows, every face "
            "planar"))
        layout.addWidget(self.drag)
        self.drags = {}
        for d in self.original_drags:
            self.drags[(d.x, d.y)] = d.z
        for widget in (self.vertex, self.drag):
            widget.setEnabled(bool(self.points))
        self.vertex.valueChanged.connect(self.vertex_changed)
        self.drag.valueChanged.connect(self.drag_changed)
        # which vertex the spin box's number is: a marker on it in the 3D view
        from facetwb.viewproviders.markers import RAISE_STYLE, Markers

        self.marker = Markers(RAISE_COLOR, RAISE_STYLE)
        view = getattr(Gui.ActiveDocument, "ActiveView", None)
        if self.points and view is not None and hasattr(view, "getSceneGraph"):
            self.marker.show_in(view)
        self.vertex_changed()
        self._show_values()
        self._show_distance()
        # the Lifting and what is made from it that are up to date now: the sliders'
        # recomputes touch them, and Cancel, which puts the same roof back, leaves them so
        self.fresh = up_to_date([obj] + list(obj.InListRecursive))
        self.recomputes = Recomputes(obj.Document)  # what a Recompute pressed meanwhile rebuilt
        #: Visibility before the panel changed it, by object name (:meth:`_show_roof`).
        self.views = {}
        self.obj.Document.openTransaction("Shape lifting")
        global active
        active = self

    def _value_label(self):
        """A label as wide as the widest value it shows (right-aligned: the value does not
        jump about as it grows)."""
        from facetwb.compat import qt_gui
        from PySide import QtCore

        label = qt_gui().QLabel()
        widest = App.Units.Quantity(-self.range, App.Units.Length).UserString
        label.setMinimumWidth(label.fontMetrics().boundingRect(widest).width() + 4)
        label.setAlignment(QtCore.Qt.AlignRight | QtCore.Qt.AlignVCenter)
        return label

    def mix(self):
        return [s.value() / STEPS * self.range for s in self.sliders]

    def _show_values(self):
        for label, value in zip(self.labels, self.mix()):
            label.setText(App.Units.Quantity(value, App.Units.Length).UserString)

    def _mark_vertex(self):
        """The raise marker on the chosen vertex of the roof, labelled with its number (a
        spin box number alone did not tell which vertex it was)."""
        points = self.obj.Points
        v = self.vertex.value()
        if self.points and 0 <= v < len(points):
            p = points[v]
            self.marker.set([(p.x, p.y, p.z)], [translate("Facet", "vertex {0}").format(v)])
        else:
            self.marker.clear()

    def vertex_changed(self, _value=None):
        self._mark_vertex()
        key = self.points[self.vertex.value()] if self.points else None
        self.drag.blockSignals(True)
        self.drag.setValue(int(round(self.drags.get(key, 0.0) / self.range * STEPS)))
        self.drag.blockSignals(False)
        self._show_drag()

    def _show_distance(self):
        text = "" if self.failed is not None else target_distance_text(self.obj)
        self.distance.setText(text)
        self.distance.setVisible(bool(text))

    def _show_drag(self):
        value = self.drag.value() / STEPS * self.range
        self.drag_label.setText(App.Units.Quantity(value, App.Units.Length).UserString)

    def drag_changed(self, _value=None):
        if not self.points:
            return
        self._show_drag()
        self.drags[self.points[self.vertex.value()]] = self.drag.value() / STEPS * self.range
        self.obj.Drags = [App.Vector(x, y, dz) for (x, y), dz in self.drags.items() if dz]
        self._follow()

    def changed(self, _value=None):
        self._show_values()
        self.obj.Mix = self.mix()
        self._follow()

    def _follow(self):
        """Re-solve the Lifting alone, live (:func:`resolve_alone`); the raise marker
        follows the roof."""
        resolve_alone(self.obj, update=False)
        self._show_roof()
        self._mark_vertex()
        self._show_distance()
        Gui.updateGui()

    def _show_roof(self):
        """While the sliders move: the Lifting shown, what waits for OK hidden (the panels
        usually hide the Lifting, and the roof would not seem to move). :meth:`_close` puts
        the views back."""
        if self.views:
            return
        for o in [self.obj] + list(self.obj.InListRecursive):
            view = getattr(o, "ViewObject", None)
            if view is not None and bool(view.Visibility) != (o is self.obj):
                self.views[o.Name] = bool(view.Visibility)
                view.Visibility = o is self.obj

    def _close(self):
        global active
        self.recomputes.stop()
        self.marker.remove()
        for name, visible in self.views.items():
            o = self.obj.Document.getObject(name)
            if o is not None and getattr(o, "ViewObject", None) is not None:
                o.ViewObject.Visibility = visible
        self.views = {}
        active = None
        if Gui.ActiveDocument is not None and Gui.ActiveDocument.getInEdit() is not None:
            Gui.ActiveDocument.resetEdit()  # (opened by a double-click)
        Gui.Control.closeDialog()

    def accept(self):
        doc = self.obj.Document
        if any("Touched" in o.State for o in self.obj.InListRecursive):
            from facetwb import progress

            # the panels and cut sheets made from the roof, in the same undo step
            with progress.reporting(translate("Facet", "Shape lifting") + " ...") as reporter:
                doc.recompute()
            if reporter.cancelled:
                App.Console.PrintWarning(
                    "Facet: Shape lifting: the roof is kept; what is made from it was not "
                    "recomputed (cancelled): recompute the document to update it\n")
        doc.commitTransaction()
        self._close()
        return True

    def reject(self):
        def restore():  # (a document without undo: the transaction put nothing back)
            if list(self.obj.Mix) == self.original and list(self.obj.Drags) == self.original_drags:
                return False
            self.obj.Mix = self.original
            self.obj.Drags = self.original_drags
            return True

        # the previous Mix, Drags and roof as the transaction puts them back; what is made
        # from the roof is up to date again, or rebuilt from it after a Recompute pressed
        # while the panel was open (the transaction puts their properties back, not the
        # PanelSet's panels that cut sheets reuse nor the files written)
        cancel_live_edit(self.obj.Document, self.obj, self.fresh, self.recomputes, restore,
                         solve_again=False)
        self._close()
        return True

    def getStandardButtons(self):
        return forms.ok_cancel_buttons()


def edit(obj):
    """Open the Shape lifting panel of the Lifting ``obj`` (the command, or a double-click
    on a Lifting that follows a surface or points). True when it opened."""
    if Gui.Control.activeDialog():
        App.Console.PrintWarning(f"Facet: {obj.Label}: close the open task panel first\n")
        return False
    Gui.Control.showDialog(LiftMixPanel(obj))
    return True


def resolve_alone(obj, update=True):
    """Re-solve the Lifting ``obj`` alone, live, and mark what is made from it for
    recompute. What is made from it waits for OK: recomputed at every slider step, 5,000
    panels made each step take 10 s, and a drag across the slider minutes."""
    obj.recompute()
    if obj.isValid():
        obj.purgeTouched()
    for dependent in obj.InListRecursive:
        dependent.touch()
    if update:
        Gui.updateGui()


def target_distance_text(obj):
    """How far the roof ``obj`` is from its targets (pins, surface or points), as the Shape
    lifting panel says it: largest distance, where, and RMS (or that it is in error)."""
    from facetwb.objects.lifting import pins_in_use

    if not obj.isValid():
        return translate("Facet", "The roof is in error: no distance from its targets.")
    if pins_in_use(obj):
        text = translate("Facet", "Roof to its pins (the markers): {0} at most (vertex {1}), "
                                  "{2} RMS.")
    else:
        text = translate("Facet", "Roof to its targets: {0} at most (vertex {1}), {2} RMS.")
    return (text.format(obj.TargetMax.UserString, int(obj.TargetMaxVertex),
                        obj.TargetRms.UserString) + " "
            + translate("Facet", "With every slider at 0 and no vertex raised the roof is "
                                 "closest to them."))


def _not_lifted(obj):
    """Why ``obj`` holds no lifting to shape (one line), or None when it holds one."""
    from facetwb.recompute import failure

    if not obj.isValid():
        text = failure(obj)
        return text[len(obj.Label) + 2:] if text.startswith(obj.Label + ": ") else text
    if obj.Plan is None or int(obj.Dimension) < 3 or not obj.Points:
        return "it is not lifted yet"
    return None
