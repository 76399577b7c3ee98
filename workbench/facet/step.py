# SPDX-License-Identifier: LGPL-2.1-or-later
"""Panel solids through FreeCAD/OCC: Part solids and STEP files.

FreeCAD is imported only when a function here is called: inside FreeCAD it
is already there; from a plain Python it is looked for where Debian and the
FreeCAD AppImage/conda builds put its libraries (and in ``$FREECAD_LIB``).
When it cannot be imported, :class:`FreeCADMissing` says so in one line.

Each solid is built from shared edges (top ring, bottom ring, one edge per
side), so its faces share their edges and the shell is closed: a valid OCC
solid (BRepCheck) whose volume is the polyhedron's. The solids are handed
to OCC in its own BRep text format, computed here with numpy (see
:func:`panel_solids`).
"""

import functools
import os
import sys

import numpy as np

from facet.errors import Cancelled, FacetError

__all__ = ["FreeCADMissing", "SolidError", "StepJob", "import_freecad", "panel_solid",
           "panel_solids", "start_step", "write_step"]

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


#: tolerance of vertices, edges and faces that lie on their planes (OCC's
#: Precision::Confusion, model units); raised where a corner lies off a plane
_TOL = 1e-7
#: a face whose corners lie farther than this fraction of its panel's size
#: from their common plane is not planar: no solid is made
_PLANAR_REL = 1e-6
#: panels per BRep text read at once (progress and cancelling between them)
_SOLID_CHUNK = 1000

_HEADER = "\nCASCADE Topology V1, (c) Matra-Datavision\nLocations 0\nCurve2ds 0\n"


class SolidError(FacetError):
    """A panel's outlines do not bound a valid solid (the message names it)."""


@functools.lru_cache(maxsize=None)
def _topology(k):
    """The boundary of a k-cornered panel: (edges, loops, loop corners, edge faces).

    Corners: top 0..k-1, bottom k..2k-1. Edges: top i (top i -> top i+1) is
    i, bottom i is k + i, side i (bottom i -> top i) is 2k + i. Faces: the
    bottom, side i (bottom i, bottom i+1, top i+1, top i) as face 1 + i, the
    top last, so that OCC lists the corners (``Shape.Vertexes``) as the
    solids built face by face did: bottom 0..k-1, then top 1, 0, 2, ..., k-1.
    Each loop is [(edge, forward)], counter-clockwise about the outward
    normal when the top ring turns counter-clockwise seen from above the top
    (the bottom's edges are listed against their order around it, which OCC
    does not mind).
    """
    edges = ([(i, (i + 1) % k) for i in range(k)]
             + [(k + i, k + (i + 1) % k) for i in range(k)]
             + [(k + i, i) for i in range(k)])
    loops = [[(k + i, False) for i in range(k)]]
    corners = [[k + (i + 1) % k for i in reversed(range(k))]]
    for i in range(k):
        j = (i + 1) % k
        loops.append([(k + i, True), (2 * k + j, True), (i, False), (2 * k + i, False)])
        corners.append([k + i, k + j, j, i])
    loops.append([(i, True) for i in range(k)])
    corners.append(list(range(k)))
    edge_faces = ([(k + 1, 1 + i) for i in range(k)] + [(0, 1 + i) for i in range(k)]
                  + [(1 + i, 1 + (i - 1) % k) for i in range(k)])
    return edges, loops, corners, edge_faces


def _face_name(k, f):
    return "bottom" if f == 0 else "top" if f == k + 1 else f"side face {f - 1}"


@functools.lru_cache(maxsize=None)
def _template(k):
    """The text of one k-cornered solid's shapes in OCC's BRep format (V1),
    with a %-field for every number (tolerances, coordinates, curve and
    surface indices, edge lengths, shape references)."""
    edges, loops, _, _ = _topology(k)
    out = ["Ve\n%r\n%r %r %r\n0 0\n\n0101101\n*\n"] * (2 * k)
    out += ["Ed\n %r 1 1 0\n1  %d 0 0 %r\n0\n\n0101000\n+%d 0 -%d 0 *\n"] * (3 * k)
    for loop in loops:
        out.append("Wi\n\n0101100\n"
                   + " ".join(("+" if fwd else "-") + "%d 0" for _, fwd in loop) + " *\n")
        out.append(f"Fa\n0  {_TOL!r} %d 0\n\n0101000\n+%d 0 *\n")
    out.append("Sh\n\n0101100\n" + " ".join(["+%d 0"] * (k + 2)) + " *\n")
    out.append("So\n\n0100000\n+%d 0 *\n")
    return "".join(out)


