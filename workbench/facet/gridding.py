# SPDX-License-Identifier: LGPL-2.1-or-later
"""Control meshes from surfaces: quad and hexagonal grids over a (u, v) parameter domain, and
triangles paired into quads.

Nothing here knows FreeCAD: a surface is a function ``evaluate(u, v) -> (k, 3)`` over a
parameter rectangle ``u_range x v_range`` (FreeCAD's ``Face.valueAt`` wrapped by the
workbench, or any numpy function), optionally with ``inside(u, v) -> (k,) bool`` for trimmed
faces.

>>> import numpy as np
>>> mesh = sample_surface(lambda u, v: np.column_stack([u, v, u * v]),
...                       (0.0, 1.0), (0.0, 1.0), "quad", 4, 3)
>>> mesh.n_faces, mesh.n_vertices
(12, 20)

Patterns:

- ``"quad"``: ``nu x nv`` quads along the parameter lines;
- ``"hex"``: a honeycomb of ``nu`` hexagons per row, ``nv`` rows (pointy side along v), fitted
  into the parameter rectangle, every interior vertex of degree 3;
- ``"tri-quad"``: use :func:`pair_triangles` on a triangulation instead.

:func:`weld` joins meshes (the faces of a shell) along coincident vertices, and drops faces
that collapse (the poles of a sphere).
"""

import math

import numpy as np

from facet.errors import Cancelled, InputError
from facet.mesh import PolyMesh

__all__ = ["GridError", "PATTERNS", "quad_grid", "hex_grid", "grid_counts", "sample_surface",
           "pair_triangles", "weld"]

#: Grid patterns of :func:`sample_surface`.
PATTERNS = ("quad", "hex")

#: Largest number of cells per direction (a guard against a panel size in the wrong unit).
MAX_COUNT = 2000


class GridError(InputError):
    """A surface, count or size that cannot give a control mesh."""


def _check_count(name, value, minimum=1):
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise GridError(f"{name} must be an integer, not {value!r}")
    if not minimum <= value <= MAX_COUNT:
        raise GridError(f"{name} is {value}; it must be between {minimum} and {MAX_COUNT}")
    return int(value)


def _check_range(name, values):
    try:
        low, high = (float(x) for x in values)
    except (TypeError, ValueError):
        raise GridError(f"{name} must be two numbers (low, high), not {values!r}") from None
    if not (math.isfinite(low) and math.isfinite(high)):
        raise GridError(f"{name} ({low}, {high}) is not finite")
    if not high > low:
        raise GridError(f"{name} ({low}, {high}) is empty: high must be above low")
    return low, high


def quad_grid(nu, nv, periodic_u=False):
    """Topology and unit parameters of an ``nu x nv`` quad grid.

    With ``periodic_u`` the grid closes around u (a cylinder): u = 1 is u = 0, so the last
    column of quads joins the first and there are ``nu`` columns of vertices (nu >= 3).

    Returns
    -------
    uv : ndarray, shape ((nu + 1) * (nv + 1), 2)
        Parameters in [0, 1]^2; vertex ``i + j * (nu + 1)`` is at ``(i / nu, j / nv)``
        (``nu`` instead of ``nu + 1`` columns when periodic).
    faces : ndarray of int32, shape (nu * nv, 4)
        Counter-clockwise in (u, v), so normals follow the surface's ``du x dv``.
    """
    nu = _check_count("nu", nu, 3 if periodic_u else 1)
    nv = _check_count("nv", nv)
    columns = nu if periodic_u else nu + 1
    i, j = np.meshgrid(np.arange(columns), np.arange(nv + 1))
    uv = np.column_stack([i.ravel() / nu, j.ravel() / nv]).astype(np.float64)
    ci, cj = np.meshgrid(np.arange(nu), np.arange(nv))
    ci, cj = ci.ravel(), cj.ravel()
    right = (ci + 1) % columns
    faces = np.column_stack([ci + cj * columns, right + cj * columns,
                             right + (cj + 1) * columns, ci + (cj + 1) * columns])
    return uv, faces.astype(np.int32)


