# SPDX-License-Identifier: LGPL-2.1-or-later
"""Reading OFF files: the libigl tube, free-form layout, header variants, errors."""

import pytest

from facet import MeshError
from facet.io import read_mesh, read_off

TRIANGLE_AND_QUAD = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0.5 0\n"


def test_reads_tubemesh(data_dir):
    mesh = read_off(data_dir / "tubemesh.off")
    assert (mesh.n_vertices, mesh.n_faces) == (200, 171)
    assert mesh.vertices[0].tolist() == [-11.708, -2.365, 2.351]
    assert mesh.face(0) == [174, 198, 122, 102]
    assert mesh.face(-1) == [173, 196, 120, 101]
    assert mesh.info["format"] == "off" and mesh.info["header"] == "OFF"


def test_free_form_tokens_span_lines(write_file):
    path = write_file(
        "free.off",
        "OFF 5 2 6  # counts on the header line\n"
        "0 0 0 1 0\n0   # a vertex split over two lines\n"
        "1 1 0 0 1 0 2 0.5 0\n"
        "\n"
        "4 0 1 2 3\n"
        "3 1 4\n2\n",
    )
    mesh = read_off(path)
    assert mesh.vertices.tolist() == [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0.5, 0]]
    assert mesh.faces() == [[0, 1, 2, 3], [1, 4, 2]]


def test_headerless_counts(write_file):
    path = write_file("bare.off", "5 2 0\n" + TRIANGLE_AND_QUAD + "4 0 1 2 3\n3 1 4 2\n")
    assert read_off(path).n_faces == 2


def test_face_colours_are_skipped(write_file):
    path = write_file(
        "colours.off",
        "OFF\n5 2 0\n" + TRIANGLE_AND_QUAD + "4 0 1 2 3 255 0 0\n3 1 4 2 0.1 0.2 0.3 1\n",
    )
    assert read_off(path).faces() == [[0, 1, 2, 3], [1, 4, 2]]


@pytest.mark.parametrize(
    "header, extra",
    [
        ("COFF", " 255 128 0 255"),
        ("COFF", " 0.5 0.5 0.5"),
        ("NOFF", " 0 0 1"),
        ("CNOFF", " 0 0 1 0.2 0.2 0.2 1"),
        ("STOFF", " 0.25 0.75"),
    ],
)
def test_optional_vertex_fields_are_skipped(write_file, header, extra):
    vertices = "".join(line + extra + "\n" for line in TRIANGLE_AND_QUAD.splitlines())
    path = write_file("fields.off", f"{header}\n5 2 0\n{vertices}4 0 1 2 3\n3 1 4 2\n")
    mesh = read_off(path)
    assert mesh.vertices.tolist() == [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0.5, 0]]
    assert mesh.info["header"] == header


def test_index_out_of_range_names_line_and_face(write_file):
    path = write_file(
        "tubemesh.off",
        "OFF 8 4 0\n"
        "0 0 0  1 0 0\n1 1 0  0 1 0\n0 0 1  1 0 1\n1 1 1  0 1 1\n"
        "# faces\n\n\n"
        "4 0 1 2 3\n4 4 5 6 7\n4 0 1 5 4\n4 2 3 7 9\n",
    )
    with pytest.raises(MeshError) as caught:
        read_mesh(path)
    assert str(caught.value) == (
        f"{path}: line 12: face 3 has vertex index 9 out of range (8 vertices)"
    )
    assert (caught.value.line, caught.value.face) == (12, 3)


def test_file_ends_in_the_vertices(write_file):
    path = write_file("x.off", "OFF\n8 6 12\n0 0 0\n1 0 0\n1 1 0\n0 1\n")
    with pytest.raises(MeshError) as caught:
        read_off(path)
    assert str(caught.value) == f"{path}: file ends after 3 of 8 vertices"


def test_file_ends_in_the_faces(write_file):
    path = write_file("x.off", "OFF\n5 3 0\n" + TRIANGLE_AND_QUAD + "4 0 1 2 3\n3 1 4 2\n")
    with pytest.raises(MeshError, match=r"x\.off: file ends after 2 of 3 faces"):
        read_off(path)


def test_several_faces_on_one_line_fail_loudly(write_file):
    path = write_file("x.off", "OFF\n5 2 0\n" + TRIANGLE_AND_QUAD + "4 0 1 2 3 3 1 4 2\n")
    with pytest.raises(MeshError, match="file ends after 1 of 2 faces"):
        read_off(path)


def test_bad_number(write_file):
    path = write_file("x.off", "OFF\n3 1 0\n0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n")
    with pytest.raises(MeshError) as caught:
        read_off(path)
    assert str(caught.value) == f"{path}: line 4: cannot read 'zero' as a number"


def test_bad_count(write_file):
    with pytest.raises(MeshError, match=r"line 2: cannot read 'three' as a vertex count"):
        read_off(write_file("x.off", "OFF\nthree 1 0\n"))


def test_negative_count(write_file):
    with pytest.raises(MeshError, match=r"line 2: negative face count -1"):
        read_off(write_file("x.off", "OFF\n3 -1 0\n"))


def test_face_with_two_vertices(write_file):
    path = write_file("x.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n2 0 1\n")
    with pytest.raises(MeshError) as caught:
        read_off(path)
    assert str(caught.value) == f"{path}: line 7: face 1 has 2 vertices (at least 3 needed)"
    assert caught.value.face == 1


def test_no_faces(write_file):
    path = write_file("x.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n")
    with pytest.raises(MeshError) as caught:
        read_off(path)
    assert str(caught.value) == f"{path}: no faces"


def test_non_finite_coordinate(write_file):
    path = write_file("x.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 nan 0\n3 0 1 2\n")
    with pytest.raises(MeshError) as caught:
        read_off(path)
    assert str(caught.value) == f"{path}: line 5: vertex 2 has a non-finite coordinate"


def test_data_after_the_last_face(write_file):
    path = write_file("x.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 2 1 0\n")
    with pytest.raises(MeshError, match=r"line 7: unexpected '3' after the last face"):
        read_off(path)


@pytest.mark.parametrize(
    "text, message",
    [
        ("", "file is empty"),
        ("# only a comment\n", "file is empty"),
        ("v 0 0 0\n", r"line 1: not an OFF file: it starts with 'v'"),
        ("4OFF\n1 1 0\n", r"line 1: 4OFF \(4-D or n-D vertices\) is not supported"),
        ("OFF BINARY\n", "line 1: binary OFF is not supported"),
        ("OFF\n", "file ends before the vertex count"),
    ],
)
def test_not_an_off_file(write_file, text, message):
    with pytest.raises(MeshError, match=message):
        read_off(write_file("x.off", text))


def test_repeated_vertex_found_by_validation_gets_its_line(write_file):
    path = write_file("x.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n4 0 2 3 2\n")
    with pytest.raises(MeshError) as caught:
        read_off(path)
    assert caught.value.line == 8
    assert caught.value.face == 1
    assert caught.value.status_name == "FACET_ERROR_REPEATED_VERTEX"


def test_huge_vertex_count_does_not_allocate(write_file):
    path = write_file("x.off", "OFF\n99999999999 1 0\n0 0 0\n")
    with pytest.raises(MeshError, match="file ends after 1 of 99999999999 vertices"):
        read_off(path)


def test_the_trailing_data_message_counts_in_the_singular(tmp_path):
    # "(the header declares 4 vertices and 1 faces)"
    path = tmp_path / "one.off"
    path.write_text("OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\nextra\n")
    with pytest.raises(MeshError, match=r"declares 4 vertices and 1 face\)"):
        read_off(path)
