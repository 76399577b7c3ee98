# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet_EditControlMesh: drag the control vertices of a Planarized object, live."""

import FreeCAD as App

from facetwb import paths
from facetwb.commands.macro import selected
from facetwb.translation import QT_TRANSLATE_NOOP


def _editable():
    from facetwb.objects.planarized import is_planarized
    from facetwb.objects.polymesh import is_polymesh

    return selected(lambda obj: is_planarized(obj) or is_polymesh(obj))


class CommandEditControlMesh:
    """Start an edit-and-observe session on the selected Planarized object."""

    def GetResources(self):
        return {
            "Pixmap": paths.icon_path("Facet_EditControlMesh"),
            "MenuText": QT_TRANSLATE_NOOP("Facet_EditControlMesh", "Edit control mesh"),
            "ToolTip": QT_TRANSLATE_NOOP(
                "Facet_EditControlMesh",
                "Drag the control vertices of the selected Planarized object (or its "
                "control PolyMesh) in the 3D view; the planar result follows live. "
                "OK writes the moved vertices in one undoable step, Cancel drops them."),
        }

    def IsActive(self):
        import FreeCADGui as Gui

        # not while a task panel is open: the session closed it without its Cancel or OK,
        # and a Planarize edit panel's changes stayed, its transaction open
        return (App.ActiveDocument is not None and Gui.ActiveDocument is not None
                and Gui.Control.activeDialog() is False and len(_editable()) == 1)

    def Activated(self):
        from facetwb import edit_control

        objects = _editable()
        if len(objects) != 1:
            return
        try:
            edit_control.start(objects[0])
        except (edit_control.EditError, ValueError) as exc:
            App.Console.PrintError(f"Facet: Edit control mesh: {exc}\n")
