# SPDX-License-Identifier: LGPL-2.1-or-later
"""A quad whose edge vanished is built as a triangle panel (``facet.panels(min_edge=...)``):
the edge's two ends become one corner in every face, the neighbours still meet along their
edges and nodes, and the solids, the DXF and the schedule work for the 3-corner panels."""

import csv
import json
import math
import re

import numpy as np
import pytest

import facet
from facet.errors import Cancelled
from facet.mesh import next_corners
from facet.panels import DEFAULT_MIN_EDGE, PanelError, panels
from panel_meshes import folded_grid, freecad_step

STEP = 1000.0
#: the faces beside the short edge 2-7 of folded_grid, and the faces touching vertex 7 only
BESIDE, TOUCHING = (1, 2), (5, 6)


def face_edge_lengths(mesh):
    """(per-corner edge lengths, per-face mean edge): computed here, not by facet.panels."""
    fv, fs = np.asarray(mesh.face_vertices), np.asarray(mesh.face_start)
    xyz = np.asarray(mesh.vertices)
    lengths = np.linalg.norm(xyz[fv[next_corners(fs)]] - xyz[fv], axis=1)
    return lengths, np.add.reduceat(lengths, fs[:-1]) / np.diff(fs)


def faces_with_short_edge(mesh, fraction):
    lengths, mean = face_edge_lengths(mesh)
    fs = np.asarray(mesh.face_start)
    return np.flatnonzero(np.minimum.reduceat(lengths, fs[:-1]) < fraction * mean)


@pytest.fixture(scope="module")
def vanished():
    mesh = folded_grid(short=1e-9 * STEP)
    before = (mesh.vertices.copy(), mesh.face_start.copy(), mesh.face_vertices.copy())
    ps = panels(mesh, 18.0, edge="bisector", gap=4.0)
    return mesh, before, ps


def test_default_is_the_quality_reports_short_edge():
    from facet.quality import DEFAULT_SHORT_EDGE

    assert DEFAULT_MIN_EDGE == DEFAULT_SHORT_EDGE == 0.01


def test_the_quads_beside_a_vanished_edge_become_triangles(vanished):
    mesh, before, ps = vanished
    assert list(faces_with_short_edge(mesh, DEFAULT_MIN_EDGE)) == list(BESIDE)
    assert [p.face for p in ps.vanished_panels] == list(BESIDE)
    for p in ps.panels:
        want = 3 if p.face in BESIDE else 4
        assert (p.corners, p.input_corners, p.vanished_edges) == (want, 4, 4 - want)
        assert len(p.top) == len(p.bottom) == len(p.flat_bottom) == want
        assert len(p.bevel_deg) == len(p.edge_lengths) == len(p.neighbors) == want
    # both lose the duplicate corner: vertex 7 is vertex 2 in every face now
    assert ps.panels[1].vertices.tolist() == [1, 2, 6]
    assert ps.panels[2].vertices.tolist() == [2, 3, 8]
    assert ps.panels[5].vertices.tolist() == [6, 2, 12, 11]
    assert ps.panels[6].vertices.tolist() == [2, 8, 13, 12]
    assert [d["vertices"] for d in ps.vanished_edges] == [[2, 7]]
    assert ps.vanished_edges[0]["faces"] == list(BESIDE)
    # the merged corner is the edge's midpoint, on the fold line
    assert ps.vanished_edges[0]["moved"] == pytest.approx(0.5 * ps.vanished_edges[0]["length"])
    assert ps.short_edges_kept == []
    assert any("2 panels built with fewer corners" in w for w in ps.warnings)
    # neighbours still meet: the triangles' across their edges 2-6 and 8-2, and the two
    # quads touching the merged corner across theirs
    assert ps.panels[1].neighbors == [None, 5, 0]
    assert ps.panels[2].neighbors == [None, 3, 6]
    assert ps.panels[5].neighbors == [1, 6, None, 4]
    assert ps.panels[6].neighbors == [2, 7, None, 5]
    # no edge shorter than the limit is left, and the grid IDs stay
    assert min(min(p.edge_lengths) for p in ps.panels) > 0.3 * STEP
    assert ps.id_scheme == "grid" and ps.panels[1].id == "P-R01C02"
    assert float(ps.planarity.max()) <= 1e-6 * STEP


