# SPDX-License-Identifier: LGPL-2.1-or-later
"""Import OBJ and OFF polygon meshes as PolyMesh objects (File > Open / File > Import).

Registered in Init.py as "Polygon mesh for Facet (*.obj *.off)". FreeCAD calls ``open()`` to
read a file into a new document and ``insert()`` to add it to an existing one.

A file Facet cannot read (missing, not a mesh, a face with an index out of range, ...) is
reported as one clear line in the report view (and a message box in the GUI) naming the file,
line and face; nothing is added to any document and no document is created.

In the GUI an import shows its progress with Cancel (:mod:`facetwb.progress`: the reading,
then a busy bar while the mesh is checked, added and recomputed). Cancel leaves the
documents as they were (an object already added is removed again, a document the import
created is closed) and says "import cancelled" in the report view; headless, or in a
script, nothing is shown and nothing can cancel.
"""

import os

import FreeCAD as App

from facetwb import progress
from facetwb.translation import translate

#: Show a message box for import errors when the GUI is up. Scripts and tests that drive the
#: GUI set this to False so no modal dialog waits for a click.
SHOW_DIALOGS = True

#: The mesh (or the error) of the file :func:`read_kept` read, with that file's state, for
#: the next :func:`read_polymesh` of it: {filename: (state, mesh or exception)}.
_KEPT = {}

#: The units a file can be read in (facet.cutsheets.LENGTH_UNITS), as the designer reads them.
UNIT_NAMES = {"mm": "millimetres", "cm": "centimetres", "m": "metres", "in": "inches",
              "ft": "feet"}


class MeshImportError(Exception):
    """A file that cannot be imported; ``str()`` is one line naming the file and the problem."""


def size_warning(mesh, units="mm"):
    """The warning for a mesh whose mean edge, read in ``units``, is no facade's
    (facet.cutsheets.implausible_edge_mm: a facade in metres read as millimetres), or
    None."""
    from facet.cutsheets import implausible_edge_mm

    edge = implausible_edge_mm(mesh.mean_edge_length(), units)
    if edge is None:
        return None
    return (f"its edges are {edge:.3g} mm long on average, its numbers read as "
            f"{UNIT_NAMES[units]}: if the file is in other units, import it again with Facet "
            "> Import polygon mesh, which asks for them, or its panels and cut sheets come "
            "out at the wrong size")


def likely_units(mesh, among=None):
    """The unit that makes ``mesh``'s mean edge closest to a panel's (1.5 m), of those that
    make it plausible; "mm" when none does, or when mm does unless ``among`` (units of
    UNIT_NAMES) is given: then the closest of those it names that make it plausible
    (an imperial designer's: mm, in, ft)."""
    import math

    from facet.cutsheets import implausible_edge_mm, length_unit

    edge = mesh.mean_edge_length()
    plausible = [u for u in among or UNIT_NAMES if implausible_edge_mm(edge, u) is None]
    if not plausible or ("mm" in plausible and among is None):
        return "mm"
    return min(plausible, key=lambda u: abs(math.log(edge * length_unit(u)[0] / 1500.0)))


