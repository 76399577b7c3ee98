# SPDX-License-Identifier: LGPL-2.1-or-later
"""Writing OBJ and OFF: exact round trips, no NaN, no half-written files."""

import numpy as np
import pytest

from facet import MeshError, PolyMesh, read_mesh, write_mesh
from facet.io import read_obj, read_off, write_obj, write_off

AWKWARD = [
    [1.0 / 3.0, -0.0, 1e22],
    [5e-324, 2.0**0.5, -1.7976931348623157e308],
    [0.1 + 0.2, 123456789.12345679, -1e-300],
    [np.nextafter(1.0, 2.0), 7.0, np.pi],
]


def awkward_mesh():
    return PolyMesh.from_faces(AWKWARD, [[0, 1, 2, 3], [0, 2, 1]])


@pytest.mark.parametrize("suffix", [".obj", ".off"])
def test_round_trip_is_bit_exact(tmp_path, suffix):
    mesh = awkward_mesh()
    path = tmp_path / f"panels{suffix}"
    write_mesh(mesh, path)
    back = read_mesh(path, validate=False)
    assert back.vertices.tobytes() == mesh.vertices.tobytes()
    assert back.faces() == mesh.faces()


@pytest.mark.parametrize("suffix", [".obj", ".off"])
def test_real_mesh_round_trip(data_dir, tmp_path, suffix):
    mesh = read_mesh(data_dir / "conical1.obj")
    path = tmp_path / f"conical{suffix}"
    write_mesh(mesh, path)
    back = read_mesh(path)
    assert np.array_equal(back.vertices, mesh.vertices)
    assert back.vertices.tobytes() == mesh.vertices.tobytes()
    assert back.faces() == mesh.faces()


def test_obj_text(tmp_path):
    mesh = PolyMesh.from_faces([[0, 0, 0], [1, 0, 0], [1, 1, 0.5]], [[0, 1, 2]])
    path = tmp_path / "one.obj"
    write_obj(mesh, path)
    lines = path.read_text().splitlines()
    assert lines[0].startswith("#")
    assert lines[1:] == ["v 0.0 0.0 0.0", "v 1.0 0.0 0.0", "v 1.0 1.0 0.5", "f 1 2 3"]


def test_off_text(tmp_path):
    mesh = PolyMesh.from_faces([[0, 0, 0], [1, 0, 0], [1, 1, 0.5], [0, 1, 0]],
                               [[0, 1, 2, 3], [0, 2, 1]])
    path = tmp_path / "two.off"
    write_off(mesh, path)
    assert path.read_text().splitlines() == [
        "OFF", "4 2 5",
        "0.0 0.0 0.0", "1.0 0.0 0.0", "1.0 1.0 0.5", "0.0 1.0 0.0",
        "4 0 1 2 3", "3 0 2 1",
    ]


@pytest.mark.parametrize("writer, suffix", [(write_obj, ".obj"), (write_off, ".off")])
@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_coordinates_are_never_written(tmp_path, writer, suffix, bad):
    vertices = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0.0]])
    vertices[1, 2] = bad
    mesh = PolyMesh.from_faces(vertices, [[0, 1, 2]])
    path = tmp_path / f"out{suffix}"
    path.write_text("previous content\n")
    with pytest.raises(MeshError, match=r"vertex 1 has a non-finite coordinate; nothing written"):
        writer(mesh, path)
    assert path.read_text() == "previous content\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == [f"out{suffix}"]


def test_written_file_replaces_the_old_and_leaves_no_part_file(tmp_path):
    path = tmp_path / "out.obj"
    path.write_text("old\n")
    write_mesh(awkward_mesh(), path)
    assert read_obj(path, validate=False).n_faces == 2
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.obj"]


def test_write_into_missing_folder_raises_os_error(tmp_path):
    with pytest.raises(OSError):
        write_mesh(awkward_mesh(), tmp_path / "no" / "such" / "out.obj")


