# SPDX-License-Identifier: LGPL-2.1-or-later
"""PolyMesh objects: import, planarity, and bit-exact storage in .FCStd files."""

import os

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


def awkward_coordinates(count, seed):
    """Coordinates that use all 53 bits, of the sizes of a facade in mm, and values float32
    or a text of 6-17 digits would change: subnormal, -0.0, tiny, large."""
    rng = np.random.default_rng(seed)
    xyz = rng.uniform(-5e4, 5e4, size=(count, 3)) + rng.uniform(-1e-9, 1e-9, size=(count, 3))
    xyz[0] = (np.pi * 1e4, -np.e, 1e-300)
    xyz[1] = (np.nextafter(1.0, 2.0), 0.1, -0.0)
    xyz[2] = (5e-324, -1.2345678901234567e12, np.nextafter(0.0, -1.0))
    return xyz


class TestStoredArrays(DocumentTestCase):
    """The arrays a PolyMesh gives back (stored_arrays: get_mesh, the drawing) are those
    stored, bit for bit: as kept by its proxy after set_mesh, read again from its properties,
    after every change of a property (a script, undo, redo) and after save and reopen. The
    properties hold the same values as App.Vector objects give (what the .FCStd saves)."""

    def make(self, seed=37):
        from facetwb.objects.polymesh import stored_arrays

        topology = facet.read_mesh(data_path("hypar.obj"))
        xyz = awkward_coordinates(topology.n_vertices, seed)
        mesh = facet.PolyMesh(xyz, topology.face_start, topology.face_vertices)
        obj = facetwb.make_polymesh(mesh, doc=self.doc)
        return obj, mesh, stored_arrays

    def assert_holds(self, obj, mesh, stored_arrays):
        kept = stored_arrays(obj)
        obj.Proxy.stored_arrays = None  # what the properties give, read again
        read = stored_arrays(obj)
        for xyz, face_start, face_vertices in (kept, read):
            np.testing.assert_array_equal(bits(xyz), bits(mesh.vertices))
            self.assertEqual((face_start.dtype, face_vertices.dtype), (np.int32, np.int32))
            np.testing.assert_array_equal(face_start, mesh.face_start)
            np.testing.assert_array_equal(face_vertices, mesh.face_vertices)
            self.assertFalse(xyz.flags.writeable or face_start.flags.writeable
                             or face_vertices.flags.writeable)
        np.testing.assert_array_equal(bits(points_array(obj)), bits(mesh.vertices))
        self.assertEqual(list(obj.FaceStart), mesh.face_start.tolist())
        self.assertEqual(list(obj.FaceVertices), mesh.face_vertices.tolist())
        np.testing.assert_array_equal(bits(facetwb.get_mesh(obj).vertices), bits(mesh.vertices))

    def test_set_mesh_round_trip_bit_for_bit(self):
        obj, mesh, stored_arrays = self.make()
        self.assert_holds(obj, mesh, stored_arrays)

    def test_set_points_round_trip_bit_for_bit(self):
        from facetwb.objects.polymesh import set_points

        obj, mesh, stored_arrays = self.make()
        moved = mesh.with_vertices(awkward_coordinates(mesh.n_vertices, 38))
        set_points(obj, moved.vertices)
        self.assert_holds(obj, moved, stored_arrays)

    def test_kept_arrays_follow_every_change(self):
        obj, mesh, stored_arrays = self.make()
        self.doc.recompute()
        stored_arrays(obj)  # kept
        moved = mesh.with_vertices(awkward_coordinates(mesh.n_vertices, 39))
        self.doc.UndoMode = 1
        self.doc.openTransaction("move by script")
        obj.Points = [App.Vector(*row) for row in moved.vertices.tolist()]
        self.doc.commitTransaction()
        self.assert_holds(obj, moved, stored_arrays)
        self.doc.undo()
        self.assert_holds(obj, mesh, stored_arrays)
        self.doc.redo()
        self.assert_holds(obj, moved, stored_arrays)
        # set_mesh in a transaction (a recompute's write-back), undone and redone
        from facetwb.objects.polymesh import set_mesh

        other = facet.read_mesh(data_path("panels.off"))
        self.doc.openTransaction("store another mesh")
        set_mesh(obj, other)
        self.doc.commitTransaction()
        self.assert_holds(obj, other, stored_arrays)
        self.doc.undo()
        self.assert_holds(obj, moved, stored_arrays)
        self.doc.redo()
        self.assert_holds(obj, other, stored_arrays)
        self.doc.undo()
        self.assert_holds(obj, moved, stored_arrays)
        # a re-solve: the same topology, only the coordinates stored (and undone)
        resolved = moved.with_vertices(awkward_coordinates(mesh.n_vertices, 42))
        self.doc.openTransaction("re-solve")
        set_mesh(obj, resolved)
        self.doc.commitTransaction()
        self.assert_holds(obj, resolved, stored_arrays)
        self.doc.undo()
        # a face's corners in the other order, by script: the topology given back follows
        face_vertices = moved.face_vertices.copy()
        face_vertices[:4] = face_vertices[:4][::-1]
        obj.FaceVertices = face_vertices.tolist()
        turned = facet.PolyMesh(moved.vertices, moved.face_start, face_vertices)
        self.assert_holds(obj, turned, stored_arrays)

    def test_index_beyond_32_bits_is_an_error_not_wrapped(self):
        """A script's index beyond 32 bits was read as int32, wrapped around: 2**32 + 1
        became vertex 1, a mesh silently different from the properties."""
        from facetwb.objects.polymesh import mesh_arrays

        obj, mesh, _ = self.make()
        face_vertices = mesh.face_vertices.tolist()
        face_vertices[0] = 2**32 + 1
        obj.FaceVertices = face_vertices
        with self.assertRaisesRegex(ValueError, "FaceVertices holds values beyond the 32-bit"):
            facetwb.get_mesh(obj)
        self.assertIsNone(mesh_arrays(obj))

    def test_save_reopen_bit_for_bit(self):
        obj, mesh, stored_arrays = self.make(40)
        self.doc.recompute()
        name = obj.Name
        doc = self.save_and_reopen("stored_arrays.FCStd")
        self.assert_holds(doc.getObject(name), mesh, stored_arrays)


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


