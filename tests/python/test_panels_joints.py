"""Every joint's narrowest width, and square joints that overlap on the inner
side of a fold (facet_panel_output.joint; Panel.joint_widths,
PanelSet.narrowest_joint, overlapping_joints, clearing_gap)."""
import csv
import math
import re
from pathlib import Path

import numpy as np
import pytest
from panel_meshes import FOLDS, folded_grid, freecad_step

from facet.mesh import PolyMesh
from facet.panels import PanelError, panels

STEP = 1000.0
THICKNESS = 200.0
GAP = 10.0


def _fold_angle(i):
    """The fold (radians) at the line x = i * STEP of folded_grid: the change
    of slope there, positive where the surface bends up (a valley on top)."""
    before = math.atan(FOLDS[i] - FOLDS[i - 1])
    after = math.atan(FOLDS[i + 1] - FOLDS[i])
    return after - before


def _overlap_depth(fold, gap, t=THICKNESS):
    """How deep two panels cut square overlap across a valley of this fold (radians),
    in the joint's section: the least overlap of the two sections along the normals of
    their edges (each is a half-strip t high, running from its side, half the gap off
    the edge, into its panel). 0 when they do not overlap."""
    run = [np.array([-1.0, 0.0]), np.array([math.cos(fold), math.sin(fold)])]
    normal = [np.array([0.0, 1.0]), np.array([-math.sin(fold), math.cos(fold)])]
    ends = [[gap / 2 * r, gap / 2 * r + t * n] for r, n in zip(run, normal)]
    least = math.inf
    for axis in normal + run:
        lo, hi = [], []
        for r, (p, q) in zip(run, ends):
            lo.append(-math.inf if axis @ r < -1e-12 else min(axis @ p, axis @ q))
            hi.append(math.inf if axis @ r > 1e-12 else max(axis @ p, axis @ q))
        least = min(least, min(hi) - max(lo))
    return max(least, 0.0)


def _joint_line(mesh, panel, k):
    """The fold line index i of a panel's edge k when it runs along x = i * STEP
    (None for an edge across the rows, which is flat)."""
    a, b = panel.vertices[k], panel.vertices[(k + 1) % len(panel.vertices)]
    x0 = mesh.vertices[0][0]
    xa, xb = mesh.vertices[a][0] - x0, mesh.vertices[b][0] - x0
    return int(round(xa / STEP)) if abs(xa - xb) < 1e-9 else None


def test_fold_lines_of_the_mesh_are_a_valley_between_two_ridges():
    # the facts the tests below rely on, so that a change of the mesh shows here
    assert _fold_angle(1) < 0 and _fold_angle(2) > 0 and _fold_angle(3) < 0


@pytest.mark.parametrize("offset", [(0.0, 0.0, 0.0), (2.5e6, 1.2e6, 350.0)])
def test_square_joints_narrow_on_the_inner_side_of_a_fold_and_overlap_in_the_valley(offset):
    mesh = folded_grid()
    mesh = type(mesh).from_faces(mesh.vertices + np.array(offset), mesh.faces())
    ps = panels(mesh, THICKNESS, gap=GAP)
    seen = set()
    for p in ps:
        assert len(p.joint_widths) == len(p.neighbors)
        for k, (n, width) in enumerate(zip(p.neighbors, p.joint_widths)):
            if n is None:
                assert width is None
                continue
            line = _joint_line(mesh, p, k)
            fold = 0.0 if line is None else _fold_angle(line)
            if fold > 0:
                # the top corners meet first; here the panels overlap, as deep as their
                # sections overlap along the normals of their edges
                expected = -_overlap_depth(fold, GAP)
                assert expected < 0
            else:
                # a ridge opens the joint on top; it is narrowest between the bottoms
                expected = GAP * math.cos(fold / 2)
            assert width == pytest.approx(expected, abs=1e-9 * STEP)
            seen.add(line)
    assert seen == {None, 1, 2, 3}
    valley = _fold_angle(2)
    clearing = 2 * THICKNESS * math.tan(valley / 2)
    assert ps.overlapping_joints == 2  # the valley's two edges, one per row
    assert ps.clearing_gap == pytest.approx(clearing, rel=1e-9)
    assert ps.narrowest_joint == pytest.approx(-_overlap_depth(valley, GAP), abs=1e-9 * STEP)
    a, b = ps.narrowest_joint_panels
    assert {ps.by_id(a).face, ps.by_id(b).face} in ({1, 2}, {5, 6})
    (warning,) = [w for w in ps.warnings if "on the inner side of a fold" in w]
    assert warning.startswith("2 joints cut square on the inner side of a fold overlap: "
                              f"the panels {a} and {b} by {-ps.narrowest_joint:.3g}")
    assert f"a gap of {clearing:.3g} (now 10)" in warning and "bisector edges" in warning
    # at the clearing gap they no longer overlap; just below, they do
    wide = panels(mesh, THICKNESS, gap=clearing * (1 + 1e-7))
    assert wide.overlapping_joints == 0 and wide.clearing_gap is None
    assert 0.0 <= wide.narrowest_joint < 1e-6 * STEP
    assert not [w for w in wide.warnings if "on the inner side of a fold" in w]
    assert panels(mesh, THICKNESS, gap=clearing * (1 - 1e-5)).overlapping_joints == 2


