# SPDX-License-Identifier: LGPL-2.1-or-later
"""PanelSet and CutSheets: valid OCC solids, volumes, gaps, DXF and STEP read back."""

import contextlib
import os
import re
import sys

import numpy as np

import FreeCAD as App
import Part

import facet
import facetwb
from facet.panels import panels
from facet_test_support import DocumentTestCase, bits, data_path, points_array

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                "python"))
from panel_meshes import cylinder, folded_grid, translational  # noqa: E402

T = 30.0
GAP = 6.0


@contextlib.contextmanager
def counting_builds():
    """A list that records each call of facet's panels() ("panels") and panel_solids()
    ("solids") while the block runs."""
    import facet.step  # noqa: F401

    # facet.panels is also the name of a function in facet: the modules by name
    fpanels, fstep = sys.modules["facet.panels"], sys.modules["facet.step"]
    calls = []
    saved = fpanels.panels, fstep.panel_solids

    def counting(name, f):
        def wrapped(*a, **k):
            calls.append(name)
            return f(*a, **k)
        return wrapped

    fpanels.panels = counting("panels", saved[0])
    fstep.panel_solids = counting("solids", saved[1])
    try:
        yield calls
    finally:
        fpanels.panels, fstep.panel_solids = saved


@contextlib.contextmanager
def counting_nests():
    """A list that gets an item at each call of facet.nest.nest while the block runs."""
    fnest = sys.modules["facet.nest"]
    nests = []
    saved = fnest.nest

    def counting(*a, **k):
        nests.append(1)
        return saved(*a, **k)

    fnest.nest = counting
    try:
        yield nests
    finally:
        fnest.nest = saved


def written(out):
    """{path relative to ``out``: (inode, mtime)} of each file there: a file written again
    is a new one."""
    found = {}
    for root, _dirs, names in os.walk(out):
        for name in names:
            st = os.stat(os.path.join(root, name))
            found[os.path.relpath(os.path.join(root, name), out)] = (st.st_ino, st.st_mtime_ns)
    return found


def changed_since(out, before):
    """The files in ``out`` written (or made) since ``before`` (:func:`written`)."""
    now = written(out)
    return sorted(k for k in now if now[k] != before.get(k))


