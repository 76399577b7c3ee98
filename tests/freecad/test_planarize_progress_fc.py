# SPDX-License-Identifier: LGPL-2.1-or-later
"""A Planarized object's recompute that re-solves for panel quality: the progress text
says so ("re-solving for panel quality (stage k of n)") and the count runs on through the
re-solves (headless: the reporter records what the dialog would show); method auto's
comparison solve by L/L and its L/G solve with a finer hold are named too."""

import os
import re
import sys

import facet
import facetwb
from facetwb import progress
from facet_test_support import ROOT, DocumentTestCase

sys.path.insert(0, os.path.join(ROOT, "tools", "bench"))
import families  # noqa: E402


class TestPlanarizeProgress(DocumentTestCase):
    def tearDown(self):
        progress.cancel_after(0)

    def _hypar(self):
        # the 32 x 32 hypar: the default's first solve closes corners (0.54 degrees when
        # this was written); a re-solve recovers
        b = families.hypar(32)
        mesh = facet.PolyMesh(b.vertices, b.face_start, b.face_vertices)
        return facetwb.make_polymesh(mesh, doc=self.doc, label="hypar 32")

    def test_progress_text_names_the_resolve(self):
        source = self._hypar()
        result = facetwb.make_planarized(source, method="lg")  # (auto: the test below)
        self.doc.recompute()  # the source first, without a dialog
        result.touch()
        with progress.reporting("Planarize ...") as reporter:
            self.doc.recompute()
        self.assertTrue(result.isValid(), result.getStatusString())
        # the planarity reached against the tolerance, from the first iteration on
        first = re.fullmatch(r"Planarize \.\.\.\nplanarity (\S+) \(tolerance (\S+)\)",
                             reporter.texts[1])
        self.assertTrue(first, reporter.texts[:2])
        self.assertEqual(float(first.group(2)), result.Tolerance)
        self.assertGreater(float(first.group(1)), 100 * result.Tolerance)  # a skew hypar
        said = [t for t in reporter.texts if "re-solving for panel quality" in t]
        if result.QualityCheck == "ok":  # the first solve kept its corners open
            self.assertEqual(said, [])
            return
        self.assertIn(result.QualityCheck, ("recovered", "narrow"))
        # each re-solve named as it starts, then with its planarity below
        stages = [t.split("\n")[1] for t in said]
        starts = [t for k, t in enumerate(stages) if k == 0 or t != stages[k - 1]]
        self.assertGreaterEqual(len(starts), 1)
        for k, text in enumerate(starts, start=1):
            self.assertEqual(text, f"Planarize {result.Label}: re-solving for panel quality "
                                   f"(stage {k} of 4)")
        self.assertTrue(all(len(t.split("\n")) == 2 or t.split("\n")[2].startswith("planarity ")
                            for t in said), said[:3])
        self.assertTrue(any(len(t.split("\n")) == 3 for t in said))
        # one count through the re-solves: one call per iteration, the last at the total,
        # within its bound
        self.assertEqual(reporter.calls, result.Iterations)
        self.assertEqual(reporter.done, result.Iterations)
        self.assertGreaterEqual(reporter.total, reporter.done)
        # the text is the title again once the solve is done
        self.assertEqual(reporter.text, "Planarize ...")

    def _recompute_reporting(self, source):
        """A Planarized object of source (method auto), recomputed once without and
        then with the progress reporter; returns (object, reporter)."""
        result = facetwb.make_planarized(source)
        self.doc.recompute()
        result.touch()
        with progress.reporting("Planarize ...") as reporter:
            self.doc.recompute()
        self.assertTrue(result.isValid(), result.getStatusString())
        return result, reporter

    def test_progress_text_names_the_comparison(self):
        result, reporter = self._recompute_reporting(self._hypar())
        title = (f"Planarize {result.Label}: solving by local/local too, for a result closer "
                 "to the design")
        said = [k for k, t in enumerate(reporter.texts) if title in t]
        self.assertTrue(said, reporter.texts[-3:])
        # after every re-solve's text, then with its planarity below
        self.assertFalse(any("re-solving" in t for t in reporter.texts[said[0]:]))
        self.assertTrue(any(t.endswith(")") and "\nplanarity " in t
                            for t in reporter.texts[said[0]:]))
        self.assertEqual(reporter.calls, result.Iterations)
        self.assertEqual(reporter.text, "Planarize ...")

    def test_progress_text_names_the_finer_solve(self):
        # the demo facade: L/L's result moves the vertices too far, L/G with a finer
        # hold follows, named after the comparison
        from facetwb import importer
        from facet_test_support import ROOT
        source = importer.import_mesh(os.path.join(ROOT, "examples", "wave_facade.obj"), self.doc)
        result, reporter = self._recompute_reporting(source)
        compare = [k for k, t in enumerate(reporter.texts) if "local/local too" in t]
        finer = [k for k, t in enumerate(reporter.texts)
                 if f"Planarize {result.Label}: solving by local/global again with a finer hold, "
                    "closer to the design" in t]
        self.assertTrue(compare and finer and finer[0] > compare[-1], reporter.texts[-3:])
        self.assertEqual(reporter.calls, result.Iterations)

    def test_stop_in_a_resolve_keeps_the_first_result(self):
        # once the first solve reached the tolerance the button reads "Stop and keep":
        # pressed in a re-solve, the object keeps the first solve's result, and the rest
        # of the recompute is not cancelled
        source = self._hypar()
        result = facetwb.make_planarized(source, method="lg")
        self.doc.recompute()
        first = facet.planarize(facetwb.get_mesh(source), method="lg", quality_angle=0.0)
        if result.QualityCheck == "ok":
            self.skipTest("the first solve of the 32 x 32 hypar no longer closes a corner")
        finished = (result.Iterations, result.QualityCheck)
        from facetwb.objects.planarized import planarize_summary
        self.assertNotIn("stopped (Stop and keep)", planarize_summary(result))
        # recomputed after it: a Planarized object of the Planarized one (the kept result
        # has narrow corners, which panels may refuse), to a tolerance that takes iterations
        after = facetwb.make_planarized(result, method="lg", tolerance=1e-9)
        self.doc.recompute()
        self.assertTrue(after.isValid(), after.getStatusString())
        result.touch()
        progress.cancel_after(first.iterations + 3)  # the third iteration of the first re-solve
        with progress.reporting("Planarize ...") as reporter:
            self.doc.recompute()
            self.assertFalse(reporter.keeps or reporter.cancelled)
        # the stop at the planarizer's call first.iterations + 3, then the next one's calls
        self.assertGreater(reporter.calls, first.iterations + 3)
        self.assertIn("stage 1 of 4", "".join(reporter.texts))
        self.assertTrue(result.isValid(), result.getStatusString())
        self.assertEqual(result.QualityCheck, "narrow")
        self.assertGreater(result.NarrowCorners, 0)  # what the re-solves had yet to mend
        self.assertEqual(result.Iterations, first.iterations + 3)
        self.assertNotEqual((result.Iterations, result.QualityCheck), finished)
        self.assertTrue(result.Converged)
        self.assertLessEqual(result.PlanarityMaxRel, result.Tolerance)
        kept = facetwb.get_mesh(result).vertices
        self.assertTrue((kept == first.mesh.vertices).all())
        summary = planarize_summary(result)
        self.assertIn("stopped (Stop and keep)", summary)
        self.assertIn(f"{result.NarrowCorners} panel corners under 5 degrees", summary)
        # the rest of the recompute ran, on the kept result
        self.assertTrue(after.isValid(), after.getStatusString())
        self.assertNotIn("Touched", after.State)
        self.assertTrue((facetwb.get_mesh(after.Source).vertices == kept).all())

    def test_cancel_in_the_first_solve(self):
        # before any result reached the tolerance the button is Cancel: nothing is kept
        source = self._hypar()
        result = facetwb.make_planarized(source, method="lg")
        self.doc.recompute()
        before = facetwb.get_mesh(result).vertices.copy()
        result.Tolerance = 1e-9
        progress.cancel_after(5)
        with progress.reporting("Planarize ...") as reporter:
            self.doc.recompute()
        self.assertTrue(reporter.cancelled)
        self.assertFalse(reporter.keeps)
        self.assertFalse(result.isValid())
        self.assertIn("ancel", result.getStatusString())
        self.assertTrue((facetwb.get_mesh(result).vertices == before).all())

    def test_a_firmer_hold_is_named_in_the_summary(self):
        # heart.obj with plane data: every re-solve at the preset's own weight closes a
        # panel; the one holding the vertices more firmly along the design keeps them
        # open, and the report view says with which weight
        from facetwb import importer
        from facetwb.objects.planarized import planarize_summary

        source = importer.import_mesh(os.path.join(ROOT, "tests", "data", "heart.obj"), self.doc)
        before = facetwb.get_mesh(source).vertices.copy()
        result = facetwb.make_planarized(source)
        result.Data = "plane"
        self.doc.recompute()
        self.assertTrue(result.isValid(), result.getStatusString())
        self.assertEqual(result.QualityCheck, "recovered")
        self.assertEqual(result.NarrowCorners, 0)
        self.assertEqual(result.DataTangentUsed, 0.03)  # kept in the document
        self.assertIn("solved again without it, holding the vertices more firmly along the "
                      "design (data tangent 0.03 instead of 0.01)", planarize_summary(result))
        self.assertTrue((facetwb.get_mesh(source).vertices == before).all())
        # point data: nothing to hold more firmly, and the summary says nothing of it
        result.Data = "point"
        self.doc.recompute()
        self.assertEqual(result.DataTangentUsed, 1.0)
        self.assertNotIn("more firmly", planarize_summary(result))

    def test_a_stalled_result_names_its_narrow_corners(self):
        # local/local alone stalls short of the tolerance on this saddle with a corner
        # under 5 degrees: not re-solved, but counted in NarrowCorners and the summary
        sys.path.insert(0, os.path.join(ROOT, "tests", "python"))
        from test_planarize_fallback import _saddle
        from facetwb.objects.planarized import planarize_summary

        source = facetwb.make_polymesh(_saddle(101, 8.0, 0.4), doc=self.doc, label="saddle")
        result = facetwb.make_planarized(source, method="ll")
        self.doc.recompute()
        self.assertTrue(result.isValid(), result.getStatusString())
        self.assertFalse(result.Converged)
        self.assertEqual(result.QualityCheck, "not_checked")
        self.assertGreater(result.NarrowCorners, 0)
        self.assertIn(f"{result.NarrowCorners} panel corners under 5 degrees that the source "
                      "did not have, not re-solved", planarize_summary(result))
