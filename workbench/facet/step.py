# SPDX-License-Identifier: LGPL-2.1-or-later
"""Panel solids through FreeCAD/OCC: Part solids and STEP files.

FreeCAD is imported only when a function here is called: inside FreeCAD it
is already there; from a plain Python it is looked for where Debian and the
FreeCAD AppImage/conda builds put its libraries (and in ``$FREECAD_LIB``).
When it cannot be imported, :class:`FreeCADMissing` says so in one line.

Each solid is built from shared edges (top ring, bottom ring, one edge per
side), so its faces share their edges and the shell is closed: a valid OCC
solid (BRepCheck) whose volume is the polyhedron's.
"""

import os
import sys

from facet.errors import Cancelled, FacetError

__all__ = ["FreeCADMissing", "import_freecad", "panel_solid", "panel_solids", "write_step"]

_CANDIDATES = (
    "/usr/lib/freecad-python3/lib",
    "/usr/lib/freecad/lib",
    "/usr/local/lib/freecad/lib",
    "/opt/freecad/lib",
)


class FreeCADMissing(FacetError):
    """FreeCAD's Python modules cannot be imported (STEP needs them)."""


def import_freecad():
    """Import FreeCAD and Part (and Import, for STEP).

    Returns
    -------
    (FreeCAD, Part)

    Raises
    ------
    FreeCADMissing
    """
    try:
        import FreeCAD  # noqa: F401
    except ImportError:
        extra = [os.environ.get("FREECAD_LIB", "")] + list(_CANDIDATES)
        for path in extra:
            if path and os.path.isdir(path) and path not in sys.path:
                sys.path.append(path)
        try:
            import FreeCAD  # noqa: F401,F811
        except ImportError as exc:
            raise FreeCADMissing(
                "STEP export needs FreeCAD, which was not found (looked in "
                f"{', '.join(p for p in extra if p)}; set FREECAD_LIB to its lib folder): "
                f"{exc}") from None
    import FreeCAD
    import Part

    return FreeCAD, Part


def panel_solid(panel, Part=None, FreeCAD=None):
    """The OCC solid of one panel (a Part.Solid with outward faces)."""
    if Part is None:
        FreeCAD, Part = import_freecad()
    V = FreeCAD.Vector
    top = [V(*map(float, p)) for p in panel.top]
    bottom = [V(*map(float, p)) for p in panel.bottom]
    k = len(top)
    top_edges = [Part.LineSegment(top[i], top[(i + 1) % k]).toShape() for i in range(k)]
    bot_edges = [Part.LineSegment(bottom[i], bottom[(i + 1) % k]).toShape() for i in range(k)]
    side_edges = [Part.LineSegment(bottom[i], top[i]).toShape() for i in range(k)]
    faces = [Part.Face(Part.Wire(top_edges)), Part.Face(Part.Wire(bot_edges))]
    for i in range(k):
        j = (i + 1) % k
        wire = Part.Wire([bot_edges[i], side_edges[j], top_edges[i], side_edges[i]])
        faces.append(Part.Face(wire))
    shell = Part.Shell(faces)
    solid = Part.Solid(shell)
    if solid.Volume < 0:
        solid.reverse()
    return solid


#: panels per chunk built in a worker process
_SOLID_CHUNK = 250


