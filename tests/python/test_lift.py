# SPDX-License-Identifier: LGPL-2.1-or-later
"""Optimal liftings: checked against an independent dense computation."""

import re

import numpy as np
import pytest

from facet.errors import InputError, MeshError
from facet.mesh import PolyMesh

_core = pytest.importorskip("facet._core")

from facet.lift import Lifter, TargetError, lift, lifting_space  # noqa: E402
from facet.plan import PlanError, pinned_targets, plan_from_segments  # noqa: E402


def dense_lifting_basis(mesh):
    """Null space of B (corners x (heights, a, b, c per face)) by SVD, its
    height part: an independent reference for the lifting space."""
    n, nf = mesh.n_vertices, mesh.n_faces
    xy = mesh.vertices[:, :2]
    xy = (xy - xy.mean(axis=0)) / np.ptp(xy, axis=0).max()
    rows = []
    for f, face in enumerate(mesh.faces()):
        for v in face:
            row = np.zeros(n + 3 * nf)
            row[v] = 1.0
            row[n + 3 * f : n + 3 * f + 3] = [-xy[v, 0], -xy[v, 1], -1.0]
            rows.append(row)
    b = np.array(rows)
    _, s, vt = np.linalg.svd(b)
    rank = int(np.sum(s > 1e-9 * s[0]))
    null = vt[rank:].T
    return null[:n]


def voronoi_plan(seed, count=12):
    """Bounded Voronoi cells of random points: faces of many degrees."""
    from scipy.spatial import Voronoi

    rng = np.random.default_rng(seed)
    points = rng.uniform(0, 1, size=(count, 2))
    ring = np.array([[np.cos(a), np.sin(a)] for a in np.linspace(0, 2 * np.pi, 9)[:-1]])
    vor = Voronoi(np.vstack([points, 0.5 + 3 * ring]))
    faces = []
    for i in range(count):
        region = vor.regions[vor.point_region[i]]
        if -1 in region or len(region) < 3:
            continue
        faces.append(region)
    used = sorted({v for f in faces for v in f})
    remap = {v: k for k, v in enumerate(used)}
    xyz = np.zeros((len(used), 3))
    xyz[:, :2] = vor.vertices[used]
    return PolyMesh.from_faces(xyz, [[remap[v] for v in f] for f in faces])


def nested_triangles(angle):
    outer = np.array([[0.0, 0.0], [4.0, 0.0], [1.0, 3.0]])
    c = outer.mean(axis=0)
    rot = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    inner = c + (0.4 * (outer - c)) @ rot.T
    xyz = np.zeros((6, 3))
    xyz[:3, :2], xyz[3:, :2] = outer, inner
    faces = [[3, 4, 5], [0, 1, 4, 3], [1, 2, 5, 4], [2, 0, 3, 5]]
    return PolyMesh.from_faces(xyz, faces)


@pytest.mark.parametrize("seed", range(8))
def test_dimension_and_optimum_agree_with_dense_svd(seed):
    mesh = voronoi_plan(seed)
    reference = dense_lifting_basis(mesh)
    rng = np.random.default_rng(100 + seed)
    weights = rng.uniform(0.2, 3.0, mesh.n_vertices)
    targets = rng.normal(size=mesh.n_vertices)
    lifter = Lifter(mesh, weights)
    assert lifter.dimension == reference.shape[1]
    result = lifter.solve(targets)
    w = np.diag(weights)
    n = reference
    expected = n @ np.linalg.solve(n.T @ w @ n, n.T @ w @ targets)
    assert np.max(np.abs(result.heights - expected)) < 1e-9
    assert result.planarity_max_rel < 1e-9
    assert result.target_rms == pytest.approx(np.sqrt(np.mean((expected - targets) ** 2)))


def test_known_dimensions():
    assert Lifter(nested_triangles(0.0)).dimension == 4
    assert Lifter(nested_triangles(0.25)).dimension == 3
    # A triangulated plan admits every height assignment.
    rng = np.random.default_rng(3)
    from scipy.spatial import Delaunay

    points = rng.uniform(size=(40, 2))
    tri = Delaunay(points)
    xyz = np.zeros((40, 3))
    xyz[:, :2] = points
    mesh = PolyMesh.from_faces(xyz, tri.simplices.tolist())
    t = rng.normal(size=40)
    result = lift(mesh, t)
    assert result.dimension == 40
    assert np.max(np.abs(result.heights - t)) < 1e-12


