# SPDX-License-Identifier: LGPL-2.1-or-later
"""Error classes and the conversion of core errors."""

import pickle

import numpy as np
import pytest

from facet.errors import Cancelled, FacetError, MeshError, from_core


def test_mesh_error_message_names_file_line_and_problem():
    error = MeshError("face 3 has vertex index 9 out of range (8 vertices)",
                      source="tubemesh.off", line=12, face=3)
    assert str(error) == (
        "tubemesh.off: line 12: face 3 has vertex index 9 out of range (8 vertices)"
    )
    assert (error.source, error.line, error.face, error.vertex) == ("tubemesh.off", 12, 3, None)
    assert "\n" not in str(error)


def test_mesh_error_without_line_or_source():
    assert str(MeshError("no faces", source="x.obj")) == "x.obj: no faces"
    assert str(MeshError("mesh has no edges")) == "mesh has no edges"


def test_mesh_error_is_a_value_error_and_a_facet_error():
    error = MeshError("bad")
    assert isinstance(error, ValueError)
    assert isinstance(error, FacetError)
    assert not isinstance(Cancelled("stop"), MeshError)
    assert isinstance(Cancelled("stop"), FacetError)


def test_located_adds_file_and_line_and_keeps_indices():
    error = MeshError("face 2 repeats vertex 4", face=2, vertex=4)
    placed = error.located("roof.obj", 17)
    assert str(placed) == "roof.obj: line 17: face 2 repeats vertex 4"
    assert (placed.face, placed.vertex) == (2, 4)
    assert error.source is None


def test_mesh_error_survives_pickling():
    error = MeshError("vertex 2 has a non-finite coordinate", source="x.obj", line=3, vertex=2)
    error.status_name = "FACET_ERROR_NONFINITE"
    copy = pickle.loads(pickle.dumps(error))
    assert str(copy) == str(error)
    assert (copy.line, copy.vertex, copy.status_name) == (3, 2, "FACET_ERROR_NONFINITE")


class FakeCoreError(Exception):
    def __init__(self, message, status_name, face=-1, vertex=-1):
        super().__init__(message)
        self.status = -6
        self.status_name = status_name
        self.face = face
        self.vertex = vertex


@pytest.mark.parametrize(
    "status_name",
    [
        "FACET_ERROR_EMPTY_MESH",
        "FACET_ERROR_BAD_FACE_START",
        "FACET_ERROR_INDEX_OUT_OF_RANGE",
        "FACET_ERROR_DEGENERATE_FACE",
        "FACET_ERROR_REPEATED_VERTEX",
        "FACET_ERROR_NONFINITE",
    ],
)
def test_from_core_mesh_statuses_become_mesh_errors(status_name):
    error = from_core(FakeCoreError("face 17 repeats vertex 4", status_name, 17, 4), "a.obj")
    assert type(error) is MeshError
    assert str(error) == "a.obj: face 17 repeats vertex 4"
    assert (error.face, error.vertex, error.status_name) == (17, 4, status_name)


def test_from_core_minus_one_means_no_face_or_vertex():
    error = from_core(FakeCoreError("empty mesh", "FACET_ERROR_EMPTY_MESH"))
    assert error.face is None and error.vertex is None
    assert str(error) == "empty mesh"


def test_from_core_cancelled():
    error = from_core(FakeCoreError("cancelled", "FACET_ERROR_CANCELLED"))
    assert type(error) is Cancelled


@pytest.mark.parametrize(
    "status_name", ["FACET_ERROR_NUMERICAL", "FACET_ERROR_OUT_OF_MEMORY", "FACET_ERROR_TOO_LARGE"]
)
def test_from_core_other_statuses_are_facet_errors(status_name):
    error = from_core(FakeCoreError("solve failed", status_name), source="a.off")
    assert type(error) is FacetError
    assert not isinstance(error, MeshError)
    assert str(error) == "a.off: solve failed"
    assert error.status_name == status_name


def test_from_core_with_the_real_core_error():
    _core = pytest.importorskip("facet._core")
    xyz = np.array([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0], dtype=np.float64)
    start = np.array([0, 4], dtype=np.int32)
    faces = np.array([0, 1, 1, 2], dtype=np.int32)
    with pytest.raises(_core.CoreError) as caught:
        _core.validate(xyz, start, faces)
    error = from_core(caught.value, source="panel.obj")
    assert isinstance(error, MeshError)
    assert error.status_name == "FACET_ERROR_REPEATED_VERTEX"
    assert error.face == 0
    assert str(error).startswith("panel.obj: face 0")


def test_mesh_error_message_stays_on_one_line():
    error = MeshError("first part\nsecond part", source="a.obj", line=2)
    assert str(error) == "a.obj: line 2: first part second part"
