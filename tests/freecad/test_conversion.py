# SPDX-License-Identifier: LGPL-2.1-or-later
"""PolyMeshes from FreeCAD Mesh and Part objects (Facet_ToPolyMesh's scripting API)."""

import FreeCAD as App
import Mesh
import numpy as np
import Part

import facet
import facetwb
from facet_test_support import DocumentTestCase, outward_faces, points_array


class TestToPolyMesh(DocumentTestCase):
    def test_part_box_gives_quads(self):
        box = self.doc.addObject("Part::Box", "Box")
        box.Length, box.Width, box.Height = 3000, 2000, 1000
        obj = facetwb.make_polymesh_from_object(box)
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual((obj.VertexCount, obj.FaceCount), (8, 6))
        self.assertEqual(set(np.diff(np.array(obj.FaceStart)).tolist()), {4})
        self.assertTrue(all(outward_faces(obj)))
        self.assertEqual(obj.PlanarityMaxAbs.Value, 0.0)

    def test_follows_its_source(self):
        box = self.doc.addObject("Part::Box", "Box")
        obj = facetwb.make_polymesh_from_object(box)
        self.doc.recompute()
        box.Height = 55.5
        self.doc.recompute()
        self.assertAlmostEqual(points_array(obj)[:, 2].max(), 55.5)

    def test_polygon_faces_share_vertices(self):
        square = [(0, 0, 0), (1000, 0, 0), (1000, 1000, 0), (0, 1000, 0)]
        faces = [Part.Face(Part.makePolygon(square + [square[0]]))]
        roof = [(1000, 0, 0), (2000, 0, 300), (2000, 1000, 300), (1000, 1000, 0)]
        faces.append(Part.Face(Part.makePolygon(roof + [roof[0]])))
        feature = self.doc.addObject("Part::Feature", "Panels")
        feature.Shape = Part.makeCompound(faces)
        obj = facetwb.make_polymesh_from_object(feature)
        self.doc.recompute()
        self.assertEqual((obj.VertexCount, obj.FaceCount), (6, 2))

    def test_panels_modelled_apart_are_joined(self):
        """Two panels modelled one by one, their common corners a rounding apart (0.1 + 0.2
        against 0.3): one vertex each, so the panels are joined and mitred. They were two
        vertices each, and the panels' common edge was cut square, with no bevel."""
        from facet.mesh import coincident_vertices

        def face(points):
            return Part.Face(Part.makePolygon([App.Vector(*p) for p in points + points[:1]]))

        a = face([(0, 0, 0), (0.1 + 0.2, 0, 0), (0.1 + 0.2, 1, 0), (0, 1, 0)])
        b = face([(0.3, 0, 0), (0.6, 0, 0.1), (0.6, 1, 0.1), (0.3, 1, 0)])
        obj = self.doc.addObject("Part::Feature", "Panels")
        obj.Shape = Part.makeCompound([a, b])
        mesh = facetwb.conversion.mesh_from_object(obj)
        self.assertEqual((mesh.n_vertices, mesh.n_faces), (6, 2))
        self.assertEqual(coincident_vertices(mesh), (0, None))
        panel_set = facet.panels(mesh, 0.01, edge="bisector")
        self.assertEqual(sum(abs(b) > 1 for p in panel_set.panels for b in p.bevel_deg), 2)

    def test_mesh_gives_triangles(self):
        feature = self.doc.addObject("Mesh::Feature", "MeshBox")
        feature.Mesh = Mesh.createBox(10, 20, 30)
        obj = facetwb.make_polymesh_from_object(feature)
        self.doc.recompute()
        self.assertEqual((obj.VertexCount, obj.FaceCount), (8, 12))
        self.assertEqual(set(np.diff(np.array(obj.FaceStart)).tolist()), {3})

    def test_curved_shape_is_triangulated(self):
        cylinder = self.doc.addObject("Part::Cylinder", "Cylinder")
        obj = facetwb.make_polymesh_from_object(cylinder)
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertGreater(obj.FaceCount, 20)
        self.assertEqual(set(np.diff(np.array(obj.FaceStart)).tolist()), {3})
        facet.PolyMesh(*[np.asarray(a) for a in (
            points_array(obj), np.array(obj.FaceStart, np.int32),
            np.array(obj.FaceVertices, np.int32))]).validate()

    def test_planarize_a_part_shape_directly(self):
        box = self.doc.addObject("Part::Box", "Box")
        result = facetwb.make_planarized(box)
        self.doc.recompute()
        self.assertTrue(result.isValid(), result.getStatusString())
        self.assertEqual(result.FaceCount, 6)
