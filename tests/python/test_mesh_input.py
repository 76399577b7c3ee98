# SPDX-License-Identifier: LGPL-2.1-or-later
"""Mesh files as designers bring them (Rhino, Blender, Grasshopper exports): what the
readers, ``planarize`` and ``check`` make of them."""

import json

import numpy as np
import pytest

import facet
from facet.io import read_mesh

# two non-planar quads side by side, sharing the edge x = 1
_POINTS = [(0, 0, 0), (1, 0, 0), (2, 0, 0.1), (0, 1, 0.1), (1, 1, 0), (2, 1, 0)]


def _obj(points, faces):
    return "".join(f"v {x} {y} {z}\n" for x, y, z in points) + "".join(
        "f " + " ".join(str(i + 1) for i in face) + "\n" for face in faces)


def _welded():
    return _obj(_POINTS, [[0, 1, 4, 3], [1, 2, 5, 4]])


def _unwelded():
    """The same two quads, each with its own vertices (an unwelded export): the shared
    edge's two points are written twice."""
    points = _POINTS + [_POINTS[1], _POINTS[4]]
    return _obj(points, [[0, 1, 4, 3], [6, 2, 5, 7]])


def test_vertices_at_one_point_are_found(write_file):
    from facet.mesh import coincident_vertices

    assert coincident_vertices(read_mesh(write_file("welded.obj", _welded()))) == (0, None)
    assert coincident_vertices(read_mesh(write_file("apart.obj", _unwelded()))) == (2, (1, 6))


def test_unwelded_seam_is_warned_by_planarize(write_file):
    welded = facet.planarize(read_mesh(write_file("welded.obj", _welded())))
    assert not any("one point" in text for text in welded.warnings)
    mesh = read_mesh(write_file("apart.obj", _unwelded()))
    result = facet.planarize(mesh)
    warning = [text for text in result.warnings if "one point" in text]
    assert warning and "2 pairs (vertices 1 and 6 at (1, 0, 0))" in warning[0]
    assert "weld" in warning[0]
    # what the warning is about: the seam opened
    gap = np.linalg.norm(result.mesh.vertices[1] - result.mesh.vertices[6])
    assert gap > 1e-3


def test_unwelded_seam_is_warned_by_panels(write_file):
    """Panels on an unwelded seam are not joined: their edges there were cut square, with
    no bevel and no clash check, and only "2 separate parts" was said. Now the warning
    says why and what to do; a welded mesh gives none."""
    from facet.panels import panels

    points = [(x, y, 0.3 * abs(x - 1)) for x, y, _ in _POINTS]  # folded along x = 1
    welded = panels(facet.PolyMesh.from_faces(np.array(points, float),
                                              [[0, 1, 4, 3], [1, 2, 5, 4]]), 0.05,
                    edge="bisector")
    assert not any("one point" in text for text in welded.warnings)
    assert abs(welded.panels[0].bevel_deg[1]) > 1  # the joint is mitred
    apart = panels(facet.PolyMesh.from_faces(np.array(points + [points[1], points[4]], float),
                                             [[0, 1, 4, 3], [6, 2, 5, 7]]), 0.05,
                   edge="bisector")
    assert apart.panels[0].bevel_deg[1] == 0  # what the warning is about
    warning = [text for text in apart.warnings if "one point" in text]
    assert warning == [
        "vertices at one point but not one vertex: 2 pairs (vertices 1 and 6 at (1, 0, 0)); "
        "the panels there are not joined: their edges there are cut square, with no bevel, "
        "and not checked for clashes: weld them where the panels should meet: facet weld, "
        "or in FreeCAD Collapse short edges, which welds first"]


