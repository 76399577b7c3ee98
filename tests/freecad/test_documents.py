# SPDX-License-Identifier: LGPL-2.1-or-later
"""Documents that last: every Facet object type saves, reopens in a FRESH FreeCAD process
and recomputes to the same bits; property changes and object creation undo and redo;
deleting a source leaves its dependents in a clear error state; a cancelled solve keeps the
previous result.

Object types: PolyMesh, SurfaceMesh, Planarized, Cleanup, PlanGraph, Lifting, PanelSet,
CutSheets.
"""

import os
import sys
import unittest

import FreeCAD as App

import facet
import facetwb
from document_state import assert_entry_equal, reopen_in_fresh_process, state
from facet_test_support import DocumentTestCase, ROOT, data_path
from facetwb import importer

sys.path.insert(0, os.path.join(ROOT, "tests", "python"))
import bad_input_cases as cases  # noqa: E402

TYPES = {"Facet::PolyMesh", "Facet::SurfaceMesh", "Facet::Planarized", "Facet::Cleanup", "Facet::PlanGraph",
         "Facet::Lifting", "Facet::PanelSet", "Facet::CutSheets"}


def build_document(doc, folder):
    """Every Facet object type, small, recomputed. Returns {role: object}."""
    source = importer.import_mesh(data_path("hypar.obj"), doc)
    planarized = facetwb.make_planarized(source, tolerance=1e-9)
    cleanup = facetwb.make_cleanup(source, min_edge=0.05, relative=True)
    plan_path = os.path.join(folder, "plan.csv")
    with open(plan_path, "w", encoding="utf-8") as handle:
        handle.write(cases._segments_text(
            [tuple(1000.0 * c for c in s) for s in cases.plan_grid_segments(3)]))
    targets_path = os.path.join(folder, "targets.csv")
    with open(targets_path, "w", encoding="utf-8") as handle:
        handle.write("".join(f"{1000.0 * i!r},{1000.0 * j!r},{100.0 * (i * i - j) + 50 * i * j!r}\n"
                             for j in range(4) for i in range(4)))
    plan = facetwb.make_plan_graph(file=plan_path, doc=doc)
    lifting = facetwb.make_lifting(plan, target_file=targets_path)
    panels = facetwb.make_panelset(planarized, thickness=0.05, gap=0.0)
    sheets = facetwb.make_cutsheets(panels, sheet=(3.0, 3.0), margin=0.01, spacing=0.01,
                                    write_step=False)
    import Part

    cylinder = doc.addObject("Part::Feature", "Surface")
    cylinder.Shape = Part.makeCylinder(2000.0, 3000.0).Faces[0]  # the lateral face
    gridded = facetwb.make_surface_mesh(cylinder, pattern="quad", count_u=12, count_v=4)
    doc.recompute()
    return {"source": source, "planarized": planarized, "cleanup": cleanup, "plan": plan,
            "lifting": lifting, "panels": panels, "sheets": sheets, "surface": cylinder,
            "gridded": gridded}


