# SPDX-License-Identifier: LGPL-2.1-or-later
"""facet.live: soft selection, the live-update frames of a drag and the settle."""

import numpy as np
import pytest

import facet
from facet.errors import InputError
from facet.live import FALLOFFS, EditError, LiveSolver, panel_triangles, soft_weights


def grid(n=8, scale=1.0, offset=(0.0, 0.0, 0.0)):
    """An n x n quad grid over a saddle (every quad skew), unit cells times scale."""
    faces = [[j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1,
              (j + 1) * (n + 1) + i] for j in range(n) for i in range(n)]
    i, j = np.meshgrid(np.arange(n + 1.0), np.arange(n + 1.0), indexing="xy")
    x, y = i.ravel(), j.ravel()
    z = 0.05 * (x - n / 2) * (y - n / 2)
    xyz = np.stack([x, y, z], axis=1) * scale + np.asarray(offset)
    return facet.PolyMesh.from_faces(xyz, faces)


def test_soft_weights_falloffs():
    mesh = grid(8)
    center = 4 * 9 + 4  # the middle vertex
    xyz = mesh.vertices
    d = np.linalg.norm(xyz - xyz[center], axis=1)
    smooth = soft_weights(xyz, center, 2.0, "smooth")
    linear = soft_weights(xyz, center, 2.0, "linear")
    constant = soft_weights(xyz, center, 2.0, "constant")
    for w in (smooth, linear, constant):
        assert w[center] == 1.0
        assert np.all(w[d >= 2.0] == 0.0)
        assert np.all((w >= 0.0) & (w <= 1.0))
    one = np.flatnonzero(np.isclose(d, 1.0))
    assert np.allclose(linear[one], 0.5)
    assert np.allclose(smooth[one], 0.5)  # smoothstep is 1/2 half way
    diag = np.flatnonzero(np.isclose(d, np.sqrt(2.0)))
    t = np.sqrt(2.0) / 2.0
    assert np.allclose(smooth[diag], 1 - 3 * t * t + 2 * t**3)
    assert np.all(constant[d < 2.0] == 1.0)
    # The weight falls with the distance.
    order = np.argsort(d)
    assert np.all(np.diff(linear[order]) <= 1e-15)


def test_soft_weights_radius_zero_moves_one_vertex():
    mesh = grid(4)
    w = soft_weights(mesh.vertices, 7, 0.0)
    assert w.sum() == 1.0 and w[7] == 1.0


def test_soft_weights_do_not_depend_on_units_or_placement():
    small = grid(6)
    big = grid(6, scale=1000.0, offset=(6.0e6, 2.5e6, 300.0))  # mm, georeferenced
    for falloff in FALLOFFS:
        a = soft_weights(small.vertices, 10, 2.5, falloff)
        b = soft_weights(big.vertices, 10, 2500.0, falloff)
        assert np.allclose(a, b, atol=1e-9)


@pytest.mark.parametrize("args, words", [
    ((99, 1.0, "smooth"), "vertex 99 is out of range (81 vertices)"),
    ((-1, 1.0, "smooth"), "vertex -1 is out of range"),
    ((1.5, 1.0, "smooth"), "vertex 1.5 is out of range"),
    ((3, -1.0, "smooth"), "radius must be 0 or a positive length"),
    ((3, float("nan"), "smooth"), "radius must be 0 or a positive length"),
    ((3, 1.0, "gauss"), "falloff must be one of smooth, linear, constant, not 'gauss'"),
])
def test_soft_weights_bad_input(args, words):
    with pytest.raises(EditError) as info:
        soft_weights(grid(8).vertices, *args)
    assert words in str(info.value)
    assert isinstance(info.value, InputError)


