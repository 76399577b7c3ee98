# SPDX-License-Identifier: LGPL-2.1-or-later
"""Held vertices: the 3D view's selection ("VertexN" sub-elements) to a Planarized object's
FixedVertices, the messages for what is not a vertex of it, and the solve holding them."""

import numpy as np

import facet
import facetwb
from facetwb import fixed_vertices
from facetwb.fixed_vertices import SelectionError
from facetwb.objects.polymesh import get_mesh
from facet_test_support import DocumentTestCase, data_path


class TestFixedVertices(DocumentTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.mesh = facet.read_mesh(data_path("hypar.obj"))
        cls.control = facetwb.make_polymesh(cls.mesh, label="Control")
        cls.result = facetwb.make_planarized(cls.control, tolerance=1e-6)
        cls.other = facetwb.make_polymesh(cls.mesh, label="Other")
        cls.doc.recompute()

    def setUp(self):
        self.result.FixedVertices = []
        self.doc.recompute()

    def test_the_result_numbers_its_vertices_as_the_control_mesh(self):
        # a vertex picked on the planarized mesh is the control mesh's vertex of that index
        result = get_mesh(self.result)
        self.assertEqual(result.n_vertices, self.mesh.n_vertices)
        np.testing.assert_array_equal(result.face_start, self.mesh.face_start)
        np.testing.assert_array_equal(result.face_vertices, self.mesh.face_vertices)

    def test_vertices_of_the_result_and_of_its_control_mesh(self):
        selection = [(self.result, ("Vertex8", "Vertex0", "Vertex8")),
                     (self.control, ("Vertex80",))]
        self.assertEqual(fixed_vertices.selected_vertices(self.result, selection), [0, 8, 80])

    def test_hold_then_the_solve_keeps_them_where_the_control_mesh_has_them(self):
        held = [0, 8, 40, 72, 80]
        before = get_mesh(self.result).vertices.copy()
        self.assertEqual(fixed_vertices.hold(self.result, held[:3]), 3)
        self.assertEqual(fixed_vertices.hold(self.result, held), 2)
        self.assertEqual(list(self.result.FixedVertices), held)
        self.assertEqual(fixed_vertices.held_text(self.result), "5 vertices held")
        self.doc.recompute()
        self.assertTrue(self.result.isValid(), self.result.getStatusString())
        after = get_mesh(self.result).vertices
        # held: exactly the control mesh's points; before they had moved to planarize
        np.testing.assert_array_equal(after[held], self.mesh.vertices[held])
        self.assertGreater(np.abs(before[held] - self.mesh.vertices[held]).max(), 1e-3)
        self.assertLessEqual(self.result.PlanarityMaxRel, 1e-6)

    def test_free(self):
        fixed_vertices.hold(self.result, [3, 5, 7])
        self.assertEqual(fixed_vertices.free(self.result, [5, 6]), 1)
        self.assertEqual(list(self.result.FixedVertices), [3, 7])
        self.assertEqual(fixed_vertices.held_text(self.result), "2 vertices held")
        self.assertEqual(fixed_vertices.free(self.result), 2)
        self.assertEqual(list(self.result.FixedVertices), [])
        self.assertEqual(fixed_vertices.held_text(self.result), "No vertex held")

    def test_hold_is_one_undo_step(self):
        self.doc.UndoMode = 1
        self.doc.openTransaction("Hold")
        fixed_vertices.hold(self.result, [1, 2])
        self.doc.commitTransaction()
        self.assertEqual(list(self.result.FixedVertices), [1, 2])
        self.doc.undo()
        self.assertEqual(list(self.result.FixedVertices), [])

    def assert_refused(self, selection, *words):
        with self.assertRaises(SelectionError) as caught:
            fixed_vertices.selected_vertices(self.result, selection)
        text = str(caught.exception)
        for word in words:
            self.assertIn(word, text)
        return text

    def test_nothing_selected(self):
        self.assert_refused([], "Nothing is selected", self.result.Label)

    def test_a_panel_or_an_edge_is_not_a_vertex(self):
        self.assert_refused([(self.result, ("Vertex3", "Face12"))], "Face12",
                            "is a face, not a vertex", self.result.Label)
        self.assert_refused([(self.result, ("Edge4",))], "Edge4", "is an edge, not a vertex")

    def test_a_whole_object(self):
        self.assert_refused([(self.result, ())], "as a whole", self.result.Label)

    def test_another_object(self):
        self.assert_refused([(self.other, ("Vertex3",))], "Other is selected",
                            self.result.Label)

    def test_a_vertex_out_of_range(self):
        self.assert_refused([(self.result, ("Vertex81",))], "Vertex81", "81 vertices")

    def test_a_result_not_recomputed_since_its_source_changed(self):
        doc = self.doc
        small = facetwb.make_polymesh(facet.read_mesh(data_path("panels.off")), label="Small")
        result = facetwb.make_planarized(small, tolerance=1e-3)
        doc.recompute()
        result.Source = self.control  # 81 vertices; the result still shows the small mesh
        with self.assertRaises(SelectionError) as caught:
            fixed_vertices.selected_vertices(result, [(result, ("Vertex1",))])
        self.assertIn("recompute it", str(caught.exception))
        doc.removeObject(result.Name)
        doc.removeObject(small.Name)

    def test_a_run_of_selection_events_reads_the_source_once(self):
        # the edit panel asks on every selection event: a 10,000-face Source took 7.5 ms
        from facetwb import conversion

        reads = []
        read = conversion.mesh_from_object

        def counted(obj, *args, **kwargs):
            reads.append(obj.Name)
            return read(obj, *args, **kwargs)

        conversion.mesh_from_object = counted
        try:
            for picked in ("Vertex3", "Vertex5", "Vertex80"):
                fixed_vertices.selected_vertices(self.result, [(self.result, (picked,))])
        finally:
            conversion.mesh_from_object = read
        self.assertEqual(reads, [self.control.Name])

    def test_the_count_follows_a_change_of_the_source(self):
        doc = self.doc
        source = facetwb.make_polymesh(self.mesh, label="Changing")
        result = facetwb.make_planarized(source, tolerance=1e-3)
        doc.recompute()
        self.assertEqual(fixed_vertices.vertex_count(result), 81)
        small = facet.read_mesh(data_path("panels.off"))
        from facetwb.objects.polymesh import set_mesh

        doc.UndoMode = 1
        doc.openTransaction("Smaller")
        set_mesh(source, small)  # the result still shows 81 vertices: recompute it
        doc.commitTransaction()
        with self.assertRaises(SelectionError) as caught:
            fixed_vertices.vertex_count(result)
        self.assertIn(f"Changing has {small.n_vertices}", str(caught.exception))
        doc.recompute()
        self.assertEqual(fixed_vertices.vertex_count(result), small.n_vertices)
        with self.assertRaises(SelectionError) as caught:
            fixed_vertices.selected_vertices(result, [(result, ("Vertex80",))])
        self.assertIn(f"{small.n_vertices} vertices", str(caught.exception))
        doc.undo()  # the 81 vertices back
        doc.recompute()
        self.assertEqual(fixed_vertices.vertex_count(result), 81)
        doc.removeObject(result.Name)
        doc.removeObject(source.Name)