def panel_solids(panel_set, progress=None, workers=None):
    """[(id, Part.Solid)] for every panel; ``progress(done, total)`` returning
    True cancels (raises :class:`facet.Cancelled`).

    With ``workers`` > 1 (default 1: on the shared 2-CPU test machine two
    workers were slower, 11-14 s against 7.5-9 s for 2,000 panels, as each
    starts FreeCAD and the solids travel as text) chunks of solids are built
    in worker processes and come back as OCC's BRep text (coordinates to within a unit
    in the last place or so: 7e-11 mm at 40 m); when the workers cannot run
    (no FreeCAD for a plain Python), they are built here.
    """
    from facet.parallel import WorkerError, run_chunks

    FreeCAD, Part = import_freecad()
    panels = list(panel_set.panels)
    n = len(panels)
    chunks = [[(p.top, p.bottom) for p in panels[i:i + _SOLID_CHUNK]]
              for i in range(0, n, _SOLID_CHUNK)]
    workers = 1 if workers is None else max(1, int(workers))
    if workers > 1 and len(chunks) > 2:
        try:
            texts = run_chunks("facet.step:_solids_chunk", chunks, None,
                               min(workers, len(chunks)), progress=progress,
                               weights=[len(c) for c in chunks])
        except WorkerError:
            texts = None
        if texts is not None:
            solids = []
            for text in texts:
                shape = Part.Shape()
                shape.importBrepFromString(text, False)
                solids.extend(shape.Solids)
            if len(solids) == n:
                return [(p.id, s) for p, s in zip(panels, solids)]
    out = []
    for i, p in enumerate(panels):
        out.append((p.id, panel_solid(p, Part, FreeCAD)))
        if progress is not None and (i % 200 == 199 or i == n - 1) and progress(i + 1, n):
            raise Cancelled("solids cancelled")
    return out


class _Outline:
    __slots__ = ("top", "bottom")

    def __init__(self, top, bottom):
        self.top, self.bottom = top, bottom


def _solids_chunk(chunk, settings):
    """A worker's chunk: [(top, bottom)] -> BRep text of their compound."""
    FreeCAD, Part = import_freecad()
    solids = [panel_solid(_Outline(t, b), Part, FreeCAD) for t, b in chunk]
    return Part.makeCompound(solids).exportBrepToString()


def write_step(path, named_solids, pcurves=False):
    """Write solids to a STEP file, each named by its ID (the product name
    FreeCAD's importer and other CAD systems show).

    Parameters
    ----------
    path : str or os.PathLike
    named_solids : list of (str, Part.Solid)
    pcurves : bool
        Also write every edge's curve in the parameter space of its faces
        (OCC's ``write.surfacecurve.mode``). Panels are bounded by planes, for
        which a reader rebuilds them exactly; without them the file is half
        the size and written three times as fast. The setting of the session
        (FreeCAD's preference) is restored afterwards.

    Notes
    -----
    The solids are written as one assembly (FreeCAD's ``Import.export``), one
    product per solid named by its ID. To read it back headless with FreeCAD
    0.20, call ``Import.insert(path, doc, useLinkGroup=False)`` (or
    ``merge=False``): with the defaults (merge into one App::LinkGroup),
    ``Import.insert`` / ``Import.open`` crash freecadcmd on any STEP
    assembly, ours or not (the importer's link-group path needs the GUI). The
    panels then come in as Part::Feature objects labelled by their IDs.
    ``Part.read`` gives the solids without names.
    """
    FreeCAD, Part = import_freecad()
    import Import

    path = os.fspath(path)
    doc = FreeCAD.newDocument("FacetStepExport", hidden=True, temp=True)
    user_mode = FreeCAD.ParamGet("User parameter:BaseApp/Preferences/Mod/Part/General") \
        .GetInt("WriteSurfaceCurveMode", 1)
    # FreeCAD makes names and labels unique by scanning every object (each
    # addObject and Label costs O(objects): 10,000 panels took minutes). The
    # names given here are unique already, and so are the IDs, so labels are
    # not checked while they are set (the preference is restored).
    labels = FreeCAD.ParamGet("User parameter:BaseApp/Preferences/Document")
    user_duplicates = labels.GetBool("DuplicateLabels", False)
    tmp = f"{path}.tmp{os.getpid()}.step"
    try:
        labels.SetBool("DuplicateLabels", True)
        objs = []
        for i, (name, solid) in enumerate(named_solids):
            obj = doc.addObject("Part::Feature", f"Panel{i:07d}")
            obj.Label = name
            obj.Shape = solid
            objs.append(obj)
        labels.SetBool("DuplicateLabels", user_duplicates)
        Part.setStaticValue("write.surfacecurve.mode", 1 if pcurves else 0)
        Import.export(objs, tmp)
        os.replace(tmp, path)
    finally:
        labels.SetBool("DuplicateLabels", user_duplicates)
        Part.setStaticValue("write.surfacecurve.mode", user_mode)
        FreeCAD.closeDocument(doc.Name)
        if os.path.exists(tmp):
            os.remove(tmp)
