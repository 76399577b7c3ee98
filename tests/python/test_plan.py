# SPDX-License-Identifier: LGPL-2.1-or-later
"""Plan graphs from drawings, targets, and the lift / lifting-space commands."""

import json
import math
import re
import sys
from pathlib import Path

import numpy as np
import pytest

import facet
from facet.errors import InputError
from facet.mesh import PolyMesh
from panel_meshes import write_mesh_file
from facet.plan import (
    FREE_WEIGHT,
    PlanError,
    pinned_targets,
    plan_from_mesh,
    plan_from_segments,
    read_plan,
    read_segments,
    read_targets,
    targets_from_mesh,
    targets_from_points,
)

ezdxf = pytest.importorskip("ezdxf")

SQUARE = [((0, 0), (2, 0)), ((2, 0), (2, 2)), ((2, 2), (0, 2)), ((0, 2), (0, 0))]


def nested_points():
    outer = np.array([[0.0, 0.0], [4.0, 0.0], [1.0, 3.0]])
    c = outer.mean(axis=0)
    return outer, c + 0.4 * (outer - c)


def write_nested_dxf(path, *, dangling=True, arc=False):
    document = ezdxf.new()
    space = document.modelspace()
    outer, inner = nested_points()
    space.add_lwpolyline([tuple(p) for p in outer], close=True)
    # The inner triangle as an old-style POLYLINE, the joins as LINEs.
    space.add_polyline2d([tuple(p) for p in inner], close=True)
    for a, b in zip(outer, inner):
        space.add_line(tuple(a), tuple(b))
    if dangling:
        space.add_line((4, 0), (5, -1))
    if arc:
        space.add_arc((2, -1), 1.0, 0, 180)
    document.saveas(path)
    return path


def test_crossings_split_duplicates_merged_dangling_listed():
    segments = SQUARE + [((1, -0.5), (1, 2.5)), ((0, 1), (2, 1)), ((0, 0), (2, 0)),
                         ((2, 2), (3, 3))]
    plan = plan_from_segments(segments)
    assert plan.n_faces == 4 and plan.n_vertices == 9
    assert all(len(f) == 4 for f in plan.mesh.faces())
    assert ((2.0, 2.0), (3.0, 3.0)) in plan.dangling
    assert len(plan.dangling) == 3  # the two overhangs of the vertical line, the diagonal
    # Counter-clockwise faces.
    for face in plan.mesh.faces():
        p = plan.mesh.vertices[face, :2]
        area = 0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])
        assert area > 0


def test_snapping_closes_a_gap():
    gap = [((0, 0), (2, 0)), ((2, 0), (2, 2)), ((2, 2), (0, 2)), ((0, 2), (0, 1e-4))]
    # the message names where the outline is open (it said "4 dangling edges", no place)
    with pytest.raises(PlanError, match=r"no bounded face \(4 dangling edges\); lines end "
                       r"without meeting another at \(0, 0\) and \(0, 0\.0001\): close "
                       r"the outline there"):
        plan_from_segments(gap, snap=1e-6)
    plan = plan_from_segments(gap, snap=1e-3)
    assert plan.n_faces == 1 and plan.snapped == 2


def test_openings_and_holes():
    inner = [((0.5, 0.5), (1.5, 0.5)), ((1.5, 0.5), (1.5, 1.5)), ((1.5, 1.5), (0.5, 1.5)),
             ((0.5, 1.5), (0.5, 0.5))]
    with pytest.raises(PlanError, match="hole"):
        plan_from_segments(SQUARE + inner)
    # one edge to the hole does not split the ring: the advice says two (it said the hole
    # was joined by no edge, and to draw one)
    with pytest.raises(PlanError, match="draw two or more edges from the hole"):
        plan_from_segments(SQUARE + inner + [((0, 0), (0.5, 0.5))])
    # an opening inside the loose hole (the atrium) leaves the face around it with its
    # hole: the advice to mark "the face around the hole" as an opening says where that is
    # (it read as if the opening given had been in the wrong face of two)
    with pytest.raises(PlanError, match=r"or mark the face around the hole as an opening "
                       r"\(a point such as \(.*\)\); the opening at \(1, 1\) is inside the "
                       r"hole, which leaves that face as it is$"):
        plan_from_segments(SQUARE + inner, openings=[(1, 1)])
    joins = [((0, 0), (0.5, 0.5)), ((2, 0), (1.5, 0.5)), ((2, 2), (1.5, 1.5)), ((0, 2), (0.5, 1.5))]
    plan = plan_from_segments(SQUARE + inner + joins, openings=[(1, 1)])
    assert plan.n_faces == 4 and plan.openings == 1
    assert plan_from_segments(SQUARE + inner + joins).n_faces == 5


def test_not_a_plan():
    with pytest.raises(PlanError, match="no bounded face"):
        plan_from_segments([((0, 0), (1, 0)), ((1, 0), (1, 1))])
    with pytest.raises(PlanError, match="segment 1"):
        plan_from_segments([((0, 0), (1, 0)), ((1, 0), (np.nan, 1))])
    xyz = np.array([[0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0], [1, 1, 0]], float)
    overlapping = PolyMesh.from_faces(xyz, [[0, 1, 2, 3], [0, 1, 4]])
    with pytest.raises(PlanError, match="faces 0 and 1 overlap"):
        plan_from_mesh(overlapping)
    bow_tie = PolyMesh.from_faces(xyz, [[0, 1, 3, 2]])
    with pytest.raises(PlanError, match="face 0 crosses itself"):
        plan_from_mesh(bow_tie)


def test_dxf(tmp_path):
    path = write_nested_dxf(tmp_path / "nested.dxf")
    plan = read_plan(path)
    assert plan.n_vertices == 6 and plan.n_faces == 4 and len(plan.dangling) == 1
    arc = write_nested_dxf(tmp_path / "arc.dxf", arc=True)
    with pytest.raises(PlanError, match="ARC .* is curved: give an arc tolerance"):
        read_plan(arc)
    plan = read_plan(arc, arc_tolerance=0.01)
    assert plan.n_faces == 4  # the arc bounds no face: dropped, listed
    assert len(plan.dangling) > 10
    (tmp_path / "empty.dxf").write_bytes(b"")
    with pytest.raises(PlanError, match="empty.dxf"):
        read_plan(tmp_path / "empty.dxf")
    with pytest.raises(PlanError, match="reads .dxf"):
        read_plan(tmp_path / "plan.svg")


def test_targets():
    outer, inner = nested_points()
    plan = plan_from_segments(
        [(tuple(outer[i]), tuple(outer[(i + 1) % 3])) for i in range(3)]
        + [(tuple(inner[i]), tuple(inner[(i + 1) % 3])) for i in range(3)]
        + [(tuple(a), tuple(b)) for a, b in zip(outer, inner)]
    )
    xy = plan.mesh.vertices[:, :2]
    # A big tilted plane as a surface, two triangles: the ray cast finds it.
    surface = PolyMesh.from_faces(
        np.array([[-10, -10, 1.0], [10, -10, 3.0], [10, 10, 5.0], [-10, 10, 3.0]]),
        [[0, 1, 2], [0, 2, 3]],
    )
    z, w = targets_from_mesh(plan, surface)
    assert np.allclose(z, 3.0 + 0.1 * xy[:, 0] + 0.1 * xy[:, 1], atol=1e-12)
    assert np.all(w == 1)
    # Topmost hit: a second, higher sheet wins.
    higher = PolyMesh.from_faces(
        np.vstack([surface.vertices, surface.vertices + [0, 0, 10]]),
        [[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]],
    )
    assert np.allclose(targets_from_mesh(plan, higher)[0], z + 10)
    small = PolyMesh.from_faces(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0.0]]), [[0, 1, 2]])
    with pytest.raises(InputError, match="does not cover plan vertex"):
        targets_from_mesh(plan, small)
    # Same vertices: per-vertex.
    lifted = plan.mesh.with_vertices(np.column_stack([xy, np.arange(6.0)]))
    assert np.array_equal(targets_from_mesh(plan, lifted)[0], np.arange(6.0))
    # Pins and points: the rest free.
    t, w = pinned_targets(plan, {0: 1.0, 1: 2.0, 2: 0.5})
    assert np.count_nonzero(w == 1) == 3 and np.count_nonzero(w == FREE_WEIGHT) == 3
    with pytest.raises(InputError, match="pinned vertex 9"):
        pinned_targets(plan, {9: 1.0})
    points = np.column_stack([xy[:2] + 1e-9, [7.0, 8.0]])
    t, w = targets_from_points(plan, points, tolerance=1e-6)
    assert t[0] == 7.0 and t[1] == 8.0 and np.count_nonzero(w == 1) == 2


def test_lift_command(facet_command, tmp_path):
    plan = write_nested_dxf(tmp_path / "nested.dxf")
    outer, inner = nested_points()
    points = tmp_path / "heights.csv"
    points.write_text("x,y,z\n" + "".join(f"{x!r},{y!r},0\n" for x, y in outer)
                      + "".join(f"{x!r},{y!r},1\n" for x, y in inner))
    out, report = tmp_path / "roof.obj", tmp_path / "r.json"
    done = facet_command("lift", plan, "-o", out, "--targets", points, "--report", report)
    assert done.returncode == 0, done.stderr
    data = json.loads(report.read_text())
    for key in ("vertices", "faces", "dimension", "trivial_dimension", "planarity_max_rel",
                "target_rms", "target_max", "solve_seconds"):
        assert key in data
    assert data["dimension"] == 4 and data["target_max"] < 1e-12
    from facet.io import read_mesh

    roof = read_mesh(out)
    assert roof.n_faces == 4 and sorted(roof.vertices[:, 2].round(9)) == [0, 0, 0, 1, 1, 1]
    weights = tmp_path / "w.txt"
    weights.write_text("1\n1\n1\n")
    done = facet_command("lift", plan, "-o", out, "--targets", points, "--weights", weights)
    assert done.returncode == 2 and "3 weights but the plan has 6" in done.stderr
    done = facet_command("lift", plan, "-o", out)
    assert done.returncode == 2 and "--targets" in done.stderr
    done = facet_command("lift", tmp_path / "missing.dxf", "-o", out, "--pin", "0=1")
    assert done.returncode == 2 and len(done.stderr.strip().splitlines()) == 1