def test_mitred_joints_keep_the_gap():
    ps = panels(folded_grid(), THICKNESS, gap=GAP, edge="bisector")
    widths = [w for p in ps for w in p.joint_widths if w is not None]
    assert len(widths) == 2 * (3 * 2 + 4 * 1)  # each interior edge from both sides
    assert np.allclose(widths, GAP, rtol=0.0, atol=1e-9 * STEP)
    assert ps.overlapping_joints == 0 and ps.clearing_gap is None
    assert ps.narrowest_joint == pytest.approx(GAP)


def test_occ_finds_the_same_overlaps_and_widths():
    """The solids as OCC reads them: the valley's panels share volume exactly where
    the joint width is negative, and elsewhere their distance is the width."""
    step = freecad_step()
    mesh = folded_grid()
    for gap in (GAP, 2 * THICKNESS * math.tan(_fold_angle(2) / 2) * (1 + 1e-6)):
        ps = panels(mesh, THICKNESS, gap=gap)
        solids = dict(step.panel_solids(ps))
        checked = 0
        for p in ps:
            for n, width in zip(p.neighbors, p.joint_widths):
                if n is None or n < p.face:
                    continue
                a, b = solids[p.id], solids[ps.panels[n].id]
                common = a.common(b).Volume
                if width < 0:
                    assert common > 1e-6 * a.Volume
                else:
                    assert common < 1e-9 * a.Volume
                    assert a.distToShape(b)[0] == pytest.approx(width, abs=1e-6 * STEP)
                checked += 1
        assert checked == 3 * 2 + 4 * 1


def _valley(fold_deg, length=1000.0, width=800.0):
    """Two quads meeting along the y axis, the second rising on the top side of the
    first by the fold (degrees): 90 is an inner corner of a box."""
    a = math.radians(fold_deg)
    c, s = length * math.cos(a), length * math.sin(a)
    return type(folded_grid()).from_faces(
        [(-length, 0, 0), (0, 0, 0), (0, width, 0), (-length, width, 0), (c, 0, s),
         (c, width, s)], [[0, 1, 2, 3], [1, 4, 5, 2]])


@pytest.mark.parametrize("gap", [0.0, 8.0])
@pytest.mark.parametrize("fold", [60.0, 89.0, 90.0, 120.0, 150.0])
def test_square_joints_overlap_across_sharp_valleys(fold, gap):
    """A valley folded 90 degrees or more (an inner corner) with square cuts: no
    corner of one panel's section lies inside the other (at 90 degrees each lies on
    the other's faces), yet the panels overlap by up to their whole thickness. The
    joint was 0 wide (touching) or open (3 mm at a 100 degree fold and gap 8), the
    panels unflagged, while their solids shared 1.3e6 mm3 (40 mm panels, 800 mm
    joint); the cross-check of facet panels' STEP against its schedule found it."""
    t = 40.0
    ps = panels(_valley(fold), t, gap=gap)
    depth = _overlap_depth(math.radians(fold), gap, t)
    assert depth > 0.5 * t
    assert ps.overlapping_joints == 1
    assert ps.narrowest_joint == pytest.approx(-depth, abs=1e-9 * STEP)
    assert [p.clash for p in ps] == pytest.approx([depth, depth], abs=1e-9 * STEP)
    assert ps.clearing_gap == pytest.approx(2 * t * math.tan(math.radians(fold) / 2),
                                            rel=1e-9)
    if fold == 90.0:
        assert depth == pytest.approx(t - gap / 2)  # the whole thickness, less the gap's half
    # and OCC agrees: the solids share volume, and not at the clearing gap
    step = freecad_step()
    a, b = (s for _, s in step.panel_solids(ps))
    assert a.common(b).Volume > 0.01 * a.Volume
    wide = panels(_valley(fold), t, gap=ps.clearing_gap * (1 + 1e-7))
    assert wide.overlapping_joints == 0 and wide.narrowest_joint >= 0.0
    a, b = (s for _, s in step.panel_solids(wide))
    assert a.common(b).Volume < 1e-9 * a.Volume


