# SPDX-License-Identifier: LGPL-2.1-or-later
"""The OBJ/OFF importer: registration, open/insert, and clear errors for bad files."""

import os
import unittest

import numpy as np

import FreeCAD as App

from facetwb import importer
from facet_test_support import DocumentTestCase, data_path

BAD_FILES = {
    "bad_index.off": "bad_index.off",
    "bad_syntax.obj": "bad_syntax.obj",
    "missing.obj": "missing.obj",
    "README.md": "README.md",  # no mesh at all
}

WORKBENCH_INSTALLED = os.path.isdir(os.path.join(App.getUserAppDataDir(), "Mod", "Facet"))


class TestImporter(DocumentTestCase):
    @unittest.skipUnless(WORKBENCH_INSTALLED, "Init.py not run: use tests/fc_env.sh")
    def test_registered(self):
        for extension in ("obj", "off"):
            modules = App.getImportType(extension)
            modules = modules if isinstance(modules, (list, tuple)) else [modules]
            self.assertIn("facetwb.importer", modules, extension)
        # FreeCAD's Mesh importer stays the first one for .obj.
        first = App.getImportType("obj")
        first = first[0] if isinstance(first, (list, tuple)) else first
        self.assertEqual(first, "Mesh")

    def test_insert(self):
        obj = importer.insert(data_path("hypar.obj"), self.doc.Name)
        self.assertIsNotNone(obj)
        self.assertIs(obj.Document, self.doc)
        self.assertEqual(obj.FaceCount, 64)

    def test_open_new_document(self):
        before = set(App.listDocuments())
        doc = importer.open(data_path("panels.off"))
        try:
            self.assertNotIn(doc.Name, before)
            self.assertEqual(len(doc.Objects), 1)
            self.assertEqual(doc.Objects[0].FaceCount, 7)
        finally:
            App.closeDocument(doc.Name)

    def test_bad_files_change_nothing(self):
        importer.SHOW_DIALOGS = False
        for name in BAD_FILES:
            with self.subTest(file=name):
                path = data_path(name)
                objects = [obj.Name for obj in self.doc.Objects]
                documents = set(App.listDocuments())
                self.assertIsNone(importer.insert(path, self.doc.Name))
                self.assertIsNone(importer.open(path))
                self.assertEqual([obj.Name for obj in self.doc.Objects], objects)
                self.assertEqual(set(App.listDocuments()), documents)
                self.assertFalse(self.doc.isTouched() and not objects)

    def test_error_messages(self):
        for name, expected in BAD_FILES.items():
            with self.subTest(file=name):
                with self.assertRaises(importer.MeshImportError) as caught:
                    importer.read_polymesh(data_path(name))
                message = str(caught.exception)
                self.assertIn(expected, message)
                self.assertNotIn("\n", message)
                self.assertNotIn("Traceback", message)
                self.assertTrue(message.startswith("Cannot import "), message)

    def test_error_names_line_or_face(self):
        with self.assertRaises(importer.MeshImportError) as caught:
            importer.read_polymesh(data_path("bad_syntax.obj"))
        self.assertIn("line 3", str(caught.exception))
        with self.assertRaises(importer.MeshImportError) as caught:
            importer.read_polymesh(data_path("bad_index.off"))
        self.assertIn("face 1", str(caught.exception))

    def test_an_import_says_what_it_made(self):
        """A successful import said nothing in the report view: now one line gives the
        faces by kind, the vertices, the size in millimetres and the units read in."""
        said = []
        keep, importer.report_message = importer.report_message, said.append
        try:
            obj = importer.insert(data_path("panels.off"), self.doc.Name, "m")
        finally:
            importer.report_message = keep
        self.assertIsNotNone(obj)
        self.assertEqual(len(said), 1, said)
        from facetwb.objects.polymesh import get_mesh

        mesh = get_mesh(obj)
        lower, upper = mesh.bounds()
        self.assertIn(f"{mesh.n_faces:,} faces (", said[0])
        self.assertIn(f"{mesh.n_vertices:,} vertices", said[0])
        self.assertIn(" x ".join(f"{v:,.0f}" for v in upper - lower) + " mm", said[0])
        self.assertIn("read as metres", said[0])
        self.assertTrue(said[0].endswith(f"as {obj.Label}"), said[0])
        kinds = {k: int((mesh.degrees == k).sum()) for k in (3, 4)}
        for k, name in ((3, "triangle"), (4, "quad")):
            if kinds[k]:
                self.assertIn(f"{kinds[k]:,} {name}", said[0])

    def test_an_import_says_a_small_size_as_it_is(self):
        """The summary's size in whole millimetres said "1 x 0 x 0 mm" of a 0.6 x 0.45 mesh
        (a panel in metres read as millimetres): a size it does not have. Below 100 mm it
        has three significant digits."""
        import facet

        mesh = facet.PolyMesh.from_faces(
            [(0, 0, 0), (0.6, 0, 0), (0.6, 0.45, 0.0125), (0, 0.45, 0)], [[0, 1, 2, 3]])
        self.assertIn("0.6 x 0.45 x 0.0125 mm", importer.imported_summary(mesh, "mm"))
        mesh = facet.PolyMesh.from_faces(
            [(0, 0, 0), (12000, 0, 0), (12000, 99.96, 0), (0, 99.96, 0)], [[0, 1, 2, 3]])
        self.assertIn("12,000 x 100 x 0 mm", importer.imported_summary(mesh, "mm"))

    def test_an_import_of_one_face_says_one_face(self):
        """The summary said "1 faces" of a one-face mesh."""
        import facet

        mesh = facet.PolyMesh.from_faces([(0, 0, 0), (600, 0, 0), (0, 450, 0)], [[0, 1, 2]])
        self.assertTrue(importer.imported_summary(mesh, "mm").startswith(
            "1 face (1 triangle), 3 vertices, 600 x 450 x 0 mm"),
            importer.imported_summary(mesh, "mm"))

    def test_an_import_names_every_kind_of_face(self):
        """The summary counted pentagons and 7-gons as "other polygons", where `facet
        check` names each kind."""
        import facet

        ring = [(np.cos(a), np.sin(a), 0.0) for a in np.linspace(0, 2 * np.pi, 8)[:-1]]
        xyz = [(1000 * x, 1000 * y, z) for x, y, z in ring] + [(3000, 0, 0), (3500, 500, 0)]
        mesh = facet.PolyMesh.from_faces(xyz, [list(range(7)), [0, 7, 8, 1, 6]])
        self.assertIn("2 faces (1 pentagon, 1 7-gon), 9 vertices",
                      importer.imported_summary(mesh, "mm"))

    def imported_saying(self, *texts, units="m"):
        """Import each OBJ text with importer.insert, its numbers in ``units`` (metres: the
        texts' panels are 1 unit across, which no facade's are in millimetres); (the report
        view's warnings, [(path, object)])."""
        import tempfile

        said, imported = [], []
        keep, importer.report_warning = importer.report_warning, said.append
        try:
            with tempfile.TemporaryDirectory() as folder:
                for k, text in enumerate(texts):
                    path = os.path.join(folder, f"mesh{k}.obj")
                    with open(path, "w", encoding="utf-8") as stream:
                        stream.write(text)
                    imported.append((path, importer.insert(path, self.doc.Name, units)))
        finally:
            importer.report_warning = keep
        return said, imported

    def test_triangle_written_as_quad_is_read_and_said(self):
        """A face with a vertex at two corners in a row (Rhino's triangle in a quad) is
        imported with it once, and the report view says so with the file and the line."""
        said, [(path, obj)] = self.imported_saying(
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nf 1 2 3 4\nf 2 5 3 3\n")
        self.assertIsNotNone(obj)
        self.assertEqual(obj.FaceCount, 2)
        self.assertEqual(len(said), 1, said)
        self.assertTrue(said[0].startswith(f"Facet: {path}: 1 face gave a vertex at two "
                                           "corners in a row (first: face 1, line 7)"), said)

    def test_unwelded_seam_is_said_with_what_welds_it(self):
        """An OBJ whose panels each have their own vertices imports as it is, and the report
        view says at once that its faces are not joined and what in FreeCAD joins them;
        Planarize and Panels only said it later, and named no FreeCAD command."""
        said, [(path, obj), _] = self.imported_saying(
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\n"
            "f 1 2 3 4\nf 5 6 7 8\n",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\nf 1 2 3 4\nf 2 5 6 3\n")
        self.assertIsNotNone(obj)
        self.assertEqual(obj.VertexCount, 8)  # imported as it is: the source is not changed
        self.assertEqual(said, [
            f"Facet: {path}: vertices at one point but not one vertex: 2 pairs (vertices 1 "
            "and 4 at (1, 0, 0)); the faces there are not joined: weld them where the panels "
            "should meet: facet weld, or in FreeCAD Collapse short edges, which welds first"])

    def test_units_scale_to_millimetres(self):
        """A file in metres (a facade 1 m across, its numbers 0 and 1) read as FreeCAD's
        millimetres came in a thousand times too small, silently: panels of 40 mm on a 1 mm
        facade and cut sheets of specks. Read with its units it is scaled to millimetres;
        read as millimetres the report view says how long its edges are and what to do."""
        square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"
        said, [(path, obj)] = self.imported_saying(square, units="m")
        self.assertEqual(said, [])
        self.assertEqual([tuple(p) for p in obj.Points],
                         [(0, 0, 0), (1000, 0, 0), (1000, 1000, 0), (0, 1000, 0)])
        said, [(path, obj)] = self.imported_saying(square, units="mm")
        self.assertEqual(max(p.x for p in obj.Points), 1.0)  # as it is
        self.assertEqual(said, [
            f"Facet: {path}: its edges are 1 mm long on average, its numbers read as "
            "millimetres: if the file is in other units, import it again with Facet > Import "
            "polygon mesh, which asks for them, or its panels and cut sheets come out at the "
            "wrong size"])
        with self.assertRaises(importer.MeshImportError) as caught:
            importer.read_polymesh(data_path("hypar.obj"), "yards")
        self.assertIn("units 'yards': use one of mm, cm, m, in, ft", str(caught.exception))

    def test_likely_units(self):
        """The units offered first: those that make the mean edge closest to 1.5 m."""
        import facet

        square = facet.PolyMesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [0, 4],
                                [0, 1, 2, 3])
        for size, units in ((0.6, "m"), (1.5, "m"), (1500.0, "mm"), (60.0, "mm"),
                            (1e-6, "mm")):
            with self.subTest(size=size):
                mesh = square.with_vertices(square.vertices * size)
                self.assertEqual(importer.likely_units(mesh), units)

    def imported_by_the_command(self, path, units_answer="m"):
        """Import ``path`` as Facet_ImportMesh does, its dialogs answered (units:
        ``units_answer``): file_units, then importer.insert with them; (the object, how
        many times facet.read_mesh read the file)."""
        import facet
        from facetwb.commands import import_mesh

        reads = []
        read_mesh = facet.read_mesh

        def counted(filename, **options):
            reads.append(filename)
            return read_mesh(filename, **options)

        keep = importer.SHOW_DIALOGS, import_mesh.ask_units
        facet.read_mesh, importer.SHOW_DIALOGS = counted, True
        import_mesh.ask_units = lambda *args: units_answer
        try:
            units = import_mesh.file_units(path)
            obj = importer.insert(path, self.doc.Name, units)
        finally:
            facet.read_mesh = read_mesh
            importer.SHOW_DIALOGS, import_mesh.ask_units = keep
            importer.forget_kept()
        return obj, len(reads)

    def test_an_imperial_designer_is_asked_the_units_of_a_mesh_in_inches(self):
        """FreeCAD set to inches (Imperial decimal): Facet_ImportMesh of a 40 ft facade in
        inches (40 x 30 in panels, a facade's size in millimetres too) read it as
        millimetres, 25.4 times too small, and asked nothing; its summary gave the size in
        mm. Now it asks, inches offered first, and says the size in inches. In the
        Standard schema nothing changes: not asked, mm."""
        import facet
        from facetwb.commands import import_mesh

        path = os.path.join(self.tmp.name, "facade_in.obj")
        grid = [(40.0 * i, 30.0 * j, 0.0) for j in range(9) for i in range(13)]
        faces = [[13 * j + i, 13 * j + i + 1, 13 * j + i + 14, 13 * j + i + 13]
                 for j in range(8) for i in range(12)]
        facet.write_mesh(facet.PolyMesh.from_faces(grid, faces), path)
        asked = []

        def ask(filename, edge, likely, imperial=False):
            asked.append((round(edge, 1), likely, imperial))
            return likely

        schema = App.Units.getSchema()
        keep = importer.SHOW_DIALOGS, import_mesh.ask_units, importer.report_message
        said = []
        importer.SHOW_DIALOGS, import_mesh.ask_units = True, ask
        importer.report_message = said.append
        try:
            App.Units.setSchema(0)  # Standard (mm)
            self.assertEqual(import_mesh.file_units(path), "mm")
            self.assertEqual(asked, [])
            importer.forget_kept()
            for imperial_schema in (3, 5):  # Imperial decimal, Building US
                App.Units.setSchema(imperial_schema)
                del asked[:]
                self.assertEqual(import_mesh.file_units(path), "in")
                self.assertEqual(asked, [(35.1, "in", True)])
                obj = importer.insert(path, self.doc.Name, "in")
                importer.forget_kept()
                self.assertAlmostEqual(max(p.x for p in obj.Points), 480.0 * 25.4, places=6)
                self.assertIn("480 x 240 x 0 in, its numbers read as inches", said[-1])
        finally:
            App.Units.setSchema(schema)
            importer.SHOW_DIALOGS, import_mesh.ask_units, importer.report_message = keep
            importer.forget_kept()
        # the Standard schema's summary is in mm, as it was
        self.assertIn("12,192 x 6,096 x 0 mm, its numbers read as inches",
                      importer.imported_summary(facet.read_mesh(path).with_vertices(
                          facet.read_mesh(path).vertices * 25.4), "in"))

    def test_the_import_command_reads_the_file_once(self):
        """Facet_ImportMesh read the file to ask for its units, then its macro line
        importer.insert read the whole file again (a 100k-face OBJ: 0.4 s more). Now
        insert takes the mesh that was read; a file changed in between is read again."""
        import shutil

        path = os.path.join(self.tmp.name, "square.obj")
        with open(path, "w", encoding="utf-8") as stream:
            stream.write("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n")
        obj, reads = self.imported_by_the_command(path)
        self.assertEqual(reads, 1)
        self.assertEqual(max(p.x for p in obj.Points), 1000.0)  # read in metres

        obj, reads = self.imported_by_the_command(data_path("panels.off"))
        self.assertEqual((reads, obj.FaceCount), (1, 7))

        importer.SHOW_DIALOGS = False  # no message box for the bad file
        try:
            bad = os.path.join(self.tmp.name, "bad_index.off")
            shutil.copy(data_path("bad_index.off"), bad)
            objects = len(self.doc.Objects)
            obj, reads = self.imported_by_the_command(bad)
            self.assertEqual((obj, reads, len(self.doc.Objects)), (None, 1, objects))
        finally:
            importer.SHOW_DIALOGS = True

        importer.read_kept(path)
        with open(path, "a", encoding="utf-8") as stream:  # changed after it was read
            stream.write("v 2 0 0\nv 2 1 0\nf 2 5 6 3\n")
        try:
            self.assertEqual(importer.read_polymesh(path, "m").n_faces, 2)
        finally:
            importer.forget_kept()


class TestImportCancel(DocumentTestCase):
    """An import's progress and Cancel (facetwb.progress): a 1M-face OBJ read for seconds
    with no dialog and no way to stop it. Cancel at any of its progress calls leaves every
    document as it was and says so in one line."""

    def setUp(self):
        self.said = []
        self.keep = importer.report_message, importer.report_error
        importer.report_message = self.said.append
        importer.report_error = self.said.append

    def tearDown(self):
        importer.report_message, importer.report_error = self.keep
        from facetwb import progress

        progress.cancel_after(0)
        importer.forget_kept()

    def state(self):
        return ([(obj.Name, obj.Label) for obj in self.doc.Objects], sorted(App.listDocuments()),
                self.doc.isTouched(), list(self.doc.UndoNames))

    def imported(self, function, *arguments, cancel_at=0):
        """``function(*arguments)`` in a reporter that cancels at its ``cancel_at``-th call
        (0: never); (its result, the reporter)."""
        from facetwb import progress

        progress.cancel_after(cancel_at)
        try:
            with progress.reporting("test") as reporter:
                result = function(*arguments)
        finally:
            progress.cancel_after(0)
        return result, reporter

    def test_cancel_at_every_step_changes_nothing(self):
        from facetwb import progress

        self.doc.addObject("App::FeaturePython", "Existing")
        self.doc.recompute()
        for name in ("hypar.obj", "panels.off"):
            path = data_path(name)
            obj, reporter = self.imported(importer.insert, path, self.doc.Name)
            calls = reporter.calls
            self.assertIsNotNone(obj)
            self.assertGreaterEqual(calls, 5, "the reading, the checks, the adding and "
                                              "the recompute report progress")
            self.assertEqual(reporter.texts[0], "test")
            self.doc.removeObject(obj.Name)
            self.doc.recompute()
            for cancel_at in range(1, calls + 1):
                for function, target in ((importer.insert, self.doc.Name),
                                         (importer.insert, "NotYetThere"),
                                         (importer.open, None)):
                    with self.subTest(file=name, call=cancel_at, function=function.__name__,
                                      document=target):
                        del self.said[:]
                        before = self.state()
                        arguments = (path,) if target is None else (path, target)
                        result, reporter = self.imported(function, *arguments,
                                                         cancel_at=cancel_at)
                        self.assertIsNone(result)
                        self.assertTrue(reporter.cancelled)
                        self.assertEqual(self.state(), before)
                        self.assertEqual(self.said,
                                         [f"Facet: {path}: import cancelled; nothing changed"])
        self.assertIsNone(progress.hook())

    def test_a_scripted_import_has_no_reporter_and_is_not_cancelled(self):
        from facetwb import progress

        progress.cancel_after(1)  # (a reporter would cancel; none is opened headless)
        obj = importer.insert(data_path("panels.off"), self.doc.Name)
        self.assertIsNotNone(obj)
        self.assertEqual(obj.FaceCount, 7)
        self.assertTrue(obj.isValid())

    def test_the_command_reading_cancelled_keeps_nothing(self):
        """Facet_ImportMesh reads the file (to ask for its units) in a progress dialog of its
        own: Cancel there imports nothing and keeps no mesh for a later import."""
        from facetwb import progress
        from facetwb.commands import import_mesh

        path = os.path.join(self.tmp.name, "panel.obj")  # a 1.5 m panel in millimetres
        with open(path, "w", encoding="utf-8") as stream:
            stream.write("v 0 0 0\nv 1500 0 0\nv 1500 1500 0\nv 0 1500 0\nf 1 2 3 4\n")
        progress.cancel_after(1)
        try:
            units = import_mesh.file_units(path)
        finally:
            progress.cancel_after(0)
        self.assertIsNone(units)
        self.assertEqual(importer._KEPT, {})
        self.assertEqual(self.said, [f"Facet: {path}: import cancelled; nothing changed"])
        self.assertEqual(import_mesh.file_units(path), "mm")  # read whole this time
        self.assertIn(path, importer._KEPT)