def test_lifting_space_command(facet_command, tmp_path):
    plan = write_nested_dxf(tmp_path / "nested.dxf")
    # the report inside the folder the command makes (the check of the outputs' folders
    # must not refuse it)
    folder = tmp_path / "space"
    report = folder / "s.json"
    done = facet_command("lifting-space", plan, "--basis", "eigen", "-o", folder,
                         "--report", report)
    assert done.returncode == 0, done.stderr
    data = json.loads(report.read_text())
    assert data["dimension"] == 4 and data["count"] == 4
    assert (folder / "eigen_0003.obj").exists() and (folder / "eigen.csv").exists()
    done = facet_command("lifting-space", plan, "--basis", "fundamental", "--count", "2",
                         "-o", folder)
    assert done.returncode == 0 and (folder / "fundamental_0001.obj").exists()


def test_lift_command_moves_a_rounded_drawing(facet_command, tmp_path):
    outer, inner = nested_points()
    c = outer.mean(axis=0)
    turn = 1e-5
    rot = np.array([[np.cos(turn), -np.sin(turn)], [np.sin(turn), np.cos(turn)]])
    inner = c + (inner - c) @ rot.T
    plan = tmp_path / "plan.csv"
    segments = [(outer[i], outer[(i + 1) % 3]) for i in range(3)]
    segments += [(inner[i], inner[(i + 1) % 3]) for i in range(3)] + list(zip(outer, inner))
    plan.write_text("".join(f"{a[0]!r},{a[1]!r},{b[0]!r},{b[1]!r}\n" for a, b in segments))
    points = tmp_path / "heights.csv"
    points.write_text("".join(f"{x!r},{y!r},0\n" for x, y in outer)
                      + "".join(f"{x!r},{y!r},1\n" for x, y in inner))
    out, report = tmp_path / "roof.obj", tmp_path / "r.json"
    done = facet_command("lift", plan, "-o", out, "--targets", points, "--report", report)
    assert done.returncode == 0 and "only the trivial" in done.stdout
    done = facet_command("lift", plan, "-o", out, "--targets", points, "--report", report,
                         "--move-tolerance", "0.001")
    assert done.returncode == 0, done.stderr
    assert "plan moved" in done.stdout
    data = json.loads(report.read_text())
    assert data["within_tolerance"] and data["target_max"] < 1e-6 and data["moved_vertices"]
    done = facet_command("lift", plan, "-o", out, "--targets", points,
                         "--move-tolerance", "1e-12")
    assert done.returncode == 1 and "MORE THAN" in done.stdout


def test_csv_text_with_stray_bytes_and_binary_data(tmp_path):
    # A spreadsheet export in Latin-1 ("Höhe" header, a comment with "ü"):
    # read, the header skipped; the same numbers as a UTF-8 file.
    rows = "".join(f"{a[0]},{a[1]},{b[0]},{b[1]}\n" for a, b in SQUARE)
    latin = tmp_path / "latin.csv"
    latin.write_bytes("x1,y1,x2,y2 Höhe\n# Grundriss Süd\n".encode("latin-1") + rows.encode())
    utf8 = tmp_path / "utf8.csv"
    utf8.write_text(rows)
    a, b = read_plan(latin), read_plan(utf8)
    assert np.array_equal(a.mesh.vertices, b.mesh.vertices)
    # A stray byte on a data line: refused by its line number.
    bad = tmp_path / "bad.csv"
    bad.write_bytes(rows.encode() + b"1,2,3,4\xe9\n")
    with pytest.raises(PlanError, match=r"bad\.csv: line 5: not four numbers"):
        read_plan(bad)
    # Binary data: not a text file, the byte named.
    binary = tmp_path / "binary.csv"
    binary.write_bytes(b"1,2\x00\x01\xff\xfe")
    with pytest.raises(PlanError, match=r"binary\.csv: not a text file: byte 6 is not UTF-8"):
        read_plan(binary)


def test_plan_meshes_whose_faces_meet_without_sharing_vertices_are_named():
    # two unit squares side by side: joined, with their own copies of the shared corners
    # (an export that writes each face on its own), and with a T (the left square's right
    # edge is one edge where the right side has two squares): each was lifted apart,
    # silently, a roof torn along the shared edge
    from facet.lift import lift

    joined = PolyMesh.from_faces([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (2, 0, 0),
                                  (2, 1, 0)], [[0, 1, 2, 3], [1, 4, 5, 2]])
    assert plan_from_mesh(joined).warnings == []
    copies = PolyMesh.from_faces([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (1, 0, 0),
                                  (2, 0, 0), (2, 1, 0), (1, 1, 0)], [[0, 1, 2, 3], [4, 5, 6, 7]])
    warned = plan_from_mesh(copies).warnings
    assert len(warned) == 1 and "but not one vertex: 2 pairs (vertices 1 and 4" in warned[0]
    tee = PolyMesh.from_faces([(0, 0, 0), (1, 0, 0), (1, 2, 0), (0, 2, 0), (2, 0, 0),
                               (2, 1, 0), (1, 1, 0), (2, 2, 0)],
                              [[0, 1, 2, 3], [1, 4, 5, 6], [6, 5, 7, 2]])
    plan = plan_from_mesh(tee)
    assert len(plan.warnings) == 1 and "(vertex 6 on the edge 1-2 of face 0)" in plan.warnings[0]
    result = lift(plan, [0, 0, 0, 0, 0, 0, 1, 0])
    assert plan.warnings[0] in result.warnings


@pytest.mark.parametrize("short, exact", [
    # a line drawn 1e-11 short of the edge it meets (a drawing's rounding): dropped as
    # dangling, a face lost
    ([(5, 0, 5, 10 - 1e-11), (0, 3, 10, 7 + 1e-11)], [(5, 0, 5, 10), (0, 3, 10, 7)]),
    # two ridges meeting the eaves 1e-9 apart: snapped to their mean, off the eaves line
    ([(5, 0, 2, 10), (5, 1e-9, 8, 10)], [(5, 0, 2, 10), (5, 0, 8, 10)]),
])
def test_a_line_within_the_snap_distance_of_another_meets_it(short, exact):
    square = [(0, 0, 10, 0), (10, 0, 10, 10), (10, 10, 0, 10), (0, 10, 0, 0)]
    drawn = plan_from_segments([((a, b), (c, d)) for a, b, c, d in square + short])
    meant = plan_from_segments([((a, b), (c, d)) for a, b, c, d in square + exact])
    assert drawn.dangling == [] and drawn.n_faces == meant.n_faces
    assert drawn.snapped >= 1


def test_dxf_blocks_and_mirrored_polylines_are_read_where_they_are_drawn(tmp_path):
    # a 2 x 2 grid of 10 m squares drawn three ways: LINEs; the inner lines in a block
    # placed by an INSERT (its content was ignored beside other lines); the outline as a
    # mirrored LWPOLYLINE (extrusion 0, 0, -1: its points in a system with z down, read
    # as if they were world coordinates)
    import ezdxf
    from ezdxf.math import OCS

    outline = [(0, 0), (20, 0), (20, 20), (0, 20)]
    inner = [((10, 0), (10, 20)), ((0, 10), (20, 10))]
    plain = ezdxf.new()
    for a, b in zip(outline, outline[1:] + outline[:1]):
        plain.modelspace().add_line(a, b)
    for a, b in inner:
        plain.modelspace().add_line(a, b)
    plain.saveas(tmp_path / "plain.dxf")
    drawn = ezdxf.new()
    block = drawn.blocks.new("INNER")
    for a, b in inner:
        block.add_line((a[0] - 5, a[1] - 5), (b[0] - 5, b[1] - 5))
    drawn.modelspace().add_blockref("INNER", (5, 5))
    ocs = OCS((0, 0, -1))
    drawn.modelspace().add_lwpolyline([tuple(ocs.from_wcs((x, y, 0)))[:2] for x, y in outline],
                                      close=True, dxfattribs={"extrusion": (0, 0, -1)})
    drawn.saveas(tmp_path / "drawn.dxf")
    meant, got = read_plan(tmp_path / "plain.dxf"), read_plan(tmp_path / "drawn.dxf")
    assert meant.n_faces == got.n_faces == 4 and got.dangling == []
    assert sorted(map(tuple, got.mesh.vertices.tolist())) == \
        sorted(map(tuple, meant.mesh.vertices.tolist()))


