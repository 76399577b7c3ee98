# SPDX-License-Identifier: LGPL-2.1-or-later
"""Panels: geometry, IDs, unfolding, nesting, cut files and the command line."""

import csv
import re
import os
import sys
import json
import functools
import math

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import facet
from facet.errors import Cancelled
from facet.panels import PanelError, grid_positions, panels
from facet.unfold import label_point, unfold
from panel_meshes import cylinder, folded_grid, freecad_step, translational


def face_points(mesh, p):
    return mesh.vertices[p.vertices]


def angles(poly):
    out = []
    k = len(poly)
    for i in range(k):
        a, b, c = poly[i - 1], poly[i], poly[(i + 1) % k]
        u, v = a - b, c - b
        out.append(math.atan2(np.linalg.norm(np.cross(u, v)) if len(u) == 3 else abs(u[0] * v[1] - u[1] * v[0]), np.dot(u, v)))
    return np.array(out)


@pytest.mark.parametrize("make", [cylinder, translational])
def test_square_edges_no_gap_are_congruent_prisms(make):
    mesh = make()
    ps = panels(mesh, 40.0)
    assert len(ps) == mesh.n_faces
    for p in ps:
        face = face_points(mesh, p)
        for flat in (p.flat_bottom, p.flat_top):
            l3 = np.linalg.norm(np.roll(face, -1, axis=0) - face, axis=1)
            l2 = np.linalg.norm(np.roll(flat, -1, axis=0) - flat, axis=1)
            np.testing.assert_allclose(l2, l3, rtol=1e-9)
            np.testing.assert_allclose(angles(flat), angles(face), rtol=1e-9, atol=1e-12)
        assert p.volume == pytest.approx(p.area * 40.0, rel=1e-9)
        # exactly 0: the schedule wrote rounding noise such as -3.975693351829398e-16
        assert p.bevel_deg == [0.0] * 4
        # outer: the bottom lies on the mesh, the top t above along the normal
        np.testing.assert_allclose(p.bottom, face, atol=1e-7)
        np.testing.assert_allclose(p.top - p.bottom, np.tile(40.0 * p.normal, (4, 1)), atol=1e-7)


def test_offset_sides():
    mesh = cylinder()
    face = None
    for offset, lo, hi in (("outer", 0, 40), ("inner", -40, 0), ("center", -20, 20)):
        p = panels(mesh, 40.0, offset=offset).panels[3]
        face = face_points(mesh, p)
        np.testing.assert_allclose((p.bottom - face) @ p.normal, lo, atol=1e-7)
        np.testing.assert_allclose((p.top - face) @ p.normal, hi, atol=1e-7)


def test_bisector_gap_is_constant_and_bevels_are_half_the_fold():
    mesh = translational()
    g = 6.0
    ps = panels(mesh, 30.0, edge="bisector", gap=g)
    by_face = {p.face: p for p in ps}
    checked = 0
    for p in ps:
        sides = p.side_faces()
        for k, h in enumerate(p.neighbors):
            if h is None:
                continue
            fold = 180.0 - p.dihedral_deg[k]
            assert abs(p.bevel_deg[k]) == pytest.approx(abs(fold) / 2, abs=1e-9)
            q = by_face[h]
            kq = q.neighbors.index(p.face)
            s = sides[k]
            n = np.cross(s[1] - s[0], s[3] - s[0])
            n /= np.linalg.norm(n)
            other = q.side_faces()[kq]
            d = (other - s[0]) @ n
            np.testing.assert_allclose(np.abs(d), g, rtol=1e-9)
            checked += 1
    assert checked == 2 * (4 * 4 + 5 * 3)


def test_node_deviation_zero_on_cylinder_positive_on_translational():
    assert panels(cylinder(), 10.0).max_node_deviation_deg < 1e-7
    ps = panels(translational(), 10.0)
    assert ps.max_node_deviation_deg > 0.01
    assert ps.worst_node is not None
    assert ps.node_deviation_deg.shape == (30,)


def test_grid_ids_and_index_ids():
    ps = panels(cylinder(nu=6, nv=4), 10.0)
    assert ps.id_scheme == "grid" and ps.grid_shape == (4, 6)
    assert ps.panels[0].id == "P-R01C01"
    assert ps.panels[7].id == "P-R02C02"
    assert len({p.id for p in ps}) == 24
    ps = panels(cylinder(), 10.0, ids="index", prefix="F")
    assert ps.panels[5].id == "F0005"
    # triangles: not a grid
    tri = facet.PolyMesh.from_faces(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0.0]]),
                                    [[0, 1, 2], [1, 3, 2]])
    assert panels(tri, 0.01).id_scheme == "index"
    with pytest.raises(PanelError, match="it has 2 triangles: choose auto or index"):
        panels(tri, 0.01, ids="grid")
    custom = panels(tri, 0.01, ids=["A", "B"])
    assert [p.id for p in custom] == ["A", "B"]


def test_grid_detection_survives_a_reversed_face():
    mesh = cylinder(nu=3, nv=2)
    faces = mesh.faces()
    faces[4] = faces[4][::-1]
    bad = facet.PolyMesh.from_faces(mesh.vertices, faces)
    ps = panels(bad, 10.0)
    assert ps.n_reversed == 1
    assert ps.id_scheme == "grid"
    assert any("reversed" in w for w in ps.warnings)
    n0 = panels(mesh, 10.0).panels[4].normal
    np.testing.assert_allclose(ps.panels[4].normal, n0, atol=1e-12)
    assert grid_positions(bad) is None  # without the orientation it is not read as a grid


def test_flip_swaps_the_sides():
    a = panels(cylinder(), 10.0).panels[0]
    b = panels(cylinder(), 10.0, flip=True).panels[0]
    np.testing.assert_allclose(a.normal, -b.normal, atol=1e-12)


def test_bad_inputs_are_one_line_panel_errors():
    mesh = cylinder()
    for kwargs, text in (({"thickness": 0}, "thickness"), ({"thickness": -1}, "thickness"),
                         ({"thickness": float("nan")}, "thickness"),
                         ({"thickness": 1, "gap": -1}, "gap"),
                         ({"thickness": 1, "offset": "up"}, "offset"),
                         ({"thickness": 1, "edge": "round"}, "edge"),
                         ({"thickness": 1, "gap": 5000}, "gap")):
        with pytest.raises(PanelError, match=text) as info:
            panels(mesh, **kwargs)
        assert "\n" not in str(info.value)


def test_nonplanar_faces_are_listed():
    mesh = cylinder()
    xyz = mesh.vertices.copy()
    xyz[8] += (30.0, 0, 0)  # bends the four faces around vertex 8
    with pytest.raises(PanelError, match="4 faces are not planar") as info:
        panels(mesh.with_vertices(xyz), 10.0)
    assert info.value.faces == [0, 1, 6, 7]
    assert isinstance(info.value, facet.InputError)
    # within an absolute tolerance it is accepted
    panels(mesh.with_vertices(xyz), 10.0, tol_abs=20.0)


def test_georeferenced_coordinates_give_the_same_panels():
    a = panels(cylinder(), 40.0, edge="bisector", gap=5)
    b = panels(cylinder(origin=(2.6e6, 1.2e6, 400.0)), 40.0, edge="bisector", gap=5)
    for p, q in zip(a, b):
        np.testing.assert_allclose(p.flat_bottom, q.flat_bottom, atol=1e-6)
        assert p.volume == pytest.approx(q.volume, rel=1e-9)


def test_source_mesh_is_not_modified():
    mesh = translational()
    before = mesh.vertices.copy()
    panels(mesh, 10.0, edge="bisector", gap=2)
    np.testing.assert_array_equal(mesh.vertices, before)


def test_progress_cancels():
    mesh = cylinder(nu=60, nv=40)
    with pytest.raises(Cancelled):
        panels(mesh, 10.0, progress=lambda done, total: True)


def test_unfolding_reports_progress_and_cancels():
    """Unfolding 5,041 parts took 2.4 s with nothing on the progress bar or line, under
    the stage before it; it now counts its parts, and True cancels."""
    from facet.cli_panels import run_pipeline

    ps = panels(translational(nu=12, nv=10), 18.0, edge="bisector", gap=4)
    seen = []
    unfold(ps, progress=lambda done, total: seen.append((done, total)) and False)
    n = len(ps.panels)
    assert seen[0] == (0, n) and seen[-1] == (n, n)
    assert [d for d, _ in seen] == sorted(d for d, _ in seen)
    with pytest.raises(Cancelled, match="unfolding cancelled"):
        unfold(ps, progress=lambda done, total: done > 0)
    stages = []
    run_pipeline(translational(nu=12, nv=10), 18.0, edge="bisector", gap=4,
                 sheet=(6000, 3000), progress=lambda stage, d, t: stages.append(stage) and False)
    assert "unfold" in stages and stages.index("unfold") < stages.index("nest")


def test_wave_facade_planarized(tmp_path):
    from pathlib import Path

    example = Path(__file__).resolve().parents[2] / "examples" / "wave_facade.obj"
    mesh = facet.read_mesh(example)
    planar = facet.planarize(mesh, tol=1e-6).mesh
    ps = panels(planar, 40.0, edge="bisector", gap=8)
    assert ps.id_scheme == "grid"
    assert all(p.volume > 0 for p in ps)
    with pytest.raises(PanelError, match="not planar"):
        panels(mesh, 40.0)


@pytest.mark.parametrize("thickness", [8.0, 40.0])  # make demo's; the PanelSet's default
def test_cli_panels_default_gap_gives_the_bundled_facade_clean_joints(
        facet_command, tmp_path, thickness):
    """``facet panels`` without --gap cut the example facade's panels edge to edge (gap 0):
    square cuts overlapped on every valley and at the nodes, 216 of its 280 panels, and a
    designer's first run was a list of clashes. The default is a 6 mm joint
    (DEFAULT_GAP_MM), which clears them: no overlap is hidden, --gap 0 still has them."""
    from pathlib import Path

    from facet import write_mesh
    from facet.panels import DEFAULT_GAP_MM

    example = Path(__file__).resolve().parents[2] / "examples" / "wave_facade.obj"
    write_mesh(facet.planarize(facet.read_mesh(example), tol=1e-6).mesh, tmp_path / "p.obj")
    done = facet_command("panels", tmp_path / "p.obj", "--thickness", str(thickness),
                         "--report", tmp_path / "r.json")
    assert done.returncode == 0, done.stderr
    report = json.load(open(tmp_path / "r.json"))
    assert DEFAULT_GAP_MM == 6.0 and report["options"]["gap"] == DEFAULT_GAP_MM
    assert report["options"]["edge"] == "square"
    assert report["overlapping_joints"] == 0 and report["node_clash_pairs"] == 0
    assert report["narrowest_joint"] > 0 and report["clearing_gap"] is None
    assert "overlap" not in done.stderr
    assert f"(gap {DEFAULT_GAP_MM:g} mm)" in done.stdout  # (lengths in --units)
    # edge to edge the same panels overlap, and the gap that clears them is under 6 mm
    done = facet_command("panels", tmp_path / "p.obj", "--thickness", str(thickness), "--gap",
                         "0", "--report", tmp_path / "r0.json")
    assert done.returncode == 0, done.stderr
    zero = json.load(open(tmp_path / "r0.json"))
    assert zero["overlapping_joints"] > 100 and zero["node_clash_pairs"] > 0
    assert 0 < zero["clearing_gap"] < DEFAULT_GAP_MM


def test_default_gap_is_in_the_given_units_and_hides_no_real_overlap(tmp_path):
    """The default joint is 6 mm in --units (as the sheet's margin and spacing are); a fold
    whose square joints need more than that still overlaps and is reported."""
    from facet.cli_panels import run_pipeline
    from facet.panels import DEFAULT_GAP_MM

    mm = translational(nu=3, nv=2, step=400.0)
    metres = facet.PolyMesh(mm.vertices / 1000.0, mm.face_start, mm.face_vertices)
    report, ps, _, _ = run_pipeline(metres, 0.018, units="m")
    assert ps.options["gap"] == pytest.approx(DEFAULT_GAP_MM / 1000.0)
    assert report["options"]["gap"] == ps.options["gap"]
    folded = folded_grid()  # valleys that 200 mm thick square cuts overlap by far more
    report, ps, _, _ = run_pipeline(folded, 200.0)
    assert ps.options["gap"] == DEFAULT_GAP_MM
    assert report["overlapping_joints"] > 0
    assert report["clearing_gap"] > DEFAULT_GAP_MM


# ---- unfolding -------------------------------------------------------------

def test_label_point_matches_polylabel():
    from shapely.geometry import Point, Polygon
    from shapely.ops import polylabel

    poly = np.array([[0, 0], [10, 0], [10, 2], [3, 2], [3, 8], [0, 8.0]])
    (x, y), depth = label_point(poly)
    ref = polylabel(Polygon(poly), 1e-4)
    assert Polygon(poly).contains(Point(x, y))
    assert depth == pytest.approx(Polygon(poly).exterior.distance(ref), rel=0.02)


@pytest.mark.parametrize("edge, offset", [("bisector", "outer"), ("bisector", "inner"),
                                          ("square", "center")])
def test_convex_footprints_and_labels_match_the_general_ones(edge, offset):
    from shapely.geometry import Polygon

    from facet.unfold import _convex, _convex_footprints, _edge_distance, _inside, label_points

    ps = panels(translational(nu=6, nv=5, step=400.0), 18.0, edge=edge, offset=offset, gap=4)
    feet = _convex_footprints(ps.panels)
    assert all(f is not None for f in feet)  # every panel here is convex
    for p, f in zip(ps.panels, feet):
        general = p.footprint()
        fast = Polygon(f)
        assert fast.is_valid
        assert fast.symmetric_difference(general).area <= 1e-12 * general.area
    # the convex depth is the general one
    outlines = [p.flat_bottom for p in ps.panels]
    poly = np.array(outlines)
    assert _convex(poly).all()
    for (xy, depth), o in zip(label_points(outlines), outlines):
        pts = np.array([[xy]])
        assert _inside(o[None], pts)[0, 0]
        assert depth == pytest.approx(_edge_distance(o[None], pts)[0, 0], rel=1e-12)


def test_concave_panels_keep_the_general_footprint():
    from facet.unfold import _convex_footprints

    class P:
        flat_bottom = np.array([[0, 0], [10, 0], [10, 2], [3, 2], [3, 8], [0, 8.0]])
        flat_top = flat_bottom

    assert _convex_footprints([P()]) == [None]


def test_unfold_labels_inside_and_bevel_texts():
    from shapely.geometry import Point, Polygon

    ps = panels(translational(), 30.0, edge="bisector", gap=4)
    drawings = unfold(ps)
    for p, d in zip(ps, drawings):
        assert Polygon(d.cut).contains(Point(d.label_position))
        assert d.label_height > 0
        bevelled = sum(1 for b in p.bevel_deg if f"{b:.1f}" not in ("0.0", "-0.0"))
        assert len(d.bevels) == bevelled
        for text, x, y, ang, h in d.bevels:
            assert Polygon(d.cut).contains(Point(x, y))
            assert text.endswith("\u00b0")
        assert Polygon(d.footprint).buffer(1e-6).contains(Polygon(d.cut))


def test_no_bevel_text_reads_zero():
    """A bevel that rounds to 0.0 degrees was engraved as "+0.0°" or "-0.0°" (a chevron
    facade on a cylinder, 3 mm mitred: 196 of its 304 bevel texts, on edges between
    coplanar panels): a text for the fabricator to read and skip. Only the bevels the text
    shows are written; the schedule's bevel_deg keeps every angle."""
    fold = math.tan(math.radians(0.02)) * 1000.0     # a 0.02 degree fold at x = 1000
    z = [0.0, 0.0, fold, fold + math.tan(math.radians(10.02)) * 1000.0]
    pts = [[x, y, zx] for y in (0.0, 800.0) for x, zx in zip((0.0, 1000.0, 2000.0, 3000.0), z)]
    mesh = facet.PolyMesh.from_faces(np.array(pts), [[0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6]])
    ps = panels(mesh, 3.0, edge="bisector", gap=4.0)
    drawings = unfold(ps)
    texts = [t for d in drawings for t, *_ in d.bevels]
    assert texts and not [t for t in texts if t[1:] == "0.0\u00b0"]
    assert [t[1:] for t in texts] == ["5.0\u00b0", "5.0\u00b0"]
    # the tiny bevels are still scheduled
    assert 0 < abs(ps.panels[0].bevel_deg[1]) < 0.05


@functools.lru_cache(maxsize=None)
def _text_size(text):
    """(width, whole height) of a DXF TEXT of capital height 1, as ezdxf measures it."""
    import ezdxf
    from ezdxf.tools.text_size import text_size

    size = text_size(ezdxf.new().modelspace().add_text(text, dxfattribs={"height": 1.0}))
    return size.width, size.total_height


def _text_box(x, y, h, text, angle=0.0):
    """The box of a DXF TEXT of capital height h centred at (x, y): its width, and its
    whole height with descenders."""
    from shapely import affinity
    from shapely.geometry import box

    width, height = _text_size(text)
    w, below = width * h, (height - 0.5) * h
    return affinity.rotate(box(x - w / 2, y - below, x + w / 2, y + 0.5 * h), angle,
                           origin=(x, y))


