# SPDX-License-Identifier: LGPL-2.1-or-later
"""Reading Wavefront OBJ files: real files, the syntax corners, every error."""

import numpy as np
import pytest

from facet import MeshError
from facet.io import read_mesh, read_obj


def test_reads_conical_mesh_from_dos(data_dir):
    mesh = read_obj(data_dir / "conical1.obj")
    assert (mesh.n_vertices, mesh.n_faces) == (1147, 1080)
    assert set(mesh.degrees.tolist()) == {4}
    # first vertex and first face exactly as written in the file
    assert mesh.vertices[0].tolist() == [-14.0889854431, 16.3727531433, -0.0830370634794]
    assert mesh.face(0) == [0, 31, 32, 1]
    assert mesh.info["format"] == "obj"
    assert mesh.info["source"] == data_dir / "conical1.obj"


def test_reads_corners_with_normals_and_ignores_vn(data_dir):
    mesh = read_mesh(data_dir / "quad_dome.obj")  # 'f a//n', 'vn', 'g'
    assert (mesh.n_vertices, mesh.n_faces) == (57, 48)
    assert mesh.face(0) == [37, 44, 39, 11]
    assert mesh.vertices[37].tolist() == [0.9027777910232544, 6.753472328186035, 0.0]


def test_reads_corners_with_texture_and_normal(data_dir):
    mesh = read_mesh(data_dir / "rhinomesh.obj")  # 'f a/t/n'
    assert (mesh.n_vertices, mesh.n_faces) == (121, 100)
    assert mesh.face(0) == [0, 1, 12, 11]


def test_reads_hypar(data_dir):
    mesh = read_mesh(data_dir / "hypar.obj")
    assert (mesh.n_vertices, mesh.n_faces) == (81, 64)
    assert mesh.vertices[0].tolist() == [0.0, 0.0, 3.0]


def test_graph_of_polylines_has_no_faces(data_dir):
    with pytest.raises(MeshError, match=r"funicular\.obj: no faces: the file holds 7 lines or"):
        read_obj(data_dir / "funicular.obj")


def test_syntax_corners(write_file):
    path = write_file(
        "corners.obj",
        "# a comment\n"
        "mtllib panels.mtl\n"
        "o facade\n"
        "g north\n"
        "v 0 0 0 1.0\n"  # weight, ignored
        "v 1 0 0 0.5 0.5 0.5\n"  # colour, ignored
        "v 1 1 \\\n"  # continued line
        "   0\n"
        "v 0 1 0   # trailing comment\n"
        "vt 0 0\n"
        "vn 0 0 1\n"
        "vp 0.5\n"
        "s off\n"
        "usemtl glass\n"
        "l 1 2\n"
        "f 1/1/1 2/1/1 3//1 4\n"
        "v 2 0.5 0\n"
        "f -4 -1 -3\n"  # relative: vertices 2, 5, 3
        "fo 1 2 3\r\n",
    )
    mesh = read_obj(path)
    assert mesh.vertices.tolist() == [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0.5, 0]]
    assert mesh.faces() == [[0, 1, 2, 3], [1, 4, 2], [0, 1, 2]]


def test_windows_line_ends(write_file):
    path = write_file("crlf.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n")
    assert read_obj(path).faces() == [[0, 1, 2]]


def test_bad_number_names_line_and_token(write_file):
    path = write_file("bad.obj", "# panels\nv 0 0 0\nv 1 0 0\nv 1 abc 0\nf 1 2 3\n")
    with pytest.raises(MeshError) as caught:
        read_obj(path)
    assert str(caught.value) == f"{path}: line 4: cannot read 'abc' as a number"
    assert caught.value.line == 4
    assert caught.value.source == path


def test_face_with_two_vertices(write_file):
    path = write_file("x.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\n\nf 3 4\n")
    with pytest.raises(MeshError) as caught:
        read_obj(path)
    assert str(caught.value) == f"{path}: line 7: face 1 has 2 vertices (at least 3 needed)"


