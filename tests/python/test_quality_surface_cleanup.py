# SPDX-License-Identifier: LGPL-2.1-or-later
"""Surface closest points, the quality report and cleanup, from Python and the command line."""

import json
import os

import numpy as np
import pytest

import facet
from facet import cli
from facet.errors import InputError

DATA = os.path.join(os.path.dirname(os.path.dirname(__file__)), "data")


def _grid(nu, nv, squeeze=None):
    xs = np.arange(nu + 1, dtype=float)
    if squeeze is not None:
        xs[squeeze] = xs[squeeze - 1] + 0.01
    vertices = [(x, y, 0.1 * np.sin(x) * np.cos(y)) for y in range(nv + 1) for x in xs]
    faces = []
    for j in range(nv):
        for i in range(nu):
            v = j * (nu + 1) + i
            faces.append([v, v + 1, v + nu + 2, v + nu + 1])
    return facet.PolyMesh.from_faces(vertices, faces)


def _brute_distance(points, vertices, triangles):
    """Distance by dense sampling of each triangle (an upper bound, close for fine sampling)."""
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    s = np.linspace(0, 1, 41)
    u, v = np.meshgrid(s, s)
    keep = u + v <= 1
    u, v = u[keep], v[keep]
    samples = (a[:, None] + u[None, :, None] * (b - a)[:, None] + v[None, :, None] * (c - a)[:, None])
    samples = samples.reshape(-1, 3)
    return np.array([np.min(np.linalg.norm(samples - p, axis=1)) for p in points])


def test_surface_against_sampling():
    rng = np.random.default_rng(3)
    vertices = rng.random((30, 3)) * 10 + 1e6  # georeferenced
    triangles = rng.integers(0, 30, size=(20, 3)).astype(np.int32)
    surface = facet.Surface(vertices, triangles)
    points = rng.random((50, 3)) * 12 - 1 + 1e6
    closest, distance, triangle, normal = surface.closest(points)
    brute = _brute_distance(points, vertices, triangles)
    assert np.all(distance <= brute + 1e-9)
    assert np.all(distance >= brute - 0.3)  # sampling step bound
    assert np.allclose(np.linalg.norm(closest - points, axis=1), distance, atol=1e-8)
    assert np.all(np.isfinite(normal))
    assert surface.triangle_faces is None


def test_surface_of_mesh_holds_its_vertices():
    mesh = facet.read_mesh(os.path.join(DATA, "hypar.obj"))
    surface = facet.Surface(mesh)
    _, distance, triangle, normal = surface.closest(mesh.vertices, threads=1)
    assert distance.max() < 1e-12
    assert surface.n_triangles == 2 * mesh.n_faces
    assert set(surface.triangle_faces[triangle]) <= set(range(mesh.n_faces))
    assert np.allclose(np.linalg.norm(normal, axis=1), 1.0)


def test_surface_bad_input():
    with pytest.raises(InputError, match="triangle 0"):
        facet.Surface(np.zeros((3, 3)), [[0, 1, 5]])
    surface = facet.Surface(np.eye(3), [[0, 1, 2]])
    with pytest.raises(InputError, match="point 1 has a non-finite"):
        surface.closest([[0, 0, 0], [np.nan, 0, 0]])
    with pytest.raises(InputError, match="triangles are needed"):
        facet.Surface(np.eye(3))


def test_quality_of_planarize():
    mesh = facet.read_mesh(os.path.join(DATA, "hypar.obj"))
    result = facet.planarize(mesh)
    report = facet.quality(result, input=mesh)
    figures = report.as_dict()
    assert figures["planarity_max_rel"] <= 1e-6
    assert figures["displacement_max"] == pytest.approx(result.displacement_max)
    assert 0 < figures["distance_rms"] <= figures["distance_max"] <= figures["displacement_max"]
    assert 0 < figures["min_angle_deg"] < figures["input_min_angle_deg"] <= 90
    assert figures["ratio_change_max"] > 0
    # the nearest planar mesh of this skew hypar turns some quads into triangles: an
    # edge shrinks to nothing while every angle stays wide; those faces are degenerate
    v, fs, fv = result.mesh.vertices, result.mesh.face_start, result.mesh.face_vertices
    short = [f for f in range(mesh.n_faces)
             if min(np.linalg.norm(v[fv[k]] - v[fv[fs[f] + (k - fs[f] + 1) % (fs[f + 1] - fs[f])]])
                    for k in range(fs[f], fs[f + 1])) < 0.01 * report.planarity.mean_edge[f]]
    assert len(short) > 0 and figures["min_angle_deg"] > 5.0
    assert report.degenerate.tolist() == short
    assert figures["degenerate_faces"] == len(short) and figures["degenerate_short_edge"] == 0.01
    json.dumps(figures, allow_nan=False)
    # the unchanged input measured against itself
    same = facet.quality(mesh, input=mesh).as_dict()
    assert same["displacement_max"] == 0 and same["distance_max"] < 1e-12
    assert same["ratio_change_max"] == 0


