# SPDX-License-Identifier: LGPL-2.1-or-later
"""Benchmark meshes: the paper's families, generated, and the public meshes.

Generated families (numpy only, no FreeCAD, deterministic for a given seed):

``level``
    Catmull-Clark refinements of an open, doubly curved quad patch, as in
    Poranne et al. 2013, Table 1. Level 1 is a 3 x 4 quad control net
    (12 faces, 20 vertices: the paper's Level 1 counts); level n has
    ``12 * 4**(n-1)`` faces, so Level 5 has 3,072 faces and Level 6 12,288.
    The paper's own control net is not published; its vertex counts
    (64, 224, 832, 3200 for levels 2-5) say it was an annulus (Euler
    characteristic 0), ours is a disk, so we have 63, 221, 825 and 3,185.
``hex_torus``
    Hexagonal meshes on a torus (every vertex of valence 3, V = 2F), the
    duals of a triangulated torus. ``Torus1`` (1,080 faces) and ``Torus2``
    (1,944 faces) have the paper's counts; others are sized by face count.
``quad_grid``
    An open ``nu x nv`` quad grid on a doubly curved height field.
``quad_torus``
    A closed ``nu x nv`` quad mesh on a torus.
``hypar``
    A quad grid on the hyperbolic paraboloid z = x y (no face is planar).

Every generated mesh is perturbed so that it is not planar by construction:
each vertex moves along its vertex normal by ``noise * h * u`` with ``h`` the
mean edge length of the mesh and ``u`` uniform in [-1, 1] from
``numpy.random.default_rng(seed)`` (seed given by the spec; default noise
0.05). The perturbation is the same bits on every run and machine.

Public meshes: every readable mesh with faces in ``tests/data`` and, when the
folder exists, in ``/work/shared/data`` (skipped cleanly when absent).
"""

import hashlib
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

__all__ = [
    "BenchMesh",
    "catmull_clark",
    "level_patch",
    "hex_torus",
    "quad_grid",
    "quad_torus",
    "hypar",
    "perturb",
    "generate",
    "family_specs",
    "public_meshes",
    "PAPER_TABLE1",
]

ROOT = Path(__file__).resolve().parents[2]
TEST_DATA = ROOT / "tests" / "data"
SHARED_DATA = Path(os.environ.get("FACET_SHARED_DATA", "/work/shared/data"))

#: Poranne, Ovreiu, Gotsman 2013, Table 1: C++/Eigen on a 4-core Intel i7
#: (2012), milliseconds. (name, faces, vertices, 30 L/G iterations, 100 L/L).
PAPER_TABLE1 = [
    ("Level 1", 12, 20, 16, 1),
    ("Level 2", 48, 64, 44, 4),
    ("Level 3", 192, 224, 64, 16),
    ("Level 4", 768, 832, 238, 42),
    ("Quadmesh 1", 1027, 1154, 310, 50),
    ("Torus1", 1080, 2160, 618, 70),
    ("Quad mesh 2", 1579, 1791, 536, 76),
    ("Torus2", 1944, 3888, 1068, 144),
    ("Level 5", 3072, 3200, 1126, 176),
]
PAPER_MACHINE = "C++/Eigen, 4-core Intel Core i7, 2012"


@dataclass
class BenchMesh:
    """A benchmark mesh: CSR faces as the compiled core reads them."""

    name: str
    family: str
    vertices: np.ndarray  # (n, 3) float64, C-contiguous
    face_start: np.ndarray  # (F + 1,) int32
    face_vertices: np.ndarray  # (C,) int32
    source: str = "generated"
    params: dict = field(default_factory=dict)

    @property
    def n_vertices(self):
        return int(self.vertices.shape[0])

    @property
    def n_faces(self):
        return int(self.face_start.shape[0] - 1)

    def faces(self):
        s = self.face_start
        return [self.face_vertices[s[j] : s[j + 1]].tolist() for j in range(self.n_faces)]


# ---------------------------------------------------------------------------
# Topology helpers (vectorised; faces of one degree as an (F, k) array)
# ---------------------------------------------------------------------------


def _csr(faces):
    faces = np.ascontiguousarray(faces, dtype=np.int32)
    f, k = faces.shape
    start = np.arange(0, (f + 1) * k, k, dtype=np.int32)
    return start, faces.reshape(-1)


def _edge_keys(faces, n_vertices):
    """Undirected edge key of each face side, (F, k) int64."""
    a = faces.astype(np.int64)
    b = np.roll(a, -1, axis=1)
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    return lo * n_vertices + hi