def test_drag_moves_neighbours_by_weight_and_leaves_the_mesh_alone():
    mesh = grid(8)
    before = mesh.vertices.copy()
    live = LiveSolver(mesh)
    weights = live.begin_drag(40, radius=2.0, falloff="linear")
    moved = live.drag([0.0, 0.0, 0.5])
    assert set(moved) == set(np.flatnonzero(weights > 0))
    assert np.allclose(live.control - before, weights[:, None] * [0.0, 0.0, 0.5])
    live.drag_to(before[40] + [0.0, 0.0, 0.2])  # absolute, from the drag's start
    assert np.allclose(live.control[40], before[40] + [0.0, 0.0, 0.2])
    assert np.array_equal(mesh.vertices, before)
    assert live.moved
    live.end_drag()
    assert not live.dragging
    with pytest.raises(EditError, match="pick a vertex first"):
        live.drag([0, 0, 1])
    live.begin_drag(3)
    with pytest.raises(EditError, match="three finite numbers"):
        live.drag([0, 0, float("inf")])


def test_frames_follow_the_drag_and_settle_reaches_the_tolerance():
    mesh = grid(10)
    live = LiveSolver(mesh, tol=1e-6)
    assert live.result.planarity.max_rel_all <= 1e-6
    start = live.result.mesh.vertices.copy()
    live.begin_drag(60, radius=2.5)
    h = mesh.mean_edge_length()
    for step in range(1, 11):
        live.drag([0.0, 0.0, 0.05 * h * step])
        result = live.frame()
        assert np.all(np.isfinite(result.mesh.vertices))
        assert result.solve_seconds < 10 * live.frame_seconds + 0.5  # budgeted, loosely
    live.end_drag()
    # The planar result followed the control vertex up.
    assert live.result.mesh.vertices[60, 2] - start[60, 2] > 0.2 * h
    final = live.settle()
    assert final.converged and final.planarity.max_rel_all <= 1e-6
    assert live.settled and live.converged
    # The settled result is near the moved control mesh, not the original one.
    assert np.linalg.norm(final.mesh.vertices[60] - live.control[60]) < \
        np.linalg.norm(final.mesh.vertices[60] - mesh.vertices[60])


def test_seeded_from_a_result_starts_where_it_is():
    mesh = grid(8)
    solved = facet.planarize(mesh)
    live = LiveSolver(mesh, result=solved)
    assert live.result is solved
    live.begin_drag(20)
    live.drag([0.0, 0.0, 0.01])
    first = live.frame()
    # The first frame is a live update from the result it was seeded with: planar to
    # the tolerance, and the vertices more than 4 edges from the picked one (2, 2) keep
    # their seeded positions (the seed is one iteration from `solved`: within 1e-9).
    assert first.converged and first.planarity.max_rel_all <= 1e-6
    rows, cols = np.divmod(np.arange(mesh.n_vertices), 9)
    far = np.abs(rows - 2) + np.abs(cols - 2) > 4
    assert far.sum() > 40
    assert np.allclose(first.mesh.vertices[far], solved.mesh.vertices[far], rtol=0, atol=1e-9)
    assert not np.allclose(first.mesh.vertices[20], solved.mesh.vertices[20], rtol=0, atol=1e-6)
    assert np.all(np.isfinite(first.mesh.vertices))


def test_every_frame_is_planar_and_local():
    """Frames are live updates: each reaches the tolerance, the result follows the
    drag, and vertices far from the drag keep their bits from frame to frame."""
    mesh = grid(16, scale=1000.0, offset=(3.5e6, 5.6e6, 200.0))  # mm, georeferenced
    live = LiveSolver(mesh, tol=1e-6)
    start = live.result.mesh.vertices.copy()
    picked = 8 * 17 + 8
    live.begin_drag(picked, radius=1200.0)  # the picked vertex and its 4 neighbours
    rows, cols = np.divmod(np.arange(mesh.n_vertices), 17)
    # the region: 4 rings around the five moving vertices
    near = np.abs(rows - 8) + np.abs(cols - 8) <= 5
    previous = start
    for step in range(1, 6):
        live.drag([0.0, 0.0, 10.0 * step])
        result = live.frame()
        assert result.converged and result.planarity.max_rel_all <= 1e-6
        assert np.array_equal(result.mesh.vertices[~near], previous[~near])
        assert live.settled  # planar at the current positions: nothing left to settle
        previous = result.mesh.vertices.copy()
    assert previous[picked, 2] - start[picked, 2] > 10.0  # it followed 5 cm up by 1 cm+
    assert live.frames == 5