def test_weld_joins_the_seam_the_warnings_name(write_file, tmp_path, facet_command):
    """The warnings say "weld them": facet.mesh.weld and ``facet weld`` do, joining each
    group of coincident vertices into its first, dropping a corner that then repeats the one
    before it, keeping the faces' order and an isolated vertex; the welded mesh planarizes
    with its seam closed and no warning."""
    from facet.mesh import coincident_vertices, weld

    path = write_file("apart.obj", _unwelded() + "v 9 9 9\ng sides\nf 1 2 8 8 5 4\n")
    mesh = read_mesh(path)
    welded, merged = weld(mesh)
    assert merged == 2 and welded.n_vertices == mesh.n_vertices - 2
    assert welded.faces() == [[0, 1, 4, 3], [1, 2, 5, 4], [0, 1, 4, 3]]
    assert welded.vertices[6].tolist() == [9, 9, 9]  # isolated, kept
    assert welded.info["obj_sections"] == mesh.info["obj_sections"]
    assert coincident_vertices(welded) == (0, None)
    result = facet.planarize(read_mesh(write_file("two.obj", _unwelded())))
    assert any("one point" in text for text in result.warnings)
    result = facet.planarize(weld(read_mesh(write_file("two.obj", _unwelded())))[0])
    assert not any("one point" in text for text in result.warnings)

    run = facet_command("weld", write_file("two.obj", _unwelded()), "-o", tmp_path / "w.obj")
    assert run.returncode == 0, run.stderr
    assert "2 vertices joined to another: 8 -> 6 vertices, 2 faces" in run.stdout
    assert read_mesh(tmp_path / "w.obj").faces() == [[0, 1, 4, 3], [1, 2, 5, 4]]
    # a chain of points each within the tolerance of the next, longer than twice it, is
    # refused rather than made one vertex (its ends would move by more than asked)
    chain = [(0.009 * k, 0.0, 0.0) for k in range(4)]  # 0.009 apart, 0.027 long
    far = [(0.3 * k, 1.0, 0.0) for k in range(4)] + [(0.3 * k + 0.1, 1.0, 0.0)
                                                     for k in range(4)]
    triangles = [[k, 4 + k, 8 + k] for k in range(4)]  # (the mesh is 1 wide: tol 0.01)
    with pytest.raises(facet.MeshError, match=r"form a chain 0.027 long, from vertex 0 to "
                       r"vertex 3 at \(0.027, 0, 0\)"):
        weld(facet.PolyMesh.from_faces(np.array(chain + far), triangles), rel_tol=0.01)
    # a face that welding leaves with two corners apart is named
    with pytest.raises(facet.MeshError, match="face 0 has fewer than 3 corners apart"):
        weld(facet.PolyMesh.from_faces(np.array(_POINTS[:3] + [_POINTS[1]], float),
                                       [[0, 1, 2, 3]]), rel_tol=1.0)
    # so is one left with a vertex at two corners apart, which no reader takes back: it
    # was written ("f 1 2 1 3 4") and `facet check` refused the file it wrote
    pinched = write_file("pinched.obj", "v 0 0 0\nv 1 0 0\nv 0 0 0\nv 0 1 0\nv -1 1 0\n"
                         "f 1 2 3 4 5\n")
    with pytest.raises(facet.MeshError, match="face 0 has one vertex at two corners apart"):
        weld(read_mesh(pinched))
    run = facet_command("weld", pinched, "-o", tmp_path / "p.obj")
    assert run.returncode == 2 and "face 0 has one vertex at two corners apart" in run.stderr
    assert not (tmp_path / "p.obj").exists()


def test_weld_carries_the_compas_supports_and_keys(write_file):
    """A compas session welded: its support vertices and vertex keys follow the vertices
    kept, as facet.cleanup's do. The supports kept their input indices, so one named a
    vertex past the welded mesh's last (6 of 6) and a results file written back by key
    would have lost it; the keys of the vertices joined were dropped unsaid."""
    from facet.mesh import weld

    def vertex(x, y, support=False):
        return {"x": x, "y": y, "z": 0, **({"is_support": True} if support else {})}

    session = {"vertex": {"a": vertex(0, 0), "b": vertex(1, 0, True), "c": vertex(1, 1),
                          "d": vertex(0, 1), "e": vertex(1, 0), "f": vertex(2, 0),
                          "g": vertex(2, 1, True), "h": vertex(1, 1)},
               "face": {"0": ["a", "b", "c", "d"], "1": ["e", "f", "g", "h"]}}
    mesh = read_mesh(write_file("apart.json", json.dumps(session)))
    welded, merged = weld(mesh)
    assert merged == 2 and welded.faces() == [[0, 1, 2, 3], [1, 4, 5, 2]]
    info = welded.info
    assert info["vertex_keys"] == ["a", "b", "c", "d", "f", "g"]
    assert info["merged_vertex_keys"] == {"b": ["e"], "c": ["h"]}
    assert info["face_keys"] == mesh.info["face_keys"]
    assert [welded.vertices[v].tolist() for v in info["support_vertices"]] == [
        [1, 0, 0], [2, 1, 0]]