def test_only_trivial_gives_best_plane_and_says_so():
    mesh = nested_triangles(0.25)
    rng = np.random.default_rng(5)
    t = rng.normal(size=6)
    w = rng.uniform(0.5, 2, 6)
    result = lift(mesh, t, w)
    assert result.liftable_only_trivially
    assert any("trivial" in text for text in result.warnings)
    a = np.column_stack([np.ones(6), mesh.vertices[:, :2]])
    coef = np.linalg.lstsq(a * np.sqrt(w)[:, None], t * np.sqrt(w), rcond=None)[0]
    assert np.max(np.abs(result.heights - a @ coef)) < 1e-12
    assert result.report()["liftable_only_trivially"] is True


def straight_grid(xs, ys):
    xyz = np.array([[x, y, 0.0] for y in ys for x in xs])
    nx = len(xs)
    faces = [[j * nx + i, j * nx + i + 1, (j + 1) * nx + i + 1, (j + 1) * nx + i]
             for j in range(len(ys) - 1) for i in range(nx - 1)]
    return PolyMesh.from_faces(xyz, faces)


def test_georeferenced_coordinates_and_heights():
    # Coordinates exact in binary at both placements (a Voronoi plan would
    # be rounded by the shift, and rounding breaks its non-trivial lifting).
    mesh = straight_grid([0, 1.5, 2.25, 4, 5], [0, 0.5, 2, 2.75])
    rng = np.random.default_rng(7)
    t = rng.normal(size=mesh.n_vertices)
    local = lift(mesh, t)
    xyz = mesh.vertices.copy()
    xyz[:, 0] += 2_500_000.0
    xyz[:, 1] += 1_200_000.0
    far = lift(mesh.with_vertices(xyz), t + 450.0)
    assert far.dimension == local.dimension == 5 + 4 - 1
    assert np.max(np.abs((far.heights - 450.0) - local.heights)) < 1e-8
    assert far.planarity_max_rel < 1e-9


def test_bases():
    mesh = voronoi_plan(4, count=20)
    lifter = Lifter(mesh)
    d = lifter.dimension
    basis, energies = lifter.basis("eigen")
    assert basis.shape == (d, mesh.n_vertices)
    # Orthonormal, every one a lifting, energies ascending after the trivial three.
    assert np.allclose(basis @ basis.T, np.eye(d), atol=1e-9)
    for b in basis:
        assert np.max(np.abs(lifter.solve(b).heights - b)) < 1e-10
    assert np.all(np.diff(energies[3:]) >= -1e-10)
    # Eigen-liftings against a dense P L P.
    reference = dense_lifting_basis(mesh)
    q, _ = np.linalg.qr(reference)
    edges = mesh.edges()
    lap = np.zeros((mesh.n_vertices,) * 2)
    for a, b in edges:
        lap[a, a] += 1
        lap[b, b] += 1
        lap[a, b] -= 1
        lap[b, a] -= 1
    affine = np.column_stack([np.ones(mesh.n_vertices), mesh.vertices[:, :2]])
    qa, _ = np.linalg.qr(affine)
    rest = q - qa @ (qa.T @ q)
    u, s, _ = np.linalg.svd(rest, full_matrices=False)
    h = u[:, : d - 3]
    values = np.linalg.eigvalsh(h.T @ lap @ h)
    assert np.allclose(energies[3:], values, atol=1e-9)
    # Fundamental: the solve for a unit target.
    unit = np.zeros(mesh.n_vertices)
    unit[2] = 1.0
    assert np.allclose(lifter.fundamental(2), lifter.solve(unit).heights, atol=1e-14)
    fundamental, _ = lifter.basis("fundamental", 4)
    assert fundamental.shape == (4, mesh.n_vertices)
    space = lifting_space(mesh, "orthonormal")
    assert space.dimension == d and space.basis.shape == (d, mesh.n_vertices)


def test_bad_inputs():
    mesh = nested_triangles(0.0)
    with pytest.raises(TargetError, match="5 values but the plan has 6"):
        lift(mesh, np.zeros(5))
    with pytest.raises(TargetError, match="vertex 2"):
        lift(mesh, [0, 0, np.nan, 0, 0, 0])
    with pytest.raises(TargetError, match="vertex 1"):
        lift(mesh, np.zeros(6), [1, -1, 1, 1, 1, 1])
    xyz = mesh.vertices.copy()
    xyz[3:, :2] = [[1, 1], [2, 2], [3, 3]]  # collinear inner triangle
    with pytest.raises(PlanError, match=r"face 0 has collinear corners .*; the face is "
                       r"around \(2, 2\)"):  # (a drawing's user cannot see face numbers)
        lift(mesh.with_vertices(xyz), np.zeros(6))
    # placed in a georeferenced grid, the place reads to the millimetre: it said
    # "(512346, 5.71236e+06)", ten metres out
    xyz[:, :2] += [512344.25, 5712358.5]
    with pytest.raises(PlanError, match=r"the face is around \(512346\.25, 5712360\.5\)"):
        lift(mesh.with_vertices(xyz), np.zeros(6))
    # weights 1e30 apart gave faces 0.2 of an edge off planar, with exit 0
    with pytest.raises(TargetError, match=r"the weight of vertex 3 is 1e-17, 1e-17 times "
                       r"vertex 0's \(1\): weights more than 1e\+16 apart"):
        lift(mesh, np.zeros(6), [1, 1, 1, 1e-17, 1, 1])
    assert lift(mesh, np.arange(6.0), [1, 1, 1, 2e-16, 1, 1]).planarity_max_rel <= 1e-12
    # a pin weighted 1e4 beside free vertices at 1e-10 (many of them) is taken
    assert lift(mesh, np.arange(6.0), [1e4, 1, 1, 1e-10, 1, 1]).planarity_max_rel <= 1e-12
    with pytest.raises(InputError):
        Lifter(mesh).basis("smooth")
    assert issubclass(PlanError, InputError) and issubclass(TargetError, InputError)
    with pytest.raises(MeshError):
        Lifter(PolyMesh(np.zeros((3, 3)), [0, 3], [0, 1, 5]))