class TestSavedDocumentsRead(DocumentTestCase):
    """Documents saved before the bulk storage (examples/*.FCStd) give the arrays their
    properties hold, bit for bit: the coordinates the App.Vector path gives."""

    def test_examples_read_bit_for_bit(self):
        import importlib
        import shutil

        from facet_test_support import ROOT
        from facetwb.objects.polymesh import stored_arrays

        for module in ("polymesh", "planarized", "cleanup", "plangraph", "lifting",
                       "panelset"):  # (as test_examples: FreeCAD 0.20.2 imports no proxy
            importlib.import_module(f"facetwb.objects.{module}")  # from outside Mod)
        checked = 0
        for name in ("facade.FCStd", "roof.FCStd"):
            path = os.path.join(self.tmp.name, name)
            shutil.copy(os.path.join(ROOT, "examples", name), path)
            doc = App.openDocument(path)
            try:
                for obj in doc.Objects:
                    if not facetwb.is_polymesh(obj):
                        continue
                    xyz, face_start, face_vertices = stored_arrays(obj)
                    np.testing.assert_array_equal(bits(xyz), bits(points_array(obj)))
                    self.assertEqual(face_start.tolist(), list(obj.FaceStart))
                    self.assertEqual(face_vertices.tolist(), list(obj.FaceVertices))
                    checked += 1
            finally:
                App.closeDocument(doc.Name)
        self.assertGreaterEqual(checked, 2)

class TestCoinFieldsFromArrays(DocumentTestCase):
    """The view provider hands numpy arrays to Coin (pivy reads them without a Python object
    per value): the fields hold what the lists gave, float32 and int32 as Coin keeps them."""

    def test_set_mfield_takes_arrays(self):
        from pivy import coin

        from facetwb.viewproviders.view_polymesh import _set_mfield

        xyz = awkward_coordinates(50, 41)
        from_array, from_list = coin.SoCoordinate3(), coin.SoCoordinate3()
        _set_mfield(from_array.point, xyz)
        _set_mfield(from_list.point, xyz.tolist())
        values = [[from_array.point[i].getValue(), from_list.point[i].getValue()]
                  for i in range(from_array.point.getNum())]
        self.assertEqual(len(values), 50)
        drawn = np.array(values, dtype=np.float32)  # (exact: Coin's floats)
        np.testing.assert_array_equal(drawn[:, 0].view(np.uint32),
                                      xyz.astype(np.float32).view(np.uint32))
        np.testing.assert_array_equal(drawn[:, 0].view(np.uint32), drawn[:, 1].view(np.uint32))

        index = np.array([0, 1, 2, 3, -1, 4, 5, 6, -1], dtype=np.int32)
        faces = coin.SoIndexedFaceSet()
        _set_mfield(faces.coordIndex, index)
        self.assertEqual([faces.coordIndex[i] for i in range(faces.coordIndex.getNum())],
                         index.tolist())
        _set_mfield(faces.coordIndex, index[:4])  # shrinks
        self.assertEqual(faces.coordIndex.getNum(), 4)
        _set_mfield(from_array.point, np.zeros((0, 3)))
        self.assertEqual(from_array.point.getNum(), 0)