def _dot(a, b):
    return np.einsum("...i,...i->...", a, b)


def _faces(top, bottom):
    """Planes of the faces of P panels with k corners (top, bottom: (P, k, 3)).

    Returns (planes (P, k+2, 12): centre, unit outward normal, x and y axes
    when the top ring turns counter-clockwise about the top's normal, else
    inward; deviation (P, k+2) of the corners from their face's plane;
    signed volume (P,))."""
    k = top.shape[1]
    _, _, corners, _ = _topology(k)
    v = np.concatenate([top, bottom], axis=1)
    origin = v.mean(axis=1)
    v = v - origin[:, None, :]
    planes, devs = [], []
    volume = np.zeros(len(v))
    for ring_index in corners:
        ring = v[:, ring_index]
        newell = np.cross(ring, np.roll(ring, -1, axis=1)).sum(axis=1)  # 2 area n
        volume += _dot(newell, ring[:, 0]) / 6.0
        n = newell / np.maximum(np.sqrt(_dot(newell, newell)), 1e-300)[:, None]
        c = ring.mean(axis=1)
        devs.append(np.abs(_dot(ring - c[:, None, :], n[:, None, :])).max(axis=1))
        x = ring[:, 1] - ring[:, 0]
        x = x - _dot(x, n)[:, None] * n
        x = x / np.maximum(np.sqrt(_dot(x, x)), 1e-300)[:, None]
        planes.append(np.concatenate([c + origin, n, x, np.cross(n, x)], axis=1))
    return np.stack(planes, axis=1), np.stack(devs, axis=1), volume


def _simple_rings(ids, rings, planes):
    """Raise SolidError unless each top and bottom ring is a simple polygon
    in its plane: convex ones by their turns, the others with shapely."""
    from shapely.geometry import Polygon

    k = rings[0].shape[1]
    # each ring in the order that turns counter-clockwise about its face's
    # normal (the bottom's normal was taken from it reversed)
    for f, name, ring in ((k + 1, "top", rings[0]), (0, "bottom", rings[1][:, ::-1])):
        c, n, x, y = (planes[:, f, 3 * i:3 * i + 3] for i in range(4))
        rel = ring - c[:, None, :]
        flat = np.stack([_dot(rel, x[:, None, :]), _dot(rel, y[:, None, :])], axis=2)
        d = np.roll(flat, -1, axis=1) - flat
        turn = np.arctan2(np.cross(d, np.roll(d, -1, axis=1)),
                          _dot(d, np.roll(d, -1, axis=1)))
        convex = (turn >= 0).all(axis=1) & (np.abs(turn.sum(axis=1) - 2 * np.pi) < 1e-6)
        for m in np.flatnonzero(~convex):
            if not Polygon(flat[m]).is_valid:
                raise SolidError(f"panel {ids[m]}: its {name} outline crosses itself")