def hex_grid(nu, nv, periodic_u=False):
    """Topology and unit parameters of a honeycomb: ``nv`` rows of ``nu`` hexagons.

    Rows alternate by half a hexagon; vertices lie on ``nv + 1`` zigzag lines. With
    ``periodic_u`` the honeycomb closes around u (nu >= 3): the half hexagons at the ends of
    the odd rows become whole ones across the seam, and u is ``i / (2 nu)`` for vertex column
    ``i``. Otherwise, with
    parameters scaled to a square the hexagons are regular when the domain's aspect
    (u length / v length) is ``sqrt(3) (nu + 1/2) / (1.5 nv + 1/2)`` (see
    :func:`grid_counts`).

    Returns
    -------
    uv : ndarray, shape (n, 2)
        Parameters in [0, 1]^2 (both ends reached).
    faces : ndarray of int32, shape (nu * nv, 6)
        Counter-clockwise in (u, v).
    """
    nu = _check_count("nu", nu, 3 if periodic_u else 1)
    nv = _check_count("nv", nv)
    columns = 2 * nu if periodic_u else 2 * nu + 2
    r = 1.0
    w = math.sqrt(3.0) * r
    cells = []
    for j in range(nv):
        for a in range(nu):
            c = 2 * a + (j % 2)
            bottom = [((c + k) % columns, j) for k in range(3)]
            top = [((c + k) % columns, j + 1) for k in (2, 1, 0)]
            cells.append(bottom + top)
    used = sorted({vertex for cell in cells for vertex in cell}, key=lambda p: (p[1], p[0]))
    index = {p: k for k, p in enumerate(used)}
    xy = np.array([(i * w / 2.0, 1.5 * r * j + 0.5 * r * ((i + j + 1) % 2)) for i, j in used],
                  dtype=np.float64)
    low, high = xy.min(axis=0), xy.max(axis=0)
    uv = (xy - low) / (high - low)
    if periodic_u:
        uv[:, 0] = np.array([i for i, _j in used], dtype=np.float64) / columns
    faces = np.array([[index[p] for p in cell] for cell in cells], dtype=np.int32)
    return uv, faces


def _lengths(evaluate, u_range, v_range, samples=9):
    """Mean lengths of the u and v parameter lines of the surface (polyline estimates)."""
    u0, u1 = u_range
    v0, v1 = v_range
    s = np.linspace(0.0, 1.0, samples)
    uu, vv = np.meshgrid(u0 + s * (u1 - u0), v0 + s * (v1 - v0))
    xyz = _evaluate(evaluate, uu.ravel(), vv.ravel()).reshape(samples, samples, 3)
    along_u = np.linalg.norm(np.diff(xyz, axis=1), axis=-1).sum(axis=1).mean()
    along_v = np.linalg.norm(np.diff(xyz, axis=0), axis=-1).sum(axis=0).mean()
    return float(along_u), float(along_v)


def grid_counts(evaluate, u_range, v_range, panel_size, pattern="quad"):
    """``(nu, nv)`` so that the panels of ``pattern`` are about ``panel_size`` wide.

    For quads the size is the edge length; for hexagons the width across flats.
    """
    if pattern not in PATTERNS:
        raise GridError(f"pattern must be one of {PATTERNS}, not {pattern!r}")
    size = float(panel_size)
    if not (math.isfinite(size) and size > 0.0):
        raise GridError(f"panel size is {panel_size!r}; it must be a positive length")
    u_range = _check_range("u range", u_range)
    v_range = _check_range("v range", v_range)
    length_u, length_v = _lengths(evaluate, u_range, v_range)
    if pattern == "quad":
        nu, nv = length_u / size, length_v / size
    else:
        r = size / math.sqrt(3.0)
        nu, nv = length_u / size - 0.5, (length_v - 0.5 * r) / (1.5 * r)
    nu, nv = max(1, int(round(nu))), max(1, int(round(nv)))
    if max(nu, nv) > MAX_COUNT:
        raise GridError(f"panel size {size:g} gives {nu} x {nv} panels on a surface of "
                        f"{length_u:.6g} x {length_v:.6g}; at most {MAX_COUNT} per direction "
                        "(is the size in the model's unit?)")
    return nu, nv


def _evaluate(evaluate, u, v):
    xyz = np.asarray(evaluate(np.asarray(u, np.float64), np.asarray(v, np.float64)),
                     dtype=np.float64)
    if xyz.shape != (np.size(u), 3):
        raise GridError(f"the surface gave points of shape {xyz.shape}, expected "
                        f"({np.size(u)}, 3)")
    if not np.all(np.isfinite(xyz)):
        bad = int(np.argwhere(~np.isfinite(xyz).all(axis=1))[0, 0])
        raise GridError(f"the surface is not finite at (u, v) = ({float(np.ravel(u)[bad]):g}, "
                        f"{float(np.ravel(v)[bad]):g})")
    return xyz