@pytest.mark.parametrize("prefix", ["P-", "NORTH-FACADE-L2-"])
def test_ids_and_bevel_texts_stay_inside_their_parts(prefix, data_dir):
    # strips 3000 x 150: the ID (text as high as the depth allowed) was centred 83 from
    # the strip's end and ran past it, off the sheet; on square panels a long prefix made
    # the ID wider than the panel; a bevel angle beside a short edge at a sharp corner
    # was written outside its part
    from shapely.geometry import Point, Polygon

    strips = facet.PolyMesh.from_faces(
        np.array([[x, 0.0, y] for y in range(0, 1000, 150) for x in (0.0, 3000.0)]),
        [[2 * i, 2 * i + 1, 2 * i + 3, 2 * i + 2] for i in range(6)])
    heart = facet.read_mesh(data_dir / "heart_planar.obj")
    for ps in (panels(strips, 10.0, gap=4.0, prefix=prefix),
               panels(translational(), 30.0, edge="bisector", gap=4, prefix=prefix),
               panels(heart, 0.005, gap=0.01, edge="bisector", prefix=prefix)):
        for d in unfold(ps):
            part = Polygon(d.cut)
            label = _text_box(*d.label_position, d.label_height, d.id)
            assert part.contains(label), (d.id, d.label_position, d.label_height)
            assert d.label_height > 0.02 * math.sqrt(part.area)  # not shrunk to nothing
            edges = np.hypot(*np.diff(d.cut, axis=0, append=d.cut[:1]).T)
            for text, x, y, angle, h in d.bevels:
                assert part.contains(Point(x, y)), (d.id, text)
                assert _text_box(x, y, h, text).bounds[2] - x <= 0.5 * max(edges)
    strip = unfold(panels(strips, 10.0, gap=4.0))[0]
    assert strip.label_height > 50  # room for it along the strip: not crushed to its end


def test_texts_stay_put_when_the_model_changes_by_a_rounding(data_dir):
    """An ID went to the pole of inaccessibility, picked among nearly equal depths across
    a near-rectangle's middle: a 1e-9 change of the model moved 12 of heart_planar's 400
    IDs (by up to 2 % of the model), and the bevel texts that kept clear of them, so cut
    sheets written again after a tiny edit showed their texts elsewhere. The ID now goes
    to the centroid where the text fits there at full height, and follows the outline."""
    heart = facet.read_mesh(data_dir / "heart_planar.obj")
    size = float(np.ptp(heart.vertices, axis=0).max())
    rng = np.random.default_rng(2)
    nudged = facet.PolyMesh(heart.vertices + rng.uniform(-1e-9, 1e-9, heart.vertices.shape) * size,
                            heart.face_start, heart.face_vertices)
    before, after = (unfold(panels(m, 0.005, gap=0.01, edge="bisector")) for m in (heart, nudged))
    for a, b in zip(before, after):
        assert np.hypot(*np.subtract(a.label_position, b.label_position)) < 1e-7 * size, a.id
        assert a.label_height == pytest.approx(b.label_height, rel=1e-6), a.id
        assert [t[0] for t in a.bevels] == [t[0] for t in b.bevels], a.id
        for s, t in zip(a.bevels, b.bevels):
            assert np.hypot(s[1] - t[1], s[2] - t[2]) < 1e-7 * size, (a.id, s[0])
    from shapely.geometry import Polygon
    face = [Polygon(d.cut).intersection(Polygon(d.top)) for d in before]  # (engraved on)
    centred = sum(np.allclose(d.label_position, f.centroid.coords[0], atol=1e-9 * size)
                  for d, f in zip(before, face))
    assert centred > 0.9 * len(before)


@functools.lru_cache(maxsize=None)
def _heart_drawings(data_dir):
    """heart_planar's parts, mitred at 20 mm, and at 5 mm with a 10 mm gap: sharp corners
    and short edges, where the texts are hardest to place."""
    heart = facet.read_mesh(os.path.join(data_dir, "heart_planar.obj"))
    return tuple(d for ps in (panels(heart, 0.02, edge="bisector"),
                              panels(heart, 0.005, gap=0.01, edge="bisector"))
                 for d in unfold(ps))


def test_a_bevel_text_is_nearer_its_own_edge_than_any_other(data_dir):
    """A bevel angle is read as the angle of the edge it is nearest: beside a short edge at
    a sharp corner its text sat nearer the neighbouring edge (45 of heart's 1,510) or ran
    out of the part (20). Each text's box, as ezdxf measures it, now lies inside its part
    and nearer its own edge than any other."""
    from shapely.geometry import LineString, Polygon

    checked = 0
    for d in _heart_drawings(str(data_dir)):
        part = Polygon(d.cut)
        k = len(d.cut)
        edges = [LineString([d.cut[i], d.cut[(i + 1) % k]]) for i in range(k)]
        turns = [math.degrees(math.atan2(*(d.cut[(i + 1) % k] - d.cut[i])[::-1]))
                 for i in range(k)]
        for text, x, y, angle, h in d.bevels:
            box = _text_box(x, y, h, text, angle)
            own = min((i for i in range(k) if abs(turns[i] - angle) < 1e-9),
                      key=lambda i: edges[i].distance(box))
            assert part.contains(box), (d.id, text)
            nearest = min(edge.distance(box) for i, edge in enumerate(edges) if i != own)
            assert nearest > edges[own].distance(box), (d.id, text, own)
            checked += 1
    assert checked > 2900  # (2,998 texts: heart has two bevels that read 0.0, not written)


def test_bevel_texts_clear_the_id_and_each_other(data_dir):
    """A bevel angle written over the part's ID (or another angle) cannot be read: on
    heart_planar 92 of 1,517 bevel texts overlapped their part's ID (by up to 0.37 of the
    text, as ezdxf measures it) and 4 another bevel text; on a planarized conical mesh 623
    of 4,188. Now none does, and each still lies inside its part."""
    from shapely.geometry import Polygon

    checked = 0
    for d in _heart_drawings(str(data_dir)):
        part = Polygon(d.cut)
        boxes = [_text_box(*d.label_position, d.label_height, d.id)]
        for text, x, y, angle, h in d.bevels:
            box = _text_box(x, y, h, text, angle)
            assert part.contains(box), (d.id, text)
            assert all(box.intersection(other).area == 0 for other in boxes), (d.id, text)
            boxes.append(box)
            checked += 1
    assert checked > 2900  # (2,998 texts: heart has two bevels that read 0.0, not written)


def test_texts_lie_on_the_top_face_where_they_are_engraved(data_dir):
    # engraved from above, the texts lie on the top face; where a bevel makes it the
    # smaller they ran off it onto the slope: on heart_planar 20 mm mitred 34 of 1,510
    # bevel texts and 5 of 400 IDs, 11 bevel texts at 5 mm, on crossvault 40 mm 16 of 784
    from shapely.geometry import Polygon

    heart = facet.read_mesh(data_dir / "heart_planar.obj")
    for ps in (panels(heart, 0.02, edge="bisector"),
               panels(heart, 0.005, gap=0.01, edge="bisector")):
        for d in unfold(ps):
            face = Polygon(d.cut).intersection(Polygon(d.top))
            assert face.contains(_text_box(*d.label_position, d.label_height, d.id)), d.id
            for text, x, y, angle, h in d.bevels:
                assert face.contains(_text_box(x, y, h, text, angle)), (d.id, text)


def test_a_bevel_text_with_no_room_on_its_part_is_left_out_and_said(data_dir):
    """Where no place inside the part took a bevel text (a short edge at a sharp corner),
    the smallest tried was put at the edge's middle anyway: on the planarized hex mesh in
    metres (10 mm panels, mitred, 4 mm gap) a 0.03 mm '-7.2°' lay 0.08 mm outside P-0007's
    cut outline, engraved off the part. It is left out now, and a warning says so."""
    from shapely.geometry import Polygon

    from facet.unfold import small_text_warnings

    hexes = facet.planarize(facet.read_mesh(data_dir / "hex_mesh_min_surface.json")).mesh
    ps = panels(hexes, 0.01, gap=0.004, edge="bisector")
    drawings = unfold(ps)
    left_out = [(d.id, text) for d in drawings for text in d.bevels_left_out]
    assert left_out == [("P-0007", "-7.2°")]
    for p, d in zip(ps.panels, drawings):
        face = Polygon(d.cut).intersection(Polygon(d.top))
        for text, x, y, angle, h in d.bevels:
            assert face.contains(_text_box(x, y, h, text, angle)), (d.id, text)
        bevelled = sum(abs(b) >= 1e-6 for b in p.bevel_deg)  # (unfold's tolerance)
        assert len(d.bevels) + len(d.bevels_left_out) == bevelled, d.id
    (said,) = [w for w in small_text_warnings(drawings, 1000.0) if "left out" in w]
    assert said.startswith("1 bevel angle text found no room inside its part and is left "
                           "out (P-0007)")


def test_texts_too_small_to_engrave_are_warned_about(data_dir, tmp_path):
    """A text is as large as its place allows; beside a short edge that was under 3 mm,
    unsaid (heart_planar in metres, mitred at 5 mm with a 10 mm gap: 23 of 1,517 bevel
    texts). Now a warning counts them, in the model's units, and names the smallest."""
    from facet.cli_panels import run_pipeline
    from facet.unfold import MIN_TEXT_MM, small_text_warnings

    heart = facet.read_mesh(data_dir / "heart_planar.obj")
    drawings = unfold(panels(heart, 0.005, gap=0.01, edge="bisector"))
    heights = [bh for d in drawings for *_, bh in d.bevels]
    small = [h for h in heights if h * 1000.0 < MIN_TEXT_MM]
    assert 0 < len(small) < len(heights)
    (warning,) = small_text_warnings(drawings, 1000.0)
    assert warning.startswith(f"{len(small)} of {len(heights)} bevel angle texts are under "
                              f"{MIN_TEXT_MM:g} mm high")
    assert f"the smallest {1000.0 * min(small):.3g} mm" in warning
    assert all(d.label_height * 1000.0 >= MIN_TEXT_MM for d in drawings)  # (no ID warning)
    # the same parts in millimetres: every text under 3 mm (IDs too)
    assert len(small_text_warnings(drawings, 1.0)) == 2
    # the command's report and output: 20 mm panels' IDs (a tenth of the part) are under
    # 3 mm; in centimetres the same numbers are ten times larger and say nothing
    tiny = translational(nu=3, nv=2, step=20.0)
    report = run_pipeline(tiny, 1.0, units="mm", sheet=(200, 100), margin=1, spacing=1,
                          dxf=str(tmp_path / "tiny.dxf"))[0]
    assert [w for w in report["warnings"] if "part IDs are under 3 mm high" in w]
    report = run_pipeline(tiny, 1.0, units="cm", sheet=(200, 100), margin=1, spacing=1,
                          dxf=str(tmp_path / "tiny.dxf"))[0]
    assert not [w for w in report["warnings"] if "engrave" in w]
    # with no DXF, SVG or PNG no text is written: nothing to warn about (it warned)
    report = run_pipeline(tiny, 1.0, units="mm", schedule=str(tmp_path / "tiny.csv"))[0]
    assert not [w for w in report["warnings"] if "engrave" in w]
    assert report["text_warnings"] == []



def test_small_text_warnings_of_a_model_in_inches_say_inches(tmp_path):
    """A fabricator working in inches (--units in) read "under 3 mm high ... the smallest
    2.87 mm" about parts whose every other length the command gave in inches. The heights
    are in inches now, the least in mm too."""
    from facet.cli_panels import run_pipeline
    from facet.unfold import MIN_TEXT_MM

    tiny = translational(nu=3, nv=2, step=0.8)  # 0.8 in panels: IDs 0.08 in high
    report = run_pipeline(tiny, 0.0625, units="in", gap=0.02, sheet=(12, 24), margin=0.25,
                          spacing=0.25, dxf=str(tmp_path / "tiny.dxf"))[0]
    (warning,) = [w for w in report["warnings"] if "engrave" in w]
    least = MIN_TEXT_MM / 25.4
    assert warning.startswith(f"6 of 6 part IDs are under {least:.3g} in ({MIN_TEXT_MM:g} mm)"
                              " high"), warning
    smallest = float(re.search(r"the smallest ([0-9.]+) in,", warning).group(1))
    assert 0.05 < smallest < least
    assert " mm," not in warning and "mm high" not in warning


def test_the_dashed_linetype_says_its_dash_in_the_files_unit(tmp_path):
    """An inch DXF's FACET_DASHED (the TOP outlines) is a 0.5 in dash, but the
    description AutoCAD's linetype manager shows said "Dashed, 12.7 mm" to a user in
    inches. It gives the dash in the file's unit now."""
    import ezdxf

    from facet.cli_panels import run_pipeline
    from facet.cutsheets import DASH_MM

    tiny = translational(nu=3, nv=2, step=20.0)
    for units, said in (("in", "0.5 in"), ("mm", "12.7 mm"), ("ft", "0.0417 ft")):
        run_pipeline(tiny, 0.25, units=units, gap=0.1, sheet=(200, 100), margin=1, spacing=1,
                     dxf=str(tmp_path / "tiny.dxf"))
        dashed = ezdxf.readfile(tmp_path / "tiny.dxf").linetypes.get("FACET_DASHED")
        assert dashed.dxf.description == f"Dashed, {said} __  __  __", units
        lengths = [t.value for t in dashed.pattern_tags.tags if t.code == 49]  # (+dash, -gap)
        scale = {"in": 25.4, "ft": 304.8, "mm": 1.0}[units]
        assert [v * scale for v in lengths] == pytest.approx([DASH_MM[0], -DASH_MM[1]])

def test_grain_turns_parts_and_is_checked():
    ps = panels(cylinder(), 10.0)
    drawings = unfold(ps, grain=(0, 0, 1))
    for p, d in zip(ps, drawings):
        # the cylinder's vertical edges become parallel to +x
        e = d.cut[2] - d.cut[1]
        assert abs(e[1]) < 1e-6 * np.linalg.norm(e)
        assert d.grain is not None
    with pytest.raises(PanelError, match="grain"):
        unfold(ps, grain=(0, 0, 0))


def test_the_grain_arrow_lies_inside_its_part_clear_of_the_texts(data_dir):
    # the arrow (engraved) was drawn 1.5 ID heights below the ID whatever the part's shape:
    # on heart_planar with grain 1,0,0 it ran out of 8 of the 400 parts, onto the sheet
    # beyond them, and through a text on 4
    from shapely.geometry import LineString, Polygon

    ps = panels(facet.read_mesh(data_dir / "heart_planar.obj"), 0.005, gap=0.01,
                edge="bisector")
    for d in unfold(ps, grain=(1, 0, 0)):
        a, b = np.asarray(d.grain, dtype=float)
        length = np.linalg.norm(b - a)
        assert length > 0
        u = (b - a) / length
        n = np.array([-u[1], u[0]])
        # the shaft and the head, as write_dxf draws them
        lines = [LineString([a, b])] + [
            LineString([b, b - 0.15 * length * u + s * 0.075 * length * n]) for s in (1, -1)]
        part = Polygon(d.cut)
        texts = [_text_box(*d.label_position, d.label_height, d.id)] + [
            _text_box(x, y, h, text, angle) for text, x, y, angle, h in d.bevels]
        assert all(part.contains(line) for line in lines), d.id
        assert not any(t.intersects(line) for t in texts for line in lines), d.id


@pytest.mark.parametrize("grain", [(1, 0, 1), (1, 0, 2), (-2, 0, 1), (0, 0, 1), (1, 0, 0)])
def test_grain_runs_along_x_at_any_angle_to_the_panels_edges(grain):
    # a square panel in the XZ plane; the grain at an angle to its edges (the cylinder's
    # vertical grain is parallel to an edge, where a part turned the wrong way round
    # only came out reversed: at 45 degrees it came out at 90)
    mesh = facet.PolyMesh.from_faces(
        np.array([[0, 0, 0], [1000, 0, 0], [1000, 0, 1000], [0, 0, 1000.0]]), [[0, 1, 2, 3]])
    ps = panels(mesh, 10.0)
    part = unfold(ps, grain=grain)[0]
    # the drawing as a map of the panel's 3D corners: where does the grain go?
    fit, *_ = np.linalg.lstsq(np.c_[ps.panels[0].bottom, np.ones(4)], part.cut, rcond=None)
    along = np.asarray(grain, float) @ fit[:3]
    assert abs(along[1]) < 1e-9 * np.linalg.norm(along) and along[0] > 0
    arrow = np.subtract(part.grain[1], part.grain[0])
    assert arrow[0] > 0 and arrow[1] == 0


def test_a_gap_that_closes_a_notch_is_refused_by_face():
    # a 1 m square panel with a slot 20 mm wide at its mouth and 700 mm deep: with a 10 mm
    # gap the slot's sides crossed, and the self-crossing outline went to the schedule
    # (area, perimeter, corners measured on it) with exit 0
    from shapely.geometry import LinearRing

    slot = facet.PolyMesh.from_faces(
        np.array([[0, 0, 0], [1000, 0, 0], [1000, 1000, 0], [510, 1000, 0], [500, 300, 0],
                  [490, 1000, 0], [0, 1000, 0.0]]), [[0, 1, 2, 3, 4, 5, 6]])
    ok = panels(slot, 8.0, gap=6.0).panels[0]
    assert LinearRing(ok.flat_bottom).is_simple and LinearRing(ok.flat_top).is_simple
    with pytest.raises(PanelError, match=r"face 0: its cut \(bottom\) outline crosses itself "
                       r"once the joint gap \(10\)") as caught:
        panels(slot, 8.0, gap=10.0)
    assert caught.value.faces == [0]


def test_a_gap_that_eats_an_arm_says_so():
    # an L with 300 mm arms and a 301 mm gap: "the edges at vertex 1 are collinear; remove
    # the vertex" (a square corner), where a convex panel is told the gap consumes it
    ell = facet.PolyMesh.from_faces(
        np.array([[0, 0, 0], [1000, 0, 0], [1000, 300, 0], [300, 300, 0], [300, 1000, 0],
                  [0, 1000, 0.0]]), [[0, 1, 2, 3, 4, 5]])
    with pytest.raises(PanelError, match=r"face 0: the gap 301 consumes edges of its outline "
                       r"until two parallel ones meet \(at vertex \d\); use a smaller gap"):
        panels(ell, 8.0, gap=301.0)
    assert len(panels(ell, 8.0, gap=290.0)) == 1
    # a vertex on a straight edge stays a (straight) corner on its offset edge, also
    # when the gap consumes a chamfer elsewhere on the face
    chamfered = facet.PolyMesh.from_faces(
        np.array([[0, 0, 0], [10, 0, 0], [20, 0, 0], [20, 9.9, 0], [19.9, 10, 0],
                  [0, 10, 0.0]]), [[0, 1, 2, 3, 4, 5]])
    for gap in (0.0, 1.0):
        p = panels(chamfered, 0.5, gap=gap).panels[0]
        np.testing.assert_allclose(p.top[1], [10, gap / 2, 0.5], atol=1e-9)
        np.testing.assert_allclose(p.bottom[1], [10, gap / 2, 0], atol=1e-9)


