# SPDX-License-Identifier: LGPL-2.1-or-later
"""SurfaceMesh: control meshes sampled from FreeCAD surfaces (Facet_SurfaceMesh's scripting
API), the preferences, and progress/Cancel in recomputes (headless)."""

import math

import FreeCAD as App
import Mesh
import numpy as np

import facetwb
from facet_test_support import DocumentTestCase, outward_faces, points_array
from facetwb import preferences, progress


def face_sizes(obj):
    return sorted(set(np.diff(np.array(obj.FaceStart)).tolist()))


class TestSurfaceMesh(DocumentTestCase):
    def cylinder_face(self, name, wanted):
        """A Part::Feature holding the first face that ``wanted`` accepts of a cylinder of
        radius 2000 and height 3000 on the z axis."""
        cyl = self.doc.addObject("Part::Cylinder", "Cylinder")
        cyl.Radius, cyl.Height = 2000, 3000
        self.doc.recompute()
        face = self.doc.addObject("Part::Feature", name)
        face.Shape = [f for f in cyl.Shape.Faces if wanted(f)][0]
        return face

    def test_cylinder_quad_grid_closed_and_outward(self):
        side = self.cylinder_face("Side", lambda f: f.Surface.__class__.__name__ == "Cylinder")
        shape_before = side.Shape.exportBrepToString()
        obj = facetwb.make_surface_mesh(side, "quad", 12, 4)
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual((obj.FaceCount, obj.VertexCount), (48, 60))  # seam welded
        self.assertEqual(face_sizes(obj), [4])
        mesh = facetwb.get_mesh(obj)
        mesh.validate()
        self.assertTrue(all(outward_faces(obj, np.array([0.0, 0.0, 1500.0]))))
        self.assertTrue(np.allclose(np.hypot(mesh.vertices[:, 0], mesh.vertices[:, 1]), 2000.0))
        self.assertEqual(side.Shape.exportBrepToString(), shape_before)

    def test_hex_grid_closes_around_a_cylinder(self):
        side = self.cylinder_face("Side", lambda f: f.Surface.__class__.__name__ == "Cylinder")
        obj = facetwb.make_surface_mesh(side, "hex", 12, 5)
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual((obj.FaceCount, face_sizes(obj)), (60, [6]))
        mesh = facetwb.get_mesh(obj)
        count = {}
        for face in mesh.faces():
            for a, b in zip(face, np.roll(face, -1)):
                key = (min(a, b), max(a, b))
                count[key] = count.get(key, 0) + 1
        self.assertEqual(sum(1 for n in count.values() if n == 1), 2 * 24)  # two zigzag rims
        self.assertTrue(all(outward_faces(obj, np.array([0.0, 0.0, 1500.0]))))

    def test_trimmed_face_keeps_cells_inside(self):
        disc = self.cylinder_face("Disc", lambda f: f.Surface.__class__.__name__ == "Plane")
        obj = facetwb.make_surface_mesh(disc, "quad", 8, 8)
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        radii = np.hypot(points_array(obj)[:, 0], points_array(obj)[:, 1])
        self.assertLessEqual(radii.max(), 2000.0 + 1e-6)
        self.assertTrue(0 < obj.FaceCount < 64)

    def test_panel_size_and_follows_source(self):
        box = self.doc.addObject("Part::Box", "Wall")
        box.Length, box.Width, box.Height = 6000, 10, 3000
        obj = facetwb.make_surface_mesh(box, "quad", panel_size=1000.0)
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        lengths = [np.linalg.norm(a - b) for a, b in
                   ((facetwb.get_mesh(obj).vertices[i], facetwb.get_mesh(obj).vertices[j])
                    for i, j in facetwb.get_mesh(obj).edges())]
        self.assertLessEqual(max(lengths), 1000.0 + 1e-6)
        before = points_array(obj).copy()
        box.Height = 4000
        self.doc.recompute()
        self.assertEqual(points_array(obj)[:, 2].max(), 4000.0)
        self.assertNotEqual(before.shape, points_array(obj).shape)

    def test_hex_grid_on_a_bspline_face(self):
        import Part

        poles = [[App.Vector(1000 * i, 1000 * j, 300 * math.sin(i + j)) for j in range(4)]
                 for i in range(4)]
        surface = Part.BSplineSurface()
        surface.buildFromPolesMultsKnots(poles, [4, 4], [4, 4], [0, 1], [0, 1], False, False,
                                         3, 3)
        feature = self.doc.addObject("Part::Feature", "Free")
        feature.Shape = surface.toShape()
        obj = facetwb.make_surface_mesh(feature, "hex", 5, 4)
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual((obj.FaceCount, face_sizes(obj)), (20, [6]))
        self.assertGreater(obj.PlanarityMaxAbs.Value, 1.0)

    def test_mesh_triangles_paired(self):
        mesh = Mesh.Mesh()
        for i in range(3):
            a = App.Vector(1000 * i, 0, 0)
            b, c, d = (a + App.Vector(1000, 0, 0), a + App.Vector(1000, 1000, 0),
                       a + App.Vector(0, 1000, 0))
            mesh.addFacet(a, b, c)
            mesh.addFacet(a, c, d)
        feature = self.doc.addObject("Mesh::Feature", "Tris")
        feature.Mesh = mesh
        obj = facetwb.make_surface_mesh(feature, "tri-quad")
        bad = facetwb.make_surface_mesh(feature, "quad")
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual((obj.FaceCount, face_sizes(obj)), (3, [4]))
        self.assertFalse(bad.isValid())

    def test_bad_arguments(self):
        box = self.doc.addObject("Part::Box", "Box")
        with self.assertRaisesRegex(ValueError, "pattern must be one of"):
            facetwb.make_surface_mesh(box, "hexagons")
        with self.assertRaisesRegex(ValueError, "count_u is 0"):
            facetwb.make_surface_mesh(box, count_u=0)
        with self.assertRaisesRegex(ValueError, "panel_size is nan"):
            facetwb.make_surface_mesh(box, panel_size=float("nan"))

    def test_save_reopen_recompute(self):
        sphere = self.doc.addObject("Part::Sphere", "Sphere")
        obj = facetwb.make_surface_mesh(sphere, "quad", 8, 6)
        self.doc.recompute()
        name, points = obj.Name, points_array(obj)
        self.assertEqual(obj.VertexCount, 42)
        doc = self.save_and_reopen("surface.FCStd")
        obj = doc.getObject(name)
        self.assertTrue(facetwb.is_surface_mesh(obj))
        self.assertTrue(np.array_equal(points_array(obj), points))
        obj.CountU = 10
        doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.VertexCount, 10 * 5 + 2)


