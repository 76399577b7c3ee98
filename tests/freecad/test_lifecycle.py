# SPDX-License-Identifier: LGPL-2.1-or-later
"""A designer's document life cycle: a document reopened after its CutSheets' output
folder went, two CutSheets writing into one folder (a copy), a FreeCAD Mesh replaced under
the Facet objects made from it."""

import os
import shutil
import sys

import FreeCAD as App

import facetwb
from facet_test_support import DocumentTestCase
from test_bad_input_fc import captured, error_lines

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                "python"))
from panel_meshes import translational  # noqa: E402


def reopened(case, doc, path=None, meanwhile=None):
    """``doc`` saved (as ``path`` when given), closed, ``meanwhile()`` run, and opened again
    as ``case``'s document: (the document, what opening it printed)."""
    if path:
        doc.saveAs(path)
    else:
        doc.save()
        path = doc.FileName
    App.closeDocument(doc.Name)
    if meanwhile is not None:
        meanwhile()
    doc, text = captured(lambda: App.openDocument(path))
    type(case).doc = doc
    return doc, text


def recomputed(case, doc):
    """The names of the objects a recompute of ``doc`` recomputed."""
    from facetwb.recompute import Recomputes

    recorded = Recomputes(doc)
    case.addCleanup(recorded.stop)
    doc.recompute()
    return recorded.take()


