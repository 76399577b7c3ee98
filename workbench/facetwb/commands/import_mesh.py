# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet_ImportMesh: import an OBJ or OFF polygon mesh into the active document."""

import os

import FreeCAD as App
import FreeCADGui as Gui

from facetwb import paths
from facetwb.translation import QT_TRANSLATE_NOOP
from facetwb.commands.macro import run_as_macro
from facetwb.compat import qt_gui

PARAMETERS = "User parameter:BaseApp/Preferences/Mod/Facet"


class CommandImportMesh:
    """Ask for a mesh file and add it as a PolyMesh (a new document if none is open)."""

    def GetResources(self):
        return {
            "Pixmap": paths.icon_path("Facet_ImportMesh"),
            "MenuText": QT_TRANSLATE_NOOP("Facet_ImportMesh", "Import polygon mesh..."),
            "ToolTip": QT_TRANSLATE_NOOP(
                "Facet_ImportMesh",
                "Import an OBJ or OFF file as a Facet polygon mesh (quads, hexagons and "
                "other polygons are kept, not split into triangles)"),
        }

    def IsActive(self):
        return True

    def Activated(self):
        parameters = App.ParamGet(PARAMETERS)
        folder = parameters.GetString("LastImportDir", os.path.expanduser("~"))
        filename, _ = qt_gui().QFileDialog.getOpenFileName(
            Gui.getMainWindow(), "Import polygon mesh", folder,
            "Polygon meshes (*.obj *.off);;All files (*)")
        if not filename:
            return
        parameters.SetString("LastImportDir", os.path.dirname(filename))
        doc = App.ActiveDocument or App.newDocument()
        # importer.insert reports a file it cannot read and leaves the document unchanged.
        run_as_macro(doc, "Import polygon mesh",
                     [f'facetwb.importer.insert({filename!r}, "{doc.Name}")'],
                     modules=("facetwb.importer",))
