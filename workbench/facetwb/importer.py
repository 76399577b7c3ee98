# SPDX-License-Identifier: LGPL-2.1-or-later
"""Import OBJ and OFF polygon meshes as PolyMesh objects (File > Open / File > Import).

Registered in Init.py as "Polygon mesh for Facet (*.obj *.off)". FreeCAD calls ``open()`` to
read a file into a new document and ``insert()`` to add it to an existing one.

A file Facet cannot read (missing, not a mesh, a face with an index out of range, ...) is
reported as one clear line in the report view (and a message box in the GUI) naming the file,
line and face; nothing is added to any document and no document is created.
"""

import os

import FreeCAD as App

#: Show a message box for import errors when the GUI is up. Scripts and tests that drive the
#: GUI set this to False so no modal dialog waits for a click.
SHOW_DIALOGS = True


class MeshImportError(Exception):
    """A file that cannot be imported; ``str()`` is one line naming the file and the problem."""


def read_polymesh(filename):
    """``facet.read_mesh(filename)``, raising MeshImportError with a one-line message; what
    the reader changed in reading it (faces with a vertex twice in a row) and an unwelded
    seam (vertices at one point, which the faces there do not share) are warnings in the
    report view."""
    import facet
    from facet.io import read_warnings
    from facet.mesh import unwelded_warning

    try:
        mesh = facet.read_mesh(filename)
        for warning in read_warnings(mesh):
            report_warning(f"Facet: {filename}: {warning}")
        seam = unwelded_warning(mesh, "the faces there are not joined")
        if seam:
            report_warning(f"Facet: {filename}: {seam}")
        return mesh
    except (facet.errors.FacetError, OSError, ValueError) as error:
        message = str(error)
        if isinstance(error, OSError) and error.strerror:
            message = error.strerror
        for prefix in (f"{filename}: ", f"{os.path.basename(filename)}: "):
            if message.startswith(prefix):  # facet names the file; so does our message
                message = message[len(prefix):]
        raise MeshImportError(f"Cannot import {filename}: {message}") from error


def import_mesh(filename, doc):
    """Read ``filename`` into a new, recomputed PolyMesh in ``doc`` and return it.

    Raises MeshImportError, with ``doc`` unchanged, if the file cannot be read.
    """
    return _add_polymesh(read_polymesh(filename), filename, doc)


def _add_polymesh(mesh, filename, doc):
    from facetwb.make.make_polymesh import make_polymesh

    label = os.path.splitext(os.path.basename(filename))[0]
    obj = make_polymesh(mesh, label=label, doc=doc)
    doc.recompute()
    return obj


def report_warning(message):
    """One line in the report view, as a warning."""
    App.Console.PrintWarning(message + "\n")


def report_error(message):
    """One line in the report view, and a message box in the GUI."""
    App.Console.PrintError(message + "\n")
    if App.GuiUp and SHOW_DIALOGS:
        import FreeCADGui as Gui

        from facetwb.compat import qt_gui

        qt_gui().QMessageBox.critical(Gui.getMainWindow(), "Facet: import polygon mesh",
                                      message)


def open(filename):  # noqa: A001 - the name FreeCAD's import mechanism calls
    """Read ``filename`` into a new document named after it; returns the document or None."""
    try:
        mesh = read_polymesh(filename)
    except MeshImportError as error:
        report_error(str(error))
        return None
    doc = App.newDocument(os.path.splitext(os.path.basename(filename))[0])
    _add_polymesh(mesh, filename, doc)
    return doc


def insert(filename, docname):
    """Add ``filename`` to the document ``docname`` (created if missing); returns the object."""
    try:
        mesh = read_polymesh(filename)
    except MeshImportError as error:
        report_error(str(error))
        return None
    try:
        doc = App.getDocument(docname)
    except NameError:
        doc = App.newDocument(docname)
    return _add_polymesh(mesh, filename, doc)