def read_polymesh(filename, units="mm"):
    """``facet.read_mesh(filename)`` with its coordinates read in ``units`` (UNIT_NAMES)
    and turned into millimetres, FreeCAD's unit, raising MeshImportError with a one-line
    message (facet.Cancelled when Cancel was pressed: :func:`progress_title`); what the
    reader changed in reading it (faces with a vertex twice in a row), an unwelded seam
    (vertices at one point, which the faces there do not share) and a size no facade has
    in those units (:func:`size_warning`) are warnings in the report view."""
    import facet
    from facet.cutsheets import length_unit
    from facet.io import read_warnings
    from facet.mesh import unwelded_warning

    scale = length_unit(units)[0] if units in UNIT_NAMES else None
    if scale is None:
        raise MeshImportError(f"Cannot import {filename}: units {units!r}: use one of "
                              f"{', '.join(UNIT_NAMES)}")
    try:
        mesh = _kept_or_read(filename)
        _step(translate("Facet", "Checking the mesh"))
        for warning in read_warnings(mesh):
            report_warning(f"Facet: {filename}: {warning}")
        seam = unwelded_warning(mesh, "the faces there are not joined")
        if seam:
            report_warning(f"Facet: {filename}: {seam}")
        _step()
        size = size_warning(mesh, units)
        if size:
            report_warning(f"Facet: {filename}: {size}")
        if scale != 1.0:
            mesh = mesh.with_vertices(mesh.vertices * scale)
        return mesh
    except facet.Cancelled:
        raise
    except (facet.errors.FacetError, OSError, ValueError) as error:
        message = str(error)
        if isinstance(error, OSError) and error.strerror:
            message = error.strerror
        for prefix in (f"{filename}: ", f"{os.path.basename(filename)}: "):
            if message.startswith(prefix):  # facet names the file; so does our message
                message = message[len(prefix):]
        raise MeshImportError(f"Cannot import {filename}: {message}") from error


def read_kept(filename):
    """``facet.read_mesh(filename)`` (its errors raised as it raises them), kept for the
    next :func:`read_polymesh` of the file while it is unchanged (same size, time and
    inode): Facet_ImportMesh reads a file to ask for its units, then runs the macro line
    ``importer.insert(filename, ...)``, which read the whole file a second time (a
    replayed macro, with nothing kept, reads it). :func:`forget_kept` drops it.

    Its progress goes to the open reporter (:func:`facetwb.progress.hook`); a read cancelled
    there raises facet.Cancelled and keeps nothing."""
    import facet

    state = _file_state(filename)
    _KEPT.pop(filename, None)
    try:
        mesh = facet.read_mesh(filename, progress=progress.hook())
    except facet.Cancelled:
        raise
    except (facet.errors.FacetError, OSError, ValueError) as error:
        _KEPT[filename] = (state, error)
        raise
    _KEPT[filename] = (state, mesh)
    return mesh


def forget_kept():
    """Drop what :func:`read_kept` kept and no read has taken."""
    _KEPT.clear()


def _file_state(filename):
    try:
        stat = os.stat(filename)
    except OSError:
        return None
    return stat.st_size, stat.st_mtime_ns, stat.st_ino


def _kept_or_read(filename):
    """What :func:`read_kept` kept of ``filename`` if it is unchanged since (used once),
    else ``facet.read_mesh(filename)``."""
    import facet

    state, kept = _KEPT.pop(filename, (None, None))
    if kept is not None and state == _file_state(filename):
        if isinstance(kept, Exception):
            raise kept
        return kept
    return facet.read_mesh(filename, progress=progress.hook())


def import_mesh(filename, doc, units="mm"):
    """Read ``filename`` (its numbers in ``units``) into a new, recomputed PolyMesh in
    ``doc`` and return it.

    Raises MeshImportError, with ``doc`` unchanged, if the file cannot be read, and
    facet.Cancelled, with ``doc`` unchanged, if Cancel is pressed in an open reporter
    (:mod:`facetwb.progress`).
    """
    return _add_polymesh(read_polymesh(filename, units), filename, doc, units)


def _add_polymesh(mesh, filename, doc, units="mm"):
    """A new PolyMesh of ``mesh`` in ``doc``, recomputed; on Cancel (seen after it was
    made or recomputed) it is removed again and facet.Cancelled raised."""
    import facet
    from facetwb.make.make_polymesh import make_polymesh

    _step(translate("Facet", "Adding it to the document"))
    label = os.path.splitext(os.path.basename(filename))[0]
    obj = make_polymesh(mesh, label=label, doc=doc)
    try:
        _step()
        doc.recompute()
        _step()
    except facet.Cancelled:
        doc.removeObject(obj.Name)
        raise
    report_message(f"Facet: {filename}: {imported_summary(mesh, units)}, as {obj.Label}")
    return obj


