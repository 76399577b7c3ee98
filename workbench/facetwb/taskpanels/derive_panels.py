# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panels that make a Facet object from the selection: Surface to control mesh,
Planarize, Lift plan, Panels, Cut sheets.

Each panel shows the parameters (defaults from the preferences, tooltips on every field).
Nothing is added to the document until OK: OK makes the objects as macro lines
(``Gui.doCommand``, so they are recorded), recomputes with a progress dialog whose Cancel
stops the solver, and commits everything as ONE undo step; Cancel in the progress dialog, an
error, or the panel's Cancel leave the document as it was. Wiring only.
"""

import FreeCAD as App
import FreeCADGui as Gui

from facet.report import count_noun
from facetwb import preferences, progress
from facetwb.recompute import failure
from facetwb.commands.macro import object_expression
from facetwb.objects.planarized import METHODS
from facetwb.taskpanels import forms
from facetwb.translation import QT_TRANSLATE_NOOP

#: The open panel, if any (for scripts and the GUI test).
active = None


class DerivePanel:
    """Base class: subclasses set UI, TITLE, FIELDS and write ``lines()``.

    FIELDS: (field name, preference name or None, choices or None, default when no
    preference). ``self.values`` holds the fields' values when ``lines`` is called.
    """

    UI = ""
    TITLE = ""
    FIELDS = ()

    def __init__(self, sources):
        global active
        self.sources = list(sources)
        self.doc = self.sources[0].Document
        self.form = forms.load(self.UI)
        self.form.setWindowTitle(progress.translate("Facet", self.TITLE))
        self.values = {}
        for name, pref, choices, default in self.FIELDS:
            value = preferences.get(pref) if pref else default
            forms.set_value(self.form, name, value, choices)
        self.setup()
        self.made = []
        active = self

    def setup(self):
        """Subclasses: fill fields that depend on the selection."""

    def lines(self):
        raise NotImplementedError

    def is_result(self, obj):
        return True

    def summary(self, obj):
        return f"{obj.Label}: made" if obj.isValid() else (
            failure(obj))

    def read(self):
        """Read every field into ``self.values``; False (message shown) when one is bad."""
        try:
            for name, pref, choices, default in self.FIELDS:
                number = isinstance(default, float) or (
                    pref is not None and preferences.DEFAULTS[pref][0] == "float")
                self.values[name] = forms.get_value(self.form, name, choices, number)
            self.check()
        except ValueError as error:
            self.show_message(str(error))
            return False
        return True

    def check(self):
        """Subclasses: raise ValueError naming a field whose value cannot work."""

    def show_message(self, text):
        forms.widget(self.form, "message").setText(text)
        if text:
            App.Console.PrintError(f"Facet: {self.TITLE}: {text}\n")

    # --- Gui.Control ---------------------------------------------------------------------

    def accept(self):
        if not self.read():
            return False
        # a source in error (a Lifting whose pins missed its plan): FreeCAD does not
        # recompute what is made from it, and Panels made an empty PanelSet reported as
        # "0 panels", Cut sheets "0 sheets ... written to"
        broken = [obj for obj in self.sources if obj is not None and not obj.isValid()]
        if broken:
            self.show_message(progress.translate(
                "Facet", "In error: {0}. Correct it and recompute it first.").format(
                    failure(broken[0])))
            return False
        doc = self.doc
        before = set(doc.Objects)
        shown = {obj.Name: obj.ViewObject.Visibility for obj in before
                 if getattr(obj, "ViewObject", None) is not None}
        doc.openTransaction(self.TITLE)
        try:
            Gui.addModule("facetwb")
            for line in self.lines():
                Gui.doCommand(line)
            with progress.reporting(progress.translate("Facet", self.TITLE) + " ...") as r:
                doc.recompute()
            if r.cancelled:
                _abort(doc, shown)
                App.Console.PrintWarning(f"Facet: {self.TITLE} cancelled; nothing changed\n")
                self._close()
                return True
            failed = [obj for obj in doc.Objects
                      if obj not in before and self.is_result(obj) and not obj.isValid()]
            if failed:
                # bad input: the document as it was, the panel open with the reason, for
                # another try (the error is in the report view too)
                message = failure(failed[0])
                _abort(doc, shown)
                self.show_message(message)
                return False
        except Exception as error:  # noqa: BLE001 - leave the document as it was
            _abort(doc, shown)
            self.show_message(f"{self.TITLE} failed: {error}")
            return False
        self.after(doc)
        doc.commitTransaction()
        self.made = [obj for obj in doc.Objects if obj not in before and self.is_result(obj)]
        for obj in self.made:
            forms.report_summary(obj, self.summary(obj))
        Gui.Selection.clearSelection()
        for obj in self.made:
            Gui.Selection.addSelection(obj)
        self._close()
        return True

    def after(self, doc):
        """Subclasses: view settings on the new objects, inside the transaction."""

    def reject(self):
        self._close()
        return True

    def _close(self):
        global active
        active = None
        Gui.Control.closeDialog()

    def getStandardButtons(self):
        return forms.ok_cancel_buttons()


def _browse_button(form, name, tip):
    """A "..." button beside the line edit ``name`` of ``form``'s grid; returns it."""
    from facetwb.compat import qt_gui

    QtGui = qt_gui()
    field = forms.widget(form, name)
    layout = form.layout()
    index = layout.indexOf(field)
    row, column, _rows, _columns = layout.getItemPosition(index)
    box = QtGui.QWidget()
    line = QtGui.QHBoxLayout(box)
    line.setContentsMargins(0, 0, 0, 0)
    layout.removeWidget(field)
    line.addWidget(field, 1)
    button = QtGui.QToolButton()
    button.setText("...")
    button.setToolTip(tip)
    line.addWidget(button)
    layout.addWidget(box, row, column)
    return button