def t_junction(fold_deg, left=True, bend=0.0):
    """A 2 x 1 m panel A under two 1 x 1 m panels B and C that meet at the middle of
    A's top edge (A's vertex 3 is a straight corner, or moved out by ``bend`` mm: a nearly
    straight one), folded up by fold_deg along that edge; left=False leaves B out, A's
    edge free there."""
    t = math.tan(math.radians(fold_deg))
    xyz = np.array([[0, 0, 0], [2000, 0, 0], [2000, 1000, 0], [1000, 1000 + bend, 0],
                    [0, 1000, 0], [0, 2000, 1000 * t], [1000, 2000 + bend, 1000 * t],
                    [2000, 2000, 1000 * t]])
    faces = [[0, 1, 2, 3, 4], [3, 2, 7, 6]] + ([[4, 3, 6, 5]] if left else [])
    return facet.PolyMesh.from_faces(xyz, faces)


@pytest.mark.parametrize("edge", ["square", "bisector"])
@pytest.mark.parametrize("fold", [0.0, 30.0])
def test_two_panels_along_one_side_of_a_third(edge, fold):
    # a T-junction: B and C share A's top edge (a planar mesh makes them coplanar); A's
    # straight corner there was refused ("the edges at vertex 3 are collinear")
    ps = panels(t_junction(fold), 20.0, gap=10.0, edge=edge)
    a = ps.panels[0]
    assert len(a.top) == 5 and a.dropped_edges == a.squared_edges == 0
    for outline, h in ((a.top, 20.0), (a.bottom, 0.0)):
        # A's top edge is one line, 5 mm (half the gap) in, at the straight corner too
        side = outline[2:5]
        np.testing.assert_allclose(side[:, 2], h, atol=1e-9)
        assert np.ptp(side[:, 1]) < 1e-9
        np.testing.assert_allclose(outline[3, 0], 1000.0, atol=1e-9)
    # both joints along that edge alike: the gap's width where mitred or flat
    assert a.joint_widths[2] == pytest.approx(a.joint_widths[3])
    if edge == "bisector" or fold == 0:
        assert a.joint_widths[2] == pytest.approx(10.0)
        assert max(p.clash for p in ps) == 0.0
    assert a.bevel_deg[2] == pytest.approx(a.bevel_deg[3])


def test_a_straight_corner_between_a_mitre_and_a_free_edge_squares_the_mitre():
    # A's top edge is free left of its straight corner and mitred to C right of it: the two
    # cuts would need a step in A's side. The mitre becomes a butt joint (square on A);
    # without repair it is an error that says why
    mesh = t_junction(30.0, left=False)
    ps = panels(mesh, 20.0, gap=10.0, edge="bisector")
    a, c = ps.panels
    assert (a.squared_edges, c.butt_edges) == (1, 1)
    assert a.bevel_deg[2] == pytest.approx(0.0, abs=1e-9)
    assert a.bevel_deg[3] == pytest.approx(0.0, abs=1e-9)
    assert abs(c.bevel_deg[0]) == pytest.approx(30.0)  # the whole fold
    np.testing.assert_allclose(a.top[2:5, 1], 995.0, atol=1e-9)
    np.testing.assert_allclose(a.bottom[2:5, 1], 995.0, atol=1e-9)
    with pytest.raises(PanelError, match=r"face 0: the edges at vertex 3 are collinear and "
                       r"their joints are cut at different angles, .*cut them square or "
                       r"split the face"):
        panels(mesh, 20.0, gap=10.0, edge="bisector", repair=False)


@pytest.mark.parametrize("bend", [2.0, 5.0, 20.0])
def test_a_nearly_straight_corner_between_a_mitre_and_a_free_edge_squares_the_mitre(bend):
    # turned 0.23, 0.57 and 2.3 degrees: the mitre's top line and the free edge's met far
    # along the edge (554 mm at 0.57 degrees, 139 mm at 2.3: 28 and 7 thicknesses), the
    # panel's top reaching 5.4 mm into the mitred joint over that length, no clash said.
    # As at a straight corner the mitre becomes a butt joint: the corner stays at the
    # vertex, half the gap in
    ps = panels(t_junction(30.0, left=False, bend=bend), 20.0, gap=10.0, edge="bisector")
    a, c = ps.panels
    assert (a.squared_edges, c.butt_edges) == (1, 1)
    vertex = np.array([1000.0, 1000.0 + bend])
    for outline in (a.top, a.bottom):
        assert np.linalg.norm(outline[3, :2] - vertex) < 6.0


def test_a_straight_corner_between_a_butt_joint_and_a_mitre_makes_both_butt_joints():
    # B's short edge beside A (5 mm, a chamfer) consumes B's mitre to A, which another
    # repair makes a butt joint: square on B, A cut on B's square plane with the whole
    # fold. Right of A's straight corner A's mitre to C was then cut square on A too,
    # and A's butt joint to B square on both: "cut square on both, the panels overlap by
    # 0.67". C is coplanar with B, so their square planes are one: A takes the whole
    # fold along both, B and C are square
    t = math.tan(math.radians(30.0))
    xyz = np.array([[0, 0, 0], [2000, 0, 0], [2000, 1000, 0], [1000, 1000, 0], [0, 1000, 0],
                    [-5, 1005, 5 * t], [1000, 2000, 1000 * t], [2000, 2000, 1000 * t]])
    mesh = facet.PolyMesh.from_faces(xyz, [[0, 1, 2, 3, 4], [3, 2, 7, 6], [4, 3, 6, 5]])
    for thickness in (8.0, 20.0):
        a, c, b = panels(mesh, thickness, gap=10.0, edge="bisector", min_edge=0.0)
        assert (a.butt_edges, a.squared_edges) == (2, 0)
        assert (b.squared_edges, c.squared_edges, b.butt_edges, c.butt_edges) == (1, 1, 0, 0)
        np.testing.assert_allclose(a.bevel_deg[2:4], [-30.0, -30.0], atol=1e-9)
        np.testing.assert_allclose(b.bevel_deg[0], 0.0, atol=1e-9)
        np.testing.assert_allclose(c.bevel_deg[3], 0.0, atol=1e-9)
        for outline in (a.top, a.bottom):  # A's top edge is one line through the corner
            d = outline[4] - outline[2]
            assert abs(np.cross(d, outline[3] - outline[2])).max() < 1e-6 * np.dot(d, d)
        # butt joints keep the gap
        np.testing.assert_allclose(a.joint_widths[2:4], [10.0, 10.0], rtol=1e-9)
        assert max(p.clash for p in (a, b, c)) == 0.0



def test_a_joint_square_on_both_at_a_straight_corner_says_why():
    # A's edge is free right of its straight corner; left of it B's mitre is consumed by
    # B's chamfer, 7.6 mm long (a butt joint on A), which must then be square on A too, square on
    # both; they overlap on the fold. The error said the mitre "meets the next edge's
    # beyond the nearly straight corner at vertex 3 (180 degrees)": nothing is beyond
    t = math.tan(math.radians(30.0))
    xyz = np.array([[0, 0, 0], [2000, 0, 0], [2000, 1000, 0], [1000, 1000, 0], [0, 1000, 0],
                    [-5, 1005, 5 * t], [1000, 2000, 1000 * t]])
    mesh = facet.PolyMesh.from_faces(xyz, [[0, 1, 2, 3, 4], [4, 3, 6, 5]])
    with pytest.raises(PanelError, match=r"on face 0 it meets a cut of another angle at the "
                       r"straight corner at vertex 3 \(a vertex on a straight edge\), and on "
                       r"face 1 the gap and the bevels consume"):
        panels(mesh, 20.0, gap=10.0, edge="bisector", min_edge=0.0)

def test_a_running_bond_roof_keeps_a_bevel_on_every_folded_joint():
    # rows of panels in running bond on three roof planes (a plan lifted: every row one
    # plane, its joints along two fold lines, each with T-junctions); the top row stops
    # short, so one panel's edge along the upper fold is free beside a mitre, which must
    # be square. Along that straight fold line every joint is then a butt joint (one
    # panel square, the other the whole fold), cut alike at every straight corner; the
    # squaring was passed on as square cuts on both panels: 3 joints of no bevel, open
    # into a wedge across the fold instead of the gap
    xs = {0: [0, 1000, 2000, 3000], 1: [0, 500, 1500, 2500, 3000], 2: [0, 1000, 2000]}
    ys, zs = [0.0, 750.0, 1500.0, 2250.0], [0.0, 300.0, 500.0, 600.0]
    index, xyz, faces = {}, [], []

    def vertex(x, level):
        if (x, level) not in index:
            index[x, level] = len(xyz)
            xyz.append([x, ys[level], zs[level]])
        return index[x, level]

    for row, bounds in xs.items():
        for x0, x1 in zip(bounds[:-1], bounds[1:]):
            below = sorted({x for r in (row - 1, row) if r in xs for x in xs[r]
                            if x0 <= x <= x1 and (r == row or x <= xs[row][-1])})
            above = sorted({x for r in (row, row + 1) if r in xs for x in xs[r]
                            if x0 <= x <= x1 and (r == row or x <= xs[r][-1])}, reverse=True)
            faces.append([vertex(x, row) for x in below] + [vertex(x, row + 1) for x in above])
    mesh = facet.PolyMesh.from_faces(np.array(xyz), faces)
    ps = panels(mesh, 20.0, gap=10.0, edge="bisector")
    assert sum(len(f) > 4 for f in faces) == 7 and max(p.clash for p in ps) == 0.0
    edges = {}
    for p in ps:
        for k, h in enumerate(p.neighbors):
            if h is not None and abs(p.dihedral_deg[k] - 180.0) > 1e-6:
                pair = frozenset((int(p.vertices[k]), int(p.vertices[(k + 1) % len(p.vertices)])))
                edges.setdefault(pair, []).append((abs(p.bevel_deg[k]), 180.0 - p.dihedral_deg[k]))
    assert len(edges) == 10
    for sides in edges.values():  # mitred (half the fold each) or butt (0 and the fold)
        assert sum(b for b, _ in sides) == pytest.approx(abs(sides[0][1]))
    assert sum(p.squared_edges for p in ps) == sum(p.butt_edges for p in ps) == 4
    for p in ps:
        np.testing.assert_allclose([w for w in p.joint_widths if w is not None and w > 0],
                                   10.0, rtol=1e-9)


@pytest.mark.parametrize("grain", [None, (0, 0, 1), (1, 0, 1)])
def test_the_schedules_placement_rebuilds_the_cut_outline_on_the_sheet(grain):
    # with a grain every row said rotation 0 while each part lay turned by its grain angle
    from facet.cutsheets import schedule_rows
    from facet.nest import nest

    ps = panels(cylinder(), 10.0)
    drawings = unfold(ps, grain=grain)
    result = nest({d.id: d.footprint for d in drawings}, (3000, 3000), margin=10, spacing=5,
                  rotations="none" if grain else "90")
    rows = {r["id"]: r for r in schedule_rows(ps, result, drawings)}
    turned = 0
    for p, d in zip(ps, drawings):
        row, placed = rows[p.id], result.placements[p.id].transform(d.cut)
        a = math.radians(row["rotation_deg"])
        turn = np.array([[math.cos(a), math.sin(a)], [-math.sin(a), math.cos(a)]])
        rebuilt = p.flat_bottom @ turn
        assert np.allclose(rebuilt + (row["x"], row["y"]), placed, atol=1e-9 * 3000)
        assert 0 <= row["rotation_deg"] < 360
        turned += abs(d.rotation_deg) > 1e-9
    assert turned == (0 if grain is None else len(ps))


# ---- nesting ---------------------------------------------------------------

def _parts():
    ps = panels(translational(nu=6, nv=5, step=400.0), 18.0, edge="bisector", gap=4)
    return {d.id: d.footprint for d in unfold(ps)}


@pytest.mark.parametrize("rotations", ["none", "90", "free"])
def test_nesting_holds_margin_and_spacing(rotations):
    from facet.nest import nest, verify

    parts = _parts()
    r = nest(parts, (1300, 900), margin=15, spacing=8, rotations=rotations)
    assert not r.unplaced
    assert len(r.placements) == len(parts)
    assert verify(r, parts) == []
    assert 0 < r.utilisation < 1
    assert all(0 < s.utilisation < 1 for s in r.sheets)
    if rotations == "none":
        assert all(pl.angle_deg == 0 for pl in r.placements.values())
    # a tighter check than the nester's own: shrink the margin test
    from shapely.geometry import Polygon
    for pid, pl in r.placements.items():
        placed = Polygon(pl.transform(np.asarray(parts[pid])))
        minx, miny, maxx, maxy = placed.bounds
        assert minx >= 15 - 1e-6 and miny >= 15 - 1e-6
        assert maxx <= 1300 - 15 + 1e-6 and maxy <= 900 - 15 + 1e-6


@pytest.mark.parametrize("mesh, thickness, edge, gap, sheet, margin, spacing, rotations", [
    # footprints with short edges (the bevels' sides seen from above): libnest2d left
    # parts touching, 0 apart for a 3 mm kerf
    ("crossvault_form_planar.obj", 0.05, "bisector", 0.01, (2, 2), 0.02, 0.003, "none"),
])
def test_nesting_of_real_parts_keeps_the_spacing(data_dir, mesh, thickness, edge, gap, sheet,
                                                 margin, spacing, rotations):
    from facet.nest import nest, verify

    ps = panels(facet.read_mesh(data_dir / mesh), thickness, edge=edge, gap=gap)
    parts = {d.id: d.footprint for d in unfold(ps)}
    r = nest(parts, sheet, margin=margin, spacing=spacing, rotations=rotations)
    assert not r.unplaced and sorted(r.placements) == sorted(parts)
    assert verify(r, parts) == []
    assert [s.index for s in r.sheets] == list(range(len(r.sheets)))
    assert sorted(pid for s in r.sheets for pid in s.parts) == sorted(parts)
    assert all(r.placements[pid].sheet == s.index for s in r.sheets for pid in s.parts)


def test_a_part_libnest2d_keeps_misplacing_ends_in_an_error(monkeypatch):
    # the re-nest of crowded parts recursed until Python's recursion limit when the same
    # part kept failing the check
    import facet.nest
    from facet.errors import FacetError

    def always(result, parts, tolerance=None):
        return [(f"part {pid} leaves the sheet less its margin", (pid,))
                for pid in result.placements]

    monkeypatch.setattr(facet.nest, "_problems", always)
    square = {"A": np.array([[0, 0], [100, 0], [100, 100], [0, 100.0]])}
    with pytest.raises(FacetError, match="nesting failed its own check"):
        facet.nest.nest(square, (1000, 1000), margin=10, spacing=5)


@pytest.mark.parametrize("shift", [k / 7.0 for k in range(7)])
def test_a_part_with_a_sloping_side_stays_on_the_sheet(shift):
    # at spacing 0 libnest2d left a parallelogram up to 1.4 of its integer units (4 um on
    # a 3 m sheet) past the sheet's edge: the check refused the nesting and facet panels
    # wrote nothing ("P-R02C05 on sheet 0 leaves the sheet less its margin"), for a
    # 1,128 x 983 mm panel of a translational surface (50 mm, square, gap 20, centred)
    from facet.nest import nest, verify

    unit = 3000.0 / 2 ** 20
    part = {"P": np.array([[10.39571375, 10.0], [1099.61462078, 10.0],
                           [1137.78405224, 993.28621289], [48.56514521, 993.28621289]])
            + shift * unit}
    for margin in (0.0, 10.0):
        r = nest(part, (3000, 2000), margin=margin)
        assert verify(r, part, tolerance=1e-9) == []
        placed = r.placements["P"].transform(part["P"])
        assert placed.min() >= margin - 1e-9


def test_a_part_that_fits_only_turned_is_turned():
    # a 1000 x 2000 panel on a 3000 x 1500 sheet: libnest2d refused it before it tried a
    # quarter turn, so the command said it fit on no sheet
    from facet.nest import nest, verify

    tall = {"T": np.array([[0, 0], [1000, 0], [1000, 2000], [0, 2000.0]])}
    r = nest(tall, (3000, 1500), margin=10, spacing=5, rotations="90")
    assert not r.unplaced and r.placements["T"].angle_deg in (90.0, 270.0)
    assert verify(r, tall) == []
    assert nest(tall, (3000, 1500), margin=10, spacing=5, rotations="none").unplaced == ["T"]


def test_verify_catches_overlap():
    from facet.nest import Placement, nest, verify

    parts = _parts()
    r = nest(parts, (1300, 900), margin=15, spacing=8)
    a, b = list(r.placements)[:2]
    pa = r.placements[a]
    r.placements[b] = Placement(b, pa.sheet, pa.angle_deg, pa.x, pa.y)
    problems = verify(r, parts)
    assert any(a in p and b in p for p in problems)