class TestDocuments(DocumentTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.objects = build_document(cls.doc, cls.tmp.name)
        cls.doc.UndoMode = 1

    def setUp(self):
        for obj in self.objects.values():
            self.assertTrue(obj.isValid(), f"{obj.Label}: {obj.getStatusString()}")

    def test_every_type_is_in_the_document(self):
        self.assertEqual({e["type"] for e in state(self.doc).values()}, TYPES)

    def test_reopens_and_recomputes_bit_for_bit_in_a_fresh_process(self):
        before = state(self.doc)
        path = os.path.join(self.tmp.name, "all_types.FCStd")
        self.doc.save() if self.doc.FileName == path else self.doc.saveAs(path)
        result, output = reopen_in_fresh_process(path, self.tmp.name)
        self.assertIsNotNone(result, output)
        self.assertNotIn("error", result, result.get("error"))
        self.assertNotIn("Traceback", output)
        for phase in ("loaded", "recomputed"):
            self.assertEqual(set(result[phase]), set(before), phase)
            for name, entry in before.items():
                got = result[phase][name]
                self.assertTrue(got["valid"], f"{phase} {name}: {got['status']}")
                # a loaded shape comes from BREP text; a recomputed one is bit for bit
                assert_entry_equal(self, got, entry, f"{phase} {name}",
                                   shape_bits=phase == "recomputed")

    def _undo_redo(self, obj, prop, value):
        doc = self.doc
        before = state(doc)
        doc.openTransaction(f"change {prop}")
        setattr(obj, prop, value)
        doc.commitTransaction()
        doc.recompute()
        changed = state(doc)
        self.assertNotEqual(changed[obj.Name], before[obj.Name], f"{prop} changed nothing")
        self.assertIn(f"change {prop}", doc.UndoNames)
        doc.undo()
        doc.recompute()
        self.assertEqual(state(doc), before, f"undo of {obj.Label}.{prop}")
        doc.redo()
        doc.recompute()
        self.assertEqual(state(doc), changed, f"redo of {obj.Label}.{prop}")
        doc.undo()
        doc.recompute()
        self.assertEqual(state(doc), before)

    def test_undo_redo_planarized_method(self):
        self._undo_redo(self.objects["planarized"], "Method", "ll")

    def test_undo_redo_cleanup_planarize(self):
        self._undo_redo(self.objects["cleanup"], "Planarize", False)

    def test_undo_redo_lifting_weights(self):
        lifting = self.objects["lifting"]
        self._undo_redo(lifting, "Weights", [50.0] + [1.0] * (lifting.VertexCount - 1))

    def test_undo_redo_panel_thickness(self):
        self._undo_redo(self.objects["panels"], "Thickness", 0.08)

    def test_undo_redo_sheet_size(self):
        self._undo_redo(self.objects["sheets"], "SheetWidth", 2.0)

    def test_undo_redo_surface_grid(self):
        self._undo_redo(self.objects["gridded"], "CountU", 16)

    def test_undo_redo_object_creation(self):
        doc = self.doc
        before = state(doc)
        doc.openTransaction("Planarize again")
        extra = facetwb.make_planarized(self.objects["source"], name="Extra")
        doc.commitTransaction()
        doc.recompute()
        name = extra.Name
        self.assertTrue(extra.isValid(), extra.getStatusString())
        doc.undo()
        doc.recompute()
        self.assertIsNone(doc.getObject(name))
        self.assertEqual(state(doc), before)
        doc.redo()
        doc.recompute()
        again = doc.getObject(name)
        self.assertIsNotNone(again)
        self.assertTrue(again.isValid(), again.getStatusString())
        doc.undo()
        doc.recompute()
        self.assertEqual(state(doc), before)

    def test_cancelled_solve_keeps_the_previous_result(self):
        """A solve stopped by its progress callback (the Cancel button) leaves the previous
        result in place and the object in an error state that says so."""
        planarized = self.objects["planarized"]
        before = state(self.doc)
        original = facet.planarize

        def cancelling(*args, **kwargs):
            kwargs["progress"] = lambda *a: True
            return original(*args, **kwargs)

        facet.planarize = cancelling
        try:
            planarized.Tolerance = 1e-10
            self.doc.recompute()
        finally:
            facet.planarize = original
        self.assertFalse(planarized.isValid())
        self.assertIn("cancel", planarized.getStatusString().lower())
        after = state(self.doc)
        self.assertEqual(after[planarized.Name]["points"], before[planarized.Name]["points"])
        planarized.Tolerance = 1e-9
        self.doc.recompute()
        self.assertEqual(state(self.doc), before)


class TestDeletedSources(DocumentTestCase):
    """Deleting a source leaves its dependents in a clear error state: no crash, one line,
    the dependent keeps its last result."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.objects = build_document(cls.doc, cls.tmp.name)

    def _delete(self, role, dependents, words):
        doc = self.doc
        victim = self.objects[role]
        before = state(doc)
        doc.removeObject(victim.Name)
        doc.recompute()
        for dep in dependents:
            obj = self.objects[dep]
            self.assertFalse(obj.isValid(), f"{obj.Label} still valid without its source")
            status = obj.getStatusString()
            self.assertNotIn("\n", status)
            self.assertIn(obj.Label, status)
            self.assertIn(words, status)
            now = state(doc)[obj.Name]
            for key in ("points", "shape"):
                if key in now:
                    self.assertEqual(now[key], before[obj.Name][key], obj.Label)

    def test_1_delete_panelset_leaves_cutsheets_in_error(self):
        self._delete("panels", ["sheets"], "Panels")

    def test_2_delete_plan_leaves_lifting_in_error(self):
        self._delete("plan", ["lifting"], "Plan")

    def test_3_delete_source_leaves_planarized_and_cleanup_in_error(self):
        self._delete("source", ["planarized", "cleanup"], "Source")

    def test_4_delete_surface_leaves_surfacemesh_in_error(self):
        self._delete("surface", ["gridded"], "Source")


if __name__ == "__main__":
    unittest.main()