def test_plan_from_segments_lifts():
    segments = [((0, 0), (2, 0)), ((2, 0), (2, 2)), ((2, 2), (0, 2)), ((0, 2), (0, 0)),
                ((1, 0), (1, 2)), ((0, 1), (2, 1))]
    plan = plan_from_segments(segments)
    t = np.random.default_rng(0).normal(size=plan.n_vertices)
    result = lift(plan, t)
    assert result.dimension == 5  # a 3 x 3 straight grid: 3 + 3 - 1
    assert result.mesh.n_faces == 4
    assert result.planarity_max_rel < 1e-9
    assert np.array_equal(result.mesh.vertices[:, :2], plan.mesh.vertices[:, :2])


def test_lift_nearly_moves_a_rounded_drawing():
    from facet.lift import lift_nearly

    # The frustum's inner triangle turned by 1e-5: liftable only up to rounding.
    mesh = nested_triangles(1e-5)
    t = np.array([0.0, 0.0, 0.0, 1.0, 1.0, 1.0])
    plain = lift(mesh, t)
    assert plain.liftable_only_trivially and plain.target_max > 0.4
    nearly = lift_nearly(mesh, t, tolerance=1e-3)
    assert nearly.method in ("exact", "planarized")
    assert nearly.within_tolerance and 0 < nearly.max_move < 1e-4
    assert nearly.result.target_max < 1e-6
    assert nearly.result.planarity_max_rel <= 1e-9
    assert nearly.moved_vertices and nearly.moved_vertices[0][0] in range(6)
    moved = nearly.result.mesh.vertices[:, :2] - mesh.vertices[:, :2]
    assert np.allclose(moved, nearly.moves)
    report = nearly.report()
    assert report["within_tolerance"] and report["max_move"] == nearly.max_move
    # A tolerance smaller than the moves needed is said, not hidden.
    strict = lift_nearly(mesh, t, tolerance=1e-9)
    assert not strict.within_tolerance
    # A liftable plan is left alone.
    exact = lift_nearly(nested_triangles(0.0), t, tolerance=1e-3)
    assert exact.method == "unmoved" and exact.max_move == 0.0


def test_sparse_liftings_are_local_independent_liftings():
    mesh = straight_grid([0, 1, 2.5, 3, 4.5, 6, 7], [0, 1, 2, 3.5, 4, 5])
    lifter = Lifter(mesh)
    d = lifter.dimension
    assert d == 7 + 6 - 1
    basis, energies = lifter.basis("sparse")
    assert basis.shape == (d, mesh.n_vertices)
    assert np.linalg.matrix_rank(basis, tol=1e-8) == d
    for b in basis:
        assert np.max(np.abs(lifter.solve(b).heights - b)) < 1e-9  # each one is a lifting
    supports = [np.count_nonzero(np.abs(b) > 1e-12) for b in basis[3:]]
    # On a straight grid the sparsest liftings are bumps along one grid line: f(x) or g(y).
    assert max(supports) <= 7
    assert np.allclose(np.max(np.abs(basis[3:]), axis=1), 1.0)
    # A Voronoi plan (dimension 4: its lifting is convex, global): filled from the space.
    vor = voronoi_plan(1)
    basis, _ = Lifter(vor).basis("sparse")
    assert basis.shape[0] == Lifter(vor).dimension


