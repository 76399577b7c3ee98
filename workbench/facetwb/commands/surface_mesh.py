# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet_SurfaceMesh: a control polygon mesh (quads, hexagons or paired triangles) on the
selected FreeCAD surfaces, through its task panel."""

import FreeCAD as App
import FreeCADGui as Gui

from facetwb import paths
from facetwb.commands.macro import selected
from facetwb.translation import QT_TRANSLATE_NOOP


def _sources():
    from facetwb.conversion import has_surface

    return selected(has_surface)


class CommandSurfaceMesh:
    """Open the Surface mesh task panel for the selected surfaces (or Meshes)."""

    def GetResources(self):
        return {
            "Pixmap": paths.icon_path("Facet_SurfaceMesh"),
            "MenuText": QT_TRANSLATE_NOOP(
                "Facet_SurfaceMesh", "Surface to control mesh"),
            "ToolTip": QT_TRANSLATE_NOOP(
                "Facet_SurfaceMesh",
                "Panelize the selected surfaces (Part, Surface or Curves faces, shells, "
                "solids) into a quad grid, a hexagonal grid or triangles paired into quads, "
                "or pair the triangles of a selected Mesh. The control mesh follows changes "
                "of the surface; the surface is not modified."),
        }

    def IsActive(self):
        return (App.ActiveDocument is not None and Gui.Control.activeDialog() is False
                and bool(_sources()))

    def Activated(self):
        from facetwb.taskpanels.derive_panels import SurfaceMeshPanel

        sources = _sources()
        if sources:
            Gui.Control.showDialog(SurfaceMeshPanel(sources))