def test_quality_a_vanishing_edge_makes_a_face_degenerate():
    # a square whose edge 1-2 shrinks to 0.5% of the mean edge: its angles stay wide
    for shrink, degenerate in ((0.005, [0]), (0.02, [])):
        xyz = np.array([[0.0, 0, 0], [1.0, 0, 0], [1.0, shrink, 0], [0.0, 1, 0]])
        report = facet.quality(facet.PolyMesh.from_faces(xyz, [[0, 1, 2, 3]]))
        assert report.degenerate.tolist() == degenerate
        assert report.as_dict()["min_angle_deg"] > 5.0


def test_quality_a_folded_panel_is_degenerate():
    # A planar bowtie (edges 0-1 and 2-3 cross) beside a dart (non-convex,
    # not folded): the bowtie's signed corners look fine (its narrow corner
    # turns the other way and counts as reflex), but it has no interior.
    mesh = facet.PolyMesh.from_faces(
        [(0, 0, 0), (2, 2, 0), (2, 0, 0), (0, 1, 0), (10, 0, 0), (14, 0, 0), (11, 1, 0), (10, 4, 0)],
        [[0, 1, 2, 3], [4, 5, 6, 7]],
    )
    report = facet.quality(mesh)
    assert report.min_angle[0] == 0.0
    assert report.min_angle[1] == pytest.approx(np.degrees(np.arctan2(1.0, 3.0)))
    assert report.degenerate.tolist() == [0]


def test_quality_degenerate_and_errors():
    mesh = facet.PolyMesh.from_faces(
        [(0, 0, 0), (1, 0, 0), (0, 1, 0), (2, 0, 0), (3, 0, 0), (2.5, 0.01, 0)],
        [[0, 1, 2], [3, 4, 5]],
    )
    report = facet.quality(mesh)
    assert report.degenerate.tolist() == [1]
    assert report.min_angle[0] == pytest.approx(45.0)
    assert report.as_dict()["displacement_max"] is None
    other = _grid(2, 2)
    with pytest.raises(InputError, match="another topology"):
        facet.quality(mesh, input=other)
    with pytest.raises(InputError, match="min_angle"):
        facet.quality(mesh, min_angle=200)


def test_cleanup_squeezed_column():
    mesh = _grid(6, 4, squeeze=3)
    result = facet.cleanup(mesh, 0.1, relative=False)
    assert len(result.collapsed_edges) == 5
    assert result.removed_faces.tolist() == [2, 8, 14, 20]
    assert result.mesh.n_faces == 20 and result.mesh.n_vertices == 30
    assert result.skipped == 0
    assert result.face_map.tolist() == [f for f in range(24) if f % 6 != 2]
    report = result.mesh.validate()
    assert report["n_non_manifold_edges"] == 0
    assert result.vertex_map[2] == result.vertex_map[3]
    # the source is untouched
    assert mesh.n_faces == 24
    planar = facet.planarize(result.mesh)
    assert planar.converged


def test_cleanup_bad_input():
    mesh = _grid(2, 2)
    for bad in (0, -1, float("nan"), "x"):
        with pytest.raises(InputError, match="min_edge"):
            facet.cleanup(mesh, bad)
    with pytest.raises(InputError, match="every face would collapse"):
        facet.cleanup(mesh, 5.0)


def test_cli_cleanup(tmp_path, capsys):
    source = tmp_path / "squeezed.obj"
    facet.write_mesh(_grid(6, 4, squeeze=3), source)
    out, report_path = tmp_path / "out.obj", tmp_path / "r.json"
    status = cli.main(["cleanup", str(source), "-o", str(out), "--min-edge", "0.1",
                       "--report", str(report_path)])
    assert status == 0
    text = capsys.readouterr().out
    assert "5 edges shorter than 0.1 collapsed" in text
    report = json.loads(report_path.read_text())
    assert report["cleanup"]["collapsed_edges"] == 5
    assert report["cleanup"]["faces"] == 20
    assert report["quality"]["planarity_max_rel"] <= 1e-6
    assert report["quality"]["distance_max"] is not None
    assert facet.read_mesh(out).n_faces == 20
    status = cli.main(["cleanup", str(source), "-o", str(out), "--min-edge", "50"])
    assert status == 2
    assert "min_edge" in capsys.readouterr().err


@pytest.mark.parametrize("when", ["in a re-solve", "after the last check", "short", "before",
                                  "unwritable"])
