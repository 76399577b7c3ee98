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
        # not while a task panel is open (its transaction would be committed by this one's)
        return Gui.Control.activeDialog() is False

    def Activated(self):
        parameters = App.ParamGet(PARAMETERS)
        folder = parameters.GetString("LastImportDir", os.path.expanduser("~"))
        filename, _ = qt_gui().QFileDialog.getOpenFileName(
            Gui.getMainWindow(), "Import polygon mesh", folder,
            "Polygon meshes (*.obj *.off);;All files (*)")
        if not filename:
            return
        parameters.SetString("LastImportDir", os.path.dirname(filename))
        from facetwb import importer

        try:
            units = file_units(filename)
            if units is None:
                return
            created = App.ActiveDocument is None
            doc = App.ActiveDocument or App.newDocument()
            # importer.insert reports a file it cannot read, or Cancel pressed in its
            # progress dialog, and leaves the document unchanged (nothing to undo then;
            # the document made for it closed again: an empty "Unnamed" was left);
            # it takes the mesh file_units read instead of reading it again.
            arguments = (f'{filename!r}, "{doc.Name}"'
                         + (f", units={units!r}" if units != "mm" else ""))
            before = set(doc.Objects)
            run_as_macro(doc, "Import polygon mesh", [f"facetwb.importer.insert({arguments})"],
                         modules=("facetwb.importer",),
                         keep=lambda: bool(set(doc.Objects) - before))
            if created and not doc.Objects:
                App.closeDocument(doc.Name)
        finally:
            importer.forget_kept()


def file_units(filename):
    """The units of ``filename``'s numbers: "mm", FreeCAD's unit, unless its mean edge read
    so is no facade's (a mesh in metres has edges of a few millimetres then), or FreeCAD
    shows lengths in inches or feet (its unit schema: an OBJ in inches has a facade's
    edges read as millimetres too, and came in 25.4 times too small, unasked), when the
    designer is asked (:func:`ask_units`; not when importer.SHOW_DIALOGS is off: the
    report view's warning then says it). None: the designer cancelled the import (here,
    or in the progress dialog of the reading, said in the report view).

    The file is read once: importer.insert of it takes the mesh read here
    (importer.read_kept)."""
    import facet
    from facetwb import importer, progress

    if not importer.SHOW_DIALOGS:
        return "mm"
    try:
        with progress.reporting(importer.progress_title(filename)):
            mesh = importer.read_kept(filename)
    except facet.Cancelled:
        importer.report_cancelled(filename)
        return None
    except Exception:  # noqa: BLE001 - importer.insert reports what is wrong with the file
        return "mm"
    from facetwb import units

    if importer.size_warning(mesh) is None:
        if not units.imperial():
            return "mm"
        return ask_units(filename, mesh.mean_edge_length(),
                         importer.likely_units(mesh, among=("mm", "in", "ft")), imperial=True)
    return ask_units(filename, mesh.mean_edge_length(), importer.likely_units(mesh))


def ask_units(filename, edge, likely, imperial=False):
    """Ask which units ``filename``'s numbers are in (its mean edge is ``edge`` of them,
    ``likely`` is offered first; ``imperial``: asked because FreeCAD shows inches or
    feet, the size being a facade's in millimetres too); a unit of importer.UNIT_NAMES,
    or None (Cancel)."""
    from facetwb import importer
    from facetwb.translation import translate

    units = list(importer.UNIT_NAMES)
    names = [f"{importer.UNIT_NAMES[u]} ({u})" for u in units]
    question = (translate("Facet", "{0}: its edges are {1:.3g} of its units long on "
                                   "average. FreeCAD shows lengths in inches or feet here "
                                   "(its unit schema) and the file does not say its units: "
                                   "which units are its numbers in?") if imperial else
                translate("Facet", "{0}: its edges are {1:.3g} of its units long on average; "
                                   "as millimetres, no facade's panel is that small or large. "
                                   "Which units are its numbers in?"))
    item, ok = qt_gui().QInputDialog.getItem(
        Gui.getMainWindow(), translate("Facet", "Import polygon mesh"),
        question.format(os.path.basename(filename), edge),
        names, units.index(likely), False)
    return units[names.index(item)] if ok else None
