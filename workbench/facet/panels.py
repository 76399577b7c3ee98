# SPDX-License-Identifier: LGPL-2.1-or-later
"""Panels: a planar mesh turned into solid panels with edge cuts.

Every face becomes a slab of the given thickness. Its top and bottom outlines
are where its two offset planes meet its edge planes (square to the panel,
or mitred on the bisector of the two panels' planes), so each side face is
planar and the solid is a true polyhedron. The geometry comes from the
compiled core (``facet_panels`` in libfacet); this module names the parts,
lays each outline flat and measures what a schedule needs.

>>> result = panels(mesh, thickness=40, edge="bisector", gap=8)  # doctest: +SKIP
>>> result.panels[0].id, result.panels[0].bevel_deg              # doctest: +SKIP
('P-R01C01', [0.0, 2.5, 2.5, 0.0])

Conventions
-----------
Each panel's corners run counter-clockwise seen from its top (the +n side,
after orientation was made consistent and optionally flipped). Edge ``k``
runs from corner ``k`` to corner ``k+1``. Angles in the public attributes
are degrees. "Bottom" is the side that lies on the sheet when cut.
"""

import math
from dataclasses import dataclass, field

import numpy as np

from facet import _core
from facet.errors import Cancelled, InputError, from_core
from facet.mesh import PolyMesh, next_corners
from facet.quality import DEFAULT_SHORT_EDGE
from facet.report import (count_noun, degrees_text, face_degrees, first_names, length_text,
                           point_text)

__all__ = ["PanelError", "Panel", "PanelSet", "panels", "OFFSETS", "EDGES", "ID_SCHEMES",
           "grid_positions", "DEFAULT_GAP_MM", "DEFAULT_MIN_EDGE", "check_density",
           "mass_kg"]

#: Default of ``panels(min_edge=...)``: an edge shorter than this fraction of
#: the mean edge of a face beside it has vanished, and its two ends become one
#: corner. It is the quality report's degenerate short edge
#: (:data:`facet.quality.DEFAULT_SHORT_EDGE`, 1%), so the faces the report
#: calls degenerate for a short edge are the panels built with fewer corners.
DEFAULT_MIN_EDGE = DEFAULT_SHORT_EDGE

#: The joint width between panels that ``facet panels`` and FreeCAD's PanelSet use unless
#: told otherwise, in millimetres (converted to the model's units; :func:`panels` itself
#: takes its ``gap`` in model units and defaults to 0). A glass or metal facade has no
#: joint of width 0: its panels need room for tolerances and movement, and a sealed joint's
#: silicone is at least 6 mm wide. Square cuts close a joint on the inner side of a fold by
#: about 2 t tan(fold/2); with no gap the panels overlapped there on every valley, and
#: mitred ones at the nodes: a first PanelSet of the bundled facade (40 mm, square) had 16
#: of its 32 panels red, of ``make demo``'s mesh 216 of 280. 6 mm clears both (their
#: clearing gaps 1.25 and 2.99 mm), as it does at the demo's own 8 mm (0.60 mm); sharper
#: folds still overlap and are reported (the roof example's 30 mm panels need 18.3 mm).
DEFAULT_GAP_MM = 6.0

#: Offset sides: where the panel lies relative to the mesh surface.
OFFSETS = ("outer", "inner", "center")
#: Edge cuts.
EDGES = ("square", "bisector")
#: Part-ID schemes: "auto" is "grid" when the mesh is a regular quad grid,
#: else "index".
ID_SCHEMES = ("auto", "grid", "index")

_PANEL_STATUSES = {
    "FACET_ERROR_NOT_PLANAR",
    "FACET_ERROR_NOT_ORIENTABLE",
    "FACET_ERROR_PANEL_GEOMETRY",
    "FACET_ERROR_INVALID_ARGUMENT",
}


class PanelError(InputError):
    """The mesh or the panel options cannot make panels.

    Attributes
    ----------
    faces : list of int
        The faces concerned (for non-planar faces: all of them), may be empty.
    """

    def __init__(self, message, faces=()):
        super().__init__(message)
        self.faces = list(faces)


@dataclass
class Panel:
    """One panel: a planar slab cut from its face.

    Attributes
    ----------
    id : str
        Part ID (``"P-R03C12"`` on a grid, ``"P-0042"`` otherwise).
    face : int
        Index of its face in the mesh.
    vertices : numpy.ndarray
        Mesh vertex of each corner (int), counter-clockwise from the top.
    top, bottom : numpy.ndarray
        (k, 3) outline corners of the top and bottom faces, model units.
    flat_top, flat_bottom : numpy.ndarray
        (k, 2) the same outlines laid flat in the panel's own frame (see
        `frame`): the top seen from above, the bottom in the same view.
    frame : numpy.ndarray
        (3, 4) rigid transform ``flat = R @ x + t`` (R = frame[:, :3], t =
        frame[:, 3]): the face's first input corner to the origin, its first
        input edge along +x, its normal to +z. Where a short edge vanished there (see
        ``min_edge``), the first corner and edge that remain of the face.
    normal : numpy.ndarray
        Unit normal (top side).
    edge_lengths : list of float
        Bottom outline edge lengths, model units.
    bevel_deg : list of float
        Per edge, the side face's angle from square (0 for square cuts;
        positive when the top is the larger face).
    dihedral_deg : list of float
        Per edge, the angle between the two panels on their bottom side
        (180 when flat; None on the boundary).
    neighbors : list of int or None
        Per edge, the face across it (None on the boundary).
    dropped_edges : int
        Edges of the face that the joint gap (or a bevel) consumed: the
        outline drops them, so the panel has that many corners fewer than its
        face (`vertices` keeps the last mesh vertex of each merged corner).
    squared_edges : int
        Mitred edges cut square instead, because their mitre would consume a
        short edge, meet beyond a nearly straight corner, or meet a cut of
        another angle at a straight corner (bevel 0): butt
        joints, whose other half is the neighbour's...
    butt_edges : int
        ... edge cut on this panel's square plane, with the whole fold (the
        joint stays a slot of constant width).
    joint_widths : list of float or None
        Per edge, the narrowest width of its joint across the joint's section
        (the same along the edge), model units: the gap where the joint is
        mitred or a butt joint; cut square across a fold, less on the fold's
        inner side, and negative where the gap is too small for the fold and
        the two panels overlap (minus how deep: the least overlap of their
        sections along the normals of their planes and side planes). None on
        the boundary and where a panel dropped the edge.
    clash : float
        How deep the panel overlaps another one, across a joint or at a node
        (model units, the deepest); 0 when it overlaps none.
    """

    id: str
    face: int
    vertices: np.ndarray
    top: np.ndarray
    bottom: np.ndarray
    flat_top: np.ndarray
    flat_bottom: np.ndarray
    frame: np.ndarray
    normal: np.ndarray
    thickness: float
    edge_lengths: list
    bevel_deg: list
    dihedral_deg: list
    neighbors: list
    grid: tuple = None
    dropped_edges: int = 0
    squared_edges: int = 0
    butt_edges: int = 0
    input_corners: int = None
    joint_widths: list = None
    clash: float = 0.0

    def __post_init__(self):
        if self.input_corners is None:
            self.input_corners = len(self.vertices) + self.dropped_edges
        if self.joint_widths is None:
            self.joint_widths = [None] * len(self.vertices)

    @property
    def narrowest_joint(self):
        """The narrowest of its joints (negative: it overlaps a neighbour by
        that much), or None when it has no neighbour."""
        widths = [w for w in self.joint_widths if w is not None]
        return min(widths) if widths else None

    @property
    def corners(self):
        """Number of corners of the panel."""
        return len(self.vertices)

    @property
    def vanished_edges(self):
        """How many of its face's edges vanished (their ends merged into one
        corner): a quad built as a triangle has 1."""
        return int(self.input_corners) - len(self.vertices) - int(self.dropped_edges)

    @property
    def area(self):
        """Area of the bottom face, model units squared."""
        return _polygon_area(self.flat_bottom)

    @property
    def area_top(self):
        """Area of the top face."""
        return _polygon_area(self.flat_top)

    @property
    def perimeter(self):
        """Perimeter of the bottom face."""
        return float(sum(self.edge_lengths))

    @property
    def flat(self):
        """(k, 2) the cut outline on the sheet: the bottom face, flat."""
        return self.flat_bottom

    def footprint(self):
        """The flat solid seen from above (shapely Polygon): the union of
        the top, the bottom and every side face, what the sheet must hold."""
        from shapely.geometry import Polygon
        from shapely.ops import unary_union

        top, bottom = self.flat_top, self.flat_bottom
        if np.allclose(top, bottom, rtol=0.0, atol=1e-9 * max(1.0, np.abs(bottom).max())):
            return Polygon(bottom.tolist())
        k = len(bottom)
        b, t = bottom.tolist(), top.tolist()
        parts = [Polygon(b), Polygon(t)]
        for i in range(k):
            j = (i + 1) % k
            # the side face seen from above: a trapezoid (its top and bottom
            # edges are parallel), simple whenever it has an area
            quad = Polygon([b[i], b[j], t[j], t[i]])
            if quad.area > 1e-12 * parts[0].area:
                parts.append(quad)
        return unary_union(parts)

    @property
    def size(self):
        """(width, height) of the footprint's bounding box in the panel's
        frame (width along its first edge)."""
        pts = np.vstack([self.flat_top, self.flat_bottom])
        span = pts.max(axis=0) - pts.min(axis=0)
        return float(span[0]), float(span[1])

    @property
    def volume(self):
        """Volume of the solid (divergence theorem over its planar faces)."""
        k = len(self.top)
        faces = [list(self.top), list(self.bottom[::-1])]
        for i in range(k):
            j = (i + 1) % k
            faces.append([self.bottom[i], self.bottom[j], self.top[j], self.top[i]])
        origin = self.bottom.mean(axis=0)
        vol = 0.0
        for poly in faces:
            a = np.asarray(poly) - origin
            for m in range(1, len(a) - 1):
                vol += np.dot(a[0], np.cross(a[m], a[m + 1]))
        return float(abs(vol) / 6.0)

    def side_faces(self):
        """List of (4, 3) arrays: each side face (bottom i, bottom i+1, top
        i+1, top i), planar by construction."""
        k = len(self.top)
        return [np.array([self.bottom[i], self.bottom[(i + 1) % k], self.top[(i + 1) % k],
                          self.top[i]]) for i in range(k)]

    def schedule_row(self):
        """A dict of plain values for the schedule."""
        w, h = self.size
        return {
            "id": self.id,
            "face": self.face,
            "corners": self.corners,
            "input_corners": int(self.input_corners),
            "area": self.area,
            "area_top": self.area_top,
            "perimeter": self.perimeter,
            "width": w,
            "height": h,
            "thickness": self.thickness,
            "volume": self.volume,
            "edge_lengths": [float(x) for x in self.edge_lengths],
            "bevel_deg": [float(x) for x in self.bevel_deg],
            "dihedral_deg": [None if x is None else float(x) for x in self.dihedral_deg],
            "dropped_edges": int(self.dropped_edges),
            "squared_edges": int(self.squared_edges),
            "butt_edges": int(self.butt_edges),
            "joint_widths": [None if x is None else float(x) for x in self.joint_widths],
            "narrowest_joint": self.narrowest_joint,
            "clash": float(self.clash),
        }