def test_schedule_has_each_panels_joint_widths(tmp_path):
    from facet.cli_panels import run_pipeline

    report, ps, _, _ = run_pipeline(folded_grid(), THICKNESS, gap=GAP,
                                    schedule=str(tmp_path / "schedule.csv"))
    with open(tmp_path / "schedule.csv", newline="") as f:
        rows = {r["id"]: r for r in csv.DictReader(f)}
    for p in ps:
        row = rows[p.id]
        cells = row["joint_widths_mm"].split(";")
        assert len(cells) == len(p.vertices)
        for cell, width in zip(cells, p.joint_widths):
            assert (cell == "") == (width is None)
            if width is not None:
                assert float(cell) == width  # full precision
        assert float(row["narrowest_joint_mm"]) == min(w for w in p.joint_widths if w is not None)
        assert float(row["clash_mm"]) == p.clash
    assert report["overlapping_joints"] == 2
    assert report["clearing_gap"] == ps.clearing_gap
    assert tuple(report["narrowest_joint_panels"]) == ps.narrowest_joint_panels


def test_an_edge_a_panel_dropped_has_no_joint():
    # the cut tip's short edge is consumed by the gap and dropped from face 0;
    # face 1 keeps it, facing a corner of face 0, not a joint
    mesh = type(folded_grid()).from_faces(
        [(0, 0, 0), (10, 0, 0), (5.1, 20, 0), (4.9, 20, 0), (12, 24, 0), (-2, 24, 0)],
        [[0, 1, 2, 3], [3, 2, 4, 5]])
    ps = panels(mesh, 0.05, gap=0.4)
    tip, top = ps.panels
    assert tip.dropped_edges == 1
    assert all(w is None for w in tip.joint_widths)
    k = [list(top.vertices[[k, (k + 1) % 4]]) for k in range(4)].index([3, 2])
    assert top.neighbors[k] == 0 and top.joint_widths[k] is None
    assert ps.narrowest_joint is None and ps.overlapping_joints == 0


# Faces 6-9 and 42-45 of WWmore/DOS pillow_1.obj in mm, planarized with the defaults: faces
# 1 and 2 (the pillow's 7 and 8) share an 88 mm edge folded 43 degrees, between a 9 degree
# and a 210 degree corner of face 1 and a 23 and a 194 degree corner of face 2: at 40 mm
# mitred it is consumed on both panels, which are then cut square there.
STUB = Path(__file__).resolve().parents[1] / "data" / "pillow_stub_edge.obj"


def _stub():
    from facet.io import read_mesh

    return read_mesh(str(STUB))


def test_a_joint_one_panel_dropped_is_no_failed_joint():
    """At a 15 mm gap face 1 drops the short edge (its neighbours' edge lines meet before
    it): it has no side there, so the joint is not measured across a section with a
    side the panel lacks; that refused it ("faces 1 and 2 ... overlap by 14.4"). The
    two panels are measured as a node's instead: they do not overlap, and every solid
    is valid and closed."""
    ps = panels(_stub(), 40.0, gap=15.0, edge="bisector", units="mm")
    assert ps.panels[1].dropped_edges == 1
    assert ps.node_clash_pairs == 0 and ps.overlapping_joints == 0
    assert all(p.clash == 0.0 for p in ps)
    step = freecad_step()
    for _pid, solid in step.panel_solids(ps):
        assert solid.isValid() and solid.isClosed() and solid.Volume > 0.0
    solids = dict(step.panel_solids(ps))
    a, b = solids[ps.panels[1].id], solids[ps.panels[2].id]
    assert a.common(b).Volume < 1e-9 * a.Volume


def test_a_failed_joint_says_what_builds_the_panels():
    """At a 10 mm gap the joint had to be cut square on both panels and they overlap: the
    error names the edge, its fold and the corners at its ends, in mm, and the ways that
    were tried and build the panels: the least larger gap, square edges. The advice was
    "use a larger gap or thinner panels, or collapse short edges first", with the
    overlap in no unit ("by 18.7"), and no gap named."""
    mesh = _stub()
    with pytest.raises(PanelError) as caught:
        panels(mesh, 40.0, gap=10.0, edge="bisector", units="mm")
    text = str(caught.value)
    assert caught.value.faces == [1, 2]
    assert "faces 1 and 2:" in text and "overlap by 18.7 mm there" in text, text
    assert "is 88 mm long and folds 43.2 degrees" in text, text
    assert "face 1 210 and 9.06 degrees, face 2 23.3 and 194 degrees" in text, text
    found = re.search(r"a gap of ([0-9.]+) mm \(now 10 mm\) builds the panels", text)
    assert found, text
    built = float(found.group(1))
    assert 10.0 < built < 20.0
    ps = panels(mesh, 40.0, gap=built, edge="bisector", units="mm")
    assert len(ps.panels) == mesh.n_faces
    assert "so do square edges" in text, text
    panels(mesh, 40.0, gap=10.0, edge="square", units="mm")


