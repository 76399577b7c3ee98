# SPDX-License-Identifier: LGPL-2.1-or-later
"""Edit control mesh without a GUI: which objects can be edited, and live parameters stay
quiet (the dragging itself is tested in tests/gui/gui_test.py)."""

import facet
import facetwb
from facet_test_support import DocumentTestCase, data_path
from facetwb import importer


class TestEditControl(DocumentTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.control = importer.import_mesh(data_path("hypar.obj"), cls.doc)
        cls.result = facetwb.make_planarized(cls.control)
        cls.doc.recompute()

    def test_control_of_planarized_and_of_its_polymesh(self):
        from facetwb import edit_control

        self.assertEqual(edit_control.control_of(self.result), (self.result, self.control))
        self.assertEqual(edit_control.control_of(self.control), (self.result, self.control))

    def test_refusals_name_the_object(self):
        from facetwb import edit_control

        lone = facetwb.make_polymesh(facet.read_mesh(data_path("hypar.obj")))
        lone.Label = "Lone"
        with self.assertRaisesRegex(edit_control.EditError,
                                    "^Lone: no Planarized object uses it; planarize it first$"):
            edit_control.control_of(lone)
        box = self.doc.addObject("Part::Box", "Box")
        derived = facetwb.make_polymesh_from_object(box)
        flat = facetwb.make_planarized(derived)
        self.doc.recompute()
        # a control mesh rebuilt from the box is edited too: Done puts the moved vertices
        # in a new PolyMesh (it was refused, and the tutorial's SurfaceMesh with it)
        self.assertEqual(edit_control.control_of(flat), (flat, derived))
        self.assertTrue(edit_control.is_linked(derived))
        self.assertFalse(edit_control.is_linked(self.control))
        with self.assertRaisesRegex(edit_control.EditError, "is not a Planarized object"):
            edit_control.control_of(box)

    def test_solver_settings_follow_the_properties(self):
        from facetwb import edit_control

        self.result.Boundary = "fixed"
        settings = edit_control.solver_settings(self.result, facetwb.get_mesh(self.control))
        self.assertEqual(settings["boundary"], "fixed")
        self.assertEqual(settings["tol"], self.result.Tolerance)
        self.result.Boundary = "free"
        self.doc.recompute()

    def test_live_parameters_quiet_without_gui(self):
        from facetwb import live_parameters

        live_parameters.parameter_changed(self.result, "Tolerance")
        self.assertEqual(live_parameters.pending(), 0)
