# SPDX-License-Identifier: LGPL-2.1-or-later
"""PlanGraph and Lifting objects: parametric on their drawing and targets, planar results
that the rest of the workbench takes as sources, saved and reopened."""

import os

import FreeCAD as App
import numpy as np
import Part
import Sketcher

import facet
import facetwb
from facet.report import point_text
from facet_test_support import DocumentTestCase, bits, points_array

OUTER = [(0.0, 0.0), (4000.0, 0.0), (1000.0, 3000.0)]


def inner_triangle(angle=0.0):
    """The outer triangle scaled by 0.4 about its centroid, then turned by angle."""
    c = np.mean(OUTER, axis=0)
    rot = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    return [tuple(c + rot @ (0.4 * (np.array(p) - c))) for p in OUTER]


def nested_segments(angle=0.0):
    inner = inner_triangle(angle)
    segs = []
    for ring in (OUTER, inner):
        segs += [(ring[i], ring[(i + 1) % 3]) for i in range(3)]
    segs += list(zip(OUTER, inner))
    return segs


def add_sketch(doc, segments, name="Sketch"):
    sketch = doc.addObject("Sketcher::SketchObject", name)
    for a, b in segments:
        sketch.addGeometry(Part.LineSegment(App.Vector(*a, 0), App.Vector(*b, 0)), False)
    return sketch


def add_plane(doc, z0, slope_x, slope_y, name="Surface"):
    """A big tilted planar face z = z0 + slope_x x + slope_y y as a Part feature."""
    corners = [(-1e4, -1e4), (1e4, -1e4), (1e4, 1e4), (-1e4, 1e4)]
    points = [App.Vector(x, y, z0 + slope_x * x + slope_y * y) for x, y in corners]
    face = Part.Face(Part.makePolygon(points + points[:1]))
    feature = doc.addObject("Part::Feature", name)
    feature.Shape = face
    return feature


