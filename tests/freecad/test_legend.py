# SPDX-License-Identifier: LGPL-2.1-or-later
"""Legend tick labels: lengths in the unit FreeCAD's schema picks, and below its smallest
unit (a planarized mesh is often below a nanometre) in pm, or in scientific notation below
a picometre; never as 0.000000000735 mm."""

import unittest

from facetwb.viewproviders.legend import tick_labels


class TestTickLabels(unittest.TestCase):
    def test_schema_units(self):
        self.assertEqual(tick_labels(88.8e-6, 5)[-1], "88.8 nm")
        self.assertEqual(tick_labels(2.5, 2), ["0.00 mm", "2.50 mm"])

    def test_picometres(self):
        self.assertEqual(tick_labels(3.2e-9, 2), ["0.00 pm", "3.20 pm"])
        self.assertEqual(tick_labels(73.5e-9, 2), ["0.0 pm", "73.5 pm"])

    def test_below_a_picometre_is_scientific(self):
        self.assertEqual(tick_labels(7.35e-10, 2), ["0.00e+00 mm", "7.35e-10 mm"])


    def test_an_imperial_schema_stays_in_inches(self):
        """FreeCAD set to inches: a source's planarity of 0.05 in was labelled "1270 µm",
        its lengths below a tenth of an inch in metric units. Inches down to a thou now,
        then microinches; '"' (US customary's inch) written "in"."""
        import FreeCAD as App

        schema = App.Units.getSchema()
        try:
            for number in (3, 5, 7):  # Imperial decimal, Building US, Civil Eng
                App.Units.setSchema(number)
                with self.subTest(schema=number):
                    self.assertEqual(tick_labels(0.05 * 25.4, 2), ["0.0000 in", "0.0500 in"])
                    self.assertEqual(tick_labels(0.002 * 25.4, 2)[-1], "0.00200 in")
                    self.assertEqual(tick_labels(250e-6 * 25.4, 2)[-1], "250 \u00b5in")
            App.Units.setSchema(3)
            self.assertEqual(tick_labels(6.35, 2)[-1], "0.250 in")
            App.Units.setSchema(2)  # US customary: its thou, and its '"' written "in"
            self.assertEqual(tick_labels(1.27, 2)[-1], "50.0 thou")
            self.assertEqual(tick_labels(6.35, 2)[-1], "0.250 in")
            App.Units.setSchema(0)  # Standard: as it was
            self.assertEqual(tick_labels(1.27, 2)[-1], "1.27 mm")
            self.assertEqual(tick_labels(0.0635, 2)[-1], "63.5 \u00b5m")
        finally:
            App.Units.setSchema(schema)

if __name__ == "__main__":
    unittest.main()