class TestPanelSet(DocumentTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.mesh = translational(nu=5, nv=4, step=1000.0)
        cls.source = facetwb.make_polymesh(cls.mesh, label="translational")
        cls.square = facetwb.make_panelset(cls.source, thickness=T)
        cls.mitred = facetwb.make_panelset(cls.source, thickness=T, edge="bisector", gap=GAP,
                                           name="Mitred")
        cls.doc.recompute()

    def test_square_solids_valid_with_volume_area_times_thickness(self):
        obj = self.square
        self.assertTrue(obj.isValid(), obj.getStatusString())
        solids = obj.Shape.Solids
        self.assertEqual(len(solids), 20)
        self.assertEqual(obj.PanelCount, 20)
        self.assertEqual(obj.PartIds[0], "P-R01C01")
        self.assertEqual(len(set(obj.PartIds)), 20)
        for solid, area, volume in zip(solids, obj.Areas, obj.Volumes):
            self.assertTrue(solid.isValid())
            solid.check(True)  # BRepCheck: raises on any fault
            self.assertAlmostEqual(solid.Volume / (area * T), 1.0, places=9)
            self.assertAlmostEqual(volume, solid.Volume, places=6)
            self.assertEqual(len(solid.Faces), 6)

    def test_mitred_neighbours_do_not_overlap_and_keep_the_gap(self):
        obj = self.mitred
        self.assertTrue(obj.isValid(), obj.getStatusString())
        ps = panels(self.mesh, T, edge="bisector", gap=GAP)
        solids = obj.Shape.Solids
        checked = 0
        for p in ps:
            for h in p.neighbors:
                if h is None or h < p.face:
                    continue
                a, b = solids[p.face], solids[h]
                a.check(True)
                common = a.common(b)
                self.assertLess(abs(common.Volume), 1e-6 * a.Volume)
                self.assertAlmostEqual(a.distToShape(b)[0], GAP, places=6)
                checked += 1
        self.assertEqual(checked, 4 * 4 + 5 * 3)

    def test_source_unchanged(self):
        np.testing.assert_array_equal(bits(points_array(self.source)), bits(self.mesh.vertices))

    def test_an_edge_the_gap_consumes_is_dropped_and_reported(self):
        # a sharp quad whose tip is cut off by an edge 200 long (mm): a 400 joint
        # consumes it, so that panel is cut as a triangle and the object says so
        xy = [(0, 0), (10, 0), (5.1, 20), (4.9, 20), (12, 24), (-2, 24)]
        mesh = facet.PolyMesh.from_faces([(1000.0 * x, 1000.0 * y, 0.0) for x, y in xy],
                                         [[0, 1, 2, 3], [3, 2, 4, 5]])
        source = facetwb.make_polymesh(mesh, label="cut tip")
        obj = facetwb.make_panelset(source, thickness=50.0, gap=400.0, name="CutTip")
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(sorted(len(s.Faces) for s in obj.Shape.Solids), [5, 6])
        for solid in obj.Shape.Solids:
            solid.check(True)
        self.assertTrue(any(w.startswith("1 short edges that the joint gap or a bevel consumes "
                                         "dropped from the outlines of 1 panel")
                            for w in obj.Warnings), obj.Warnings)
        np.testing.assert_array_equal(bits(points_array(source)), bits(mesh.vertices))
        self.doc.removeObject(obj.Name)
        self.doc.removeObject(source.Name)

    def test_a_mitre_that_cannot_be_cut_becomes_a_butt_joint(self):
        # sys.path has tests/python: the folded cut-tip mesh of the Python tests, in mm
        from test_panels import _folded_tip_mesh

        mesh = _folded_tip_mesh()
        mesh = facet.PolyMesh(mesh.vertices * 1000.0, mesh.face_start, mesh.face_vertices)
        source = facetwb.make_polymesh(mesh, label="folded tip")
        obj = facetwb.make_panelset(source, thickness=200.0, gap=200.0, edge="bisector",
                                    name="FoldedTip")
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        solids = obj.Shape.Solids
        self.assertEqual(len(solids), 3)
        for solid in solids:
            solid.check(True)
        for other in solids[1:]:  # the butt joints keep their gap: no overlap
            self.assertLess(abs(solids[0].common(other).Volume), 1e-6 * solids[0].Volume)
            self.assertAlmostEqual(solids[0].distToShape(other)[0], 200.0, places=6)
        self.assertTrue(any("mitred joints cut as butt joints" in w for w in obj.Warnings),
                        obj.Warnings)
        self.doc.removeObject(obj.Name)
        self.doc.removeObject(source.Name)

    def test_bad_thickness_marks_the_object_invalid(self):
        obj = facetwb.make_panelset(self.source, thickness=T, name="Bad")
        obj.Thickness = 0.0
        self.doc.recompute()
        self.assertFalse(obj.isValid())
        self.doc.removeObject(obj.Name)

    def test_density_gives_each_panel_its_mass_in_the_object_and_the_schedule(self):
        """A PanelSet's Density (kg/m³) gives Masses and TotalMass, and the cut sheets'
        schedule a mass_kg column (the schedule had no volume or mass). A Density that is
        not a number > 0 leaves the object in error with its last shape."""
        import csv

        obj = facetwb.make_panelset(self.source, thickness=T, edge="bisector", gap=GAP,
                                    name="Heavy")
        self.doc.recompute()
        self.assertEqual((list(obj.Masses), obj.TotalMass), ([], 0.0))
        obj.Density = 2500.0
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        expected = [v * 1e-9 * 2500.0 for v in obj.Volumes]
        np.testing.assert_allclose(list(obj.Masses), expected, rtol=1e-12)
        self.assertAlmostEqual(obj.TotalMass / sum(expected), 1.0, places=12)
        out = os.path.join(self.tmp.name, "heavy")
        sheets = facetwb.make_cutsheets(obj, sheet=(2600.0, 1400.0), output_dir=out,
                                        write_step=False, name="HeavySheets")
        self.doc.recompute()
        self.assertTrue(sheets.isValid(), sheets.getStatusString())
        with open(os.path.join(out, "schedule.csv"), encoding="utf-8") as handle:
            rows = list(csv.DictReader(handle))
        self.assertEqual([r["id"] for r in rows], list(obj.PartIds))
        # (the schedule's volumes are facet's, the object's OCC's: the same solids)
        np.testing.assert_allclose([float(r["mass_kg"]) for r in rows], expected, rtol=1e-9)
        np.testing.assert_allclose([float(r["volume_mm3"]) for r in rows], list(obj.Volumes),
                                   rtol=1e-9)
        before = (len(obj.Shape.Solids), obj.Shape.Volume, list(obj.Masses))
        for bad in (-1.0, float("nan")):
            obj.Density = bad
            self.doc.recompute()
            self.assertFalse(obj.isValid())
            self.assertIn(f"{obj.Label}: density (kg/m³) must be a finite number > 0",
                          obj.getStatusString())
            self.assertEqual((len(obj.Shape.Solids), obj.Shape.Volume, list(obj.Masses)),
                             before)
        obj.Density = 0.0
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(list(obj.Masses), [])
        self.doc.removeObject(sheets.Name)
        self.doc.removeObject(obj.Name)

    def test_density_and_part_ids_change_no_solid(self):
        """A Density change only changes masses, but every solid was built again (280
        panels: 0.28 s a recompute, 0.001 s now); OnePerPanel and the part IDs (IdPrefix,
        IdScheme) change no solid either. The Shape is kept; Thickness, Gap and the
        Source's mesh build them again."""
        from facet.panels import mass_kg

        obj = facetwb.make_panelset(self.source, thickness=T, name="Light")
        self.addCleanup(self.doc.removeObject, obj.Name)
        self.doc.recompute()
        shape = obj.Shape
        with counting_builds() as calls:
            obj.Density = 2700.0
            self.doc.recompute()
            self.assertTrue(obj.isValid(), obj.getStatusString())
            self.assertEqual(calls, [])
            self.assertTrue(obj.Shape.isSame(shape))
            expected = [float(m) for m in mass_kg(obj.Volumes, 2700.0)]
            np.testing.assert_allclose(list(obj.Masses), expected, rtol=1e-12)
            self.assertAlmostEqual(obj.TotalMass / sum(expected), 1.0, places=12)
            # hidden and shown in the tree, renamed: no input changed (they made the next
            # Density change build every solid again)
            obj.Visibility = False
            obj.Visibility = True
            obj.Label = "Light panels"
            obj.Density = 2600.0
            self.doc.recompute()
            self.assertEqual(calls, [])
            self.assertTrue(obj.Shape.isSame(shape))
            obj.Density = 2700.0
            self.doc.recompute()
            obj.OnePerPanel = True
            self.doc.recompute()
            self.assertEqual(calls, [])
            self.assertEqual(len(obj.PanelObjects), 20)
            for child, solid in zip(obj.PanelObjects, obj.Shape.Solids):
                self.assertAlmostEqual(child.Shape.Volume / solid.Volume, 1.0, places=12)
                self.assertTrue(child.Shape.BoundBox.isInside(solid.BoundBox.Center))
            # a recompute marked by hand builds them again
            obj.touch()
            self.doc.recompute()
            self.assertEqual(calls, ["panels", "solids"])
            del calls[:]
            shape = obj.Shape
            obj.OnePerPanel = False
            obj.IdPrefix = "G-"
            self.doc.recompute()
            self.assertEqual(calls, ["panels"])  # the IDs, not the solids
            self.assertTrue(obj.Shape.isSame(shape))
            self.assertEqual(obj.PartIds[0], "G-R01C01")
            self.assertEqual(len(obj.PanelObjects), 0)
            del calls[:]
            obj.Thickness = 2 * T
            obj.Density = 2500.0
            self.doc.recompute()
            self.assertEqual(calls, ["panels", "solids"])
            self.assertFalse(obj.Shape.isSame(shape))
            np.testing.assert_allclose(list(obj.Masses),
                                       [float(m) for m in mass_kg(obj.Volumes, 2500.0)],
                                       rtol=1e-12)
            # the Source's mesh moved: the same properties, new solids
            del calls[:]
            shape = obj.Shape
            moved = facetwb.make_polymesh(self.mesh, label="moved", doc=self.doc)
            self.addCleanup(self.doc.removeObject, moved.Name)
            obj.Source = moved
            self.doc.recompute()
            self.assertEqual(calls, ["panels", "solids"])
            del calls[:]
            from facetwb.objects.polymesh import set_mesh

            set_mesh(moved, self.mesh.with_vertices(self.mesh.vertices + [0.0, 0.0, 100.0]))
            self.doc.recompute()
            self.assertEqual(calls, ["panels", "solids"])
            self.assertAlmostEqual(obj.Shape.BoundBox.ZMin - shape.BoundBox.ZMin, 100.0,
                                   places=6)

    def test_cutsheets_dxf_and_step_read_back(self):
        out = os.path.join(self.tmp.name, "cut")
        sheets = facetwb.make_cutsheets(self.mitred, sheet=(2600.0, 1400.0), margin=10.0,
                                        spacing=6.0, output_dir=out)
        self.doc.recompute()
        self.assertTrue(sheets.isValid(), sheets.getStatusString())
        self.assertGreater(sheets.SheetCount, 0)
        self.assertEqual(list(sheets.Unplaced), [])
        self.assertTrue(0 < sheets.Utilisation < 1)
        for name in ("sheets.dxf", "panels.step", "schedule.csv", "schedule.json"):
            self.assertTrue(os.path.exists(os.path.join(out, name)), name)

        # DXF: ezdxf audit, then FreeCAD's own importer gives the same CUT outlines
        import ezdxf
        import Import

        path = os.path.join(out, "sheets.dxf")
        dxf = ezdxf.readfile(path)
        self.assertFalse(dxf.audit().has_errors)
        cuts = [np.array([(x, y) for x, y, *_ in e.get_points()])
                for e in dxf.modelspace().query("LWPOLYLINE[layer=='CUT']")]
        self.assertEqual(len(cuts), 20)
        doc = App.newDocument("DxfBack")
        Import.readDXF(path, doc.Name, True)
        # the importer makes one edge per polyline segment: every CUT segment must be there
        def key(a, b):
            pa = tuple(np.round(a, 6))
            pb = tuple(np.round(b, 6))
            return (pa, pb) if pa <= pb else (pb, pa)

        segments = set()
        for o in doc.Objects:
            shape = getattr(o, "Shape", None)
            if shape is None or shape.isNull():
                continue
            for e in shape.Edges:
                a, b = e.Vertexes[0].Point, e.Vertexes[-1].Point
                segments.add(key((a.x, a.y), (b.x, b.y)))
        for cut in cuts:
            for i in range(len(cut)):
                self.assertIn(key(cut[i], cut[(i + 1) % len(cut)]), segments)
        App.closeDocument(doc.Name)

        # STEP: the same solids (volumes, in order) and each product named by its part ID
        step = os.path.join(out, "panels.step")
        shape = Part.read(step)
        solids = shape.Solids
        self.assertEqual(len(solids), 20)
        for s, v in zip(solids, self.mitred.Volumes):
            self.assertTrue(s.isValid())
            self.assertAlmostEqual(s.Volume / v, 1.0, places=9)
        text = open(step, encoding="latin-1").read()
        names = re.findall(r"PRODUCT\('([^']*)'", text)
        self.assertEqual([n for n in names if n.startswith("P-")], list(self.mitred.PartIds))
        # FreeCAD's STEP importer (headless: not its default link group, which
        # crashes FreeCAD 0.20 without a GUI) gives one object per panel, by ID
        back = App.newDocument("StepBack")
        try:
            Import.insert(step, back.Name, useLinkGroup=False)
            got = {o.Label: o.Shape for o in back.Objects
                   if o.TypeId == "Part::Feature" and o.Label.startswith("P-")}
            self.assertEqual(sorted(got), sorted(self.mitred.PartIds))
            for pid, v in zip(self.mitred.PartIds, self.mitred.Volumes):
                self.assertTrue(got[pid].isValid())
                self.assertAlmostEqual(got[pid].Volume / v, 1.0, places=9)
        finally:
            App.closeDocument(back.Name)
        self.assertEqual(text.count("PCURVE"), 0)  # planar faces: written without

    def test_one_object_per_panel(self):
        obj = facetwb.make_panelset(self.source, thickness=T, one_per_panel=True, name="Each")
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        children = list(obj.PanelObjects)
        self.assertEqual([c.Label for c in children], list(obj.PartIds))
        for c, v in zip(children, obj.Volumes):
            self.assertTrue(c.Shape.isValid())
            self.assertAlmostEqual(c.Shape.Volume / v, 1.0, places=12)
        self.assertFalse(any("Touched" in c.State for c in children))
        # a recompute reuses the objects; switching off removes them
        names = [c.Name for c in children]
        obj.Thickness = 2 * T
        self.doc.recompute()
        self.assertEqual([c.Name for c in obj.PanelObjects], names)
        self.assertAlmostEqual(obj.PanelObjects[0].Shape.Volume / obj.Volumes[0], 1.0, places=12)
        obj.OnePerPanel = False
        self.doc.recompute()
        self.assertEqual(list(obj.PanelObjects), [])
        self.assertTrue(all(self.doc.getObject(n) is None for n in names))
        # on again: the objects come back under their names and stay. FreeCAD 0.20 removed
        # every object made later under a name removed during a recompute, at the end of
        # each recompute after: the PanelSet had no panel objects, valid and silent
        obj.OnePerPanel = True
        self.doc.recompute()
        self.assertEqual([c.Name for c in obj.PanelObjects], names)
        obj.touch()
        self.doc.recompute()
        self.assertEqual([c.Name for c in obj.PanelObjects], names)
        self.assertTrue(all(self.doc.getObject(n) is not None for n in names))
        # a copy (without its dependencies) links the original's panel objects: it makes
        # its own and leaves the original's alone (it rewrote and deleted them)
        volume = obj.PanelObjects[0].Shape.Volume
        copy = self.doc.copyObject(obj, False)
        copy.Thickness = 3 * T
        self.doc.recompute()
        self.assertTrue(copy.isValid(), copy.getStatusString())
        own = [c.Name for c in copy.PanelObjects]
        self.assertEqual(len(own), len(names))
        self.assertFalse(set(own) & set(names))
        self.assertAlmostEqual(copy.PanelObjects[0].Shape.Volume / volume, 1.5, places=9)
        self.assertEqual(obj.PanelObjects[0].Shape.Volume, volume)
        copy.OnePerPanel = False
        self.doc.recompute()
        self.assertTrue(all(self.doc.getObject(n) is None for n in own))
        self.assertEqual([c.Name for c in obj.PanelObjects], names)
        self.assertTrue(all(self.doc.getObject(n) is not None for n in names))
        self.doc.removeObject(copy.Name)
        # a copy with its dependencies: the copied panel objects are its own (they were
        # left in the document, linked by nothing, and it made another set)
        made = self.doc.copyObject(obj, True)
        twin = [o for o in (made if isinstance(made, list) else [made])
                if facetwb.is_panelset(o)][-1]
        copied = [c.Name for c in twin.PanelObjects]
        self.assertFalse(set(copied) & set(names))
        twin.touch()
        self.doc.recompute()
        self.assertEqual([c.Name for c in twin.PanelObjects], copied)
        panels_in_doc = [o.Name for o in self.doc.Objects if o.TypeId == "Part::Feature"
                         and "_Panel" in o.Name]
        self.assertEqual(sorted(panels_in_doc), sorted(names + copied))
        self.doc.removeObject(twin.Name)
        for name in copied:
            self.doc.removeObject(name)
        self.doc.removeObject(obj.Name)
        for name in names:
            self.doc.removeObject(name)

    def small_cutsheets(self, label, panels_name, sheets_name, folder):
        """Panels 20 mm wide, 2 mm thick (a mesh labelled ``label``) and their CutSheets on
        200 x 100 mm sheets, writing into ``folder`` (no STEP): (PanelSet, CutSheets)."""
        small = facetwb.make_polymesh(translational(nu=3, nv=2, step=20.0), label=label,
                                      doc=self.doc)
        panels = facetwb.make_panelset(small, thickness=2.0, name=panels_name)
        sheets = facetwb.make_cutsheets(panels, sheet=(200.0, 100.0), margin=1.0, spacing=1.0,
                                        name=sheets_name, write_step=False,
                                        output_dir=os.path.join(self.tmp.name, folder))
        return panels, sheets

    def test_cutsheets_warn_of_texts_too_small_to_engrave(self):
        """Parts 20 mm wide get IDs of 2 mm (a tenth of the part): the CutSheets' Warnings
        say so when they write the DXF, as facet panels does; only the command line said
        it. Parts a metre wide get none, and nor do sheets with no output folder (no text
        is written anywhere)."""
        small_panels, tiny = self.small_cutsheets("small", "SmallPanels", "TinySheets", "tiny")
        unwritten = facetwb.make_cutsheets(small_panels, sheet=(200.0, 100.0), margin=1.0,
                                           spacing=1.0, name="UnwrittenSheets")
        large = facetwb.make_cutsheets(self.square, sheet=(2600.0, 1400.0), margin=10.0,
                                       spacing=6.0, name="LargeSheets", write_step=False,
                                       output_dir=os.path.join(self.tmp.name, "large"))
        self.doc.recompute()
        self.assertTrue(tiny.isValid(), tiny.getStatusString())
        self.assertEqual(len(tiny.Warnings), 1, list(tiny.Warnings))
        self.assertRegex(tiny.Warnings[0], r"^6 of 6 part IDs are under 3 mm high")
        self.assertTrue(unwritten.isValid(), unwritten.getStatusString())
        self.assertEqual(list(unwritten.Warnings), [])
        self.assertTrue(large.isValid(), large.getStatusString())
        self.assertEqual(list(large.Warnings), [])

    def test_cutsheets_text_warnings_in_inches_when_freecad_shows_inches(self):
        """FreeCAD set to inches: the CutSheets' Warnings said "under 3 mm high ... the
        smallest 2 mm" beside a property editor in inches. They give the heights in inches
        now (the least in mm too); in the Standard schema as they were."""
        small_panels, sheets = self.small_cutsheets("small in", "SmallPanelsIn", "InchSheets",
                                                    "inch")
        schema = App.Units.getSchema()
        try:
            App.Units.setSchema(3)  # Imperial decimal
            self.doc.recompute()
            self.assertTrue(sheets.isValid(), sheets.getStatusString())
            self.assertEqual(len(sheets.Warnings), 1, list(sheets.Warnings))
            said = sheets.Warnings[0]
            self.assertTrue(said.startswith("6 of 6 part IDs are under 0.118 in (3 mm) high"),
                            said)
            smallest = float(re.search(r"the smallest ([0-9.]+) in,", said).group(1))
            self.assertTrue(0.06 < smallest < 0.118, said)
        finally:
            App.Units.setSchema(schema)
            for obj in (sheets, small_panels, small_panels.Source):
                self.doc.removeObject(obj.Name)

    def test_cutsheets_progress_names_each_stage(self):
        """The progress bar starts again from 0 at each stage (unfolding, nesting, the DXF,
        the previews): the dialog's text now names the stage, which nothing said."""
        from facetwb import progress

        out = os.path.join(self.tmp.name, "staged")
        sheets = facetwb.make_cutsheets(self.mitred, sheet=(2600.0, 1400.0), margin=10.0,
                                        spacing=6.0, output_dir=out, write_step=False,
                                        name="StagedSheets")
        self.doc.recompute()
        sheets.touch()
        with progress.reporting("Cut sheets ...") as reporter:
            self.doc.recompute()
        self.assertTrue(sheets.isValid(), sheets.getStatusString())
        said = [t.split("\n", 1)[1] for t in reporter.texts if "\n" in t]
        # (no "Comparing the parts": the PanelSet's part types, still current, are theirs)
        self.assertEqual(said, ["Unfolding the parts", "Nesting the parts on the sheets",
                                "Drawing the parts in the DXF", "Writing the SVG sheets"])

    def test_panels_of_no_facades_size_are_warned_about(self):
        """A facade in metres read as millimetres (panels 0.6 mm across) made 40 mm thick
        sticks with no word about the units; its Warnings and the report view now say how
        long the edges are and what to do. Panels a metre across get no such warning."""
        tiny = facetwb.make_polymesh(translational(nu=3, nv=2, step=0.6), label="tiny",
                                     doc=self.doc)
        sticks = facetwb.make_panelset(tiny, thickness=40.0, gap=0.0, name="Sticks")
        self.doc.recompute()
        self.assertTrue(sticks.isValid(), sticks.getStatusString())
        said = [w for w in sticks.Warnings if "long on average" in w]
        self.assertEqual(len(said), 1, list(sticks.Warnings))
        self.assertRegex(said[0], r"^the panels' edges are 0\.6\d* mm long on average, which "
                                  r"no facade's are: a mesh drawn in metres .* asks for its units$")
        self.assertFalse([w for w in self.square.Warnings if "long on average" in w])

    def test_panel_messages_give_lengths_in_the_users_unit(self):
        """FreeCAD set to inches (Imperial decimal): the PanelSet's report-view lines said
        "within 0.5 mm", "by 20.01 mm", "a Gap of 23.78 mm clears them" beside a property
        editor in inches. They give lengths in the unit FreeCAD shows them in now; in the
        Standard schema still in mm."""
        from facetwb.taskpanels.derive_panels import PanelsPanel

        source = facetwb.make_polymesh(folded_grid(), label="folded")
        ps = facetwb.make_panelset(source, thickness=40.0, gap=2.0)
        schema, warn = App.Units.getSchema(), App.Console.PrintWarning
        said = []
        App.Console.PrintWarning = said.append
        try:
            for number, unit in ((3, "in"), (0, "mm")):
                del said[:]
                App.Units.setSchema(number)
                ps.touch()
                ps.Document.recompute()
                self.assertTrue(ps.isValid(), ps.getStatusString())
                summary = PanelsPanel.summary(None, ps)
                lines = [line for line in said if ps.Label in line] + [summary]
                self.assertEqual(len(lines), 3, lines)
                self.assertIn(" within 0.0197 in," if unit == "in" else " within 0.5 mm,",
                              summary)
                clearing = ps.ClearingGap.Value / (25.4 if unit == "in" else 1.0)
                for line in lines:
                    self.assertIn(f"a Gap of {clearing:.4g} {unit} ", line)
                    if unit == "in":
                        self.assertNotIn(" mm", line)
        finally:
            App.Units.setSchema(schema)
            App.Console.PrintWarning = warn
            ps.Document.removeObject(ps.Name)
            source.Document.removeObject(source.Name)

    def test_cutsheets_summary_says_where_the_files_are(self):
        """The report view's line after Cut sheets' OK named the sheets and the use but no
        file: with no Output folder nothing was written and nothing said so."""
        out = os.path.join(self.tmp.name, "summary")
        written = facetwb.make_cutsheets(self.mitred, sheet=(2600.0, 1400.0), output_dir=out,
                                         write_step=False, name="SummarySheets")
        unwritten = facetwb.make_cutsheets(self.mitred, sheet=(2600.0, 1400.0),
                                           name="UnwrittenSheets")
        self.doc.recompute()
        text = facetwb.cutsheets_summary(written)
        self.assertRegex(text, rf"^{written.Label}: \d+ sheets, utilisation [\d.]+%, 0 unplaced; "
                               rf"written to {re.escape(out)}: sheets\.dxf, schedule\.csv, "
                               r"schedule\.json, svg/ \(\d+ sheets\)$")
        self.assertTrue(facetwb.cutsheets_summary(unwritten).endswith(
            "; no files written: choose an Output folder (the object's OutputDir) and "
            "recompute"))

    def test_panels_of_a_planarization_stopped_short_say_why(self):
        """Panels of a Planarized object stopped by its iteration limit failed with 'faces
        are not planar within the tolerance ...; planarize first', to a designer who had
        planarized: the message now says that it stopped short, why, and what to change."""
        warped = facetwb.make_polymesh(facet.read_mesh(data_path("hypar.obj")), label="warped",
                                       doc=self.doc)
        short = facetwb.make_planarized(warped, max_iterations=2, name="Short")
        sticks = facetwb.make_panelset(short, thickness=0.5, name="ShortPanels")
        self.doc.recompute()
        self.assertFalse(short.Converged)
        self.assertFalse(sticks.isValid())
        self.assertRegex(sticks.getStatusString(),
                         r"not planar within the tolerance: .*; planarize first; "
                         rf"{short.Label} stopped before its tolerance \(iteration limit "
                         r"reached, tolerance NOT reached\): raise its Max\. iterations, or "
                         r"set it to 0 for the solver to decide$")

    def test_panelset_progress_covers_the_solids(self):
        """Making the solids is most of a large PanelSet's recompute (3,200 panels: 0.4 s
        the panels, 2.6-10 s the solids); it reported no progress, the dialog stayed away
        and Cancel could not stop it. Now a stage of its own, named, to the last solid, and
        Cancel there leaves the object cancelled."""
        from facetwb import progress

        self.square.touch()
        with progress.reporting("Panels ...") as reporter:
            self.doc.recompute([self.square])
        self.assertTrue(self.square.isValid(), self.square.getStatusString())
        said = [t.split("\n", 1)[1] for t in reporter.texts if "\n" in t]
        self.assertEqual(said, ["Making the panel solids", "Comparing the parts"])
        self.assertEqual((reporter.done, reporter.total), (20, 20))
        calls = reporter.calls
        self.square.touch()
        progress.cancel_after(calls - 1)  # the last call of the solids (then the part types')
        try:
            with progress.reporting("Panels ...") as reporter:
                self.doc.recompute([self.square])
        finally:
            progress.cancel_after(0)
        self.assertTrue(reporter.cancelled)
        self.assertIn("cancelled", self.square.getStatusString())
        self.square.touch()
        self.doc.recompute([self.square])
        self.assertTrue(self.square.isValid(), self.square.getStatusString())

    def test_cutsheets_lay_their_sheets_in_rows_as_the_dxf(self):
        """The CutSheets' Shape laid the sheets in one row (161 sheets of 3000 mm: a thin
        red line 483 m long in the top view); now in rows, about as wide as high, each
        sheet's border where the DXF's SHEET rectangle is, each part on it."""
        import ezdxf

        out = os.path.join(self.tmp.name, "rows")
        sheets = facetwb.make_cutsheets(self.mitred, sheet=(1300.0, 1300.0), margin=10.0,
                                        spacing=6.0, output_dir=out, write_step=False,
                                        name="RowSheets")
        self.doc.recompute()
        self.assertTrue(sheets.isValid(), sheets.getStatusString())
        self.assertEqual(list(sheets.Unplaced), [])
        self.assertGreaterEqual(sheets.SheetCount, 16)
        box = sheets.Shape.BoundBox
        self.assertTrue(0.5 <= box.XLength / box.YLength <= 2.0, box)

        def corners(points):  # a closed rectangle's lower-left and upper-right corners
            points = np.asarray(points)
            return tuple(np.round(np.concatenate([points.min(axis=0), points.max(axis=0)]), 6))

        msp = ezdxf.readfile(os.path.join(out, "sheets.dxf")).modelspace()
        dxf = sorted(corners(e.get_points("xy")) for e in msp.query("LWPOLYLINE[layer=='SHEET']"))
        wires = [[(v.X, v.Y) for v in w.Vertexes] for w in sheets.Shape.Wires]
        borders = sorted(corners(w) for w in wires
                         if np.allclose(np.ptp(np.asarray(w), axis=0), 1300.0))
        self.assertEqual(len(borders), sheets.SheetCount)
        self.assertEqual(borders, dxf)
        parts = [corners(w) for w in wires
                 if not np.allclose(np.ptp(np.asarray(w), axis=0), 1300.0)]
        self.assertEqual(len(parts), 20)
        for part in parts:  # (inside one sheet)
            self.assertEqual(sum(b[0] <= part[0] and b[1] <= part[1] and part[2] <= b[2]
                                 and part[3] <= b[3] for b in borders), 1, part)

    def test_cutsheets_write_texts_as_outlines_when_asked(self):
        """TextOutlines: sheets.dxf holds the IDs and bevel angles as closed outlines on
        their layers, no TEXT there (many CAM importers skip TEXT)."""
        import ezdxf

        out = os.path.join(self.tmp.name, "outlines")
        sheets = facetwb.make_cutsheets(self.mitred, sheet=(2600.0, 1400.0), margin=10.0,
                                        spacing=6.0, output_dir=out, write_step=False,
                                        name="OutlineSheets")
        self.assertFalse(sheets.TextOutlines)
        sheets.TextOutlines = True
        self.doc.recompute()
        self.assertTrue(sheets.isValid(), sheets.getStatusString())
        msp = ezdxf.readfile(os.path.join(out, "sheets.dxf")).modelspace()
        self.assertEqual({t.dxf.layer for t in msp.query("TEXT")}, {"SHEET"})
        for layer in ("LABEL", "BEVEL"):
            letters = msp.query(f"LWPOLYLINE[layer=='{layer}']")
            self.assertGreater(len(letters), 0, layer)
            self.assertTrue(all(e.closed for e in letters), layer)

    def test_cutsheets_nest_tightly_when_asked(self):
        """TightNesting (off by default): the parts are nested again with
        facet.nest.nest's tight pass, on no more sheets than before."""
        sheets = facetwb.make_cutsheets(self.mitred, sheet=(2600.0, 1400.0), margin=10.0,
                                        spacing=6.0, name="TightSheets")
        self.doc.recompute()
        self.assertTrue(sheets.isValid(), sheets.getStatusString())
        self.assertFalse(sheets.TightNesting)
        count = sheets.SheetCount
        fnest = sys.modules["facet.nest"]
        saved, asked = fnest.nest, []

        def recording(*a, **k):
            asked.append(k.get("tight"))
            return saved(*a, **k)

        fnest.nest = recording
        try:
            sheets.TightNesting = True
            self.doc.recompute()
        finally:
            fnest.nest = saved
        self.assertTrue(sheets.isValid(), sheets.getStatusString())
        self.assertEqual(asked, [True])
        self.assertLessEqual(sheets.SheetCount, count)
        self.doc.removeObject(sheets.Name)

    def test_cutsheets_reuse_the_panelsets_panels_and_solids(self):
        ps_obj = facetwb.make_panelset(self.source, thickness=T, name="Reused")
        sheets = facetwb.make_cutsheets(ps_obj, sheet=(2600.0, 1400.0), margin=10.0,
                                        spacing=6.0, output_dir=os.path.join(self.tmp.name,
                                                                             "reuse"))
        self.doc.recompute()
        self.assertTrue(sheets.isValid(), sheets.getStatusString())
        with counting_builds() as calls:
            sheets.touch()
            self.doc.recompute()
            self.assertTrue(sheets.isValid(), sheets.getStatusString())
            self.assertEqual(calls, [])  # nothing recomputed: the PanelSet's are reused
            ps_obj.Thickness = 2 * T   # the PanelSet recomputes first, CutSheets reuse that
            self.doc.recompute()
            # the PanelSet's own recompute, once each; none by the CutSheets
            self.assertEqual(calls, ["panels", "solids"])
            step = Part.read(os.path.join(self.tmp.name, "reuse", "panels.step"))
            self.assertAlmostEqual(step.Solids[0].Volume / ps_obj.Volumes[0], 1.0, places=9)
        self.doc.removeObject(sheets.Name)
        self.doc.removeObject(ps_obj.Name)

    def counted_cutsheets(self, name):
        """A PanelSet ``name`` of the source and its CutSheets writing to a folder of that
        name (lower case), removed after the test, with the nestings counted: (the list
        of nest calls, the PanelSet, the CutSheets, the folder)."""
        nests = self.enterContext(counting_nests())
        ps_obj = facetwb.make_panelset(self.source, thickness=T, name=name)
        out = os.path.join(self.tmp.name, name.lower())
        sheets = facetwb.make_cutsheets(ps_obj, sheet=(2600.0, 1400.0), output_dir=out)
        self.addCleanup(self.doc.removeObject, ps_obj.Name)
        self.addCleanup(self.doc.removeObject, sheets.Name)
        return nests, ps_obj, sheets, out

    def test_part_types_in_the_panelset_and_the_cut_sheets_schedule(self):
        """The PanelSet gives each panel's part type (PartTypes, PartTypeCount) and the
        cut sheets' schedule the same in its type column. PartTypeTolerance builds no
        solid and nests nothing again: only the schedules are written again."""
        import csv

        nests, ps_obj, sheets, out = self.counted_cutsheets("Typed")

        def schedule_types():
            with open(os.path.join(out, "schedule.csv"), encoding="utf-8") as handle:
                return [r["type"] for r in csv.DictReader(handle)]

        self.doc.recompute()
        self.assertTrue(sheets.isValid(), sheets.getStatusString())
        # a half turn about the translational surface's centre maps face f onto face 19 - f
        types = list(ps_obj.PartTypes)
        self.assertEqual(ps_obj.PartTypeCount, 10)
        self.assertEqual(types, [types[19 - f] for f in range(20)])
        self.assertEqual(schedule_types(), types)
        before, shape = written(out), ps_obj.Shape
        del nests[:]
        ptypes = sys.modules["facet.part_types"]
        found = []
        original = ptypes.part_types

        def counted(*args, **kwargs):
            found.append(1)
            return original(*args, **kwargs)

        ptypes.part_types = counted
        self.addCleanup(setattr, ptypes, "part_types", original)
        # a Density change finds no part types again (a PanelSet of 10,000 panels: 0.8 s
        # on a recompute that builds nothing); the CutSheets take the PanelSet's
        ps_obj.Density = 2500.0
        self.doc.recompute()
        self.assertTrue(sheets.isValid(), sheets.getStatusString())
        self.assertEqual(found, [])
        self.assertEqual(schedule_types(), types)
        ps_obj.PartTypeTolerance = 5000.0  # every quad within 5 m of the first
        self.doc.recompute()
        self.assertEqual(found, [1])  # the PanelSet's, which the CutSheets took
        self.assertTrue(sheets.isValid(), sheets.getStatusString())
        self.assertTrue(ps_obj.Shape.isSame(shape))
        self.assertEqual(nests, [])
        self.assertEqual((list(ps_obj.PartTypes), ps_obj.PartTypeCount), (["T1"] * 20, 1))
        self.assertEqual(changed_since(out, before), ["schedule.csv", "schedule.json"])
        self.assertEqual(schedule_types(), ["T1"] * 20)

    def test_cutsheets_keep_their_nesting_when_only_the_masses_change(self):
        """A PanelSet's Density changes the schedules' masses, not the nesting (1,536
        panels: 75 s a Density change, which nested them again and wrote every file, 0.4 s
        now): the DXF, SVG and STEP files are left as they are, schedule.csv and
        schedule.json are written again, the same as after a whole recompute. OnePerPanel
        writes nothing; the sheet's inputs and a recompute marked by hand nest again, and a
        missing file is written again from the same nesting."""
        import csv
        import json

        nests, ps_obj, sheets, out = self.counted_cutsheets("Glass")

        def files():
            return written(out)

        def changed(before):
            return changed_since(out, before)

        def schedule():
            with open(os.path.join(out, "schedule.csv"), "rb") as handle:
                text = handle.read()
            with open(os.path.join(out, "schedule.json"), encoding="utf-8") as handle:
                meta = json.load(handle)["meta"]
            return text, meta["density"]

        self.doc.recompute()
        self.assertTrue(sheets.isValid(), sheets.getStatusString())
        self.assertEqual(len(nests), 1)
        before = files()
        self.assertIn("panels.step", before)
        self.assertTrue(any(k.startswith("svg") for k in before))
        del nests[:]
        ps_obj.Density = 2500.0
        self.doc.recompute()
        self.assertTrue(sheets.isValid(), sheets.getStatusString())
        self.assertEqual(nests, [])
        self.assertEqual(changed(before), ["schedule.csv", "schedule.json"])
        text, density = schedule()
        self.assertEqual(density, 2500.0)
        rows = list(csv.DictReader(text.decode("utf-8").splitlines()))
        np.testing.assert_allclose([float(r["mass_kg"]) for r in rows], list(ps_obj.Masses),
                                   rtol=1e-9)
        # the same schedules as a whole recompute's (marked by hand: it nests again)
        before = files()
        sheets.touch()
        self.doc.recompute()
        self.assertEqual(len(nests), 1)
        self.assertIn("sheets.dxf", changed(before))
        self.assertEqual(schedule(), (text, 2500.0))
        del nests[:]
        before = files()
        ps_obj.OnePerPanel = True
        self.doc.recompute()
        self.assertEqual((nests, changed(before)), ([], []))
        ps_obj.OnePerPanel = False
        ps_obj.Density = 0.0  # no mass: empty column, density null
        self.doc.recompute()
        self.assertEqual((nests, changed(before)), ([], ["schedule.csv", "schedule.json"]))
        text, density = schedule()
        self.assertIsNone(density)
        self.assertEqual({r["mass_kg"] for r in csv.DictReader(
            text.decode("utf-8").splitlines())}, {""})
        # what the nesting depends on nests again
        sheets.Spacing = 8.0
        self.doc.recompute()
        self.assertEqual(len(nests), 1)
        # a file no longer there is written again, from the same nesting
        os.remove(os.path.join(out, "sheets.dxf"))
        before = files()
        ps_obj.Density = 2700.0
        self.doc.recompute()
        self.assertEqual(len(nests), 1)
        self.assertEqual(changed(before), ["schedule.csv", "schedule.json", "sheets.dxf"])
        self.assertEqual(schedule()[1], 2700.0)

    def test_cutsheets_keep_their_nesting_for_new_part_ids_and_file_options(self):
        """The part IDs (IdPrefix, IdScheme) are written in every file, but change no
        part's outline: the CutSheets keep their nesting (1,536 panels: 75 s of nesting
        a change) and write every file again with the new IDs. TextOutlines writes the DXF
        alone, WriteStep on the STEP file alone, off removes the panels.step it wrote (it
        would no longer be the panels of the sheets beside it), a new OutputDir gets every
        file, the old one is left as it was."""
        import csv

        import ezdxf

        nests, ps_obj, sheets, out = self.counted_cutsheets("Named")

        def places(folder=out):
            """The schedule's ID and place of each part, in the order of the panels."""
            with open(os.path.join(folder, "schedule.csv"), encoding="utf-8") as handle:
                rows = list(csv.DictReader(handle))
            return ([r["id"] for r in rows],
                    [(r["sheet"], r["x_mm"], r["y_mm"], r["rotation_deg"]) for r in rows])

        def labels(folder=out):
            dxf = ezdxf.readfile(os.path.join(folder, "sheets.dxf"))
            return sorted(e.dxf.text for e in dxf.modelspace().query("TEXT[layer=='LABEL']"))

        def step_names(folder=out):
            with open(os.path.join(folder, "panels.step"), encoding="latin-1") as handle:
                return re.findall(r"PRODUCT\('([^']*)'", handle.read())

        self.doc.recompute()
        self.assertTrue(sheets.isValid(), sheets.getStatusString())
        self.assertEqual(len(nests), 1)
        ids, placed = places()
        self.assertEqual(ids, list(ps_obj.PartIds))
        layout = sheets.Shape
        everything = sorted(written(out))
        for prefix, scheme, first in (("G-", "auto", "G-R01C01"), ("G-", "index", "G-0000")):
            before = written(out)
            ps_obj.IdPrefix, ps_obj.IdScheme = prefix, scheme
            self.doc.recompute()
            self.assertTrue(sheets.isValid(), sheets.getStatusString())
            self.assertEqual(len(nests), 1)  # not nested again
            self.assertEqual(changed_since(out, before), everything)
            ids, now = places()
            self.assertEqual((ids[0], ids), (first, list(ps_obj.PartIds)))
            self.assertEqual(now, placed)  # each part where it was
            self.assertEqual(labels(), sorted(ps_obj.PartIds))
            self.assertEqual([n for n in step_names() if n.startswith(prefix)],
                             list(ps_obj.PartIds))
            self.assertTrue(sheets.Shape.isSame(layout))
        # the files' own options: the files they change alone
        before = written(out)
        sheets.TextOutlines = True
        self.doc.recompute()
        self.assertEqual((len(nests), changed_since(out, before)), (1, ["sheets.dxf"]))
        self.assertEqual(labels(), [])  # (the IDs are letters' outlines now)
        before = written(out)
        sheets.WriteStep = False
        self.doc.recompute()
        self.assertEqual((len(nests), changed_since(out, before)), (1, []))
        self.assertNotIn("panels.step", written(out))
        self.assertNotIn(os.path.join(out, "panels.step"), sheets.Files)
        sheets.WriteStep = True
        self.doc.recompute()
        self.assertEqual((len(nests), changed_since(out, before)), (1, ["panels.step"]))
        self.assertEqual([n for n in step_names() if n.startswith("G-")], list(ps_obj.PartIds))
        self.assertEqual(sorted(sheets.Files), sorted(os.path.join(out, f) for f in everything))
        before = written(out)
        other = os.path.join(self.tmp.name, "named2")
        sheets.OutputDir = other
        self.doc.recompute()
        self.assertEqual(len(nests), 1)
        self.assertEqual(changed_since(out, before), [])  # the old folder left as it was
        self.assertEqual(sorted(written(other)), everything)
        self.assertEqual(sorted(sheets.Files), sorted(os.path.join(other, f) for f in everything))
        self.assertEqual(places(other), (list(ps_obj.PartIds), placed))
        # an outline that changes (Thickness moves the top face, Gap the cut) nests again
        ps_obj.Gap = 2 * GAP
        self.doc.recompute()
        self.assertEqual(len(nests), 2)

    def test_undo_after_files_were_written_marks_the_cut_sheets_for_recompute(self):
        """Undo (and redo) after a recompute wrote the files: FreeCAD marks the PanelSet
        whose Gap it put back, but left its CutSheets shown up to date, their files those
        of the Gap undone. They are marked now, and the next recompute writes the files of
        the values the document holds; a CutSheets property undone was marked already."""
        import csv

        doc = App.newDocument("UndoFiles")
        self.addCleanup(App.closeDocument, doc.Name)
        doc.UndoMode = 1
        source = facetwb.make_polymesh(self.mesh, label="undone", doc=doc)
        ps_obj = facetwb.make_panelset(source, thickness=T)
        out = os.path.join(self.tmp.name, "undo")
        sheets = facetwb.make_cutsheets(ps_obj, sheet=(2600.0, 1400.0), output_dir=out)
        # no files, but a layout (Shape, SheetCount) of the panels all the same
        unwritten = facetwb.make_cutsheets(ps_obj, sheet=(2600.0, 1400.0))
        doc.recompute()

        def areas():
            with open(os.path.join(out, "schedule.csv"), encoding="utf-8") as handle:
                return [float(r["area_mm2"]) for r in csv.DictReader(handle)]

        np.testing.assert_allclose(areas(), list(ps_obj.Areas), rtol=1e-12)
        for obj, prop, value in ((ps_obj, "Gap", 2 * GAP), (sheets, "SheetWidth", 2800.0)):
            old = getattr(obj, prop)
            doc.openTransaction(f"Set {prop}")
            setattr(obj, prop, value)
            doc.commitTransaction()
            doc.recompute()
            self.assertTrue(sheets.isValid(), sheets.getStatusString())
            self.assertEqual(sheets.State, ["Up-to-date"])
            before = written(out)
            for step in (doc.undo, doc.redo, doc.undo):
                step()
                self.assertIn("Touched", sheets.State, (prop, step.__name__))
                if obj is ps_obj:
                    self.assertIn("Touched", unwritten.State, (prop, step.__name__))
            self.assertEqual(getattr(obj, prop), old)
            self.assertEqual(changed_since(out, before), [])  # (nothing written on undo)
            doc.recompute()
            self.assertEqual((ps_obj.State, sheets.State, unwritten.State),
                             (["Up-to-date"], ["Up-to-date"], ["Up-to-date"]))
            self.assertIn("sheets.dxf", changed_since(out, before))
            np.testing.assert_allclose(areas(), list(ps_obj.Areas), rtol=1e-12)
        # nothing upstream marked: nothing more is
        doc.openTransaction("Set Label")
        sheets.Label = "renamed"
        doc.commitTransaction()
        doc.undo()
        self.assertEqual((ps_obj.State, sheets.State, unwritten.State),
                         (["Up-to-date"], ["Up-to-date"], ["Up-to-date"]))

    def test_z_save_reopen(self):
        ids = list(self.square.PartIds)
        volumes = list(self.square.Volumes)
        name = self.square.Name
        doc = self.save_and_reopen("panels.FCStd")
        obj = doc.getObject(name)
        self.assertEqual(obj.Proxy.Type, "Facet::PanelSet")
        self.assertEqual(list(obj.PartIds), ids)
        obj.touch()
        doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        np.testing.assert_allclose(list(obj.Volumes), volumes, rtol=1e-12)


class TestPanelSetDefaults(DocumentTestCase):
    """The joint a PanelSet starts with, and what a saved document keeps."""

    def test_a_new_panelset_has_the_command_lines_default_gap(self):
        """The Gap of a new PanelSet (from make_panelset, the task panel's preference, or
        the bare proxy) is facet panels' default, DEFAULT_GAP_MM; it was 0."""
        from facet.cli_panels import run_pipeline
        from facet.panels import DEFAULT_GAP_MM
        from facetwb import preferences
        from facetwb.objects.panelset import PanelSet

        mesh = translational(nu=3, nv=2, step=1000.0)
        source = facetwb.make_polymesh(mesh, label="defaults", doc=self.doc)
        made = facetwb.make_panelset(source, name="Made")
        bare = self.doc.addObject("Part::FeaturePython", "Bare")
        PanelSet(bare)
        self.assertEqual(DEFAULT_GAP_MM, 6.0)
        self.assertEqual(made.Gap.Value, DEFAULT_GAP_MM)
        self.assertEqual(bare.Gap.Value, DEFAULT_GAP_MM)
        self.assertEqual(preferences.DEFAULTS["PanelGap"], ("float", DEFAULT_GAP_MM))
        self.assertEqual((made.EdgeMode, bare.EdgeMode), ("square", "square"))
        self.doc.recompute()
        self.assertTrue(made.isValid(), made.getStatusString())
        _, ps, _, _ = run_pipeline(mesh, made.Thickness.Value)
        self.assertEqual(ps.options["gap"], made.Gap.Value)
        self.assertEqual(ps.options["edge"], made.EdgeMode)
        np.testing.assert_allclose(made.Volumes, [p.volume for p in ps.panels], rtol=1e-9)

    def test_a_mesh_too_small_for_the_gap_says_its_size(self):
        """A facade in metres read as millimetres: the default 6 mm joint consumes its
        0.6 mm panels, and the error named a face and a gap; it now says the size too."""
        tiny = facetwb.make_polymesh(translational(nu=3, nv=2, step=0.6), label="tiny",
                                     doc=self.doc)
        obj = facetwb.make_panelset(tiny, name="Consumed")
        self.doc.recompute()
        self.assertFalse(obj.isValid())
        self.assertRegex(obj.getStatusString(),
                         r"the gap 6 mm leaves fewer than three edges .*; the panels' edges are "
                         r"0\.6\d* mm long on average, which no facade's are: a mesh drawn in "
                         r"metres")

    def test_a_failed_joint_names_the_panelsets_min_edge(self):
        """A mitred joint that cannot be cut names the MinEdge that builds the panels as
        the PanelSet's (facet panels says --min-edge), and its MinEdgeAbs when one is set;
        the message named neither."""
        from facet.io import read_mesh

        stub = read_mesh(os.path.join(os.path.dirname(__file__), "..", "data",
                                      "pillow_stub_edge.obj"))
        source = facetwb.make_polymesh(stub, label="stub", doc=self.doc)
        obj = facetwb.make_panelset(source, thickness=40.0, gap=10.0, edge="bisector",
                                    name="Stub")
        obj.MinEdgeAbs = 5.0
        self.doc.recompute()
        self.assertFalse(obj.isValid())
        status = obj.getStatusString()
        found = re.search(r"; so does the PanelSet's MinEdge ([0-9.]+) \(now 0\.01\); so "
                          r"does the PanelSet's MinEdgeAbs ([0-9.]+) mm \(now 5 mm\);", status)
        self.assertTrue(found, status)
        obj.MinEdge = float(found.group(1))
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())

    def test_z_a_saved_document_keeps_its_gap(self):
        """A PanelSet saved with Gap 0 (the old default) reopens with Gap 0, not the new
        default, and recomputes to the same panels."""
        source = facetwb.make_polymesh(translational(nu=3, nv=2, step=1000.0),
                                       label="saved", doc=self.doc)
        obj = facetwb.make_panelset(source, gap=0.0, name="Saved")
        self.doc.recompute()
        clashing, volumes = list(obj.ClashingPanels), list(obj.Volumes)
        self.assertGreater(len(clashing), 0)
        doc = self.save_and_reopen("saved_gap.FCStd")
        obj = doc.getObject("Saved")
        self.assertEqual(obj.Gap.Value, 0.0)
        obj.touch()
        doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(list(obj.ClashingPanels), clashing)
        np.testing.assert_allclose(list(obj.Volumes), volumes, rtol=1e-12)


