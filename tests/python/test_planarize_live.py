# SPDX-License-Identifier: LGPL-2.1-or-later
"""Live updates (Planarizer.solve(live=True)): the region around an edit is
re-solved, the rest of the mesh keeps its bits, and the mesh stays planar."""

import numpy as np
import pytest

import facet


def grid(n=24):
    faces = [[j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i]
             for j in range(n) for i in range(n)]
    i, j = np.meshgrid(np.arange(n + 1.0), np.arange(n + 1.0), indexing="xy")
    x, y = i.ravel(), j.ravel()
    z = 0.3 * np.sin(0.4 * x) * np.cos(0.3 * y) + 0.02 * (x - n / 2) * (y - n / 2) / n
    # metres at georeferenced coordinates
    v = np.stack([x * 1.5 + 3.5e6, y * 1.5 + 5.6e6, z * 1.5 + 210.0], axis=1)
    return facet.PolyMesh.from_faces(v, faces)


@pytest.mark.parametrize("method", ["lg", "ll"])
def test_live_update_follows_a_drag_locally(method):
    mesh = grid()
    tol = 1e-6 if method == "lg" else 1e-4
    solver = facet.Planarizer(mesh)
    first = solver.solve(method=method, tol=tol)
    assert first.converged
    control = mesh.vertices.copy()
    dragged = 12 * 25 + 11
    previous = first.mesh.vertices
    for _ in range(4):
        control[dragged, 2] += 0.015  # 1% of an edge per frame
        live = solver.solve(control, method=method, tol=tol, live=True)
        assert live.converged and live.planarity.max_rel.max() <= tol * 1.0001
        moved = np.any(live.mesh.vertices != previous, axis=1)
        assert moved[dragged]
        rows, cols = np.divmod(np.flatnonzero(moved), 25)
        # only the region (4 rings by default) moved; the rest kept its bits
        assert np.all(np.abs(rows - 12) + np.abs(cols - 11) <= 4)
        previous = live.mesh.vertices
    # it followed the drag (6 cm in all) by a third at least
    assert previous[dragged, 2] - first.mesh.vertices[dragged, 2] > 0.02


def test_first_live_call_is_a_full_solve():
    mesh = grid(8)
    a = facet.Planarizer(mesh).solve(live=True)
    b = facet.Planarizer(mesh).solve()
    assert a.converged and np.array_equal(a.mesh.vertices, b.mesh.vertices)


@pytest.mark.parametrize("data, weight", [("point", 1.0), ("plane", 0.01)])
def test_live_update_says_the_weight_it_was_solved_with(data, weight):
    """A live update says the weight it was solved with: the options' (its region's solve
    is not re-solved for panel quality, so nothing holds the vertices more firmly)."""
    mesh = grid(12)
    solver = facet.Planarizer(mesh)
    first = solver.solve(data=data, method="lg")
    assert first.converged and first.data_tangent == weight
    control = mesh.vertices.copy()
    control[6 * 13 + 6, 2] += 0.015
    live = solver.solve(control, data=data, method="lg", live=True)
    assert live.converged and live.data_tangent == weight
    assert live.options["data_tangent"] == weight