def _solids_text(ids, tops, bottoms):
    """BRep text of a compound of the panels' solids, after checking that
    each is one: its corners finite, its faces planar and simple, its edges
    longer than their tolerance, its volume positive. Raises SolidError
    naming the first panel that is not."""
    n = len(tops)
    ks = np.array([len(t) for t in tops], dtype=np.int64)
    n_shapes = 7 * ks + 6  # vertices, edges, wires, faces, shell, solid
    before = np.concatenate([[0], np.cumsum(n_shapes)[:-1]])
    curve0 = np.concatenate([[0], np.cumsum(3 * ks)[:-1]])
    surface0 = np.concatenate([[0], np.cumsum(ks + 2)[:-1]])
    total = int(n_shapes.sum()) + 1  # and the compound
    # shapes are referred to by their position counted from the end
    ref0 = (total + 1 - before).astype(float)
    curves, surfaces, records = [None] * n, [None] * n, [None] * n
    sign = np.ones(n, dtype=np.int64)
    for k in (int(v) for v in np.unique(ks)):
        if k < 3:
            i = int(np.flatnonzero(ks == k)[0])
            raise SolidError(f"panel {ids[i]}: its outline has {k} corners")
        idx = np.flatnonzero(ks == k)
        gids = [ids[i] for i in idx]
        top = np.array([tops[i] for i in idx], dtype=float).reshape(len(idx), k, 3)
        bottom = np.array([bottoms[i] for i in idx], dtype=float).reshape(len(idx), k, 3)
        bad = ~(np.isfinite(top).all(axis=(1, 2)) & np.isfinite(bottom).all(axis=(1, 2)))
        if bad.any():
            raise SolidError(f"panel {gids[int(np.argmax(bad))]}: a corner is not finite")
        planes, dev, volume = _faces(top, bottom)
        # rings turning the other way: every face points inwards, so the
        # solid is written reversed (as the solids built face by face were)
        sign[idx] = np.where(volume < 0, -1, 1)
        volume = np.abs(volume)
        edges, loops, _, edge_faces = _topology(k)
        v = np.concatenate([top, bottom], axis=1)
        size = np.sqrt(_dot(v.max(axis=1) - v.min(axis=1), v.max(axis=1) - v.min(axis=1)))
        bad = dev > _PLANAR_REL * size[:, None]
        if bad.any():
            m, f = np.argwhere(bad)[0]
            raise SolidError(f"panel {gids[m]}: its {_face_name(k, f)} is not planar (corners "
                             f"{dev[m, f]:.3g} from its plane)")
        start = v[:, [a for a, _ in edges]]
        d = v[:, [b for _, b in edges]] - start
        length = np.sqrt(_dot(d, d))
        # an edge lies within its tolerance of both its faces' planes; and no tolerance is
        # below the rounding of the panel's coordinates (far from the origin, as map
        # coordinates in mm, 1e-7 is below one unit in the last place)
        floor = np.maximum(_TOL, 64.0 * np.finfo(float).eps * np.abs(v).max(axis=(1, 2)))
        edge_tol = np.maximum(floor[:, None], 2.0 * dev[:, np.array(edge_faces)].max(axis=2))
        bad = ~(length > 10.0 * edge_tol)
        if bad.any():
            m, e = np.argwhere(bad)[0]
            raise SolidError(f"panel {gids[m]}: edge {e} of its solid has no length "
                             f"({length[m, e]:.3g})")
        twisted = _dot(d[:, :k], d[:, k:2 * k]) <= 0  # a top edge against its bottom edge
        if twisted.any():
            m, e = np.argwhere(twisted)[0]
            raise SolidError(f"panel {gids[m]}: side face {e} is twisted (its top edge "
                             "runs against its bottom edge)")
        bad = ~(volume > 1e-9 * size ** 3)
        if bad.any():
            raise SolidError(f"panel {gids[int(np.argmax(bad))]}: its solid has no volume")
        _simple_rings(gids, (top, bottom), planes)
        incident = [[e for e, ab in enumerate(edges) if c in ab] for c in range(2 * k)]
        vertex_tol = np.stack([edge_tol[:, inc].max(axis=1) for inc in incident], axis=1)
        r0 = ref0[idx][:, None]
        ends = np.array(edges)
        cols = [np.concatenate([vertex_tol[:, :, None], v], axis=2).reshape(len(idx), -1),
                np.stack([edge_tol, curve0[idx][:, None] + 1.0 + np.arange(3 * k), length,
                          r0 - 1 - ends[:, 0], r0 - 1 - ends[:, 1]], axis=2)
                .reshape(len(idx), -1)]
        for f, loop in enumerate(loops):
            cols.append(r0 - (2 * k + 1) - np.array([e for e, _ in loop], dtype=float))
            cols.append(surface0[idx][:, None] + 1.0 + f)
            cols.append(r0 - (5 * k + 1 + 2 * f))
        cols.append(r0 - (5 * k + 2 + 2 * np.arange(k + 2, dtype=float)))
        cols.append(r0 - (7 * k + 5))
        values = np.concatenate(cols, axis=1).tolist()
        template = _template(k)
        lines = np.concatenate([start, d / length[..., None]], axis=2).tolist()
        plane_rows = planes.tolist()
        for m, i in enumerate(idx):
            records[i] = template % tuple(values[m])
            curves[i] = "".join(["1 %r %r %r %r %r %r\n" % tuple(r) for r in lines[m]])
            surfaces[i] = "".join(["1 %r %r %r %r %r %r %r %r %r %r %r %r\n" % tuple(r)
                                   for r in plane_rows[m]])
    compound = ("Co\n\n1100000\n"
                + " ".join("%+d 0" % r for r in
                           (sign * (total + 1 - before - n_shapes)).tolist())
                + " *\n")
    return "".join([_HEADER, "Curves %d\n" % int(3 * ks.sum())] + curves
                   + ["Polygon3D 0\nPolygonOnTriangulations 0\n",
                      "Surfaces %d\n" % int((ks + 2).sum())] + surfaces
                   + ["Triangulations 0\n\nTShapes %d\n" % total] + records
                   + [compound, "\n+1 0\n"])