class TestPreferencesAndProgress(DocumentTestCase):
    def tearDown(self):
        preferences.reset()
        progress.cancel_after(0)

    def test_preferences_defaults_and_values(self):
        preferences.reset()
        self.assertEqual(preferences.get("PanelThickness"), 40.0)
        self.assertEqual(preferences.get("SheetRotations"), "90")
        preferences.set("PanelThickness", 25.0)
        self.assertEqual(preferences.get("PanelThickness"), 25.0)
        preferences.group().SetString("PanelOffset", "sideways")
        self.assertEqual(preferences.get("PanelOffset"), "outer")
        with self.assertRaisesRegex(ValueError, "PanelEdge must be one of"):
            preferences.set("PanelEdge", "round")

    def test_cancel_stops_the_planarizer(self):
        hypar = facetwb.make_polymesh(__import__("facet").read_mesh(
            __import__("facet_test_support").data_path("hypar.obj")), doc=self.doc)
        result = facetwb.make_planarized(hypar, tolerance=1e-12)
        progress.cancel_after(2)
        with progress.reporting("test") as reporter:
            self.doc.recompute()
        self.assertTrue(reporter.cancelled)
        self.assertEqual(reporter.calls, 2)
        self.assertFalse(result.isValid())
        self.assertIn("ancel", result.getStatusString())
        progress.cancel_after(0)
        self.assertIsNone(progress.hook())
        result.touch()
        self.doc.recompute()
        self.assertTrue(result.isValid(), result.getStatusString())

    def test_a_mesher_failing_in_its_worker_is_an_error_not_a_second_run(self):
        # a worker that found no FreeCAD falls back to meshing here; one whose mesher
        # failed or crashed made it all again here, minutes with no Cancel (and a crash
        # would take FreeCAD down): it is now an error that names the source
        import MeshPart
        import Part

        import facet.parallel
        from facetwb import tessellation
        from facetwb.conversion import SourceError

        shape = Part.makePlane(20000.0, 20000.0)
        length = 100.0
        self.assertGreater(tessellation.estimated_triangles(shape, length),
                           tessellation.WORKER_TRIANGLES)
        here = []
        keep_run, keep_mesh = facet.parallel.run_chunks, MeshPart.meshFromShape

        def mesh_here(**kwargs):
            here.append(kwargs)
            return keep_mesh(**kwargs)

        try:
            MeshPart.meshFromShape = mesh_here

            def crashed(*args, **kwargs):
                raise facet.parallel.WorkerError("worker process 0 stopped: EOFError()")

            facet.parallel.run_chunks = crashed
            with self.assertRaisesRegex(SourceError, "^Plane: FreeCAD's mesher failed"):
                tessellation.triangles_from_shape(shape, length, "Plane",
                                                  lambda done, total: False)
            self.assertEqual(here, [])  # not made here again
            facet.parallel.run_chunks = lambda *args, **kwargs: [None]  # no FreeCAD there
            mesh = tessellation.triangles_from_shape(shape, length, "Plane",
                                                     lambda done, total: False)
            self.assertEqual(len(here), 1)
            self.assertGreater(mesh.n_faces, tessellation.WORKER_TRIANGLES // 2)
        finally:
            facet.parallel.run_chunks, MeshPart.meshFromShape = keep_run, keep_mesh

    def test_triangulating_a_surface_shows_progress_and_can_be_cancelled(self):
        # tri-quad's triangulation (FreeCAD's mesher, one call) took over three minutes for
        # 130,000 triangles with no progress and no Cancel: a large one runs in a worker
        # process, the same triangles, a busy bar meanwhile, Cancel stops it
        import Part

        from facetwb.tessellation import WORKER_TRIANGLES, estimated_triangles

        poles = [[App.Vector(i * 3000.0, j * 3000.0, 250.0 * ((i - 2) ** 2 + (j - 2) ** 2))
                  for j in range(5)] for i in range(5)]
        surface = Part.BSplineSurface()
        surface.interpolate(poles)
        feature = self.doc.addObject("Part::Feature", "Canopy")
        feature.Shape = surface.toShape()
        obj = facetwb.make_surface_mesh(feature, "tri-quad", 100, 100)
        length = feature.Shape.BoundBox.DiagonalLength / 100
        self.assertGreater(estimated_triangles(feature.Shape, length), WORKER_TRIANGLES)
        self.doc.recompute()  # (no one listens: made here)
        self.assertTrue(obj.isValid(), obj.getStatusString())
        here = points_array(obj)
        self.assertGreater(obj.FaceCount, 2000)
        obj.touch()
        with progress.reporting("test") as reporter:  # in a worker: the same mesh
            self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        np.testing.assert_array_equal(points_array(obj), here)
        self.assertGreater(reporter.calls, 2)
        obj.CountU = obj.CountV = 110
        progress.cancel_after(1)
        with progress.reporting("test") as reporter:
            self.doc.recompute()
        self.assertTrue(reporter.cancelled)
        self.assertEqual((reporter.done, reporter.total), (0, 0))  # (a busy bar)
        self.assertFalse(obj.isValid())
        self.assertIn("triangulating Canopy cancelled", obj.getStatusString())
        np.testing.assert_array_equal(points_array(obj), here)  # the last mesh kept
