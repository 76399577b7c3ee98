# SPDX-License-Identifier: LGPL-2.1-or-later
"""PolyMesh: construction checks, topology queries, validation."""

import numpy as np
import pytest

from facet import MeshError, PolyMesh

SQUARE = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]


def two_panels():
    """A quad and a triangle sharing the edge 1-2."""
    vertices = SQUARE + [[2.0, 0.5, 0.0]]
    return PolyMesh.from_faces(vertices, [[0, 1, 2, 3], [1, 4, 2]])


def test_from_faces_builds_compressed_rows():
    mesh = two_panels()
    assert mesh.n_vertices == 5
    assert mesh.n_faces == 2
    assert mesh.face_start.tolist() == [0, 4, 7]
    assert mesh.face_vertices.tolist() == [0, 1, 2, 3, 1, 4, 2]
    assert mesh.degrees.tolist() == [4, 3]
    assert mesh.faces() == [[0, 1, 2, 3], [1, 4, 2]]
    assert mesh.face(1) == [1, 4, 2]
    assert mesh.face(-1) == [1, 4, 2]


def test_arrays_have_the_core_dtypes_and_layout():
    mesh = PolyMesh(np.array(SQUARE, dtype=np.float32), [0, 4], np.array([0, 1, 2, 3], np.int64))
    assert mesh.vertices.dtype == np.float64 and mesh.vertices.flags.c_contiguous
    assert mesh.face_start.dtype == np.int32 and mesh.face_start.flags.c_contiguous
    assert mesh.face_vertices.dtype == np.int32 and mesh.face_vertices.flags.c_contiguous
    assert mesh.vertices.shape == (4, 3)


def test_face_out_of_range_raises_index_error():
    with pytest.raises(IndexError):
        two_panels().face(2)


def test_arrays_are_read_only_and_copied_from_the_caller():
    vertices = np.array(SQUARE)
    mesh = PolyMesh(vertices, [0, 4], [0, 1, 2, 3])
    vertices[0, 0] = 99.0
    assert mesh.vertices[0, 0] == 0.0
    with pytest.raises(ValueError):
        mesh.vertices[0, 0] = 5.0
    with pytest.raises(ValueError):
        mesh.face_vertices[0] = 3


def test_with_vertices_shares_topology_and_copies_coordinates():
    mesh = two_panels()
    moved = np.array(mesh.vertices) + [0.0, 0.0, 1.0]
    lifted = mesh.with_vertices(moved)
    assert lifted.face_start is mesh.face_start
    assert lifted.face_vertices is mesh.face_vertices
    assert np.array_equal(lifted.vertices[:, 2], np.ones(5))
    assert np.array_equal(mesh.vertices[:, 2], np.zeros(5))
    assert lifted.same_topology(mesh)
    with pytest.raises(MeshError, match="shape"):
        mesh.with_vertices(moved[:4])


def test_copy_is_independent_and_equal():
    mesh = two_panels()
    twin = mesh.copy()
    assert twin.face_vertices is not mesh.face_vertices
    assert np.array_equal(twin.vertices, mesh.vertices)
    assert twin.faces() == mesh.faces()
    assert twin.same_topology(mesh)


def test_same_topology_sees_a_different_face():
    mesh = two_panels()
    other = PolyMesh.from_faces(mesh.vertices, [[0, 1, 2, 3], [1, 4, 3]])
    assert not mesh.same_topology(other)


def test_edges_are_unique_undirected_and_sorted():
    edges = two_panels().edges()
    assert edges.dtype == np.int32
    assert edges.tolist() == [[0, 1], [0, 3], [1, 2], [1, 4], [2, 3], [2, 4]]


def test_mean_edge_length():
    mesh = two_panels()
    side = np.hypot(1.0, 0.5)
    assert mesh.mean_edge_length() == pytest.approx((4 * 1.0 + 2 * side) / 6, rel=1e-15)


def test_bounds():
    lower, upper = two_panels().bounds()
    assert lower.tolist() == [0.0, 0.0, 0.0]
    assert upper.tolist() == [2.0, 1.0, 0.0]