def _mean_edge_length(vertices, faces):
    a = vertices[faces]
    b = np.roll(a, -1, axis=1)
    return float(np.linalg.norm(a - b, axis=2).mean())


def vertex_normals(vertices, faces):
    """Area-weighted vertex normals of a polygon mesh (F, k faces), unit length."""
    p = vertices[faces]
    c = p.mean(axis=1, keepdims=True)
    # vector area of each face: 1/2 sum (p_i - c) x (p_{i+1} - c)
    cross = np.cross(p - c, np.roll(p, -1, axis=1) - c).sum(axis=1)
    normals = np.zeros_like(vertices)
    k = faces.shape[1]
    for i in range(k):
        np.add.at(normals, faces[:, i], cross)
    length = np.linalg.norm(normals, axis=1, keepdims=True)
    length[length == 0] = 1.0
    return normals / length


def perturb(vertices, faces, noise, seed):
    """Move each vertex along its normal by ``noise * h * U(-1, 1)`` (seeded)."""
    if noise <= 0:
        return vertices
    rng = np.random.default_rng(seed)
    h = _mean_edge_length(vertices, faces)
    u = rng.uniform(-1.0, 1.0, size=vertices.shape[0])
    return np.ascontiguousarray(vertices + (noise * h * u)[:, None] * vertex_normals(vertices, faces))


# ---------------------------------------------------------------------------
# Catmull-Clark subdivision of a quad mesh with boundary
# ---------------------------------------------------------------------------


def catmull_clark(vertices, faces):
    """One Catmull-Clark step of a quad mesh, open boundaries kept.

    Interior rules are the classic ones (face points, edge points as the
    average of the edge ends and the two face points, vertex points
    (Q + 2R + (n - 3) S) / n); boundary edges get their midpoint and
    boundary vertices the cubic B-spline rule (v/4 of the neighbours, 3/4
    itself); corners (valence 2 on the boundary) stay.

    Parameters
    ----------
    vertices : (n, 3) float64
    faces : (F, 4) int

    Returns
    -------
    (vertices, faces) of the refined mesh: n + E + F vertices, 4F quads.
    New vertex order: old vertices, edge points, face points.
    """
    vertices = np.asarray(vertices, dtype=np.float64)
    faces = np.asarray(faces, dtype=np.int64)
    n, (f, k) = vertices.shape[0], faces.shape
    if k != 4:
        raise ValueError("catmull_clark: quads only")
    keys = _edge_keys(faces, n)
    uniq, edge_of_side, counts = np.unique(keys.reshape(-1), return_inverse=True, return_counts=True)
    if counts.max() > 2:
        raise ValueError("catmull_clark: non-manifold edge")
    edge_of_side = edge_of_side.reshape(f, k)
    e = uniq.shape[0]
    ea, eb = uniq // n, uniq % n
    boundary_edge = counts == 1

    face_points = vertices[faces].mean(axis=1)
    # edge points
    face_sum = np.zeros((e, 3))
    for i in range(k):
        np.add.at(face_sum, edge_of_side[:, i], face_points)
    mid = 0.5 * (vertices[ea] + vertices[eb])
    edge_points = np.where(
        boundary_edge[:, None], mid, (vertices[ea] + vertices[eb] + face_sum) / 4.0
    )

    # vertex points
    valence = np.bincount(np.concatenate([ea, eb]), minlength=n).astype(np.float64)
    boundary_vertex = np.zeros(n, bool)
    boundary_vertex[ea[boundary_edge]] = True
    boundary_vertex[eb[boundary_edge]] = True
    q = np.zeros((n, 3))
    nf = np.zeros(n)
    for i in range(k):
        np.add.at(q, faces[:, i], face_points)
        np.add.at(nf, faces[:, i], 1.0)
    q /= np.maximum(nf, 1)[:, None]
    r = np.zeros((n, 3))
    np.add.at(r, ea, mid)
    np.add.at(r, eb, mid)
    r /= np.maximum(valence, 1)[:, None]
    vv = valence[:, None]
    interior = (q + 2.0 * r + (vv - 3.0) * vertices) / vv
    # boundary: neighbours along boundary edges
    bsum = np.zeros((n, 3))
    bcount = np.zeros(n)
    np.add.at(bsum, ea[boundary_edge], vertices[eb[boundary_edge]])
    np.add.at(bsum, eb[boundary_edge], vertices[ea[boundary_edge]])
    np.add.at(bcount, ea[boundary_edge], 1.0)
    np.add.at(bcount, eb[boundary_edge], 1.0)
    bspline = 0.75 * vertices + 0.125 * bsum
    corner = boundary_vertex & (valence == 2)
    new_old = np.where(boundary_vertex[:, None], bspline, interior)
    new_old[corner] = vertices[corner]

    new_vertices = np.concatenate([new_old, edge_points, face_points])
    fp = n + e + np.arange(f)
    ep = n + edge_of_side  # edge point of side i (from corner i to i+1)
    new_faces = np.empty((4 * f, 4), dtype=np.int64)
    for i in range(4):
        prev = (i - 1) % 4
        new_faces[i::4] = np.stack([faces[:, i], ep[:, i], fp, ep[:, prev]], axis=1)
    return np.ascontiguousarray(new_vertices), new_faces