class TestPlanGraphAndLifting(DocumentTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.sketch = add_sketch(cls.doc, nested_segments() + [((4000, 0), (5000, -1000))])
        cls.plan = facetwb.make_plan_graph([cls.sketch])
        cls.surface = add_plane(cls.doc, 3000.0, 0.1, -0.2)
        cls.lifting = facetwb.make_lifting(cls.plan, targets=cls.surface)
        cls.doc.recompute()

    def test_plan_graph(self):
        plan = self.plan
        self.assertTrue(plan.isValid(), plan.getStatusString())
        self.assertTrue(facetwb.is_plan_graph(plan))
        self.assertEqual((plan.VertexCount, plan.FaceCount), (6, 4))
        self.assertEqual(plan.DanglingEdges, 1)
        self.assertTrue(all(p.z == 0.0 for p in plan.Points))

    def test_lifting_reaches_a_planar_target_exactly(self):
        lifting = self.lifting
        self.assertTrue(lifting.isValid(), lifting.getStatusString())
        self.assertTrue(facetwb.is_lifting(lifting))
        self.assertEqual(lifting.Dimension, 4)
        self.assertFalse(lifting.OnlyTrivial)
        xyz = points_array(lifting)
        expected = 3000.0 + 0.1 * xyz[:, 0] - 0.2 * xyz[:, 1]
        np.testing.assert_allclose(xyz[:, 2], expected, rtol=0, atol=1e-9)
        self.assertLess(lifting.TargetMax.Value, 1e-9)
        self.assertLessEqual(lifting.PlanarityMaxRel, 1e-9)
        np.testing.assert_array_equal(xyz[:, :2], points_array(self.plan)[:, :2])
        self.assertIn("dimension 4", facetwb.lifting_summary(lifting))

    def test_summary_gives_the_misses_in_the_users_unit(self):
        """FreeCAD set to inches: the summary said "targets missed by 0.00 in RMS" (Imperial
        decimal's two decimals) or "0" (Building US's eighths) of a lifting that missed its
        targets by a few thousandths of an inch: three significant digits now."""
        import re

        xy = points_array(self.plan)[:, :2]
        heights = [0.0, 40.0, 0.0, 25.0, 0.0, 10.0, 5.0][:len(xy)]  # (no lifting meets them)
        lifting = facetwb.make_lifting(self.plan, pins=[(float(x), float(y), h)
                                                        for (x, y), h in zip(xy, heights)])
        self.doc.recompute()
        schema = App.Units.getSchema()
        try:
            self.assertTrue(lifting.isValid(), lifting.getStatusString())
            self.assertGreater(lifting.TargetMax.Value, 0.01)
            for number in (3, 5):
                App.Units.setSchema(number)
                text = facetwb.lifting_summary(lifting)
                found = re.search(r"missed by (\S+) in RMS, (\S+) in max", text)
                self.assertTrue(found, text)
                for said, value in zip(found.groups(), (lifting.TargetRms, lifting.TargetMax)):
                    self.assertAlmostEqual(float(said), value.Value / 25.4,
                                           delta=0.005 * value.Value / 25.4)
        finally:
            App.Units.setSchema(schema)
            self.doc.removeObject(lifting.Name)

    def test_mix_keeps_faces_planar(self):
        lifting = self.lifting
        before = points_array(lifting)
        lifting.Mix = [500.0]
        self.doc.recompute()
        try:
            self.assertTrue(lifting.isValid(), lifting.getStatusString())
            after = points_array(lifting)
            change = after[:, 2] - before[:, 2]
            self.assertAlmostEqual(float(np.max(np.abs(change))), 500.0, places=6)
            self.assertLessEqual(lifting.PlanarityMaxRel, 1e-9)
            self.assertAlmostEqual(lifting.TargetMax.Value, 500.0, places=6)
            np.testing.assert_array_equal(after[:, :2], before[:, :2])
            # more values than the plan has liftings beyond the planes: refused, not cut
            extra = lifting.Dimension - 3
            lifting.Mix = [500.0] + [0.0] * extra + [200.0]
            self.doc.recompute()
            self.assertFalse(lifting.isValid())
            self.assertIn(f"Mix value {extra + 2} is 200, but the plan has only {extra} "
                          "liftings that are not planes", lifting.getStatusString())
            lifting.Mix = [500.0] + [0.0] * (extra + 1)  # zeros beyond are fine
            self.doc.recompute()
            self.assertTrue(lifting.isValid(), lifting.getStatusString())
        finally:
            lifting.Mix = []
            self.doc.recompute()
        np.testing.assert_allclose(points_array(lifting), before, rtol=0, atol=1e-9)

    def test_drag_a_vertex(self):
        lifting = self.lifting
        before = points_array(lifting)
        x, y = inner_triangle()[1]
        vertex = int(np.argmin(np.hypot(before[:, 0] - x, before[:, 1] - y)))
        lifting.Drags = [App.Vector(x, y, 300.0)]
        self.doc.recompute()
        try:
            self.assertTrue(lifting.isValid(), lifting.getStatusString())
            after = points_array(lifting)
            self.assertAlmostEqual(after[vertex, 2] - before[vertex, 2], 300.0, places=6)
            self.assertLessEqual(lifting.PlanarityMaxRel, 1e-9)
            lifting.Drags = [App.Vector(x + 50, y, 300.0)]
            self.doc.recompute()
            self.assertFalse(lifting.isValid())
            self.assertIn("no plan vertex within", lifting.getStatusString())
        finally:
            lifting.Drags = []
            self.doc.recompute()
        np.testing.assert_allclose(points_array(lifting), before, rtol=0, atol=1e-9)

    def test_bad_weights_are_refused_as_given(self):
        # the check ran on the weights times the pins' own (1e-6 on a free vertex): a -1
        # typed by the designer was reported as -1e-06, and Weights was not named
        lifting = self.lifting
        before = points_array(lifting)
        n = len(before)
        try:
            for value, shown in ((-1.0, "-1"), (float("nan"), "nan"), (0.0, "0")):
                lifting.Weights = [1.0] * (n - 1) + [value]
                self.doc.recompute()
                self.assertFalse(lifting.isValid())
                self.assertIn(f"Weights: the weight of vertex {n - 1} is {shown}: weights must "
                              "be finite and > 0", lifting.getStatusString())
                np.testing.assert_array_equal(points_array(lifting), before)
        finally:
            lifting.Weights = []
            self.doc.recompute()
        self.assertTrue(lifting.isValid(), lifting.getStatusString())

    def test_downstream_planarize_takes_it(self):
        result = facetwb.make_planarized(self.lifting, tolerance=1e-6)
        self.doc.recompute()
        self.assertTrue(result.isValid(), result.getStatusString())
        self.assertEqual(result.FaceCount, 4)
        self.assertLess(result.DisplacementMax.Value, 1e-6)

    def test_parametric_on_the_drawing(self):
        doc = self.doc
        sketch = add_sketch(doc, nested_segments(0.3), "Turned")
        plan = facetwb.make_plan_graph([sketch])
        pins = [(x, y, 0.0) for x, y in OUTER] + [(x, y, 1000.0) for x, y in inner_triangle()]
        lifting = facetwb.make_lifting(plan, pins=pins)
        doc.recompute()
        # Turned inner triangle: only planes; the inner pins are off the plan's vertices.
        self.assertFalse(lifting.isValid())
        self.assertIn("3 of the 6 pinned points", lifting.getStatusString())
        lifting.PinnedPoints = [App.Vector(x, y, 0.0) for x, y in OUTER] + [
            App.Vector(x, y, 1000.0) for x, y in inner_triangle(0.3)]
        doc.recompute()
        self.assertTrue(lifting.isValid(), lifting.getStatusString())
        self.assertTrue(lifting.OnlyTrivial)
        self.assertEqual(lifting.Dimension, 3)
        lifting.PinnedPoints = [App.Vector(x, y, 0.0) for x, y in OUTER] + [
            App.Vector(x, y, 1000.0) for x, y in inner_triangle(0.0)]
        # Edit the drawing: turn the inner triangle back; the chain follows.
        for k, (a, b) in enumerate(nested_segments(0.0)):
            sketch.movePoint(k, 1, App.Vector(*a, 0))
            sketch.movePoint(k, 2, App.Vector(*b, 0))
        doc.recompute()
        self.assertTrue(lifting.isValid(), lifting.getStatusString())
        self.assertEqual(lifting.Dimension, 4)
        self.assertLess(lifting.TargetMax.Value, 0.1)  # (mm: the corner moved 0.2 mm)

    def test_source_untouched(self):
        geometry = [(g.StartPoint, g.EndPoint) for g in self.sketch.Geometry]
        self.doc.recompute()
        self.assertEqual(len(geometry), 10)
        self.assertEqual(geometry, [(g.StartPoint, g.EndPoint) for g in self.sketch.Geometry])

    def test_the_factorization_can_be_cancelled(self):
        """The Lifting's factorization reports its stages to the recompute's progress and
        Cancel stops it (it was one uninterruptible call: seconds on a large plan); the
        object says so, and recomputed again it lifts."""
        lifting = facetwb.make_lifting(self.plan, targets=self.surface)
        reporter = self.recompute_cancelled(3)  # (after matching the targets: 2 calls)
        self.assertTrue(reporter.cancelled and reporter.calls >= 3)
        self.assertEqual((reporter.done, reporter.total), (1, 3))
        self.assertFalse(lifting.isValid())
        self.assertIn("cancelled", lifting.getStatusString())
        lifting.touch()
        self.doc.recompute()
        self.assertTrue(lifting.isValid(), lifting.getStatusString())
        self.doc.removeObject(lifting.Name)
        self.doc.recompute()

    def test_z_save_reopen(self):  # last: it replaces the class's document
        names = {key: obj.Name for key, obj in (("plan", self.plan), ("lifting", self.lifting))}
        before = points_array(self.lifting)
        doc = self.save_and_reopen("lifting.FCStd")
        plan, lifting = doc.getObject(names["plan"]), doc.getObject(names["lifting"])
        self.assertEqual(lifting.Proxy.Type, "Facet::Lifting")
        self.assertEqual(plan.Proxy.Type, "Facet::PlanGraph")
        self.assertIs(lifting.Plan, plan)
        np.testing.assert_array_equal(bits(points_array(lifting)), bits(before))
        self.assertEqual(lifting.Dimension, 4)
        lifting.touch()
        doc.recompute()
        self.assertTrue(lifting.isValid(), lifting.getStatusString())
        np.testing.assert_allclose(points_array(lifting), before, rtol=0, atol=1e-9)


class TestPlanGraphSources(DocumentTestCase):
    def test_part_wire_and_file(self):
        wire = self.doc.addObject("Part::Feature", "Wire")
        square = [App.Vector(x, y, 500) for x, y in ((0, 0), (2, 0), (2, 2), (0, 2), (0, 0))]
        cross = [Part.LineSegment(App.Vector(1, 0, 500), App.Vector(1, 2, 500)).toShape(),
                 Part.LineSegment(App.Vector(0, 1, 500), App.Vector(2, 1, 500)).toShape()]
        wire.Shape = Part.Compound([Part.makePolygon(square)] + cross)
        plan = facetwb.make_plan_graph([wire])
        self.doc.recompute()
        self.assertTrue(plan.isValid(), plan.getStatusString())
        self.assertEqual((plan.VertexCount, plan.FaceCount), (9, 4))
        path = os.path.join(self.tmp.name, "plan.csv")
        with open(path, "w", encoding="utf-8") as handle:
            for (a, b) in nested_segments():
                handle.write(f"{a[0]!r},{a[1]!r},{b[0]!r},{b[1]!r}\n")
        from_file = facetwb.make_plan_graph(file=path, doc=self.doc)
        self.doc.recompute()
        self.assertTrue(from_file.isValid(), from_file.getStatusString())
        self.assertEqual(from_file.FaceCount, 4)

    def test_dxf_layers_that_are_off_are_left_out_and_said(self):
        import ezdxf

        document = ezdxf.new()
        document.units = 4  # millimetres (ezdxf's default is metres)
        document.layers.add("HELP").off()
        space = document.modelspace()
        space.add_lwpolyline([(0, 0), (3000, 0), (3000, 2000), (0, 2000)], close=True)
        space.add_line((0, 0), (3000, 2000), dxfattribs={"layer": "HELP"})
        path = os.path.join(self.tmp.name, "hidden.dxf")
        document.saveas(path)
        plan = facetwb.make_plan_graph(file=path, doc=self.doc)
        self.doc.recompute()
        self.assertTrue(plan.isValid(), plan.getStatusString())
        self.assertEqual(plan.FaceCount, 1)  # the diagonal on HELP did not split it
        self.assertEqual(len(plan.Warnings), 1)
        self.assertTrue(plan.Warnings[0].startswith(
            "left out 1 entity on layers that are off or frozen (HELP 1)"), plan.Warnings)
        document.layers.get("HELP").on()
        document.saveas(path)
        plan.touch()
        self.doc.recompute()
        self.assertEqual((plan.FaceCount, list(plan.Warnings)), (2, []))

    def read_cancelled_then_again(self, path, prop, value):
        """A PlanGraph of the 64-face grid at ``path``; its read again after ``prop`` is set
        to ``value`` cancelled at the third progress call (the object in error, its last
        plan kept), then recomputed: (the PlanGraph, its points before)."""
        plan = facetwb.make_plan_graph(file=path, doc=self.doc)
        self.doc.recompute()
        self.assertEqual(plan.FaceCount, 64)
        before = points_array(plan)
        setattr(plan, prop, value)
        reporter = self.recompute_cancelled(3)
        self.assertTrue(reporter.cancelled)
        self.assertEqual(reporter.total, facet.plan.PLAN_STAGES * facet.plan.PLAN_STEPS)
        self.assertFalse(plan.isValid())
        self.assertIn("cancelled", plan.getStatusString())
        np.testing.assert_array_equal(points_array(plan), before)  # the last plan kept
        plan.touch()
        self.doc.recompute()
        self.assertTrue(plan.isValid(), plan.getStatusString())
        return plan, before

    def test_reading_a_plan_shows_progress_and_can_be_cancelled(self):
        # a 40,000-face plan took 8 s to read with no progress and no Cancel
        path = os.path.join(self.tmp.name, "grid_plan.csv")
        with open(path, "w") as f:
            for k in range(9):
                f.write(f"0,{k * 500},4000,{k * 500}\n{k * 500},0,{k * 500},4000\n")
        plan, before = self.read_cancelled_then_again(path, "Snap", 1.0)
        self.assertEqual(plan.FaceCount, 64)

    def test_reading_a_plan_mesh_shows_progress_and_can_be_cancelled(self):
        # a plan mesh (.obj, .off, .json) was read with no progress and no Cancel: a
        # 320 x 320 grid took 3 s
        import facet.io
        from facet.mesh import PolyMesh

        k = [i * 500.0 for i in range(9)]
        xyz = [(x, y, 0.0) for y in k for x in k]
        faces = [[j * 9 + i, j * 9 + i + 1, j * 9 + i + 10, j * 9 + i + 9]
                 for j in range(8) for i in range(8)]
        path = os.path.join(self.tmp.name, "grid_plan.obj")
        facet.io.write_mesh(PolyMesh.from_faces(np.array(xyz), faces), path)
        plan, before = self.read_cancelled_then_again(path, "FileUnits", "m")
        np.testing.assert_array_equal(points_array(plan), np.asarray(before) * 1000.0)

    def test_a_dxf_drawn_in_metres_is_read_in_millimetres(self):
        # a canopy drawn in metres ($INSUNITS 6, as Rhino and AutoCAD set it) became a
        # 9 x 6 mm plan in the millimetre document, without a word: a target surface
        # drawn over the real canopy gave every vertex its height at the origin (FreeCAD's
        # own DXF importers scale by $INSUNITS)
        import ezdxf

        document = ezdxf.new()
        document.units = 6
        space = document.modelspace()
        space.add_lwpolyline([(0, 0), (9, 0), (9, 6), (0, 6)], close=True)
        space.add_lwpolyline([(3, 0), (3, 6), (6, 6), (6, 0)], format="xy")
        path = os.path.join(self.tmp.name, "metres.dxf")
        document.saveas(path)
        plan = facetwb.make_plan_graph(file=path, doc=self.doc)
        surface = add_plane(self.doc, 3000.0, 0.1, -0.2, name="MetresTarget")
        lifting = facetwb.make_lifting(plan, targets=surface)
        self.doc.recompute()
        self.assertTrue(lifting.isValid(), lifting.getStatusString())
        xyz = points_array(plan)
        np.testing.assert_array_equal(np.ptp(xyz[:, :2], axis=0), [9000.0, 6000.0])
        self.assertEqual(list(plan.Warnings), [
            "drawn in metres ($INSUNITS 6): read in millimetres, scaled by 1000"])
        lifted = points_array(lifting)
        want = 3000.0 + 0.1 * lifted[:, 0] - 0.2 * lifted[:, 1]
        self.assertLess(np.abs(lifted[:, 2] - want).max(), 1e-6)

    def test_a_dangling_edge_is_said_in_mm_with_the_plangraphs_snap(self):
        # a ridge drawn to miss the outline bounds no face: the PlanGraph was valid with
        # DanglingEdges 1, no warning, the ridge not drawn; an arc was named by its handle
        # alone ("ARC 31 is curved"); both in mm and the PlanGraph's terms now
        import ezdxf

        document = ezdxf.new()
        document.units = 6
        document.layers.add("RIDGE")
        space = document.modelspace()
        space.add_lwpolyline([(0, 0), (9, 0), (9, 6), (0, 6)], close=True)
        space.add_line((2, 3), (7, 3), dxfattribs={"layer": "RIDGE"})
        path = os.path.join(self.tmp.name, "ridge.dxf")
        document.saveas(path)
        plan = facetwb.make_plan_graph(file=path, doc=self.doc)
        self.doc.recompute()
        self.assertTrue(plan.isValid(), plan.getStatusString())
        self.assertEqual(plan.DanglingEdges, 1)
        self.assertEqual(list(plan.Warnings)[1:], [
            "1 dangling edge bounds no face and was dropped, not part of the plan: from "
            "(2000, 3000) to (7000, 3000) mm: extend or join it to the lines it should meet, "
            "or give a larger snap distance (the PlanGraph's Snap) that joins its ends to "
            "them"])
        arc = space.add_arc((4.5, 6), 4.5, 0, 180, dxfattribs={"layer": "RIDGE"})
        document.saveas(path)
        plan.touch()
        self.doc.recompute()
        self.assertFalse(plan.isValid())
        self.assertIn(f"ARC {arc.dxf.handle} on layer RIDGE from (9000, 6000) to (0, 6000) "
                      "mm is curved: give an arc tolerance (the PlanGraph's ArcTolerance)",
                      plan.getStatusString())

    def test_file_units_name_the_drawings_unit_and_old_documents_keep_their_plan(self):
        # a plan table in metres (a table has no unit) was read as millimetres with no way
        # to say otherwise but to rescale the file; a DXF whose $INSUNITS is wrong, the
        # same; and a document saved before DXFs were scaled by their $INSUNITS grew a
        # thousand times on its next recompute, away from its targets and panels
        import ezdxf

        table = os.path.join(self.tmp.name, "metres_plan.csv")
        with open(table, "w") as f:
            f.write("x1,y1,x2,y2\n")
            for a, b in [((0, 0), (9, 0)), ((9, 0), (9, 6)), ((9, 6), (0, 6)),
                         ((0, 6), (0, 0)), ((3, 0), (3, 6))]:
                f.write(f"{a[0]},{a[1]},{b[0]},{b[1]}\n")
        plan = facetwb.make_plan_graph(file=table, doc=self.doc)
        self.assertEqual(plan.FileUnits, "From file")
        self.doc.recompute()
        np.testing.assert_array_equal(np.ptp(points_array(plan)[:, :2], axis=0), [9.0, 6.0])
        # (a 9 x 6 mm roof was made without a word)
        self.assertEqual(list(plan.Warnings), [
            "its edges are 5.14 mm long on average, which no roof's are: set File Units to "
            "the unit the file is drawn in (m, cm, in or ft)"])
        plan.FileUnits = "m"
        self.doc.recompute()
        self.assertTrue(plan.isValid(), plan.getStatusString())
        np.testing.assert_array_equal(np.ptp(points_array(plan)[:, :2], axis=0),
                                      [9000.0, 6000.0])
        self.assertEqual(plan.FaceCount, 2)
        self.assertEqual(list(plan.Warnings), [])

        document = ezdxf.new()
        document.units = 6
        space = document.modelspace()
        space.add_lwpolyline([(0, 0), (9, 0), (9, 6), (0, 6)], close=True)
        space.add_lwpolyline([(3, 0), (3, 6)], format="xy")
        drawing = os.path.join(self.tmp.name, "said_metres.dxf")
        document.saveas(drawing)
        old = facetwb.make_plan_graph(file=drawing, doc=self.doc)
        old.FileUnits = "mm"
        self.doc.recompute()
        np.testing.assert_array_equal(np.ptp(points_array(old)[:, :2], axis=0), [9.0, 6.0])
        self.assertEqual(list(old.Warnings), [
            "drawn in metres ($INSUNITS 6) but read in millimetres, as asked",
            "its edges are 5.14 mm long on average, which no roof's are: set File Units to "
            "the unit the file is drawn in (m, cm, in or ft)"])

        # an older document: no FileUnits; reopened, it reads the DXF as it did then
        old.removeProperty("FileUnits")
        name = old.Name
        path = os.path.join(self.tmp.name, "before_file_units.FCStd")
        self.doc.saveCopy(path)
        reopened = App.openDocument(path)
        try:
            again = reopened.getObject(name)
            self.assertEqual(again.FileUnits, "mm")
            again.touch()
            reopened.recompute()
            np.testing.assert_array_equal(np.ptp(points_array(again)[:, :2], axis=0),
                                          [9.0, 6.0])
        finally:
            App.closeDocument(reopened.Name)

    def test_target_points_that_match_no_vertex_are_said(self):
        # a table of heights in metres for the millimetre plan: its point at 0, 0 matched a
        # vertex, the rest fell near none and were left out; the Lifting was valid, flat at
        # the one height, with no warning
        path = os.path.join(self.tmp.name, "metres.csv")
        with open(path, "w", encoding="utf-8") as handle:
            handle.write("x,y,z\n0,0,3.5\n4,0,3.6\n1,3,4.2\n")
        sketch = add_sketch(self.doc, nested_segments(), "Unmatched")
        lifting = facetwb.make_lifting(facetwb.make_plan_graph([sketch]), target_file=path)
        self.doc.recompute()
        self.assertTrue(lifting.isValid(), lifting.getStatusString())
        self.assertEqual(len(lifting.Warnings), 1, lifting.Warnings)
        # (in mm, named as the Lifting's Snap: "the match distance 0.021" had no unit)
        self.assertTrue(lifting.Warnings[0].startswith(
            f"{path}: 2 of the 3 target points lie farther than the match distance"),
            lifting.Warnings)
        self.assertRegex(lifting.Warnings[0], r"match distance [0-9.e-]+ mm \(the Lifting's "
                         r"Snap\) from every plan vertex")
        self.assertIn("1 of the 6 plan vertices has a target height", lifting.Warnings[0])

    def test_pins_at_the_drawn_corners_of_a_snapped_plan(self):
        # a 9 x 6 m rectangle whose outline misses a corner by 0.4 mm, its plan graph's
        # Snap 1 mm: the corner merged to the endpoints' mean, 0.2 mm from the drawn one,
        # and pins typed at the drawn corners failed ("no target point lies within 0.011
        # of a plan vertex"): the Lifting matches them within the plan graph's Snap
        path = os.path.join(self.tmp.name, "gap.csv")
        with open(path, "w", encoding="utf-8") as handle:
            handle.write("0,0,9000,0\n9000,0,9000,6000\n9000,6000,0,6000\n"
                         "0,6000,0,0.4\n3000,0,3000,6000\n")
        plan = facetwb.make_plan_graph(file=path, snap=1.0, doc=self.doc)
        lifting = facetwb.make_lifting(plan, pins=[(0, 0, 3000), (9000, 0, 3300),
                                                   (0, 6000, 3600), (9000, 6000, 3900)])
        self.doc.recompute()
        self.assertTrue(plan.isValid() and plan.FaceCount == 2, plan.getStatusString())
        self.assertTrue(lifting.isValid(), lifting.getStatusString())
        self.assertLess(lifting.TargetMax.Value, 0.1)  # (mm: the corner moved 0.2 mm)
        # Pin heights matches the pins as the Lifting does: it took the Lifting's Snap (0),
        # found the pin at the drawn corner at no vertex, and pinning that corner again
        # added a second pin there, which the Lifting refused (two heights at one vertex)
        from facetwb import pins
        from facetwb.objects.lifting import match_snap

        self.assertEqual(match_snap(lifting), 1.0)
        mesh = facetwb.conversion.mesh_from_object(plan)
        at = pins.pins_vertices(mesh, lifting.PinnedPoints, match_snap(lifting))
        self.assertNotIn(-1, at)
        self.assertEqual(len(pins.pin(mesh, lifting.PinnedPoints, at[:1], 3100.0,
                                      match_snap(lifting))), 4)
        # the Lifting's own Snap, when set, is the one used
        lifting.Snap = 0.05
        self.doc.recompute()
        self.assertFalse(lifting.isValid())

    def test_a_plan_torn_at_its_vertices_says_so(self):
        # 2 x 2 bays exported unwelded (each face its own corners): lifted apart, the
        # command line warned; the Lifting said nothing and looked fine
        path = os.path.join(self.tmp.name, "torn.obj")
        with open(path, "w", encoding="utf-8") as handle:
            for j in range(2):
                for i in range(2):
                    for x, y in ((i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)):
                        handle.write(f"v {3000.0 * x!r} {3000.0 * y!r} 0\n")
            for k in range(4):
                handle.write("f %d %d %d %d\n" % (4 * k + 1, 4 * k + 2, 4 * k + 3, 4 * k + 4))
        plan = facetwb.make_plan_graph(file=path, doc=self.doc)
        lifting = facetwb.make_lifting(plan, pins=[(0, 0, 3000), (6000, 0, 3300),
                                                   (0, 6000, 3600)])
        self.doc.recompute()
        self.assertTrue(lifting.isValid(), lifting.getStatusString())
        expected = facet.lift(facet.read_plan(path, units="mm"), np.zeros(16)).warnings
        self.assertEqual(len(expected), 2, expected)  # unjoined vertices, 4 pieces
        self.assertEqual(list(lifting.Warnings), expected)
        from facetwb.objects.lifting import lifting_summary

        self.assertIn(f"  warning: {expected[0]}", lifting_summary(lifting))

    def test_a_curved_target_at_georeferenced_coordinates_keeps_its_precision(self):
        # a sloped plane as a B-spline face, tessellated into FreeCAD's single-precision
        # Mesh where it stood: at E 512 km, N 5,712 km in mm the heights were 16 mm off
        # while TargetMax said 0; and a target whose outline is the plan's did not
        # "cover" the plan's corners
        east, north = 512000000.0, 5712000000.0
        corners = {"a": (0, 0), "b": (10000, 0), "c": (10000, 6000), "d": (0, 6000),
                   "e": (3000, 3000), "f": (7000, 3000)}
        edges = [Part.makeLine(App.Vector(east + corners[u][0], north + corners[u][1], 0),
                               App.Vector(east + corners[v][0], north + corners[v][1], 0))
                 for u, v in ("ab", "bc", "cd", "da", "ae", "de", "ef", "bf", "cf")]
        drawing = self.doc.addObject("Part::Feature", "GeoPlan")
        drawing.Shape = Part.Compound(edges)
        surface = Part.BSplineSurface()
        poles = [[App.Vector(east + x, north + y, 1000 + 0.3 * x + 0.1 * y)
                  for y in (0, 3000, 6000)] for x in (0, 5000, 10000)]
        surface.buildFromPolesMultsKnots(poles, [3, 3], [3, 3], [0, 1], [0, 1], False, False,
                                         2, 2)
        target = self.doc.addObject("Part::Feature", "GeoTarget")
        target.Shape = surface.toShape()
        lifting = facetwb.make_lifting(facetwb.make_plan_graph([drawing], doc=self.doc),
                                       targets=target)
        self.doc.recompute()
        self.assertTrue(lifting.isValid(), lifting.getStatusString())
        xyz = points_array(lifting)
        want = 1000 + 0.3 * (xyz[:, 0] - east) + 0.1 * (xyz[:, 1] - north)
        self.assertLess(np.abs(xyz[:, 2] - want).max(), 1e-6)
        # a drag beside every vertex names its point to the millimetre (six digits gave
        # "(5.12005e+08, 5.712e+09)": kilometres out)
        lifting.Drags = [App.Vector(east + 5000.0, north + 50.0, 300.0)]
        self.doc.recompute()
        self.assertFalse(lifting.isValid())
        self.assertIn(f"of the drag at {point_text((east + 5000.0, north + 50.0))}",
                      lifting.getStatusString())

    def test_arcs_refused_then_split(self):
        shape = self.doc.addObject("Part::Feature", "Arcs")
        arc = Part.ArcOfCircle(Part.Circle(App.Vector(0, 0, 0), App.Vector(0, 0, 1), 1000.0),
                               0.0, np.pi)
        chord = Part.LineSegment(App.Vector(-1000, 0, 0), App.Vector(1000, 0, 0))
        shape.Shape = Part.Compound([arc.toShape(), chord.toShape()])
        plan = facetwb.make_plan_graph([shape])
        self.doc.recompute()
        self.assertFalse(plan.isValid())
        self.assertIn("ArcTolerance", plan.getStatusString())
        plan.ArcTolerance = 1.0
        self.doc.recompute()
        self.assertTrue(plan.isValid(), plan.getStatusString())
        self.assertEqual(plan.FaceCount, 1)
        self.assertGreater(plan.VertexCount, 20)

    def test_targets_not_used_are_said(self):
        # a heights file or pins typed into the property editor of a Lifting made towards a
        # surface changed nothing, and nothing said why: Targets comes first
        sketch = add_sketch(self.doc, nested_segments(), "Unused")
        plan = facetwb.make_plan_graph([sketch])
        surface = add_plane(self.doc, 1000.0, 0.0, 0.0, "Flat")
        lifting = facetwb.make_lifting(plan, targets=surface)
        self.doc.recompute()
        self.assertEqual(list(lifting.Warnings), [])
        path = os.path.join(self.tmp.name, "heights.csv")
        with open(path, "w", encoding="utf-8") as handle:
            handle.write("x,y,z\n0,0,3500\n")
        lifting.TargetFile = path
        lifting.PinnedPoints = [App.Vector(0, 0, 2000)]
        self.doc.recompute()
        self.assertTrue(lifting.isValid(), lifting.getStatusString())
        self.assertEqual(list(lifting.Warnings), [
            "TargetFile and PinnedPoints are not used: the targets are Flat's surface "
            "(empty Targets to use them)"], lifting.Warnings)
        self.assertIn("warning: TargetFile and PinnedPoints are not used",
                      facetwb.lifting_summary(lifting))
        lifting.Targets = None
        self.doc.recompute()
        self.assertEqual(list(lifting.Warnings), [
            "PinnedPoints are not used: the targets are the points of TargetFile (empty it "
            "to use them)"], lifting.Warnings)
        self.assertAlmostEqual(points_array(lifting)[0, 2], 3500.0, delta=1e-6)
        lifting.TargetFile = ""
        self.doc.recompute()
        self.assertEqual(list(lifting.Warnings), [])
        self.assertAlmostEqual(points_array(lifting)[0, 2], 2000.0, delta=1e-6)

    def test_no_targets_is_an_error(self):
        sketch = add_sketch(self.doc, nested_segments(), "S")
        plan = facetwb.make_plan_graph([sketch])
        lifting = facetwb.make_lifting(plan)
        self.doc.recompute()
        self.assertFalse(lifting.isValid())
        self.assertIn("no targets", lifting.getStatusString())


class TestLiftingTargetsFromMesh(DocumentTestCase):
    def test_same_vertices(self):
        sketch = add_sketch(self.doc, nested_segments(), "S")
        plan = facetwb.make_plan_graph([sketch])
        self.doc.recompute()
        mesh = facetwb.get_mesh(plan)
        xyz = mesh.vertices.copy()
        xyz[:, 2] = np.where(np.arange(6) < 3, 0.0, 800.0)  # order as in the plan
        inner = [tuple(p) for p in np.round(inner_triangle(), 6)]
        xyz[:, 2] = [800.0 if tuple(np.round(p, 6)) in inner else 0.0 for p in xyz[:, :2]]
        target = facetwb.make_polymesh(facet.PolyMesh(xyz, mesh.face_start, mesh.face_vertices),
                                       doc=self.doc)
        lifting = facetwb.make_lifting(plan, targets=target)
        self.doc.recompute()
        self.assertTrue(lifting.isValid(), lifting.getStatusString())
        np.testing.assert_allclose(points_array(lifting)[:, 2], xyz[:, 2], atol=1e-9)


class TestLiftingProgress(DocumentTestCase):
    """Progress and Cancel in a Lifting's recompute beyond its factorization."""

    def _grid(self, n, size, z=0.0, at=0.0):
        k = [at + i * size for i in range(n + 1)]
        xyz = [(x, y, z) for y in k for x in k]
        m = n + 1
        faces = [[j * m + i, j * m + i + 1, (j + 1) * m + i + 1, (j + 1) * m + i]
                 for j in range(n) for i in range(n)]
        return facet.PolyMesh.from_faces(np.array(xyz), faces)

    def test_matching_targets_shows_progress_and_can_be_cancelled(self):
        # the ray cast of a plan's vertices on a target mesh (2 s for 100,000 vertices)
        # had no progress and no Cancel
        import facet.io

        plan = facetwb.make_polymesh(self._grid(8, 500.0), name="GridPlan", doc=self.doc)
        files = []
        for height in (3000.0, 3500.0):
            files.append(os.path.join(self.tmp.name, f"target{int(height)}.obj"))
            facet.io.write_mesh(self._grid(3, 1500.0, height, at=-250.0), files[-1])
        target = facetwb.make_polymesh(self._grid(3, 1500.0, 3500.0, at=-250.0),
                                       name="HighTarget", doc=self.doc)
        lifting = facetwb.make_lifting(plan, target_file=files[0])
        self.doc.recompute()
        self.assertTrue(lifting.isValid(), lifting.getStatusString())
        before = points_array(lifting)
        np.testing.assert_allclose(before[:, 2], 3000.0)
        for change in (lambda: setattr(lifting, "TargetFile", files[1]),
                       lambda: (setattr(lifting, "TargetFile", ""),
                                setattr(lifting, "Targets", target))):
            change()
            reporter = self.recompute_cancelled(1)  # (the factorization is kept: same plan)
            self.assertTrue(reporter.cancelled)
            self.assertEqual(reporter.total, 81)  # the plan's vertices
            self.assertFalse(lifting.isValid())
            self.assertIn("matching the targets cancelled", lifting.getStatusString())
            np.testing.assert_array_equal(points_array(lifting), before)
        lifting.touch()
        self.doc.recompute()
        self.assertTrue(lifting.isValid(), lifting.getStatusString())
        np.testing.assert_allclose(points_array(lifting)[:, 2], 3500.0)

    def test_the_first_mix_value_shows_progress_and_can_be_cancelled(self):
        # the eigen-liftings a Mix value needs (ARPACK beyond the dense solver's dimension
        # 2,000: a Voronoi plan's) were computed with no progress and no Cancel
        from scipy.spatial import Delaunay

        p = np.random.default_rng(0).random((2500, 2)) * 5000.0
        mesh = facet.PolyMesh.from_faces(np.column_stack([p, np.zeros(len(p))]),
                                         [list(t) for t in Delaunay(p).simplices])
        plan = facetwb.make_polymesh(mesh, name="TrianglePlan", doc=self.doc)
        lifting = facetwb.make_lifting(plan, pins=[(*p[v], 3000.0) for v in (0, 1, 2)])
        self.doc.recompute()
        self.assertTrue(lifting.isValid(), lifting.getStatusString())
        before = points_array(lifting)
        lifting.Mix = [500.0]
        reporter = self.recompute_cancelled(1)  # (the factorization is kept: same plan)
        self.assertTrue(reporter.cancelled)
        self.assertFalse(lifting.isValid())
        self.assertIn("eigen-liftings cancelled", lifting.getStatusString())
        np.testing.assert_array_equal(points_array(lifting), before)
        lifting.touch()
        self.doc.recompute()
        self.assertTrue(lifting.isValid(), lifting.getStatusString())
        self.assertGreater(np.abs(points_array(lifting)[:, 2] - before[:, 2]).max(), 1.0)