def sample_surface(evaluate, u_range, v_range, pattern, nu, nv, inside=None, progress=None,
                   periodic_u=False):
    """A control mesh of ``pattern`` on the surface ``evaluate`` over the parameter rectangle.

    Parameters
    ----------
    evaluate : callable
        ``evaluate(u, v)`` with two float arrays of length k returns a (k, 3) array.
    u_range, v_range : (float, float)
        The parameter rectangle.
    pattern : {"quad", "hex"}
    nu, nv : int
        Cells along u and rows along v.
    inside : callable, optional
        ``inside(u, v)`` -> (k,) bool, False outside a trimmed face; a cell with a corner
        outside is dropped.
    progress : callable, optional
        ``progress(done, total)`` as the points are evaluated; returning True cancels
        (raises :class:`facet.Cancelled`).
    periodic_u : bool
        The surface is closed in u with period ``u_range[1] - u_range[0]``: the grid closes
        around (see :func:`quad_grid`, :func:`hex_grid`).

    Returns
    -------
    PolyMesh
        Faces oriented with the surface normal ``du x dv``. Vertices that coincide (the seam
        of a closed surface, a pole) are not merged here: use :func:`weld`.
    """
    if pattern not in PATTERNS:
        raise GridError(f"pattern must be one of {PATTERNS}, not {pattern!r}")
    u_range = _check_range("u range", u_range)
    v_range = _check_range("v range", v_range)
    grid = quad_grid if pattern == "quad" else hex_grid
    uv, faces = grid(nu, nv, periodic_u=bool(periodic_u))
    u = u_range[0] + uv[:, 0] * (u_range[1] - u_range[0])
    v = v_range[0] + uv[:, 1] * (v_range[1] - v_range[0])
    chunk = 4096
    parts = []
    for start in range(0, u.size, chunk):
        parts.append(_evaluate(evaluate, u[start:start + chunk], v[start:start + chunk]))
        if progress is not None and progress(min(start + chunk, u.size), u.size):
            raise Cancelled("sampling the surface was cancelled")
    xyz = np.concatenate(parts)
    if inside is not None:
        keep_vertex = np.asarray(inside(u, v), dtype=bool).reshape(-1)
        if keep_vertex.shape != (u.size,):
            raise GridError(f"inside() gave {keep_vertex.size} values for {u.size} points")
        faces = faces[keep_vertex[faces].all(axis=1)]
        if faces.shape[0] == 0:
            raise GridError(f"no {pattern} cell of {nu} x {nv} lies inside the face: use "
                            "more cells")
        used = np.unique(faces)
        renumber = np.full(u.size, -1, dtype=np.int32)
        renumber[used] = np.arange(used.size, dtype=np.int32)
        xyz, faces = xyz[used], renumber[faces]
    return PolyMesh.from_faces(xyz, faces.tolist())


def weld(meshes, tolerance):
    """One mesh of ``meshes`` with vertices closer than ``tolerance`` merged.

    A face that repeats a vertex after merging loses the repeat; a face left with fewer than
    three vertices (a collapsed cell at a pole) is dropped.
    """
    from scipy.spatial import cKDTree

    meshes = list(meshes)
    if not meshes:
        raise GridError("nothing to weld: no meshes")
    tol = float(tolerance)
    if not (math.isfinite(tol) and tol >= 0.0):
        raise GridError(f"weld tolerance is {tolerance!r}; it must be 0 or more")
    xyz = np.concatenate([np.asarray(m.vertices, dtype=np.float64) for m in meshes])
    faces = []
    offset = 0
    for m in meshes:
        faces.extend([[offset + int(i) for i in face] for face in m.faces()])
        offset += m.n_vertices
    # Union-find over the pairs closer than tol (a chain of near points joins up).
    parent = np.arange(xyz.shape[0])

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    if tol > 0.0:
        for i, j in cKDTree(xyz).query_pairs(tol):
            ri, rj = root(i), root(j)
            if ri != rj:
                parent[max(ri, rj)] = min(ri, rj)
    else:
        _, first = np.unique(xyz, axis=0, return_index=True)
        _, inverse = np.unique(xyz, axis=0, return_inverse=True)
        parent = first[inverse.reshape(-1)]
    roots = np.array([root(i) for i in range(xyz.shape[0])])
    keep = np.unique(roots)
    renumber = np.full(xyz.shape[0], -1, dtype=np.int64)
    renumber[keep] = np.arange(keep.size)
    out_faces = []
    for face in faces:
        merged = []
        for i in renumber[roots[face]]:
            if not merged or merged[-1] != i:
                merged.append(int(i))
        while len(merged) > 1 and merged[0] == merged[-1]:
            merged.pop()
        if len(set(merged)) == len(merged) >= 3:
            out_faces.append(merged)
    if not out_faces:
        raise GridError("every face collapsed when welding: the tolerance is too large")
    used = sorted({i for f in out_faces for i in f})
    again = {old: new for new, old in enumerate(used)}
    return PolyMesh.from_faces(xyz[keep][used], [[again[i] for i in f] for f in out_faces])


