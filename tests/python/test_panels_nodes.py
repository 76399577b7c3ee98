"""Panels that meet at a node but not across a joint there must not overlap
(facet_panel_output.node_clash; PanelSet.node_clashes, node_clash_pairs,
deepest_node_clash_panels)."""
import math
import os

import numpy as np
import pytest
from panel_meshes import freecad_step

import facet
from facet.panels import panels

DATA = os.path.join(os.path.dirname(os.path.dirname(__file__)), "data")
SLOPE = math.tan(math.radians(30.0))
T = 200.0


def _bowl(offset=(0.0, 0.0, 0.0)):
    """Four planar quads around vertex 4, z = s (|x| + |y|): a torsion-free node
    at the bottom of a bowl; faces 0 and 3, 1 and 2 meet only there."""
    pts = [((i - 1) * 1000.0, (j - 1) * 1000.0, SLOPE * 1000.0 * (abs(i - 1) + abs(j - 1)))
           for j in range(3) for i in range(3)]
    faces = [[j * 3 + i, j * 3 + i + 1, (j + 1) * 3 + i + 1, (j + 1) * 3 + i]
             for j in range(2) for i in range(2)]
    return facet.PolyMesh.from_faces(np.array(pts) + np.array(offset), faces)


def _clearing():
    # the edges' fold: cos(fold) = 1 / (1 + 2 s^2); square joints clear at 2 t tan(fold / 2)
    return 2 * T * math.tan(math.acos(1 / (1 + 2 * SLOPE**2)) / 2)


def _non_joint_pairs(ps):
    """(vertex, face, face) for the panels that share a vertex but not an edge joint."""
    joints = {(min(p.face, n), max(p.face, n)) for p in ps
              for n, w in zip(p.neighbors, p.joint_widths) if n is not None and w is not None}
    at = {}
    for p in ps:
        for v in p.vertices:
            at.setdefault(int(v), []).append(p.face)
    return [(v, a, b) for v, faces in at.items() for i, a in enumerate(sorted(faces))
            for b in sorted(faces)[i + 1:] if (a, b) not in joints]


@pytest.mark.parametrize("offset", [(0.0, 0.0, 0.0), (2.5e6, 1.2e6, 350.0)])
def test_square_panels_over_a_valley_node_clash_until_the_joints_clear(offset):
    mesh = _bowl(offset)
    ps = panels(mesh, T, gap=10.0)
    assert ps.node_clash_pairs == 2
    (clash,) = ps.node_clashes
    assert clash["vertex"] == 4 and clash["depth"] > 1.0
    assert sorted(clash["panels"]) == sorted(p.id for p in ps)
    ids = [p.id for p in ps]
    assert set(ps.deepest_node_clash_panels) in ({ids[0], ids[3]}, {ids[1], ids[2]})
    # each panel overlaps its neighbours across the valley's joints and its diagonal at
    # the node: its clash is the deepest of those
    assert [p.id for p in ps.clashing_panels] == ids
    for p in ps:
        deepest_joint = -min(w for w in p.joint_widths if w is not None)
        assert p.clash == pytest.approx(max(deepest_joint, clash["depth"]), rel=1e-12)
        assert p.schedule_row()["clash"] == p.clash
    (warning,) = [w for w in ps.warnings if "meet at a node" in w]
    assert warning.startswith("2 pairs of panels that meet at a node but not across a joint "
                              "overlap there (at 1 node): the panels ")
    assert f"by {clash['depth']:.3g} at vertex 4 (the deepest)" in warning
    # the gap that clears the node is the joints' (the bowl's overlaps end together)
    assert ps.clearing_gap == pytest.approx(_clearing(), rel=2e-4)
    assert ps.clearing_gap >= _clearing() * (1 - 1e-9)
    assert f"a gap of {ps.clearing_gap:.3g} (now 10) clears every overlap" in warning
    wide = panels(mesh, T, gap=_clearing() * (1 + 1e-6))
    assert wide.node_clash_pairs == 0 and wide.node_clashes == []
    assert wide.deepest_node_clash_panels is None
    assert wide.clashing_panels == [] and all(p.clash == 0.0 for p in wide)
    assert not [w for w in wide.warnings if "meet at a node" in w]
    mitred = panels(mesh, T, gap=10.0, edge="bisector")
    assert mitred.max_node_deviation_deg < 1e-6 and mitred.node_clash_pairs == 0