def test_cli_cleanup_stopped_by_ctrl_c(tmp_path, capsys, monkeypatch, when):
    """Ctrl+C stops the planarization after the collapse as it stops ``facet planarize``:
    a result reached at the tolerance before the stop (in a re-solve: Cancelled.result) or
    just before it (after the solve's last progress check) is written; a result short of
    the tolerance, or none, is not. A file that cannot be written then is that error, not
    an interrupt."""
    import dataclasses

    source = tmp_path / "squeezed.obj"
    facet.write_mesh(_grid(6, 4, squeeze=3), source)
    solve = facet.planarize

    def stopped(mesh, progress=None, **options):
        result = solve(mesh, **options)
        cli._CTRL_C.seen = True  # Ctrl+C, as its handler remembers it
        assert progress(1, 2, 1e-3) is True  # the progress check stops the solve
        if when == "after the last check":
            return result
        if when == "short":
            return dataclasses.replace(result, converged=False, stop_reason="max_iter")
        error = facet.Cancelled("cancelled")
        error.result = dataclasses.replace(result, stopped=True) if when != "before" else None
        raise error

    monkeypatch.setattr(facet, "planarize", stopped)
    monkeypatch.setattr(cli._CTRL_C, "seen", False)  # (and False again after the test)
    out = tmp_path / "out.obj"
    if when == "unwritable":
        out.mkdir()  # (a missing folder is refused before the solve)
    status = cli.main(["cleanup", str(source), "-o", str(out), "--min-edge", "0.1"])
    text, err = capsys.readouterr()
    if when == "unwritable":
        assert status == 2 and err == f"facet: error: {out}: Is a directory\n"
        assert sorted(p.name for p in tmp_path.iterdir()) == ["out.obj", "squeezed.obj"]
        return
    assert status == 130
    if when in ("in a re-solve", "after the last check"):
        assert err == f"facet: interrupted: {out} holds the result the solve had reached\n"
        assert facet.read_mesh(out).n_faces == 20
        assert ("  stopped" in text) == (when == "in a re-solve")
    else:
        assert err == "facet: error: interrupted\n" and not out.exists()


def test_cli_reports_have_quality(tmp_path, capsys):
    out, report_path = tmp_path / "p.obj", tmp_path / "p.json"
    assert cli.main(["planarize", os.path.join(DATA, "hypar.obj"), "-o", str(out),
                     "--report", str(report_path)]) == 0
    text = capsys.readouterr().out
    assert "smallest angle" in text and "distance from the input surface" in text
    quality = json.loads(report_path.read_text())["quality"]
    assert quality["distance_max"] > 0 and quality["min_angle_deg"] > 5
    assert cli.main(["check", os.path.join(DATA, "hypar.obj"), "--report",
                     str(report_path)]) == 0
    assert json.loads(report_path.read_text())["quality"]["degenerate_faces"] == 0


def _vector_areas(mesh):
    areas = []
    for face in mesh.faces():
        p = mesh.vertices[face]
        areas.append(np.cross(p - p[0], np.roll(p, -1, axis=0) - p[0]).sum(axis=0))
    return np.array(areas)


@pytest.mark.parametrize("seed", range(12))
def test_cleanup_keeps_jittered_meshes_valid_and_unturned(seed):
    """Heavily jittered mixed quad/triangle grids: every collapse keeps the mesh valid,
    manifold, without isolated vertices, and no face turns over against its input face."""
    rng = np.random.default_rng(seed)
    n = 10
    xy = np.array([(i, j) for j in range(n + 1) for i in range(n + 1)], float)
    xy += rng.uniform(-0.45, 0.45, xy.shape)
    vertices = np.c_[xy, rng.uniform(-0.3, 0.3, len(xy))]
    faces = []
    for j in range(n):
        for i in range(n):
            v = j * (n + 1) + i
            if rng.random() < 0.5:
                faces.append([v, v + 1, v + n + 2, v + n + 1])
            else:
                faces += [[v, v + 1, v + n + 2], [v, v + n + 2, v + n + 1]]
    mesh = facet.PolyMesh.from_faces(vertices, faces)
    before = _vector_areas(mesh)
    for threshold in (0.6, 0.9):
        result = facet.cleanup(mesh, threshold)
        assert len(result.collapsed_edges) > 0
        report = result.mesh.validate()
        assert report["n_non_manifold_edges"] == 0
        assert report["n_isolated_vertices"] == 0
        after = _vector_areas(result.mesh)
        assert np.all(np.einsum("ij,ij->i", before[result.face_map], after) > 0)
        # every input vertex maps to a vertex of the new mesh, merged ones together
        assert result.vertex_map.min() >= 0
        for a, b in result.collapsed_edges:
            assert result.vertex_map[a] == result.vertex_map[b]


