# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet_Planarize: make the selected polygon meshes' faces planar."""

import FreeCAD as App
import FreeCADGui as Gui

from facetwb import paths
from facetwb.translation import QT_TRANSLATE_NOOP
from facetwb.commands.macro import selected


def _selected_meshes():
    from facetwb.objects.polymesh import is_polymesh

    return selected(is_polymesh)


class CommandPlanarize:
    """Add a Planarized object for each selected PolyMesh (or Planarized) and solve it."""

    def GetResources(self):
        return {
            "Pixmap": paths.icon_path("Facet_Planarize"),
            "MenuText": QT_TRANSLATE_NOOP("Facet_Planarize", "Planarize"),
            "ToolTip": QT_TRANSLATE_NOOP(
                "Facet_Planarize",
                "Move the vertices of the selected polygon mesh as little as possible so "
                "that every face is planar (a flat panel). The source is kept; the result "
                "is coloured by planarity."),
        }

    def IsActive(self):
        return (App.ActiveDocument is not None and Gui.Control.activeDialog() is False
                and bool(_selected_meshes()))

    def Activated(self):
        from facetwb.taskpanels.derive_panels import PlanarizePanel

        sources = _selected_meshes()
        if sources:
            Gui.Control.showDialog(PlanarizePanel(sources))