def test_every_other_panel_is_unchanged(vanished):
    mesh, _, ps = vanished
    faces = mesh.faces()
    for p in ps.panels:
        if p.face not in BESIDE:  # the same corners, vertex 7 now called 2
            assert p.vertices.tolist() == [2 if v == 7 else v for v in faces[p.face]]
    # the same panels as the mesh merged by hand: vertex 7 gone, 2 at the edge's middle
    xyz = mesh.vertices.copy()
    xyz[2] = 0.5 * (xyz[2] + xyz[7])
    by_hand = [[2 if v == 7 else v for v in f] for f in faces]
    by_hand = [[v for k, v in enumerate(f) if v != f[(k + 1) % len(f)]] for f in by_hand]
    ref = panels(facet.PolyMesh.from_faces(xyz, by_hand), 18.0, edge="bisector", gap=4.0,
                 min_edge=0.0)
    for p, q in zip(ps.panels, ref.panels):
        assert p.vertices.tolist() == q.vertices.tolist()
        np.testing.assert_allclose(p.top, q.top, rtol=0, atol=1e-9 * STEP)
        np.testing.assert_allclose(p.bottom, q.bottom, rtol=0, atol=1e-9 * STEP)
        assert p.bevel_deg == pytest.approx(q.bevel_deg, abs=1e-9)
    # square cuts without a gap: the panels away from vertices 2 and 7 are the input's
    square = panels(mesh, 18.0)
    kept = panels(mesh, 18.0, min_edge=0.0)
    assert not kept.vanished_edges and all(p.corners == 4 for p in kept.panels)
    for p, q in zip(square.panels, kept.panels):
        if not {2, 7} & set(q.vertices.tolist()):
            np.testing.assert_allclose(p.bottom, q.bottom, rtol=0, atol=1e-9 * STEP)
            np.testing.assert_allclose(p.top, q.top, rtol=0, atol=1e-9 * STEP)


def test_the_input_mesh_is_unchanged(vanished):
    mesh, before, _ = vanished
    for got, want in zip((mesh.vertices, mesh.face_start, mesh.face_vertices), before):
        np.testing.assert_array_equal(got, want)


@pytest.mark.parametrize("fraction, merged", [(0.02, False), (0.005, True)])
def test_an_edge_above_min_edge_stays(fraction, merged):
    mesh = folded_grid(short=1.0)  # to measure the faces' mean edge with that edge
    _, mean = face_edge_lengths(mesh)
    short = fraction * float(mean[list(BESIDE)].max())
    mesh = folded_grid(short=short)
    lengths, mean = face_edge_lengths(mesh)
    assert (short < DEFAULT_MIN_EDGE * mean[list(BESIDE)]).all() == merged
    ps = panels(mesh, 18.0)
    assert [p.face for p in ps.vanished_panels] == (list(BESIDE) if merged else [])
    assert all(p.corners == 4 for p in ps.panels if p.face not in BESIDE)
    # the limit follows min_edge and min_edge_abs
    assert panels(mesh, 18.0, min_edge=0.0).vanished_panels == []
    bigger = panels(mesh, 18.0, min_edge=0.0, min_edge_abs=1.5 * short)
    assert [p.face for p in bigger.vanished_panels] == list(BESIDE)


def tilted(short, lift_first, lift_last):
    """folded_grid with 3 rows and its edge 7-12 `short` long; the outer lines of
    vertices lifted (by 300 at their first vertex, the rest solved so every quad stays
    planar) when asked, which tilts the planes of faces 1 and 2 (touching vertex 7
    only) or 9 and 10 (touching vertex 12 only) out of the fold line 7-12 runs on."""
    mesh = folded_grid(nv=3)
    xyz = mesh.vertices.copy()
    xyz[12, 1] = xyz[7, 1] + short
    faces = mesh.faces()
    for lift, row, outer in ((lift_first, range(0, 4), (0, 1)), (lift_last, range(8, 12), (3, 2))):
        if not lift:
            continue
        for n, f in enumerate(row):
            quad = faces[f]
            p, q = quad[outer[0]], quad[outer[1]]  # on the outer line, q after p
            if n == 0:
                xyz[p, 2] += 300.0
            a, b, c = (xyz[v] for v in quad if v != q)
            normal = np.cross(b - a, c - a)
            xyz[q, 2] = a[2] - (normal[0] * (xyz[q, 0] - a[0])
                                + normal[1] * (xyz[q, 1] - a[1])) / normal[2]
    out = mesh.with_vertices(xyz)
    assert facet.planarity(out).max_abs.max() < 1e-9 * STEP
    return out