def test_dxf_layers_that_are_off_or_frozen_are_not_read(facet_command, tmp_path):
    # an architect's plan keeps construction lines, grids and notes on layers turned off;
    # they were read as edges of the plan: here a diagonal that split the square in two
    import ezdxf

    square = [(0, 0), (10, 0), (10, 10), (0, 10)]
    document = ezdxf.new()
    document.layers.add("Construction").off()
    document.layers.add("grid").freeze()
    document.layers.add("Blocks").off()
    space = document.modelspace()
    space.add_lwpolyline(square, close=True, dxfattribs={"layer": "PANELS"})
    space.add_line((0, 0), (10, 10), dxfattribs={"layer": "CONSTRUCTION"})  # any case
    space.add_line((10, 0), (0, 10), dxfattribs={"layer": "Grid"})
    # a block on layer 0 takes its INSERT's layer (off): hidden; its line on a layer
    # that is on is shown; an INSERT on a frozen layer hides all it places
    block = document.blocks.new("MARKS")
    block.add_line((0, 2), (10, 2))
    block.add_line((5, 0), (5, 10), dxfattribs={"layer": "PANELS"})
    space.add_blockref("MARKS", (0, 0), dxfattribs={"layer": "Blocks"})
    space.add_blockref("MARKS", (0, 1), dxfattribs={"layer": "Grid"})
    document.saveas(tmp_path / "plan.dxf")
    plan = read_plan(tmp_path / "plan.dxf")
    assert plan.n_faces == 2  # the square split by the block's line on PANELS only
    assert sorted(len(f) for f in plan.mesh.faces()) == [4, 4]
    # (named as the layer table spells them, whatever the entities' spelling)
    assert plan.warnings[0] == (
        "left out 4 entities on layers that are off or frozen (grid 2, Blocks 1, "
        "Construction 1): turn a layer on (and thaw it) to read what is drawn there")
    assert read_segments(tmp_path / "plan.dxf", notes=None)  # notes are optional
    # both commands say so
    for command in (["lift", "-o", tmp_path / "roof.obj", "--pin", "0=0", "--pin", "1=1",
                     "--pin", "2=3"],
                    ["lifting-space", "-o", tmp_path / "space"]):
        done = facet_command(command[0], tmp_path / "plan.dxf", *command[1:])
        assert done.returncode == 0, done.stderr
        assert "warning       left out 4 entities on layers that are off or frozen" in done.stdout
    # turned on again, the layers are read
    for name in ("Construction", "grid", "Blocks"):
        layer = document.layers.get(name)
        layer.on(), layer.thaw()
    document.saveas(tmp_path / "shown.dxf")
    shown = read_plan(tmp_path / "shown.dxf")
    assert shown.n_faces > 2 and [w for w in shown.warnings if "left out" in w] == []


def test_dxf_block_arrays_and_spline_fit_polylines_are_read_as_drawn(tmp_path):
    # MINSERT (a block placed as rows x columns) gave its first cell only: 1 face for 6
    # bays; a spline-fit POLYLINE was read through its control frame, which is not drawn
    import ezdxf

    document = ezdxf.new()
    bay = document.blocks.new("BAY")
    bay.add_lwpolyline([(0, 0), (4, 0), (4, 3), (0, 3)], close=True)
    document.modelspace().add_blockref("BAY", (0, 0)).grid(size=(2, 3), spacing=(3, 4))
    document.saveas(tmp_path / "array.dxf")
    plan = read_plan(tmp_path / "array.dxf")
    assert plan.n_faces == 6 and plan.n_vertices == 12
    fitted = ezdxf.new()
    line = fitted.modelspace().add_polyline2d([(0, 0), (10, 10), (20, 0)])  # the frame
    for v in line.vertices:
        v.dxf.flags |= 16
    line.append_vertices([(0, 0), (10, 5), (20, 0)], dxfattribs={"flags": 8})
    line.dxf.flags |= 4  # spline-fit
    fitted.saveas(tmp_path / "fitted.dxf")
    assert read_segments(tmp_path / "fitted.dxf") == [((0.0, 0.0), (10.0, 5.0)),
                                                     ((10.0, 5.0), (20.0, 0.0))]


def test_dxf_messages_name_an_entity_of_a_block_by_its_block_and_insert(tmp_path):
    import ezdxf

    document = ezdxf.new()
    block = document.blocks.new("ROUND")
    block.add_lwpolyline([(0, 0, 0.5), (1, 0, 0)], format="xyb")
    insert = document.modelspace().add_blockref("ROUND", (0, 0))
    document.saveas(tmp_path / "round.dxf")
    with pytest.raises(PlanError, match=rf"LWPOLYLINE in block ROUND of INSERT "
                       rf"{insert.dxf.handle} on layer 0 at \(0, 0\) m has arc segments"):
        read_plan(tmp_path / "round.dxf")


def test_a_snap_distance_that_chains_endpoints_is_refused():
    # a front edge drawn in 20 mm steps with a snap of 25: every endpoint was within 25 of
    # the next, and single-linkage snapping merged the whole 10 m curve and both corners
    # into one vertex: two triangles, exit 0
    x = np.arange(0.0, 10001.0, 20.0)
    front = np.column_stack([x, -300.0 * np.sin(np.pi * x / 10000.0)])
    segments = list(zip(map(tuple, front[:-1]), map(tuple, front[1:])))
    segments += [((10000.0, 0.0), (10000.0, 6000.0)), ((10000.0, 6000.0), (0.0, 6000.0)),
                 ((0.0, 6000.0), (0.0, 0.0)), ((5000.0, -300.0), (5000.0, 6000.0))]
    assert plan_from_segments(segments, snap=10.0).n_faces == 2
    with pytest.raises(PlanError, match=r"the snap distance 25 \(snap\) joins 502 endpoints in a "
                       r"chain 10000 wide, from \(0, 0\) to \(10000, "):
        plan_from_segments(segments, snap=25.0)
    # endpoints scattered about a node within the snap distance are one vertex, as before
    node = [((0.0, 0.0), (10.0, 0.0)), ((10.4, 0.3), (10.0, 10.0)), ((9.7, 10.2), (0.0, 10.0)),
            ((0.2, 9.6), (0.0, 0.0))]
    assert plan_from_segments(node, snap=0.6).n_faces == 1


def test_dxf_entities_flagged_invisible_are_not_read():
    # group code 60 (ezdxf does not write it, other CAD programs do): checked in memory
    import ezdxf
    from ezdxf import path as ezpath

    from facet.plan import _dxf_model_segments, _DxfReader

    document = ezdxf.new()
    document.modelspace().add_line((0, 0), (1, 0))
    document.modelspace().add_line((0, 1), (1, 1), dxfattribs={"invisible": 1})
    notes = []
    reader = _DxfReader("plan.dxf", document, None, ezpath)
    segments = _dxf_model_segments(reader, document, notes)
    assert segments == [((0.0, 0.0), (1.0, 0.0))]
    assert notes == ["left out 1 entity flagged invisible: make the entity visible to read "
                     "what is drawn there"]


def test_dxf_with_everything_hidden_says_so(tmp_path):
    import ezdxf

    document = ezdxf.new()
    document.layers.add("OLD").off()
    document.modelspace().add_lwpolyline([(0, 0), (1, 0), (1, 1)], close=True,
                                         dxfattribs={"layer": "OLD"})
    document.saveas(tmp_path / "hidden.dxf")
    with pytest.raises(PlanError, match=r"no LINE, LWPOLYLINE or POLYLINE in the model space "
                       r"\(nothing; 1 entity on layers that are off or frozen \(OLD 1\), "
                       r"left out\)"):
        read_plan(tmp_path / "hidden.dxf")


@pytest.mark.parametrize("tolerance, says", [
    (0.0, "the arc tolerance must be a finite number > 0, not 0.0"),
    (-1.0, "the arc tolerance must be a finite number > 0, not -1.0"),
    (float("nan"), "the arc tolerance must be a finite number > 0, not nan"),
    # millions of segments: ten minutes and 6 GB before it was stopped
    (1e-9, "ARC .*: the arc tolerance 1e-09 m \\(arc_tolerance\\) would split it into more "
     "than 2000 straight"),
])
def test_arc_tolerance_is_checked(tmp_path, tolerance, says):
    # a bad tolerance was reported as "a malformed entity", blaming the drawing
    arc = write_nested_dxf(tmp_path / "arc.dxf", arc=True)
    with pytest.raises(PlanError, match=says):
        read_plan(arc, arc_tolerance=tolerance)


def test_an_opening_in_no_face_and_a_vertex_pinned_twice_are_refused(tmp_path):
    # both did nothing, silently: the face meant to stay open got a panel; the first pin
    # was dropped
    from facet import cli

    with pytest.raises(PlanError, match=r"the opening at \(5, 5\) lies in no face"):
        plan_from_segments(SQUARE, openings=[(5, 5)])
    with pytest.raises(PlanError, match="lies in no face"):
        plan_from_segments(SQUARE, openings=[(0, 1)])  # on an edge
    plan = tmp_path / "square.csv"
    plan.write_text("".join(f"{a},{b},{c},{d}\n" for (a, b), (c, d) in SQUARE))
    assert cli.main(["lift", str(plan), "-o", str(tmp_path / "o.obj"), "--pin", "0=0",
                     "--pin", "0=1"]) == 2
    assert not (tmp_path / "o.obj").exists()


def test_an_opening_that_is_not_a_finite_point_is_refused_by_its_index():
    # (nan, nan) failed inside shapely with "index out of range" and a traceback in FreeCAD
    for bad, shown in (((math.nan, math.nan), "nan, nan"), ((1.0, math.inf), "1, inf")):
        with pytest.raises(PlanError, match=rf"opening 1 at \({shown}\) is not a finite point"):
            plan_from_segments(SQUARE, openings=[(0.5, 0.5), bad])
    with pytest.raises(PlanError, match=r"openings must be \(x, y\) points"):
        plan_from_segments(SQUARE, openings=[(0.5, 0.5, 0.0)])


def test_pins_that_no_planar_lifting_meets_are_named(tmp_path, capsys):
    from facet import cli

    plan = tmp_path / "square.csv"
    plan.write_text("".join(f"{a},{b},{c},{d}\n" for (a, b), (c, d) in SQUARE))
    pins = ["--pin", "0=0", "--pin", "1=0", "--pin", "2=1", "--pin", "3=0"]  # a twisted quad
    assert cli.main(["lift", str(plan), "-o", str(tmp_path / "o.obj"), *pins]) == 0
    assert "no planar lifting meets every pin: the closest misses vertex" in \
        capsys.readouterr().out
    flat = ["--pin", "0=0", "--pin", "1=1", "--pin", "2=2"]
    assert cli.main(["lift", str(plan), "-o", str(tmp_path / "o.obj"), *flat]) == 0
    assert "meets every pin" not in capsys.readouterr().out