def _abort(doc, shown):
    """Undo what a panel's OK did: the transaction, and the sources it hid (a view
    provider's Visibility is not always in the transaction)."""
    doc.abortTransaction()
    doc.recompute()
    for name, visible in shown.items():
        obj = doc.getObject(name)
        if obj is not None and obj.ViewObject.Visibility != visible:
            obj.ViewObject.Visibility = visible


def _legend_max(doc, made):
    top = preferences.get("LegendMax")
    if top > 0:
        for obj in made:
            vobj = getattr(obj, "ViewObject", None)
            if vobj is not None and "LegendMax" in vobj.PropertiesList:
                vobj.LegendMax = top


class SurfaceMeshPanel(DerivePanel):
    UI = "surface_mesh"
    TITLE = QT_TRANSLATE_NOOP("Facet", "Surface to control mesh")
    FIELDS = (("Pattern", "SurfacePattern", ["quad", "hex", "tri-quad"], None),
              ("CountU", "SurfaceCountU", None, None),
              ("CountV", "SurfaceCountV", None, None),
              ("PanelSize", "SurfacePanelSize", None, None))

    def setup(self):
        if all(obj.isDerivedFrom("Mesh::Feature") for obj in self.sources):
            forms.set_value(self.form, "Pattern", "tri-quad", self.FIELDS[0][2])

    def check(self):
        v = self.values
        if v["Pattern"] != "tri-quad" and any(o.isDerivedFrom("Mesh::Feature")
                                              for o in self.sources):
            raise ValueError("a Mesh has no (u, v) parameters: choose Paired triangles")

    def lines(self):
        v = self.values
        return [f"facetwb.make_surface_mesh({object_expression(src)}, "
                f"pattern={v['Pattern']!r}, count_u={v['CountU']}, count_v={v['CountV']}, "
                f"panel_size={v['PanelSize']!r})" for src in self.sources]

    def is_result(self, obj):
        from facetwb.objects.surfacemesh import is_surface_mesh

        return is_surface_mesh(obj)

    def summary(self, obj):
        if not obj.isValid():
            return failure(obj)
        return f"{obj.Label}: {obj.FaceCount} panels, {obj.VertexCount} vertices"

    def after(self, doc):
        _legend_max(doc, [o for o in doc.Objects if self.is_result(o)])


def check_planarize(values):
    """Raise ValueError naming a field of the Planarize form whose value cannot work."""
    if not values["Tolerance"] > 0:
        raise ValueError(f"Rel. tolerance is {values['Tolerance']!r}; it must be above 0")


class PlanarizePanel(DerivePanel):
    UI = "planarize"
    TITLE = QT_TRANSLATE_NOOP("Facet", "Planarize")
    FIELDS = (("Method", "PlanarizeMethod", METHODS, None),
              ("Tolerance", "PlanarizeTolerance", None, None),
              ("ToleranceAbs", "PlanarizeToleranceAbs", None, None),
              ("MaxIterations", "PlanarizeMaxIterations", None, None))

    def check(self):
        check_planarize(self.values)

    def lines(self):
        v = self.values
        return [f"facetwb.make_planarized({object_expression(src)}, method={v['Method']!r}, "
                f"tolerance={v['Tolerance']!r}, tolerance_abs={v['ToleranceAbs']!r}, "
                f"max_iterations={v['MaxIterations']})" for src in self.sources]

    def is_result(self, obj):
        from facetwb.objects.planarized import is_planarized

        return is_planarized(obj)

    def summary(self, obj):
        from facetwb.objects.planarized import planarize_summary

        return planarize_summary(obj)

    def after(self, doc):
        _legend_max(doc, [o for o in doc.Objects if self.is_result(o)])


