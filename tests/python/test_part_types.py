# SPDX-License-Identifier: LGPL-2.1-or-later
"""Part types: panels that are one part within a tolerance."""

from collections import Counter

import numpy as np
import pytest

import facet
from facet.errors import Cancelled
from facet.panels import panels
from facet.part_types import part_types
from panel_meshes import cylinder, grid_faces, translational


def rotation(axis, angle):
    """The rotation matrix about a unit axis."""
    x, y, z = np.asarray(axis, float) / np.linalg.norm(axis)
    c, s = np.cos(angle), np.sin(angle)
    k = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    return np.eye(3) + s * k + (1 - c) * k @ k


def apart(*outlines):
    """One face per (k, 3) outline, each its own piece of mesh."""
    xyz = np.vstack(outlines)
    faces, n = [], 0
    for o in outlines:
        faces.append(list(range(n, n + len(o))))
        n += len(o)
    return facet.PolyMesh.from_faces(xyz, faces)


# a trapezoid with no symmetry, 1.2 x 0.8 m
TRAPEZOID = np.array([[0, 0, 0], [1200, 0, 0], [1000, 800, 0], [150, 700, 0.0]])


def test_the_quads_of_a_cylinder_are_one_part_with_square_edges():
    ps = panels(cylinder(), 20.0, gap=6.0)
    assert Counter(part_types(ps, 0.5)) == {"T1": 24}


def test_mitred_the_cylinders_edge_columns_are_a_second_part():
    # the first and last columns have a square (free) side, the others two mitres; a
    # half turn makes the first column's panels the last column's
    ps = panels(cylinder(), 20.0, gap=6.0, edge="bisector")
    types = part_types(ps, 0.5)
    assert Counter(types) == {"T1": 16, "T2": 8}
    edge_column = [any(n is None for n in p.neighbors[1::2]) for p in ps]
    assert all((t == "T2") == e for t, e in zip(types, edge_column))


def test_a_turned_and_moved_copy_is_the_same_part_a_mirror_image_is_not():
    r = rotation([1, 2, 3], 0.7)
    moved = TRAPEZOID @ r.T + [5e5, -3e6, 2e3]
    # the same side up (a mirrored face wound the other way is the panel turned over)
    mirrored = (TRAPEZOID * [-1, 1, 1])[::-1] + [3000, 0, 0]
    ps = panels(apart(TRAPEZOID, moved, mirrored), 30.0, gap=10.0)
    assert part_types(ps, 0.5) == ["T1", "T1", "T2"]


def test_the_tolerance_is_the_distance_between_matching_corners():
    # the copy's far corner moved by 0.4 and by 1.0: one part within 0.5, two beyond (the
    # copy fitted to the first in the least squares sense spreads a shift over the corners)
    for shift, same in ((0.4, True), (1.0, False)):
        copy = TRAPEZOID + [3000, 0, 0]
        copy[2, 0] += shift
        types = part_types(panels(apart(TRAPEZOID, copy), 30.0, gap=10.0), 0.5)
        assert (types[0] == types[1]) == same, shift
    assert part_types(panels(apart(TRAPEZOID, TRAPEZOID + [0, 0, 1e3]), 30.0), 0.0) == \
        ["T1", "T1"]


def test_a_corner_on_a_straight_edge_makes_no_other_part():
    rect = np.array([[0, 0, 0], [1000, 0, 0], [1000, 600, 0], [0, 600, 0.0]])
    with_t = np.insert(rect, 2, [1000, 250, 0], axis=0) + [2000, 0, 0]
    ps = panels(apart(rect, with_t), 30.0, gap=10.0)
    assert [p.corners for p in ps] == [4, 5]
    assert part_types(ps, 0.5) == ["T1", "T1"]


def test_types_are_numbered_from_the_most_panels():
    mirrored = (TRAPEZOID * [-1, 1, 1])[::-1]
    ps = panels(apart(TRAPEZOID, mirrored + [3000, 0, 0], mirrored + [6000, 0, 0]), 30.0)
    assert part_types(ps, 0.5) == ["T2", "T1", "T1"]


def test_a_doubly_curved_surface_pairs_only_the_panels_a_half_turn_maps():
    # z = a (x - 2500)^2 - b (y - 2000)^2 on 5 x 4 quads: a half turn about its centre
    # maps face f onto face 19 - f, and no two other panels are alike
    ps = panels(translational(), 20.0, gap=6.0)
    types = part_types(ps, 0.5)
    assert len(set(types)) == 10
    assert all(types[f] == types[19 - f] for f in range(20))