#: The gap that clears the nodes' overlaps is found to this fraction of itself...
_CLEARING_REL = 1e-4
#: ... in at most this many trials (each a whole panel computation).
_CLEARING_TRIALS = 40

#: Bevel angles (degrees) smaller than this are rounding, not a bevel: written as 0.
BEVEL_ZERO_DEG = 1e-9


def _least_passing(passes, lo, hi, progress, done, limit=math.inf):
    """The least value above `lo` (which fails) for which ``passes(value)``, to
    _CLEARING_REL of itself, by bisection: `hi` is tried first and doubled (up to
    `limit`, at most 20 times) until it passes; None when none does (or `lo` is `limit`
    or above: no larger value is tried). The value returned was tried. Each trial reports
    ``progress(done + trial, done + _CLEARING_TRIALS)``; a true return cancels."""
    trials = 0

    def trial(value):
        nonlocal trials
        trials += 1
        if progress is not None and progress(done + trials, done + _CLEARING_TRIALS):
            raise Cancelled("panels cancelled")
        return passes(value)

    hi = min(hi, limit)
    if not hi > lo:  # (a min_edge_abs given above the largest tried: not a larger one)
        return None
    while not trial(hi):
        if trials >= 20 or hi >= limit:
            return None
        lo, hi = hi, min(2.0 * hi, limit)
    while hi - lo > _CLEARING_REL * hi and trials < _CLEARING_TRIALS:
        mid = 0.5 * (lo + hi)
        if trial(mid):
            hi = mid
        else:
            lo = mid
    return float(hi)


def _clearing_gap(xyz, mesh, options, gap, joints, progress, done, builds_only=False):
    """The least gap (to _CLEARING_REL) at which no joint and no node overlaps, by
    bisection over whole panel computations (a wider gap moves every outline, so
    the nodes' overlaps have no closed form), from the joints' own clearing gap
    `joints` (None when no joint overlaps) up; None when none up to 2^20 times the
    first trial clears them, or the panels fail first. With `builds_only`, the least
    gap at which the panels are built at all (overlaps allowed: they are counted);
    the gap returned was tried. Reports ``progress(done + trial, done +
    _CLEARING_TRIALS)``; a true return cancels."""
    def clears(trial_gap):
        try:
            r = _core.panels(xyz, mesh.face_start, mesh.face_vertices, gap=trial_gap, **options)
        except _core.CoreError:
            return False
        return builds_only or (r["n_overlapping_joints"] == 0 and r["n_node_clashes"] == 0)

    return _least_passing(clears, gap, max(joints or 0.0, 2.0 * gap, 0.01 * options["thickness"]),
                          progress, done)


def _builds(xyz, mesh, options, gap):
    """Whether the core builds the panels with these options at this gap."""
    try:
        _core.panels(xyz, mesh.face_start, mesh.face_vertices, gap=gap, **options)
    except _core.CoreError:
        return False
    return True


def _rounded_up(value, passes):
    """(said, digits): `value` as a message writes it (3 significant digits, more when
    those do not pass), rounded up, and checked: ``passes(said)``; None when no
    rounding passes."""
    for digits in (3, 4, 6, 17):
        said = float(f"{value:.{digits}g}")
        if said < value:  # up by one in the last digit written
            said = float(f"{said + 10.0 ** (math.floor(math.log10(said)) - digits + 1):.{digits}g}")
        if said >= value and passes(said):
            return said, digits
    return None


def _corner_angles(mesh, f):
    """Face f's interior angles (degrees, over 180 at a reflex corner), by corner, in its
    plane (the winding's side of its Newell normal)."""
    p = np.asarray(mesh.vertices)[mesh.face_vertices[mesh.face_start[f]:mesh.face_start[f + 1]]]
    n = np.cross(p, np.roll(p, -1, axis=0)).sum(axis=0)
    before, after = p - np.roll(p, 1, axis=0), np.roll(p, -1, axis=0) - p
    turn = np.degrees(np.arctan2(np.cross(before, after) @ n / np.linalg.norm(n),
                                 np.einsum("ij,ij->i", before, after)))
    return 180.0 - turn, n / np.linalg.norm(n)


#: How ``panels()``'s messages name the options a caller's user sets (the value follows):
#: the Python keywords; the command line and the FreeCAD PanelSet give theirs
#: (``panels(option_names=...)``).
OPTION_NAMES = {"min_edge": "min_edge", "min_edge_abs": "min_edge_abs", "ids": "ids"}