def test_sparse_and_fundamental_bases_report_progress_and_can_be_cancelled():
    # the sparse search took 24 s on a 100 x 100 grid plan with no word and no way to
    # stop it but Ctrl+C; the fundamental basis is a solve per vertex
    from facet.errors import Cancelled

    mesh = straight_grid([0, 1, 2.5, 3, 4.5, 6, 7], [0, 1, 2, 3.5, 4, 5])
    lifter = Lifter(mesh)
    for kind, total in (("sparse", mesh.n_vertices), ("fundamental", 5)):
        seen = []
        count = None if kind == "sparse" else 5
        basis, _ = lifter.basis(kind, count, progress=lambda d, t: seen.append((d, t)) and False)
        quiet, _ = lifter.basis(kind, count)
        assert np.array_equal(basis, quiet)  # the same result with a progress callback
        assert seen[0][0] == 0 and seen[-1] == (total, total)
        assert all(t == total for _, t in seen) and [d for d, _ in seen] == sorted(d for d, _ in seen)
        with pytest.raises(Cancelled, match=f"{kind} liftings cancelled"):
            lifter.basis(kind, count, progress=lambda d, t: d >= 2)
        with pytest.raises(Cancelled, match=f"{kind} liftings cancelled"):
            lifting_space(mesh, kind, count, progress=lambda d, t: d >= 2)


def test_the_misses_count_only_vertices_given_a_target():
    # four pins that a planar lifting meets, on a 2 x 2 grid of squares: the free vertices'
    # filler targets (the pins' plane) counted too, and the report said "max 2 at vertex
    # 3", an unpinned vertex
    from facet.plan import pinned_targets, plan_from_segments

    lines = [((0, 0), (20, 0)), ((20, 0), (20, 20)), ((20, 20), (0, 20)), ((0, 20), (0, 0)),
             ((10, 0), (10, 20)), ((0, 10), (20, 10))]
    plan = plan_from_segments(lines)
    corners = [int(np.argmin(np.hypot(*(plan.mesh.vertices[:, :2] - c).T)))
               for c in ((0, 0), (20, 0), (0, 20), (10, 10))]
    heights = {corners[0]: 0.0, corners[1]: 1.0, corners[2]: 0.0, corners[3]: 3.0}
    targets, weights = pinned_targets(plan, heights)
    result = lift(plan, targets, weights)
    assert result.target_max_vertex in heights
    assert result.target_max < 1e-4 and result.target_rms < 1e-4
    assert {v for v, _d in result.far_targets()} <= set(heights)


def test_a_plan_in_separate_pieces_counts_their_affine_liftings():
    # two unjoined squares: "dimension 6 (3 trivial)", as if the plan had three liftings
    # beyond the affine ones, where each square admits only a plane
    from facet.plan import plan_from_segments

    def square(x):
        return [((x, 0), (x + 1, 0)), ((x + 1, 0), (x + 1, 1)), ((x + 1, 1), (x, 1)),
                ((x, 1), (x, 0))]

    plan = plan_from_segments(square(0) + square(3))
    result = lift(plan, np.arange(plan.n_vertices, dtype=float))
    assert result.dimension == 6 and result.trivial_dimension == 6
    assert result.liftable_only_trivially
    assert any("2 separate pieces" in w for w in result.warnings)
    assert lifting_space(plan).trivial_dimension == 6
    one = plan_from_segments(square(0))
    assert Lifter(one).trivial_dimension == 3
    assert not any("pieces" in w for w in lift(one, np.zeros(4)).warnings)


def test_lift_nearly_takes_the_rank_tolerance():
    # --rank-tol with --move-tolerance was ignored
    from facet.lift import lift_nearly
    from facet.plan import plan_from_segments

    lines = [((0, 0), (20, 0)), ((20, 0), (20, 20)), ((20, 20), (0, 20)), ((0, 20), (0, 0)),
             ((10, 0), (10, 20)), ((0, 10), (20, 10))]
    plan = plan_from_segments(lines)
    t = np.arange(plan.n_vertices, dtype=float)
    loose = lift(plan, t, rank_tol=0.9).dimension
    assert loose != lift(plan, t).dimension
    assert lift_nearly(plan, t, tolerance=1e-3, rank_tol=0.9).result.dimension == loose


def test_a_vertex_in_no_face_is_a_trivial_lifting():
    # its free height adds one to the dimension; it was not counted as trivial
    square = PolyMesh.from_faces([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (5, 5, 0)],
                                 [[0, 1, 2, 3]])
    lifter = Lifter(square)
    assert lifter.dimension == 4 and lifter.trivial_dimension == 4
    assert lift(square, np.zeros(5)).liftable_only_trivially


