# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet_Planarize: make the selected polygon meshes' faces planar."""

import FreeCAD as App
import FreeCADGui as Gui

from facetwb import paths
from facetwb.commands.macro import object_expression, run_as_macro


def _selected_meshes():
    from facetwb.objects.polymesh import is_polymesh

    return [obj for obj in Gui.Selection.getSelection() if is_polymesh(obj)]


class CommandPlanarize:
    """Add a Planarized object for each selected PolyMesh (or Planarized) and solve it."""

    def GetResources(self):
        return {
            "Pixmap": paths.icon_path("Facet_Planarize"),
            "MenuText": "Planarize",
            "ToolTip": "Move the vertices of the selected polygon mesh as little as possible so "
                       "that every face is planar (a flat panel). The source is kept; the result "
                       "is coloured by planarity.",
        }

    def IsActive(self):
        return App.ActiveDocument is not None and bool(_selected_meshes())

    def Activated(self):
        from facetwb.objects.planarized import is_planarized, planarize_summary

        sources = _selected_meshes()
        if not sources:
            return
        doc = sources[0].Document
        before = set(doc.Objects)
        lines = [f"facetwb.make_planarized({object_expression(src)})" for src in sources]
        lines.append(f'FreeCAD.getDocument("{doc.Name}").recompute()')
        if not run_as_macro(doc, "Planarize", lines):
            return
        results = [obj for obj in doc.Objects if obj not in before and is_planarized(obj)]
        for obj in results:
            if obj.isValid():
                App.Console.PrintMessage(planarize_summary(obj) + "\n")
            else:
                App.Console.PrintError(planarize_summary(obj) + "\n")
        Gui.Selection.clearSelection()
        for obj in results:
            Gui.Selection.addSelection(obj)
