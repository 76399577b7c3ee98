# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet_ToPolyMesh: a polygon mesh from selected FreeCAD Mesh or Part objects."""

import FreeCAD as App
import FreeCADGui as Gui

from facetwb import paths
from facetwb.translation import QT_TRANSLATE_NOOP
from facetwb.commands.macro import object_expression, run_as_macro



class CommandToPolyMesh:
    """Add a PolyMesh linked to each selected Mesh or Part object."""

    def GetResources(self):
        return {
            "Pixmap": paths.icon_path("Facet_ToPolyMesh"),
            "MenuText": QT_TRANSLATE_NOOP("Facet_ToPolyMesh", "To polygon mesh"),
            "ToolTip": QT_TRANSLATE_NOOP(
                "Facet_ToPolyMesh",
                "Make a Facet polygon mesh from the selected Mesh or Part objects: a shape "
                "of planar polygons gives one panel per face, other shapes and meshes "
                "give triangles. It follows changes of its source."),
        }

    def IsActive(self):
        from facetwb.conversion import has_surface

        # not while a task panel is open (its transaction would be committed by this one's)
        return App.ActiveDocument is not None and Gui.Control.activeDialog() is False and any(
            has_surface(obj) for obj in Gui.Selection.getSelection())

    def Activated(self):
        from facetwb.conversion import has_surface

        sources = [obj for obj in Gui.Selection.getSelection() if has_surface(obj)]
        if not sources:
            return
        doc = sources[0].Document
        lines = [f"facetwb.make_polymesh_from_object({object_expression(src)})"
                 for src in sources]
        lines.append(f'FreeCAD.getDocument("{doc.Name}").recompute()')
        run_as_macro(doc, "To polygon mesh", lines)