def test_verify_catches_overlap_without_spacing(data_dir):
    # with no spacing (the default) overlapping parts, 0 apart, passed the check, so they
    # were written overlapping: 42 pairs of heart_planar's square-edged parts, by up to
    # 0.025 m2 (a part is about 0.012 m2)
    from facet.nest import Placement, nest, verify
    from shapely.geometry import Polygon

    parts = _parts()
    r = nest(parts, (1300, 900))
    assert verify(r, parts) == []
    a, b = list(r.placements)[:2]
    pa = r.placements[a]
    r.placements[b] = Placement(b, pa.sheet, pa.angle_deg, pa.x + 1.0, pa.y)
    assert any(a in p and b in p and "overlap" in p for p in verify(r, parts))
    heart = {d.id: d.footprint for d in unfold(panels(
        facet.read_mesh(data_dir / "heart_planar.obj"), 0.005))}
    r = nest(heart, (2.5, 1.25))
    assert verify(r, heart) == [] and not r.unplaced
    placed = {}
    for pid, pl in r.placements.items():
        placed.setdefault(pl.sheet, []).append(Polygon(pl.transform(heart[pid])))
    worst = max(g.intersection(h).area for items in placed.values()
                for i, g in enumerate(items) for h in items[i + 1:])
    assert worst < 1e-9


def test_parts_too_big_are_unplaced_and_bad_sheets_rejected():
    from facet.nest import NestError, nest

    parts = _parts()
    big = {"BIG": np.array([[0, 0], [5000, 0], [5000, 100], [0, 100.0]]), **parts}
    r = nest(big, (1300, 900), margin=15, spacing=8)
    assert r.unplaced == ["BIG"]
    for kwargs in ({"sheet": (0, 100)}, {"sheet": (100, 100), "margin": 60},
                   {"sheet": (100, 100), "spacing": -1}, {"sheet": (100, 100), "rotations": "45"}):
        with pytest.raises(NestError):
            nest(parts, **kwargs)


def test_nesting_progress_cancels():
    from facet.nest import nest

    with pytest.raises(Cancelled):
        nest(_parts(), (1300, 900), progress=lambda d, t: True)


def test_nesting_in_chunks_is_the_same_for_any_number_of_workers(monkeypatch):
    import facet.nest as fn

    parts = _parts()
    monkeypatch.setattr(fn, "_CHUNK", 8)  # 30 parts: 3 chunks and the open sheets
    one = fn.nest(parts, (1300, 900), margin=15, spacing=8, workers=1)
    two = fn.nest(parts, (1300, 900), margin=15, spacing=8, workers=2)
    assert fn.verify(one, parts) == [] and fn.verify(two, parts) == []
    assert not one.unplaced and len(one.placements) == len(parts)
    assert one.placements == two.placements
    assert [s.parts for s in one.sheets] == [s.parts for s in two.sheets]
    seen = []
    with pytest.raises(Cancelled):
        fn.nest(parts, (1300, 900), workers=2, progress=lambda d, t: seen.append(d) or True)
    assert seen and seen[0] < len(parts)
    with pytest.raises(fn.NestError, match="workers"):
        fn.nest(parts, (1300, 900), workers=0)


def test_tight_nesting_regroups_the_least_filled_sheets(monkeypatch):
    """Batches close their sheets before smaller parts come: squares just over half the
    sheet's width stay alone on their sheets beside room for the smaller squares, which
    then pair on sheets of their own. ``tight`` nests the parts of the least-filled
    sheets again together: fewer sheets, every one verified, the same for any number of
    workers; with nothing to gain it keeps the sheets it had."""
    import facet.nest as fn

    def square(a):
        return [(0, 0), (a, 0), (a, a), (0, a)]

    parts = {f"L{k}": square(520 + k) for k in range(20)}
    parts.update({f"S{k}": square(440 + k) for k in range(20)})
    plain = fn.nest(parts, (1000, 700), margin=5, spacing=4, rotations="none", workers=1)
    tight = fn.nest(parts, (1000, 700), margin=5, spacing=4, rotations="none", workers=1,
                    tight=True)
    assert fn.verify(plain, parts) == [] and fn.verify(tight, parts) == []
    assert not tight.unplaced and len(tight.placements) == len(parts)
    assert tight.tight and not plain.tight
    # no two of the larger squares share a sheet (1,040 mm > 990 mm); a larger and a
    # smaller one can
    big = [s for s in plain.sheets if any(pid.startswith("L") for pid in s.parts)]
    assert len(big) == 20
    assert len(tight.sheets) < len(plain.sheets)
    assert len(tight.sheets) >= 20
    assert sum(s.used_area for s in tight.sheets) == pytest.approx(plain.utilisation * len(
        plain.sheets) * 1000 * 700)
    # chunks in workers: the same sheets
    monkeypatch.setattr(fn, "_CHUNK", 16)
    one = fn.nest(parts, (1000, 700), margin=5, spacing=4, workers=1, tight=True)
    two = fn.nest(parts, (1000, 700), margin=5, spacing=4, workers=2, tight=True)
    assert fn.verify(one, parts) == [] and one.placements == two.placements
    # nothing to gain (one part a sheet): the sheets stay
    alone = {k: v for k, v in parts.items() if k.startswith("L")}
    r = fn.nest(alone, (1000, 700), margin=5, spacing=4, workers=1, tight=True)
    assert len(r.sheets) == 20 and fn.verify(r, alone) == []
    with pytest.raises(Cancelled):
        fn.nest(parts, (1000, 700), tight=True, workers=1, progress=lambda d, t: d == t)


# ---- files -----------------------------------------------------------------

def _made(tmp_path, **kw):
    from facet.cli_panels import run_pipeline

    mesh = translational(nu=6, nv=5, step=400.0)
    return run_pipeline(mesh, 18.0, edge="bisector", gap=4, sheet=(1300, 900), margin=15,
                        spacing=8, dxf=str(tmp_path / "cut.dxf"),
                        schedule=str(tmp_path / "schedule.csv"), svg=str(tmp_path / "svg"),
                        png=str(tmp_path / "png"), **kw)


def test_dxf_layers_units_audit_and_outlines(tmp_path):
    import ezdxf

    report, ps, drawings, result = _made(tmp_path)
    doc = ezdxf.readfile(tmp_path / "cut.dxf")
    assert doc.header["$INSUNITS"] == 4
    assert not doc.audit().has_errors
    for layer in ("CUT", "LABEL", "BEVEL", "SHEET", "GRAIN"):
        assert layer in doc.layers
    msp = doc.modelspace()
    cuts = [e for e in msp.query("LWPOLYLINE[layer=='CUT']")]
    assert len(cuts) == len(ps)
    assert all(c.closed for c in cuts)
    labels = {e.dxf.text: e for e in msp.query("TEXT[layer=='LABEL']")}
    assert set(labels) == {p.id for p in ps}
    sheets = msp.query("LWPOLYLINE[layer=='SHEET']")
    assert len(sheets) == len(result.sheets)
    # every CUT outline is a placed part's outline, point for point
    from facet.cutsheets import sheet_origins

    origins = sheet_origins(result)
    by_id = {d.id: d for d in drawings}
    expected = []
    for pid, pl in result.placements.items():
        expected.append(pl.transform(by_id[pid].cut) + origins[pl.sheet])
    got = [np.array([(x, y) for x, y, *_ in c.get_points()]) for c in cuts]
    for e in expected:
        assert any(g.shape == e.shape and np.allclose(g, e, atol=1e-9) for g in got)
    assert msp.query("TEXT[layer=='BEVEL']")


def test_the_top_outline_is_a_reference_layer_of_its_own(tmp_path):
    """The top face's outline (a closed contour that crosses the cut outline where a
    bevel leans out) lay on BEVEL with the bevel angles to engrave: mapping BEVEL to
    engraving engraved it too. It is on TOP now, dashed by layer, and BEVEL holds texts
    only; every layer says in the file what it holds."""
    import ezdxf
    from shapely.geometry import Polygon

    from facet.cutsheets import LAYERS, sheet_origins

    report, ps, drawings, result = _made(tmp_path)
    doc = ezdxf.readfile(tmp_path / "cut.dxf")
    msp = doc.modelspace()
    assert {e.dxftype() for e in msp.query("*[layer=='BEVEL']")} == {"TEXT"}
    for name in LAYERS:
        assert doc.layers.get(name).description  # (what it is for, for the fabricator)
    assert doc.layers.get("TOP").dxf.linetype == "FACET_DASHED"
    tops = list(msp.query("LWPOLYLINE[layer=='TOP']"))
    origins = sheet_origins(result)
    by_id = {d.id: d for d in drawings}
    expected = [result.placements[pid].transform(by_id[pid].top)
                + origins[result.placements[pid].sheet]
                for pid in result.placements
                if not np.allclose(by_id[pid].top, by_id[pid].cut, atol=1e-6)]
    assert len(tops) == len(expected) > 0
    got = [np.array([(x, y) for x, y, *_ in t.get_points()]) for t in tops]
    assert all(t.closed and t.dxf.linetype == "BYLAYER" for t in tops)
    for e in expected:
        assert any(g.shape == e.shape and np.allclose(g, e, atol=1e-9) for g in got)
    # (the reason it must not be cut: it crosses the cut outline)
    cuts = [Polygon([(x, y) for x, y, *_ in c.get_points()])
            for c in msp.query("LWPOLYLINE[layer=='CUT']")]
    assert any(not any(c.contains(Polygon(g)) for c in cuts) for g in got)


def test_the_sheets_of_one_dxf_lie_in_rows_read_like_pages(tmp_path):
    """The sheets of a run lay in one row: 161 sheets 3000 mm wide were a line 483 m long
    in the DXF (and the FreeCAD CutSheets' Shape), a thin line to whoever viewed it all.
    They lie in rows now, the whole about as wide as high; each sheet's name under it,
    clear of the others; numbered as a book's pages are read (left to right, row under
    row), and every part inside the sheet its name says it is on."""
    import ezdxf
    from shapely.geometry import Point, Polygon, box

    from facet.cli_panels import run_pipeline

    _, ps, drawings, result = run_pipeline(
        translational(nu=8, nv=5, step=400.0), 18.0, sheet=(900, 500), margin=5, spacing=8,
        dxf=str(tmp_path / "cut.dxf"))
    count = len(result.sheets)
    assert count >= 20
    msp = ezdxf.readfile(tmp_path / "cut.dxf").modelspace()
    rects = [Polygon(e.get_points("xy")) for e in msp.query("LWPOLYLINE[layer=='SHEET']")]
    assert len(rects) == count
    lo = np.min([r.bounds[:2] for r in rects], axis=0)
    hi = np.max([r.bounds[2:] for r in rects], axis=0)
    assert 0.5 <= (hi - lo)[0] / (hi - lo)[1] <= 2.0
    # each sheet's name: under its sheet, nearer it than any other
    named = {}
    for t in msp.query("TEXT[layer=='SHEET']"):
        where = Point(t.dxf.align_point.x, t.dxf.align_point.y)
        (number,) = re.fullmatch(r"SHEET (\d+)", t.dxf.text).groups()
        sheet = min(rects, key=where.distance)
        x0, y0, x1, _ = sheet.bounds
        assert x0 < where.x < x1 and where.y < y0, t.dxf.text
        named[int(number)] = sheet
    assert sorted(named) == list(range(1, count + 1))
    assert len({id(r) for r in named.values()}) == count
    for k in range(1, count):  # (left to right, then the next row down, on its left)
        a, b = named[k].bounds, named[k + 1].bounds
        assert (b[1] == a[1] and b[0] > a[2]) or (b[3] < a[1] and b[0] < a[0]), k
    for a in rects:
        grown = box(*a.bounds).buffer(0.05 * 500)  # (with its name under it)
        assert sum(grown.intersects(b) for b in rects) == 1
    # each part (its ID and its cut outline) on the sheet its placement says
    cuts = [Polygon(e.get_points("xy")) for e in msp.query("LWPOLYLINE[layer=='CUT']")]
    labels = list(msp.query("TEXT[layer=='LABEL']"))
    assert len(labels) == len(cuts) == len(result.placements)
    for t in labels:
        where = Point(t.dxf.align_point.x, t.dxf.align_point.y)
        (cut,) = [c for c in cuts if c.contains(where)]
        assert named[result.placements[t.dxf.text].sheet + 1].contains(cut), t.dxf.text


@pytest.mark.parametrize("units, mm", [("mm", 1.0), ("m", 1000.0), ("in", 25.4)])
def test_the_dxf_opens_on_its_sheets_and_its_dashes_read_as_dashes(tmp_path, units, mm):
    """The DXF left $EXTMIN/$EXTMAX unset (+-1e20) and its view a window 1000 units high at
    the origin (sheets in metres showed as a dot), and its dashes were 1.27 drawing units
    long whatever the units: 1.27 mm on parts a metre wide, 1.27 m on parts 20 cm wide,
    both a continuous line to the eye."""
    import ezdxf

    from facet.cutsheets import write_dxf

    _, ps, drawings, result = _made(tmp_path)
    path = tmp_path / f"cut_{units}.dxf"
    write_dxf(path, result, drawings, units=units)  # (the same numbers in other units)
    doc = ezdxf.readfile(path)
    msp = doc.modelspace()
    lo, hi = np.array(doc.header["$EXTMIN"])[:2], np.array(doc.header["$EXTMAX"])[:2]
    points = np.array([(x, y) for e in msp.query("LWPOLYLINE") for x, y, *_ in e.get_points()])
    assert (points >= lo - 1e-9).all() and (points <= hi + 1e-9).all()
    span = points.max(axis=0) - points.min(axis=0)
    assert (hi - lo <= 1.2 * span).all()  # (the sheets and their names, no more)
    (view,) = doc.viewports.get("*Active")
    assert np.allclose(np.array(view.dxf.center)[:2], 0.5 * (lo + hi))
    assert view.dxf.height >= hi[1] - lo[1]
    dashed = doc.linetypes.get(doc.layers.get("TOP").dxf.linetype)
    dash = max(tag.value for tag in dashed.pattern_tags.tags if tag.code == 49)
    scale = doc.header.get("$LTSCALE", 1.0)
    assert 5.0 <= dash * scale * mm <= 50.0  # millimetres


def test_schedule_csv_and_json(tmp_path):
    report, ps, drawings, result = _made(tmp_path)
    rows = list(csv.DictReader(open(tmp_path / "schedule.csv", encoding="utf-8")))
    assert len(rows) == len(ps)
    first = rows[0]
    p = ps.by_id(first["id"])
    assert float(first["area_mm2"]) == p.area  # repr round-trips exactly
    assert [float(x) for x in first["bevel_deg"].split(";")] == p.bevel_deg
    assert int(first["sheet"]) == result.placements[p.id].sheet + 1
    assert float(first["thickness_mm"]) == 18.0
    from facet.cutsheets import schedule_rows, write_schedule_json

    write_schedule_json(tmp_path / "s.json", schedule_rows(ps, result))
    data = json.load(open(tmp_path / "s.json"))
    assert data["panels"][0]["id"] == first["id"]
    svgs = sorted((tmp_path / "svg").glob("*.svg"))
    pngs = sorted((tmp_path / "png").glob("*.png"))
    assert len(svgs) == len(pngs) == len(result.sheets)
    w, h = result.sheet_size
    assert f'width="{w:.10g}mm" height="{h:.10g}mm"' in svgs[0].read_text()
    assert pngs[0].read_bytes()[:4] == b"\x89PNG"
    turned, counts = _svg_holds_what_the_dxf_holds(svgs, tmp_path / "cut.dxf", result)
    assert turned > 0  # the nesting turned some parts
    assert counts["BEVEL"] > len(ps) and counts["TOP"] == len(ps)  # (mitred: every part)


def test_previews_draw_the_grain(tmp_path):
    _, ps, _, result = _made(tmp_path, grain=(0.0, 0.0, 1.0))
    svgs = sorted((tmp_path / "svg").glob("*.svg"))
    _, counts = _svg_holds_what_the_dxf_holds(svgs, tmp_path / "cut.dxf", result)
    assert counts["GRAIN"] == 3 * len(ps)  # (a shaft and two barbs a part)


def test_png_texts_are_as_tall_as_the_dxfs(tmp_path, monkeypatch):
    """The PNG previews drew each text at a font size of its DXF height, so its capitals
    were 0.73 of the DXF's (a font size is an em) and its middle at half the lower-case
    letters' height: now the capitals are as tall, their middle on the DXF's point."""
    import ezdxf
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.axes import Axes

    from facet.cutsheets import OUTLINE_FONT, sheet_origins, write_png

    _, ps, drawings, result = _made(tmp_path)
    drawn = []
    text = Axes.text

    def recorded(ax, x, y, s, **kw):
        (x0, y0), (x1, _) = ax.transData.transform([(0.0, 0.0), (1.0, 0.0)])
        points = (x1 - x0) * 72.0 / ax.figure.dpi  # points per model unit
        drawn.append((len(drawn_sheets) - 1, s, x, y, kw, points))
        return text(ax, x, y, s, **kw)

    drawn_sheets = []
    monkeypatch.setattr(Axes, "text", recorded)
    write_png(tmp_path / "png", result, drawings,
              progress=lambda done, total: drawn_sheets.append(done) and False)
    cap = _cap_height_in_ems(OUTLINE_FONT)
    origins = np.array(sheet_origins(result))
    w, h = result.sheet_size
    dxf = {}
    for e in ezdxf.readfile(tmp_path / "cut.dxf").modelspace().query("TEXT[layer!='SHEET']"):
        at = np.array([e.dxf.align_point.x, e.dxf.align_point.y])
        (k,) = np.flatnonzero(np.all((origins <= at) & (at <= origins + (w, h)), axis=1))
        dxf.setdefault((k, e.dxf.text), []).append(e)
    assert len(drawn) == sum(map(len, dxf.values())) > len(ps)
    for k, s, x, y, kw, points in drawn:
        assert kw["va"] == "baseline" and kw["ha"] == "center"
        height = kw["fontsize"] / points * cap  # the capitals', in model units
        turn = np.radians(kw["rotation"])
        cx, cy = x - 0.5 * height * np.sin(turn), y + 0.5 * height * np.cos(turn)
        (same,) = [e for e in dxf[(k, s)]
                   if abs(e.dxf.align_point.x - origins[k][0] - cx) < 1e-6
                   and abs(e.dxf.align_point.y - origins[k][1] - cy) < 1e-6]
        assert height == pytest.approx(same.dxf.height, rel=1e-9)
        assert kw["rotation"] == pytest.approx(same.dxf.rotation, abs=1e-9)