def test_panel_error_lengths_name_their_unit():
    """Every length in a panel error is followed by the model's unit when it is given
    (the core formatted "the gap 3 leaves ... (the edge ... is 1 long)" and "0 (0.0125)"
    bare, and the point a bare triple), and by none without one."""
    flat = PolyMesh.from_faces([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2, 3]])
    with pytest.raises(PanelError, match=r"the gap 3 mm leaves fewer than three edges of its "
                       r"outline \(the edge from vertex \d is 1 mm long\) \(vertex \d at "
                       r"\([0-9, ]+\) mm\)"):
        panels(flat, 0.01, gap=3.0, units="mm")
    with pytest.raises(PanelError, match=r"the gap 3 leaves .* is 1 long\) \(vertex \d at "
                       r"\([0-9, ]+\)\)$"):
        panels(flat, 0.01, gap=3.0)
    warped = PolyMesh.from_faces([[0, 0, 0], [1, 0, 0], [1, 1, 0.05], [0, 1, 0]], [[0, 1, 2, 3]])
    with pytest.raises(PanelError, match=r"not planar within the tolerance: 0 \(0\.0125 mm\)"):
        panels(warped, 0.01, units="mm")
    with pytest.raises(PanelError, match=r"faces 1 and 2: .* overlap by 18\.7 ft there"):
        panels(_stub(), 40.0, gap=10.0, edge="bisector", units="ft")


def test_a_failed_joint_says_which_min_edge_builds_the_panels(facet_command):
    """The least larger min_edge (relative, as it is given) that builds the panels is
    tried and named, in the caller's terms: a larger min_edge merges the short edge's
    ends into one corner before the panels are cut. The value written was run again and
    builds them; the one a digit below it does not. The advice named no min_edge."""
    mesh = _stub()
    with pytest.raises(PanelError) as caught:
        panels(mesh, 40.0, gap=10.0, edge="bisector", units="mm")
    text = str(caught.value)
    found = re.search(r"; so does min_edge ([0-9.]+) \(now 0\.01\);", text)
    assert found, text
    said = found.group(1)
    ps = panels(mesh, 40.0, gap=10.0, edge="bisector", units="mm", min_edge=float(said))
    assert ps.vanished_edges and ps.overlapping_joints == 0 and ps.node_clash_pairs == 0
    below = float(said) - 10.0 ** (len(said.split(".")[1]) * -1)
    with pytest.raises(PanelError):
        panels(mesh, 40.0, gap=10.0, edge="bisector", units="mm", min_edge=below)
    # the command line names its option
    done = facet_command("panels", STUB, "--thickness", "40", "--gap", "10", "--edge",
                         "bisector")
    assert done.returncode == 2
    assert f"; so does --min-edge {said} (now 0.01);" in done.stderr, done.stderr


def test_a_failed_joint_says_which_min_edge_abs_builds_the_panels():
    """With an absolute min_edge given, its least larger value that builds the panels is
    named too, in the model's unit, as it is given; the value written builds them."""
    mesh = _stub()
    with pytest.raises(PanelError) as caught:
        panels(mesh, 40.0, gap=10.0, edge="bisector", units="mm", min_edge_abs=5.0,
               option_names={"min_edge": "MinEdge", "min_edge_abs": "MinEdgeAbs"})
    text = str(caught.value)
    assert re.search(r"; so does MinEdge [0-9.]+ \(now 0\.01\);", text), text
    found = re.search(r"; so does MinEdgeAbs ([0-9.]+) mm \(now 5 mm\);", text)
    assert found, text
    panels(mesh, 40.0, gap=10.0, edge="bisector", min_edge_abs=float(found.group(1)))
    with pytest.raises(PanelError) as bare:
        panels(mesh, 40.0, gap=10.0, edge="bisector")
    assert "min_edge_abs" not in str(bare.value)