def _grid_faces(nu, nv, wrap_u=False, wrap_v=False):
    """Quads of an nu x nv grid; vertex (i, j) is j * cu + i with cu columns."""
    cu = nu if wrap_u else nu + 1
    cv = nv if wrap_v else nv + 1
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="xy")
    i, j = i.reshape(-1), j.reshape(-1)
    i1 = (i + 1) % cu
    j1 = (j + 1) % cv
    faces = np.stack([j * cu + i, j * cu + i1, j1 * cu + i1, j1 * cu + i], axis=1)
    return faces, cu, cv


def level_patch(level, noise=0.05, seed=None):
    """The paper's Level ``level`` (>= 1): Catmull-Clark of a curved 3 x 4 net."""
    if level < 1:
        raise ValueError(f"level must be >= 1 (Level 1 is the 12-face control net), not {level}")
    faces, cu, cv = _grid_faces(3, 4)
    i, j = np.meshgrid(np.arange(cu, dtype=float), np.arange(cv, dtype=float), indexing="xy")
    x, y = i.reshape(-1), j.reshape(-1)
    # a doubly curved control net: a saddle and a bump
    z = 0.35 * (x - 1.5) * (y - 2.0) + 1.2 * np.exp(-((x - 1.2) ** 2 + (y - 2.3) ** 2) / 2.0)
    v = np.stack([x, y, z], axis=1)
    for _ in range(level - 1):
        v, faces = catmull_clark(v, faces)
    v = perturb(v, faces, noise, 1000 + level if seed is None else seed)
    start, fv = _csr(faces)
    return BenchMesh(f"Level {level}", "level", v, start, fv, params={"level": level, "noise": noise})


# ---------------------------------------------------------------------------
# Hexagonal torus
# ---------------------------------------------------------------------------


def hex_torus(a, b, radius=2.0, tube=1.0, noise=0.05, seed=None, name=None):
    """Hexagonal mesh on a torus with ``a * b`` hexagons (b even), V = 2F.

    The dual of a triangulated torus: the triangular lattice with vertices
    (i, j), periodic with the lattice vectors (a, 0) and (-b/2, b), which are
    orthogonal in the plane, so the hexagons are regular before the torus map.
    """
    if b % 2 or a < 3 or b < 4:
        raise ValueError(f"hex_torus needs a >= 3 and an even b >= 4, got {a} x {b}")
    half = b // 2

    def lattice(i, j):
        # canonical index of lattice vertex (i, j)
        wraps = np.floor_divide(j, b)
        return np.mod(i + half * wraps, a) + a * np.mod(j, b)

    ii, jj = np.meshgrid(np.arange(a), np.arange(b), indexing="xy")
    ii, jj = ii.reshape(-1), jj.reshape(-1)
    # triangles: up U(i,j) = (i,j),(i+1,j),(i,j+1) -> index 2*L(i,j);
    #            down D(i,j) = (i+1,j),(i+1,j+1),(i,j+1) -> 2*L(i,j)+1
    def up(i, j):
        return 2 * lattice(i, j)

    def down(i, j):
        return 2 * lattice(i, j) + 1

    faces = np.stack(
        [
            up(ii, jj),
            down(ii - 1, jj),
            up(ii - 1, jj),
            down(ii - 1, jj - 1),
            up(ii, jj - 1),
            down(ii, jj - 1),
        ],
        axis=1,
    )
    # triangle centroids in the plane (unwrapped lattice coordinates of the canonical cell)
    n_tri = 2 * a * b
    ci = np.empty(n_tri)
    cj = np.empty(n_tri)
    lat = lattice(ii, jj)
    ci[2 * lat], cj[2 * lat] = ii + 1.0 / 3.0, jj + 1.0 / 3.0
    ci[2 * lat + 1], cj[2 * lat + 1] = ii + 2.0 / 3.0, jj + 2.0 / 3.0
    px = ci + 0.5 * cj
    py = cj * np.sqrt(3.0) / 2.0
    theta = 2.0 * np.pi * px / a
    phi = 2.0 * np.pi * py / (b * np.sqrt(3.0) / 2.0)
    ring = radius + tube * np.cos(phi)
    v = np.stack([ring * np.cos(theta), ring * np.sin(theta), tube * np.sin(phi)], axis=1)
    v = perturb(v, faces, noise, 2000 + a * b if seed is None else seed)
    start, fv = _csr(faces)
    return BenchMesh(
        name or f"hex torus {a * b}",
        "hex_torus",
        v,
        start,
        fv,
        params={"a": a, "b": b, "noise": noise},
    )