def test_quality_per_face():
    mesh = facet.read_mesh(os.path.join(DATA, "hypar.obj"))
    result = facet.planarize(mesh)
    report = facet.quality(result, input=mesh)
    displacement = report.per_face("displacement")
    assert displacement.shape == (mesh.n_faces,)
    for f, face in enumerate(mesh.faces()):
        assert displacement[f] == max(result.displacement[v] for v in face)
    assert report.per_face("distance").max() == pytest.approx(report.distance.max())
    assert report.per_face("min_angle") is report.min_angle
    assert facet.quality(mesh).per_face("distance") is None
    with pytest.raises(InputError, match="not one of"):
        report.per_face("colour")


def test_closest_progress_and_cancel():
    surface = facet.Surface(np.eye(3), [[0, 1, 2]])
    points = np.zeros((70000, 3))
    calls = []
    _, distance, _, _ = surface.closest(points, progress=lambda done, total: calls.append(
        (done, total)))
    assert calls == [(65536, 70000), (70000, 70000)]
    assert np.allclose(distance, 1 / np.sqrt(3))
    with pytest.raises(facet.Cancelled, match="65536 of 70000"):
        surface.closest(points, progress=lambda done, total: True)
    mesh = facet.read_mesh(os.path.join(DATA, "hypar.obj"))
    with pytest.raises(facet.Cancelled):
        facet.quality(mesh, input=mesh, progress=lambda done, total: True)


def test_cleanup_triangles():
    """A triangulated grid with one short diagonal: its two triangles go, the rest stay."""
    n = 4
    vertices = [(i, j, 0.0) for j in range(n + 1) for i in range(n + 1)]
    faces = []
    for j in range(n):
        for i in range(n):
            v = j * (n + 1) + i
            faces += [[v, v + 1, v + n + 2], [v, v + n + 2, v + n + 1]]
    vertices = np.array(vertices)
    vertices[12] = vertices[6] + (0.02, 0.02, 0.0)  # (2,2) pulled onto (1,1): short diagonal 6-12
    mesh = facet.PolyMesh.from_faces(vertices, faces)
    result = facet.cleanup(mesh, 0.05, relative=False)
    assert result.collapsed_edges.tolist() == [[6, 12]]
    assert result.removed_faces.tolist() == [10, 11]  # cell (1,1)'s two triangles
    assert result.mesh.n_faces == 30 and result.mesh.n_vertices == 24
    assert set(np.diff(result.mesh.face_start)) == {3}
    assert result.mesh.validate()["n_non_manifold_edges"] == 0


def test_a_threshold_that_collapses_everything_names_the_file(data_dir):
    mesh = facet.read_mesh(data_dir / "hypar.obj")
    with pytest.raises(InputError) as caught:
        facet.cleanup(mesh, 100.0, relative=False)
    message = str(caught.value)
    assert message.startswith(f"{data_dir / 'hypar.obj'}: min_edge 100 ")
    assert "every face would collapse" in message and "min_edge: min_edge" not in message


def test_cleanup_carries_the_compas_keys_to_the_new_topology(data_dir):
    # the cleaned mesh kept the input's 225 vertex keys and 224 face keys, and support
    # vertices by index past its last vertex: results written back by key went to the
    # wrong compas vertices
    mesh = facet.read_mesh(data_dir / "crossvault_form.json")
    result = facet.cleanup(mesh, 0.9, relative=True)
    new, info = result.mesh, result.mesh.info
    assert new.n_vertices < mesh.n_vertices and new.n_faces < mesh.n_faces
    assert len(info["vertex_keys"]) == new.n_vertices and len(info["face_keys"]) == new.n_faces
    old = mesh.info
    assert info["face_keys"] == [old["face_keys"][f] for f in result.face_map]
    for v, key in enumerate(info["vertex_keys"]):
        first = int(np.flatnonzero(result.vertex_map == v)[0])
        assert key == old["vertex_keys"][first]
    merged = sum(len(k) for k in info.get("merged_vertex_keys", {}).values())
    assert merged == int(np.count_nonzero(result.vertex_map >= 0)) - new.n_vertices
    assert all(0 <= v < new.n_vertices for v in info["support_vertices"])
    assert info["support_vertices"] == sorted({int(result.vertex_map[v])
                                               for v in old["support_vertices"]})


def test_cleanup_of_a_fin_says_what_collapses():
    # three triangles on one 0.1-long edge (a non-manifold fin): "min_edge 0.2 is longer
    # than the mesh's edges", where only that edge is short
    fin = facet.PolyMesh.from_faces(
        np.array([[0, 0, 0], [0.1, 0, 0], [0.05, 1, 0], [0.05, -1, 0], [0.05, 0, 1.0]]),
        [[0, 1, 2], [1, 0, 3], [0, 1, 4]])
    with pytest.raises(facet.FacetError, match=r"every face would collapse: collapsing 1 "
                                               r"edge shorter than min_edge 0.2 \(0.2 model "
                                               r"units\) leaves no face of three corners"):
        facet.cleanup(fin, 0.2, relative=False)