def test_occ_finds_the_bowls_diagonal_panels_overlapping_exactly_when_reported():
    step = freecad_step()
    mesh = _bowl()
    for gap in (10.0, 100.0, _clearing() * (1 + 1e-6)):
        ps = panels(mesh, T, gap=gap)
        solids = [s for _, s in step.panel_solids(ps)]
        for a, b in ((0, 3), (1, 2)):
            common = solids[a].common(solids[b]).Volume
            assert (common > 1e-6 * solids[a].Volume) == (ps.node_clash_pairs > 0), gap


def test_mitred_panels_clash_at_nodes_far_from_torsion_free_as_occ_finds():
    """crossvault_form planarized: nodes up to 28 degrees from a common axis. At
    thickness 5% and gap 1% of the mean edge no mitred joint overlaps, but 20
    pairs of panels meet inside each other at 20 nodes; OCC finds the same
    nodes (every such pair of solids, common volume)."""
    mesh = facet.read_mesh(os.path.join(DATA, "crossvault_form_planar.obj"))
    e = mesh.mean_edge_length()
    ps = panels(mesh, 0.05 * e, gap=0.01 * e, edge="bisector")
    assert ps.overlapping_joints == 0
    assert ps.max_node_deviation_deg > 20.0
    assert ps.node_clash_pairs == 20 and len(ps.node_clashes) == 20
    step = freecad_step()
    solids = [s for _, s in step.panel_solids(ps)]
    occ = {v for v, a, b in _non_joint_pairs(ps)
           if solids[a].common(solids[b]).Volume > 1e-9 * solids[a].Volume}
    assert occ == {c["vertex"] for c in ps.node_clashes}
    # thinner panels with a wider gap clear them; so does the clearing gap alone, found
    # by bisection to 1e-4 of itself
    assert panels(mesh, 0.02 * e, gap=0.02 * e, edge="bisector").node_clash_pairs == 0
    gap = ps.clearing_gap
    assert 0.01 * e < gap < 0.1 * e
    assert panels(mesh, 0.05 * e, gap=gap, edge="bisector").node_clash_pairs == 0
    assert panels(mesh, 0.05 * e, gap=gap * (1 - 2e-4), edge="bisector").node_clash_pairs > 0


def test_the_search_for_the_clearing_gap_reports_progress_and_can_be_cancelled():
    mesh = facet.read_mesh(os.path.join(DATA, "crossvault_form_planar.obj"))
    e = mesh.mean_edge_length()
    seen = []
    panels(mesh, 0.05 * e, gap=0.01 * e, edge="bisector",
           progress=lambda done, total: seen.append((done, total)) and False)
    core = 2 * mesh.n_faces  # the core's own units come first
    search = [(d, t) for d, t in seen if t > core]
    assert search and all(t == core + 40 for _, t in search)
    assert [d for d, _ in search] == list(range(core + 1, core + 1 + len(search)))
    with pytest.raises(facet.Cancelled):
        panels(mesh, 0.05 * e, gap=0.01 * e, edge="bisector",
               progress=lambda done, total: total > core and done > core + 3)


def test_the_command_line_names_the_overlaps(facet_command, tmp_path):
    import json

    facet.write_mesh(_bowl(), tmp_path / "bowl.obj")
    done = facet_command("panels", tmp_path / "bowl.obj", "--thickness", "200", "--gap", "10",
                         "--report", tmp_path / "r.json")
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    (joints,) = [t for t in lines if t.strip().startswith("joints")]
    assert joints.split()[1:3] == ["4", "overlap,"]
    # (the gap that clears the nodes too: the joints warning gives the one for joints alone)
    assert f"{_clearing():.4g} mm clears them and the nodes' overlaps" in joints
    (nodes,) = [t for t in lines if t.strip().startswith("nodes")]
    assert "2 pairs of panels overlap at 1 node, the deepest by" in nodes
    assert "meet at a node but not across a joint" in done.stderr
    # lengths in the model's units (--units, mm by default), as the summary gives them
    assert f"a gap of {_clearing():.3g} mm (now 10 mm) clears every overlap" in done.stderr
    r = json.load(open(tmp_path / "r.json"))
    assert r["overlapping_joints"] == 4 and r["clearing_gap"] == pytest.approx(_clearing())
    assert r["node_clash_pairs"] == 2 and [c["vertex"] for c in r["node_clashes"]] == [4]