def _cap_height_in_ems(family):
    """The height of the font's "H" in ems, read from the font file that matplotlib
    finds for ``family`` (it ships DejaVu Sans)."""
    from matplotlib import font_manager, ft2font

    font = ft2font.FT2Font(font_manager.findfont(family, fallback_to_default=False))
    glyph = font.load_char(ord("H"), flags=ft2font.LOAD_NO_SCALE)
    return glyph.bbox[3] / font.units_per_EM


def _svg_holds_what_the_dxf_holds(svgs, dxf_path, result):
    """Each SVG preview is its sheet of the DXF: a layer (an Inkscape layer, a group) for
    each DXF layer, with the same outlines (CUT, TOP), grain arrows and texts (LABEL,
    BEVEL: the same text, its capitals as tall and centred at the same place, turned the
    same way). The previews drew the IDs alone: no bevel angle, no top outline, no grain;
    then their texts 0.73 of the DXF's height (a font size is an em, not a capital)."""
    import re
    import xml.etree.ElementTree as ET

    import ezdxf

    from facet.cutsheets import OUTLINE_FONT, sheet_origins

    svg_ns = "{http://www.w3.org/2000/svg}"
    ink = "{http://www.inkscape.org/namespaces/inkscape}"
    msp = ezdxf.readfile(dxf_path).modelspace()
    cap_height = _cap_height_in_ems(OUTLINE_FONT)
    origins = np.array(sheet_origins(result))
    size = np.array(result.sheet_size)

    def on_sheet(k, points):  # (n, 2) -> whether each lies on sheet k
        return np.all((points >= origins[k] - 1e-9) & (points <= origins[k] + size + 1e-9),
                      axis=1)

    turned = 0
    counts = {"TOP": 0, "BEVEL": 0, "GRAIN": 0}
    for k, svg in enumerate(svgs):
        root = ET.parse(svg).getroot()
        layers = {g.get("id"): g for g in root.findall(f"{svg_ns}g")}
        assert all(g.get(f"{ink}groupmode") == "layer" and g.get(f"{ink}label") == name
                   for name, g in layers.items())
        for name in ("CUT", "TOP"):
            def ordered(rings):
                return sorted(rings, key=lambda r: tuple(np.round(r.mean(axis=0), 6)))

            rings = [np.array(e.get_points("xy"))
                     for e in msp.query(f"LWPOLYLINE[layer=='{name}']")]
            rings = ordered([r - origins[k] for r in rings if on_sheet(k, r).all()])
            paths = [] if name not in layers else layers[name].findall(f"{svg_ns}path")
            got = ordered([np.array([[float(v) for v in xy.split()]
                                     for xy in p.get("d")[2:-2].split(" L ")])
                           for p in paths])
            assert len(got) == len(rings), (svg.name, name)
            assert all(np.allclose(a, b, rtol=0, atol=1e-9) for a, b in zip(got, rings))
            counts["TOP"] += len(got) if name == "TOP" else 0
        lines = [] if "GRAIN" not in layers else layers["GRAIN"].findall(f"{svg_ns}line")
        dxf_lines = [e for e in msp.query("LINE[layer=='GRAIN']")
                     if on_sheet(k, np.array([(e.dxf.start.x, e.dxf.start.y)]))[0]]
        assert len(lines) == len(dxf_lines)
        counts["GRAIN"] += len(lines)
        for name in ("LABEL", "BEVEL"):
            dxf = {}
            for e in msp.query(f"TEXT[layer=='{name}']"):
                if on_sheet(k, np.array([(e.dxf.align_point.x, e.dxf.align_point.y)]))[0]:
                    dxf.setdefault(e.dxf.text, []).append(e)
            texts = list(layers[name].iter(f"{svg_ns}text")) if name in layers else []
            assert len(texts) == sum(map(len, dxf.values())), (svg.name, name)
            for text in texts:
                x, y = float(text.get("x")), float(text.get("y"))
                rotate = float(re.fullmatch(r"scale\(1 -1\) rotate\((\S+) (\S+) (\S+)\)",
                                            text.get("transform")).group(1))
                # its capitals as tall as the DXF's (a DXF height is theirs, a font size
                # the em's), their middle at the DXF's middle-centre point
                cap = float(text.get("font-size")) * cap_height
                turn = np.radians(-rotate)
                cx, cy = x - 0.5 * cap * np.sin(turn), -y + 0.5 * cap * np.cos(turn)
                (same,) = [e for e in dxf[text.text]
                           if abs(e.dxf.align_point.x - origins[k][0] - cx) < 1e-9
                           and abs(e.dxf.align_point.y - origins[k][1] - cy) < 1e-9]
                assert rotate == pytest.approx(-same.dxf.rotation, abs=1e-9)
                assert cap == pytest.approx(same.dxf.height)
                turned += name == "LABEL" and same.dxf.rotation != 0.0
                counts["BEVEL"] += name == "BEVEL"
    return turned, counts


def test_sheets_of_an_earlier_longer_run_are_removed(tmp_path):
    # run 1 on small sheets, run 2 on large ones into the same names: run 1's extra
    # numbered sheets stayed, and their parts would be cut twice
    from facet.cli_panels import run_pipeline

    mesh = translational(nu=6, nv=5, step=400.0)
    names = dict(dxf=str(tmp_path / "cut.dxf"), per_sheet=True, svg=str(tmp_path / "svg"),
                 png=str(tmp_path / "png"))
    (tmp_path / "cut_99.dxf").write_text("not ours\n")  # not in the run's sequence: kept
    _, _, _, first = run_pipeline(mesh, 18.0, sheet=(1300, 900), margin=15, spacing=8, **names)
    _, _, _, second = run_pipeline(mesh, 18.0, sheet=(4000, 3000), margin=15, spacing=8, **names)
    assert len(first.sheets) > len(second.sheets) >= 1
    count = len(second.sheets)
    assert sorted(p.name for p in tmp_path.glob("cut_*.dxf")) == (
        [f"cut_{k:02d}.dxf" for k in range(1, count + 1)] + ["cut_99.dxf"])
    assert len(list((tmp_path / "svg").iterdir())) == len(list((tmp_path / "png").iterdir())) \
        == count


def test_sheet_files_past_99_sort_as_the_sheets_go(tmp_path):
    """A run of 100 sheets or more numbers its files with as many digits as the last
    ("sheet_001" ... "sheet_110"): with two, "sheet_100" sorted before "sheet_11" in a
    listing. An earlier run numbered with two digits is removed as stale, as a longer
    run's extra sheets are."""
    from facet.cli_panels import run_pipeline

    mesh = translational(nu=11, nv=10, step=400.0)  # 110 panels, one per sheet
    svg = tmp_path / "svg"
    _, _, _, few = run_pipeline(mesh, 18.0, sheet=(4000, 3000), margin=15, spacing=8,
                                svg=str(svg), dxf=str(tmp_path / "cut.dxf"), per_sheet=True)
    assert 1 < len(few.sheets) < 10 and (svg / "sheet_01.svg").exists()
    _, _, _, many = run_pipeline(mesh, 18.0, sheet=(600, 600), margin=5, spacing=8,
                                 svg=str(svg), dxf=str(tmp_path / "cut.dxf"), per_sheet=True)
    count = len(many.sheets)
    assert count >= 100
    names = sorted(path.name for path in svg.iterdir())
    assert names == [f"sheet_{k:03d}.svg" for k in range(1, count + 1)]
    assert sorted(p.name for p in tmp_path.glob("cut_*.dxf")) == [
        f"cut_{k:03d}.dxf" for k in range(1, count + 1)]
    # the listing's order is the sheets': each file's title names its sheet (and its one
    # part as one: it said "1 parts")
    for name in names[:12] + names[98:102]:
        number = int(name[6:9])
        assert f"<title>sheet {number}: 1 part, " in (svg / name).read_text()


def test_a_failed_preview_leaves_no_temporary_file(tmp_path, monkeypatch):
    import matplotlib.figure

    from facet.cli_panels import run_pipeline

    def interrupted(self, fname, *args, **kwargs):
        with open(fname, "wb") as half:  # Ctrl+C half way through writing the preview
            half.write(b"\x89PNG")
        raise KeyboardInterrupt

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", interrupted)
    with pytest.raises(KeyboardInterrupt):
        run_pipeline(translational(nu=3, nv=2, step=400.0), 18.0, sheet=(1300, 900),
                     png=str(tmp_path / "png"))
    assert list((tmp_path / "png").iterdir()) == []


# ---- command line ----------------------------------------------------------

def test_cli_panels_report(facet_command, tmp_path):
    from facet import write_mesh

    mesh_path = tmp_path / "t.obj"
    write_mesh(translational(nu=6, nv=5, step=400.0), mesh_path)
    done = facet_command("panels", mesh_path, "--thickness", "18", "--edge", "bisector",
                         "--gap", "4", "--sheet", "1300x900", "--margin", "15", "--spacing",
                         "8", "--dxf", tmp_path / "o.dxf", "--schedule", tmp_path / "o.csv",
                         "--report", tmp_path / "r.json")
    assert done.returncode == 0, done.stderr
    r = json.load(open(tmp_path / "r.json"))
    for key in ("panels", "sheets", "unplaced", "utilisation", "max_node_deviation", "seconds"):
        assert key in r
    assert len(r["panels"]) == 30 and r["unplaced"] == []
    assert set(r["seconds"]) >= {"panels", "unfold", "nest", "dxf", "schedule"}
    assert (tmp_path / "o.dxf").exists()


def _gaps(result, drawings):
    """The least distance between two parts on one sheet, and from a part to its sheet's
    edge, of a nested run."""
    from shapely.geometry import Polygon

    by_id = {d.id: d for d in drawings}
    w, h = result.sheet_size
    placed = {}
    for pid, pl in result.placements.items():
        placed.setdefault(pl.sheet, []).append(Polygon(pl.transform(by_id[pid].footprint)))
    between = min(a.distance(b) for polys in placed.values()
                  for i, a in enumerate(polys) for b in polys[:i])
    edge = min(min(x0, y0, w - x1, h - y1) for polys in placed.values()
               for x0, y0, x1, y1 in (p.bounds for p in polys))
    return between, edge


def test_cli_panels_default_margin_and_spacing(facet_command, tmp_path):
    """Without --margin and --spacing the command nested parts 0 apart and up to the
    sheet's edge: neighbours shared a cut line, and a kerf took its width from both, while
    FreeCAD's cut sheets kept 10 and 6 mm. Both now default to 10 mm and 6 mm, in the
    mesh's units."""
    from facet import write_mesh
    from facet.cli_panels import run_pipeline
    from facet.nest import DEFAULT_MARGIN_MM, DEFAULT_SPACING_MM

    mm = translational(nu=6, nv=5, step=400.0)
    report, _, drawings, result = run_pipeline(mm, 18.0, sheet=(1300, 900))
    assert (report["options"]["margin"], report["options"]["spacing"]) == (
        DEFAULT_MARGIN_MM, DEFAULT_SPACING_MM) == (10.0, 6.0)
    between, edge = _gaps(result, drawings)
    assert between >= 6.0 - 1e-6 and edge >= 10.0 - 1e-6
    # the same in metres, through the command line
    metres = facet.PolyMesh(mm.vertices / 1000.0, mm.face_start, mm.face_vertices)
    write_mesh(metres, tmp_path / "m.obj")
    done = facet_command("panels", tmp_path / "m.obj", "--thickness", "0.018", "--units", "m",
                         "--sheet", "1.3x0.9", "--report", tmp_path / "r.json")
    assert done.returncode == 0, done.stderr
    options = json.load(open(tmp_path / "r.json"))["options"]
    assert (options["margin"], options["spacing"]) == pytest.approx((0.01, 0.006), rel=1e-12)
    # and a spacing of 0 is still there to be asked for (parts sharing a cut line)
    report = run_pipeline(mm, 18.0, sheet=(1300, 900), margin=0, spacing=0)[0]
    assert (report["options"]["margin"], report["options"]["spacing"]) == (0, 0)


def test_schedule_gives_each_panel_its_volume_and_mass(facet_command, tmp_path):
    """The schedule had no volume (area times thickness is not a mitred panel's) and no
    mass, which a fabricator needs for handling, transport and cranes. It now gives each
    panel's volume, and its mass from --density (kg/m³) in any units; the summary gives
    the total and the heaviest panel."""
    from facet import write_mesh
    from facet.cli_panels import run_pipeline
    from facet.errors import InputError

    mm = translational(nu=4, nv=3, step=400.0)
    report, ps, _, _ = run_pipeline(mm, 18.0, edge="bisector", gap=4, density=2500.0,
                                    schedule=str(tmp_path / "s.csv"))
    rows = list(csv.DictReader(open(tmp_path / "s.csv", encoding="utf-8")))
    volumes = np.array([float(r["volume_mm3"]) for r in rows])
    assert volumes == pytest.approx([p.volume for p in ps.panels], rel=1e-15)
    # mitred: not area x thickness
    assert not np.allclose(volumes, [18.0 * float(r["area_mm2"]) for r in rows], rtol=1e-3)
    masses = np.array([float(r["mass_kg"]) for r in rows])
    assert masses == pytest.approx(volumes * 1e-9 * 2500.0, rel=1e-12)
    assert report["total_mass_kg"] == pytest.approx(masses.sum(), rel=1e-12)
    k = int(np.argmax(masses))
    assert report["heaviest_panel"] == {"id": rows[k]["id"], "mass_kg": masses[k]}
    # the same panels in metres weigh the same
    metres = facet.PolyMesh(mm.vertices / 1000.0, mm.face_start, mm.face_vertices)
    write_mesh(metres, tmp_path / "m.obj")
    done = facet_command("panels", tmp_path / "m.obj", "--thickness", "0.018", "--gap",
                         "0.004", "--edge", "bisector", "--units", "m", "--density", "2500",
                         "--schedule", tmp_path / "m.json")
    assert done.returncode == 0, done.stderr
    in_metres = json.load(open(tmp_path / "m.json"))
    assert in_metres["meta"]["density"] == 2500.0
    assert [r["mass_kg"] for r in in_metres["panels"]] == pytest.approx(masses, rel=1e-9)
    assert (f"mass          {masses.sum():,.1f} kg in all at 2500 kg/m³, the heaviest "
            f"{rows[k]['id']} {masses[k]:,.1f} kg") in done.stdout
    # without a density: volumes, and no mass
    run_pipeline(mm, 18.0, schedule=str(tmp_path / "n.csv"))
    rows = list(csv.DictReader(open(tmp_path / "n.csv", encoding="utf-8")))
    assert all(float(r["volume_mm3"]) > 0 and r["mass_kg"] == "" for r in rows)
    for bad in (0.0, -2500.0, float("nan"), float("inf")):
        with pytest.raises(InputError, match="density"):
            run_pipeline(mm, 18.0, density=bad, schedule=str(tmp_path / "bad.csv"))
    assert not (tmp_path / "bad.csv").exists()


def test_cli_panels_in_metres(facet_command, tmp_path):
    # a facade modelled in metres: the DXF said millimetres ($INSUNITS 4) and the STEP was
    # written as if its metres were millimetres, parts a thousandth of their size, unsaid
    import ezdxf

    from facet import write_mesh

    freecad_step()
    mm = translational(nu=3, nv=2, step=400.0)
    metres = facet.PolyMesh(mm.vertices / 1000.0, mm.face_start, mm.face_vertices)
    write_mesh(metres, tmp_path / "m.obj")
    common = ["--edge", "bisector", "--sheet", "1.3x0.9", "--dxf", tmp_path / "o.dxf",
              "--step", tmp_path / "o.step", "--report", tmp_path / "r.json",
              "--svg", tmp_path / "svg"]
    done = facet_command("panels", tmp_path / "m.obj", "--thickness", "0.018", "--gap",
                         "0.004", "--units", "m", *common)
    assert done.returncode == 0, done.stderr
    assert "units" not in done.stderr
    doc = ezdxf.readfile(tmp_path / "o.dxf")
    assert doc.header["$INSUNITS"] == 6 and doc.header["$MEASUREMENT"] == 1
    assert json.load(open(tmp_path / "r.json"))["units"] == "m"
    # the SVG previews at true size: a 1.3 x 0.9 m sheet is 1300 x 900 mm (it was 1000
    # pixels wide whatever the sheet and unit)
    import xml.etree.ElementTree as ET

    root = ET.parse(sorted((tmp_path / "svg").glob("*.svg"))[0]).getroot()
    assert (root.get("width"), root.get("height"), root.get("viewBox")) == (
        "1300mm", "900mm", "0 0 1.3 0.9")
    import Part

    shape = Part.read(str(tmp_path / "o.step"))  # (STEP in millimetres)
    box = shape.BoundBox
    assert box.XLength == pytest.approx(np.ptp(mm.vertices[:, 0]), rel=0.05)
    assert shape.Volume == pytest.approx(sum(s.Volume for s in shape.Solids))
    assert shape.Volume > 0.9 * 18.0 * 1200.0 * 800.0
    # the same mesh cut as millimetres (the default) is said to be the wrong size
    done = facet_command("panels", tmp_path / "m.obj", "--thickness", "0.018", "--gap", "0",
                         *common[:2])
    assert done.returncode == 0, done.stderr
    assert "edges are 0.429 mm long on average, taking the mesh to be in mm" in done.stderr
    # with the default joint (6 mm) its 0.4 mm panels vanish: the error, which named a face
    # and a gap of 6, says the units too
    done = facet_command("panels", tmp_path / "m.obj", "--thickness", "0.018", *common[:2])
    assert done.returncode == 2
    assert re.search(r"face \d+: the gap 6 mm leaves fewer than three edges .*; the panels' "
                     r"edges are 0\.429 mm long on average, taking the mesh to be in mm "
                     r"\(--units\)", done.stderr), done.stderr


