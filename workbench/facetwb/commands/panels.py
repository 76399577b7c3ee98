# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet_PanelSet and Facet_CutSheets: panel solids from a planar mesh, nested cut sheets."""

import FreeCAD as App
import FreeCADGui as Gui

from facetwb import paths
from facetwb.translation import QT_TRANSLATE_NOOP
from facetwb.commands.macro import selected


def _is_mesh(obj):
    from facetwb.objects.polymesh import is_polymesh

    return is_polymesh(obj)


def _is_panelset(obj):
    from facetwb.objects.panelset import is_panelset

    return is_panelset(obj)


class CommandPanelSet:
    """Add a PanelSet (panel solids) for each selected planar PolyMesh or Planarized object."""

    def GetResources(self):
        return {
            "Pixmap": paths.icon_path("Facet_PanelSet"),
            "MenuText": QT_TRANSLATE_NOOP("Facet_PanelSet", "Panels"),
            "ToolTip": QT_TRANSLATE_NOOP(
                "Facet_PanelSet",
                "Turn every planar face of the selected mesh into a panel solid with "
                "its thickness and edge cuts, named by part ID (edit Thickness, Offset, "
                "Gap, EdgeMode in the property view)"),
        }

    def IsActive(self):
        return (App.ActiveDocument is not None and Gui.Control.activeDialog() is False
                and bool(selected(_is_mesh)))

    def Activated(self):
        from facetwb.taskpanels.derive_panels import PanelsPanel

        sources = selected(_is_mesh)
        if sources:
            Gui.Control.showDialog(PanelsPanel(sources))


class CommandCutSheets:
    """Nest the selected PanelSet's parts on stock sheets (and write the cut files)."""

    def GetResources(self):
        return {
            "Pixmap": paths.icon_path("Facet_CutSheets"),
            "MenuText": QT_TRANSLATE_NOOP("Facet_CutSheets", "Cut sheets"),
            "ToolTip": QT_TRANSLATE_NOOP(
                "Facet_CutSheets",
                "Lay the selected panels flat with their IDs and bevel angles, nest them "
                "on stock sheets, and write DXF, STEP, schedule and previews to the "
                "folder set in OutputDir"),
        }

    def IsActive(self):
        return (App.ActiveDocument is not None and Gui.Control.activeDialog() is False
                and bool(selected(_is_panelset)))

    def Activated(self):
        from facetwb.taskpanels.derive_panels import CutSheetsPanel

        sources = selected(_is_panelset)
        if sources:
            Gui.Control.showDialog(CutSheetsPanel(sources))