class TestPanelSetOnPlanarized(DocumentTestCase):
    def test_cylinder_planarized_chain(self):
        source = facetwb.make_polymesh(cylinder(), label="cyl")
        planar = facetwb.make_planarized(source, tolerance=1e-9)
        ps = facetwb.make_panelset(planar, thickness=20.0, edge="bisector")
        self.doc.recompute()
        self.assertTrue(ps.isValid(), ps.getStatusString())
        self.assertEqual(ps.PanelCount, 24)
        self.assertLess(ps.MaxNodeDeviation.Value, 1e-5)
        for s in ps.Shape.Solids:
            s.check(True)


    def test_overlapping_joints_that_no_gap_clears_are_a_warning(self):
        # a planarized hypar, 20 mm square panels, no gap: the clearing gap is None (no
        # gap found) and its warning raised TypeError formatting it: no PanelSet at all
        source = facetwb.make_polymesh(facet.read_mesh(data_path("hypar.obj")), doc=self.doc)
        planar = facetwb.make_planarized(source, tolerance=1e-7)
        ps = facetwb.make_panelset(planar, thickness=20.0, gap=0.0)
        self.doc.recompute()
        self.assertTrue(ps.isValid(), ps.getStatusString())
        self.assertGreater(ps.OverlappingJoints, 0)
        self.assertEqual(ps.ClearingGap.Value, 0.0)
        self.assertTrue(any("no gap" in w or "thinner panels" in w for w in ps.Warnings),
                        list(ps.Warnings))
        # its lengths in millimetres, the document's unit (they were bare numbers)
        (joints,) = [w for w in ps.Warnings if "cut square on the inner side" in w]
        self.assertRegex(joints, r"by [0-9.e+-]+ mm \(the deepest")


