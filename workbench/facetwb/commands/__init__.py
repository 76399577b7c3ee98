# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet's GUI commands. ``register()`` adds them to FreeCAD (InitGui.py calls it)."""

#: Commands in toolbar and menu order.
COMMANDS = ["Facet_ImportMesh", "Facet_ToPolyMesh", "Facet_SurfaceMesh",
            "Facet_Planarize", "Facet_EditControlMesh", "Facet_Cleanup",
            "Facet_PlanGraph", "Facet_Lift", "Facet_LiftPins", "Facet_LiftMix",
            "Facet_PanelSet",
            "Facet_CutSheets"]


def register():
    """Add Facet's commands to FreeCADGui (idempotent)."""
    import FreeCADGui as Gui

    from facetwb.commands.cleanup import CommandCleanup
    from facetwb.commands.edit_control import CommandEditControlMesh
    from facetwb.commands.import_mesh import CommandImportMesh
    from facetwb.commands.lift import (CommandLift, CommandLiftMix, CommandLiftPins,
                                       CommandPlanGraph)
    from facetwb.commands.panels import CommandCutSheets, CommandPanelSet
    from facetwb.commands.planarize import CommandPlanarize
    from facetwb.commands.surface_mesh import CommandSurfaceMesh
    from facetwb.commands.to_polymesh import CommandToPolyMesh

    known = set(Gui.listCommands())
    for name, command in (("Facet_ImportMesh", CommandImportMesh()),
                          ("Facet_ToPolyMesh", CommandToPolyMesh()),
                          ("Facet_SurfaceMesh", CommandSurfaceMesh()),
                          ("Facet_Planarize", CommandPlanarize()),
                          ("Facet_EditControlMesh", CommandEditControlMesh()),
                          ("Facet_Cleanup", CommandCleanup()),
                          ("Facet_PlanGraph", CommandPlanGraph()),
                          ("Facet_Lift", CommandLift()),
                          ("Facet_LiftPins", CommandLiftPins()),
                          ("Facet_LiftMix", CommandLiftMix()),
                          ("Facet_PanelSet", CommandPanelSet()),
                          ("Facet_CutSheets", CommandCutSheets())):
        if name not in known:
            Gui.addCommand(name, command)