@pytest.mark.parametrize("args, text", [
    (["--thickness", "0"], "thickness"),
    (["--thickness", "-3"], "thickness"),
    (["--thickness", "10", "--gap", "9000"], "gap"),
    (["--thickness", "10", "--sheet", "0x10"], "sheet"),
    (["--thickness", "10", "--dxf", "x.dxf"], "--sheet"),
])
def test_cli_panels_bad_input_exit_2(facet_command, tmp_path, args, text):
    from facet import write_mesh

    mesh_path = tmp_path / "t.obj"
    write_mesh(translational(), mesh_path)
    done = facet_command("panels", mesh_path, *args)
    assert done.returncode == 2, (done.stdout, done.stderr)
    assert text in done.stderr
    assert "Traceback" not in done.stderr


def test_grid_ids_on_a_mesh_that_is_no_grid_say_what_it_has(facet_command, tmp_path):
    """`--ids grid` on a hexagonal or mixed mesh said "ids='grid' but the mesh is not a
    regular quad grid": the Python keyword on the command line, and neither the file nor
    what the mesh has. It names the file, the option as the user gives it, the faces by
    kind (or, all quads, that they are no complete grid) and the choices that work."""
    from facet import write_mesh

    mixed = facet.PolyMesh.from_faces(
        np.array([[0, 0, 0], [2, 0, 0], [3, 1, 0], [2, 2, 0], [0, 2, 0], [4, 2, 0.0]]),
        [[0, 1, 2, 3, 4], [2, 5, 3]])
    write_mesh(mixed, tmp_path / "mixed.obj")
    done = facet_command("panels", tmp_path / "mixed.obj", "--thickness", "0.01", "--gap",
                         "0", "--ids", "grid")
    assert done.returncode == 2, (done.stdout, done.stderr)
    assert ("mixed.obj: --ids grid (part IDs by row and column) needs a mesh of quads in "
            "complete rows and columns, and it has 1 triangle, 1 pentagon: choose auto or "
            "index") in done.stderr, done.stderr
    # quads in an L: three of the 2 x 2 grid's four
    ell = facet.PolyMesh.from_faces(
        np.array([[x, y, 0.0] for y in range(3) for x in range(3)]),
        [[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6]])
    with pytest.raises(PanelError, match=r"^ids grid .*, and its 3 quads are not in complete "
                                         r"rows and columns: choose auto or index$"):
        panels(ell, 0.01, gap=0, ids="grid")
    assert panels(ell, 0.01, gap=0).id_scheme == "index"


def test_step_says_clearly_when_freecad_is_missing(monkeypatch):
    import facet.step as step

    monkeypatch.setitem(sys.modules, "FreeCAD", None)
    monkeypatch.setattr(step, "_CANDIDATES", ())
    monkeypatch.delenv("FREECAD_LIB", raising=False)
    with pytest.raises(step.FreeCADMissing, match="STEP export needs FreeCAD") as info:
        step.import_freecad()
    assert "\n" not in str(info.value)
    assert not isinstance(info.value, facet.InputError)  # exit 1 on the command line, not 2


def test_panel_solids_are_valid_closed_polyhedra_in_chunks(monkeypatch):
    step = freecad_step()
    ps = panels(translational(nu=6, nv=5, step=400.0), 18.0, edge="bisector", gap=4)
    monkeypatch.setattr(step, "_SOLID_CHUNK", 7)  # 30 panels: 5 texts read
    seen = []
    solids = step.panel_solids(ps, progress=lambda d, t: seen.append(d) and False)
    assert [i for i, _ in solids] == [p.id for p in ps.panels]
    assert seen == [7, 14, 21, 28, 30]
    for (_, s), p in zip(solids, ps.panels):
        k = len(p.top)
        assert s.isValid() and s.ShapeType == "Solid"
        assert len(s.Faces) == k + 2 and len(s.Edges) == 3 * k and len(s.Vertexes) == 2 * k
        assert s.Shells[0].isClosed()
        assert s.Volume == pytest.approx(p.volume, rel=1e-9)  # positive: faces point out
        corners = sorted((round(v.X, 6), round(v.Y, 6), round(v.Z, 6)) for v in s.Vertexes)
        assert corners == sorted(tuple(round(float(c), 6) for c in q)
                                 for q in np.vstack([p.top, p.bottom]))
    fast = step.panel_solids(ps, brepcheck=False)
    assert [s.Volume for _, s in fast] == [s.Volume for _, s in solids]
    with pytest.raises(Cancelled):
        step.panel_solids(ps, progress=lambda d, t: True)


def test_panel_solids_at_map_coordinates_in_millimetres():
    # a facade at UTM-like coordinates in mm (E 512 km, N 5,712 km): every solid failed
    # BRepCheck ("its solid is not valid"), since 1e-7 mm is below the coordinates' last place
    step = freecad_step()
    mesh = translational(nu=4, nv=3, step=1000.0)
    far = facet.PolyMesh(mesh.vertices + (512345678.0, 5712345678.0, 100000.0),
                         mesh.face_start, mesh.face_vertices)
    near_ps, far_ps = (panels(m, 8.0, edge="bisector", gap=6) for m in (mesh, far))
    solids = step.panel_solids(far_ps)
    for (_, s), (_, n), p in zip(solids, step.panel_solids(near_ps), far_ps.panels):
        assert s.isValid() and s.Shells[0].isClosed()
        assert s.Volume == pytest.approx(n.Volume, rel=1e-6)
        assert s.BoundBox.XMin > 5e8


def test_panel_solids_of_reversed_rings_still_face_outwards():
    step = freecad_step()
    ps = panels(translational(nu=3, nv=2, step=400.0), 18.0, edge="bisector", gap=4)
    p = ps.panels[0]
    a = step.panel_solid(p)
    p.top, p.bottom = p.top[::-1].copy(), p.bottom[::-1].copy()
    b = step.panel_solid(p)
    assert b.isValid() and a.Volume > 0
    assert b.Volume == pytest.approx(a.Volume, rel=1e-12)


@pytest.mark.parametrize("spoil, message", [
    (lambda t, b: t.__setitem__((0, 2), t[0, 2] + 5.0), "is not planar"),
    (lambda t, b: t.__setitem__(0, np.nan), "a corner is not finite"),
    (lambda t, b: b.__setitem__(slice(None), t), "edge 8 of its solid has no length"),
])
def test_panel_solids_refuse_outlines_that_bound_no_solid(spoil, message):
    step = freecad_step()
    ps = panels(translational(nu=3, nv=2, step=400.0), 18.0)
    p = ps.panels[4]
    top, bottom = p.top.copy(), p.bottom.copy()
    spoil(top, bottom)
    p.top, p.bottom = top, bottom
    with pytest.raises(step.SolidError, match=message) as info:
        step.panel_solids(ps)
    assert str(info.value).startswith(f"panel {p.id}: ")


@pytest.mark.parametrize("top, bottom, message", [
    # a side face whose top edge runs against its bottom edge (every face planar)
    ([(4, 0, 1), (0, 0, 1), (0, 3, 1), (4, 3, 1)], [(0, 0, 0), (4, 0, 0), (4, 3, 0), (0, 3, 0)],
     "side face 0 is twisted"),
    ([(0, 0, 1), (4, 0, 1), (4, 0, 1), (0, 3, 1)], [(0, 0, 0), (4, 0, 0), (4, 0, 0), (0, 3, 0)],
     "edge 1 of its solid has no length"),
    ([(0, 0, 1), (6, 0, 1), (0, 3, 1), (2, 3, 1)], [(0, 0, 0), (6, 0, 0), (0, 3, 0), (2, 3, 0)],
     "outline crosses itself"),
])
def test_panel_solids_refuse_degenerate_panels(top, bottom, message):
    step = freecad_step()

    class Panel:
        id = "P-X"

    class Set:
        panels = [Panel()]

    Set.panels[0].top, Set.panels[0].bottom = np.array(top, float), np.array(bottom, float)
    with pytest.raises(step.SolidError, match=message):
        step.panel_solids(Set)


def test_half_turn_symmetric_parts_skip_the_redundant_rotations():
    from facet.nest import _half_turn_symmetric, nest, verify

    assert _half_turn_symmetric([(0, 0), (0, 4), (6, 4), (6, 0), (0, 0)])
    assert _half_turn_symmetric([(0, 0), (1, 3), (5, 3), (4, 0)])          # parallelogram
    assert not _half_turn_symmetric([(0, 0), (0, 4), (2, 4), (2, 2), (6, 2), (6, 0)])  # L
    assert not _half_turn_symmetric([(0, 0), (2, 3), (5, 3), (4, 0)])      # trapezoid
    # rectangles with collinear extra vertices (dropped before nesting)
    rects = {f"R{k}": np.array([[0, 0], [150, 0], [300 + k, 0], [300 + k, 200], [0, 200.0]])
             for k in range(12)}
    r = nest(rects, (1000, 700), margin=5, spacing=4, rotations="90", workers=1)
    assert verify(r, rects) == [] and not r.unplaced
    assert {pl.angle_deg for pl in r.placements.values()} <= {0.0, 90.0}
    # concave parts (libnest2d overlapped them; now nested by their convex hull),
    # not symmetric: every quarter turn may be used again
    ells = {f"L{k}": np.array([[0, 0], [0, 300], [100, 300], [100, 100], [250, 100],
                               [250, 0.0]]) for k in range(10)}
    r = nest(ells, (1000, 700), margin=5, spacing=4, rotations="90", workers=1)
    assert verify(r, ells) == [] and not r.unplaced


# ---- solids and STEP in a worker process -----------------------------------

def test_step_job_writes_the_solids_in_a_worker_while_this_process_goes_on(tmp_path):
    step = freecad_step()
    FreeCAD, Part = step.import_freecad()
    ps = panels(translational(nu=4, nv=3, step=400.0), 18.0, edge="bisector", gap=4)
    path = tmp_path / "p.step"
    job = step.start_step(path, ps)
    assert job.in_worker
    assert job.wait() == str(path)
    assert set(job.seconds) == {"solids", "step"}
    assert os.listdir(tmp_path) == ["p.step"]  # no temporary file left
    back = Part.read(str(path))
    assert len(back.Solids) == len(ps.panels)
    got = sorted(s.Volume for s in back.Solids)
    assert got == pytest.approx(sorted(p.volume for p in ps.panels), rel=1e-9)
    text = path.read_text()
    assert all(f"'{p.id}'" in text for p in ps.panels)  # each product named by its ID


def test_step_job_takes_its_place_with_the_staged_files(tmp_path):
    """Inside facet.io.files.staged (a run's files together, or none of them) the worker's
    STEP file took its place as soon as it was waited for: a later failure in the block
    left a new panels.step beside the last run's DXF and schedule. It now takes its place
    when the block ends well, and a failure removes it, leaving the old file."""
    from facet.io.files import staged

    step = freecad_step()
    ps = panels(translational(nu=3, nv=2, step=400.0), 18.0, edge="bisector", gap=4)
    path = tmp_path / "p.step"
    path.write_text("the last run's")
    with pytest.raises(RuntimeError, match="a later file failed"):
        with staged():
            job = step.start_step(path, ps)
            assert job.in_worker
            job.wait()
            assert path.read_text() == "the last run's"  # not yet in place
            raise RuntimeError("a later file failed")
    assert path.read_text() == "the last run's"
    assert os.listdir(tmp_path) == ["p.step"]  # the worker's file removed
    with staged():
        step.start_step(path, ps).wait()
        assert path.read_text() == "the last run's"
    assert "ISO-10303-21" in path.read_text()
    assert os.listdir(tmp_path) == ["p.step"]


def test_step_written_here_takes_its_place_with_the_staged_files(tmp_path):
    """As the worker's: the STEP file write_step makes in this process (the cut sheets'
    STEP from the PanelSet's solids, or a StepJob without a worker) took its place at once
    inside facet.io.files.staged, and a later failure in the block (the JSON schedule)
    left it beside the last run's files. It takes its place when the block ends well."""
    from facet.io.files import staged

    step = freecad_step()
    ps = panels(translational(nu=3, nv=2, step=400.0), 18.0, edge="bisector", gap=4)
    solids = step.panel_solids(ps)
    path = tmp_path / "p.step"
    path.write_text("the last run's")
    with pytest.raises(RuntimeError, match="a later file failed"):
        with staged():
            step.write_step(path, solids)
            assert path.read_text() == "the last run's"  # not yet in place
            raise RuntimeError("a later file failed")
    assert path.read_text() == "the last run's"
    assert os.listdir(tmp_path) == ["p.step"]  # its temporary file removed
    with staged():
        step.write_step(path, solids)
        assert path.read_text() == "the last run's"
    assert "ISO-10303-21" in path.read_text()
    assert os.listdir(tmp_path) == ["p.step"]
    step.write_step(path, solids[:1])  # (outside staged: at once)
    assert path.read_text().count("MANIFOLD_SOLID_BREP") == 1


def _step_root(path):
    """The STEP file's top assembly: the product no other one holds (its
    NEXT_ASSEMBLY_USAGE_OCCURRENCEs' relating definitions name it)."""
    text = path.read_text()
    products = re.findall(r"PRODUCT\('([^']*)'", text)
    children = set(re.findall(r"NEXT_ASSEMBLY_USAGE_OCCURRENCE\('[^']*','([^']*)'", text))
    return [p for p in products if p not in children]


def test_the_step_files_assembly_is_named_after_the_job(tmp_path):
    """A fabricator importing the STEP file sees its top assembly as the root: it was
    "FacetStepExport" (FreeCAD's temporary document) in every file; it is the file's stem,
    written by the worker (which writes a temporary file first) or here, and FreeCAD
    reads it back as an App::Part of that label holding the panels by ID."""
    step = freecad_step()
    FreeCAD, Part = step.import_freecad()
    import Import

    ps = panels(translational(nu=3, nv=2, step=400.0), 18.0, edge="bisector", gap=4)
    worker = tmp_path / "wave_facade_panels.step"
    assert step.start_step(worker, ps).wait() == str(worker)
    assert _step_root(worker) == ["wave_facade_panels"]
    here = tmp_path / "Roof east (rev 2).stp"
    step.write_step(here, step.panel_solids(ps))
    assert _step_root(here) == ["Roof east (rev 2)"]
    step.write_step(here, step.panel_solids(ps), name="job 7")
    assert _step_root(here) == ["job 7"]
    assert step.step_name(tmp_path / ".step") == "panels"
    back = FreeCAD.newDocument("StepRoot", hidden=True, temp=True)
    try:
        Import.insert(str(worker), back.Name, useLinkGroup=False)
        roots = [o for o in back.Objects if o.TypeId == "App::Part"]
        assert [o.Label for o in roots] == ["wave_facade_panels"]
        held = sorted(o.Label for o in roots[0].Group if o.TypeId == "Part::Feature")
        assert held == sorted(p.id for p in ps.panels)
    finally:
        FreeCAD.closeDocument(back.Name)
    assert len(Part.read(str(worker)).Solids) == len(ps.panels)


def test_step_job_cancelled_or_failed_writes_nothing(tmp_path):
    step = freecad_step()
    ps = panels(translational(nu=4, nv=3, step=400.0), 18.0, edge="bisector", gap=4)
    job = step.start_step(tmp_path / "c.step", ps)
    job.cancel()
    assert os.listdir(tmp_path) == []
    with pytest.raises(Cancelled):
        step.start_step(tmp_path / "c.step", ps).wait(progress=lambda d, t: True)
    assert os.listdir(tmp_path) == []
    p = ps.panels[5]
    p.top = p.top.copy()
    p.top[0, 2] += 5.0  # not planar: the worker's SolidError comes back as one
    with pytest.raises(step.SolidError, match=f"panel {p.id}: its .* is not planar"):
        step.start_step(tmp_path / "f.step", ps).wait()
    assert os.listdir(tmp_path) == []


def test_cli_panels_writes_step_next_to_the_other_files(tmp_path, facet_command):
    from facet import write_mesh

    step = freecad_step()
    FreeCAD, Part = step.import_freecad()
    mesh_path = tmp_path / "m.obj"
    write_mesh(translational(nu=4, nv=3, step=400.0), mesh_path)
    report = tmp_path / "r.json"
    done = facet_command("panels", mesh_path, "--thickness", "18", "--edge", "bisector",
                         "--gap", "4", "--sheet", "2000x1000", "--dxf", tmp_path / "s.dxf",
                         "--step", tmp_path / "p.step", "--report", report)
    assert done.returncode == 0, done.stderr
    data = json.loads(report.read_text())
    assert {"solids", "step", "step_wait", "total"} <= set(data["seconds"])
    assert data["seconds"]["total"] >= data["seconds"]["nest"]
    assert len(Part.read(str(tmp_path / "p.step")).Solids) == 12
    assert not [f for f in os.listdir(tmp_path) if ".part" in f]


def test_cli_panels_whose_step_fails_leaves_the_last_whole_run(tmp_path, facet_command):
    # the DXF, schedule and previews were written before the STEP worker failed: exit 1
    # with this run's cut sheets beside the last run's STEP file
    from facet import write_mesh

    freecad_step()
    mesh_path = tmp_path / "m.obj"
    write_mesh(translational(nu=4, nv=3, step=400.0), mesh_path)
    out = ["--sheet", "2000x1000", "--dxf", tmp_path / "s.dxf", "--schedule",
           tmp_path / "s.csv", "--svg", tmp_path / "svg", "--step", tmp_path / "p.step"]
    done = facet_command("panels", mesh_path, "--thickness", "18", *out)
    assert done.returncode == 0, done.stderr
    files = sorted(str(p.relative_to(tmp_path)) for p in tmp_path.rglob("*") if p.is_file())
    before = {f: (tmp_path / f).read_bytes() for f in files}
    failed = facet_command("panels", mesh_path, "--thickness", "1e-7", *out)  # no solid
    assert failed.returncode == 1 and "has no length" in failed.stderr
    after = sorted(str(p.relative_to(tmp_path)) for p in tmp_path.rglob("*") if p.is_file())
    assert after == files and all((tmp_path / f).read_bytes() == before[f] for f in files)


