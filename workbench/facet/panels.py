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
from facet.errors import Cancelled, FacetError, InputError, from_core

__all__ = ["PanelError", "Panel", "PanelSet", "panels", "OFFSETS", "EDGES", "ID_SCHEMES",
           "grid_positions"]

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
        input edge along +x, its normal to +z.
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
        Edges of the face the joint gap consumed (square edges): the outline
        drops them, so the panel has that many corners fewer than its face
        (`vertices` keeps the last mesh vertex of each merged corner).
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
            "area": self.area,
            "area_top": self.area_top,
            "perimeter": self.perimeter,
            "width": w,
            "height": h,
            "thickness": self.thickness,
            "edge_lengths": [float(x) for x in self.edge_lengths],
            "bevel_deg": [float(x) for x in self.bevel_deg],
            "dihedral_deg": [None if x is None else float(x) for x in self.dihedral_deg],
            "dropped_edges": int(self.dropped_edges),
        }


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

    def schedule(self):
        """List of schedule rows (dicts), in panel order."""
        return [p.schedule_row() for p in self.panels]


def _check_float(name, value, minimum, strict):
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise PanelError(f"{name} must be a number, not {value!r}") from None
    if not math.isfinite(value) or value < minimum or (strict and value == minimum):
        op = ">" if strict else ">="
        raise PanelError(f"{name} must be a finite number {op} {minimum:g}, not {value!r}")
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


def panels(mesh, thickness, offset="outer", gap=0.0, edge="square", flip=False, ids="auto",
           prefix="P-", tol=1e-6, tol_abs=0.0, progress=None):
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
    progress : callable, optional
        ``progress(done, total)``; returning True cancels (raises
        :class:`facet.Cancelled`).

    Returns
    -------
    PanelSet

    Raises
    ------
    PanelError
        Bad option, faces not planar (``error.faces`` lists them all), a
        non-orientable surface, or a gap/bevel that consumes a panel.
    facet.MeshError
        The mesh is not valid.
    """
    thickness = _check_float("thickness", thickness, 0.0, True)
    gap = _check_float("gap", gap, 0.0, False)
    tol = _check_float("tol", tol, 0.0, False)
    tol_abs = _check_float("tol_abs", tol_abs, 0.0, False)
    if offset not in OFFSETS:
        raise PanelError(f"offset must be one of {', '.join(OFFSETS)}, not {offset!r}")
    if edge not in EDGES:
        raise PanelError(f"edge must be one of {', '.join(EDGES)}, not {edge!r}")
    source = mesh.info.get("source") if mesh.info else None
    report = mesh.validate()
    _check_face_areas(mesh, source)
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
    }
    xyz = np.ascontiguousarray(mesh.vertices, dtype=np.float64).reshape(-1)
    try:
        res = _core.panels(xyz, mesh.face_start, mesh.face_vertices, thickness=thickness,
                           offset=offset, gap=gap, edge=edge, flip=bool(flip), tol_abs=tol_abs,
                           tol_rel=tol, progress=progress, **out)
    except _core.CoreError as exc:
        name = getattr(exc, "status_name", None)
        if name == "FACET_ERROR_CANCELLED" or isinstance(exc, _core.Cancelled):
            raise Cancelled("panels cancelled") from None
        if name in _PANEL_STATUSES:
            faces = out["nonplanar"][out["nonplanar"] >= 0].tolist()
            if name != "FACET_ERROR_NOT_PLANAR":
                faces = [exc.face] if getattr(exc, "face", -1) >= 0 else []
            prefix_ = f"{source}: " if source else ""
            raise PanelError(prefix_ + str(exc), faces=faces) from None
        raise from_core(exc, source=source) from None

    warnings = []
    if report.get("n_non_manifold_edges"):
        warnings.append(f"{report['n_non_manifold_edges']} non-manifold edges treated as "
                        "boundary")
    if res["n_reversed"]:
        warnings.append(f"{res['n_reversed']} faces had the opposite winding and were "
                        "reversed to make orientation consistent")
    if res["n_components"] > 1:
        warnings.append(f"{res['n_components']} separate parts, each oriented on its own")
    if res["n_dropped_edges"]:
        warnings.append(f"the joint gap consumes {res['n_dropped_edges']} short edges: "
                        "dropped from their panels' outlines (those panels have fewer corners "
                        "than their faces)")

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
    dropped = out["dropped"]

    grid = grid_positions(mesh, rev) if ids in ("auto", "grid") else None
    if isinstance(ids, str):
        if ids not in ID_SCHEMES:
            raise PanelError(f"ids must be one of {', '.join(ID_SCHEMES)} or a list, not {ids!r}")
        if ids == "grid" and grid is None:
            raise PanelError("ids='grid' but the mesh is not a regular quad grid")
        scheme = "grid" if grid is not None else "index"
        names = _ids(nf, scheme, prefix, grid)
    else:
        names = [str(x) for x in ids]
        scheme = "custom"
        if len(names) != nf:
            raise PanelError(f"ids has {len(names)} names for {nf} faces")
        if len(set(names)) != nf:
            raise PanelError("ids are not unique")

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
        lengths = np.linalg.norm(np.roll(fb, -1, axis=0) - fb, axis=1)
        nb = nbr[edges]
        result.append(Panel(
            id=names[f], face=f, vertices=fv[corners], top=tp, bottom=bt, flat_top=ft,
            flat_bottom=fb, frame=frames[f].copy(), normal=planes[f, :3].copy(),
            thickness=thickness, edge_lengths=lengths.tolist(), bevel_deg=bev[edges].tolist(),
            dihedral_deg=[None if n < 0 else float(a) for n, a in zip(nb, dih[edges])],
            neighbors=[None if n < 0 else int(n) for n in nb],
            grid=None if grid is None else tuple(int(x) for x in grid[2][f]),
            dropped_edges=int(gone.sum()),
        ))
    worst = res["worst_node"]
    return PanelSet(
        panels=result,
        options={"thickness": thickness, "offset": offset, "gap": gap, "edge": edge,
                 "flip": bool(flip), "tol": tol, "tol_abs": tol_abs, "ids": scheme,
                 "prefix": prefix},
        id_scheme=scheme,
        grid_shape=None if grid is None else (grid[0], grid[1]),
        node_deviation_deg=np.degrees(out["node_deviation"]),
        max_node_deviation_deg=math.degrees(res["max_node_deviation"]),
        worst_node=None if worst < 0 else int(worst),
        planarity=out["planarity"],
        n_reversed=int(res["n_reversed"]),
        n_components=int(res["n_components"]),
        warnings=warnings,
        seconds=float(res["seconds"]),
    )