@pytest.mark.parametrize("name, kind", [("out.stl", ".stl files"),
                                        ("out", "files without an extension")])
def test_unknown_extension_cannot_be_written(tmp_path, name, kind):
    with pytest.raises(MeshError, match=rf"cannot write {kind} \(Facet writes \.obj, \.off\)"):
        write_mesh(awkward_mesh(), tmp_path / name)
    assert not (tmp_path / name).exists()


def test_unknown_extension_cannot_be_read(tmp_path):
    path = tmp_path / "roof.stl"
    path.write_text("solid roof\n")
    with pytest.raises(MeshError, match=r"roof\.stl: cannot read \.stl files"):
        read_mesh(path)


def test_extension_is_case_insensitive(data_dir, tmp_path):
    path = tmp_path / "TUBE.OFF"
    path.write_bytes((data_dir / "tubemesh.off").read_bytes())
    assert read_mesh(path).n_faces == 171


def test_mixed_degrees_round_trip_through_off(tmp_path, data_dir):
    mesh = read_mesh(data_dir / "crossvault_form.json")
    path = tmp_path / "vault.off"
    write_mesh(mesh, path)
    back = read_off(path)
    assert back.faces() == mesh.faces()
    assert back.vertices.tobytes() == mesh.vertices.tobytes()


def test_a_file_named_like_the_temporary_one_is_kept(tmp_path):
    # the text goes to a temporary file of a name no other file has, not to NAME.part
    mine = tmp_path / "out.obj.part"
    mine.write_text("the designer's notes\n")
    write_mesh(awkward_mesh(), tmp_path / "out.obj")
    assert mine.read_text() == "the designer's notes\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.obj", "out.obj.part"]


def test_a_missing_folder_is_named_by_the_path_asked_for(tmp_path):
    path = tmp_path / "no" / "out.obj"
    with pytest.raises(FileNotFoundError) as caught:
        write_mesh(awkward_mesh(), path)
    assert caught.value.filename == str(path)


def test_a_written_file_gets_the_usual_mode(tmp_path):
    import os
    import stat

    mask = os.umask(0o022)
    try:
        write_mesh(awkward_mesh(), tmp_path / "out.obj")
    finally:
        os.umask(mask)
    assert stat.S_IMODE((tmp_path / "out.obj").stat().st_mode) == 0o644


def test_a_folder_in_the_way_is_named_by_the_path_asked_for(tmp_path):
    path = tmp_path / "out.obj"
    path.mkdir()
    with pytest.raises(IsADirectoryError) as caught:
        write_mesh(awkward_mesh(), path)
    assert caught.value.filename == str(path)
    assert [p.name for p in tmp_path.iterdir()] == ["out.obj"]  # no temporary file left


def _small():
    return PolyMesh.from_faces([[0.1, 0.0, 0.0], [1.0, 0.0, 1e-17], [0.0, 1.0, 0.5]], [[0, 1, 2]])


def test_a_symbolic_link_is_written_through(tmp_path):
    # the link was replaced by a file of its own: the file it named, in a project folder,
    # kept the old mesh
    project = tmp_path / "project"
    project.mkdir()
    linked = project / "facade.obj"
    linked.write_text("old\n")
    link = tmp_path / "link.obj"
    link.symlink_to(linked)
    write_mesh(_small(), link)
    assert link.is_symlink() and linked.read_text().startswith(("v ", "#"))
    assert np.array_equal(read_mesh(linked).vertices, _small().vertices)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.obj", "project"]
    assert [p.name for p in project.iterdir()] == ["facade.obj"]


def test_a_name_near_the_length_limit_can_be_written(tmp_path):
    # the temporary file's name (NAME.<8 hex>.part) went past 255 bytes: "File name too long"
    path = tmp_path / ("f" * 250 + ".obj")
    write_mesh(_small(), path)
    assert np.array_equal(read_mesh(path).vertices, _small().vertices)
    assert [p.name for p in tmp_path.iterdir()] == [path.name]
