# SPDX-License-Identifier: LGPL-2.1-or-later
"""PolyMesh objects: import, planarity, and bit-exact storage in .FCStd files."""

import FreeCAD as App
import numpy as np

import facet
import facetwb
from facetwb import importer
from facet_test_support import DocumentTestCase, bits, data_path, points_array


class TestPolyMeshImport(DocumentTestCase):
    def test_obj_quads(self):
        obj = importer.import_mesh(data_path("hypar.obj"), self.doc)
        mesh = facet.read_mesh(data_path("hypar.obj"))
        self.assertTrue(facetwb.is_polymesh(obj))
        self.assertEqual(obj.Proxy.Type, "Facet::PolyMesh")
        self.assertEqual(obj.Label, "hypar")
        self.assertEqual((obj.VertexCount, obj.FaceCount), (81, 64))
        np.testing.assert_array_equal(bits(points_array(obj)), bits(mesh.vertices))
        self.assertEqual(list(obj.FaceStart), mesh.face_start.tolist())
        self.assertEqual(list(obj.FaceVertices), mesh.face_vertices.tolist())
        self.assertNotIn("Invalid", obj.State)
        self.assertTrue(obj.isValid())

    def test_planarity_measured(self):
        obj = importer.import_mesh(data_path("hypar.obj"), self.doc)
        report = facet.planarity(facet.read_mesh(data_path("hypar.obj")))
        self.assertEqual(len(obj.FacePlanarity), 64)
        np.testing.assert_array_equal(bits(obj.FacePlanarity), bits(report.max_abs))
        self.assertEqual(obj.PlanarityMaxAbs.Value, report.max_abs_all)
        self.assertGreater(obj.PlanarityMaxAbs.Value, 1e-3)  # a hypar's quads are warped
        self.assertEqual(str(obj.PlanarityMaxAbs.Unit), str(App.Units.Length))

    def test_off_mixed_polygons(self):
        obj = importer.import_mesh(data_path("panels.off"), self.doc)
        degrees = np.diff(np.array(obj.FaceStart))
        self.assertEqual(sorted(degrees.tolist()), [3, 3, 4, 4, 4, 5, 6])
        self.assertEqual(obj.VertexCount, 14)

    def test_get_mesh_round_trip(self):
        obj = importer.import_mesh(data_path("panels.off"), self.doc)
        mesh = facetwb.get_mesh(obj)
        source = facet.read_mesh(data_path("panels.off"))
        np.testing.assert_array_equal(bits(mesh.vertices), bits(source.vertices))
        np.testing.assert_array_equal(mesh.face_start, source.face_start)
        np.testing.assert_array_equal(mesh.face_vertices, source.face_vertices)


class TestPolyMeshSavedBitExact(DocumentTestCase):
    """A mesh saved in .FCStd and reopened has the very same coordinate bits."""

    def test_save_reopen(self):
        rng = np.random.default_rng(20130)
        # Coordinates that use all 53 bits, of the sizes of a facade in mm, some tiny, some
        # negative: float32 or 6-17 digit text would change some of them.
        xyz = rng.uniform(-5e4, 5e4, size=(81, 3)) + rng.uniform(-1e-9, 1e-9, size=(81, 3))
        xyz[0] = (np.pi * 1e4, -np.e, 1e-300)
        xyz[1] = (np.nextafter(1.0, 2.0), 0.1, -0.0)
        topology = facet.read_mesh(data_path("hypar.obj"))
        mesh = facet.PolyMesh(xyz, topology.face_start, topology.face_vertices)
        obj = facetwb.make_polymesh(mesh, label="random", doc=self.doc)
        self.doc.recompute()
        planarity = list(obj.FacePlanarity)
        name = obj.Name

        doc = self.save_and_reopen("polymesh_bits.FCStd")
        obj = doc.getObject(name)
        self.assertIsNotNone(obj)
        self.assertEqual(obj.Proxy.Type, "Facet::PolyMesh")
        self.assertTrue(facetwb.is_polymesh(obj))
        np.testing.assert_array_equal(bits(points_array(obj)), bits(xyz))
        self.assertEqual(list(obj.FaceStart), topology.face_start.tolist())
        self.assertEqual(list(obj.FaceVertices), topology.face_vertices.tolist())
        np.testing.assert_array_equal(bits(obj.FacePlanarity), bits(planarity))
        # The reopened mesh measures the same, bit for bit.
        again = facet.planarity(facetwb.get_mesh(obj))
        np.testing.assert_array_equal(bits(again.max_abs), bits(planarity))
        # Restored objects are not touched: opening a document does not re-solve anything.
        self.assertNotIn("Touched", obj.State)


class TestOlderDocumentsGainProperties(DocumentTestCase):
    """init_properties() runs again on restore: a document saved before a property existed
    gains it, with its default, and keeps its mesh."""

    def test_restore_adds_missing_properties(self):
        source = importer.import_mesh(data_path("hypar.obj"), self.doc)
        result = facetwb.make_planarized(source)
        self.doc.recompute()
        source.removeProperty("TessellationTolerance")
        result.removeProperty("DisplacementRms")
        result.removeProperty("ToleranceAbs")
        names = source.Name, result.Name
        doc = self.save_and_reopen("older.FCStd")
        source, result = (doc.getObject(name) for name in names)
        self.assertIn("TessellationTolerance", source.PropertiesList)
        self.assertIn("DisplacementRms", result.PropertiesList)
        self.assertEqual(result.ToleranceAbs.Value, 0.0)
        self.assertEqual(result.FaceCount, 64)
        doc.recompute()
        self.assertTrue(result.isValid(), result.getStatusString())


class TestFitView(DocumentTestCase):
    def test_fit_of_an_object_deleted_before_its_timer_fires_does_nothing(self):
        """The view is fitted by a timer once a plan graph whose first read failed draws:
        the object deleted (its document closed) before the timer fired raised
        ReferenceError ("Cannot access attribute 'Document' of deleted object") there."""
        from facetwb.viewproviders.view_polymesh import _fit_view

        doc = App.newDocument("FitGone")
        obj = doc.addObject("App::FeaturePython", "Plan")
        App.closeDocument(doc.Name)
        self.assertIsNone(_fit_view(obj, None))