def test_repr_counts_vertices_and_faces():
    assert repr(two_panels()) == "<PolyMesh: 5 vertices, 2 faces>"


@pytest.mark.parametrize(
    "vertices, face_start, face_vertices, message",
    [
        (np.zeros((4, 2)), [0, 3], [0, 1, 2], r"\(n, 3\) array"),
        ([["a", "b", "c"]], [0, 3], [0, 0, 0], "cannot be read as numbers"),
        (SQUARE, [], [], "at least one offset"),
        (SQUARE, [1, 4], [0, 1, 2, 3], "start at 0"),
        (SQUARE, [0, 4, 3, 7], [0, 1, 2, 3, 0, 1, 2], "decreases at face 1"),
        (SQUARE, [0, 4], [0, 1, 2], "ends at 4 but face_vertices holds 3"),
        (SQUARE, [0, 3.0], [0, 1, 2], "must hold integers"),
        (SQUARE, [[0, 3]], [0, 1, 2], "1-D array"),
        (SQUARE, [0, 3], [0, 1, 2**40], "32-bit"),
    ],
)
def test_constructor_refuses_bad_structure(vertices, face_start, face_vertices, message):
    with pytest.raises(MeshError, match=message):
        PolyMesh(vertices, face_start, face_vertices)


def test_validate_reports_edges_and_boundary():
    report = two_panels().validate()
    assert report["n_edges"] == 6
    assert report["n_boundary_edges"] == 5
    assert report["n_non_manifold_edges"] == 0
    assert report["n_isolated_vertices"] == 0
    assert report["max_degree"] == 4


def test_validate_counts_isolated_vertices():
    mesh = PolyMesh.from_faces(SQUARE + [[5.0, 5.0, 5.0]], [[0, 1, 2, 3]])
    report = mesh.validate()
    assert report["n_isolated_vertices"] == 1
    assert report["first_isolated_vertex"] == 4


@pytest.mark.parametrize(
    "vertices, faces, status, face",
    [
        (SQUARE, [[0, 1, 2, 1]], "FACET_ERROR_REPEATED_VERTEX", 0),
        (SQUARE, [[0, 1, 2], [0, 2, 2]], "FACET_ERROR_DEGENERATE_FACE", 1),
        (SQUARE, [[0, 1, 7]], "FACET_ERROR_INDEX_OUT_OF_RANGE", 0),
        (SQUARE, [[0, 1, -1]], "FACET_ERROR_INDEX_OUT_OF_RANGE", 0),
        (SQUARE, [], "FACET_ERROR_EMPTY_MESH", None),
    ],
)
def test_validate_raises_mesh_errors_naming_the_face(vertices, faces, status, face):
    mesh = PolyMesh.from_faces(vertices, faces)
    with pytest.raises(MeshError) as caught:
        mesh.validate()
    assert caught.value.status_name == status
    assert caught.value.face == face
    if face is not None:
        assert f"face {face}" in str(caught.value)


def test_validate_refuses_non_finite_coordinates():
    vertices = np.array(SQUARE)
    vertices[2, 1] = np.inf
    with pytest.raises(MeshError) as caught:
        PolyMesh.from_faces(vertices, [[0, 1, 2, 3]]).validate()
    assert caught.value.status_name == "FACET_ERROR_NONFINITE"
    assert caught.value.vertex == 2


def test_validate_names_the_source_file():
    mesh = PolyMesh.from_faces(SQUARE, [[0, 1, 2, 1]], info={"source": "wall.obj"})
    with pytest.raises(MeshError, match=r"^wall\.obj: face 0"):
        mesh.validate()


def test_info_is_carried_to_new_meshes():
    mesh = PolyMesh.from_faces(SQUARE, [[0, 1, 2, 3]], info={"source": "wall.obj"})
    assert mesh.with_vertices(SQUARE).info["source"] == "wall.obj"
    assert mesh.copy().info == {"source": "wall.obj"}