class PanelsPanel(DerivePanel):
    UI = "panels"
    TITLE = QT_TRANSLATE_NOOP("Facet", "Panels")
    FIELDS = (("Thickness", "PanelThickness", None, None),
              ("Offset", "PanelOffset", ["outer", "inner", "center"], None),
              ("Gap", "PanelGap", None, None),
              ("EdgeMode", "PanelEdge", ["square", "bisector"], None),
              ("IdPrefix", "PanelIdPrefix", None, None))

    def check(self):
        if not self.values["Thickness"] > 0:
            raise ValueError("Thickness must be above 0")

    def lines(self):
        v = self.values
        return [f"facetwb.make_panelset({object_expression(src)}, "
                f"thickness={v['Thickness']!r}, offset={v['Offset']!r}, gap={v['Gap']!r}, "
                f"edge={v['EdgeMode']!r}, prefix={v['IdPrefix']!r})" for src in self.sources]

    def is_result(self, obj):
        from facetwb.objects.panelset import is_panelset

        return is_panelset(obj)

    def summary(self, obj):
        if not obj.isValid():
            return failure(obj)
        from facetwb.units import length_text

        # lengths in the unit FreeCAD shows them in (it said "within 0.5 mm" and
        # "narrowest joint 1.178 mm" beside a property editor in inches)
        text = (f"{obj.Label}: {obj.PanelCount} panels, "
                f"{count_noun(obj.PartTypeCount, 'part type')} within "
                f"{length_text(obj.PartTypeTolerance.Value)}, node deviation up to "
                f"{obj.MaxNodeDeviation.Value:.3g} degrees")
        if obj.OverlappingJoints:
            text += (f"; joints that overlap: {obj.OverlappingJoints} (a Gap of "
                     f"{length_text(obj.ClearingGap.Value, 4)} clears them)")
        elif obj.NarrowestJointPanels:
            text += f"; narrowest joint {length_text(obj.NarrowestJoint.Value, 4)}"
        if obj.NodeClashes:
            text += f"; pairs of panels that overlap at nodes: {obj.NodeClashes}"
        return text


class CutSheetsPanel(DerivePanel):
    UI = "cutsheets"
    TITLE = QT_TRANSLATE_NOOP("Facet", "Cut sheets")
    FIELDS = (("SheetWidth", "SheetWidth", None, None),
              ("SheetHeight", "SheetHeight", None, None),
              ("Margin", "SheetMargin", None, None),
              ("Spacing", "SheetSpacing", None, None),
              ("Rotations", "SheetRotations", ["90", "none", "free"], None),
              ("OutputDir", "SheetOutputDir", None, None),
              ("TextOutlines", "SheetTextOutlines", None, None))

    def setup(self):
        """A Browse button beside the output folder."""
        self.browse = _browse_button(self.form, "OutputDir", progress.translate(
            "Facet", "Choose the output folder"))
        self.browse.clicked.connect(self.choose_folder)

    def choose_folder(self):
        from facetwb.compat import qt_gui

        field = forms.widget(self.form, "OutputDir")
        folder = qt_gui().QFileDialog.getExistingDirectory(
            Gui.getMainWindow(), progress.translate("Facet", "Folder for the cut files"),
            field.text())
        if folder:
            field.setText(folder)

    def check(self):
        v = self.values
        if not (v["SheetWidth"] > 2 * v["Margin"] and v["SheetHeight"] > 2 * v["Margin"]):
            raise ValueError("the sheet margin leaves no room on the sheet")

    def lines(self):
        v = self.values
        return [f"facetwb.make_cutsheets({object_expression(src)}, "
                f"sheet=({v['SheetWidth']!r}, {v['SheetHeight']!r}), margin={v['Margin']!r}, "
                f"spacing={v['Spacing']!r}, rotations={v['Rotations']!r}, "
                f"output_dir={v['OutputDir']!r}, text_outlines={v['TextOutlines']!r})"
                for src in self.sources]

    def is_result(self, obj):
        from facetwb.objects.panelset import is_cutsheets

        return is_cutsheets(obj)

    def summary(self, obj):
        from facetwb.objects.panelset import cutsheets_summary

        return cutsheets_summary(obj)