def hex_torus_faces(target):
    """(a, b) with a * b near ``target`` and a / b near 1.8 (b even)."""
    b = max(4, 2 * int(round(np.sqrt(target / 1.8) / 2.0)))
    a = max(3, int(round(target / b)))
    return a, b


# ---------------------------------------------------------------------------
# Quad grid, quad torus, hypar
# ---------------------------------------------------------------------------


def quad_grid(nu, nv, noise=0.05, seed=None, name=None):
    """An nu x nv quad grid over a doubly curved height field (unit cells)."""
    faces, cu, cv = _grid_faces(nu, nv)
    i, j = np.meshgrid(np.arange(cu, dtype=float), np.arange(cv, dtype=float), indexing="xy")
    x, y = i.reshape(-1), j.reshape(-1)
    s, t = x / nu, y / nv
    size = 0.5 * (nu + nv)
    z = size * (0.15 * (s - 0.5) * (t - 0.5) + 0.08 * np.sin(5.0 * s) * np.cos(4.0 * t))
    v = np.stack([x, y, z], axis=1)
    v = perturb(v, faces, noise, 3000 + nu * nv if seed is None else seed)
    start, fv = _csr(faces)
    return BenchMesh(name or f"quad grid {nu * nv}", "quad_grid", v, start, fv,
                     params={"nu": nu, "nv": nv, "noise": noise})


def quad_torus(nu, nv, radius=2.0, tube=0.8, noise=0.05, seed=None, name=None):
    """A closed nu x nv quad mesh on a torus (nu around the axis)."""
    faces, cu, cv = _grid_faces(nu, nv, wrap_u=True, wrap_v=True)
    i, j = np.meshgrid(np.arange(cu, dtype=float), np.arange(cv, dtype=float), indexing="xy")
    theta = 2.0 * np.pi * i.reshape(-1) / nu
    phi = 2.0 * np.pi * j.reshape(-1) / nv
    ring = radius + tube * np.cos(phi)
    v = np.stack([ring * np.cos(theta), ring * np.sin(theta), tube * np.sin(phi)], axis=1)
    v = perturb(v, faces, noise, 4000 + nu * nv if seed is None else seed)
    start, fv = _csr(faces)
    return BenchMesh(name or f"quad torus {nu * nv}", "quad_torus", v, start, fv,
                     params={"nu": nu, "nv": nv, "noise": noise})


def hypar(n, noise=0.0, seed=None, name=None):
    """An n x n quad grid on z = x y over [-1, 1]^2: every quad is skew.

    Not perturbed by default: the hypar is non-planar by itself (it is the
    classic case where plane-constraint solvers stall).
    """
    faces, cu, cv = _grid_faces(n, n)
    i, j = np.meshgrid(np.linspace(-1, 1, cu), np.linspace(-1, 1, cv), indexing="xy")
    x, y = i.reshape(-1), j.reshape(-1)
    v = np.stack([x, y, x * y], axis=1)
    v = perturb(v, faces, noise, 5000 + n if seed is None else seed)
    start, fv = _csr(faces)
    return BenchMesh(name or f"hypar {n * n}", "hypar", v, start, fv, params={"n": n, "noise": noise})


# ---------------------------------------------------------------------------
# Specs: what the benchmark runs
# ---------------------------------------------------------------------------

_GENERATORS = {
    "level": lambda p: level_patch(p["level"], noise=p.get("noise", 0.05)),
    "hex_torus": lambda p: hex_torus(p["a"], p["b"], noise=p.get("noise", 0.05), name=p.get("name")),
    "quad_grid": lambda p: quad_grid(p["nu"], p["nv"], noise=p.get("noise", 0.05), name=p.get("name")),
    "quad_torus": lambda p: quad_torus(p["nu"], p["nv"], noise=p.get("noise", 0.05), name=p.get("name")),
    "hypar": lambda p: hypar(p["n"], noise=p.get("noise", 0.0), name=p.get("name")),
}


