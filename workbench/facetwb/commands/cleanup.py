# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet_Cleanup: collapse the short edges of the selected polygon meshes, then planarize."""

import FreeCAD as App

from facetwb import paths
from facetwb.translation import QT_TRANSLATE_NOOP
from facetwb.commands.macro import derive, object_expression, selected


def _selected_meshes():
    from facetwb.objects.polymesh import is_polymesh

    return selected(is_polymesh)


class CommandCleanup:
    """Add a Cleanup object for each selected PolyMesh (or Planarized) and run it."""

    def GetResources(self):
        return {
            "Pixmap": paths.icon_path("Facet_Cleanup"),
            "MenuText": QT_TRANSLATE_NOOP("Facet_Cleanup", "Collapse short edges"),
            "ToolTip": QT_TRANSLATE_NOOP(
                "Facet_Cleanup",
                "Join the selected polygon mesh's unwelded seams (vertices at one point), "
                "collapse its edges shorter than a tenth of its mean edge (change MinEdge in "
                "the new object), then planarize again. The result is a new mesh with fewer "
                "panels; the source is kept."),
        }

    def IsActive(self):
        import FreeCADGui as Gui

        # not while a task panel is open: its transaction (a Planarize edit panel's) was
        # committed by this command's, and its Cancel then kept the changes
        return (App.ActiveDocument is not None and Gui.Control.activeDialog() is False
                and bool(_selected_meshes()))

    def Activated(self):
        from facetwb.objects.cleanup import cleanup_summary, is_cleanup

        sources = _selected_meshes()
        if not sources:
            return
        lines = [f"facetwb.make_cleanup({object_expression(src)})" for src in sources]
        derive(sources[0].Document, "Collapse short edges", lines, is_cleanup, cleanup_summary)