def _read_solids(Part, ids, tops, bottoms, brepcheck):
    shape = Part.Shape()
    shape.importBrepFromString(_solids_text(ids, tops, bottoms), False)
    solids = shape.Solids
    if len(solids) != len(ids):
        raise SolidError(f"{len(ids)} panels gave {len(solids)} solids")
    if brepcheck:
        for pid, solid in zip(ids, solids):
            if not solid.isValid():
                raise SolidError(f"panel {pid}: its solid is not valid (BRepCheck)")
    return solids


def panel_solid(panel, Part=None, FreeCAD=None, brepcheck=True):
    """The OCC solid of one panel (a Part.Solid with outward faces); see
    :func:`panel_solids`."""
    if Part is None:
        FreeCAD, Part = import_freecad()
    pid = getattr(panel, "id", "?")
    return _read_solids(Part, [pid], [panel.top], [panel.bottom], brepcheck)[0]


def panel_solids(panel_set, progress=None, brepcheck=True):
    """[(id, Part.Solid)] for every panel; ``progress(done, total)`` returning
    True cancels (raises :class:`facet.Cancelled`).

    Each solid is a polyhedron bounded by its top, its bottom and one plane
    per side: its corners and edges are shared by the faces that meet there,
    so the shell is closed, and its faces point outwards. The solids are
    not built face by face through FreeCAD's Python (2 ms a panel, most of
    it a BRepCheck in ``Part.Shell``): the planes, lines and topology are
    computed here, vectorised, and read by OCC from its own BRep text format
    (:func:`_solids_text`), a thousand panels at a time. Tolerances are
    OCC's 1e-7 where corners lie on their planes, raised to twice a face's
    deviation where they do not quite (rounding at 40 m from the origin is
    ~1e-11), and never below 64 units in the last place of a panel's
    coordinates (a facade at map coordinates in mm: 1e-5 at 5.7e9).

    Before reading, every panel is checked: finite corners, faces planar to
    1e-6 of the panel's size, simple top and bottom outlines, untwisted side
    faces, edges longer than ten times their tolerance, a positive volume;
    :class:`SolidError` names the first panel that fails. With
    ``brepcheck`` (default) each solid is also checked by OCC's
    BRepCheck_Analyzer (``isValid``), which costs about as much again as
    building it.

    Raises
    ------
    SolidError, Cancelled, FreeCADMissing
    """
    FreeCAD, Part = import_freecad()
    panels = list(panel_set.panels)
    n = len(panels)
    out = []
    for c0 in range(0, n, _SOLID_CHUNK):
        chunk = panels[c0:c0 + _SOLID_CHUNK]
        ids = [p.id for p in chunk]
        solids = _read_solids(Part, ids, [p.top for p in chunk], [p.bottom for p in chunk],
                              brepcheck)
        out.extend(zip(ids, solids))
        if progress is not None and progress(len(out), n):
            raise Cancelled("solids cancelled")
    return out