class TestCutSheetFiles(DocumentTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.source = facetwb.make_polymesh(translational(nu=4, nv=3, step=1000.0),
                                           label="facade", doc=cls.doc)
        cls.panels = facetwb.make_panelset(cls.source, thickness=30.0)
        cls.out = os.path.join(cls.tmp.name, "cut")
        cls.sheets = facetwb.make_cutsheets(cls.panels, sheet=(2600.0, 1400.0),
                                            output_dir=cls.out, write_step=False)
        cls.doc.recompute()

    def test_reopened_without_its_output_folder_writes_its_files_again(self):
        """The output folder deleted (or the document opened elsewhere): the reopened
        CutSheets were shown up to date, their Files naming files that were not there,
        and a recompute wrote nothing. Now the report view says so and the next
        recompute rebuilds them (them alone) and writes the files again."""
        sheets = self.sheets
        self.assertTrue(sheets.isValid(), sheets.getStatusString())
        files = list(sheets.Files)
        self.assertTrue(files and all(os.path.isfile(f) for f in files))
        name, label = sheets.Name, sheets.Label
        doc, text = reopened(self, self.doc, os.path.join(self.tmp.name, "moved.FCStd"),
                             meanwhile=lambda: shutil.rmtree(self.out))
        sheets = doc.getObject(name)
        said = [line for line in error_lines(text) if line.startswith(label + ":")]
        self.assertEqual(len(said), 1, text)
        self.assertIn(f"{len(files)} of the {len(files)} files", said[0])
        self.assertIn(self.out, said[0])
        self.assertEqual(recomputed(self, doc), {name})
        self.assertTrue(sheets.isValid(), sheets.getStatusString())
        self.assertEqual(sheets.State, ["Up-to-date"])
        self.assertEqual(list(sheets.Files), files)
        self.assertTrue(all(os.path.isfile(f) for f in files))
        # files all there: reopened as saved, up to date
        doc, text = reopened(self, doc)
        self.assertNotIn(label, text)
        self.assertEqual(recomputed(self, doc), set())

    def test_a_copy_writing_into_the_same_folder_is_refused(self):
        """A copy of a CutSheets (Edit > Duplicate, copy and paste) keeps its OutputDir:
        recomputed with another sheet, the copy replaced the original's files, which
        still showed up to date. Now the copy's recompute writes nothing and says why;
        given a folder of its own, it writes there."""
        from test_panelset import changed_since, written

        doc, sheets = self.doc, self.sheets
        self.assertTrue(sheets.isValid(), sheets.getStatusString())
        copy = doc.copyObject(sheets, False)
        self.addCleanup(lambda: doc.getObject(copy.Name) and doc.removeObject(copy.Name))
        self.assertEqual(copy.OutputDir, sheets.OutputDir)
        before = written(self.out)
        copy.SheetWidth = 3000.0
        doc.recompute()
        self.assertFalse(copy.isValid())
        status = copy.getStatusString()
        self.assertIn(copy.Label, status)
        self.assertIn(self.out, status)
        self.assertIn(sheets.Label, status)
        self.assertEqual(changed_since(self.out, before), [])
        self.assertTrue(sheets.isValid(), sheets.getStatusString())
        other = os.path.join(self.tmp.name, "copy")
        copy.OutputDir = other
        doc.recompute()
        self.assertTrue(copy.isValid(), copy.getStatusString())
        self.assertTrue(all(f.startswith(other + os.sep) and os.path.isfile(f)
                            for f in copy.Files))
        self.assertEqual(changed_since(self.out, before), [])

    def test_a_cutsheets_of_another_document_in_the_same_folder_is_named_with_it(self):
        """Two versions of a design open at once (the second saved as another file): the
        refusal of the second's CutSheets said its OutputDir "is also that of CutSheets",
        its own label, as if it were itself. Now it names the other document too."""
        other = App.newDocument("Version2")
        self.addCleanup(App.closeDocument, other.Name)
        source = facetwb.make_polymesh(translational(nu=4, nv=3, step=1000.0),
                                       label="facade", doc=other)
        panels = facetwb.make_panelset(source, thickness=30.0)
        sheets = facetwb.make_cutsheets(panels, sheet=(2600.0, 1400.0),
                                        output_dir=self.out, write_step=False)
        other.recompute()
        self.assertFalse(sheets.isValid())
        self.assertEqual(sheets.Label, self.sheets.Label)
        status = sheets.getStatusString()
        self.assertIn(f"that of {self.sheets.Label} of the document {self.doc.Label},",
                      status)


class TestReplacedMesh(DocumentTestCase):
    def test_a_freecad_mesh_replaced_marks_what_is_made_from_it(self):
        """A FreeCAD Mesh replaced by a script or a Mesh workbench tool: FreeCAD marks
        neither it nor what is made from it (its Mesh is an output property), and the
        Planarized and panels made from it stayed up to date with the old mesh's results
        through any recompute. They are marked now, and undo marks them again."""
        import Mesh

        from facet_test_support import data_path

        doc = self.doc
        doc.UndoMode = 1
        source = doc.addObject("Mesh::Feature", "Triangles")
        source.Mesh = Mesh.Mesh(data_path("hypar.obj"))
        result = facetwb.make_planarized(source, tolerance=1e-9)
        panels = facetwb.make_panelset(result, thickness=0.05, gap=0.0)
        doc.recompute()
        self.assertTrue(panels.isValid(), panels.getStatusString())
        old = (len(result.Points), panels.PanelCount)
        replacement = Mesh.Mesh(data_path("quad_dome.obj"))
        doc.openTransaction("Replace the mesh")
        source.Mesh = replacement
        doc.commitTransaction()
        self.assertIn("Touched", result.State)
        doc.recompute()
        self.assertTrue(panels.isValid(), panels.getStatusString())
        self.assertEqual((len(result.Points), panels.PanelCount),
                         (replacement.CountPoints, replacement.CountFacets))
        self.assertEqual((result.State, panels.State), (["Up-to-date"], ["Up-to-date"]))
        doc.undo()
        self.assertIn("Touched", result.State)
        doc.recompute()
        self.assertEqual((len(result.Points), panels.PanelCount), old)


class TestSavedWithoutPartTypes(DocumentTestCase):
    def test_a_panelset_saved_before_part_types_finds_them_at_the_next_recompute(self):
        """A PanelSet saved by a Facet without part types (examples/facade.FCStd of
        ed6ee55) reopened with PartTypes empty and PartTypeCount 0 beside its 12 panels,
        up to date: a Recompute did nothing, ShowPartTypes showed nothing. Now the report
        view says so and the next recompute finds them; saved with them, it reopens up to
        date."""
        doc = self.doc
        source = facetwb.make_polymesh(translational(nu=4, nv=3, step=1000.0),
                                       label="facade", doc=doc)
        panels = facetwb.make_panelset(source, thickness=30.0)
        doc.recompute()
        self.assertTrue(panels.isValid(), panels.getStatusString())
        count, types = panels.PartTypeCount, list(panels.PartTypes)
        self.assertTrue(count > 0 and len(types) == panels.PanelCount == 12)
        for prop in ("PartTypes", "PartTypeCount", "PartTypeTolerance"):  # as saved then
            panels.removeProperty(prop)
        name, label = panels.Name, panels.Label
        doc, text = reopened(self, doc, os.path.join(self.tmp.name, "older.FCStd"))
        panels = doc.getObject(name)
        said = [line for line in error_lines(text) if line.startswith(label + ":")]
        self.assertEqual(len(said), 1, text)
        self.assertIn("12 panels", said[0])
        self.assertEqual((panels.PartTypeCount, list(panels.PartTypes)), (0, []))
        self.assertIn(name, recomputed(self, doc))
        self.assertTrue(panels.isValid(), panels.getStatusString())
        self.assertEqual((panels.PartTypeCount, list(panels.PartTypes)), (count, types))
        doc, text = reopened(self, doc)
        self.assertNotIn(label + ":", text)
        self.assertEqual(recomputed(self, doc), set())
        self.assertEqual(doc.getObject(name).PartTypeCount, count)