def _angles(corners):
    """Interior angles in degrees at each corner of polygons (m, k, 3)."""
    prev = np.roll(corners, 1, axis=1) - corners
    nxt = np.roll(corners, -1, axis=1) - corners
    cos = (prev * nxt).sum(-1) / np.maximum(
        np.linalg.norm(prev, axis=-1) * np.linalg.norm(nxt, axis=-1), 1e-300)
    return np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))


def pair_triangles(mesh, max_corner_deviation=45.0, max_fold=20.0, progress=None):
    """Pair the triangles of ``mesh`` into quads, best pairs first.

    Two triangles sharing an edge (with the same orientation) become one quad when the quad is
    convex, no corner angle is further than ``max_corner_deviation`` degrees from 90 and the
    triangles fold by at most ``max_fold`` degrees along the shared edge. Candidate pairs are
    taken greedily in order of their score, the worst corner deviation plus the fold, so the
    most rectangular, flattest quads win. Triangles left unpaired stay triangles; faces with
    more than three vertices are kept as they are.

    Returns
    -------
    PolyMesh
        Same vertices (same order); quads first in the order of their first triangle, then the
        rest.
    """
    for name, value, top in (("max_corner_deviation", max_corner_deviation, 90.0),
                             ("max_fold", max_fold, 180.0)):
        if not (isinstance(value, (int, float)) and 0.0 <= value <= top):
            raise GridError(f"{name} is {value!r}; it must be between 0 and {top:g} degrees")
    faces = mesh.faces()
    xyz = np.asarray(mesh.vertices, dtype=np.float64)
    tri = [k for k, f in enumerate(faces) if len(f) == 3]
    edge_face = {}
    for k in tri:
        a, b, c = (int(x) for x in faces[k])
        for e in ((a, b), (b, c), (c, a)):
            edge_face[e] = k
    cand = []  # (tri1, tri2, quad)
    for k in tri:
        a, b, c = (int(x) for x in faces[k])
        for p, q, r in ((a, b, c), (b, c, a), (c, a, b)):
            other = edge_face.get((q, p))
            if other is None or other <= k:
                continue
            d = [int(x) for x in faces[other] if int(x) not in (p, q)]
            if len(d) != 1:
                continue
            cand.append((k, other, (p, d[0], q, r)))
    if progress is not None and progress(0, 2):
        raise Cancelled("pairing triangles was cancelled")
    chosen = set()
    quads = {}
    if cand:
        quad = np.array([c[2] for c in cand], dtype=np.int64)
        corners = xyz[quad]
        deviation = np.abs(_angles(corners) - 90.0).max(axis=1)
        n1 = np.cross(corners[:, 2] - corners[:, 0], corners[:, 3] - corners[:, 0])  # p q r
        n2 = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])  # p d q
        len1, len2 = np.linalg.norm(n1, axis=1), np.linalg.norm(n2, axis=1)
        ok = (len1 > 0) & (len2 > 0)
        cos = (n1 * n2).sum(1) / np.where(ok, len1 * len2, 1.0)
        fold = np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))
        # Convex: each corner turns the same way as the quad's mean normal.
        normal = n1 + n2
        edges = np.roll(corners, -1, axis=1) - corners
        turn = np.cross(np.roll(edges, 1, axis=1), edges)
        convex = ((turn * normal[:, None, :]).sum(-1) > 0).all(axis=1)
        good = ok & convex & (deviation <= max_corner_deviation) & (fold <= max_fold)
        score = deviation + fold
        for idx in np.flatnonzero(good)[np.argsort(score[good], kind="stable")]:
            k1, k2, q = cand[idx]
            if k1 in chosen or k2 in chosen:
                continue
            chosen.update((k1, k2))
            quads[k1] = q
    if progress is not None and progress(1, 2):
        raise Cancelled("pairing triangles was cancelled")
    out = [list(quads[k]) for k in sorted(quads)]
    out += [[int(x) for x in f] for k, f in enumerate(faces) if k not in chosen]
    return PolyMesh.from_faces(xyz, out)
