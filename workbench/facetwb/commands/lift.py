# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet_PlanGraph (a plan graph from a drawing) and Facet_Lift (lift a plan to planar faces
close to a target surface)."""

import FreeCAD as App
import FreeCADGui as Gui

from facetwb import paths
from facetwb.translation import QT_TRANSLATE_NOOP
from facetwb.commands.macro import object_expression, run_as_macro

PLAN_FILE_FILTER = "Plan drawings (*.dxf *.csv *.obj *.off *.json)"
TARGET_FILE_FILTER = "Target heights (*.csv *.tsv *.txt *.obj *.off *.json)"


def _has_edges(obj):
    from facetwb.conversion import shape_has
    from facetwb.objects.polymesh import is_polymesh

    return not is_polymesh(obj) and shape_has(obj, "Edges")


def _selected_lifting():
    """The one Lifting selected (its vertices picked in the 3D view count), or None."""
    from facetwb.objects.lifting import is_lifting

    selection = Gui.Selection.getSelection()
    return selection[0] if len(selection) == 1 and is_lifting(selection[0]) else None


class CommandPlanGraph:
    """A PlanGraph from the selected Sketches, Draft wires or Part edges, or from a file."""

    def GetResources(self):
        return {
            "Pixmap": paths.icon_path("Facet_PlanGraph"),
            "MenuText": QT_TRANSLATE_NOOP("Facet_PlanGraph", "Plan graph"),
            "ToolTip": QT_TRANSLATE_NOOP(
                "Facet_PlanGraph",
                "Make a plan graph (faces seen from above) from the selected Sketches, "
                "Draft wires or Part edges, or, with nothing selected, from a drawing "
                "file (.dxf, .csv, plan mesh). Crossings are split, dangling edges "
                "dropped. It follows changes of the drawing."),
        }

    def IsActive(self):
        # inactive while a task panel is open: its macro commits the panel's transaction
        return App.ActiveDocument is not None and Gui.Control.activeDialog() is False

    def Activated(self):
        sources = [obj for obj in Gui.Selection.getSelection() if _has_edges(obj)]
        doc = App.ActiveDocument
        if sources:
            items = ", ".join(object_expression(obj) for obj in sources)
            lines = [f"facetwb.make_plan_graph([{items}])"]
        else:
            from facetwb.compat import qt_gui

            path, _ = qt_gui().QFileDialog.getOpenFileName(
                Gui.getMainWindow(), "Facet: plan drawing", "", PLAN_FILE_FILTER)
            if not path:
                return
            lines = [f"facetwb.make_plan_graph(file={path!r}, "
                     f"doc=FreeCAD.getDocument({doc.Name!r}))"]
        # nothing shown yet (a drawing read into a new document): the view is fitted to the
        # plan, as an import does; it showed the default few millimetres about the origin,
        # a 12 m plan one flat colour filling part of it
        empty = not any(getattr(getattr(o, "ViewObject", None), "Visibility", False)
                        for o in doc.Objects)
        before = {o.Name for o in doc.Objects}
        lines.append(f'FreeCAD.getDocument("{doc.Name}").recompute()')
        if run_as_macro(doc, "Plan graph", lines) and empty:
            from facetwb.viewproviders import attach

            Gui.SendMsgToActiveView("ViewFit")
            pose = attach.view_pose(doc.Name)
            for obj in doc.Objects:
                if obj.Name not in before and not getattr(obj, "FaceCount", 0):
                    # its first read failed (an arc, say): the view is fitted once the
                    # designer's fix draws it (fitted now, the view kept the default few
                    # millimetres about the origin, a corner of the plan in sight), if
                    # they have not moved it from this pose meanwhile
                    proxy = getattr(getattr(obj, "ViewObject", None), "Proxy", None)
                    if proxy is not None:
                        proxy.fit_when_drawn = pose


class CommandLift:
    """A Lifting of the selected plan towards the selected target surface."""

    def GetResources(self):
        return {
            "Pixmap": paths.icon_path("Facet_Lift"),
            "MenuText": QT_TRANSLATE_NOOP("Facet_Lift", "Lift plan"),
            "ToolTip": QT_TRANSLATE_NOOP(
                "Facet_Lift",
                "Select a plan (PlanGraph or Facet mesh), then a target surface (mesh or "
                "shape), or the plan alone to lift it to the heights of a points file: "
                "every plan vertex gets a height so that every face is exactly planar, as "
                "close as possible to the surface straight above it or to the points."),
        }

    def _selection(self):
        from facetwb.objects.polymesh import is_polymesh

        selection = Gui.Selection.getSelection()
        if len(selection) not in (1, 2) or not is_polymesh(selection[0]):
            return None
        return tuple(selection)

    def IsActive(self):
        return (App.ActiveDocument is not None and Gui.Control.activeDialog() is False
                and self._selection() is not None)

    def Activated(self):
        from facetwb.taskpanels.derive_panels import LiftPanel

        chosen = self._selection()
        if chosen is None:
            return
        # a plan whose drawing failed to read (an arc, a face with a hole) holds no faces:
        # the panel broke on it with a traceback ending "Plan holds no mesh"
        if not chosen[0].FaceStart:
            from facetwb.recompute import failure
            from facetwb.translation import translate

            reason = failure(chosen[0]) if not chosen[0].isValid() else chosen[0].Label
            App.Console.PrintError("Facet: {0}: {1}\n".format(
                translate("Facet", "Lift plan"), translate(
                    "Facet", "{0} holds no plan to lift ({1}): correct the drawing or the "
                    "plan's properties and recompute it first").format(
                        chosen[0].Label, reason)))
            return
        Gui.Control.showDialog(LiftPanel(list(chosen)))


class _OnSelectedLifting:
    """A command on the one selected Lifting, active while no task panel is open."""

    def _selected(self):
        return _selected_lifting()

    def IsActive(self):
        return self._selected() is not None and Gui.Control.activeDialog() is False


class CommandLiftMix(_OnSelectedLifting):
    """Open the task panel that mixes non-planar liftings into the selected Lifting."""

    def GetResources(self):
        return {
            "Pixmap": paths.icon_path("Facet_LiftMix"),
            "MenuText": QT_TRANSLATE_NOOP("Facet_LiftMix", "Shape lifting"),
            "ToolTip": QT_TRANSLATE_NOOP(
                "Facet_LiftMix",
                "Sliders for the selected Lifting: add the smoothest other planar-faced "
                "shapes over the same plan; the result follows live and every face "
                "stays exactly planar."),
        }

    def Activated(self):
        from facetwb.taskpanels.lift_mix import edit

        obj = self._selected()
        if obj is not None:
            edit(obj)


class CommandLiftPins(_OnSelectedLifting):
    """Open the Pin heights panel of the selected Lifting."""

    def GetResources(self):
        return {
            "Pixmap": paths.icon_path("Facet_LiftPins"),
            "MenuText": QT_TRANSLATE_NOOP("Facet_LiftPins", "Pin heights"),
            "ToolTip": QT_TRANSLATE_NOOP(
                "Facet_LiftPins",
                "Pin heights of the selected Lifting: click vertices of the roof or of its "
                "plan in the 3D view, type a height and pin them; the roof follows, every "
                "face planar, the other vertices free. Also by double-clicking a "
                "Lifting that has no other targets."),
        }

    def Activated(self):
        from facetwb.taskpanels.lift_pins import edit

        obj = self._selected()
        if obj is not None:
            edit(obj)