def test_a_bad_tolerance_is_refused_and_a_long_run_can_be_cancelled():
    ps = panels(cylinder(), 20.0)
    for bad in (-1.0, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="part type tolerance must be a finite length"):
            part_types(ps, bad)
    xyz = np.array([[i * 100.0, j * 100.0, 0.0] for j in range(21) for i in range(21)])
    grid = panels(facet.PolyMesh.from_faces(xyz, grid_faces(20, 20)), 5.0)
    seen = []

    def cancel(done, total):
        seen.append((done, total))
        return True
    with pytest.raises(Cancelled):
        part_types(grid, 0.5, progress=cancel)
    assert seen == [(256, 400)]
    # not cancelled, the count reaches the end (it stopped at 256 of 400)
    del seen[:]
    part_types(grid, 0.5, progress=lambda done, total: seen.append((done, total)))
    assert seen == [(256, 400), (400, 400)]


def test_the_schedule_report_and_summary_give_the_part_types(tmp_path, capsys):
    import csv
    import json

    from facet import cli
    from facet.io import write_obj

    mesh = tmp_path / "cylinder.obj"
    write_obj(cylinder(), str(mesh))
    status = cli.main(["panels", str(mesh), "--thickness", "20", "--edge", "bisector",
                       "--schedule", str(tmp_path / "s.csv"), "--report", str(tmp_path / "r.json")])
    out, err = capsys.readouterr()
    assert status == 0, err
    assert "  types         2 part types within 0.5 mm: T1 16 panels, T2 8\n" in out
    rows = list(csv.DictReader(open(tmp_path / "s.csv", encoding="utf-8")))
    assert list(rows[0])[:2] == ["id", "type"]
    assert Counter(r["type"] for r in rows) == {"T1": 16, "T2": 8}
    report = json.load(open(tmp_path / "r.json", encoding="utf-8"))
    assert report["part_types"] == {"T1": 16, "T2": 8}
    assert report["part_type_tolerance"] == 0.5
    assert [r["type"] for r in report["panels"]] == [r["type"] for r in rows]
    # in metres the default is still half a millimetre; a tolerance of 0 parts panels
    # that differ by rounding
    write_obj(facet.PolyMesh.from_faces(cylinder().vertices / 1000.0, cylinder().faces()),
              str(mesh))
    assert cli.main(["panels", str(mesh), "--thickness", "0.02", "--units", "m",
                     "--report", str(tmp_path / "m.json")]) == 0
    assert json.load(open(tmp_path / "m.json"))["part_type_tolerance"] == 0.0005
    capsys.readouterr()
    assert cli.main(["panels", str(mesh), "--thickness", "0.02", "--units", "m",
                     "--type-tol", "0"]) == 0
    assert "24 part types within 0 m: every panel its own" in capsys.readouterr().out
    # one panel is no "every panel its own"
    write_obj(apart(TRAPEZOID), str(mesh))
    assert cli.main(["panels", str(mesh), "--thickness", "20"]) == 0
    assert "  types         1 part type within 0.5 mm: T1 1 panel\n" in capsys.readouterr().out
    with pytest.raises(SystemExit):
        cli.main(["panels", str(mesh), "--thickness", "0.02", "--type-tol", "-1"])
    assert "--type-tol" in capsys.readouterr().err


def test_a_bad_tolerance_names_the_unit_and_refuses_infinity_as_not_finite():
    """run_pipeline said "must be a length >= 0, not inf" of an infinite tolerance (which is
    >= 0), named no unit, and a tolerance that was no number raised a TypeError from its
    format; part_types refused the same values with another message."""
    from facet.cli_panels import run_pipeline
    from facet.errors import InputError

    mesh = apart(TRAPEZOID)
    for bad, said in ((float("inf"), "not inf mm"), (float("nan"), "not nan mm"),
                      (-1.0, "not -1 mm"), ("half", "not 'half'")):
        with pytest.raises(InputError, match=r"^the part type tolerance must be a finite "
                           rf"length >= 0, {said}$"):
            run_pipeline(mesh, 30.0, type_tol=bad)
    with pytest.raises(InputError, match=r"finite length >= 0, not -0\.5 in$"):
        run_pipeline(mesh, 1.0, units="in", type_tol=-0.5)
    with pytest.raises(InputError, match=r"finite length >= 0, not -1$"):
        part_types(panels(mesh, 30.0), -1.0)


def test_the_schedule_refuses_part_types_of_another_panel_set():
    """schedule_rows zipped the panels with ``types``: a list of types for fewer panels (an
    earlier PanelSet's) left the last panels out of the schedule without a word."""
    from facet.cutsheets import schedule_rows

    ps = panels(cylinder(), 20.0, gap=6.0)
    assert len(schedule_rows(ps, types=part_types(ps, 0.5))) == 24
    with pytest.raises(ValueError, match=r"^23 part types for 24 panels: one per panel$"):
        schedule_rows(ps, types=["T1"] * 23)
