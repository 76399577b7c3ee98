# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet_Planarize: make the selected polygon meshes' faces planar."""

import FreeCAD as App

from facetwb import paths
from facetwb.commands.macro import derive, object_expression, selected


def _selected_meshes():
    from facetwb.objects.polymesh import is_polymesh

    return selected(is_polymesh)


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
        lines = [f"facetwb.make_planarized({object_expression(src)})" for src in sources]
        derive(sources[0].Document, "Planarize", lines, is_planarized, planarize_summary,
               select=True)
