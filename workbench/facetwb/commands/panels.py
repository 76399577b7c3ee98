# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet_PanelSet and Facet_CutSheets: panel solids from a planar mesh, nested cut sheets."""

import FreeCAD as App

from facetwb import paths
from facetwb.commands.macro import derive, object_expression, selected


def _is_mesh(obj):
    from facetwb.objects.polymesh import is_polymesh

    return is_polymesh(obj)


def _is_panelset(obj):
    from facetwb.objects.panelset import is_panelset

    return is_panelset(obj)


def _described(describe):
    """A summary that says why an object failed, else ``describe(obj)``."""
    return lambda obj: describe(obj) if obj.isValid() else (
        f"{obj.Label}: failed: {obj.getStatusString()}")


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
        return App.ActiveDocument is not None and bool(selected(_is_mesh))

    def Activated(self):
        sources = selected(_is_mesh)
        if not sources:
            return
        lines = [f"facetwb.make_panelset({object_expression(src)})" for src in sources]
        derive(sources[0].Document, "Panels", lines, _is_panelset, _described(lambda o: (
            f"{o.Label}: {o.PanelCount} panels, node deviation up to "
            f"{o.MaxNodeDeviation.Value:.3g} degrees")), select=True)


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
        return App.ActiveDocument is not None and bool(selected(_is_panelset))

    def Activated(self):
        from facetwb.objects.panelset import is_cutsheets

        sources = selected(_is_panelset)
        if not sources:
            return
        lines = [f"facetwb.make_cutsheets({object_expression(src)})" for src in sources]
        derive(sources[0].Document, "Cut sheets", lines, is_cutsheets, _described(lambda o: (
            f"{o.Label}: {o.SheetCount} sheets, utilisation {100 * o.Utilisation:.1f}%, "
            f"{len(o.Unplaced)} unplaced")), select=True)