def test_unwelded_seam_is_warned_by_check_and_planarize_commands(write_file, tmp_path,
                                                                facet_command):
    run_facet = facet_command
    path = write_file("apart.obj", _unwelded())
    check = run_facet("check", path, "--report", tmp_path / "check.json")
    assert check.returncode == 0, check.stderr
    assert "warning       vertices at one point but not one vertex: 2 pairs (first: 1 and 6)" \
        in check.stdout
    report = json.loads((tmp_path / "check.json").read_text())
    assert report["coincident_vertex_pairs"] == 2
    assert report["first_coincident_vertices"] == [1, 6]
    run = run_facet("planarize", path, "-o", tmp_path / "out.obj")
    assert run.returncode == 0, run.stderr
    assert "vertices at one point but not one vertex" in run.stdout
    assert "facet weld, or in FreeCAD Collapse short edges" in run.stdout
    assert "facet weld, or in FreeCAD Collapse short edges" in check.stdout
    welded = run_facet("check", write_file("welded.obj", _welded()))
    assert "one point" not in welded.stdout


_QUAD_OBJ = "# Fassade Süd\nv 0 0 0\nv 1 0 0\nv 1 1 0.1\nv 0 1 0\nf 1 2 3 4\n"
_QUAD_OFF = "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0.1\n0 1 0\n4 0 1 2 3\n"
_QUAD_JSON = ('{"vertex": {"0": {"x": 0, "y": 0, "z": 0}, "1": {"x": 1, "y": 0, "z": 0}, '
              '"2": {"x": 1, "y": 1, "z": 0.1}, "3": {"x": 0, "y": 1, "z": 0}}, '
              '"face": {"0": [0, 1, 2, 3]}}')


def test_utf16_files_with_a_byte_order_mark_are_read(tmp_path):
    """Windows tools write "Unicode" text as UTF-16 with a byte order mark (PowerShell's
    '>', Notepad, .NET scripts): it was read as UTF-8, found no 'v' line and said "not an
    OBJ file" (OFF: "starts with '\\ufffd\\ufffdO\\x00F...'", JSON: "not valid JSON")."""
    for name, text in (("in.obj", _QUAD_OBJ), ("in.off", _QUAD_OFF), ("in.json", _QUAD_JSON)):
        for encoding in ("utf-16", "utf-16-be", "utf-8-sig", "utf-8"):
            path = tmp_path / f"{encoding}-{name}"
            # (Windows line ends with the Windows encoding)
            data = (text.replace("\n", "\r\n") if encoding == "utf-16" else text).encode(encoding)
            if encoding == "utf-16-be":
                data = b"\xfe\xff" + data
            path.write_bytes(data)
            mesh = read_mesh(path)
            assert (mesh.n_vertices, mesh.n_faces) == (4, 1), path
            assert mesh.vertices[2].tolist() == [1.0, 1.0, 0.1]


def test_a_triangle_written_as_a_quad_is_read_as_a_triangle(write_file, tmp_path,
                                                            facet_command):
    """Rhino writes a triangle of a quad mesh as a quad with its last vertex twice
    ("f 2 3 5 5"); a vertex twice in a row round the end ("f 5 2 3 5") is the same. Both
    were refused ("face 1 repeats vertex 4"): now each is read with the vertex once, the
    file's other faces as written, and the reading is said, with the first such face's
    line, by the readers, the command line (every command, and the report) and the
    FreeCAD importer (test_fc_importer)."""
    from facet.io import read_warnings

    faces = [[0, 1, 4, 3], [1, 2, 5, 5], [4, 1, 5, 4]]
    path = write_file("tri_as_quad.obj", _obj(_POINTS, faces))
    mesh = read_mesh(path)
    assert mesh.faces() == [[0, 1, 4, 3], [1, 2, 5], [4, 1, 5]]
    assert read_warnings(mesh) == [
        "2 faces gave a vertex at two corners in a row (first: face 1, line 8): read with it "
        "once (a quad written so is a triangle)"]
    assert read_warnings(read_mesh(write_file("welded.obj", _welded()))) == []
    off = write_file("tri_as_quad.off", "OFF\n6 1 0\n" + "".join(
        f"{x} {y} {z}\n" for x, y, z in _POINTS) + "4 1 2 5 5\n")
    assert read_mesh(off).faces() == [[1, 2, 5]]
    # a vertex twice in a row that leaves two corners is the degenerate face it was
    with pytest.raises(facet.MeshError, match=r"line 9: face 0 .*2 distinct"):
        read_mesh(write_file("two.off", "OFF\n6 1 0\n" + "".join(
            f"{x} {y} {z}\n" for x, y, z in _POINTS) + "4 1 1 2 2\n"))

    run = facet_command("check", path, "--report", tmp_path / "c.json")
    assert run.returncode == 0, run.stderr
    assert (f"facet: warning: {path}: 2 faces gave a vertex at two corners in a row "
            "(first: face 1, line 8)") in run.stderr
    report = json.loads((tmp_path / "c.json").read_text())
    assert (report["faces"], report["face_degrees"]) == (3, {"3": 2, "4": 1})
    assert report["source_repeated_corners_merged"] == 2
    assert report["source_repeated_corners_first"] == "face 1, line 8"
    # a plan mesh for `facet lift` says so too (it lifted without a word)
    from facet.plan import read_plan

    plan = read_plan(path)
    assert plan.warnings[:1] == read_warnings(mesh)


