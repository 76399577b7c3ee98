# SPDX-License-Identifier: LGPL-2.1-or-later
"""The bad-input catalogue (docs/bad-input.md) in FreeCAD: one test per row.

Every row of tests/python/bad_input_cases.py is fed to the workbench the way a designer
would feed it:

- mesh files: File > Import (importer.insert);
- plan drawings: the File of a PlanGraph that had a good drawing;
- CSV targets: the TargetFile of a Lifting that had good targets;
- panel options and meshes: the Thickness, Gap, Source of a PanelSet and the sheet of a
  CutSheets that had good ones.

A bad row must give ONE line in the report view naming the object or file and the problem
(no Python traceback), change nothing in the document (object count, source geometry) and,
on recompute, leave the object in FreeCAD's error state with its previous shape. A row that
works must give a valid object with finite coordinates.
"""

import os
import sys
import tempfile
import unittest

import FreeCAD as App
import numpy as np

import facetwb
from facetwb import importer
from facet_test_support import ROOT, bits, points_array

sys.path.insert(0, os.path.join(ROOT, "tests", "python"))
import bad_input_cases as cases  # noqa: E402


def captured(function):
    """Run ``function()`` with file descriptors 1 and 2 (FreeCAD's console) captured.

    Returns (result, text)."""
    sys.stdout.flush()
    sys.stderr.flush()
    with tempfile.TemporaryFile(mode="w+b") as sink:
        saved = os.dup(1), os.dup(2)
        os.dup2(sink.fileno(), 1)
        os.dup2(sink.fileno(), 2)
        try:
            result = function()
            sys.stdout.flush()
            sys.stderr.flush()
        finally:
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            os.close(saved[0])
            os.close(saved[1])
        sink.seek(0)
        return result, sink.read().decode("utf-8", "replace")


def error_lines(text):
    """The report-view lines of ``text`` without FreeCAD's recompute progress chatter."""
    lines = []
    for line in text.replace("\r", "\n").splitlines():
        line = line.strip()
        if not line or line.startswith("Recompute") or line.startswith("("):
            continue
        lines.append(line)
    return lines


def shape_state(obj):
    """What recompute must not change on failure: points (bits) or the shape's volume/bbox."""
    if hasattr(obj, "Points"):
        return bits(points_array(obj)).tobytes()
    shape = obj.Shape
    box = shape.BoundBox
    return (len(shape.Solids), len(shape.Edges), round(shape.Volume, 9),
            tuple(round(v, 9) for v in (box.XMin, box.YMin, box.ZMin, box.XMax, box.YMax,
                                        box.ZMax)))


def finite_points(obj):
    xyz = points_array(obj)
    return xyz.size > 0 and bool(np.all(np.isfinite(xyz)))