def test_long_polylines_are_not_taken_for_fine_curves(tmp_path):
    # the cap on a curve's segments counted a polyline's own vertices: a mirrored
    # 2,500-vertex outline, or one with a single bulge, was refused
    import ezdxf

    ring = [(math.cos(2 * math.pi * k / 2500), math.sin(2 * math.pi * k / 2500))
            for k in range(2500)]
    mirrored = ezdxf.new()
    mirrored.modelspace().add_lwpolyline(ring, close=True, dxfattribs={"extrusion": (0, 0, -1)})
    mirrored.saveas(tmp_path / "mirrored.dxf")
    segments = read_segments(tmp_path / "mirrored.dxf")
    assert len(segments) == 2500
    assert min(a[0] for a, _b in segments) == pytest.approx(-1.0)
    bulged = ezdxf.new()
    bulged.modelspace().add_lwpolyline([(x, y, 0, 0, 0.1 if k == 0 else 0)
                                        for k, (x, y) in enumerate(ring)],
                                       format="xyseb", close=True)
    bulged.saveas(tmp_path / "bulged.dxf")
    assert len(read_segments(tmp_path / "bulged.dxf", arc_tolerance=0.01)) > 2500


def test_a_nan_pin_is_refused_by_name(tmp_path, capsys):
    from facet import cli

    plan = tmp_path / "square.csv"
    plan.write_text("".join(f"{a},{b},{c},{d}\n" for (a, b), (c, d) in SQUARE))
    assert cli.main(["lift", str(plan), "-o", str(tmp_path / "o.obj"), "--pin", "0=0",
                     "--pin", "1=nan"]) == 2
    assert "pinned height of vertex 1 is nan" in capsys.readouterr().err


def test_the_example_plan_lifts_as_the_readme_says(facet_command, tmp_path):
    # examples/roof_plan.dxf and roof_heights.csv: the README's lift command
    root = Path(__file__).resolve().parents[2]
    plan, heights = root / "examples" / "roof_plan.dxf", root / "examples" / "roof_heights.csv"
    out, report = tmp_path / "roof.obj", tmp_path / "roof.json"
    done = facet_command("lift", plan, "-o", out, "--targets", heights, "--report", report)
    assert done.returncode == 0, done.stderr
    assert "left out 5 entities on layers that are off or frozen (CONSTRUCTION 5)" in done.stdout
    data = json.loads(report.read_text())
    assert (data["plan"]["vertices"], data["plan"]["faces"], data["dimension"]) == (12, 7, 7)
    roof = facet.read_mesh(out)
    assert float(np.max(facet.planarity(roof).max_rel)) <= 1e-9
    pins = np.loadtxt(heights, delimiter=",", skiprows=1)
    for x, y, z in pins:
        v = int(np.argmin(np.hypot(roof.vertices[:, 0] - x, roof.vertices[:, 1] - y)))
        assert abs(roof.vertices[v, 2] - z) <= 1e-3  # mm
    # the files are what tools/make_example_plan.py writes (the plan of roof.FCStd)
    sys.path.insert(0, str(root / "tools"))
    try:
        import make_example_plan
    finally:
        sys.path.remove(str(root / "tools"))
    make_example_plan.write_plan_dxf(tmp_path / "again.dxf")
    make_example_plan.write_heights_csv(tmp_path / "again.csv")
    assert read_segments(tmp_path / "again.dxf") == read_segments(plan)
    assert (tmp_path / "again.csv").read_text() == heights.read_text()


def test_lifting_space_writes_twenty_liftings_unless_asked(facet_command, tmp_path):
    # --basis fundamental wrote one OBJ per vertex by default: 961 files and 88 MB for a
    # 30 x 30 plan
    plan = tmp_path / "grid.csv"
    lines = [f"0,{y!r},6,{y!r}\n" for y in range(7)] + [f"{x!r},0,{x!r},6\n" for x in range(7)]
    plan.write_text("".join(lines))
    done = facet_command("lifting-space", plan, "--basis", "fundamental", "-o",
                         tmp_path / "space")
    assert done.returncode == 0, done.stderr
    assert len(list((tmp_path / "space").glob("fundamental_*.obj"))) == 20
    assert "the first 20 of 49; --count K writes more" in done.stdout


def test_a_target_drawn_on_the_plan_outline_covers_its_corners():
    # a surface lofted from the plan's outline and exported with 3 decimals missed the
    # corners by 0.4 micrometres: "does not cover plan vertex", exit 2
    corners = [(0.0004, 0.0004), (10000.0004, 0.0004), (10000.0004, 6000.0004),
               (0.0004, 6000.0004)]
    plan = plan_from_segments(list(zip(corners, corners[1:] + corners[:1]))
                              + [((0.0004, 0.0004), (10000.0004, 6000.0004))])
    rounded = [(round(x, 3), round(y, 3), 1000 + 0.1 * round(x, 3)) for x, y in corners]
    surface = PolyMesh.from_faces(rounded, [[0, 1, 2, 3]])
    targets, _ = targets_from_mesh(plan, surface)
    xy = plan.mesh.vertices[:, :2]
    assert np.allclose(targets, 1000 + 0.1 * xy[:, 0], atol=1e-3)
    # farther out than the tolerance: said, with the tolerance
    with pytest.raises(InputError, match=r"does not cover plan vertex .* none within "
                       r"1e-07 of its edge in plan"):
        targets_from_mesh(plan, surface, tolerance=1e-7)