def test_a_vertex_repeated_apart_is_quoted_as_the_obj_line_writes_it(write_file):
    """A face that gives one vertex at two corners apart ("f 2 5 3 5") is not a panel: the
    error names the line and the vertex as that line writes it (it said only "repeats
    vertex 4", counted from 0, on a line that shows 5)."""
    path = write_file("bowtie.obj", _obj(_POINTS, [[0, 1, 4, 3], [1, 4, 2, 4]]))
    with pytest.raises(facet.MeshError) as caught:
        read_mesh(path)
    assert str(caught.value).endswith(
        "bowtie.obj: line 8: face 1 repeats vertex 4 (written 5 in the file)")
    # OFF counts from 0 as the message does: nothing to add
    off = write_file("bowtie.off", "OFF\n6 1 0\n" + "".join(
        f"{x} {y} {z}\n" for x, y, z in _POINTS) + "4 1 4 2 4\n")
    with pytest.raises(facet.MeshError, match=r"line 9: face 0 repeats vertex 4$"):
        read_mesh(off)


def test_an_edge_of_no_length_is_not_an_unwelded_seam(write_file):
    """Two vertices at one point that an edge joins are joined: no seam warning (the
    quality report counts the faces as degenerate)."""
    from facet.mesh import coincident_vertices

    points = [(0, 0, 0), (1, 0, 0), (1, 0, 0), (1, 1, 0.1), (0, 1, 0)]
    mesh = read_mesh(write_file("short.obj", _obj(points, [[0, 1, 2, 3, 4]])))
    assert coincident_vertices(mesh) == (0, None)


def test_a_face_twice_is_named_as_a_copy(write_file, tmp_path, facet_command):
    """A face written twice (a join of overlapping meshes, a double-sided export, here
    turned the other way) was said only as "4 non-manifold edges": now as the copy it is,
    by planarize, check and facet.planarize."""
    from facet.mesh import duplicate_faces

    faces = [[0, 1, 4, 3], [1, 2, 5, 4], [4, 5, 2, 1], [0, 1, 4, 3]]
    mesh = read_mesh(write_file("twice.obj", _obj(_POINTS, faces)))
    assert duplicate_faces(mesh) == (2, (1, 2))
    assert duplicate_faces(read_mesh(write_file("once.obj", _welded()))) == (0, None)
    warning = [text for text in facet.planarize(mesh).warnings if "same vertices" in text]
    assert warning == ["2 faces with the same vertices as another (first: face 2 repeats "
                       "face 1): two panels at one place; remove the copies"]
    check = facet_command("check", tmp_path / "twice.obj", "--report", tmp_path / "c.json")
    assert "2 faces with the same vertices as another (first: face 2 repeats face 1)" \
        in check.stdout
    report = json.loads((tmp_path / "c.json").read_text())
    assert (report["duplicate_faces"], report["first_duplicate_faces"]) == (2, [1, 2])


def test_faces_wound_opposite_ways_are_named_by_check(write_file, tmp_path, facet_command):
    """Two faces wound opposite ways across their edge (normals to opposite sides, shaded
    dark in FreeCAD) passed `facet check` without a word: only `facet panels` said it
    reversed them. Now check names the edges and the first pair of faces."""
    from facet.mesh import opposite_windings

    assert opposite_windings(read_mesh(write_file("once.obj", _welded()))) == (0, None)
    turned = read_mesh(write_file("turned.obj", _obj(_POINTS, [[0, 1, 4, 3], [4, 5, 2, 1]])))
    assert opposite_windings(turned) == (1, (0, 1))
    check = facet_command("check", tmp_path / "turned.obj", "--report", tmp_path / "t.json")
    assert ("faces wound opposite ways across 1 edge (first: faces 0 and 1): their normals "
            "point to opposite sides") in check.stdout
    report = json.loads((tmp_path / "t.json").read_text())
    assert (report["opposite_windings"], report["first_opposite_windings"]) == (1, [0, 1])
    once = facet_command("check", tmp_path / "once.obj")
    assert "wound opposite" not in once.stdout
