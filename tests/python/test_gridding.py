# SPDX-License-Identifier: LGPL-2.1-or-later
"""Control meshes from surfaces: quad and hex grids, welding, triangle pairing."""

import math

import numpy as np
import pytest

import facet
from facet.errors import Cancelled, InputError
from facet.gridding import (GridError, grid_counts, hex_grid, pair_triangles, quad_grid,
                            sample_surface, weld)


def plane(u, v):
    return np.column_stack([u, v, np.zeros_like(u)])


def cylinder(u, v, radius=1000.0):
    return np.column_stack([radius * np.cos(u), radius * np.sin(u), v])


def sphere(u, v, radius=5.0):
    return np.column_stack([radius * np.cos(v) * np.cos(u), radius * np.cos(v) * np.sin(u),
                            radius * np.sin(v)])


def degree_counts(mesh):
    counts = np.zeros(mesh.n_vertices, dtype=int)
    for a, b in mesh.edges():
        counts[a] += 1
        counts[b] += 1
    return counts


def signed_area_z(mesh):
    return [0.5 * np.cross(mesh.vertices[f][:, :2], np.roll(mesh.vertices[f][:, :2], -1,
                                                              axis=0)).sum()
            for f in mesh.faces()]


def test_quad_grid_topology_and_orientation():
    uv, faces = quad_grid(3, 2)
    assert uv.shape == (12, 2) and faces.shape == (6, 4)
    mesh = sample_surface(plane, (0, 3), (0, 2), "quad", 3, 2)
    assert mesh.n_faces == 6
    areas = signed_area_z(mesh)
    assert np.allclose(areas, 1.0)  # unit squares, counter-clockwise (normal +z)
    assert mesh.vertices.min(axis=0).tolist() == [0, 0, 0]
    assert mesh.vertices.max(axis=0).tolist() == [3, 2, 0]


def test_hex_grid_is_a_honeycomb():
    uv, faces = hex_grid(4, 3)
    assert faces.shape == (12, 6)
    assert uv.min() == 0.0 and uv.max() == 1.0
    # every hexagon counter-clockwise in (u, v), every interior vertex of degree 3
    mesh = facet.PolyMesh.from_faces(np.column_stack([uv, np.zeros(len(uv))]), faces.tolist())
    assert all(a > 0 for a in signed_area_z(mesh))
    degrees = degree_counts(mesh)
    assert degrees.max() == 3 and degrees.min() == 2
    mesh.validate()


def test_hex_grid_regular_on_matching_aspect():
    nu, nv = 5, 4
    size = 100.0  # across flats
    r = size / math.sqrt(3)
    width, height = size * (nu + 0.5), 1.5 * r * nv + 0.5 * r
    mesh = sample_surface(plane, (0, width), (0, height), "hex", nu, nv)
    lengths = [np.linalg.norm(mesh.vertices[a] - mesh.vertices[b]) for a, b in mesh.edges()]
    assert np.allclose(lengths, r)
    assert grid_counts(plane, (0, width), (0, height), size, "hex") == (nu, nv)


def test_grid_counts_from_panel_size():
    # a quarter cylinder of radius 1000: arc 1570.8 mm, height 3000 mm
    counts = grid_counts(cylinder, (0, math.pi / 2), (0, 3000), 500.0)
    assert counts == (3, 6)
    with pytest.raises(GridError, match="panel size"):
        grid_counts(cylinder, (0, 1), (0, 1), -1.0)
    with pytest.raises(GridError, match="at most"):
        grid_counts(cylinder, (0, math.pi), (0, 3000), 0.001)


def test_closed_surface_welds_seam_and_poles():
    parts = sample_surface(sphere, (0, 2 * math.pi), (-math.pi / 2, math.pi / 2), "quad", 8, 6)
    assert parts.n_vertices == 9 * 7
    mesh = weld([parts], 1e-9)
    # seam column merged, each pole one vertex: 8 * 5 + 2
    assert mesh.n_vertices == 42
    sizes = sorted({len(f) for f in mesh.faces()})
    assert sizes == [3, 4]  # pole cells become triangles
    assert mesh.n_faces == 48
    mesh.validate()
    assert all(d >= 3 for d in degree_counts(mesh))  # closed: no boundary


def test_weld_two_patches():
    a = sample_surface(plane, (0, 1), (0, 1), "quad", 2, 2)
    b = sample_surface(plane, (1, 2), (0, 1), "quad", 2, 2)
    mesh = weld([a, b], 1e-9)
    assert mesh.n_vertices == 15 and mesh.n_faces == 8
    assert weld([a, b], 0.0).n_vertices == 15
    with pytest.raises(GridError, match="tolerance"):
        weld([a], float("nan"))


def test_trimmed_domain_drops_outside_cells():
    mesh = sample_surface(plane, (0, 4), (0, 4), "quad", 4, 4,
                          inside=lambda u, v: (u <= 2.0) | (v <= 2.0))
    assert mesh.n_faces == 12
    with pytest.raises(GridError, match="inside"):
        sample_surface(plane, (0, 1), (0, 1), "quad", 2, 2, inside=lambda u, v: u < -1)