def test_free_vertices_do_not_pull_the_pins_off():
    # 5 pins on a 30 x 30 plan (956 free vertices at 1e-6 each) were missed by 0.09 mm
    # in 30 m (1.8 mm on a 60 x 60 plan, where the command said no lifting met every pin)
    from facet.lift import lift

    n = 30
    i, j = np.meshgrid(np.arange(n + 1.0), np.arange(n + 1.0), indexing="xy")
    x = (i + 0.3 * np.sin(0.3 * i + 0.1 * j)).ravel()
    y = (j + 0.3 * np.cos(0.2 * j + 0.1 * i)).ravel()
    faces = [[r * (n + 1) + c, r * (n + 1) + c + 1, (r + 1) * (n + 1) + c + 1,
              (r + 1) * (n + 1) + c] for r in range(n) for c in range(n)]
    plan = PolyMesh.from_faces(np.column_stack([x, y, np.zeros_like(x)]), faces)
    middle = (n // 2) * (n + 1) + n // 2
    pins = {0: 0.0, n: 0.0, n * (n + 1): 0.0, (n + 1) ** 2 - 1: 0.0, middle: 8.0}
    targets, weights = pinned_targets(plan, pins)
    assert weights[1] == pytest.approx(FREE_WEIGHT * 5 / (len(x) - 5))
    result = lift(plan, targets, weights)
    misses = [abs(result.heights[v] - z) for v, z in pins.items()]
    assert max(misses) < 1e-5, misses


def test_just_outside_a_target_with_a_fascia_takes_the_topmost_edge():
    # a flat roof at z = 10 with a vertical fascia down to 0 on its east edge, the plan's
    # east corners 1e-7 outside it: the height was 10 or 0 by the faces' order (review)
    corners = [(0, 0), (10 + 1e-7, 0), (10 + 1e-7, 6), (0, 6)]
    plan = plan_from_segments(list(zip(corners, corners[1:] + corners[:1])))
    xyz = np.array([(0, 0, 10), (10, 0, 10), (10, 6, 10), (0, 6, 10), (10, 0, 0), (10, 6, 0)],
                   float)
    for faces in ([[0, 1, 2, 3], [1, 4, 5, 2]], [[1, 4, 5, 2], [0, 1, 2, 3]]):
        targets, _ = targets_from_mesh(plan, PolyMesh.from_faces(xyz, faces))
        assert np.array_equal(targets, np.full(4, 10.0))


def test_a_snap_node_narrower_than_twice_the_snap_is_no_chain():
    # four lines drawn 0.95 short of a node and a fifth through it, snap 1: every end is
    # within 1 of the node and no two are 2 apart; the box's diagonal (2.7) was taken
    # for the spread and the drawing refused (review)
    segments = [((-10, -10), (10, -10)), ((10, -10), (10, 10)), ((10, 10), (-10, 10)),
                ((-10, 10), (-10, -10)), ((0.95, 0), (10, 0)), ((-0.95, 0), (-10, 0)),
                ((0, 0.95), (0, 10)), ((0, -0.95), (0, -10)), ((0, 0), (10, 10))]
    assert plan_from_segments(segments, snap=1.0).n_faces == 5


def test_a_snap_node_of_thousands_of_endpoints_is_judged_by_its_true_spread():
    # 2,100 spokes end on a circle of radius 0.95 about their hub, snap 1: one vertex, no
    # two ends 2 apart. Above 2,000 endpoints the box's diagonal (2.69) was taken for the
    # spread and the plan refused, naming two ends 1.9 apart
    n = 2100
    angle = 2.0 * np.pi * np.arange(n) / n
    ring = np.column_stack([np.cos(angle), np.sin(angle)])
    inner, outer = 0.95 * ring, 700.0 * ring
    segments = [(tuple(a), tuple(b)) for a, b in zip(inner, outer)]
    segments += [(tuple(outer[i]), tuple(outer[(i + 1) % n])) for i in range(n)]
    plan = plan_from_segments(segments, snap=1.0)
    assert (plan.n_vertices, plan.n_faces) == (n + 1, n)
    # and a cluster as large that is a chain is still refused, with its true ends
    with pytest.raises(PlanError, match=r"joins 2100 endpoints in a chain 4 wide, from \(-1.9999"):
        plan_from_segments([(tuple(2.0 * a), tuple(b)) for a, b in zip(ring, outer)]
                           + segments[n:], snap=1.0)


def test_targets_and_plans_from_a_spreadsheet_s_unicode_text(tmp_path):
    # Excel's "Unicode Text" export: UTF-16 with a byte order mark, tab-separated, .txt;
    # refused as "not a text file: byte 1 is not UTF-8" (and .txt not read at all)
    from facet.plan import read_plan, read_targets

    square = [((0, 0), (10, 0)), ((10, 0), (10, 10)), ((10, 10), (0, 10)), ((0, 10), (0, 0)),
              ((5, 0), (5, 10))]
    table = "x1\ty1\tx2\ty2\r\n" + "".join(f"{a[0]}\t{a[1]}\t{b[0]}\t{b[1]}\r\n"
                                           for a, b in square)
    (tmp_path / "plan.txt").write_bytes(table.encode("utf-16"))
    plan = read_plan(tmp_path / "plan.txt")
    assert plan.n_faces == 2
    points = "x\ty\tz\r\n0\t0\t1.5\r\n10\t10\t2.5\r\n"
    (tmp_path / "heights.txt").write_bytes(points.encode("utf-16"))
    (tmp_path / "heights.csv").write_bytes(b"\xef\xbb\xbf0,0,1.5\r\n10,10,2.5\r\n")  # CSV UTF-8
    for name in ("heights.txt", "heights.csv"):
        targets, weights = read_targets(plan, tmp_path / name)
        given = weights > weights.min()
        assert sorted(targets[given]) == [1.5, 2.5]


def test_two_target_points_at_one_vertex_with_two_heights_are_refused(tmp_path):
    """Two points of a table within the match distance of one vertex, at different
    heights (two readings of a survey, tables joined): the nearest was taken and the other
    dropped without a word. Now refused, naming both lines and heights; the same point
    twice at one height is taken."""
    from facet.plan import read_targets

    plan = plan_from_mesh(PolyMesh.from_faces(
        np.array([[0, 0, 0], [10, 0, 0], [10, 10, 0], [0, 10, 0.0]]), [[0, 1, 2, 3]]))
    table = tmp_path / "heights.csv"
    table.write_text("x,y,z\n0,0,1\n10,0,2\n10,10,3\n0,10,4\n10.000001,0,2.5\n")
    with pytest.raises(InputError, match=r"heights.csv: two target points at plan vertex 1 "
                       r"give it different heights: line 3 gives 2 and line 6 2.5, both within the "
                       r"match distance of it: keep the one meant"):
        read_targets(plan, table, tolerance=1e-3)
    table.write_text("x,y,z\n0,0,1\n10,0,2\n10,10,3\n0,10,4\n10.000001,0,2\n")
    targets, weights = read_targets(plan, table, tolerance=1e-3)
    assert targets.tolist() == [1, 2, 3, 4] and np.all(weights == 1)


def test_target_points_that_reach_no_vertex_are_refused_by_line(tmp_path):
    # A georeferenced 30 m quad plan and a table of its corners' heights rounded to
    # 0.1 mm: the default match distance (1e-6 of the plan's size, 3e-5) left 84 of the
    # 121 vertices free without a word, and the lifting missed their heights by 5 cm.
    from facet.plan import read_targets

    rng = np.random.default_rng(0)
    k = 10
    grid = np.stack(np.meshgrid(np.arange(k + 1) * 3.0, np.arange(k + 1) * 3.0), -1)
    corners = grid + rng.uniform(-0.3, 0.3, grid.shape) + [512345.678, 5712345.678]
    xy = corners.reshape(-1, 2)
    faces = [[i * (k + 1) + j, i * (k + 1) + j + 1, (i + 1) * (k + 1) + j + 1,
              (i + 1) * (k + 1) + j] for i in range(k) for j in range(k)]
    plan = plan_from_mesh(PolyMesh.from_faces(np.column_stack([xy, np.zeros(len(xy))]), faces))
    table = tmp_path / "heights.csv"
    table.write_text("x,y,z\n" + "".join(f"{x:.4f},{y:.4f},20\n" for x, y in xy))
    with pytest.raises(InputError, match=r"heights.csv: 84 of the 121 target points lie "
                       r"near a plan vertex but farther than the match distance 3.059\d*e-05 "
                       r"\(tolerance\); the nearest of them, "
                       r"line \d+ at \(512\d{3}\.\d+, 57\d{5}\.\d+\), .*give a larger "
                       r"match distance"):
        read_targets(plan, table)
    targets, weights = read_targets(plan, table, tolerance=1e-4)
    assert np.all(weights == 1) and np.all(targets == 20)
    # given as numbers: named by their place; a point far from every vertex (a denser
    # survey than the plan) is left out
    points = np.column_stack([np.vstack([xy[:3], xy[:1] + 1.0]), [20.0, 21.0, 22.0, 23.0]])
    points[1, :2] += 0.01
    with pytest.raises(InputError, match=r"1 of the 4 target points lies near .* point 2 at"):
        targets_from_points(plan, points, tolerance=1e-3)
    targets, weights = targets_from_points(plan, points, tolerance=0.02)
    assert list(targets[:3]) == [20.0, 21.0, 22.0] and np.count_nonzero(weights == 1) == 3
    # a plan vertex no face uses has no edge to measure "just beyond" by: a point nearest
    # it (here 0.7 from it) was refused as meant for it ("is 0.707 from vertex 121")
    loose = plan_from_mesh(PolyMesh(np.vstack([plan.mesh.vertices, [[xy[0, 0] - 50.0,
                                                                     xy[0, 1], 0.0]]]),
                                    plan.mesh.face_start, plan.mesh.face_vertices))
    points = np.column_stack([xy, np.full(len(xy), 20.0)])
    points = np.vstack([points, [xy[0, 0] - 50.5, xy[0, 1] + 0.5, 3.0]])
    targets, weights = targets_from_points(loose, points, tolerance=1e-4)
    assert np.count_nonzero(weights == 1) == len(xy) and np.all(targets[weights == 1] == 20)
    # a survey denser than the plan, every vertex's own point in it too: a survey point
    # 1 cm from a vertex matched (within 1% of its edges) was refused as meant for it,
    # and --snap, as advised, then found two heights at that vertex
    points = np.column_stack([xy, np.full(len(xy), 20.0)])
    points = np.vstack([points, [xy[5, 0] + 0.01, xy[5, 1], 20.3]])
    targets, weights = targets_from_points(plan, points, tolerance=1e-4)
    assert np.all(weights == 1) and np.all(targets == 20)


def test_a_dxf_in_metres_or_inches_read_in_millimetres_on_request(tmp_path):
    """FreeCAD's documents are in millimetres, and a PlanGraph read a DXF drawn in metres
    as a plan a thousand times too small. read_plan(to_mm=True) scales a DXF by its
    $INSUNITS (exactly: 25.4 per inch), the arc tolerance given in millimetres, and says
    so; without it (the command line) a drawing is read in its own units, as before."""
    for code, scale in ((6, 1000.0), (1, 25.4), (4, 1.0), (0, 1.0)):
        document = ezdxf.new()
        document.units = code
        space = document.modelspace()
        space.add_lwpolyline([(0, 0), (12, 0), (12, 6), (0, 6)], close=True)
        space.add_arc((6, 6), 6.0, 0, 180)  # over the top edge: one more face
        path = tmp_path / f"units{code}.dxf"
        document.saveas(path)
        plan = read_plan(path, to_mm=True, arc_tolerance=0.001 * scale)
        xy = plan.mesh.vertices[:, :2]
        assert list(np.ptp(xy, axis=0)) == [12.0 * scale, 12.0 * scale]
        assert plan.n_faces == 2
        notes = [w for w in plan.warnings if "$INSUNITS" in w]
        assert len(notes) == (scale != 1.0)
        if code == 6:
            assert notes == ["drawn in metres ($INSUNITS 6): read in millimetres, "
                             "scaled by 1000"]
        # the arc split as finely in millimetres as in the drawing's units
        drawn = read_plan(path, arc_tolerance=0.001)
        assert drawn.n_vertices == plan.n_vertices
        assert np.ptp(drawn.mesh.vertices[:, 0]) == 12.0
        assert not [w for w in drawn.warnings if "$INSUNITS" in w]


def _read_in_stages(path, faces, stops):
    """read_plan(path) with progress: its ``faces`` faces read in PLAN_STAGES stages with
    steps between them (through the faces), and cancelled at each of ``stops`` calls and
    at the last; returns the calls, [(done, total)]."""
    from facet.errors import Cancelled
    from facet.plan import PLAN_STAGES, PLAN_STEPS

    calls = []
    plan = read_plan(path, progress=lambda done, total: calls.append((done, total)) and False)
    assert plan.n_faces == faces
    total = PLAN_STAGES * PLAN_STEPS
    assert {t for _, t in calls} == {total}
    done = [d for d, _ in calls]
    assert done == sorted(done) and done[0] == 0 and done[-1] == total
    assert {d // PLAN_STEPS for d in done} == set(range(PLAN_STAGES + 1))
    assert len(calls) > PLAN_STAGES + 1  # steps through the faces too
    for stop in stops + (len(calls) - 1,):
        seen = []
        with pytest.raises(Cancelled, match="reading the plan cancelled"):
            read_plan(path, progress=lambda done, total: seen.append(done) or len(seen) == stop)
        assert len(seen) == stop
    return calls


def test_reading_a_plan_reports_its_stages_and_can_be_cancelled(tmp_path):
    """Reading a 200 x 200 grid plan (40,000 faces) took 8 s with no progress and no way to
    stop it but to kill FreeCAD: read_plan and plan_from_segments now report their stages
    (and steps through the faces), and True from progress cancels."""
    from facet.errors import Cancelled
    from facet.plan import PLAN_STEPS

    n = 60
    path = tmp_path / "grid.csv"
    path.write_text("".join(f"0,{k},{n},{k}\n{k},0,{k},{n}\n" for k in range(n + 1)))
    _read_in_stages(path, n * n, (1, 4))
    segments = [((0, k), (n, k)) for k in range(n + 1)] + [((k, 0), (k, n)) for k in range(n + 1)]
    with pytest.raises(Cancelled):
        plan_from_segments(segments, progress=lambda done, total: done >= 4 * PLAN_STEPS)


def grid_mesh(n, size=1.0):
    """An n x n grid of square faces (z 0.5: a plan mesh exported from a 3D model)."""
    k = np.arange(n + 1) * size
    xy = np.array([(x, y) for y in k for x in k])
    faces = [[j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1,
              (j + 1) * (n + 1) + i] for j in range(n) for i in range(n)]
    return PolyMesh.from_faces(np.column_stack([xy, np.full(len(xy), 0.5)]), faces)


@pytest.mark.parametrize("suffix", [".obj", ".off", ".json"])
def test_reading_a_plan_mesh_reports_its_stages_and_can_be_cancelled(tmp_path, suffix):
    """Reading a plan mesh (a 200 x 200 grid .obj, 40,000 faces, took 1.2 s, a 320 x 320 one
    3 s, half of it in the union of the faces) reported nothing and could not be stopped:
    it now reports the same PLAN_STAGES stages as a drawing (and steps through the faces),
    and True from progress cancels."""
    from facet.errors import Cancelled
    from facet.plan import PLAN_STAGES, PLAN_STEPS

    n = 50
    path = tmp_path / f"grid{suffix}"
    write_mesh_file(grid_mesh(n), path)
    calls = _read_in_stages(path, n * n, (1, 3, 5))
    with pytest.raises(Cancelled, match="reading the plan cancelled"):
        plan_from_mesh(grid_mesh(n), progress=lambda done, total: done >= 4 * PLAN_STEPS)
    # without a check of overlaps (the Lifting's plan) its stages are skipped
    calls.clear()
    plan_from_mesh(grid_mesh(3), check_overlap=False,
                   progress=lambda done, total: calls.append(done) and False)
    assert [d // PLAN_STEPS for d in calls] == [1, 2, 5, PLAN_STAGES]


def test_reading_a_plan_mesh_file_steps_through_its_first_stage(tmp_path):
    """The file of a plan mesh (2.3 s for a 100,000-face compas JSON) is read in steps of
    the first stage, not one."""
    from facet.io import write_mesh
    from facet.plan import PLAN_STEPS

    path = tmp_path / "grid.obj"
    write_mesh(grid_mesh(130), path)  # 34,000 lines: steps at 16,384 and 32,768
    calls = []
    read_plan(path, progress=lambda done, total: calls.append(done) and False)
    assert len([d for d in calls if 0 < d < PLAN_STEPS]) == 2


def test_matching_targets_on_a_mesh_reports_progress_and_can_be_cancelled(tmp_path):
    """The ray cast of a 320 x 320 plan's vertices (103,041) on a target mesh took 2 s with
    no progress and no way to stop it (the Lifting's recompute, facet lift --targets):
    targets_from_mesh and read_targets now count the plan's vertices, and True from
    progress cancels."""
    from facet.errors import Cancelled
    from facet.io import write_mesh

    n = 90  # 8,281 plan vertices: two steps and the end
    plan = plan_from_mesh(grid_mesh(n))
    target = grid_mesh(7, size=n / 7.0)
    target = target.with_vertices(target.vertices + [[0.0, 0.0, 3.0]])
    path = tmp_path / "target.obj"
    write_mesh(target, path)
    for read in (lambda progress: targets_from_mesh(plan, target, progress=progress),
                 lambda progress: read_targets(plan, path, progress=progress)):
        calls = []
        targets, _ = read(lambda done, total: calls.append((done, total)) and False)
        np.testing.assert_allclose(targets, 3.5)
        assert {t for _, t in calls} == {plan.n_vertices}
        done = [d for d, _ in calls]
        assert done == sorted(done) and done[0] == 0 and done[-1] == plan.n_vertices
        assert len(set(done)) >= 4
        for stop in (1, 2, len(calls) - 1):
            seen = []
            with pytest.raises(Cancelled, match="matching the targets cancelled"):
                read(lambda done, total: seen.append(done) or len(seen) == stop)
            assert len(seen) == stop


def test_any_drawing_read_at_a_given_unit(tmp_path):
    """A table or mesh has no unit and a DXF's $INSUNITS can be wrong: read_plan(units_mm=)
    reads any of them at that many millimetres a unit, snap and arc tolerance in
    millimetres, and says where a DXF's $INSUNITS disagrees; a unit that is no length is
    refused, naming the file."""
    rect = [((0, 0), (9, 0)), ((9, 0), (9, 6)), ((9, 6), (0, 6)), ((0, 6), (0, 0)),
            ((3, 0), (3, 6))]
    table = tmp_path / "plan.csv"
    table.write_text("".join(f"{a[0]},{a[1]},{b[0]},{b[1]}\n" for a, b in rect))
    document = ezdxf.new()
    document.units = 1  # said inches, drawn in metres
    for a, b in rect:
        document.modelspace().add_line(a, b)
    drawing = tmp_path / "plan.dxf"
    document.saveas(drawing)
    for path in (table, drawing):
        plan = read_plan(path, units_mm=1000.0, to_mm=True, snap=1.0)
        assert list(np.ptp(plan.mesh.vertices[:, :2], axis=0)) == [9000.0, 6000.0]
        assert plan.n_faces == 2
    assert [w for w in plan.warnings if "$INSUNITS" in w] == [
        "drawn in inches ($INSUNITS 1) but read in metres, as asked"]
    mesh = read_plan(table)
    from facet.io import write_mesh

    write_mesh(mesh.mesh, tmp_path / "plan.obj")
    scaled = read_plan(tmp_path / "plan.obj", units_mm=25.4)
    np.testing.assert_array_equal(scaled.mesh.vertices, mesh.mesh.vertices * 25.4)
    for bad in (0.0, -1.0, float("nan"), "m"):
        with pytest.raises(PlanError, match=r"plan\.csv: the drawing's unit in mm must be a "
                                            r"finite number > 0"):
            read_plan(table, units_mm=bad)


def test_tables_from_a_european_excel_and_their_missing_values(tmp_path):
    """Excel writes "CSV" with semicolons and decimal commas where the decimal separator
    is a comma (most of Europe), and "Unicode Text" with tabs and decimal commas: both were
    refused as "line 2: not three numbers x,y,z". An empty cell between two others was
    left out, which moved the next cells into its place: "0,,10,4.2" was read as the
    point (0, 10) at height 4.2, whether a comma was doubled or a value missing. Now both
    tables are read, and an empty cell is refused by its line, quoting the cells."""
    from facet.plan import read_targets

    plan = plan_from_mesh(PolyMesh.from_faces(
        np.array([[0, 0, 0], [10, 0, 0], [10, 10, 0], [0, 10, 0.0]]), [[0, 1, 2, 3]]))
    (tmp_path / "excel.csv").write_bytes(
        b"\xef\xbb\xbfx;y;z\r\n0;0;1,5\r\n10;0;2,25\r\n10;10;3\r\n0;10;-0,5;\r\n")
    (tmp_path / "excel.txt").write_bytes(
        "x\ty\tz\r\n0\t0\t1,5\r\n10\t0\t2,25\r\n10\t10\t3\r\n0\t10\t-0,5\r\n".encode("utf-16"))
    for name in ("excel.csv", "excel.txt"):
        targets, weights = read_targets(plan, tmp_path / name)
        assert targets.tolist() == [1.5, 2.25, 3.0, -0.5] and np.all(weights == 1)
    # every cell with a decimal comma: more commas than tabs, still tab-separated (it was
    # read as comma-separated: '10,5<tab>0,5<tab>1,5' refused as not three numbers)
    (tmp_path / "all_decimal.txt").write_bytes(
        "x\ty\tz\r\n0,5\t0,5\t1,5\r\n10,5\t0,5\t2,25\r\n10,5\t10,5\t3,0\r\n"
        "0,5\t10,5\t-0,5\r\n".encode("utf-16"))
    shifted = plan_from_mesh(PolyMesh.from_faces(
        np.array([[0.5, 0.5, 0], [10.5, 0.5, 0], [10.5, 10.5, 0], [0.5, 10.5, 0.0]]),
        [[0, 1, 2, 3]]))
    targets, weights = read_targets(shifted, tmp_path / "all_decimal.txt")
    assert targets.tolist() == [1.5, 2.25, 3.0, -0.5] and np.all(weights == 1)
    (tmp_path / "segments.txt").write_text(
        "0,5\t0,5\t10,5\t0,5\n10,5\t0,5\t10,5\t10,5\n10,5\t10,5\t0,5\t10,5\n"
        "0,5\t10,5\t0,5\t0,5\n")
    assert read_plan(tmp_path / "segments.txt").n_faces == 1
    # (with tabs, whose locale is not known, a comma that may group thousands is refused;
    # '0,125' groups nothing: a height in metres to the millimetre, it was refused too)
    (tmp_path / "leading_zero.txt").write_text(
        "x\ty\tz\n0\t0\t0,125\n10\t0\t-0,250\n10\t10\t3\n0\t10\t0,5\n")
    targets, _ = read_targets(plan, tmp_path / "leading_zero.txt")
    assert targets.tolist() == [0.125, -0.25, 3.0, 0.5]
    (tmp_path / "thousands.txt").write_text("x\ty\tz\n10\t0\t1,250\n")
    with pytest.raises(InputError, match=r"thousands.txt: line 2: not three numbers x,y,z "
                       r"\(10 \| 0 \| 1,250\)"):
        read_targets(plan, tmp_path / "thousands.txt")
    (tmp_path / "segments.csv").write_text("0;0;10;0\n10;0;10;10\n10;10;0;10\n0;10;0;0\n"
                                           "0;0;10,0;10,0\n")
    assert read_plan(tmp_path / "segments.csv").n_faces == 2
    (tmp_path / "gap.csv").write_text("x,y,z\n0,0,1\n10,0,2\n10,10,3\n0,,10,4.2\n")
    with pytest.raises(InputError, match=r"gap.csv: line 5: not three numbers x,y,z "
                       r"\(0 \|  \| 10 \| 4.2\)"):
        read_targets(plan, tmp_path / "gap.csv")
    (tmp_path / "short.csv").write_text("x,y,z\n0,0,1\n10,0,\n")
    with pytest.raises(InputError, match=r"short.csv: line 3: need three finite numbers "
                       r"x,y,z \(10 \| 0\)"):
        read_targets(plan, tmp_path / "short.csv")


def test_target_points_that_match_no_vertex_are_said(facet_command, tmp_path):
    """A table of heights in metres for a plan in millimetres: its point at 0, 0 matched
    vertex 0, the other three fell inside the plan near no vertex and were left out, and
    the lifting met the one height, flat, reported as a success (RMS miss 0). The points
    left out are now said: in the notes of read_targets, on the command line and in its
    report."""
    from facet.plan import read_targets

    segments = [((0, 0), (6000, 0)), ((6000, 0), (12000, 0)), ((12000, 0), (12000, 6000)),
                ((12000, 6000), (6000, 6000)), ((6000, 6000), (0, 6000)),
                ((0, 6000), (0, 0)), ((6000, 0), (6000, 6000))]
    plan_file = tmp_path / "plan.csv"
    plan_file.write_text("".join(f"{a[0]},{a[1]},{b[0]},{b[1]}\n" for a, b in segments))
    points = tmp_path / "heights.csv"
    points.write_text("x,y,z\n0,0,3.5\n12,0,3.6\n0,6,4.2\n12,6,3.3\n")
    plan = read_plan(plan_file)
    notes = []
    targets, weights = read_targets(plan, points, notes=notes)
    assert np.count_nonzero(weights == 1) == 1
    # (a table's plan is in its drawing's units; the match distance named as the caller's
    # user sets it: --snap on the command line)
    assert notes == [f"{points}: 3 of the 4 target points lie farther than the match "
                     "distance 0.012 drawing units (tolerance) from every plan vertex, left "
                     "out (the nearest of them, line 4 at (0, 6) drawing units, is 6 drawing "
                     "units from vertex 3); 1 of the 6 plan vertices has a target height; the "
                     "points span 12 drawing units and the plan 12000 drawing units, 1000 "
                     "times less: is the table in other units than the plan (metres for "
                     "millimetres)?"]
    out, report = tmp_path / "roof.obj", tmp_path / "r.json"
    done = facet_command("lift", plan_file, "-o", out, "--targets", points, "--report", report)
    assert done.returncode == 0, done.stderr
    said = notes[0].replace("(tolerance)", "(--snap)")
    assert "warning       " + said in done.stdout
    assert said in json.loads(report.read_text())["warnings"]
    # points left out of a table as large as the plan (a survey denser than the plan):
    # said, with no word of other units
    points.write_text("x,y,z\n0,0,3.5\n12000,0,3.6\n0,6000,4.2\n12000,6000,3.3\n"
                      "3000,3000,4\n")
    notes = []
    read_targets(plan, points, notes=notes)
    assert len(notes) == 1 and "1 of the 5 target points" in notes[0]
    assert "other units" not in notes[0]
    # every point on a vertex: nothing said
    points.write_text("x,y,z\n0,0,3.5\n12000,0,3.6\n0,6000,4.2\n12000,6000,3.3\n")
    notes = []
    read_targets(plan, points, notes=notes)
    assert notes == []


def test_a_line_drawn_just_short_of_another_is_said(tmp_path):
    """A bay line drawn 1 mm short of the line it meets (beyond the default snap, 0.013
    mm on this 12 x 6 m plan) bounds no face: it was dropped with the face it should have
    split, and the only trace was "1 dangling edges dropped". Now a warning says where,
    and the snap distance that joins it; an overhang past the outline (as far from it as
    it is long) names no gap."""
    document = ezdxf.new()
    space = document.modelspace()
    space.add_lwpolyline([(0, 0), (12000, 0), (12000, 6000), (0, 6000)], close=True)
    space.add_line((6000, -50), (6000, 6050))  # overhangs of 50 past the outline
    space.add_line((0, 3000), (5999, 3000))  # 1 short of the middle line
    space.add_line((6000, 3000), (12000, 3000))
    document.saveas(tmp_path / "gap.dxf")
    plan = read_plan(tmp_path / "gap.dxf")
    assert plan.n_faces == 3 and len(plan.dangling) == 3
    # (ezdxf.new() draws in metres: $INSUNITS 6, read as drawn)
    assert plan.warnings == [
        "3 dangling edges bound no face and were dropped, not part of the plan: from "
        "(6000, 6000) to (6000, 6050) m, from (6000, -50) to (6000, 0) m and from (0, 3000) "
        "to (5999, 3000) m; an edge ends 1 m short of another at (5999, 3000) m, and a face "
        "there is lost if they should meet: a snap distance (snap) above 1 m joins them"]
    assert read_plan(tmp_path / "gap.dxf", snap=1.5).n_faces == 4
    assert facet.lift(plan, np.zeros(plan.n_vertices)).warnings[0] == plan.warnings[0]
    space.add_line((5999, 3000), (6000, 3000))
    document.saveas(tmp_path / "closed.dxf")
    closed = read_plan(tmp_path / "closed.dxf")
    # the overhangs are dropped too, and said: no gap named
    assert closed.n_faces == 4 and len(closed.dangling) == 2 and closed.warnings == [
        "2 dangling edges bound no face and were dropped, not part of the plan: from "
        "(6000, 6000) to (6000, 6050) m and from (6000, -50) to (6000, 0) m: extend or join "
        "them to the lines they should meet, or give a larger snap distance (snap) that "
        "joins their ends to them"]


def test_the_search_for_lines_drawn_short_finds_the_nearest(monkeypatch):
    """The search for a dangling edge's free end near another edge measured every end
    against every piece of the drawing (16 of 18 s of reading a 150 x 150 grid with 3,000
    short annotation lines); it looks at the pieces near each end only, and must find the
    gap that measuring every piece finds. (Its speed is measured, not asserted: 2.8 s for
    that grid.)"""
    import facet.plan as plan_module

    search = plan_module._nearest_gap
    seen = {}

    def recorded(noded, dangling, limit, report=None):
        seen["found"] = search(noded, dangling, limit, report)
        seen["args"] = (noded, dangling, limit)
        return seen["found"]

    monkeypatch.setattr(plan_module, "_nearest_gap", recorded)
    n, rng = 80, np.random.default_rng(1)
    segments = [s for i in range(n + 1) for s in (((0, 100.0 * i), (100.0 * n, 100.0 * i)),
                                                 ((100.0 * i, 0), (100.0 * i, 100.0 * n)))]
    for x, y in rng.uniform(0, 100.0 * n, (1000, 2)):  # ticks meeting nothing, some near
        segments.append(((x + 10, y + 10), (x + 30, y + 30)))
    plan = plan_from_segments(segments)
    # every free end against every piece
    noded, dangling, limit = seen["args"]
    pieces = np.array([p for g in noded.geoms for p in zip(g.coords[:-1], g.coords[1:])])
    ends, counts = np.unique(pieces.reshape(-1, 2), axis=0, return_counts=True)
    free = {tuple(e) for e in ends[counts == 1]}
    start, direction = pieces[:, 0], pieces[:, 1] - pieces[:, 0]
    best = None
    for a, b in dangling:
        for end, other in ((a, b), (b, a)):
            if end not in free:
                continue
            u = np.clip(np.einsum("ij,ij->i", np.subtract(end, start), direction)
                        / np.einsum("ij,ij->i", direction, direction), 0, 1)
            gap = np.hypot(*(start + u[:, None] * direction - end).T)
            gap[np.all(pieces[:, 0] == other, axis=1) | np.all(pieces[:, 1] == other, axis=1)
                | (gap == 0)] = np.inf
            k = int(np.argmin(gap))
            if gap[k] <= min(limit, 0.05 * math.dist(end, other)) and (
                    best is None or gap[k] < best[0]):
                best = (float(gap[k]), end)
    assert best is not None and seen["found"] == best
    assert len(plan.warnings) == 1


def test_a_plan_on_a_layout_is_said_where_it_is(tmp_path):
    """A plan drawn on a layout (paper space) was refused as "no LINE, LWPOLYLINE or
    POLYLINE in the model space (nothing)": where it is, and what to do, is now said."""
    document = ezdxf.new()
    layout = document.layout("Layout1")
    layout.add_lwpolyline([(0, 0), (10, 0), (10, 10), (0, 10)], close=True)
    layout.add_text("ROOF")  # (not counted: no drawing)
    document.saveas(tmp_path / "paper.dxf")
    with pytest.raises(PlanError, match=re.escape(
            "no LINE, LWPOLYLINE or POLYLINE in the model space (nothing; 1 entity on the "
            "layout Layout1 (paper space), which Facet does not read: draw the plan in the "
            "model space)")):
        read_plan(tmp_path / "paper.dxf")


def test_the_endpoint_search_tests_a_bounded_number_of_candidates_at_once(monkeypatch):
    """A hatch of long lines across a square (exploded, as DXF plans often hold them): the
    ball around each line's middle holds most endpoints, and testing every line's at once
    took 2 GB and 7 s for 5,000 lines (one line at a time: 60 MB, 1 s). The KD-tree's
    answers are taken CANDIDATES_AT_ONCE at a time (a segment more when one alone has
    more); the plan is the same."""
    import scipy.spatial

    import facet.plan as plan_module

    sizes = []

    class Recording(scipy.spatial.cKDTree):
        def query_ball_point(self, x, r, *args, **kwargs):
            found = super().query_ball_point(x, r, *args, **kwargs)
            if not kwargs.get("return_length"):
                sizes.append(sum(len(f) for f in found))
            return found

    n, side = 200, 10000.0
    segments = [((0, 0), (side, 0)), ((side, 0), (side, side)), ((side, side), (0, side)),
                ((0, side), (0, 0))]
    for c in np.linspace(-side, side, n + 2)[1:-1]:  # x - y = c, at 45 degrees
        segments.append(((c, 0.0), (side, side - c)) if c >= 0 else
                        ((0.0, -c), (side + c, side)))
    whole = plan_from_segments(segments, snap=1e-2)
    monkeypatch.setattr(scipy.spatial, "cKDTree", Recording)
    monkeypatch.setattr(plan_module, "CANDIDATES_AT_ONCE", 500, raising=False)
    plan = plan_from_segments(segments, snap=1e-2)
    assert plan.n_faces == n + 1 and plan.snapped == 2 * n
    np.testing.assert_array_equal(plan.mesh.vertices, whole.mesh.vertices)
    np.testing.assert_array_equal(plan.mesh.face_vertices, whole.mesh.face_vertices)
    one_segment = 2 * n + 8  # (at most every endpoint; and the plan's vertices)
    assert sizes and max(sizes) <= 500 + one_segment, max(sizes)


def test_a_dangling_edge_is_said_where_and_how_to_join_it(facet_command, tmp_path):
    """A ridge drawn to miss the outline by more than the snap distance (and more than a
    twentieth of its length: no gap found) bounds no face: it was dropped without a word,
    DanglingEdges 1 the only trace. Now a warning names how many, their ends in the
    drawing's unit and what joins them, in the caller's terms (--snap on the command
    line), and `facet lift` prints it."""
    document = ezdxf.new()  # ($INSUNITS 6: metres)
    space = document.modelspace()
    space.add_lwpolyline([(0, 0), (12, 0), (12, 6), (0, 6)], close=True)
    space.add_line((3, 3), (9, 3))  # a ridge that meets nothing
    document.saveas(tmp_path / "ridge.dxf")
    plan = read_plan(tmp_path / "ridge.dxf")
    assert plan.n_faces == 1 and len(plan.dangling) == 1 and plan.units == "m"
    assert plan.warnings == [
        "1 dangling edge bounds no face and was dropped, not part of the plan: from (3, 3) "
        "to (9, 3) m: extend or join it to the lines it should meet, or give a larger snap "
        "distance (snap) that joins its ends to them"]
    # read in millimetres (as FreeCAD reads it), named as the PlanGraph's property
    read = read_plan(tmp_path / "ridge.dxf", to_mm=True, units="mm",
                     option_names={"snap": "the PlanGraph's Snap"})
    assert read.warnings[-1].startswith("1 dangling edge bounds no face")
    assert "from (3000, 3000) to (9000, 3000) mm" in read.warnings[-1]
    assert "(the PlanGraph's Snap)" in read.warnings[-1]
    done = facet_command("lift", tmp_path / "ridge.dxf", "-o", tmp_path / "roof.obj",
                         "--pin", "0=0", "--pin", "1=0", "--pin", "2=1")
    assert done.returncode == 0, done.stderr
    assert ("warning       " + plan.warnings[0].replace("(snap)", "(--snap)")
            in done.stdout), done.stdout
    # more than three: the first three named, the rest counted
    for k in range(4):
        space.add_line((1 + k, 1), (1 + k, 2))
    document.saveas(tmp_path / "stubs.dxf")
    many = read_plan(tmp_path / "stubs.dxf").warnings
    assert len(many) == 1 and many[0].startswith("5 dangling edges bound no face and were "
                                                 "dropped") and " and 2 more: " in many[0]


def test_plan_messages_name_the_unit_and_the_option(facet_command, tmp_path):
    """Lengths in the plan's messages were bare numbers ("an edge ends 0.354 short ...",
    "the snap distance 1 joins 19 endpoints ..."): they are in the unit the plan is read in
    (a DXF's $INSUNITS on the command line, "drawing units" when it names none; mm when
    scaled), and the advice names the option as the caller's user sets it."""
    document = ezdxf.new()
    document.header["$INSUNITS"] = 6  # metres
    space = document.modelspace()
    space.add_lwpolyline([(0, 0), (12, 0), (12, 6), (0, 6)], close=True)
    space.add_line((6, 0), (6, 5.999))  # 1 mm short of the outline
    document.saveas(tmp_path / "gap.dxf")
    done = facet_command("lift", tmp_path / "gap.dxf", "-o", tmp_path / "roof.obj",
                         "--pin", "0=0", "--pin", "1=0", "--pin", "2=1")
    assert done.returncode == 0, done.stderr
    assert ("an edge ends 0.001 m short of another at (6, 5.999) m, and a face there is lost "
            "if they should meet: a snap distance (--snap) above 0.001 m joins them"
            in done.stdout), done.stdout
    read = read_plan(tmp_path / "gap.dxf", to_mm=True, units="mm",
                     option_names={"snap": "the PlanGraph's Snap"})
    assert ("an edge ends 1 mm short of another at (6000, 5999) mm, and a face there is lost "
            "if they should meet: a snap distance (the PlanGraph's Snap) above 1 mm joins "
            "them") in read.warnings[-1]
    # a drawing that names no unit: its lengths in "drawing units"
    document.header["$INSUNITS"] = 0
    document.saveas(tmp_path / "plain.dxf")
    assert read_plan(tmp_path / "plain.dxf").units == "drawing units"
    with pytest.raises(PlanError, match=r"the snap distance 0.5 drawing units \(--snap\) "
                       r"joins 4 endpoints in a chain 1.2 drawing units wide, from \(0, 0\) to "
                       r"\(1.2, 0\) drawing units"):
        read_plan(_chain_csv(tmp_path), snap=0.5, option_names={"snap": "--snap"})
    # the match distance of target points, on the command line
    table = tmp_path / "heights.csv"
    table.write_text("x,y,z\n100,100,1\n")
    done = facet_command("lift", tmp_path / "plain.dxf", "-o", tmp_path / "roof.obj",
                         "--targets", table)
    assert done.returncode == 2
    assert "no target point lies within the match distance 1.2e-05 drawing units" in done.stderr
    assert "units (--snap) of a plan vertex" in done.stderr, done.stderr


def _chain_csv(tmp_path):
    """A table whose four endpoints 0.4 apart chain across a snap distance of 0.5."""
    path = tmp_path / "chain.csv"
    path.write_text("0,0,0.4,0\n0.4,0,0.8,0\n0.8,0,1.2,0\n1.2,0,1.2,5\n1.2,5,0,5\n0,5,0,0\n")
    return path


def test_a_curve_refused_is_named_by_layer_and_place(tmp_path):
    """"ARC 31 is curved" named the DXF's handle, which no designer can find: it names the
    layer and where the curve is, in the unit the plan is read in (mm when scaled), and
    the option that splits it."""
    document = ezdxf.new()  # metres
    space = document.modelspace()
    document.layers.add("ROOF")
    space.add_lwpolyline([(0, 0), (12, 0), (12, 6)], dxfattribs={"layer": "ROOF"})
    arc = space.add_arc((6, 6), 6, 0, 180, dxfattribs={"layer": "ROOF"})
    document.saveas(tmp_path / "canopy.dxf")
    with pytest.raises(PlanError, match=rf"ARC {arc.dxf.handle} on layer ROOF from "
                       r"\(12, 6\) to \(0, 6\) m is curved: give an arc tolerance "
                       r"\(--arc-tolerance\)"):
        read_plan(tmp_path / "canopy.dxf", option_names={"arc_tolerance": "--arc-tolerance"})
    with pytest.raises(PlanError, match=r"on layer ROOF from \(12000, 6000\) to \(0, 6000\) "
                       r"mm is curved: give an arc tolerance \(the PlanGraph's ArcTolerance\)"):
        read_plan(tmp_path / "canopy.dxf", to_mm=True, units="mm",
                  option_names={"arc_tolerance": "the PlanGraph's ArcTolerance"})
    # a circle: around its centre; a polyline's arc segment: where it starts
    space.add_circle((3, 3), 1, dxfattribs={"layer": "ROOF"})
    arc.destroy()
    document.saveas(tmp_path / "circle.dxf")
    with pytest.raises(PlanError, match=r"CIRCLE \w+ on layer ROOF around \(3, 3\) m is "
                       r"curved"):
        read_plan(tmp_path / "circle.dxf")
    # a tolerance too small names itself as given, in its unit
    with pytest.raises(PlanError, match=r"the arc tolerance 1e-09 mm \(the PlanGraph's "
                       r"ArcTolerance\) would split it"):
        read_plan(tmp_path / "circle.dxf", to_mm=True, units="mm", arc_tolerance=1e-9,
                  option_names={"arc_tolerance": "the PlanGraph's ArcTolerance"})
    bulged = ezdxf.new()
    bulged.modelspace().add_lwpolyline([(0, 0, 0), (4, 0, 0.5), (4, 4, 0)], format="xyb",
                                       dxfattribs={"layer": "EAVES"})
    bulged.saveas(tmp_path / "bulge.dxf")
    with pytest.raises(PlanError, match=r"LWPOLYLINE \w+ on layer EAVES at \(4, 0\) m has arc "
                       r"segments \(bulges\)"):
        read_plan(tmp_path / "bulge.dxf")