class TestBadInputFreeCAD(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="facet-bad-")
        self.doc = App.newDocument("BadInput")

    def tearDown(self):
        App.closeDocument(self.doc.Name)
        self.tmp.cleanup()

    # ------------------------------------------------------------------ checks

    def assert_one_line(self, text, obj_or_file, expected):
        self.assertNotIn("Traceback", text)
        lines = error_lines(text)
        lines = [line for line in lines if "Recompute failed" not in line]
        self.assertEqual(len(lines), 1, text)
        for part in [obj_or_file, *expected]:
            self.assertIn(part, lines[0])
        return lines[0]

    def recompute_fails(self, obj, change, expected, sources=()):
        """Apply ``change()`` to a valid ``obj``, recompute: error state, previous shape,
        one line, sources and object count unchanged."""
        self.assertTrue(obj.isValid(), obj.getStatusString())
        before = shape_state(obj)
        count = len(self.doc.Objects)
        source_states = [shape_state(s) for s in sources]
        try:
            change()
        except ValueError:  # FreeCAD refused the property value itself: nothing changed
            self.assertEqual(shape_state(obj), before)
            return
        _, text = captured(self.doc.recompute)
        self.assertFalse(obj.isValid(), f"{obj.Label} recomputed despite the bad input")
        status = obj.getStatusString()
        self.assertNotIn("\n", status)
        for part in expected:
            self.assertIn(part, status)
        self.assert_one_line(text, obj.Label, expected)
        self.assertEqual(shape_state(obj), before, "the previous result was not kept")
        self.assertEqual(len(self.doc.Objects), count)
        self.assertEqual([shape_state(s) for s in sources], source_states)

    # ------------------------------------------------------------------ kinds

    def run_mesh(self, row, folder):
        path = os.path.join(folder, row.mesh)
        count = len(self.doc.Objects)
        obj, text = captured(lambda: importer.insert(path, self.doc.Name))
        if row.works:
            self.assertIsNotNone(obj, text)
            self.assertTrue(obj.isValid(), obj.getStatusString())
            self.assertTrue(finite_points(obj))
            if row.argv[0] == "planarize":
                result = facetwb.make_planarized(obj)
                self.doc.recompute()
                self.assertTrue(result.isValid(), result.getStatusString())
                self.assertTrue(finite_points(result))
            return
        self.assertIsNone(obj)
        self.assertEqual(len(self.doc.Objects), count)
        expected = [e for e in row.expected(folder) if e != path]
        self.assert_one_line(text, path, expected)

    def good_plan(self, folder):
        path = os.path.join(folder, "good_plan.csv")
        with open(path, "w", encoding="utf-8") as handle:
            handle.write(cases._segments_text(cases.plan_grid_segments()))
        plan = facetwb.make_plan_graph(file=path, doc=self.doc)
        return plan

    def run_plan(self, row, folder):
        plan = self.good_plan(folder)
        self.doc.recompute()
        path = os.path.join(folder, row.mesh)
        if row.works:
            plan.File = path
            self.doc.recompute()
            self.assertTrue(plan.isValid(), plan.getStatusString())
            self.assertTrue(finite_points(plan))
            return
        expected = [e for e in row.expected(folder) if e != path]
        self.recompute_fails(plan, lambda: setattr(plan, "File", path), [path, *expected])

    def run_targets(self, row, folder):
        plan = self.good_plan(folder)
        good = os.path.join(folder, "good_targets.csv")
        with open(good, "w", encoding="utf-8") as handle:
            handle.write(cases._targets_text())
        lifting = facetwb.make_lifting(plan, target_file=good)
        self.doc.recompute()
        path = os.path.join(folder, row.mesh)
        expected = [e for e in row.expected(folder) if e != path]
        self.recompute_fails(lifting, lambda: setattr(lifting, "TargetFile", path),
                             [path, *expected], sources=[plan])

    def run_panels(self, row, folder):
        from facetwb.objects.panelset import make_cutsheets, make_panelset

        v, f = cases.grid(bump=0.0)
        good = os.path.join(folder, "good.obj")
        with open(good, "w", encoding="utf-8") as handle:
            handle.write(cases.obj_text(v, f))
        source = importer.insert(good, self.doc.Name)
        panels = make_panelset(source, thickness=0.01, gap=0.0)  # (a 1 mm mesh)
        self.doc.recompute()
        self.assertTrue(panels.isValid(), panels.getStatusString())
        options = row.argv
        value = {options[i]: options[i + 1] for i in range(2, len(options) - 1)
                 if options[i].startswith("--")}
        expected = [e for e in row.expected(folder) if not e.startswith(folder)]
        if row.name.endswith("_thickness"):
            thickness = float(value["--thickness"])
            self.recompute_fails(panels, lambda: setattr(panels, "Thickness", thickness),
                                 ["thickness"], sources=[source])
        elif row.name == "panels_gap_larger_than_panel":
            self.recompute_fails(panels, lambda: setattr(panels, "Gap", float(value["--gap"])),
                                 expected, sources=[source])
        elif row.name == "panels_sheet_smaller_than_panel":
            sheets = make_cutsheets(panels, sheet=(3000.0, 1500.0), margin=0.0, spacing=0.0,
                                    write_step=False)
            self.doc.recompute()
            width, height = (float(t) for t in value["--sheet"].split("x"))

            def smaller():
                sheets.SheetWidth, sheets.SheetHeight = width, height

            self.recompute_fails(sheets, smaller, expected[1:], sources=[source, panels])
        elif row.name == "panels_default_margin_larger_than_sheet":
            # the CutSheets' margin is a property in view, 10 mm unless changed
            sheets = make_cutsheets(panels, sheet=(3000.0, 1500.0), write_step=False)
            self.doc.recompute()
            width, height = (float(t) for t in value["--sheet"].split("x"))

            def smaller():
                sheets.SheetWidth, sheets.SheetHeight = width, height

            self.recompute_fails(sheets, smaller, ["margin 10 leaves nothing", "3 x 1.5 sheet"],
                                 sources=[source, panels])
        elif row.name == "panels_gap_closes_a_notch":  # the mesh with its thickness and gap
            bad = importer.insert(os.path.join(folder, row.mesh), self.doc.Name)
            bad.Label = "notched mesh"

            def notched():
                panels.Source = bad
                panels.Thickness = float(value["--thickness"])
                panels.Gap = float(value["--gap"])

            self.recompute_fails(panels, notched, expected, sources=[source, bad])
        else:  # the mesh itself: zero-area face, not planar, non-manifold
            bad = importer.insert(os.path.join(folder, row.mesh), self.doc.Name)
            bad.Label = "bad mesh"
            if row.works:
                panels.Source = bad
                self.doc.recompute()
                self.assertTrue(panels.isValid(), panels.getStatusString())
                return
            self.recompute_fails(panels, lambda: setattr(panels, "Source", bad), expected,
                                 sources=[source, bad])

    def run_row(self, row):
        folder = os.path.join(self.tmp.name, row.name)
        row.write(folder)
        getattr(self, f"run_{row.kind}")(row, folder)


def _add_test(row):
    def test(self):
        self.run_row(row)

    test.__doc__ = f"bad-input row {row.name}"
    setattr(TestBadInputFreeCAD, f"test_{row.name}", test)


for _row in cases.ROWS:
    _add_test(_row)