def test_the_lifting_space_progress_line():
    # `facet lifting-space --basis sparse` showed nothing while it searched (ProgressLine.steps)
    import io

    from facet.cli_progress import ProgressLine

    out = io.StringIO()
    line = ProgressLine(out, prefix="facet lifting-space", interval=60.0, force=True)
    mesh = straight_grid([0, 1, 2.5, 3, 4.5, 6, 7], [0, 1, 2, 3.5, 4, 5])
    Lifter(mesh).basis("sparse", progress=lambda d, t: line.steps(d, t, "vertices searched"))
    line.close()
    shown = out.getvalue().split("\r")
    n = mesh.n_vertices
    # the first at once, then none within the interval but the last
    assert shown[1:3] == ["facet lifting-space: vertices searched 0 of %d" % n,
                          "facet lifting-space: vertices searched %d of %d" % (n, n)]
    assert shown[-1] == "" and shown[-2].strip() == ""  # erased at the end


def test_lift_with_move_tolerance_shows_progress_on_a_terminal(tmp_path, monkeypatch, capsys):
    # a 14k-face plan moved for 15 s with no progress line (lift_nearly had no callback)
    import io
    import sys

    from facet.cli import main
    from facet.io import write_mesh

    class Terminal(io.StringIO):
        def isatty(self):
            return True

    write_mesh(nested_triangles(1e-5), tmp_path / "plan.obj")
    terminal = Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    from facet.cli_progress import ProgressLine

    monkeypatch.setattr(ProgressLine, "_due", lambda self, at_once=False: True)  # (fast)
    code = main(["lift", str(tmp_path / "plan.obj"), "-o", str(tmp_path / "roof.obj"),
                 "--pin", "0=0", "--pin", "1=0", "--pin", "3=1", "--pin", "4=3",
                 "--move-tolerance", "1e-3"])
    assert code in (0, 1)  # (1: moved further than the tolerance; the moves are reported)
    assert "facet lift: moving the plan: iteration 1 of at most " in terminal.getvalue()


def test_lift_matching_a_target_mesh_shows_progress_on_a_terminal(tmp_path, monkeypatch):
    # `facet lift --targets MESH` ray-cast a 100,000-vertex plan for seconds with no line
    import io
    import sys

    from facet.cli import main
    from facet.cli_progress import ProgressLine
    from facet.io import write_mesh

    class Terminal(io.StringIO):
        def isatty(self):
            return True

    plan = straight_grid(list(range(8)), list(range(6)))
    write_mesh(plan, tmp_path / "plan.obj")
    target = straight_grid([-1, 4, 9], [-1, 3, 7])
    write_mesh(target.with_vertices(target.vertices + [[0.0, 0.0, 2.0]]),
               tmp_path / "target.obj")
    terminal = Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    monkeypatch.setattr(ProgressLine, "_due", lambda self, at_once=False: True)  # (fast)
    code = main(["lift", str(tmp_path / "plan.obj"), "-o", str(tmp_path / "roof.obj"),
                 "--targets", str(tmp_path / "target.obj")])
    assert code == 0
    n = plan.n_vertices
    assert f"facet lift: matching the targets: vertices 0 of {n}" in terminal.getvalue()
    assert f"facet lift: matching the targets: vertices {n} of {n}" in terminal.getvalue()
    # (and the plan mesh its stages)
    assert "facet lift: reading the plan: stages done 6 of 6" in terminal.getvalue()


def test_lifting_space_says_what_it_computes_on_a_terminal(tmp_path, monkeypatch):
    # `facet lifting-space` showed nothing while the dense eigen-solver ran (seconds on a
    # large plan: it reports no steps)
    import io
    import sys

    from facet.cli import main
    from facet.cli_progress import ProgressLine
    from facet.io import write_mesh

    class Terminal(io.StringIO):
        def isatty(self):
            return True

    write_mesh(straight_grid(list(range(6)), list(range(5))), tmp_path / "plan.obj")
    terminal = Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    monkeypatch.setattr(ProgressLine, "_due", lambda self, at_once=False: True)  # (fast)
    assert main(["lifting-space", str(tmp_path / "plan.obj"), "-o", str(tmp_path / "space"),
                 "--count", "5"]) == 0
    assert "facet lifting-space: liftings 0 of 5" in terminal.getvalue()


def _voronoi_plan(sites, seed):
    """The Voronoi cells of random sites in the unit square, those inside [0.05, 0.95]^2 (a
    hexagon-like plan, three faces at a vertex), and the heights of its paraboloid lifting:
    each cell on the plane tangent to z = |p|^2 above its site, which makes every face
    planar (a Voronoi diagram is always liftable)."""
    from scipy.spatial import Voronoi

    p = np.random.default_rng(seed).random((sites, 2))
    vor = Voronoi(p)
    cells = [(i, vor.regions[r]) for i, r in enumerate(vor.point_region)
             if vor.regions[r] and -1 not in vor.regions[r]
             and np.all((vor.vertices[vor.regions[r]] > 0.05)
                        & (vor.vertices[vor.regions[r]] < 0.95))]
    used = np.unique(np.concatenate([c for _, c in cells]))
    index = np.full(len(vor.vertices), -1)
    index[used] = np.arange(len(used))
    xy = vor.vertices[used]
    faces, heights = [], np.empty(len(used))
    for site, cell in cells:
        face = list(index[cell])
        q = xy[face]
        area = np.sum(q[:, 0] * np.roll(q[:, 1], -1) - np.roll(q[:, 0], -1) * q[:, 1])
        faces.append(face if area > 0 else face[::-1])
        heights[face] = 2.0 * q @ p[site] - p[site] @ p[site]
    return PolyMesh.from_faces(np.column_stack([xy, np.zeros(len(used))]), faces), heights


