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


if __name__ == "__main__":
    unittest.main()
