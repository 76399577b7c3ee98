# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet GUI start-up: declares the workbench. Only wiring here; the code is in facetwb.

FreeCAD runs this file with exec(), so names defined at its top level are not visible inside
the class: everything the class needs is imported where it is used.
"""

import FreeCADGui


class FacetWorkbench(FreeCADGui.Workbench):
    """Planar panels for freeform facades."""

    from facetwb.paths import icon_path as _icon_path

    MenuText = "Facet"
    ToolTip = ("Architectural panels: polygon meshes of facades, planarization (flat panels) "
               "and planarity colour maps")
    Icon = _icon_path("Facet")
    del _icon_path

    def Initialize(self):
        import os

        import facetwb.commands
        from facetwb import paths

        FreeCADGui.addLanguagePath(os.path.join(paths.resources_dir(), "translations"))
        FreeCADGui.updateLocale()
        facetwb.commands.register()
        self.appendToolbar("Facet", facetwb.commands.COMMANDS)
        self.appendMenu("&Facet", facetwb.commands.COMMANDS)
        from facetwb.taskpanels.preferences_page import PreferencesPage

        FreeCADGui.addPreferencePage(PreferencesPage, "Facet")

    def Activated(self):
        pass

    def Deactivated(self):
        pass

    def GetClassName(self):
        return "Gui::PythonWorkbench"


FreeCADGui.addWorkbench(FacetWorkbench())