class LiftPanel(DerivePanel):
    """sources: [plan, target or None]. The target is a surface of the document or, the
    combo box's last item, a points file (x,y,z heights at plan vertices)."""

    UI = "lifting"
    TITLE = QT_TRANSLATE_NOOP("Facet", "Lift plan")
    FIELDS = (("TargetFile", None, None, ""),
              ("Snap", None, None, 0.0))

    def setup(self):
        from facetwb.conversion import has_surface
        from facetwb.objects.polymesh import is_polymesh

        self.plan = self.sources[0]
        wanted = self.sources[1] if len(self.sources) > 1 else None
        self.targets = [o for o in self.doc.Objects
                        if o is not self.plan and (has_surface(o) or (
                            is_polymesh(o) and o is not self.plan))]
        combo = forms.widget(self.form, "Target")
        # as wide as the pane allows, not as its longest label: "Points file (x, y, z)"
        # or a designer's long label widened the panel past the task pane
        combo.setSizeAdjustPolicy(combo.AdjustToMinimumContentsLengthWithIcon)
        combo.setMinimumContentsLength(8)
        for obj in self.targets:
            combo.addItem(obj.Label)
        # a table of heights (examples/roof_heights.csv): with only the plan selected the
        # command was inactive, and the panel offered surfaces only
        combo.addItem(progress.translate("Facet", "Points file (x, y, z)"))
        # heights typed at vertices picked in the 3D view (PinnedPoints): before, only
        # through the property editor or the Python console
        combo.addItem(progress.translate("Facet", "Pinned heights (pick vertices)"))
        from facetwb.taskpanels.lift_pins import PinEditor

        # (a pin added: the message asking for one no longer holds)
        self.pins = PinEditor(self.plan, preview=True,
                              changed=lambda _pins: self.show_message(""))
        self.form.layout().addWidget(self.pins.widget, self.form.layout().rowCount(), 0, 1, 2)
        if wanted in self.targets:
            combo.setCurrentIndex(self.targets.index(wanted))
        else:
            combo.setCurrentIndex(len(self.targets))
        self.browse = _browse_button(self.form, "TargetFile", progress.translate(
            "Facet", "Choose the points file"))
        self.browse.clicked.connect(self.choose_file)
        # a path typed or pasted: the last OK's "choose a points file" no longer holds
        forms.widget(self.form, "TargetFile").textChanged.connect(
            lambda *_: self.show_message(""))
        combo.currentIndexChanged.connect(self.target_changed)
        self.target_changed()

    def from_file(self):
        return forms.widget(self.form, "Target").currentIndex() == len(self.targets)

    def from_pins(self):
        return forms.widget(self.form, "Target").currentIndex() == len(self.targets) + 1

    def target_changed(self, *_args):
        self.show_message("")
        for name in ("TargetFile", "label_TargetFile"):
            forms.widget(self.form, name).setEnabled(self.from_file())
        self.browse.setEnabled(self.from_file())
        self.pins.widget.setVisible(self.from_pins())

    def choose_file(self):
        from facetwb.commands.lift import TARGET_FILE_FILTER
        from facetwb.compat import qt_gui

        field = forms.widget(self.form, "TargetFile")
        path, _ = qt_gui().QFileDialog.getOpenFileName(
            Gui.getMainWindow(), progress.translate("Facet", "Target heights"), field.text(),
            TARGET_FILE_FILTER)
        if path:
            field.setText(path)  # (clears the message)

    def check(self):
        import os

        if self.from_file():
            path = self.values["TargetFile"]
            if not path:
                raise ValueError("choose a points file, or a target surface")
            if not os.path.isfile(path):
                raise ValueError(f"{path}: there is no such file")
        if self.from_pins() and not self.pins.pins:
            raise ValueError("no pinned height yet: click plan vertices in the 3D view, type "
                             "a height and press Pin selected vertices")

    def lines(self):
        if self.from_file():
            target = f"target_file={self.values['TargetFile']!r}"
        elif self.from_pins():
            target = "pins=[{}]".format(", ".join(
                f"({x!r}, {y!r}, {z!r})" for x, y, z in self.pins.pins))
        else:
            chosen = self.targets[forms.widget(self.form, "Target").currentIndex()]
            target = f"targets={object_expression(chosen)}"
        lines = [f"lifting = facetwb.make_lifting({object_expression(self.plan)}, {target})"]
        if self.values["Snap"]:
            lines.append(f"lifting.Snap = {self.values['Snap']!r}")
        return lines

    def _close(self):
        self.pins.close()
        super()._close()

    def is_result(self, obj):
        from facetwb.objects.lifting import is_lifting

        return is_lifting(obj)

    def summary(self, obj):
        from facetwb.objects.lifting import lifting_summary

        return lifting_summary(obj)
