# SPDX-License-Identifier: LGPL-2.1-or-later
"""Planarized objects: solve on recompute, keep the source, survive save and reopen."""

import os

import numpy as np

import facet
import facetwb
from facetwb import importer
from facetwb.units import length_text
from facet_test_support import DocumentTestCase, bits, data_path, points_array

TOLERANCE = 1e-6


class TestPlanarized(DocumentTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.source_mesh = facet.read_mesh(data_path("hypar.obj"))
        cls.source = importer.import_mesh(data_path("hypar.obj"), cls.doc)
        cls.result = facetwb.make_planarized(cls.source, tolerance=TOLERANCE)
        cls.doc.recompute()

    def test_solved(self):
        result = self.result
        self.assertTrue(result.isValid(), result.getStatusString())
        self.assertEqual(result.Proxy.Type, "Facet::Planarized")
        self.assertTrue(facetwb.is_planarized(result))
        self.assertIs(result.Source, self.source)
        self.assertEqual((result.VertexCount, result.FaceCount), (81, 64))
        self.assertGreater(result.Iterations, 0)
        self.assertEqual(result.StopReason, "tolerance")
        self.assertTrue(result.Converged)
        # checked for corners under 5 degrees the source did not have: none
        self.assertIn(result.QualityCheck, ("ok", "recovered"))
        self.assertEqual(result.NarrowCorners, 0)
        self.assertLessEqual(result.PlanarityMaxRel, TOLERANCE)
        self.assertLess(result.PlanarityMaxAbs.Value, self.source.PlanarityMaxAbs.Value / 1000)
        self.assertGreater(result.DisplacementMax.Value, 0.0)
        self.assertEqual(len(result.FacePlanarity), 64)

    def test_same_topology(self):
        self.assertEqual(list(self.result.FaceStart), list(self.source.FaceStart))
        self.assertEqual(list(self.result.FaceVertices), list(self.source.FaceVertices))

    def test_source_unchanged(self):
        np.testing.assert_array_equal(bits(points_array(self.source)),
                                      bits(self.source_mesh.vertices))
        self.assertEqual(list(self.source.FaceVertices),
                         self.source_mesh.face_vertices.tolist())

    def test_stored_planarity_matches_mesh(self):
        report = facet.planarity(facetwb.get_mesh(self.result))
        np.testing.assert_array_equal(bits(report.max_abs), bits(self.result.FacePlanarity))
        self.assertEqual(report.max_abs_all, self.result.PlanarityMaxAbs.Value)

    def test_summary(self):
        text = facetwb.planarize_summary(self.result)
        self.assertIn("64 panels", text)
        self.assertIn("tolerance reached", text)

    def test_summary_lengths_keep_their_digits_in_the_users_unit(self):
        """Building US (eighths of an inch) summed a planarized facade up as "planarity max
        0", "source 1/4\"" and "rms 1/8\"", Imperial decimal as "planarity max 0.00 in":
        three significant digits in the user's unit now."""
        import re

        import FreeCAD as App

        schema = App.Units.getSchema()
        try:
            for number in (5, 3):
                App.Units.setSchema(number)
                text = facetwb.planarize_summary(self.result)
                found = re.search(r"planarity max (\S+) in \(", text)
                self.assertTrue(found, text)
                self.assertAlmostEqual(float(found.group(1)),
                                       self.result.PlanarityMaxAbs.Value / 25.4,
                                       delta=0.005 * self.result.PlanarityMaxAbs.Value / 25.4)
                self.assertNotIn('"', text)
        finally:
            App.Units.setSchema(schema)

    def test_summary_counts_straight_corners(self):
        # the hypar's skew quads planarize to triangles with a kink (a corner turning
        # under 5 degrees): `facet planarize` said so, the report view did not
        quality = facet.quality(facetwb.get_mesh(self.result), input=self.source_mesh)
        count = int(quality.straight_corner_faces.size)
        self.assertGreater(count, 0)
        self.assertEqual(facet.quality(self.source_mesh).straight_corner_faces.size, 0)
        self.assertIn(f"  {count} panels with a corner within 5 degrees of straight (the "
                      "source had 0)", facetwb.planarize_summary(self.result))

    def test_z_save_reopen(self):  # last: it replaces the class's document
        names = {"source": self.source.Name, "result": self.result.Name}
        before = {key: points_array(self.doc.getObject(name)) for key, name in names.items()}
        results = {prop: getattr(self.result, prop) for prop in (
            "Iterations", "StopReason", "Converged", "PlanarityMaxRel", "Method", "Tolerance")}
        planarity_max = self.result.PlanarityMaxAbs.Value
        doc = self.save_and_reopen("planarized.FCStd")
        source, result = doc.getObject(names["source"]), doc.getObject(names["result"])
        self.assertEqual(result.Proxy.Type, "Facet::Planarized")
        self.assertEqual(source.Proxy.Type, "Facet::PolyMesh")
        self.assertIs(result.Source, source)
        for key, obj in (("source", source), ("result", result)):
            np.testing.assert_array_equal(bits(points_array(obj)), bits(before[key]))
        for prop, value in results.items():
            if isinstance(value, float):  # scalar floats are saved with 16 decimals
                self.assertAlmostEqual(getattr(result, prop), value, places=15, msg=prop)
            else:
                self.assertEqual(getattr(result, prop), value, prop)
        self.assertAlmostEqual(result.PlanarityMaxAbs.Value, planarity_max, places=15)
        # Still planar after the round trip: measured again from the reopened coordinates,
        # the very same bits as before saving.
        report = facet.planarity(facetwb.get_mesh(result))
        self.assertEqual(report.max_abs_all, planarity_max)
        self.assertLessEqual(report.max_rel_all, TOLERANCE)
        # Parametric: a changed parameter re-solves from the (unchanged) source.
        result.Method = "ll"
        result.MaxIterations = 5000
        doc.recompute()
        self.assertTrue(result.isValid(), result.getStatusString())
        self.assertGreater(result.Iterations, 0)
        np.testing.assert_array_equal(bits(points_array(source)), bits(before["source"]))


class TestPlanarizedMethod(DocumentTestCase):
    def test_auto_is_the_default_and_returns_the_closer_of_lg_and_ll_on_a_small_mesh(self):
        from facetwb.objects.planarized import METHODS
        source = importer.import_mesh(data_path("tubemesh.off"), self.doc)
        auto = facetwb.make_planarized(source, tolerance=TOLERANCE)
        lg = facetwb.make_planarized(source, method="lg", tolerance=TOLERANCE)
        ll = facetwb.make_planarized(source, method="ll", tolerance=TOLERANCE)
        self.doc.recompute()
        self.assertEqual(auto.Method, "auto")
        self.assertEqual(list(auto.getEnumerationsOfProperty("Method")), METHODS)
        # 171 quads are far below auto's threshold: L/G, then L/L, whose result is closer
        # to the source surface here with as little sliding (facet's
        # test_planarize_compare.py has the rule) and, solved once without re-solves,
        # the same bits as the L/L object's
        np.testing.assert_array_equal(bits(points_array(auto)), bits(points_array(ll)))
        self.assertEqual(auto.Iterations, lg.Iterations + ll.Iterations)
        from facetwb.objects.planarized import planarize_summary
        summary = planarize_summary(auto)
        self.assertIn("automatic: local/local,", summary)
        self.assertIn("local/global and local/local compared: local/local kept, distance from "
                      "the source surface rms", summary)

    def test_auto_follows_with_a_finer_hold_when_ll_moved_too_far(self):
        from facetwb.objects.planarized import planarize_summary
        from facet_test_support import ROOT
        source = importer.import_mesh(os.path.join(ROOT, "examples", "wave_facade.obj"), self.doc)
        auto = facetwb.make_planarized(source, tolerance=TOLERANCE)
        lg = facetwb.make_planarized(source, method="lg", tolerance=TOLERANCE)
        self.doc.recompute()
        # the demo facade: L/L's result is closer but moves the vertices further:
        # refused; L/G with a finer hold is closer than the first L/G result and kept
        finer = auto.Proxy.compared["finer"]
        self.assertTrue(finer["kept"])
        self.assertGreater(finer["iterations"], 0)
        self.assertEqual(auto.Iterations, lg.Iterations + auto.Proxy.compared["iterations"]
                         + finer["iterations"])
        # the figures are the returned result's; its vertices moved no more than 5%
        # further than the first L/G result's (the L/G object's)
        self.assertAlmostEqual(auto.DisplacementRms.Value,
                               auto.Proxy.compared["lg"]["displacement_rms"], places=9)
        self.assertLessEqual(auto.DisplacementRms.Value, 1.05 * lg.DisplacementRms.Value)
        self.assertNotEqual(bits(points_array(auto)).tobytes(), bits(points_array(lg)).tobytes())
        summary = planarize_summary(auto)
        self.assertIn("automatic: local/global,", summary)
        self.assertIn(f"; local/global again with a finer hold ({finer['iterations']} iterations): "
                      "its result kept", summary)

    def test_a_document_from_before_auto_keeps_its_method(self):
        from facetwb.objects.planarized import METHODS
        source = importer.import_mesh(data_path("hypar.obj"), self.doc)
        old = facetwb.make_planarized(source, tolerance=TOLERANCE)
        old.Method = ["lg", "ll"]  # the enumeration as it was saved before "auto"
        old.Method = "ll"
        old.Proxy.onDocumentRestored(old)
        self.assertEqual(list(old.getEnumerationsOfProperty("Method")), METHODS)
        self.assertEqual(old.Method, "ll")


class TestPlanarizedMixedPolygons(DocumentTestCase):
    def test_hexagons_pentagon_triangles(self):
        source = importer.import_mesh(data_path("panels.off"), self.doc)
        result = facetwb.make_planarized(source, tolerance_abs=0.01, tolerance=1e-9)
        self.doc.recompute()
        self.assertTrue(result.isValid(), result.getStatusString())
        self.assertLessEqual(result.PlanarityMaxAbs.Value, 0.01)
        self.assertEqual(result.FaceCount, 7)


class TestPlanarizedWarnings(DocumentTestCase):
    def test_the_solver_s_warnings_reach_the_object_and_its_summary(self):
        # three quads on one edge (a fin): the command line warned of the non-manifold
        # edge; the Planarized object said nothing
        vertices = [(0, 0, 0), (1000, 0, 0), (0, 1000, 0), (1000, 1000, 0), (0, -1000, 50),
                    (1000, -1000, 0), (0, 0, 1000), (1000, 0, 1000), (3000, 3000, 0)]
        faces = [[0, 1, 3, 2], [0, 4, 5, 1], [0, 1, 7, 6]]
        mesh = facet.PolyMesh.from_faces(vertices, faces)
        expected = facet.planarize(mesh).warnings
        self.assertTrue(any("non-manifold" in w for w in expected), expected)
        source = facetwb.make_polymesh(mesh, doc=self.doc)
        result = facetwb.make_planarized(source)
        self.doc.recompute()
        self.assertTrue(result.isValid(), result.getStatusString())
        self.assertEqual(list(result.Warnings), expected)
        summary = facetwb.planarize_summary(result)
        for text in expected:
            self.assertIn(f"  warning: {text}", summary)


class TestPlanarizedErrors(DocumentTestCase):
    def test_empty_source_is_an_error_not_a_crash(self):
        result = facetwb.make_planarized(importer.import_mesh(data_path("hypar.obj"), self.doc))
        result.Source = None
        self.doc.recompute()
        self.assertFalse(result.isValid())
        self.assertIn("Source is empty", result.getStatusString())

    def test_bad_method(self):
        source = importer.import_mesh(data_path("hypar.obj"), self.doc)
        with self.assertRaises(ValueError):
            facetwb.make_planarized(source, method="newton")

    def test_bad_parameter_values_are_refused_and_the_result_kept(self):
        # a NaN weight was taken for 0 (the term off), saved with the document and solved
        source = importer.import_mesh(data_path("hypar.obj"), self.doc)
        result = facetwb.make_planarized(source, tolerance=1e-3)
        self.doc.recompute()
        solved = facetwb.get_mesh(result).vertices.copy()
        for name, value, says in (("Laplacian", float("nan"), "Laplacian is nan"),
                                  ("ShapeWeight", -1.0, "ShapeWeight is -1.0"),
                                  ("TimeBudget", float("nan"), "TimeBudget is nan"),
                                  ("Tolerance", float("nan"), "Tolerance is nan"),
                                  ("MaxIterations", -5, "MaxIterations is -5"),
                                  ("Anderson", 17, "Anderson is 17; it must be from 0 to 16"),
                                  # above the core's limits: named by property (the core
                                  # said "face 0 has planarity weight 1e+07")
                                  ("FaceWeights", [1e7] + [1.0] * 63,
                                   "FaceWeights: face 0 has weight 1e+07; weights must be in "
                                   "[0, 1e+06]"),
                                  ("Parallelogram", 2e12, "parallelogram 2e+12 is too large")):
            with self.subTest(name=name):
                good = getattr(result, name)
                setattr(result, name, value)
                self.doc.recompute()
                self.assertFalse(result.isValid())
                self.assertIn(f"{result.Label}: {says}", result.getStatusString())
                self.assertTrue(np.array_equal(facetwb.get_mesh(result).vertices, solved))
                setattr(result, name, good)
                self.doc.recompute()
                self.assertTrue(result.isValid(), result.getStatusString())

    def test_planarized_of_planarized(self):
        source = importer.import_mesh(data_path("hypar.obj"), self.doc)
        first = facetwb.make_planarized(source, tolerance=1e-3)
        second = facetwb.make_planarized(first, tolerance=1e-7)
        self.doc.recompute()
        self.assertTrue(second.isValid(), second.getStatusString())
        self.assertLessEqual(second.PlanarityMaxRel, 1e-7)
        self.assertIs(second.Source, first)


class TestPlanarizedTerms(DocumentTestCase):
    """The Terms properties reach the solver and show in the result."""

    def test_terms_that_would_be_ignored_are_refused_by_name(self):
        # a Reference with Data point, or a ShapeWeight with no shape term, gave the same
        # result as without them, and no word
        source = importer.import_mesh(data_path("hypar.obj"), self.doc)
        design = importer.import_mesh(data_path("hypar.obj"), self.doc)
        result = facetwb.make_planarized(source)
        result.Reference = design
        self.doc.recompute()
        self.assertFalse(result.isValid())
        self.assertIn(f"{result.Label}: Reference is the design surface that Data surface "
                      "holds the vertices to; with Data point it would be ignored",
                      result.getStatusString())
        result.Data = "surface"
        self.doc.recompute()
        self.assertTrue(result.isValid(), result.getStatusString())
        result.Reference = None
        result.Data = "point"
        result.ShapeWeight = 5.0
        self.doc.recompute()
        self.assertFalse(result.isValid())
        self.assertIn("ShapeWeight weighs the shape term, which is off (Shape default, Data "
                      "point)", result.getStatusString())
        result.Shape = "asap"
        self.doc.recompute()
        self.assertTrue(result.isValid(), result.getStatusString())

    def test_terms_change_the_result(self):
        source = importer.import_mesh(data_path("hypar.obj"), self.doc)
        # one method for both, so that only the terms differ (auto may return another
        # method's result for one of them)
        plain = facetwb.make_planarized(source, method="lg")
        slid = facetwb.make_planarized(source, method="lg")
        slid.Data = "surface"
        slid.Boundary = "fixed"
        slid.FixedVertices = [40]
        self.doc.recompute()
        for obj in (plain, slid):
            self.assertTrue(obj.isValid(), obj.getStatusString())
            self.assertTrue(obj.Converged)
        before = points_array(source)
        after = points_array(slid)
        np.testing.assert_array_equal(bits(after[40]), bits(before[40]))
        np.testing.assert_array_equal(bits(after[0]), bits(before[0]))  # a corner: boundary
        surface = facet.Surface(facetwb.get_mesh(source))
        d_plain = surface.closest(points_array(plain))[1]
        d_slid = surface.closest(after)[1]
        self.assertLess(np.sqrt(np.mean(d_slid**2)), 0.5 * np.sqrt(np.mean(d_plain**2)))

    def test_exempt_face_and_bad_weights(self):
        source = importer.import_mesh(data_path("hypar.obj"), self.doc)
        result = facetwb.make_planarized(source)
        before = np.asarray(source.FacePlanarity)  # (model units)
        # the source's least planar faces are exempt (four: the hypar is symmetric)
        exempt = before > 0.999 * before.max()
        self.assertEqual(np.count_nonzero(exempt), 4)
        result.FaceWeights = [0.0 if e else 1.0 for e in exempt]
        self.doc.recompute()
        self.assertTrue(result.isValid(), result.getStatusString())
        rel = np.asarray(result.FacePlanarity)
        self.assertGreater(rel[exempt].min(), rel[~exempt].max())
        # the figure over all faces leaves the exempt faces out (it was theirs)
        self.assertAlmostEqual(result.PlanarityMaxAbs.Value, rel[~exempt].max(),
                               delta=1e-6 * rel[exempt].min())
        self.assertLessEqual(result.PlanarityMaxRel, 1e-6)
        summary = facetwb.planarize_summary(result)
        self.assertIn("4 exempt faces (FaceWeights 0) not counted", summary)
        # and so does the source's beside it (it had been the source's own: the exempt faces')
        self.assertIn(f", source {length_text(before[~exempt].max())};", summary)
        self.assertNotIn(f", source {length_text(before.max())};", summary)
        result.FaceWeights = [1.0] * 3
        self.doc.recompute()
        self.assertFalse(result.isValid())
        self.assertIn("FaceWeights has 3 values for 64 faces", result.getStatusString())

    def test_out_of_range_fixed_vertex(self):
        source = importer.import_mesh(data_path("hypar.obj"), self.doc)
        result = facetwb.make_planarized(source)
        result.FixedVertices = [81]
        self.doc.recompute()
        self.assertFalse(result.isValid())
        self.assertIn("FixedVertices has vertex 81", result.getStatusString())
