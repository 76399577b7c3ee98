# SPDX-License-Identifier: LGPL-2.1-or-later
"""Cleanup objects: collapse short edges on recompute into a new topology, keep the source."""

import numpy as np

import facet
import facetwb
from facet_test_support import DocumentTestCase, bits, points_array


def squeezed_grid(nu=6, nv=4, column=3):
    """A quad grid whose column ``column`` sits 0.01 from its left neighbour."""
    xs = np.arange(nu + 1, dtype=float)
    xs[column] = xs[column - 1] + 0.01
    vertices = [(x, y, 0.1 * np.sin(x) * np.cos(y)) for y in range(nv + 1) for x in xs]
    faces = [[j * (nu + 1) + i, j * (nu + 1) + i + 1, (j + 1) * (nu + 1) + i + 1,
              (j + 1) * (nu + 1) + i] for j in range(nv) for i in range(nu)]
    return facet.PolyMesh.from_faces(vertices, faces)


class TestCleanup(DocumentTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.source_mesh = squeezed_grid()
        cls.source = facetwb.make_polymesh(cls.source_mesh, label="squeezed", doc=cls.doc)
        cls.result = facetwb.make_cleanup(cls.source, min_edge=0.1, relative=True)
        cls.doc.recompute()

    def test_collapsed(self):
        result = self.result
        self.assertTrue(result.isValid(), result.getStatusString())
        self.assertTrue(facetwb.is_cleanup(result))
        self.assertEqual(result.Proxy.Type, "Facet::Cleanup")
        self.assertIs(result.Source, self.source)
        self.assertEqual(result.CollapsedEdges, 5)
        self.assertEqual(result.RemovedFaces, 4)
        self.assertEqual(result.SkippedEdges, 0)
        self.assertEqual((result.FaceCount, result.VertexCount), (20, 30))
        self.assertTrue(result.Converged)
        self.assertLessEqual(result.PlanarityMaxRel, 1e-6)
        self.assertIn("5 short edges collapsed", facetwb.cleanup_summary(result))

    def test_new_topology_is_valid(self):
        mesh = facetwb.get_mesh(self.result)
        report = mesh.validate()
        self.assertEqual(report["n_non_manifold_edges"], 0)
        self.assertEqual(report["n_isolated_vertices"], 0)
        self.assertEqual(mesh.n_faces, 20)

    def test_source_unchanged(self):
        np.testing.assert_array_equal(bits(points_array(self.source)),
                                      bits(self.source_mesh.vertices))
        self.assertEqual(self.source.FaceCount, 24)

    def test_unwelded_seams_are_joined_first(self):
        """An unwelded export (each quad its own copy of the vertices it shares) planarized
        as it was opens its seams, which the warnings can only tell the designer to weld:
        the Cleanup joins them first (Weld, on by default), and says so."""
        quads = squeezed_grid(nu=2, nv=1, column=1)
        faces = quads.faces()
        points = np.asarray(quads.vertices)
        apart = facet.PolyMesh.from_faces(
            np.vstack([points, points[[faces[1][0], faces[1][3]]]]),
            [faces[0], [len(points), faces[1][1], faces[1][2], len(points) + 1]])
        source = facetwb.make_polymesh(apart, label="apart", doc=self.doc)
        welded = facetwb.make_cleanup(source, min_edge=0.001, name="Welded")
        kept = facetwb.make_cleanup(source, min_edge=0.001, name="Kept", weld=False)
        self.doc.recompute()
        self.assertTrue(welded.isValid(), welded.getStatusString())
        self.assertEqual((welded.WeldedVertices, welded.VertexCount), (2, 6))
        self.assertEqual((kept.WeldedVertices, kept.VertexCount), (0, 8))
        self.assertIn("2 vertices at one point with another joined first",
                      facetwb.cleanup_summary(welded))
        self.assertEqual(source.VertexCount, 8)  # the source is kept as it was

    def test_parametric(self):
        self.result.MinEdge = 0.001  # nothing that short: the source's topology again
        self.doc.recompute()
        self.assertEqual(self.result.CollapsedEdges, 0)
        self.assertEqual(self.result.FaceCount, 24)
        self.result.MinEdge = 0.1
        self.doc.recompute()
        self.assertEqual(self.result.FaceCount, 20)

    def test_too_long_fails_with_a_message(self):
        bad = facetwb.make_cleanup(self.source, min_edge=50.0, name="TooLong")
        self.doc.recompute()
        self.assertFalse(bad.isValid())
        self.assertIn("every face would collapse", facetwb.cleanup_summary(bad))
        self.doc.removeObject(bad.Name)
        self.doc.recompute()

    def test_cancel_keeps_the_previous_result(self):
        # the cleanup's planarization reports progress and can be cancelled (it could not)
        other = facetwb.make_cleanup(self.source, min_edge=0.1, relative=True, name="Cancel")
        self.doc.recompute()
        kept = facetwb.get_mesh(other).vertices.copy()
        other.Tolerance = 1e-10
        reporter = self.recompute_cancelled(2)
        self.assertTrue(reporter.cancelled and reporter.calls >= 2)
        self.assertFalse(other.isValid())
        self.assertIn("cancelled", other.getStatusString())
        self.assertTrue(np.array_equal(facetwb.get_mesh(other).vertices, kept))
        self.doc.removeObject(other.Name)
        self.doc.recompute()

    def test_z_save_reopen(self):
        name = self.result.Name
        doc = self.save_and_reopen("cleanup.FCStd")
        result = doc.getObject(name)
        self.assertEqual(result.Proxy.Type, "Facet::Cleanup")
        self.assertEqual(result.FaceCount, 20)
        self.assertEqual(result.CollapsedEdges, 5)