def generate(spec):
    """The BenchMesh of a spec dict ``{"family": ..., params...}``."""
    family = spec["family"]
    if family == "file":
        return load_file(Path(spec["path"]), spec.get("name"))
    try:
        generator = _GENERATORS[family]
    except KeyError:
        raise ValueError(f"unknown mesh family {family!r}") from None
    return generator(spec)


def _faces_of(spec):
    f = spec["family"]
    if f == "level":
        return 12 * 4 ** (spec["level"] - 1)
    if f == "hex_torus":
        return spec["a"] * spec["b"]
    if f in ("quad_grid", "quad_torus"):
        return spec["nu"] * spec["nv"]
    if f == "hypar":
        return spec["n"] ** 2
    return spec.get("faces", 0)


def family_specs(max_faces=1_000_000, levels=range(1, 7)):
    """The generated benchmark meshes, smallest first, up to ``max_faces`` faces."""
    specs = [{"family": "level", "level": n} for n in levels]
    specs += [
        {"family": "hex_torus", "a": 45, "b": 24, "name": "Torus1"},
        {"family": "hex_torus", "a": 54, "b": 36, "name": "Torus2"},
    ]
    for target in (10_000, 100_000):
        a, b = hex_torus_faces(target)
        specs.append({"family": "hex_torus", "a": a, "b": b})
    for nu, nv in ((100, 100), (320, 320), (1000, 1000)):
        specs.append({"family": "quad_grid", "nu": nu, "nv": nv})
    for nu, nv in ((100, 100), (320, 320), (1000, 1000)):
        specs.append({"family": "quad_torus", "nu": nu, "nv": nv})
    specs.append({"family": "hypar", "n": 64})
    specs = [s for s in specs if _faces_of(s) <= max_faces]
    for s in specs:
        s["faces"] = _faces_of(s)
        s.setdefault("name", _default_name(s))
    specs.sort(key=lambda s: (s["faces"], s["name"]))
    return specs


def _default_name(spec):
    f = spec["family"]
    if f == "level":
        return f"Level {spec['level']}"
    return f"{f.replace('_', ' ')} {spec['faces']}"


# ---------------------------------------------------------------------------
# Public meshes (files)
# ---------------------------------------------------------------------------

_MESH_SUFFIXES = (".obj", ".off", ".json")


def load_file(path, name=None):
    """Read a mesh file with facet.read_mesh into a BenchMesh (requires facet on sys.path)."""
    from facet import read_mesh

    mesh = read_mesh(path)
    return BenchMesh(
        name or path.name,
        "public",
        np.ascontiguousarray(mesh.vertices, dtype=np.float64),
        np.ascontiguousarray(mesh.face_start, dtype=np.int32),
        np.ascontiguousarray(mesh.face_vertices, dtype=np.int32),
        source=str(path),
    )


def public_meshes(include_shared=True, shared_root=None, include_roofs=False):
    """Specs of the readable public meshes with faces, de-duplicated by content.

    ``tests/data`` first, then ``shared_root`` (default /work/shared/data)
    when it exists. Files that fail to read (the bad_* fixtures) or have no
    face (line drawings) are left out with a note. The CC BY-NC roof data is
    read in place (never copied) and only with ``include_roofs``.

    Returns
    -------
    (specs, notes) : list of dict, list of str
    """
    from facet import InputError

    roots = [TEST_DATA]
    shared = Path(shared_root) if shared_root else SHARED_DATA
    notes = []
    if include_shared:
        if shared.is_dir():
            roots.append(shared)
        else:
            notes.append(f"{shared} is absent: shared public meshes skipped")
    seen = {}
    specs = []
    for root in roots:
        for path in sorted(root.rglob("*")):
            if path.suffix.lower() not in _MESH_SUFFIXES or not path.is_file():
                continue
            if "SGA21" in str(path) and not include_roofs:
                continue
            digest = hashlib.sha256(path.read_bytes()).hexdigest()
            if digest in seen:
                continue
            seen[digest] = path
            try:
                mesh = load_file(path)
            except InputError as exc:
                notes.append(f"{path.name}: not benchmarked ({exc})")
                continue
            if mesh.n_faces == 0:
                notes.append(f"{path.name}: not benchmarked (no faces)")
                continue
            label = path.name if root == TEST_DATA else f"{path.parent.name}/{path.name}"
            specs.append({"family": "file", "path": str(path), "name": label,
                          "faces": mesh.n_faces, "source": "tests/data" if root == TEST_DATA else "shared"})
    return specs, notes