def test_concave_panels_are_tested_by_convex_pieces_as_occ_finds():
    """heart.obj planarized: concave panels (corners near 180 degrees). Cut square at
    thickness 5% and gap 1% of the edge, their nodes' overlaps are found by convex
    pieces: every pair OCC finds sharing volume is reported, and a node reported
    beyond those is one where OCC finds the pair touching (an overlap of under 1e-9
    of a panel's volume)."""
    mesh = facet.read_mesh(os.path.join(DATA, "heart_planar.obj"))
    e = mesh.mean_edge_length()
    ps = panels(mesh, 0.05 * e, gap=0.01 * e)
    concave = [p for p in ps if _concave(p)]
    assert len(concave) > 10
    step = freecad_step()
    solids = [s for _, s in step.panel_solids(ps)]
    reported = {c["vertex"] for c in ps.node_clashes}
    pairs = _non_joint_pairs(ps)
    occ = {v for v, a, b in pairs if solids[a].common(solids[b]).Volume > 1e-9 * solids[a].Volume}
    assert occ <= reported and len(occ) >= 15
    # the concave panels' overlaps among them (the corner test alone missed 2 of 15)
    assert any(_concave(ps.panels[a]) or _concave(ps.panels[b])
               for v, a, b in pairs if v in occ)
    for v in reported - occ:
        assert min(solids[a].distToShape(solids[b])[0]
                   for w, a, b in pairs if w == v) < 1e-9 * e


def _concave(panel):
    """Whether a panel's top outline turns both ways."""
    ring, n = panel.top, panel.normal
    k = len(ring)
    turns = [np.dot(np.cross(ring[i] - ring[i - 1], ring[(i + 1) % k] - ring[i]), n)
             for i in range(k)]
    return min(turns) < 0 < max(turns)


def _joint_pairs(ps):
    """(face, face) for the panels that meet across an edge joint."""
    return sorted({(min(p.face, n), max(p.face, n)) for p in ps
                   for n, w in zip(p.neighbors, p.joint_widths) if n is not None and w is not None})


def _heart_mitred():
    # thickness 5.5%, gap 2.2% of the mean edge (0.01 and 0.004): every joint keeps its gap
    # across its section, but P-R12C19 is concave at vertex 31, and the butt joint beside it
    # (to P-R12C20, square there) bevels its short edge by the whole fold (35 degrees): the
    # top reaches past its mitre's plane into P-R13C19 there, 0.000438 deep (OCC: a corner
    # of P-R13C19 that far inside P-R12C19)
    mesh = facet.read_mesh(os.path.join(DATA, "heart_planar.obj"))
    return panels(mesh, 0.01, gap=0.004, edge="bisector")


def test_concave_panels_across_a_joint_are_tested_at_its_reflex_end():
    ps = _heart_mitred()
    assert ps.overlapping_joints == 0 and ps.narrowest_joint == pytest.approx(0.004, rel=1e-5)
    a, b = ps.by_id("P-R12C19"), ps.by_id("P-R13C19")
    assert b.face in a.neighbors  # a joint, not a node's diagonal
    assert a.clash == pytest.approx(4.3849e-4, rel=1e-3)
    assert b.clash == pytest.approx(4.3849e-4, rel=1e-3)
    at31 = [c for c in ps.node_clashes if c["vertex"] == 31]
    assert at31 and at31[0]["depth"] == pytest.approx(4.3849e-4, rel=1e-3)
    # convex panels across a joint stay the joint's to measure: the wave facade's panels
    # (all convex) have no clash
    wave = facet.read_mesh(os.path.join(os.path.dirname(os.path.dirname(DATA)), "examples",
                                        "wave_facade.obj"))
    assert panels(facet.planarize(wave).mesh, 40.0, gap=8.0,
                  edge="bisector").node_clash_pairs == 0


def test_occ_finds_the_joint_pairs_overlapping_that_are_reported():
    """Every pair of panels across a joint whose solids OCC finds sharing volume has
    its overlap reported (clash), at thickness 0.01 and gap 0.004 on heart_planar.obj."""
    ps = _heart_mitred()
    step = freecad_step()
    solids = [s for _, s in step.panel_solids(ps)]
    occ = {(a, b) for a, b in _joint_pairs(ps)
           if solids[a].common(solids[b]).Volume > 1e-9 * solids[a].Volume}
    assert occ, "the mesh no longer has such a pair"
    for a, b in occ:
        assert ps.panels[a].clash > 0 and ps.panels[b].clash > 0, (ps.panels[a].id,
                                                                    ps.panels[b].id)