def imported_summary(mesh, units="mm"):
    """What an import made of ``mesh`` (in millimetres, its file's numbers read in
    ``units``), for the report view: its faces by corner count, its vertices, its size
    and the units it was read in; a designer sees at once a mesh of the wrong size or
    kind (before, a successful import said nothing)."""
    from facet.report import count_noun, degrees_text, face_degrees

    from facetwb import units as user_units

    lower, upper = mesh.bounds()
    # in the unit FreeCAD shows it in when that is inches or feet (a mesh read in inches
    # said its size in mm beside a property editor in inches); else mm, as it was
    extents = upper - lower
    mm, unit = (user_units.user_unit(float(extents.max())) if user_units.imperial()
                else (1.0, "mm"))
    size = " x ".join(_extent_text(float(v) / mm) for v in extents)
    return (f"{count_noun(mesh.n_faces, 'face', grouped=True)} "
            f"({degrees_text(face_degrees(mesh), grouped=True)}), "
            f"{count_noun(mesh.n_vertices, 'vertex', grouped=True)}, {size} {unit}, its "
            f"numbers read as {UNIT_NAMES[units]}")


def _extent_text(length):
    """A mesh's extent (mm, or inches) for :func:`imported_summary`: whole units from 100
    ("12,000"), three significant digits below ("0.6": a mesh in metres read as
    millimetres was "1 x 0 x 0 mm", a size it does not have)."""
    return f"{length:,.0f}" if length >= 100.0 else f"{length:.3g}"


def progress_title(filename):
    """The title of the progress dialog of an import of ``filename``."""
    return translate("Facet", "Importing {0} ...").format(os.path.basename(filename))


def _step(text=None):
    """Between two steps of an import: the open reporter's busy bar (``text``, when given,
    under its title), and facet.Cancelled when its Cancel was pressed."""
    import facet

    report = progress.hook()
    if report is None:
        return
    if text is not None:
        report.say(text)
    if report(0, 0):
        raise facet.Cancelled("import cancelled")


def report_cancelled(filename):
    """The report view's line for an import of ``filename`` cancelled."""
    report_message(f"Facet: {filename}: "
                   + translate("Facet", "import cancelled; nothing changed"))


def report_message(message):
    """One line in the report view."""
    App.Console.PrintMessage(message + "\n")


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
    """Read ``filename`` into a new document named after it; returns the document or None
    (a file it cannot read, or Cancel pressed: no document is left)."""
    obj = _imported(filename, None)
    return obj.Document if obj is not None else None


def insert(filename, docname, units="mm"):
    """Add ``filename`` (its numbers in ``units``) to the document ``docname`` (created if
    missing); returns the object, or None (a file it cannot read, or Cancel pressed: the
    document is as it was)."""
    return _imported(filename, docname, units)


def _imported(filename, docname, units="mm"):
    """The new PolyMesh of ``filename`` in the document ``docname`` (None: a new document
    named after the file), with progress and Cancel in the GUI; None when the file cannot
    be read (said in the report view and a message box) or the import was cancelled (said
    in the report view), every document then as it was."""
    import facet

    with progress.unless_reporting(progress_title(filename)):
        try:
            mesh = read_polymesh(filename, units)
        except MeshImportError as error:
            report_error(str(error))
            return None
        except facet.Cancelled:
            report_cancelled(filename)
            return None
        doc = None
        if docname is not None:
            try:
                doc = App.getDocument(docname)
            except NameError:
                pass
        created = doc is None
        if created:
            doc = App.newDocument(docname or os.path.splitext(os.path.basename(filename))[0])
        try:
            return _add_polymesh(mesh, filename, doc, units)
        except facet.Cancelled:
            if created:
                App.closeDocument(doc.Name)
            report_cancelled(filename)
            return None