def test_staged_files_take_their_places_together_or_not_at_all(tmp_path):
    from facet.io.files import staged, when_staged, write_text

    write_text(tmp_path / "a.txt", "old a")
    removed = []
    with pytest.raises(RuntimeError):
        with staged():
            write_text(tmp_path / "a.txt", "new a")
            write_text(tmp_path / "b.txt", "new b")
            when_staged(lambda: removed.append(1))
            assert (tmp_path / "a.txt").read_text() == "old a"  # not yet
            raise RuntimeError("the STEP failed")
    assert sorted(os.listdir(tmp_path)) == ["a.txt"] and removed == []
    assert (tmp_path / "a.txt").read_text() == "old a"
    with staged():
        write_text(tmp_path / "a.txt", "new a")
        with staged():  # nested: the outer block decides
            write_text(tmp_path / "b.txt", "new b")
        assert not (tmp_path / "b.txt").exists()
        with pytest.raises(RuntimeError):
            with staged():  # a nested block that fails drops its own files only
                write_text(tmp_path / "c.txt", "new c")
                raise RuntimeError
        when_staged(lambda: removed.append(1))
        # another thread's writes are its own, not this block's
        import threading

        other = threading.Thread(target=write_text, args=(tmp_path / "d.txt", "d"))
        other.start()
        other.join()
        assert (tmp_path / "d.txt").read_text() == "d"
    assert (tmp_path / "a.txt").read_text() == "new a" and (tmp_path / "b.txt").exists()
    assert not (tmp_path / "c.txt").exists()
    assert removed == [1] and not [f for f in os.listdir(tmp_path) if ".part" in f]


def test_step_job_without_a_worker_interpreter_runs_in_this_process(tmp_path, monkeypatch):
    import facet.parallel

    step = freecad_step()
    FreeCAD, Part = step.import_freecad()
    monkeypatch.setattr(facet.parallel, "python_executable", lambda: None)
    ps = panels(translational(nu=3, nv=2, step=400.0), 18.0, edge="bisector", gap=4)
    job = step.start_step(tmp_path / "p.step", ps)
    assert not job.in_worker and not os.listdir(tmp_path)  # nothing done until wait()
    seen = []
    job.wait(progress=lambda d, t: seen.append(d) and False)
    assert seen[-1] == len(ps.panels) and set(job.seconds) == {"solids", "step"}
    assert len(Part.read(str(tmp_path / "p.step")).Solids) == len(ps.panels)


@pytest.mark.skipif(sys.platform == "win32", reason="SIGINT is POSIX")
def test_ctrl_c_while_the_step_worker_runs_writes_nothing(tmp_path, facet_interrupt):
    from facet import write_mesh

    freecad_step()
    mesh_path = tmp_path / "m.obj"
    write_mesh(translational(nu=60, nv=60, step=400.0), mesh_path)  # 3,600 panels
    # after 3 s nesting and the STEP worker are both running
    done = facet_interrupt("panels", mesh_path, "--thickness", "18", "--edge", "bisector",
                           "--gap", "4", "--sheet", "2000x1000", "--step", tmp_path / "p.step",
                           "--dxf", tmp_path / "s.dxf")
    assert done.returncode == 130, done.stderr
    assert sorted(os.listdir(tmp_path)) == ["m.obj"]  # no STEP, no part of one, no DXF


def test_panel_solids_check_convex_outlines_without_shapely(monkeypatch):
    import shapely.geometry

    step = freecad_step()
    ps = panels(translational(nu=6, nv=5, step=400.0), 18.0, edge="bisector", gap=4)
    calls = []
    polygon = shapely.geometry.Polygon
    monkeypatch.setattr(shapely.geometry, "Polygon",
                        lambda *a, **k: calls.append(1) or polygon(*a, **k))
    assert len(step.panel_solids(ps)) == len(ps.panels)
    assert calls == []  # top and bottom found convex (and so simple) by their turns


def _cut_tip_mesh(offset=(0.0, 0.0)):
    """A sharp quad whose tip is cut off by an edge 0.2 long (face 0) and a
    trapezoid above it on that edge (face 1); flat, in the xy plane."""
    ox, oy = offset
    xy = [(0, 0), (10, 0), (5.1, 20), (4.9, 20), (12, 24), (-2, 24)]
    vertices = [(x + ox, y + oy, 0.0) for x, y in xy]
    return facet.PolyMesh.from_faces(vertices, [[0, 1, 2, 3], [3, 2, 4, 5]])


def _line_distance(x, a, b):
    u = (b - a)[:2] / np.linalg.norm((b - a)[:2])
    w = (x - a)[:2]
    return abs(w[0] * u[1] - w[1] * u[0])


@pytest.mark.parametrize("offset", [(0.0, 0.0), (2.5e6, 1.2e6)])
def test_square_edges_drop_an_edge_the_gap_consumes(offset):
    mesh = _cut_tip_mesh(offset)
    before = mesh.vertices.copy()
    # the tip's edge shrinks by 1.57 times half the gap: kept at 0.2, consumed at 0.4
    kept = panels(mesh, 0.05, gap=0.2)
    assert [len(p.top) for p in kept] == [4, 4] and not kept.warnings
    assert [p.dropped_edges for p in kept] == [0, 0]
    ps = panels(mesh, 0.05, gap=0.4)
    a, b = ps.panels
    assert (len(a.top), len(a.bottom), len(a.flat_bottom)) == (3, 3, 3)
    assert a.dropped_edges == 1 and b.dropped_edges == 0 and len(b.top) == 4
    assert len(a.edge_lengths) == len(a.bevel_deg) == len(a.neighbors) == 3
    assert a.neighbors == [None, None, None]  # the edge to face 1 is gone
    assert b.neighbors.count(0) == 1
    assert any(w.startswith("1 short edges that the joint gap or a bevel consumes dropped "
                            "from the outlines of 1 panel: P-") for w in ps.warnings)
    # every corner of the triangle lies half the gap inside the two mesh edges it joins
    # (the tip's corner joins edges 1 and 3: vertex 1 to 2, vertex 3 to 0)
    v = mesh.vertices
    lines = {0: (v[0], v[1]), 1: (v[1], v[2]), 3: (v[3], v[0])}
    for corner, (e, f) in zip(a.bottom, [(3, 0), (0, 1), (1, 3)]):
        for edge in (e, f):
            assert _line_distance(corner, *lines[edge]) == pytest.approx(0.2, abs=1e-6)
    assert np.allclose(a.top - a.bottom, [0.0, 0.0, 0.05])
    assert a.schedule_row()["dropped_edges"] == 1
    assert np.array_equal(mesh.vertices, before)


def test_flat_mitres_are_square_and_drop_too_and_a_gap_wider_than_the_panel_is_an_error():
    ps = panels(_cut_tip_mesh(), 0.05, gap=0.4, edge="bisector")
    assert [p.dropped_edges for p in ps] == [1, 0] and [p.squared_edges for p in ps] == [0, 0]
    with pytest.raises(PanelError, match=r"face 0: the (top|bottom) outline loses its edge "
                                         r"from vertex 2, 0\.2 long") as info:
        panels(_cut_tip_mesh(), 0.05, gap=0.4, edge="bisector", repair=False)
    assert info.value.faces == [0]
    with pytest.raises(PanelError, match="fewer than three edges"):
        panels(_cut_tip_mesh(), 0.05, gap=12.0)


def _rotate_about(points, a, b, angle):
    k = (b - a) / np.linalg.norm(b - a)
    v = points - a
    return (a + v * math.cos(angle) + np.cross(k, v) * math.sin(angle)
            + np.outer(v @ k, k) * (1.0 - math.cos(angle)))


def _folded_tip_mesh(fold_deg=30.0):
    """The cut-tip quad (face 0) with a quad on each long side (faces 1, 2),
    both folded up by fold_deg about their shared edges (valleys)."""
    q = np.array([(0, 0, 0), (10, 0, 0), (5.1, 20, 0), (4.9, 20, 0), (15, 0, 0), (10.1, 20, 0),
                  (-0.1, 20, 0), (-5, 0, 0)], dtype=float)
    fold = math.radians(fold_deg)
    q[4:6] = _rotate_about(q[4:6], q[1], q[2], -fold)
    q[6:8] = _rotate_about(q[6:8], q[0], q[3], fold)
    return facet.PolyMesh.from_faces(q, [[0, 1, 2, 3], [2, 1, 4, 5], [0, 3, 6, 7]])


def test_a_mitre_that_cannot_be_cut_becomes_a_butt_joint():
    mesh = _folded_tip_mesh()
    thin = panels(mesh, 0.01, gap=0.2, edge="bisector")
    assert [p.squared_edges for p in thin] == [0, 0, 0]
    assert sorted(round(abs(b), 9) for b in thin.panels[0].bevel_deg) == [0, 0, 15, 15]
    # thick: the long sides' mitres would consume the tip's edge at the top; they
    # become butt joints, square on face 0, the whole 30-degree fold on faces 1, 2
    ps = panels(mesh, 0.2, gap=0.2, edge="bisector")
    assert [p.squared_edges for p in ps] == [2, 0, 0]
    assert [p.butt_edges for p in ps] == [0, 1, 1]
    assert [len(p.top) for p in ps] == [4, 4, 4]
    assert np.allclose(ps.panels[0].bevel_deg, 0.0, atol=1e-9)
    assert sorted(round(abs(b), 6) for b in ps.panels[1].bevel_deg) == [0, 0, 0, 30]
    assert any(w.startswith("2 mitred joints cut as butt joints") and "on 1 panel: P-" in w
               and w.endswith("the narrowest of those joints is 0.2 wide across its section "
                              "(gap 0.2)")
               for w in ps.warnings)
    assert ps.narrowest_repaired_joint == pytest.approx(0.2)
    assert thin.narrowest_repaired_joint is None
    row = ps.panels[1].schedule_row()
    assert (row["squared_edges"], row["butt_edges"]) == (0, 1)
    # the joint is a slot of constant width: each side face lies half the gap
    # off the plane through the edge square to face 0
    a, b = ps.panels[0], ps.panels[1]
    v = mesh.vertices
    e = (v[2] - v[1]) / np.linalg.norm(v[2] - v[1])
    inward = np.cross(a.normal, e)  # into face 0 (counter-clockwise)
    for panel, side in ((a, 0.1), (b, -0.1)):
        at_joint = np.isin(panel.vertices, [1, 2])  # the corners at the joint's ends
        for ring in (panel.top, panel.bottom):
            assert np.allclose((ring[at_joint] - v[1]) @ inward, side)
    step = freecad_step()
    solids = step.panel_solids(ps)
    for _, solid in solids:
        assert solid.isValid() and solid.Shells[0].isClosed()
    assert solids[0][1].common(solids[1][1]).Volume < 1e-9
    with pytest.raises(PanelError, match="face 0: the top outline loses its edge from vertex 2"):
        panels(mesh, 0.2, gap=0.2, edge="bisector", repair=False)


def test_a_panel_whose_edge_was_dropped_is_a_valid_solid_and_cut(tmp_path):
    step = freecad_step()
    ps = panels(_cut_tip_mesh(), 0.05, gap=0.4)
    solids = step.panel_solids(ps)
    (_, tri), (_, quad) = solids
    assert tri.isValid() and tri.Shells[0].isClosed() and len(tri.Faces) == 5
    assert quad.isValid() and len(quad.Faces) == 6
    assert tri.Volume == pytest.approx(ps.panels[0].volume, rel=1e-9)
    # laid flat, nested and cut: the cut outline is the triangle
    import ezdxf
    from facet.cli_panels import run_pipeline

    report, ps, drawings, result = run_pipeline(_cut_tip_mesh(), 0.05, gap=0.4,
                                                sheet=(30.0, 30.0), margin=0, spacing=0,
                                                dxf=str(tmp_path / "cut.dxf"),
                                                schedule=str(tmp_path / "schedule.csv"))
    doc = ezdxf.readfile(tmp_path / "cut.dxf")
    assert not doc.audit().has_errors
    cuts = doc.modelspace().query("LWPOLYLINE[layer=='CUT']")
    assert sorted(len(c) for c in cuts) == [3, 4]
    with open(tmp_path / "schedule.csv", newline="") as f:
        rows = {r["id"]: r for r in csv.DictReader(f)}
    assert sorted(r["dropped_edges"] for r in rows.values()) == ["0", "1"]


def test_a_joint_square_on_both_panels_reports_its_width_or_its_overlap():
    """Two cut-tip quads on either side of a long edge, folded 30 degrees (a valley):
    the mitre consumes both tips, so the joint is square on both panels; it narrows
    towards the top, as far as OCC measures between the two solids."""
    q = np.array([(0, 0, 0), (10, 0, 0), (5.1, 20, 0), (4.9, 20, 0), (15, 0, 0), (5.3, 20, 0)],
                 dtype=float)
    q[4:6] = _rotate_about(q[4:6], q[1], q[2], -math.radians(30.0))
    mesh = facet.PolyMesh.from_faces(q, [[0, 1, 2, 3], [2, 1, 4, 5]])
    ps = panels(mesh, 1.0, gap=0.8, edge="bisector")
    assert [p.squared_edges for p in ps] == [1, 1] and [p.butt_edges for p in ps] == [0, 0]
    width = 2 * (0.4 * math.cos(math.radians(15)) - math.sin(math.radians(15)))
    assert ps.narrowest_repaired_joint == pytest.approx(width, abs=1e-9)
    step = freecad_step()
    (_, a), (_, b) = step.panel_solids(ps)
    assert a.distToShape(b)[0] == pytest.approx(width, rel=1e-6)
    with pytest.raises(PanelError, match=r"faces 0 and 1: .* overlap by"):
        panels(mesh, 1.0, gap=0.02, edge="bisector")


def test_cli_panels_says_when_no_gap_clears_the_overlaps(data_dir, tmp_path, capsys):
    # thick stone panels on the cross vault: joints and nodes overlap and no gap clears
    # every overlap (clearing_gap None); the summary formatted None and the command
    # ended in a traceback after it had written its files
    from facet import cli

    status = cli.main(["panels", str(data_dir / "crossvault_form_planar.obj"), "--thickness",
                       "0.5", "--gap", "0", "--schedule", str(tmp_path / "s.csv")])
    out, err = capsys.readouterr()
    assert status == 0, err
    assert "no gap found that clears every overlap" in out
    assert "joints cut square on the inner side of a fold overlap" in err


def test_the_re_nest_of_crowded_parts_reports_progress_and_can_be_cancelled(monkeypatch):
    # the crowded parts' second nesting took no progress callback: Cancel did nothing
    # until it ended, and the bar stood at the end meanwhile
    import facet.nest
    from facet.errors import Cancelled

    checked = []
    real = facet.nest._problems

    def once(result, parts, tolerance=None):  # part "B" crowded on the first check only
        checked.append(1)
        if len(checked) == 1:
            return [("part B is closer than the spacing", ("B",))]
        return real(result, parts, tolerance)

    monkeypatch.setattr(facet.nest, "_problems", once)
    parts = {k: np.array([[0, 0], [100, 0], [100, 100], [0, 100.0]]) for k in "ABC"}
    during = []  # (done, total) reported while the re-nest runs (after the first check)
    r = facet.nest.nest(parts, (1000, 1000), margin=10, spacing=5,
                        progress=lambda d, t: checked and during.append((d, t)) and False)
    assert sorted(r.placements) == ["A", "B", "C"] and facet.nest.verify(r, parts) == []
    assert during and all(2 <= d <= 3 and t == 3 for d, t in during)  # from the 2 that stay
    checked.clear()
    with pytest.raises(Cancelled, match="nesting cancelled"):
        facet.nest.nest(parts, (1000, 1000), margin=10, spacing=5,
                        progress=lambda d, t: len(checked) > 0)  # Cancel once the re-nest runs


@pytest.mark.parametrize("text, said", [
    ("infx3000", "must have a finite width and height"),
    ("3000xnan", "must have a finite width and height"),
    ("0x1500", "must have a width and height > 0"),
    ("3000", "is not WIDTHxHEIGHT")])
def test_a_sheet_that_is_not_stock_is_refused_saying_what_is_wrong(text, said):
    """--sheet infx3000 was refused as having no width and height > 0, which it has."""
    import argparse

    from facet.cli_panels import _sheet

    with pytest.raises(argparse.ArgumentTypeError) as caught:
        _sheet(text)
    assert said in str(caught.value) and repr(text) in str(caught.value)
    assert _sheet("3000X1500") == (3000.0, 1500.0)