def step_name(path):
    """The name of a STEP file's top assembly: the file's stem ("wave_facade_panels" for
    wave_facade_panels.step), "panels" for a file named only by its extension."""
    stem = os.path.basename(os.fspath(path))
    for ext in (".step", ".stp"):
        if stem.lower().endswith(ext):
            stem = stem[:-len(ext)]
    return stem or "panels"


def write_step(path, named_solids, pcurves=False, scale=1.0, name=None):
    """Write solids to a STEP file, each named by its ID (the product name
    FreeCAD's importer and other CAD systems show), in one assembly named `name`.

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
    scale : float
        Millimetres per model unit: STEP files are written in millimetres (OCC's
        unit), so a model in metres is scaled by 1000 on the way out.
    name : str, optional
        The top assembly's name, which a fabricator importing the file sees as its
        root (FreeCAD's App::Part, gmsh's ``Shapes/<name>/<ID>/<ID>``): by default
        :func:`step_name` of `path`, its stem. It was FreeCAD's temporary document's
        name, "FacetStepExport", in every file.

    Notes
    -----
    The solids are written as one assembly (FreeCAD's ``Import.export`` of an App::Part
    holding them, labelled `name`), one product per solid named by its ID. To read it back
    headless with FreeCAD 0.20, call ``Import.insert(path, doc, useLinkGroup=False)`` (or
    ``merge=False``): with the defaults (merge into one App::LinkGroup),
    ``Import.insert`` / ``Import.open`` crash freecadcmd on any STEP
    assembly, ours or not (the importer's link-group path needs the GUI). The
    panels then come in as Part::Feature objects labelled by their IDs.
    ``Part.read`` gives the solids without names.
    """
    FreeCAD, Part = import_freecad()
    import Import

    from facet.io.files import put_in_place

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
        for i, (part_id, solid) in enumerate(named_solids):
            obj = doc.addObject("Part::Feature", f"Panel{i:07d}")
            obj.Label = part_id
            if scale != 1.0:
                solid = solid.copy()
                solid.scale(scale)
            obj.Shape = solid
            objs.append(obj)
        # the root product is the exported App::Part's label (exporting the solids
        # alone named it after the document, which FreeCAD's names restrict)
        job = doc.addObject("App::Part", "Job")
        job.Label = step_name(path) if name is None else str(name)
        job.addObjects(objs)
        labels.SetBool("DuplicateLabels", user_duplicates)
        Part.setStaticValue("write.surfacecurve.mode", 1 if pcurves else 0)
        Import.export([job], tmp)
        # (inside facet.io.files.staged, with the run's other files, as StepJob's: the
        # cut sheets' STEP made from the PanelSet's solids took its place at once)
        put_in_place(tmp, path)
        tmp = None
    finally:
        labels.SetBool("DuplicateLabels", user_duplicates)
        Part.setStaticValue("write.surfacecurve.mode", user_mode)
        FreeCAD.closeDocument(doc.Name)
        if tmp is not None and os.path.exists(tmp):
            os.remove(tmp)


def _step_job(job, settings):
    """A worker's job: build the solids and write the STEP file. Returns
    ("ok", {stage: seconds}) or ("error", class name, message) for the
    errors :class:`StepJob` raises again in the parent."""
    import time

    path, ids, tops, bottoms = job  # path: the temporary file the parent renames
    brepcheck, pcurves, scale, name = settings
    try:
        t = time.perf_counter()
        FreeCAD, Part = import_freecad()
        solids = []
        for c0 in range(0, len(ids), _SOLID_CHUNK):
            c1 = c0 + _SOLID_CHUNK
            solids.extend(_read_solids(Part, ids[c0:c1], tops[c0:c1], bottoms[c0:c1],
                                       brepcheck))
        t1 = time.perf_counter()
        write_step(path, list(zip(ids, solids)), pcurves=pcurves, scale=scale, name=name)
        return ("ok", {"solids": t1 - t, "step": time.perf_counter() - t1})
    except (SolidError, FreeCADMissing) as exc:
        return ("error", type(exc).__name__, str(exc))