def test_no_faces(write_file):
    path = write_file("x.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\n")
    with pytest.raises(MeshError) as caught:
        read_obj(path)
    assert str(caught.value) == f"{path}: no faces"


def test_empty_file_is_named_empty(write_file):
    with pytest.raises(MeshError, match="file is empty"):
        read_obj(write_file("empty.obj", ""))


@pytest.mark.parametrize("value", ["nan", "inf", "-Infinity", "NaN"])
def test_non_finite_coordinate(write_file, value):
    path = write_file("x.obj", f"v 0 0 0\nv 1 0 0\nv 1 {value} 0\nf 1 2 3\n")
    with pytest.raises(MeshError) as caught:
        read_obj(path)
    assert str(caught.value) == f"{path}: line 3: vertex 2 has a non-finite coordinate"
    assert caught.value.vertex == 2


def test_index_out_of_range_names_face_and_line(write_file):
    path = write_file("x.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\nf 1 3 9\n")
    with pytest.raises(MeshError) as caught:
        read_obj(path)
    assert str(caught.value) == (
        f"{path}: line 5: face 1 has vertex index 9 out of range (3 vertices)"
    )
    assert caught.value.face == 1


def test_index_zero_is_refused(write_file):
    path = write_file("x.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 0 1 2\n")
    with pytest.raises(MeshError, match=r"line 4: face 0 has vertex index 0 \(OBJ indices start"):
        read_obj(path)


def test_relative_index_before_the_first_vertex(write_file):
    path = write_file("x.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 1 1 0\n")
    with pytest.raises(MeshError, match=r"line 3: face 0 has relative index -3 but only 2 "):
        read_obj(path)


def test_index_that_is_not_a_number(write_file):
    path = write_file("x.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 x/3\n")
    with pytest.raises(MeshError, match=r"line 4: cannot read 'x' as a vertex index"):
        read_obj(path)


def test_vertex_with_two_coordinates(write_file):
    path = write_file("x.obj", "v 0 0 0\nv 1 0\n")
    with pytest.raises(MeshError, match=r"line 2: vertex 1 has 2 coordinates \(3 needed\)"):
        read_obj(path)


def test_repeated_vertex_found_by_validation_gets_its_line(write_file):
    path = write_file("x.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 2 3 2\n")
    with pytest.raises(MeshError) as caught:
        read_obj(path)
    assert caught.value.line == 6
    assert caught.value.face == 1
    assert caught.value.status_name == "FACET_ERROR_REPEATED_VERTEX"
    assert str(caught.value).startswith(f"{path}: line 6: face 1 ")


def test_degenerate_face_found_by_validation_gets_its_line(write_file):
    path = write_file("x.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\nf 1 1 2\n")
    with pytest.raises(MeshError) as caught:
        read_obj(path)
    assert caught.value.line == 5
    assert caught.value.status_name == "FACET_ERROR_DEGENERATE_FACE"


def test_validation_can_be_skipped(write_file):
    path = write_file("x.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 2\n")
    mesh = read_obj(path, validate=False)
    assert mesh.faces() == [[0, 1, 1]]


def test_missing_file_raises_os_error(tmp_path):
    with pytest.raises(FileNotFoundError):
        read_obj(tmp_path / "absent.obj")