def test_the_merged_corner_is_where_no_face_bends():
    # faces 9 and 10 tilted: merging at vertex 12 moves 7 along the fold (faces 1, 2 stay)
    mesh = tilted(5.0, False, True)
    ps = panels(mesh, 18.0)
    assert [d["vertices"] for d in ps.vanished_edges] == [[7, 12]]
    assert [p.face for p in ps.vanished_panels] == [5, 6]
    assert ps.vanished_edges[0]["moved"] == pytest.approx(5.0)
    assert ps.panels[9].vertices.tolist() == [11, 7, 17, 16]
    np.testing.assert_allclose(ps.panels[9].bottom, panels(mesh, 18.0, min_edge=0).panels[9].bottom,
                               rtol=0, atol=1e-9 * STEP)  # face 9's panel did not move
    assert float(ps.planarity.max()) <= 1e-6 * STEP


def test_a_merge_that_would_bend_a_face_is_kept_and_reported():
    mesh = tilted(5.0, True, True)
    ps = panels(mesh, 18.0)
    assert ps.vanished_edges == [] and ps.vanished_panels == []
    assert all(p.corners == 4 for p in ps.panels)
    assert [d["vertices"] for d in ps.short_edges_kept] == [[7, 12]]
    assert ps.short_edges_kept[0]["faces"] == [5, 6]
    assert ps.short_edges_kept[0]["planarity"] > 1e-6 * STEP
    assert ps.short_edges_kept[0]["reason"] == "planarity"
    assert any("1 edge shorter than min_edge kept: merging its ends" in w and "edge 7-12" in w
               for w in ps.warnings)


def test_a_triangle_whose_edge_vanished_is_an_error_naming_it():
    eps = 1e-9
    xyz = [[0, 0, 0], [1, 0, 0], [1, eps, 0], [2, 0, 0], [2, 1, 0]]
    mesh = facet.PolyMesh.from_faces(xyz, [[1, 3, 4, 2], [0, 1, 2]],
                                     info={"source": "sliver.obj"})
    with pytest.raises(PanelError, match=r"^sliver.obj: face 1: its edge 1-2 .*2 corners") as e:
        panels(mesh, 0.1)
    assert e.value.faces == [1]
    assert "\n" not in str(e.value)
    # a needle triangle whose short edge can still be cut is kept, and said so
    xyz[2] = [1, 0.004, 0]
    mesh = facet.PolyMesh.from_faces(xyz, [[1, 3, 4, 2], [0, 1, 2]])
    ps = panels(mesh, 0.1)
    assert [p.corners for p in ps.panels] == [4, 3] and ps.vanished_edges == []
    assert [(d["vertices"], d["reason"], d["face"]) for d in ps.short_edges_kept] == \
        [([1, 2], "corners", 1)]
    assert any("fewer than 3 corners (edge 1-2" in w for w in ps.warnings)


@pytest.mark.parametrize("kw, text", [({"min_edge": -0.1}, "min_edge must be"),
                                      ({"min_edge": float("nan")}, "min_edge must be"),
                                      ({"min_edge": 1.0}, "min_edge must be below 1"),
                                      ({"min_edge_abs": "x"}, "min_edge_abs must be a number")])
def test_bad_min_edge_is_a_panel_error(kw, text):
    with pytest.raises(PanelError, match=text):
        panels(folded_grid(), 18.0, **kw)


def test_without_the_merge_step_refuses_the_solid_and_with_it_reads_back(tmp_path, vanished):
    step = freecad_step()
    FreeCAD, Part = step.import_freecad()
    mesh, _, ps = vanished
    kept = panels(mesh, 18.0, min_edge=0.0)  # (the bisector cut with a gap is refused)
    with pytest.raises(step.SolidError, match="has no length"):
        step.panel_solids(kept)  # the safety net stays
    solids = step.panel_solids(ps)
    for (pid, s), p in zip(solids, ps.panels):
        k = p.corners
        assert pid == p.id and s.isValid() and s.Shells[0].isClosed()
        assert len(s.Faces) == k + 2 and len(s.Vertexes) == 2 * k
        assert s.Volume == pytest.approx(p.volume, rel=1e-9)
    path = tmp_path / "p.step"
    step.write_step(str(path), solids)
    back = Part.read(str(path))
    assert len(back.Solids) == len(ps.panels)
    assert all(s.isValid() and s.Shells[0].isClosed() for s in back.Solids)
    assert sorted(len(s.Faces) for s in back.Solids) == [5, 5] + [6] * (len(ps.panels) - 2)
    assert sorted(s.Volume for s in back.Solids) == pytest.approx(
        sorted(p.volume for p in ps.panels), rel=1e-9)