def test_surface_data_frames_fall_back_to_warm_resolves():
    mesh = grid(8)
    live = LiveSolver(mesh, data="surface", tol=1e-6)
    live.begin_drag(40, radius=1.5)
    live.drag([0.0, 0.0, 0.05])
    result = live.frame()
    assert np.all(np.isfinite(result.mesh.vertices)) and result.iterations >= 1
    assert not live.settled
    live.end_drag()
    assert live.settle().converged


def test_options_reach_the_solver():
    mesh = grid(8)
    live = LiveSolver(mesh, fixed=[0, 8], boundary="free", time_budget=5.0)
    live.begin_drag(0, radius=3.0)
    live.drag([0.0, 0.0, 1.0])
    live.end_drag()
    result = live.settle()
    # A fixed vertex sits on its (moved) control position.
    assert np.allclose(result.mesh.vertices[0], live.control[0], atol=1e-9)


def test_bad_options():
    mesh = grid(4)
    with pytest.raises(EditError, match="live_method must be one of auto, lg, ll, not 'xx'"):
        LiveSolver(mesh, live_method="xx")
    with pytest.raises(EditError, match="frame_seconds must be a positive time"):
        LiveSolver(mesh, frame_seconds=0)
    with pytest.raises(EditError, match="live_budget must be a positive time"):
        LiveSolver(mesh, live_budget=float("nan"))
    live = LiveSolver(mesh)
    with pytest.raises(EditError, match="25 finite points"):
        live.set_control(np.zeros((3, 3)))


def _area_vector(points):
    p = points - points.mean(axis=0)
    return 0.5 * np.cross(p, np.roll(p, -1, axis=0)).sum(axis=0)


def test_panel_triangles_cover_each_face_once():
    # a convex quad, a dart (corner 1 reflex), a dart (corner 0 reflex), a triangle, an
    # L-shaped hexagon (non-convex), georeferenced
    o = np.array([3.5e6, 5.6e6, 210.0])
    pts = [
        [0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0],           # 0-3 convex quad
        [10, 0, 0], [11, 1.5, 0], [12, 0, 0], [11, 3, 0],      # 4-7 dart, 5 reflex
        [20, 1, 0], [20, -1, 0], [23, 0, 0], [24, 3, 0],       # 8-11 (placeholder)
        [30, 0, 0], [31, 0, 0], [30, 1, 0],                    # 12-14 triangle
        [40, 0, 0], [43, 0, 0], [43, 1, 0], [41, 1, 0], [41, 3, 0], [40, 3, 0],  # 15-20 L
    ]
    xyz = np.asarray(pts, dtype=np.float64) + o
    xyz[8] = o + [21.5, 1.0, 0.0]  # corner 8 reflex: the dart 8 9 10 11 points into itself
    faces = [[0, 1, 2, 3], [4, 5, 6, 7], [8, 9, 10, 11], [12, 13, 14],
             [15, 16, 17, 18, 19, 20]]
    mesh = facet.PolyMesh.from_faces(xyz, faces)
    tri, face = panel_triangles(mesh)
    assert tri.dtype == np.int32 and face.dtype == np.int32
    assert list(np.bincount(face)) == [2, 2, 2, 1, 4]
    assert np.all(np.diff(face) >= 0)
    for f, corners in enumerate(faces):
        mine = tri[face == f]
        assert set(mine.ravel()) <= set(corners)
        whole = _area_vector(xyz[corners])
        parts = [_area_vector(xyz[t]) for t in mine]
        # every triangle wound like its face (no flipped piece) and the areas add up:
        # together they cover the face once, nothing outside it
        assert all(np.dot(a, whole) > 0 for a in parts)
        assert np.allclose(np.sum(parts, axis=0), whole, rtol=1e-9, atol=1e-9)
    # the dart is cut from its reflex corner 5 (the other diagonal leaves the face)
    assert {5, 7} <= set(tri[face == 1][0]) and {5, 7} <= set(tri[face == 1][1])
    assert {8, 10} <= set(tri[face == 2][0]) and {8, 10} <= set(tri[face == 2][1])


def test_panel_triangles_of_a_facade_grid():
    mesh = grid(6, scale=1000.0)
    tri, face = panel_triangles(mesh)
    assert tri.shape == (72, 3) and np.array_equal(face, np.repeat(np.arange(36), 2))