def test_vertex_values_parse_exactly(write_file):
    path = write_file("x.obj", "v 0.1 -2.5e-3 1e22\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    assert read_obj(path).vertices[0].tolist() == [0.1, -2.5e-3, 1e22]
    assert np.isfinite(read_obj(path).vertices).all()


def test_index_beyond_64_bits(write_file):
    path = write_file("x.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\n")
    with pytest.raises(MeshError, match=r"line 4: face 0 has vertex index 99999999999999999999999"):
        read_obj(path)


def test_a_comment_ending_in_a_backslash_joins_nothing(write_file):
    # a Windows folder in a comment; the next statement must not vanish into it
    text = ("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
            "# exported to C:\\work\\facade\\\nf 1 2 3 4\nf 2 5 6 \\\n 3  # continued\n")
    mesh = read_obj(write_file("x.obj", text))
    assert mesh.faces() == [[0, 1, 2, 3], [1, 4, 5, 2]]


@pytest.mark.parametrize("line, token", [("v 1_5 0 0", "1_5"), ("v 0 \u0663 0", "\u0663"),
                                         ("f 1 2 \u0663", "\u0663")])
def test_numbers_only_as_mesh_files_write_them(write_file, line, token):
    # Python's float() and int() read '1_5' as 15 and Arabic-Indic digits as digits
    text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n" + line + "\n"
    with pytest.raises(MeshError, match=f"line 4: cannot read '{token}' as"):
        read_obj(write_file("x.obj", text))


def test_groups_and_materials_come_back_before_the_same_faces(tmp_path):
    # the output was one flat group: a facade's zones (g), objects (o) and materials
    # (usemtl, mtllib) were dropped by planarize, unsaid
    import facet
    from facet.io import write_obj

    source = tmp_path / "zones.obj"
    source.write_text(
        "mtllib facade.mtl\no Facade\n"
        "v 0 0 0\nv 1 0 0\nv 1 1 0.1\nv 0 1 0\nv 2 0 0\nv 2 1 0.2\nv 3 0 0\nv 3 1 0\n"
        "g north\nusemtl glass\nf 1 2 3 4\n"
        "g   south  \nusemtl metal # a comment\nf 2 5 6 3\nf 5 7 8 6\ng empty\n")
    mesh = read_obj(source)
    result = facet.planarize(mesh).mesh
    write_obj(result, tmp_path / "out.obj")
    kept = [line for line in (tmp_path / "out.obj").read_text().splitlines()
            if not line.startswith(("v ", "#"))]
    assert kept == ["mtllib facade.mtl", "o Facade", "g north", "usemtl glass", "f 1 2 3 4",
                    "g south", "usemtl metal", "f 2 5 6 3", "f 5 7 8 6", "g empty"]
    assert np.array_equal(read_obj(tmp_path / "out.obj").vertices, result.vertices)
    # a mesh with other faces than the file's (one face fewer) is written without them
    fewer = facet.PolyMesh(mesh.vertices, mesh.face_start[:3], mesh.face_vertices[:8],
                           info=mesh.info)
    write_obj(fewer, tmp_path / "fewer.obj")
    text = (tmp_path / "fewer.obj").read_text()
    assert "mtllib facade.mtl" in text and "g north" not in text and "usemtl" not in text


def test_groups_follow_their_faces_through_cleanup(tmp_path):
    # a cleaned-up mesh has fewer faces: its groups were dropped with the file's face count
    import facet
    from facet.io import write_obj

    rows = ["v %g %d %g" % (x, j, 0.05 * x * j) for j in range(3) for x in (0, 1, 1.004, 2)]
    faces = []
    for j in range(2):
        for i in range(3):
            v = j * 4 + i + 1
            faces.append(f"f {v} {v + 1} {v + 5} {v + 4}")
    source = tmp_path / "strip.obj"
    source.write_text("\n".join(rows + ["g left"] + faces[:2] + ["g right"] + faces[2:]) + "\n")
    mesh = read_obj(source)
    cleaned = facet.cleanup(mesh, 0.05, relative=False)
    assert cleaned.mesh.n_faces == 4  # the two slivers between x 1 and 1.004 collapsed
    write_obj(cleaned.mesh, tmp_path / "out.obj")
    kept = [line.split()[0] if line.startswith("f ") else line
            for line in (tmp_path / "out.obj").read_text().splitlines()
            if not line.startswith(("v ", "#"))]
    assert kept == ["g left", "f", "g right", "f", "f", "f"]