class TestPanelSetJoints(DocumentTestCase):
    """Square joints that overlap on the inner side of a fold, in a document of their own."""

    def test_square_joints_that_overlap_in_a_valley_are_reported_with_the_gap_that_clears(self):
        # folded_grid (mm): a valley between two ridges; 200 mm panels cut square
        # with a 10 mm gap overlap along the valley, and the ClearingGap clears them
        mesh = folded_grid()
        source = facetwb.make_polymesh(mesh, label="folded")
        obj = facetwb.make_panelset(source, thickness=200.0, gap=10.0, name="Folded")
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.OverlappingJoints, 2)
        self.assertLess(obj.NarrowestJoint.Value, -1.0)
        a, b = obj.NarrowestJointPanels
        solid = dict(zip(obj.PartIds, obj.Shape.Solids))
        self.assertGreater(solid[a].common(solid[b]).Volume, 1e-6 * solid[a].Volume)
        self.assertTrue(any("cut square on the inner side of a fold overlap" in w
                            for w in obj.Warnings), obj.Warnings)
        clearing = obj.ClearingGap.Value
        self.assertGreater(clearing, 10.0)
        obj.Gap = clearing * (1 + 1e-6)
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.OverlappingJoints, 0)
        self.assertEqual(obj.ClearingGap.Value, 0.0)
        self.assertGreaterEqual(obj.NarrowestJoint.Value, 0.0)
        self.assertFalse([w for w in obj.Warnings if "inner side of a fold" in w], obj.Warnings)
        ps = panels(mesh, 200.0, gap=obj.Gap.Value)
        solids = obj.Shape.Solids
        for p in ps:
            for h in p.neighbors:
                if h is not None and h > p.face:
                    self.assertLess(solids[p.face].common(solids[h]).Volume,
                                    1e-9 * solids[p.face].Volume)
        np.testing.assert_array_equal(bits(points_array(source)), bits(mesh.vertices))
        self.doc.removeObject(obj.Name)
        self.doc.removeObject(source.Name)

    def test_panels_that_clash_at_a_node_are_reported(self):
        # the bowl of the Python tests (mm): four planar quads whose diagonal panels
        # meet only at its bottom; cut square they run into each other there
        from test_panels_nodes import _bowl, _clearing

        source = facetwb.make_polymesh(_bowl(), label="bowl")
        obj = facetwb.make_panelset(source, thickness=200.0, gap=10.0, name="Bowl")
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.NodeClashes, 2)
        self.assertGreater(obj.DeepestNodeClash.Value, 1.0)
        a, b = obj.NodeClashPanels
        solid = dict(zip(obj.PartIds, obj.Shape.Solids))
        self.assertGreater(solid[a].common(solid[b]).Volume, 1e-6 * solid[a].Volume)
        self.assertTrue(any("meet at a node" in w for w in obj.Warnings), obj.Warnings)
        self.assertAlmostEqual(obj.ClearingGap.Value / _clearing(), 1.0, delta=2e-4)
        obj.Gap = obj.ClearingGap.Value
        self.doc.recompute()
        self.assertEqual((obj.NodeClashes, obj.DeepestNodeClash.Value), (0, 0.0))
        self.assertEqual(list(obj.NodeClashPanels), [])
        solids = obj.Shape.Solids
        self.assertLess(solids[0].common(solids[3]).Volume, 1e-9 * solids[0].Volume)
        self.doc.removeObject(obj.Name)
        self.doc.removeObject(source.Name)