#: The largest min_edge tried for a failed joint: an edge half its face's mean edge long
#: is no short edge to merge (and min_edge_abs is tried up to this times the largest
#: face's mean edge).
_MIN_EDGE_TRIED = 0.5


def _not_a_grid(mesh, source, names):
    """Why part IDs by row and column (ids "grid") do not fit ``mesh`` (read from the file
    ``source``, if any): its faces by kind, or, all quads, that they are no complete grid;
    and what to choose instead."""
    degrees = face_degrees(mesh)
    what = (f"its {count_noun(mesh.n_faces, 'quad')} are not in complete rows and columns"
            if set(degrees) == {"4"} else f"it has {degrees_text(degrees)}")
    return (f"{source + ': ' if source else ''}"
            f"{names['ids']} grid (part IDs by row and column) needs a mesh of quads in "
            f"complete rows and columns, and {what}: choose auto or index")


def _failed_joint_message(exc, mesh, options, gap, length, progress, rebuild, min_edge,
                          min_edge_abs, names, where):
    """The error of the joint of faces ``exc.joint_faces`` at the first's edge from
    ``exc.vertex``, which had to be cut square on both panels and overlaps
    (``exc.joint_overlap`` deep), as one sentence: the edge (length, fold), the corners at
    its ends on both panels and why each consumes its mitre (a nearly straight corner
    named), then only what was tried and builds the panels: the least larger gap, the
    least larger min_edge (and min_edge_abs when one was given; ``rebuild(min_edge,
    min_edge_abs)`` tells whether they build the panels), square edges; else that only a
    change of the mesh there does. None when the edge is not found."""
    from facet.quality import DEFAULT_STRAIGHT_CORNER

    f, h = (int(x) for x in exc.joint_faces)
    vertex = int(exc.vertex)
    start, fv = mesh.face_start, mesh.face_vertices
    corners = [int(c) for c in range(start[f], start[f + 1]) if fv[c] == vertex]
    if not corners:
        return None
    c = corners[0]
    other = int(fv[c + 1] if c + 1 < start[f + 1] else fv[start[f]])
    if not {vertex, other} <= {int(v) for v in fv[start[h]:start[h + 1]]}:
        return None  # (the other face does not hold that edge: no joint to explain)
    points = np.asarray(mesh.vertices)
    edge = float(np.linalg.norm(points[other] - points[vertex]))
    parts, why, normals = [], [], []
    for g in (f, h):
        angles, n = _corner_angles(mesh, g)
        normals.append(n)
        ring = [int(v) for v in fv[start[g]:start[g + 1]]]
        at = {v: float(angles[ring.index(v)]) for v in (vertex, other) if v in ring}
        parts.append(f"face {g} {at[vertex]:.3g} and {at[other]:.3g} degrees")
        straight = min((abs(180.0 - a), v, a) for v, a in at.items())
        why.append(None if straight[0] >= DEFAULT_STRAIGHT_CORNER else
                   # a vertex on a straight edge (a T-junction): the edges there are cut
                   # alike or not at all, and the edge beside it was cut at another angle
                   f"on face {g} it meets a cut of another angle at the straight corner at "
                   f"vertex {straight[1]} (a vertex on a straight edge)"
                   if straight[0] < _STRAIGHT_DEG else
                   f"on face {g} it meets the next edge's beyond the nearly straight corner "
                   f"at vertex {straight[1]} ({straight[2]:.4g} degrees)")
    consumed = "the gap and the bevels consume the edge between those corners"
    if why == [None, None]:
        why = f"{consumed} on both panels"
    else:
        why = ", and ".join(w or f"on face {g} {consumed}" for w, g in zip(why, (f, h)))
    # the windings run the shared edge opposite ways when they agree
    ring_h = [int(v) for v in fv[start[h]:start[h + 1]]]
    same = ring_h[(ring_h.index(vertex) + 1) % len(ring_h)] == other
    fold = math.degrees(math.acos(float(np.clip(
        np.dot(normals[0], -normals[1] if same else normals[1]), -1.0, 1.0))))
    text = (f"faces {f} and {h}: their mitre at the edge from vertex {vertex} to "
            f"vertex {other} cannot be cut: the edge is {length(edge)} long and folds "
            f"{fold:.3g} degrees, the corners at its ends (vertices {vertex} and {other}) are "
            f"{parts[0]}, {parts[1]}; {why}; cut square on both, the panels "
            f"overlap by {length(float(exc.joint_overlap))} there{where}")
    xyz = np.ascontiguousarray(mesh.vertices, dtype=np.float64).reshape(-1)
    ways = []  # (what builds the panels, whether its verb is plural)
    built = _clearing_gap(xyz, mesh, options, gap, None, progress, 0, builds_only=True)
    said = None if built is None else _rounded_up(
        built, lambda g: _builds(xyz, mesh, options, g))
    if said is not None:
        ways.append((f"a gap of {length(said[0], f'.{said[1]}g')} (now {length(gap)})", False))
    # a larger min_edge merges the short edge's (or another's) ends into one corner
    # before the core runs; tried as the user gives it: relative, and absolute if used
    tries = [("min_edge", min_edge, _MIN_EDGE_TRIED, lambda m: rebuild(m, min_edge_abs),
              lambda x, spec: f"{x:{spec}}")]
    if min_edge_abs > 0.0:
        means = [np.mean(np.linalg.norm(np.diff(points[fv[start[g]:start[g + 1]]], axis=0,
                                                append=points[fv[start[g]]][None]), axis=1))
                 for g in range(mesh.n_faces)]
        tries.append(("min_edge_abs", min_edge_abs, _MIN_EDGE_TRIED * max(means),
                      lambda m: rebuild(min_edge, m), length))
    for k, (name, now, limit, passes, text_of) in enumerate(tries):
        least = _least_passing(passes, now, 2.0 * (now or DEFAULT_MIN_EDGE), progress,
                               (k + 1) * _CLEARING_TRIALS, limit)
        said = None if least is None else _rounded_up(least, passes)
        if said is not None:
            ways.append((f"{names[name]} {text_of(said[0], f'.{said[1]}g')} (now "
                         f"{text_of(now, 'g')})", False))
    if options["edge"] != "square" and _builds(xyz, mesh, dict(options, edge="square"), gap):
        ways.append(("square edges (their joints then report the gap that clears them)", True))
    mesh_change = (f"a mesh without the short edge or the sharp corner there (merge "
                   f"vertices {vertex} and {other}, or planarize so that faces {f} and {h} "
                   "keep their shape)")
    if ways:
        first, plural = ways[0]
        return (f"{text}: {first} {'build' if plural else 'builds'} the panels"
                + "".join(f"; so {'do' if plural else 'does'} {w}" for w, plural in ways[1:])
                + f"; or {mesh_change}")
    return (f"{text}: neither a larger gap, a larger {names['min_edge']} nor square edges "
            f"(tried) build them: change the mesh, {mesh_change}")


# A corner this close to 180 degrees is straight for the error's explanation: the core
# finds no corner beyond it (its edges' planes meet the top and bottom planes in one line
# or in parallel ones, to 1e-9 of the mesh's size; 1e-9 rad is 5.7e-8 degrees).
_STRAIGHT_DEG = 1e-6


def _node_clashes(result, depth):
    """The nodes where panels overlap (the core's depth per vertex), deepest
    first: vertex, depth and the IDs of the panels at the node."""
    nodes = np.flatnonzero(depth > 0.0)
    if not nodes.size:
        return []
    at = {int(v): [] for v in nodes}
    for p in result:
        for v in p.vertices:
            if int(v) in at:
                at[int(v)].append(p.id)
    clashes = [{"vertex": v, "depth": float(depth[v]), "panels": tuple(ids)}
               for v, ids in at.items()]
    clashes.sort(key=lambda d: (-d["depth"], d["vertex"]))
    return clashes


