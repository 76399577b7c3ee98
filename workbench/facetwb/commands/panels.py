# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet_PanelSet and Facet_CutSheets: panel solids from a planar mesh, nested cut sheets."""

import FreeCAD as App
import FreeCADGui as Gui

from facetwb import paths
from facetwb.commands.macro import object_expression, run_as_macro


def _selected(test):
    return [obj for obj in Gui.Selection.getSelection() if test(obj)]


def _is_mesh(obj):
    from facetwb.objects.polymesh import is_polymesh

    return is_polymesh(obj)


def _is_panelset(obj):
    from facetwb.objects.panelset import is_panelset

    return is_panelset(obj)


def _report(doc, before, test, describe):
    made = [obj for obj in doc.Objects if obj not in before and test(obj)]
    for obj in made:
        if obj.isValid():
            App.Console.PrintMessage(describe(obj) + "\n")
        else:
            App.Console.PrintError(f"{obj.Label}: failed: {obj.getStatusString()}\n")
    Gui.Selection.clearSelection()
    for obj in made:
        Gui.Selection.addSelection(obj)


class CommandPanelSet:
    """Add a PanelSet (panel solids) for each selected planar PolyMesh or Planarized object."""

    def GetResources(self):
        return {
            "Pixmap": paths.icon_path("Facet_PanelSet"),
            "MenuText": "Panels",
            "ToolTip": "Turn every planar face of the selected mesh into a panel solid with "
                       "its thickness and edge cuts, named by part ID (edit Thickness, Offset, "
                       "Gap, EdgeMode in the property view)",
        }

    def IsActive(self):
        return App.ActiveDocument is not None and bool(_selected(_is_mesh))

    def Activated(self):
        sources = _selected(_is_mesh)
        if not sources:
            return
        doc = sources[0].Document
        before = set(doc.Objects)
        lines = [f"facetwb.make_panelset({object_expression(src)})" for src in sources]
        lines.append(f'FreeCAD.getDocument("{doc.Name}").recompute()')
        if run_as_macro(doc, "Panels", lines):
            _report(doc, before, _is_panelset, lambda o: (
                f"{o.Label}: {o.PanelCount} panels, node deviation up to "
                f"{o.MaxNodeDeviation.Value:.3g} degrees"))


class CommandCutSheets:
    """Nest the selected PanelSet's parts on stock sheets (and write the cut files)."""

    def GetResources(self):
        return {
            "Pixmap": paths.icon_path("Facet_CutSheets"),
            "MenuText": "Cut sheets",
            "ToolTip": "Lay the selected panels flat with their IDs and bevel angles, nest them "
                       "on stock sheets, and write DXF, STEP, schedule and previews to the "
                       "folder set in OutputDir",
        }

    def IsActive(self):
        return App.ActiveDocument is not None and bool(_selected(_is_panelset))

    def Activated(self):
        from facetwb.objects.panelset import is_cutsheets

        sources = _selected(_is_panelset)
        if not sources:
            return
        doc = sources[0].Document
        before = set(doc.Objects)
        lines = [f"facetwb.make_cutsheets({object_expression(src)})" for src in sources]
        lines.append(f'FreeCAD.getDocument("{doc.Name}").recompute()')
        if run_as_macro(doc, "Cut sheets", lines):
            _report(doc, before, is_cutsheets, lambda o: (
                f"{o.Label}: {o.SheetCount} sheets, utilisation {100 * o.Utilisation:.1f}%, "
                f"{len(o.Unplaced)} unplaced"))