def test_bad_inputs_name_the_input():
    with pytest.raises(GridError, match="nu is 0"):
        quad_grid(0, 3)
    with pytest.raises(GridError, match="nv must be an integer"):
        hex_grid(2, 1.5)
    with pytest.raises(GridError, match="v range"):
        sample_surface(plane, (0, 1), (1, 1), "quad", 2, 2)
    with pytest.raises(GridError, match="pattern"):
        sample_surface(plane, (0, 1), (0, 1), "tri", 2, 2)
    def pole(u, v):
        xyz = plane(u, v)
        xyz[u == 0.0] = np.nan
        return xyz

    with pytest.raises(GridError, match=r"not finite at \(u, v\) = \(0, 0\)"):
        sample_surface(pole, (0, 1), (0, 1), "quad", 2, 2)
    assert issubclass(GridError, InputError)


def test_progress_cancels():
    with pytest.raises(Cancelled):
        sample_surface(plane, (0, 1), (0, 1), "quad", 100, 100, progress=lambda d, t: True)
    seen = []
    sample_surface(plane, (0, 1), (0, 1), "quad", 100, 100,
                   progress=lambda d, t: seen.append((d, t)))
    assert seen[-1] == (101 * 101, 101 * 101)


def triangulated_grid(nu, nv, diagonal="alternate"):
    uv, quads = quad_grid(nu, nv)
    xyz = np.column_stack([uv[:, 0] * nu, uv[:, 1] * nv, np.zeros(len(uv))])
    tris = []
    for k, (a, b, c, d) in enumerate(quads.tolist()):
        if diagonal == "alternate" and k % 2:
            tris += [[a, b, d], [b, c, d]]
        else:
            tris += [[a, b, c], [a, c, d]]
    return facet.PolyMesh.from_faces(xyz, tris)


def test_pair_triangles_recovers_the_quads():
    for diagonal in ("same", "alternate"):
        mesh = pair_triangles(triangulated_grid(4, 3, diagonal))
        assert [len(f) for f in mesh.faces()] == [4] * 12
        assert np.allclose(signed_area_z(mesh), 1.0)
        mesh.validate()


def test_pair_triangles_keeps_bad_pairs_as_triangles():
    # two triangles folded by 90 degrees: no quad with max_fold 20
    xyz = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 0, 1.0]])
    folded = facet.PolyMesh.from_faces(xyz, [[0, 1, 2], [1, 0, 3]])
    assert [len(f) for f in pair_triangles(folded).faces()] == [3, 3]
    assert [len(f) for f in pair_triangles(folded, max_fold=100).faces()] == [4]
    # a non-convex pair (a dart) stays two triangles
    xyz = np.array([[0, 0, 0], [2, 0, 0], [1, 0.2, 0], [1, 2, 0.0]])
    dart = facet.PolyMesh.from_faces(xyz, [[0, 2, 3], [2, 1, 3]])
    assert [len(f) for f in pair_triangles(dart, max_corner_deviation=90).faces()] == [3, 3]
    with pytest.raises(GridError, match="max_fold"):
        pair_triangles(folded, max_fold=-1)


def test_pair_triangles_prefers_the_most_rectangular():
    # a strip of 3 triangles: the middle edge pair is a square, the other pair a rhombus
    xyz = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 1.0, 0]])
    strip = facet.PolyMesh.from_faces(xyz, [[0, 1, 2], [0, 2, 3], [1, 4, 2]])
    faces = pair_triangles(strip, max_corner_deviation=60).faces()
    quads = [sorted(int(i) for i in f) for f in faces if len(f) == 4]
    assert quads == [[0, 1, 2, 3]]


@pytest.mark.parametrize("pattern,sizes", [("quad", {4}), ("hex", {6})])
def test_periodic_grid_closes_around(pattern, sizes):
    mesh = sample_surface(cylinder, (0, 2 * math.pi), (0, 3000), pattern, 8, 5,
                          periodic_u=True)
    mesh.validate()
    assert {len(f) for f in mesh.faces()} == sizes
    assert mesh.n_faces == 40
    # no vertex twice: the seam is shared, not duplicated
    rounded = {tuple(np.round(p, 6)) for p in mesh.vertices}
    assert len(rounded) == mesh.n_vertices
    # boundary edges only at the bottom and top (z = 0 and z = 3000)
    count = {}
    for face in mesh.faces():
        for a, b in zip(face, np.roll(face, -1)):
            key = (min(a, b), max(a, b))
            count[key] = count.get(key, 0) + 1
    boundary = [key for key, n in count.items() if n == 1]
    # the bottom and top rings only: 8 edges each (quads), 16 each (hexagons' zigzags)
    assert len(boundary) == (16 if pattern == "quad" else 32)
    z = mesh.vertices[np.array(boundary).ravel(), 2]
    assert np.all((z < 200.0) | (z > 2800.0))
    ring = mesh.vertices[np.array(boundary).ravel()]
    assert np.allclose(np.hypot(ring[:, 0], ring[:, 1]), 1000.0)
    # every hexagon / quad turns outward (counter-clockwise seen from outside)
    for face in mesh.faces():
        corners = mesh.vertices[face]
        normal = np.cross(corners, np.roll(corners, -1, axis=0)).sum(axis=0)
        centre = corners.mean(axis=0)
        assert np.dot(normal[:2], centre[:2]) > 0
    with pytest.raises(GridError, match="nu is 2"):
        sample_surface(cylinder, (0, 1), (0, 1), pattern, 2, 2, periodic_u=True)