def _polygon_area(p):
    x, y = p[:, 0], p[:, 1]
    return float(0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


@dataclass
class PanelSet:
    """Panels of a mesh and the facts found making them.

    Attributes
    ----------
    panels : list of Panel
        One per face, in face order.
    options : dict
        thickness, offset, gap, edge, flip, tolerances, id scheme.
    id_scheme : str
        "grid" or "index" (what "auto" chose).
    grid_shape : tuple or None
        (rows, columns) when the mesh is a grid.
    node_deviation_deg : numpy.ndarray
        Per vertex, how far its edge planes are from sharing a line (degrees).
    max_node_deviation_deg : float
    worst_node : int or None
    planarity : numpy.ndarray
        Per face, its largest vertex distance from its plane.
    n_reversed : int
        Faces whose winding was reversed to make orientation consistent.
    n_components : int
    warnings : list of str
    seconds : float
        Wall time of the geometry.
    vanished_edges : list of dict
        The edges shorter than ``min_edge`` whose ends were merged into one
        corner: ``vertices`` (the two mesh vertices), ``length``, ``faces``
        (the faces beside it, each a panel with one corner fewer), ``vertex``
        (the vertex that stands for the merged corner) and ``moved`` (how far
        the merged corner lies from the farther end).
    short_edges_kept : list of dict
        Edges shorter than ``min_edge`` left as they are: ``vertices``,
        ``length``, ``faces``, ``reason`` ("planarity": merging their ends
        would bend ``face`` beyond the planarity tolerance, its corners
        ``planarity`` from its plane; "corners": it would leave ``face``, a
        needle triangle, with fewer than 3 corners; ``planarity`` None).
    narrowest_repaired_joint : float or None
        The narrowest joint where a mitre that could not be cut was repaired,
        across its section at its edge's midpoint (model units): the gap at a
        butt joint, less where the joint had to be square on both panels
        across a fold. None when nothing was repaired.
    narrowest_joint : float or None
        The narrowest joint between any two neighbouring panels across its
        section (see ``Panel.joint_widths``; negative: the deepest overlap).
        None when no two panels share an edge.
    narrowest_joint_panels : tuple of str or None
        The IDs of the two panels it parts.
    overlapping_joints : int
        Joints whose panels overlap: cut square on the inner side of a fold
        with too small a gap (a mitre never overlaps).
    clearing_gap : float or None
        The least gap at which no panel would overlap another: with joints
        only, exactly across their sections; with node clashes, found by
        bisection over whole panel computations to 1e-4 of itself (a wider gap
        moves every outline). None when none overlaps, or no gap was found.
    node_clashes : list of dict
        The nodes where panels that meet there but not across a joint (a
        node's diagonal neighbours) overlap, deepest first: ``vertex``,
        ``depth`` (of its deepest such pair, model units) and ``panels`` (the
        IDs of every panel at the node). Where a node's edge planes miss a
        common axis, or with square cuts over a valley, such panels can run
        into each other. Two convex panels are tested exactly (separating
        axes); a concave one as convex pieces (its outline's triangles). Two
        panels across a joint are tested too at an end where either has a
        reflex corner: a concave panel can reach past its side plane there
        (the bevel of its other edge), which the joint's section does not see.
    node_clash_pairs : int
        How many such pairs overlap.
    deepest_node_clash_panels : tuple of str or None
        The IDs of the deepest pair.
    """

    panels: list
    options: dict
    id_scheme: str
    grid_shape: tuple
    node_deviation_deg: np.ndarray
    max_node_deviation_deg: float
    worst_node: object
    planarity: np.ndarray
    n_reversed: int
    n_components: int
    warnings: list = field(default_factory=list)
    seconds: float = 0.0
    vanished_edges: list = field(default_factory=list)
    short_edges_kept: list = field(default_factory=list)
    narrowest_repaired_joint: float = None
    narrowest_joint: float = None
    narrowest_joint_panels: tuple = None
    overlapping_joints: int = 0
    clearing_gap: float = None
    node_clashes: list = field(default_factory=list)
    node_clash_pairs: int = 0
    deepest_node_clash_panels: tuple = None

    @property
    def clashing_panels(self):
        """The panels that overlap another (across a joint or at a node)."""
        return [p for p in self.panels if p.clash > 0.0]

    @property
    def vanished_panels(self):
        """The panels built with fewer corners than their face has (a quad
        whose edge vanished, built as a triangle)."""
        return [p for p in self.panels if p.vanished_edges > 0]

    def __len__(self):
        return len(self.panels)

    def __iter__(self):
        return iter(self.panels)

    def by_id(self, part_id):
        """The panel with this ID (KeyError when none)."""
        for p in self.panels:
            if p.id == part_id:
                return p
        raise KeyError(part_id)

    def mean_edge_length(self):
        """The panels' mean edge length (their perimeters over their corners), model units;
        0 without panels."""
        corners = sum(p.corners for p in self.panels)
        return sum(p.perimeter for p in self.panels) / corners if corners else 0.0

    def schedule(self):
        """List of schedule rows (dicts), in panel order."""
        return [p.schedule_row() for p in self.panels]


def check_density(density):
    """`density` (kg/m³) as a float: a finite number > 0; :class:`PanelError` otherwise,
    naming it (a density of 0 would weigh every panel 0 kg without a word)."""
    return _check_float("density (kg/m³)", density, 0.0, True)


def mass_kg(volume, density, mm_per_unit=1.0):
    """The mass in kilograms of `volume` (model units cubed; an array too) of a material of
    `density` kg/m³, the model's length unit being `mm_per_unit` millimetres (1000 for
    metres): glass 2,500 kg/m³, aluminium 2,700, steel 7,850."""
    metres = mm_per_unit / 1000.0
    return np.asarray(volume, dtype=float) * (metres * metres * metres) * density


def _check_float(name, value, minimum, strict, unit=None):
    """`value` as a float, finite and > (`strict`) or >= `minimum`; else a PanelError
    naming `name` and the value, followed by `unit` (a length's, "mm") when finite."""
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise PanelError(f"{name} must be a number, not {value!r}") from None
    if not math.isfinite(value) or value < minimum or (strict and value == minimum):
        op = ">" if strict else ">="
        said = f"{value!r} {unit}" if unit and math.isfinite(value) else f"{value!r}"
        raise PanelError(f"{name} must be a finite number {op} {minimum:g}, not {said}")
    return value


def grid_positions(mesh, reversed_faces=None):
    """Row and column of every face when the mesh is a regular quad grid.

    Parameters
    ----------
    mesh : facet.PolyMesh
    reversed_faces : array of bool, optional
        Faces whose winding must be read backwards (from the core's
        orientation) so that every face turns the same way.

    Returns
    -------
    (rows, cols, positions) or None
        positions is an (n_faces, 2) int array of (row, column), 0-based,
        when the faces are quads whose adjacency is that of a complete
        rows x cols grid; None otherwise.
    """
    nf = mesh.n_faces
    start = np.asarray(mesh.face_start)
    fv = np.asarray(mesh.face_vertices)
    if nf == 0 or not np.all(np.diff(start) == 4):
        return None
    quads = fv.reshape(nf, 4).copy()
    if reversed_faces is not None:
        rev = np.asarray(reversed_faces, dtype=bool)
        quads[rev] = quads[rev][:, ::-1]
    edge_owner = {}
    for f in range(nf):
        q = quads[f]
        for k in range(4):
            key = (min(q[k], q[(k + 1) % 4]), max(q[k], q[(k + 1) % 4]))
            edge_owner.setdefault(key, []).append((f, k))
    if any(len(v) > 2 for v in edge_owner.values()):
        return None
    delta = ((-1, 0), (0, 1), (1, 0), (0, -1))
    pos = np.full((nf, 2), np.iinfo(np.int64).min, dtype=np.int64)
    rot = np.zeros(nf, dtype=np.int64)
    seen = np.zeros(nf, dtype=bool)
    seen[0] = True
    pos[0] = (0, 0)
    queue = [0]
    while queue:
        f = queue.pop()
        q = quads[f]
        for k in range(4):
            key = (min(q[k], q[(k + 1) % 4]), max(q[k], q[(k + 1) % 4]))
            for h, kh in edge_owner[key]:
                if h == f:
                    continue
                d = (k + rot[f]) % 4
                want = pos[f] + np.array(delta[d])
                want_rot = (d + 2 - kh) % 4
                if not seen[h]:
                    seen[h] = True
                    pos[h] = want
                    rot[h] = want_rot
                    queue.append(h)
                elif tuple(pos[h]) != tuple(want) or rot[h] != want_rot:
                    return None
    if not seen.all():
        return None
    pos -= pos.min(axis=0)
    rows, cols = (pos.max(axis=0) + 1).tolist()
    if rows * cols != nf or len({tuple(p) for p in pos.tolist()}) != nf:
        return None
    return int(rows), int(cols), pos


def _ids(n, scheme, prefix, grid):
    if scheme == "grid":
        rows, cols, pos = grid
        wr, wc = len(str(rows)), len(str(cols))
        wr, wc = max(wr, 2), max(wc, 2)
        return [f"{prefix}R{r + 1:0{wr}d}C{c + 1:0{wc}d}" for r, c in pos.tolist()]
    width = max(4, len(str(n)))
    return [f"{prefix}{f:0{width}d}" for f in range(n)]


def _check_face_areas(mesh, source):
    """Refuse a face with no area (collinear or coincident corners): it has no
    plane, so it cannot be a panel."""
    xyz = np.asarray(mesh.vertices, dtype=np.float64)
    start = np.asarray(mesh.face_start, dtype=np.int64)
    fv = np.asarray(mesh.face_vertices, dtype=np.int64)
    if fv.size == 0:
        return
    centre = xyz.mean(axis=0)
    p = xyz[fv] - centre
    degree = np.diff(start)
    face = np.repeat(np.arange(degree.size), degree)
    nxt = np.arange(fv.size) + 1
    last = start[1:] - 1
    nxt[last] = start[:-1]
    normal = np.zeros((degree.size, 3))
    np.add.at(normal, face, np.cross(p, p[nxt]))
    area = 0.5 * np.linalg.norm(normal, axis=1)
    edge = np.linalg.norm(p[nxt] - p, axis=1)
    mean_edge = np.bincount(face, weights=edge, minlength=degree.size) / degree
    bad = np.flatnonzero(~(area > 1e-12 * mean_edge * mean_edge))
    if bad.size:
        f = int(bad[0])
        where = f"{source}: " if source else ""
        more = f" ({bad.size} such faces)" if bad.size > 1 else ""
        raise PanelError(f"{where}face {f} has no area (its corners are collinear or "
                         f"coincide){more}", faces=bad.tolist())


#: model units: facet.step refuses a solid's edge under ten times its 1e-7
#: tolerance; a face that only a shorter edge keeps from being a line is a sliver
_SOLID_MIN_EDGE = 1e-6


def _ring(rep_of, fv, s, e):
    """A face's corners after merging (``rep_of`` maps each vertex to the one
    standing for it): runs of the same corner become one, cyclically."""
    ring = [int(v) for v in rep_of[fv[s:e]]]
    out = [v for k, v in enumerate(ring) if v != ring[k - 1]] if len(ring) > 1 else ring
    if not out:  # every corner merged into one
        out = ring[:1]
    return out


def _local_planarity(xyz, rings):
    """(max_abs, mean_edge) of these faces (rings of vertex indices into xyz),
    measured as the core measures planarity."""
    from facet.planarity import planarity

    used = sorted({v for r in rings for v in r})
    local = {v: i for i, v in enumerate(used)}
    sub = PolyMesh.from_faces(xyz[used], [[local[v] for v in r] for r in rings])
    rep = planarity(sub, threads=1)
    return rep.max_abs, rep.mean_edge


def _after(progress, first):
    """The core's progress(done, total) after `first` units of merging."""
    if progress is None or first == 0:
        return progress
    return lambda done, total: progress(first + done, first + total)


def _merge_short_edges(mesh, min_edge, min_edge_abs, tol, tol_abs, source, progress=None,
                       units=None):
    """Merge the two ends of every edge shorter than the limit into one corner.

    An edge is short when it is shorter than ``max(min_edge_abs, min_edge x
    the mean edge of a face beside it)``. Short edges that share a vertex
    make one group; each group becomes one vertex (its lowest index) in
    every face, so the faces beside the edge lose a corner and their
    neighbours still share their edges and nodes. The merged corner is the
    group's centroid or one of its vertices, whichever bends the faces
    around it least (the centroid whenever it keeps them within the
    tolerance); it lies within the group's edge lengths of every vertex it
    replaces. A group whose merge would bend a face beyond the planarity
    tolerance (``max(tol_abs, tol x mean edge)``, and beyond what the face
    already had), or leave a face with fewer than 3 corners (a needle
    triangle, whose short edge can still be cut), is left as it is and
    reported.

    Returns
    -------
    (PolyMesh, rep_of, vanished, kept, n_groups) or None when no edge is short
        The merged mesh has the input's vertices (the merged ones no longer
        used) and its faces in the same order; ``rep_of`` maps every vertex to
        the one standing for it.

    Raises
    ------
    PanelError
        A face would be left with fewer than 3 corners, or with a corner
        twice, by an edge too short for a solid (`_SOLID_MIN_EDGE`, or
        within the planarity tolerance): a sliver no panel can be made of.
    """
    if not (min_edge > 0.0 or min_edge_abs > 0.0):
        return None
    xyz = np.array(mesh.vertices, dtype=np.float64)
    fs = np.asarray(mesh.face_start, dtype=np.int64)
    fv = np.asarray(mesh.face_vertices, dtype=np.int64)
    nf, nv = fs.size - 1, xyz.shape[0]
    if fv.size == 0:
        return None
    degree = np.diff(fs)
    face = np.repeat(np.arange(nf), degree)
    nxt = next_corners(fs)
    a, b = fv, fv[nxt]
    length = np.linalg.norm(xyz[b] - xyz[a], axis=1)
    mean = np.bincount(face, weights=length, minlength=nf) / degree
    limit = np.maximum(min_edge_abs, min_edge * mean[face])
    short = np.flatnonzero(length < limit)
    if short.size == 0:
        return None
    where = f"{source}: " if source else ""

    # the short edges, and the faces beside each
    edges = {}
    for c in short.tolist():
        key = (int(min(a[c], b[c])), int(max(a[c], b[c])))
        edges.setdefault(key, float(length[c]))
    edge_faces = {}
    corner_key = np.minimum(a, b) * nv + np.maximum(a, b)
    beside = np.flatnonzero(np.isin(corner_key, corner_key[short]))
    for c in beside.tolist():
        key = (int(min(a[c], b[c])), int(max(a[c], b[c])))
        edge_faces.setdefault(key, []).append(int(face[c]))
    # groups of short edges sharing a vertex (union-find)
    parent = {}

    def find(v):
        parent.setdefault(v, v)
        while parent[v] != v:
            parent[v] = parent[parent[v]]
            v = parent[v]
        return v

    for u, v in edges:
        ru, rv = find(u), find(v)
        if ru != rv:
            parent[max(ru, rv)] = min(ru, rv)
    groups = {}
    for v in list(parent):
        groups.setdefault(find(v), []).append(v)
    group_edges = {}
    for key in edges:
        group_edges.setdefault(find(key[0]), []).append(key)
    # the corners of each vertex
    order = np.argsort(fv, kind="stable")
    vstart = np.searchsorted(fv[order], np.arange(nv + 1))

    rep_of = np.arange(nv, dtype=np.int64)
    vanished, kept = [], []
    # this step's share of the progress: one unit per group, before the
    # core's 2 per face (panels() adds the groups to the core's counts)
    total = len(groups) + 2 * nf
    for done, root in enumerate(sorted(groups)):
        if progress is not None and done % 64 == 0 and progress(done, total):
            raise Cancelled("panels cancelled")
        members = sorted(groups[root])
        keys = sorted(group_edges[root])
        faces = sorted({int(face[c]) for v in members for c in order[vstart[v]:vstart[v + 1]]})
        trial = rep_of.copy()
        trial[members] = root
        before = [_ring(rep_of, fv, fs[f], fs[f + 1]) for f in faces]
        after = [_ring(trial, fv, fs[f], fs[f + 1]) for f in faces]
        info = [{"vertices": [u, v], "length": edges[(u, v)],
                 "faces": sorted(edge_faces.get((u, v), []))} for u, v in keys]
        broken = [(f, ring) for f, ring in zip(faces, after)
                  if len(ring) < 3 or len(set(ring)) != len(ring)]
        if broken:
            f, ring = broken[0]
            u, v = next((k for k in keys if f in edge_faces.get(k, ())), keys[0])
            what = (f"{len(set(ring))} corners" if len(set(ring)) < 3 else "a corner twice")
            if edges[(u, v)] <= max(_SOLID_MIN_EDGE, tol_abs, tol * mean[f]):
                raise PanelError(
                    f"{where}face {f}: its edge {u}-{v} is {length_text(units)(edges[(u, v)])} "
                    "long, too short "
                    f"for a solid, and merging its ends would leave the face {what}: remove "
                    "the face (a sliver; facet cleanup does)", faces=[f])
            # a needle triangle: its short edge is a cut that can be made
            for d in info:
                d.update(face=f, reason="corners", planarity=None)
            kept.extend(info)
            continue
        old_dev, _ = _local_planarity(xyz, before)
        points = xyz[members]
        candidates = [points.mean(axis=0)] + [p for p in points]
        best = None
        trial_xyz = xyz.copy()
        for cand in candidates:
            trial_xyz[root] = cand
            dev, me = _local_planarity(trial_xyz, after)
            allowed = np.maximum(np.maximum(tol_abs, tol * me), old_dev)
            worst = int(np.argmax(dev - allowed))
            score = float(np.max(dev / np.where(allowed > 0, allowed, np.inf), initial=0.0))
            ok = bool(np.all(dev <= allowed))
            if best is None or (ok, -score) > (best[0], -best[1]):
                best = (ok, score, cand.copy(), worst, float(dev[worst]))
            if ok and cand is candidates[0]:
                break  # the centroid moves the vertices least
        ok, _, point, worst, worst_dev = best
        if not ok:
            for d in info:
                d.update(face=faces[worst], reason="planarity", planarity=worst_dev)
            kept.extend(info)
            continue
        moved = float(np.max(np.linalg.norm(points - point, axis=1)))
        for d in info:
            d.update(vertex=int(root), moved=moved)
        vanished.extend(info)
        rep_of[members] = root
        xyz[members] = point
    if not vanished:
        return None, rep_of, vanished, kept, len(groups)
    mapped = rep_of[fv]
    keep = mapped != mapped[nxt]
    new_degree = np.bincount(face[keep], minlength=nf)
    new_start = np.zeros(nf + 1, dtype=np.int64)
    np.cumsum(new_degree, out=new_start[1:])
    merged = PolyMesh(xyz, new_start, mapped[keep], info=mesh.info)
    return merged, rep_of, vanished, kept, len(groups)


def _unwelded_warnings(mesh):
    """A warning for vertices at one point that are not one vertex (an export that gives
    each face or part its own vertices): the panels there are not joined, so their edges
    there are cut square as the mesh's boundary is, with no bevel, and no clash between
    them is looked for."""
    from facet.mesh import unwelded_warning

    seam = unwelded_warning(mesh, "the panels there are not joined: their edges there are "
                                  "cut square, with no bevel, and not checked for clashes")
    return [] if seam is None else [seam]


def panels(mesh, thickness, offset="outer", gap=0.0, edge="square", flip=False, ids="auto",
           prefix="P-", tol=1e-6, tol_abs=0.0, min_edge=DEFAULT_MIN_EDGE, min_edge_abs=0.0,
           repair=True, progress=None, units=None, option_names=None):
    """Make the panels of a planar mesh.

    Parameters
    ----------
    mesh : facet.PolyMesh
        Faces planar within the tolerance (planarize it first); not modified.
    thickness : float
        Panel thickness, model units, > 0.
    offset : {"outer", "inner", "center"}
        Panel on the top (+n) side of the surface, the bottom side, or centred.
    gap : float
        Joint width between neighbours, model units, >= 0 (bisector edges:
        the constant width of the slot; square: each edge moves gap/2 into
        its panel).
    edge : {"square", "bisector"}
        Edge cuts perpendicular to the panel, or mitred.
    flip : bool
        Reverse every face's orientation (which side is the top).
    ids : {"auto", "grid", "index"} or sequence of str
        Part-ID scheme, or one ID per face.
    prefix : str
        Prefix of generated IDs.
    tol, tol_abs : float
        A face is planar when its vertices lie within max(tol_abs, tol x its
        mean edge length) of its plane.
    min_edge, min_edge_abs : float
        An edge shorter than max(min_edge_abs, min_edge x the mean edge of a
        face beside it) has vanished: its two ends become one corner in every
        face, so a quad whose edge vanished is built as a triangle panel, and
        the panel across that edge loses the same corner (the panels still
        meet along their edges and nodes). Planarization makes such edges
        wherever a skew quad is best made a triangle (hypar grids, dense
        subdivision patches); kept, they give a sliver side face, a cut of
        no length and a corner no fabricator can make, and under about 1e-6
        model units no solid at all (:mod:`facet.step` refuses it). The
        default, 1% of the face's mean edge, is the quality report's
        degenerate short edge (:data:`facet.quality.DEFAULT_SHORT_EDGE`), so
        the faces it calls degenerate for a short edge are the panels built
        with fewer corners; on a 1.5 m panel it is 15 mm, far above the
        length the solid needs. The merged corner moves no vertex farther
        than the edge's length; an edge whose merge would bend a face beyond
        the planarity tolerance, or leave a face (a needle triangle) with
        fewer than 3 corners, is left as it is and reported
        (``PanelSet.short_edges_kept`` and a warning); a triangle whose edge
        is too short for any solid is an error. 0 and 0 merge nothing.
        The panels' ``input_corners`` and the schedule's ``corners`` and
        ``input_corners`` tell which panels lost a corner.
    repair : bool
        Where the joint gap or a bevel turns an edge of a panel's outline
        around (a short edge, or two mitres of different angles meeting far
        beyond a nearly straight corner), or where a mitre and a cut of
        another angle meet at a straight corner (a vertex on a straight
        edge), repair it as a fabricator would:
        mitred joints there become butt joints (square on this panel, the
        whole fold on the neighbour's, the joint's width kept), and an edge
        still consumed is dropped from the outline as a CAD offset drops it
        (the panel has a corner fewer). ``Panel.squared_edges``,
        ``butt_edges``, ``dropped_edges``, the schedule and a warning say
        where. A joint that must be square on both panels and would make
        them overlap is an error. False: any such edge is an error.
    progress : callable, optional
        ``progress(done, total)``; returning True cancels (raises
        :class:`facet.Cancelled`).
    units : str, optional
        The model's length unit ("mm"), written after the lengths in errors and
        warnings; None writes them bare (model units).
    option_names : dict, optional
        How the user sets the options an error advises or names (:data:`OPTION_NAMES`'s
        keys, "min_edge", "min_edge_abs" and "ids"): the command line's "--min-edge",
        FreeCAD's "the PanelSet's MinEdge"; the Python keywords by default.

    Returns
    -------
    PanelSet

    Raises
    ------
    PanelError
        Bad option, faces not planar (``error.faces`` lists them all), a
        non-orientable surface, a gap/bevel that consumes a panel, or a face
        that an edge too short for a solid would leave with fewer than 3
        corners (a sliver triangle: remove it from the mesh).
    facet.MeshError
        The mesh is not valid.
    """
    thickness = _check_float("thickness", thickness, 0.0, True, units)
    gap = _check_float("gap", gap, 0.0, False, units)
    tol = _check_float("tol", tol, 0.0, False)
    tol_abs = _check_float("tol_abs", tol_abs, 0.0, False, units)
    min_edge = _check_float("min_edge", min_edge, 0.0, False)
    min_edge_abs = _check_float("min_edge_abs", min_edge_abs, 0.0, False, units)
    if min_edge >= 1.0:
        # below 1 a face always keeps an edge at least its mean long
        raise PanelError(f"min_edge must be below 1 (a fraction of the face's mean edge), "
                         f"not {min_edge!r}")
    if offset not in OFFSETS:
        raise PanelError(f"offset must be one of {', '.join(OFFSETS)}, not {offset!r}")
    if edge not in EDGES:
        raise PanelError(f"edge must be one of {', '.join(EDGES)}, not {edge!r}")
    source = mesh.info.get("source") if mesh.info else None
    length = length_text(units)
    report = mesh.validate()
    _check_face_areas(mesh, source)
    input_mesh = mesh
    merged = _merge_short_edges(mesh, min_edge, min_edge_abs, tol, tol_abs, source, progress,
                                units)
    rep_of, vanished, kept, n_groups = None, [], [], 0
    if merged is not None:
        merged_mesh, rep_of, vanished, kept, n_groups = merged
        if merged_mesh is not None:
            mesh = merged_mesh
    nf, nv = mesh.n_faces, mesh.n_vertices
    nc = int(mesh.face_start[-1])
    out = {
        "plane": np.empty(4 * nf),
        "top": np.empty(3 * nc),
        "bottom": np.empty(3 * nc),
        "frame": np.empty(12 * nf),
        "reversed": np.empty(nf, dtype=np.int32),
        "neighbor": np.empty(nc, dtype=np.int32),
        "dihedral": np.empty(nc),
        "bevel": np.empty(nc),
        "node_deviation": np.empty(nv),
        "planarity": np.empty(nf),
        "nonplanar": np.full(nf, -1, dtype=np.int32),
        "dropped": np.zeros(nc, dtype=np.int32),
        "squared": np.zeros(nc, dtype=np.int32),
        "joint": np.zeros(nc),
        "node_clash": np.zeros(nv),
        "clash": np.zeros(nf),
    }
    xyz = np.ascontiguousarray(mesh.vertices, dtype=np.float64).reshape(-1)
    core_options = {"thickness": thickness, "offset": offset, "edge": edge, "flip": bool(flip),
                    "tol_abs": tol_abs, "tol_rel": tol, "repair_consumed": bool(repair)}
    try:
        res = _core.panels(xyz, mesh.face_start, mesh.face_vertices, gap=gap,
                           progress=_after(progress, n_groups), length_unit=units or None,
                           **core_options, **out)
    except _core.CoreError as exc:
        name = getattr(exc, "status_name", None)
        if name == "FACET_ERROR_CANCELLED" or isinstance(exc, _core.Cancelled):
            raise Cancelled("panels cancelled") from None
        if name in _PANEL_STATUSES:
            faces = out["nonplanar"][out["nonplanar"] >= 0].tolist()
            if name != "FACET_ERROR_NOT_PLANAR":
                faces = [exc.face] if getattr(exc, "face", -1) >= 0 else []
            prefix_ = f"{source}: " if source else ""
            # where it is: the core names faces and a vertex by index, which a designer in
            # FreeCAD or Rhino cannot find; their point can be
            message, vertex, where = str(exc), getattr(exc, "vertex", -1), ""
            if 0 <= vertex < len(mesh.vertices):
                point = point_text(mesh.vertices[vertex]) + (f" {units}" if units else "")
                where = f" (vertex {vertex} at {point})"
                message += (f" {point}" if message.endswith(f"vertex {vertex}") else where)
            if getattr(exc, "joint_faces", None) is not None:
                # the core's reason is either of two; the edge's corners tell which, and
                # what builds the panels is tried: the message says it in one sentence
                def rebuild(trial_min_edge, trial_min_edge_abs):
                    try:
                        trial = _merge_short_edges(input_mesh, trial_min_edge,
                                                   trial_min_edge_abs, tol, tol_abs, source)
                    except PanelError:
                        return False
                    trial = input_mesh if trial is None or trial[0] is None else trial[0]
                    return _builds(np.ascontiguousarray(trial.vertices, dtype=np.float64)
                                   .reshape(-1), trial, core_options, gap)

                said = _failed_joint_message(
                    exc, mesh, core_options, gap, length, _after(progress, n_groups + 2 * nf),
                    rebuild, min_edge, min_edge_abs, dict(OPTION_NAMES, **(option_names or {})),
                    where)
                faces = [int(x) for x in exc.joint_faces]
                message = said or message
            raise PanelError(prefix_ + message, faces=faces) from None
        raise from_core(exc, source=source) from None

    warnings = []
    if report.get("n_non_manifold_edges"):
        warnings.append(f"{report['n_non_manifold_edges']} non-manifold edges treated as "
                        "boundary")
    if res["n_reversed"]:
        n = res['n_reversed']
        warnings.append(f"{count_noun(n, 'face')} had the opposite winding and "
                        f"{'was' if n == 1 else 'were'} reversed to make orientation consistent")
    if res["n_components"] > 1:
        warnings.append(f"{res['n_components']} separate parts, each oriented on its own")
    warnings += _unwelded_warnings(input_mesh)
    if vanished:
        n_panels = len({f for d in vanished for f in d["faces"]})
        n_edges = len(vanished)
        warnings.append(f"{count_noun(n_panels, 'panel')} built with fewer corners than "
                        f"{'its face' if n_panels == 1 else 'their faces'}: "
                        f"{count_noun(n_edges, 'edge')} shorter than min_edge vanished "
                        f"({'its' if n_edges == 1 else 'their'} ends merged into one corner)")
    for reason, why, tail in (
            ("planarity", "would bend a face beyond the planarity tolerance",
             lambda d: f": face {d['face']} {length(d['planarity'])} from its plane); "
                       "facet cleanup collapses them and planarizes again"),
            ("corners", "would leave a face with fewer than 3 corners",
             lambda d: f", of face {d['face']}, a needle)")):
        hit = [d for d in kept if d["reason"] == reason]
        if hit:
            d = hit[0]
            warnings.append(f"{count_noun(len(hit), 'edge')} shorter than min_edge kept: "
                            f"merging {'its' if len(hit) == 1 else 'their'} ends "
                            f"{why} (edge {d['vertices'][0]}-{d['vertices'][1]}, "
                            f"{length(d['length'])} long{tail(d)}")
    if rep_of is not None:
        # a merged vertex's node is its group's
        out["node_deviation"] = out["node_deviation"][rep_of]

    start = np.asarray(mesh.face_start)
    fv = np.asarray(mesh.face_vertices)
    top = out["top"].reshape(-1, 3)
    bottom = out["bottom"].reshape(-1, 3)
    fr = out["frame"].reshape(nf, 12)
    frames = np.concatenate([fr[:, :9].reshape(nf, 3, 3), fr[:, 9:].reshape(nf, 3, 1)], axis=2)
    planes = out["plane"].reshape(nf, 4)
    rev = out["reversed"].astype(bool)
    nbr = out["neighbor"]
    dih = np.degrees(out["dihedral"])
    bev = np.degrees(out["bevel"])
    # a square cut's side is square to within rounding (+-3e-15 degrees): 0, not the noise
    # the schedule wrote as "-3.975693351829398e-16" for an angle documented as 0
    bev[np.abs(bev) < BEVEL_ZERO_DEG] = 0.0
    dropped = out["dropped"]
    squared = out["squared"]
    joint = out["joint"]
    # edges a panel dropped have no joint (the core writes 0 there): by vertex pair
    nxt = next_corners(start)
    edge_lo, edge_hi = np.minimum(fv, fv[nxt]), np.maximum(fv, fv[nxt])
    unjointed = {(int(edge_lo[c]), int(edge_hi[c])) for c in np.flatnonzero(dropped)}

    # the input's faces (a merged quad is still a quad of the grid)
    grid = grid_positions(input_mesh, rev) if ids in ("auto", "grid") else None
    if isinstance(ids, str):
        if ids not in ID_SCHEMES:
            raise PanelError(f"ids must be one of {', '.join(ID_SCHEMES)} or a list, not {ids!r}")
        if ids == "grid" and grid is None:
            raise PanelError(_not_a_grid(input_mesh, source,
                                         dict(OPTION_NAMES, **(option_names or {}))))
        scheme = "grid" if grid is not None else "index"
        names = _ids(nf, scheme, prefix, grid)
    else:
        names = [str(x) for x in ids]
        scheme = "custom"
        if len(names) != nf:
            raise PanelError(f"ids has {len(names)} names for {nf} faces")
        if len(set(names)) != nf:
            raise PanelError("ids are not unique")

    from shapely.geometry import LinearRing

    result = []
    for f in range(nf):
        s, e = int(start[f]), int(start[f + 1])
        d = e - s
        if rev[f]:
            corners = np.arange(e - 1, s - 1, -1)
            # consistent edge j runs from corner d-1-j to d-2-j: input edge (d-2-j) mod d
            edges = s + (d - 2 - np.arange(d)) % d
        else:
            corners = np.arange(s, e)
            edges = corners
        R, t = frames[f, :, :3], frames[f, :, 3]
        gone = dropped[edges].astype(bool)
        if gone.any():
            # edge j dropped: corners j and j + 1 coincide, and corner j + 1
            # (whose edge is j + 1) stays
            corners, edges = corners[~gone], edges[~gone]
        tp, bt = top[corners], bottom[corners]
        ft = (tp @ R.T + t)[:, :2]
        fb = (bt @ R.T + t)[:, :2]
        for outline, which in ((fb, "cut (bottom)"), (ft, "top")):
            if not LinearRing(outline).is_simple:
                # the core moves each edge by half the gap (and the bevels by the
                # thickness) and drops edges consumed: a notch narrower than that closes
                # up and the far edges cross (a 20 mm slot with a 10 mm gap)
                raise PanelError(
                    f"{source + ': ' if source else ''}face {f}: its {which} outline crosses "
                    f"itself once the joint gap ({length(gap, 'g')}) and the bevels are cut "
                    "back: a notch or slot in it is narrower than that; use a smaller gap or "
                    "thinner panels, or split the face at the notch", faces=[f])
        lengths = np.linalg.norm(np.roll(fb, -1, axis=0) - fb, axis=1)
        nb = nbr[edges]
        result.append(Panel(
            id=names[f], face=f, vertices=fv[corners], top=tp, bottom=bt, flat_top=ft,
            flat_bottom=fb, frame=frames[f].copy(), normal=planes[f, :3].copy(),
            thickness=thickness, edge_lengths=lengths.tolist(), bevel_deg=bev[edges].tolist(),
            dihedral_deg=[None if n < 0 else float(a) for n, a in zip(nb, dih[edges])],
            neighbors=[None if n < 0 else int(n) for n in nb],
            grid=None if grid is None else tuple(int(x) for x in grid[2][f]),
            input_corners=int(input_mesh.face_start[f + 1] - input_mesh.face_start[f]),
            dropped_edges=int(gone.sum()),
            squared_edges=int(np.count_nonzero(squared[edges] == 1)),
            butt_edges=int(np.count_nonzero(squared[edges] == 2)),
            joint_widths=[None if n < 0 or (unjointed and (int(edge_lo[c]), int(edge_hi[c]))
                                             in unjointed) else float(x)
                          for n, x, c in zip(nb, joint[edges], edges)],
            clash=float(out["clash"][f]),
        ))
    narrowest = res["narrowest_repaired_joint"]
    for attr, text, tail in (
            ("dropped_edges", "short edges that the joint gap or a bevel consumes dropped from "
             "the outlines of", ""),
            ("squared_edges", "mitred joints cut as butt joints instead, square on one panel "
             "and with the whole fold on the other (the mitre would consume a short edge, "
             "meet beyond a nearly straight corner or meet a cut of another angle at a "
             "straight corner); square on",
             f"; the narrowest of those joints is {length(narrowest)} wide across its section "
             f"(gap {length(gap)})" if narrowest >= 0.0 else "")):
        hit = [p.id for p in result if getattr(p, attr)]
        if hit:
            count = sum(getattr(p, attr) for p in result)
            shown = first_names(hit, 5)
            warnings.append(f"{count} {text} {count_noun(len(hit), 'panel')}: {shown}"
                            + tail)
    overlapping = int(res["n_overlapping_joints"])
    a, b = res["narrowest_joint_faces"]
    if overlapping:
        warnings.append(
            f"{count_noun(overlapping, 'joint')} cut square on the inner side of a "
            f"fold overlap{'s' * (overlapping == 1)}: the panels "
            f"{result[a].id} and {result[b].id} by {length(-res['narrowest_joint'])} (the "
            f"deepest, at the edge from vertex {res['narrowest_joint_vertex']}); a gap of "
            f"{length(res['clearing_gap'])} (now {length(gap)}) or bisector edges would clear "
            "them")
    clashes = _node_clashes(result, out["node_clash"])
    fa, fb = res["node_clash_faces"]
    deepest_pair = None if fa < 0 else (result[fa].id, result[fb].id)
    clearing = float(res["clearing_gap"]) if overlapping else None
    if clashes:
        pairs = int(res["n_node_clashes"])
        # a wider gap moves every outline: the gap that clears the nodes too is searched
        total = n_groups + 2 * nf
        clearing = _clearing_gap(xyz, mesh, core_options, gap, clearing, progress, total)
        warnings.append(
            f"{count_noun(pairs, 'pair')} of panels that meet at a node but not across a "
            f"joint overlap there (at {count_noun(len(clashes), 'node')}): the "
            f"panels {deepest_pair[0]} and {deepest_pair[1]} by "
            f"{length(res['deepest_node_clash'])} at vertex {res['node_clash_vertex']} (the "
            "deepest); "
            + (f"a gap of {length(clearing)} (now {length(gap)}) clears every overlap, as "
               "would thinner panels" if clearing is not None else "thinner panels may clear them")
            + ", and where the node's edge planes miss a common axis (its node deviation) "
            "so does a mesh closer to torsion-free")
    worst = res["worst_node"]
    return PanelSet(
        panels=result,
        options={"thickness": thickness, "offset": offset, "gap": gap, "edge": edge,
                 "flip": bool(flip), "tol": tol, "tol_abs": tol_abs, "repair": bool(repair),
                 "ids": scheme,
                 "prefix": prefix, "min_edge": min_edge, "min_edge_abs": min_edge_abs},
        id_scheme=scheme,
        grid_shape=None if grid is None else (grid[0], grid[1]),
        node_deviation_deg=np.degrees(out["node_deviation"]),
        max_node_deviation_deg=math.degrees(res["max_node_deviation"]),
        worst_node=None if worst < 0 else int(worst),
        planarity=out["planarity"],
        n_reversed=int(res["n_reversed"]),
        n_components=int(res["n_components"]),
        narrowest_repaired_joint=None if narrowest < 0.0 else float(narrowest),
        narrowest_joint=None if a < 0 else float(res["narrowest_joint"]),
        narrowest_joint_panels=None if a < 0 else (result[a].id, result[b].id),
        overlapping_joints=overlapping,
        clearing_gap=clearing,
        node_clashes=clashes,
        node_clash_pairs=int(res["n_node_clashes"]),
        deepest_node_clash_panels=deepest_pair,
        warnings=warnings,
        seconds=float(res["seconds"]),
        vanished_edges=vanished,
        short_edges_kept=kept,
    )