class TestPanelSetVanishedEdge(DocumentTestCase):
    """A quad whose edge vanished (1e-6 of a 1000 mm grid) is built as a triangle panel."""

    def test_recomputes_with_triangle_panels_and_says_how_many(self):
        source = facetwb.make_polymesh(folded_grid(short=1e-6), label="folded")
        before = points_array(source).copy()
        obj = facetwb.make_panelset(source, thickness=18.0, edge="bisector", gap=4.0,
                                    name="Vanished")
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertTrue(obj.Shape.isValid())
        self.assertEqual(obj.PanelCount, 8)
        self.assertEqual(list(obj.VanishedEdgePanels), ["P-R01C02", "P-R01C03"])
        self.assertEqual(list(obj.Corners), [4, 3, 3, 4, 4, 4, 4, 4])
        self.assertTrue(any("2 panels built with fewer corners" in w for w in obj.Warnings))
        solids = obj.Shape.Solids
        self.assertEqual([len(s.Faces) for s in solids], [c + 2 for c in obj.Corners])
        for s in solids:
            self.assertTrue(s.isValid() and s.Shells[0].isClosed())
        np.testing.assert_array_equal(points_array(source), before)  # source untouched
        # without the merge the gap consumes the vanished edge on both panels, which drop
        # it: the same triangles, their overlap at the node counted (it was refused as a
        # joint "cut square on both" measured across the side both panels had dropped)
        obj.MinEdge = 0.0
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(list(obj.Corners), [4, 3, 3, 4, 4, 4, 4, 4])
        for s in obj.Shape.Solids:
            self.assertTrue(s.isValid() and s.Shells[0].isClosed())
        self.assertTrue(any("meet at a node" in w for w in obj.Warnings), obj.Warnings)
        obj.MinEdge = 0.01
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(list(obj.VanishedEdgePanels), ["P-R01C02", "P-R01C03"])

    def test_planarized_hypar_chain(self):
        """hypar.obj planarized (the default method shrinks 8 edges to ~5e-7 of the mean
        edge): the PanelSet builds the faces with an edge under 1% of their mean as
        triangles, and its solids are valid."""
        from facetwb import conversion

        source = facetwb.make_polymesh(facet.read_mesh(data_path("hypar.obj")), label="hypar")
        planar = facetwb.make_planarized(source)
        obj = facetwb.make_panelset(planar, thickness=0.01, gap=0.0, name="HyparPanels")
        self.doc.recompute()
        self.assertTrue(planar.isValid(), planar.getStatusString())
        self.assertTrue(obj.isValid(), obj.getStatusString())
        mesh = conversion.mesh_from_object(planar)
        fs, fv, xyz = mesh.face_start, mesh.face_vertices, mesh.vertices
        nxt = np.arange(1, fv.size + 1)
        nxt[fs[1:] - 1] = fs[:-1]
        lengths = np.linalg.norm(xyz[fv[nxt]] - xyz[fv], axis=1)
        short = np.minimum.reduceat(lengths, fs[:-1]) < 0.01 * (
            np.add.reduceat(lengths, fs[:-1]) / np.diff(fs))
        self.assertGreater(int(short.sum()), 0)
        self.assertEqual(len(obj.VanishedEdgePanels), int(short.sum()))
        self.assertEqual([c for c in obj.Corners if c == 3], [3] * int(short.sum()))
        self.assertTrue(all(s.isValid() for s in obj.Shape.Solids))
        self.assertEqual(len(obj.Shape.Solids), 64)