def _dense_dimension(mesh):
    """The lifting space's dimension by a dense SVD of the planarity constraints."""
    from facet.lift import _face_complements

    rows = []
    for face, complement in _face_complements(mesh):
        for values in complement:
            row = np.zeros(mesh.n_vertices)
            row[face] = values
            rows.append(row)
    singular = np.linalg.svd(np.array(rows), compute_uv=False)
    return mesh.n_vertices - int(np.count_nonzero(singular > 1e-10))


@pytest.mark.parametrize("seed", [3, 4, 5])
def test_a_voronoi_plan_keeps_its_liftings(seed):
    # SPQR's rank detection kept dependent constraints on these 300-site plans: the
    # dimension came out 3 (seed 3: 4 by SVD), and the paraboloid's heights, a lifting,
    # were lifted 0.08 RMS away from themselves (the best plane)
    mesh, heights = _voronoi_plan(300, seed)
    lifter = Lifter(mesh)
    assert lifter.dimension == _dense_dimension(mesh) > 3
    result = lifter.solve(heights)
    assert result.target_max < 1e-9 * np.ptp(heights)
    assert not [w for w in result.warnings if "dependencies" in w]
    basis, _ = lifter.basis("orthonormal")
    assert basis.shape[0] == lifter.dimension
    assert np.abs(basis @ basis.T - np.eye(len(basis))).max() < 1e-9  # (weights 1)
    for function in basis:
        assert np.abs(lifter.solve(function).heights - function).max() < 1e-9


@pytest.mark.parametrize("seed", [3, 4])
def test_a_large_voronoi_plan_keeps_its_liftings(seed):
    # 3,000 sites: SPQR's rank came out with the dimension 1 (seed 3; 6 by a dense SVD) or
    # 9 (seed 4, where CHOLMOD's ordering finds 15), and inverse iteration with R found
    # one of the lost directions at most; the paraboloid came back as the best plane
    mesh, heights = _voronoi_plan(3000, seed)
    lifter = Lifter(mesh)
    result = lifter.solve(heights)
    assert result.target_max < 1e-9 * np.ptp(heights)
    assert result.planarity_max_rel < 1e-9 and not result.warnings
    assert lifter.dimension == {3: 6, 4: 15}[seed]
    basis, _ = lifter.basis("orthonormal")
    for function in basis:
        assert np.abs(lifter.solve(function).heights - function).max() < 1e-9


def test_the_hidden_directions_beyond_one_block_are_found(monkeypatch):
    """Where the search for the directions SPQR's rank lost is left with a block that can
    grow no more (512 vectors, or its memory: 32 on a 300,000-site Voronoi plan) and is
    all hidden, further blocks orthogonal to those found go on. It stopped there: that
    plan's paraboloid came back 3.4 times its range away. The largest block is lowered
    here (FACET_LIFT_HIDDEN_BLOCK_MAX) to take that path on the 3,000-site plan of
    test_a_large_voronoi_plan_keeps_its_liftings, whose search finds its directions in
    blocks of 8 and 16: in blocks of 2 and of 1 it finds them all too, and the same
    lifting (a search that stopped at 2 left the dimension 7 and missed the paraboloid by
    58% of its range)."""
    mesh, heights = _voronoi_plan(3000, 4)
    whole = Lifter(mesh)
    for block in ("2", "1"):
        monkeypatch.setenv("FACET_LIFT_HIDDEN_BLOCK_MAX", block)
        lifter = Lifter(mesh)
        assert lifter.dimension == whole.dimension == 15
        result = lifter.solve(heights)
        assert result.target_max < 1e-9 * np.ptp(heights) and not result.warnings
        basis, _ = lifter.basis("orthonormal")
        for function in basis:
            assert np.abs(lifter.solve(function).heights - function).max() < 1e-9