class StepJob:
    """Solids and STEP file of a panel set made in a worker process while
    this process goes on (:func:`start_step`); :meth:`wait` for the result.

    Attributes
    ----------
    seconds : dict
        After :meth:`wait`: wall time of "solids" and "step" in the worker
        (or here, when no worker process could run).
    in_worker : bool
    """

    def __init__(self, path, panel_set, brepcheck, pcurves, scale=1.0):
        import threading

        from facet.parallel import python_executable

        self.path = os.fspath(path)
        # written under another name, renamed by wait(): nothing appears at
        # `path` unless the whole job succeeded and was waited for
        self._tmp = f"{self.path}.part{os.getpid()}-{id(self):x}.step"
        self._panels = list(panel_set.panels)
        # (the assembly is named after `path`, not the temporary file)
        self._settings = (bool(brepcheck), bool(pcurves), float(scale), step_name(self.path))
        self._cancel = threading.Event()
        self._result = None
        self.seconds = {}
        self.in_worker = python_executable() is not None
        self._thread = None
        if self.in_worker:
            job = (self._tmp, [p.id for p in self._panels],
                   [np.asarray(p.top, dtype=float) for p in self._panels],
                   [np.asarray(p.bottom, dtype=float) for p in self._panels])
            self._thread = threading.Thread(target=self._run, args=(job,), daemon=True)
            self._thread.start()

    def _run(self, job):
        from facet.parallel import WorkerError, run_chunks

        try:
            self._result = run_chunks("facet.step:_step_job", [job], self._settings, 1,
                                      progress=lambda done, total: self._cancel.is_set())[0]
        except Cancelled:
            self._result = ("cancelled",)
        except WorkerError as exc:
            self._result = ("worker", str(exc))

    def _cleanup(self):
        """Remove what a stopped worker left: its file and write_step's own
        temporary one (a killed worker cleans nothing up)."""
        import glob

        for leftover in [self._tmp] + glob.glob(glob.escape(self._tmp) + ".tmp*.step"):
            if os.path.exists(leftover):
                os.remove(leftover)

    def cancel(self):
        """Stop the worker; nothing is written."""
        self._cancel.set()
        if self._thread is not None:
            self._thread.join()
        self._cleanup()

    def wait(self, progress=None):
        """Wait for the file; ``progress(done, total)`` (0 or 1 of 1)
        returning True cancels. Returns the path.

        Raises
        ------
        SolidError, FreeCADMissing, Cancelled, FacetError
        """
        import time

        if self._thread is None:  # no worker: made here, now
            t = time.perf_counter()
            solids = panel_solids(_Panels(self._panels), progress=progress,
                                  brepcheck=self._settings[0])
            t1 = time.perf_counter()
            write_step(self.path, solids, pcurves=self._settings[1], scale=self._settings[2])
            self.seconds = {"solids": t1 - t, "step": time.perf_counter() - t1}
            return self.path
        while self._thread.is_alive():
            self._thread.join(0.2)
            if progress is not None and progress(0, 1):
                self.cancel()
                raise Cancelled("STEP cancelled")
        result = self._result
        if result[0] != "ok":
            self._cleanup()
        if result[0] == "ok":
            from facet.io.files import put_in_place

            self.seconds = result[1]
            # (inside facet.io.files.staged, with the run's other files: before, it took
            # its place at once, beside the files of the last run if a later one failed)
            put_in_place(self._tmp, self.path)
            if progress is not None:
                progress(1, 1)
            return self.path
        if result[0] == "cancelled":
            raise Cancelled("STEP cancelled")
        if result[0] == "error":
            cls = {"SolidError": SolidError, "FreeCADMissing": FreeCADMissing}[result[1]]
            raise cls(result[2])
        raise FacetError(f"STEP: {result[1]}")


class _Panels:
    def __init__(self, panels):
        self.panels = panels


def start_step(path, panel_set, brepcheck=True, pcurves=False, scale=1.0):
    """Start making the panels' solids and their STEP file (as
    :func:`panel_solids` and :func:`write_step` do) in a worker process, so
    that nesting and the DXF can go on meanwhile; returns a :class:`StepJob`.

    Where no worker process can be started (no Python interpreter for it),
    the job is done by :meth:`StepJob.wait`, in this process.
    """
    return StepJob(path, panel_set, brepcheck, pcurves, scale)