def test_a_failed_joint_reads_as_one_sentence():
    """The core gives either of two reasons ("it would consume a short edge or meet beyond
    a nearly straight corner"); the message says the one the edge's corners give, once,
    and no generic one beside it."""
    with pytest.raises(PanelError) as caught:
        panels(_stub(), 40.0, gap=10.0, edge="bisector", units="mm")
    text = str(caught.value)
    assert "would consume a short edge or meet beyond" not in text, text
    assert text.count("cannot be cut") == 1 and text.count("overlap by") == 1, text
    assert re.search(
        r"faces 1 and 2: their mitre at the edge from vertex 7 to vertex 2 cannot be cut: the "
        r"edge is 88 mm long and folds 43\.2 degrees, the corners at its ends \(vertices 7 and "
        r"2\) are face 1 210 and 9\.06 degrees, face 2 23\.3 and 194 degrees; the gap and the "
        r"bevels consume the edge between those corners on both panels; cut square on both, "
        r"the panels overlap by 18\.7 mm there \(vertex 7 at \([0-9., -]+\) mm\): a gap of ",
        text), text


def test_a_failed_joint_whose_other_face_lacks_the_edge_is_not_explained():
    """The explanation reads the edge on both faces the core names: where the second does
    not hold it (a pinched face), it raised KeyError instead of leaving the core's
    message as it is (review)."""
    from types import SimpleNamespace

    from facet.panels import _failed_joint_message

    mesh = _stub()
    f = 1
    ring = set(int(v) for v in mesh.face_vertices[mesh.face_start[f]:mesh.face_start[f + 1]])
    h = next(g for g in range(mesh.n_faces) if g != f and not ring & set(
        int(v) for v in mesh.face_vertices[mesh.face_start[g]:mesh.face_start[g + 1]]))
    vertex = int(mesh.face_vertices[mesh.face_start[f]])
    exc = SimpleNamespace(joint_faces=(f, h), vertex=vertex, joint_overlap=1.0)
    assert _failed_joint_message(exc, mesh, {}, 10.0, str, None, None, 0.0, None, {},
                                 "") is None


def test_option_errors_name_the_length_unit():
    """A length option out of range is followed by the model's unit ("not 0.0" was bare),
    in facet.panels and in the core; a number that is not finite, or not a length, is
    not."""
    from facet import _core

    flat = PolyMesh.from_faces([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2, 3]])
    for kwargs, said in ((dict(thickness=0.0), "thickness must be a finite number > 0, "
                                               "not 0.0 mm"),
                         (dict(thickness=1.0, gap=-1.0), "gap must be a finite number >= 0, "
                                                        "not -1.0 mm"),
                         (dict(thickness=1.0, min_edge_abs=-2.0), "not -2.0 mm"),
                         (dict(thickness=1.0, tol_abs=-2.0), "not -2.0 mm")):
        with pytest.raises(PanelError, match=re.escape(said) + "$"):
            panels(flat, units="mm", **kwargs)
    with pytest.raises(PanelError, match=r"not 0\.0$"):
        panels(flat, 0.0)
    with pytest.raises(PanelError, match=r"not nan$"):
        panels(flat, float("nan"), units="mm")
    with pytest.raises(PanelError, match=r"min_edge must be a finite number >= 0, not -1\.0$"):
        panels(flat, 1.0, min_edge=-1.0, units="mm")
    xyz = np.array([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 2e30])
    start, faces = np.array([0, 4], dtype=np.int32), np.arange(4, dtype=np.int32)
    with pytest.raises(_core.CoreError, match=r"not 0 mm$"):
        _core.panels(np.where(xyz > 1e30, 0.0, xyz), start, faces, thickness=0.0,
                     length_unit="mm")
    with pytest.raises(_core.CoreError, match=r"not -1 mm$"):
        _core.panels(xyz, start, faces, thickness=1.0, gap=-1.0, length_unit="mm")
    with pytest.raises(_core.CoreError, match=r"beyond 1e30 in magnitude \(2e\+30 mm\)"):
        _core.panels(xyz, start, faces, thickness=1.0, length_unit="mm")


def test_a_failed_joint_names_no_smaller_min_edge_abs_as_the_larger_one():
    """The min_edge_abs tried stops at half the largest face's mean edge: given above it,
    the advice named that smaller value as the one that builds the panels ("so does
    min_edge_abs 288 mm (now 10000 mm)"), where it says the least larger one. It names
    none then; the gap's advice stays."""
    with pytest.raises(PanelError) as caught:
        panels(_stub(), 40.0, gap=10.0, edge="bisector", units="mm", min_edge_abs=1e4)
    text = str(caught.value)
    assert "a gap of " in text, text
    assert "min_edge_abs" not in text, text