@pytest.mark.parametrize("seed", [2, 6, 8])
def test_a_voronoi_drawing_with_a_short_edge_snapped_keeps_its_liftings(seed):
    """A Voronoi plan drawn as lines, whose shortest edge (1e-4 of the plan) the snap
    distance collapses into a vertex of four faces: a near-dependency of the constraints,
    a singular value just above the rank tolerance, which shrinks in the search for the
    directions SPQR's rank lost as slowly as they do and mixed into every one of them. The
    search kept the block's vectors up to the first that A' reached, so none: the
    dimension came out 1 (seeds 2 and 8; 3 and 4 by a dense SVD) and the affine liftings
    were lost (a 3,000-site canopy drawn in metres, at the default snap, missed its
    paraboloid targets by a third of their range). The block's directions within the
    rank tolerance of A' are now taken instead of its leading vectors."""
    mesh, _ = _voronoi_plan(300, seed)
    edges = mesh.edges()
    xy = mesh.vertices[:, :2]
    length = np.hypot(*(xy[edges[:, 0]] - xy[edges[:, 1]]).T)
    shortest = np.sort(length)[:2]
    plan = plan_from_segments([(tuple(xy[a]), tuple(xy[b])) for a, b in edges],
                              snap=float(shortest.mean()))
    assert plan.n_vertices == mesh.n_vertices - 1  # (the shortest edge collapsed)
    lifter = Lifter(plan)
    assert lifter.dimension == _dense_dimension(plan.mesh) >= 3
    x, y = plan.mesh.vertices[:, 0], plan.mesh.vertices[:, 1]
    affine = 2.0 + 0.3 * x - 0.7 * y
    result = lifter.solve(affine)
    assert not [w for w in result.warnings if "dependencies" in w]
    assert np.abs(result.heights - affine).max() < 1e-9
    basis, _ = lifter.basis("orthonormal")
    for function in basis:
        assert np.abs(lifter.solve(function).heights - function).max() < 1e-9


def test_the_factorization_shows_its_stages_and_can_be_cancelled():
    """Lifter(plan) was one call with no progress and no Cancel (2.4 s on a 100,000-quad
    plan, a minute on a 300,000-site Voronoi plan). It now reports (done, 3) as its stages
    end, and between the blocks of the search for the directions SPQR's rank lost; True
    cancels at any of them, and an exception in the callback comes through as itself."""
    import facet

    mesh, heights = _voronoi_plan(3000, 4)
    calls = []
    lifter = Lifter(mesh, progress=lambda done, total: calls.append((done, total)))
    assert calls[0] == (1, 3) and calls[-2:] == [(2, 3), (3, 3)]
    assert set(calls[1:-2]) <= {(1, 3)} and len(calls) > 3  # (its search's blocks)
    assert lifter.dimension == 15
    for stop in range(1, len(calls) + 1):
        seen = []
        with pytest.raises(facet.Cancelled):
            Lifter(mesh, progress=lambda done, total: seen.append(done) or len(seen) == stop)
        assert len(seen) == stop

    def broken(done, total):
        raise ZeroDivisionError("in the callback")

    with pytest.raises(ZeroDivisionError, match="in the callback"):
        Lifter(mesh, progress=broken)
    # lift() takes it too
    assert lift(mesh, heights, progress=lambda done, total: False).target_max < 1e-9


def _triangulated_plan(n, seed=0):
    """A Delaunay triangulation of n random points, 50 across (every function lifts)."""
    from scipy.spatial import Delaunay

    p = np.random.default_rng(seed).random((n, 2)) * 50.0
    return PolyMesh.from_faces(np.column_stack([p, np.zeros(n)]),
                               [list(t) for t in Delaunay(p).simplices])


@pytest.mark.parametrize("plan", ["triangles", "voronoi"])
def test_eigen_liftings_by_arpack_are_the_dense_ones(plan):
    # the path beyond the dense eigen-solver, taken here on plans the dense one serves
    from facet.lift import _eigen_liftings

    mesh = _triangulated_plan(1200) if plan == "triangles" else _voronoi_plan(3000, 4)[0]
    lifter = Lifter(mesh)
    count = min(20, lifter.dimension - 1)
    dense, dense_energies = lifter.basis("eigen", count)
    sparse, energies = _eigen_liftings(lifter, count)
    np.testing.assert_allclose(energies, dense_energies, rtol=1e-7, atol=1e-12)
    # the same functions (unit vectors: |cosine| 1), signs as the core sets them
    assert np.abs(np.sum(dense * sparse, axis=1) - 1.0).max() < 1e-6