def test_texts_as_outlines_for_cam_that_imports_no_text(tmp_path):
    """Many CAM importers skip TEXT, so the IDs and bevel angles were lost to them. With
    text_outlines (--text-outlines) each is the closed outlines of its letters on its
    layer, where its TEXT would stand: centred on the TEXT's point, its capitals the
    TEXT's height, inside its part."""
    import ezdxf
    from shapely.geometry import Polygon
    from shapely.ops import unary_union

    from facet.cutsheets import write_dxf

    _, ps, drawings, result = _made(tmp_path)
    write_dxf(tmp_path / "outlines.dxf", result, drawings, text_outlines=True)
    texts = ezdxf.readfile(tmp_path / "cut.dxf").modelspace()
    doc = ezdxf.readfile(tmp_path / "outlines.dxf")
    assert not doc.audit().has_errors
    msp = doc.modelspace()
    assert {t.dxf.layer for t in msp.query("TEXT")} == {"SHEET"}
    cuts = [Polygon([(x, y) for x, y, *_ in c.get_points()])
            for c in msp.query("LWPOLYLINE[layer=='CUT']")]
    for layer in ("LABEL", "BEVEL"):
        letters = [Polygon([(x, y) for x, y, *_ in e.get_points()])
                   for e in msp.query(f"LWPOLYLINE[layer=='{layer}']")]
        assert letters and all(e.closed for e in msp.query(f"LWPOLYLINE[layer=='{layer}']"))
        assert all(np.isfinite(letter.exterior.coords).all() for letter in letters)
        for text in texts.query(f"TEXT[layer=='{layer}']"):
            x, y = text.dxf.align_point.x, text.dxf.align_point.y
            height = text.dxf.height
            part = next(c for c in cuts if c.contains(Polygon([(x, y), (x + 1e-9, y),
                                                               (x, y + 1e-9)])))
            near = [p for p in letters if p.distance(Polygon([(x, y), (x + 1e-9, y),
                                                              (x, y + 1e-9)])) < height
                    and part.contains(p)]
            drawn = unary_union(near).convex_hull
            cx, cy = drawn.centroid.x, drawn.centroid.y
            assert math.hypot(cx - x, cy - y) < 0.5 * height, text.dxf.text
            # the capitals' height across the text's direction
            turn = math.radians(text.dxf.rotation)
            across = [(-(px - x) * math.sin(turn) + (py - y) * math.cos(turn))
                      for px, py in drawn.exterior.coords]
            assert 0.95 * height < max(across) - min(across) < 1.4 * height, text.dxf.text


def test_texts_read_upright_on_the_sheet(tmp_path):
    """A part nested turned by 180 or 270 degrees had its ID written upside down on the
    sheet, and every part the bevel angles of its edges that run left or down (the
    fabricator reads IDs off the sheet). Every ID and bevel angle now reads from the
    sheet's bottom or its right side (its angle in (-70, 110]), on the line it lay on,
    centred where it was: in the DXF's TEXT, its outlines (the letters of the upright
    text), the SVG and so the PNG (drawn at the DXF's angles); on the sheet its letters
    lie on the part's top face, clear of the part's other texts."""
    import xml.etree.ElementTree as ET

    import ezdxf
    from ezdxf.addons import text2path
    from ezdxf.enums import TextEntityAlignment
    from shapely.geometry import MultiPoint, Polygon

    from facet.cutsheets import OUTLINE_FONT, write_dxf

    try:  # ezdxf 1.x
        from ezdxf.fonts.fonts import FontFace
    except ImportError:  # ezdxf 0.18
        from ezdxf.tools.fonts import FontFace

    _, ps, drawings, result = _made(tmp_path)
    assert {180, 270} <= {round(pl.angle_deg) % 360 for pl in result.placements.values()}
    # one file a sheet: each sheet at the origin, as nested
    as_text = write_dxf(tmp_path / "t.dxf", result, drawings, per_sheet=True)
    as_lines = write_dxf(tmp_path / "o.dxf", result, drawings, per_sheet=True,
                         text_outlines=True)
    face = FontFace(family=OUTLINE_FONT)
    literal = ((lambda s: s.replace("$", r"\$")) if hasattr(text2path, "TextPath")
               else (lambda s: s))

    @functools.lru_cache(maxsize=None)
    def letters(s):  # the upright text's outline points at height 1, centred
        paths = text2path.make_paths_from_str(literal(s), face, size=1.0,
                                              align=TextEntityAlignment.MIDDLE_CENTER)
        return np.array([(v.x, v.y) for p in paths for v in p.flattening(0.001)])

    by_id = {d.id: d for d in drawings}
    on_sheet = {}
    for pid, pl in result.placements.items():
        on_sheet.setdefault(pl.sheet, []).append((pl, by_id[pid]))
    flipped = checked = 0
    for k, (text_file, line_file) in enumerate(zip(as_text, as_lines)):
        texts = ezdxf.readfile(text_file).modelspace()
        lines = ezdxf.readfile(line_file).modelspace()
        rings = {layer: [np.array(e.get_points("xy"))
                         for e in lines.query(f"LWPOLYLINE[layer=='{layer}']")]
                 for layer in ("LABEL", "BEVEL")}
        for pl, d in on_sheet[k]:
            top = Polygon(pl.transform(d.cut)).intersection(Polygon(pl.transform(d.top)))
            wanted = [("LABEL", d.id, d.label_position, d.label_height, 0.0)] + [
                ("BEVEL", s, (x, y), h, angle) for s, x, y, angle, h in d.bevels]
            inks = []
            for layer, s, xy, h, angle in wanted:
                x, y = pl.transform([xy])[0]
                along = angle + pl.angle_deg  # the text's line on the sheet
                (text,) = [t for t in texts.query(f"TEXT[layer=='{layer}']")
                           if t.dxf.text == s and np.hypot(t.dxf.align_point.x - x,
                                                           t.dxf.align_point.y - y) < 1e-9 * h]
                turn = text.dxf.rotation
                # (up to 20 degrees past vertical it reads from the right: a part's left
                # and right edges' texts the same way)
                assert -70.0 < turn <= 110.0, (d.id, s, turn)
                assert abs(math.remainder(turn - along, 180.0)) < 1e-9, (d.id, s)
                flipped += abs(math.remainder(turn - along, 360.0)) > 90.0
                # its letters' outlines: the upright text's, turned and placed as the TEXT
                c, si = math.cos(math.radians(turn)), math.sin(math.radians(turn))
                back = np.array([[c, -si], [si, c]]) / h  # sheet -> text frame
                ref = letters(s)
                mine = []
                for ring in rings[layer]:
                    local = (ring - (x, y)) @ back
                    if np.abs(local).max() > 0.6 * len(s) + 1.0:
                        continue  # another text's
                    gap = np.min(np.hypot(*(local[:, None, :] - ref[None, :, :]).T), axis=0)
                    if gap.max() < 2e-3:  # (within the flattening's tolerance)
                        mine.append(ring)
                ink = MultiPoint(np.concatenate(mine)) if mine else None
                assert ink is not None and ink.convex_hull.area > 0.3 * h * h, (d.id, s)
                # (all the letters: as wide as the upright text)
                span = np.concatenate(mine) @ np.array([c, si])
                assert np.ptp(span) == pytest.approx(np.ptp(ref[:, 0]) * h, rel=1e-2), s
                assert top.contains(ink.convex_hull), (d.id, s)
                inks.append(ink.convex_hull)
                checked += 1
            for i, a in enumerate(inks):
                assert all(a.intersection(b).area == 0 for b in inks[i + 1:]), d.id
    assert flipped > 0.2 * checked > 10  # (upside down before)
    # the SVG previews: the texts turned as in the DXF (the PNG's angles are the DXF's,
    # test_png_texts_are_as_tall_as_the_dxfs)
    for svg in (tmp_path / "svg").glob("*.svg"):
        for text in ET.parse(svg).getroot().iter("{http://www.w3.org/2000/svg}text"):
            rotate = float(re.search(r"rotate\((\S+) ", text.get("transform")).group(1))
            assert -110.0 <= rotate < 70.0  # (y down: clockwise)


def test_writing_the_dxf_shows_progress_and_cancels_leaving_no_file(tmp_path):
    """Writing texts as outlines takes about 6 ms a part (a minute for 10,000 parts) and
    showed no progress and could not be cancelled: now progress(done, total) is called as
    the parts are drawn, and True cancels with nothing written."""
    from facet.cutsheets import write_dxf
    from facet.errors import Cancelled

    _, ps, drawings, result = _made(tmp_path)
    calls = []
    write_dxf(tmp_path / "shown.dxf", result, drawings, text_outlines=True,
              progress=lambda done, total: calls.append((done, total)) and False)
    total = len(result.placements)
    assert calls[0] == (0, total) and calls[-1] == (total, total) and len(calls) >= 2
    assert all(a[0] <= b[0] for a, b in zip(calls, calls[1:]))
    with pytest.raises(Cancelled):
        write_dxf(tmp_path / "cancelled.dxf", result, drawings, text_outlines=True,
                  progress=lambda done, total: done > 0)
    assert not (tmp_path / "cancelled.dxf").exists()


@pytest.mark.parametrize("kind", ["svg", "png"])
def test_previews_show_progress_and_cancel(tmp_path, kind):
    """The PNG previews take about 40 ms a sheet (6.5 s for the demo's 153 sheets) and
    showed no progress, and Ctrl+C waited for the last: now progress(done, total) is called
    before each sheet and at the end, and True cancels; under staged(), as facet panels
    writes them, nothing of a cancelled run is left."""
    from facet.cutsheets import write_png, write_svg
    from facet.errors import Cancelled
    from facet.io.files import staged

    write = write_svg if kind == "svg" else write_png
    _, ps, drawings, result = _made(tmp_path)
    calls = []
    written = write(tmp_path / "shown", result, drawings,
                    progress=lambda done, total: calls.append((done, total)) and False)
    n = len(result.sheets)
    assert n >= 2 and len(written) == n
    assert calls == [(k, n) for k in range(n + 1)]
    with pytest.raises(Cancelled), staged():
        write(tmp_path / "cancelled", result, drawings, progress=lambda done, total: done > 0)
    assert not list((tmp_path / "cancelled").glob(f"*.{kind}"))


def test_facet_panels_shows_each_stage_on_a_terminal(tmp_path):
    """facet panels ran silent until its summary (tens of seconds at 10,000 panels, a
    minute or more with texts as outlines): on a terminal its line now counts each stage
    (nesting, the DXF's parts, the sheets; the panels' own on larger meshes), and Ctrl+C
    still cancels."""
    import io

    from facet.cli_panels import panels_progress, run_pipeline
    from facet.cli_progress import ProgressLine

    out = io.StringIO()
    line = ProgressLine(out, prefix="facet panels", interval=0.0, force=True)
    run_pipeline(translational(nu=6, nv=5, step=400.0), 18.0, sheet=(1300, 900), margin=15,
                 spacing=8, dxf=str(tmp_path / "cut.dxf"), svg=str(tmp_path / "svg"),
                 progress=panels_progress(line, lambda: False))
    shown = out.getvalue()
    for words in ("nesting the parts", "drawing the DXF's parts 30 of 30",
                  "writing the SVG sheets"):
        assert f"facet panels: {words}" in shown, words
    with pytest.raises(facet.errors.Cancelled):
        run_pipeline(translational(nu=6, nv=5, step=400.0), 18.0, sheet=(1300, 900),
                     margin=15, spacing=8, dxf=str(tmp_path / "cancelled.dxf"),
                     progress=panels_progress(line, lambda: True))
    assert not (tmp_path / "cancelled.dxf").exists()


def test_texts_as_outlines_refuse_letters_the_font_lacks_and_skip_blank_ids(tmp_path):
    """The outline font (DejaVu Sans) has no CJK letters: an ID prefix in them was written as
    the font's empty box, each ID lost to the cutter without a word; now it is refused,
    naming the letter, and nothing is written. A blank ID has nothing to engrave (text2path
    failed on it with an AssertionError); a Cyrillic prefix and the degree sign are in
    the font."""
    from facet.cli_panels import run_pipeline

    mesh = translational(nu=3, nv=2, step=400.0)
    kw = dict(sheet=(1300, 900), margin=15, spacing=8, text_outlines=True)
    with pytest.raises(facet.errors.InputError, match=r"DejaVu Sans has no letter for '面'"):
        run_pipeline(mesh, 18.0, prefix="面-", dxf=str(tmp_path / "cjk.dxf"), **kw)
    assert not (tmp_path / "cjk.dxf").exists()
    run_pipeline(mesh, 18.0, prefix="Ж-", edge="bisector", gap=4,
                 dxf=str(tmp_path / "cyrillic.dxf"), **kw)
    ids = [" ", "A", "B", "C", "D", "E"]
    run_pipeline(mesh, 18.0, ids=ids, dxf=str(tmp_path / "blank.dxf"), **kw)
    import ezdxf

    msp = ezdxf.readfile(tmp_path / "blank.dxf").modelspace()
    assert 0 < len(msp.query("LWPOLYLINE[layer=='LABEL']"))


def test_texts_as_outlines_keep_dollar_signs():
    """ezdxf 0.18's text2path draws with matplotlib, which took the text between two $ for
    mathtext: the ID "A$1$" was written as the outlines of "A1", its $ dropped."""
    import ezdxf
    from ezdxf.enums import TextEntityAlignment

    from facet.cutsheets import _outline_writer

    outline = _outline_writer(TextEntityAlignment.MIDDLE_CENTER)
    counts = {}
    for s in ("A$1$", "A1", "$"):
        msp = ezdxf.new().modelspace()
        outline(msp, s, 0.0, 0.0, 10.0, 0.0, "LABEL")
        counts[s] = len(msp)
    assert counts["$"] > 0
    assert counts["A$1$"] == counts["A1"] + 2 * counts["$"]


@pytest.mark.parametrize("rotation", [0.0, 90.0, 180.0, 270.0, 33.0])
def test_texts_as_outlines_read_along_their_turn_upright(rotation):
    """A text as outlines reads as its TEXT would: first letter first along the turned
    baseline, letters upright to its left (a text turned half round, or mirrored, keeps its
    centre and height, which the test above checks)."""
    import ezdxf
    from ezdxf.enums import TextEntityAlignment
    from shapely.geometry import Polygon

    from facet.cutsheets import _outline_writer

    msp = ezdxf.new("R2010").modelspace()
    _outline_writer(TextEntityAlignment.MIDDLE_CENTER)(msp, "L7", 100.0, 50.0, 10.0,
                                                        rotation, "LABEL")
    contours = [Polygon(e.get_points("xy")) for e in msp.query("LWPOLYLINE")]
    assert len(contours) == 2  # the L, then the 7
    turn = math.radians(rotation)
    along = np.array([math.cos(turn), math.sin(turn)])
    up = np.array([-math.sin(turn), math.cos(turn)])
    ell, seven = contours
    first = np.array(ell.centroid.coords[0])
    last = np.array(seven.centroid.coords[0])
    assert (last - first) @ along > 5.0  # the 7 after the L, along the baseline
    # the L's foot is its lower part: its centroid below the middle of its height
    heights = np.array(ell.exterior.coords) @ up
    assert first @ up < 0.5 * (heights.min() + heights.max()) - 1.0


def test_new_part_ids_of_the_same_panels_keep_the_nesting(tmp_path, monkeypatch):
    """Other part IDs (prefix, scheme) change the texts, not the outlines: run_pipeline
    given the earlier run (``nested``) keeps its placements under the new IDs and writes
    them in the DXF (1,536 panels: the nesting took most of a recompute); other panels, or
    another sheet, are nested again."""
    import ezdxf

    import facet.nest
    from facet.cli_panels import run_pipeline

    calls = []
    nest = facet.nest.nest
    monkeypatch.setattr(facet.nest, "nest", lambda *a, **k: calls.append(1) or nest(*a, **k))
    mesh = translational(nu=4, nv=3, step=1000.0)
    options = dict(gap=6.0, sheet=(2600.0, 1400.0), margin=10.0, spacing=6.0)
    _, ps0, drawings0, result0 = run_pipeline(mesh, 30.0, **options)
    assert calls == [1]
    dxf = str(tmp_path / "index.dxf")
    report, ps, drawings, result = run_pipeline(
        mesh, 30.0, ids="index", prefix="G-", dxf=dxf, nested=(ps0, drawings0, result0),
        **options)
    assert calls == [1] and report["nested"] is False
    assert [p.id for p in ps.panels] == [f"G-{k:04d}" for k in range(12)]
    for old, new in zip(ps0.panels, ps.panels):
        a, b = result0.placements[old.id], result.placements[new.id]
        assert (a.sheet, a.angle_deg, a.x, a.y) == (b.sheet, b.angle_deg, b.x, b.y)
    assert [len(s.parts) for s in result.sheets] == [len(s.parts) for s in result0.sheets]
    assert not facet.nest.verify(result, {d.id: d.footprint for d in drawings})
    labels = {e.dxf.text for e in ezdxf.readfile(dxf).modelspace().query("TEXT[layer=='LABEL']")}
    assert labels == {p.id for p in ps.panels}
    # the same panels: the same nesting and drawings
    report, _, again, same = run_pipeline(mesh, 30.0, panel_set=ps0,
                                          nested=(ps0, drawings0, result0), **options)
    assert (calls, report["nested"], again, same) == ([1], False, drawings0, result0)
    # other outlines (a wider gap), or another sheet: nested again
    report = run_pipeline(mesh, 30.0, nested=(ps0, drawings0, result0),
                          **dict(options, gap=8.0))[0]
    assert calls == [1, 1] and report["nested"] is True
    report = run_pipeline(mesh, 30.0, nested=(ps0, drawings0, result0),
                          **dict(options, sheet=(2700.0, 1400.0)))[0]
    assert calls == [1, 1, 1] and report["nested"] is True
    # a tight nesting asked for: nested again (tightly), and the report says so
    report, _, _, tight = run_pipeline(mesh, 30.0, nested=(ps0, drawings0, result0),
                                       tight=True, **options)
    assert calls == [1, 1, 1, 1] and report["nested"] is True
    assert tight.tight and report["options"]["tight"] is True


def test_renamed_nesting_checks_its_names():
    from facet.nest import NestError, renamed

    result = facet.nest.nest({"a": [(0, 0), (10, 0), (10, 10), (0, 10)],
                              "b": [(0, 0), (5, 0), (5, 5), (0, 5)]}, (100, 100))
    moved = renamed(result, {"a": "x", "b": "y"})
    assert moved.sheets[0].parts == ["x", "y"] and moved.placements["y"].id == "y"
    assert result.sheets[0].parts == ["a", "b"]  # (the original is left as it was)
    with pytest.raises(NestError, match="no new ID for part b"):
        renamed(result, {"a": "x"})
    with pytest.raises(NestError, match="not all different"):
        renamed(result, {"a": "x", "b": "x"})