def test_dxf_audits_and_the_schedule_marks_exactly_the_triangles(tmp_path, facet_command):
    import ezdxf

    from facet import write_mesh

    mesh = folded_grid(short=1e-9 * STEP)
    mesh_path = tmp_path / "folded.obj"
    write_mesh(mesh, mesh_path)
    report = tmp_path / "r.json"
    done = facet_command("panels", mesh_path, "--thickness", "18", "--edge", "bisector",
                         "--gap", "4", "--sheet", "3000x2000", "--dxf", tmp_path / "s.dxf",
                         "--schedule", tmp_path / "s.csv", "--report", report)
    assert done.returncode == 0, done.stderr
    assert re.search(r"vanished +2 panels built with fewer corners \(1 edge under "
                     r"min_edge merged to a corner\): P-R01C02, P-R01C03", done.stdout)
    doc = ezdxf.readfile(tmp_path / "s.dxf")
    assert not doc.audit().has_errors
    cuts = list(doc.modelspace().query("LWPOLYLINE[layer=='CUT']"))
    assert sorted(len(c) for c in cuts) == [3, 3] + [4] * 6
    for c in cuts:  # no cut of (nearly) no length
        pts = np.array([(x, y) for x, y, *_ in c.get_points()])
        assert np.linalg.norm(np.roll(pts, -1, axis=0) - pts, axis=1).min() > 0.3 * STEP
    rows = list(csv.DictReader(open(tmp_path / "s.csv", encoding="utf-8")))
    marked = [r["id"] for r in rows if r["corners"] != r["input_corners"]]
    assert marked == ["P-R01C02", "P-R01C03"]
    assert {(r["corners"], r["input_corners"]) for r in rows if r["id"] in marked} == {("3", "4")}
    assert all(len(r["edge_lengths_mm"].split(";")) == int(r["corners"]) for r in rows)
    data = json.loads(report.read_text())
    assert data["n_vanished_panels"] == 2
    assert [d["vertices"] for d in data["vanished_edges"]] == [[2, 7]]
    assert [r["input_corners"] - r["corners"] for r in data["panels"]].count(1) == 2
    # 0 keeps every edge, and the run then fails at nothing before STEP: no panel lost a corner
    done = facet_command("panels", mesh_path, "--thickness", "18", "--min-edge", "0",
                         "--report", report)
    assert done.returncode == 0, done.stderr
    assert "vanished" not in done.stdout
    assert json.loads(report.read_text())["n_vanished_panels"] == 0


def test_planarized_hypar_panels_and_step():
    """The real case: hypar.obj planarized by the default method shrinks edges to about
    5e-7 of the mean edge (quads best made triangles)."""
    step = freecad_step()
    import os

    data = os.path.join(os.path.dirname(os.path.dirname(__file__)), "data", "hypar.obj")
    mesh = facet.planarize(facet.read_mesh(data), threads=1).mesh
    short = faces_with_short_edge(mesh, DEFAULT_MIN_EDGE)
    assert short.size > 0  # the solver made edges vanish: the case this guards
    lengths, mean = face_edge_lengths(mesh)
    assert lengths.min() < 1e-4 * mean.mean()
    ps = panels(mesh, 0.01)
    assert [p.face for p in ps.vanished_panels] == short.tolist()
    assert all(p.corners == 3 for p in ps.vanished_panels)
    assert min(min(p.edge_lengths) for p in ps.panels) > DEFAULT_MIN_EDGE * mean.mean()
    solids = step.panel_solids(ps)
    assert len(solids) == mesh.n_faces
    assert all(s.isValid() and s.Shells[0].isClosed() for _, s in solids)
    assert math.isclose(sum(s.Volume for _, s in solids), sum(p.volume for p in ps.panels),
                        rel_tol=1e-9)


def test_merging_reports_progress_before_the_core_and_cancels():
    # 1,200 faces: the core reports too (every 1,024 faces), after the one group merged;
    # mitred with a 5 mm gap, so that no panels clash at a node (the merged node is 8
    # degrees from torsion-free: below a 4.4 mm gap the panels beside it overlap there,
    # and the search for the clearing gap adds its own units: test_panels_nodes)
    mesh = folded_grid(short=1e-6, nv=300)
    calls = []
    ps = panels(mesh, 18.0, edge="bisector", gap=5.0,
                progress=lambda done, total: calls.append((done, total)) and False)
    assert len(ps.vanished_panels) == 2 and ps.node_clash_pairs == 0
    total = 1 + 2 * mesh.n_faces
    assert calls[0] == (0, total) and len(calls) > 1
    assert all(t == total for _, t in calls)
    assert [d for d, _ in calls] == sorted(d for d, _ in calls) and calls[-1][0] <= total
    # cancelled at the merge's first report: before the core was called
    seen = []
    with pytest.raises(Cancelled):
        panels(mesh, 18.0, progress=lambda done, total: seen.append(done) or True)
    assert seen == [0]