def test_eigen_liftings_beyond_the_dense_limit():
    # a triangulated canopy of 2,500 vertices: dimension 2,500, and the 20 smoothest
    # eigen-liftings were refused ("eigen-liftings are dense")
    mesh = _triangulated_plan(2500)
    lifter = Lifter(mesh)
    assert lifter.dimension == 2500
    basis, energies = lifter.basis("eigen", 20)
    assert basis.shape == (20, 2500)
    assert np.abs(basis @ basis.T - np.eye(20)).max() < 1e-9  # (weights 1)
    assert np.all(np.diff(energies[3:]) >= 0.0) and energies[3] > 0.0
    edges = mesh.edges()
    for function, energy in zip(basis[3:], energies[3:]):
        assert np.isclose(np.sum((function[edges[:, 0]] - function[edges[:, 1]]) ** 2), energy)
    with pytest.raises(InputError, match=r"dimension 2500, too large for all its "
                       r"eigen-liftings at once: ask for the smoothest 503 at most"):
        lifter.basis("eigen")
    from facet.errors import Cancelled

    with pytest.raises(Cancelled, match="eigen-liftings cancelled"):
        lifter.basis("eigen", 20, progress=lambda done, total: True)


def test_a_wrong_rank_is_said_even_where_a_face_is_not_planar_too():
    # At rank tolerance 1e-5 SPQR's rank stands (no search) and this 1,000-site plan loses
    # liftings: the paraboloid's heights came back 12% of their range away with only
    # "face ... is planar only to 5e-6" said; the solve named one warning, the planarity
    # one, and hid that the result is not the closest lifting
    mesh, heights = _voronoi_plan(1000, 3)
    result = Lifter(mesh, rank_tol=1e-5).solve(heights)
    assert result.target_max > 0.05 * np.ptp(heights)
    [warning] = result.warnings
    assert "dependencies could not be told from rounding" in warning
    assert re.search(r"; and face \d+ is planar only to [0-9.e-]+ of its mean edge", warning)


@pytest.mark.parametrize("offset", [(512_000.0, 5_712_000.0), (512_000_000.0, 5_712_000_000.0)])
def test_free_vertices_follow_the_pins_plane_at_map_coordinates(offset):
    # Free vertices are drawn (weakly) to the plane of the given heights. At map
    # coordinates in mm the columns 1, x, y of that plane's fit were parallel to 1e-16:
    # the fit fell back on the mean height, and the free corners of a 12 x 6 m roof came
    # out tens of millimetres from where they are at the origin.
    mesh = straight_grid([0.0, 4000.0, 8000.0, 12000.0], [0.0, 3000.0, 6000.0])
    pins = {0: 3000.0, 3: 3600.0, 8: 4200.0, 11: 3300.0, 5: 4500.0}
    local = lift(mesh, *pinned_targets(mesh, pins))
    xyz = mesh.vertices.copy()
    xyz[:, :2] += offset  # exact in binary: the same plan
    moved = mesh.with_vertices(xyz)
    far = lift(moved, *pinned_targets(moved, {v: h + 300_000.0 for v, h in pins.items()}))
    free = np.setdiff1d(np.arange(mesh.n_vertices), list(pins))
    assert np.ptp(local.heights[free]) > 100.0  # the free heights do depend on the fill
    assert np.max(np.abs((far.heights - 300_000.0) - local.heights)) < 1e-6 * 12000.0


def test_lift_names_the_drawing_unit_in_its_summary(tmp_path, capsys):
    """A roof plan drawn in feet ($INSUNITS 2): the summary read "RMS miss 0.641, max 1.27"
    with no unit (every message about the plan itself named feet). It names the drawing's
    unit now, and the report has it; a unitless drawing's lengths stay bare."""
    import json

    ezdxf = pytest.importorskip("ezdxf")
    from facet.cli import main

    for code, unit in ((2, "ft"), (0, None)):
        document = ezdxf.new()
        document.header["$INSUNITS"] = code
        msp = document.modelspace()
        for k in range(3):  # a 2 x 2 grid of 10 ft bays
            msp.add_line((0, 10 * k), (20, 10 * k))
            msp.add_line((10 * k, 0), (10 * k, 20))
        document.saveas(tmp_path / "plan.dxf")
        (tmp_path / "t.csv").write_text("x,y,z\n0,0,10\n20,0,11\n0,20,12\n20,20,14\n10,10,13\n")
        capsys.readouterr()
        assert main(["lift", str(tmp_path / "plan.dxf"), "--targets", str(tmp_path / "t.csv"),
                     "-o", str(tmp_path / "roof.obj"), "--report", str(tmp_path / "r.json")]) == 0
        (line,) = [t for t in capsys.readouterr().out.splitlines() if "RMS miss" in t]
        miss = re.search(r"RMS miss (\S+)( ft)?, max (\S+)( ft)? at vertex", line)
        assert miss and float(miss.group(1)) > 0, line
        assert (miss.group(2), miss.group(4)) == ((" ft", " ft") if unit else (None, None)), line
        assert json.loads((tmp_path / "r.json").read_text())["units"] == unit
