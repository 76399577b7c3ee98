# SPDX-License-Identifier: LGPL-2.1-or-later
"""Pinned heights from picked vertices (facetwb.pins): the selection of plan vertices
(``Vertex<n>`` of the PlanGraph or of a Lifting of it) becomes PinnedPoints at those
vertices, the Lifting meets the heights there; what is not a plan vertex is refused with a
message saying what to click."""

import math

import FreeCAD as App
import numpy as np

import facetwb
from facetwb import picked, pins
from facet_test_support import DocumentTestCase, points_array
from test_lifting import OUTER, add_plane, add_sketch, nested_segments


class TestPinsFromSelection(DocumentTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.sketch = add_sketch(cls.doc, nested_segments())
        cls.plan = facetwb.make_plan_graph([cls.sketch])
        cls.other_sketch = add_sketch(cls.doc, nested_segments(0.3), "Other")
        cls.other = facetwb.make_plan_graph([cls.other_sketch])
        cls.surface = add_plane(cls.doc, 3000.0, 0.1, -0.2)
        cls.lifting = facetwb.make_lifting(cls.plan, targets=cls.surface)
        cls.doc.recompute()
        cls.mesh = facetwb.get_mesh(cls.plan)

    def test_vertices_of_the_plan_and_of_its_roof(self):
        entries = [(self.plan, ["Vertex4", "Vertex1"]), (self.lifting, ["Vertex4", "Vertex0"])]
        self.assertEqual(pins.selected_vertices(entries, self.plan), [4, 1, 0])

    def test_pins_are_placed_at_the_vertices_and_replace_their_own(self):
        first = pins.pin(self.mesh, [], [4, 1], 2500.0)
        xy = self.mesh.vertices[:, :2]
        self.assertEqual(first, [(xy[4, 0], xy[4, 1], 2500.0), (xy[1, 0], xy[1, 1], 2500.0)])
        self.assertEqual(pins.pins_vertices(self.mesh, first), [4, 1])
        # pinned again: the pin at vertex 1 takes the new height in its place
        second = pins.pin(self.mesh, first, [1, 2], 3100.0)
        self.assertEqual(pins.pins_vertices(self.mesh, second), [4, 1, 2])
        self.assertEqual([p[2] for p in second], [2500.0, 3100.0, 3100.0])
        self.assertEqual(first[1][2], 2500.0)  # the list given is not changed
        # a pin off every vertex (the drawing moved): -1, left as it is
        moved = [(xy[0, 0] + 50.0, xy[0, 1], 1.0)] + second
        self.assertEqual(pins.pins_vertices(self.mesh, moved), [-1, 4, 1, 2])

    def test_the_lifting_meets_the_picked_heights(self):
        # the eaves (the outer triangle) at 2 m, one corner of the inner triangle at 3.5 m:
        # a frustum, which the plan admits (its lifting space is the planes and this)
        lifting = facetwb.make_lifting(self.plan, name="Pinned")
        xy = self.mesh.vertices[:, :2]
        outer = [int(np.argmin(np.hypot(*(xy - p).T))) for p in OUTER]
        inner = [v for v in range(len(xy)) if v not in outer]
        names = [picked.element_name(picked.VERTEX, v) for v in outer]
        chosen = pins.selected_vertices([(self.lifting, names)], self.plan)
        pinned = pins.pin(self.mesh, [], chosen, 2000.0)
        pinned = pins.pin(self.mesh, pinned, inner[:1], 3500.0)
        lifting.PinnedPoints = [App.Vector(*p) for p in pinned]
        self.doc.recompute()
        self.assertTrue(lifting.isValid(), lifting.getStatusString())
        z = points_array(lifting)[:, 2]
        # (within 0.01 mm: the free vertices pull at weight FREE_WEIGHT towards the plane
        # of the pins)
        np.testing.assert_allclose(z[outer + inner], [2000.0] * 3 + [3500.0] * 3,
                                   rtol=0, atol=1e-2)
        self.assertLessEqual(lifting.PlanarityMaxRel, 1e-9)

    def assert_refused(self, entries, *parts):
        with self.assertRaises(pins.PinError) as caught:
            pins.selected_vertices(entries, self.plan)
        for part in parts:
            self.assertIn(part, str(caught.exception))

    def test_what_is_not_a_plan_vertex_is_refused_saying_what_to_click(self):
        label = self.plan.Label
        self.assert_refused([], "Nothing is selected", "click vertices of " + label)
        self.assert_refused([(self.plan, ["Face2"])], "Face2 of", "is a face, not a vertex",
                            "click closer to a corner")
        self.assert_refused([(self.lifting, ["Edge5"])], "Edge5 of", "is an edge, not a vertex")
        self.assert_refused([(self.plan, [])], "is selected as a whole", "in the 3D view")
        self.assert_refused([(self.plan, ["Vertex6"])],
                            "Vertex6 of", f"{label} has 6 vertices (0 to 5)")
        self.assert_refused([(self.surface, ["Face1"])],
                            f"{self.surface.Label} is selected: click vertices of {label}")
        # a vertex of another plan's roof: not this plan's, though numbered alike
        self.assert_refused([(self.other, ["Vertex1"])], f"{self.other.Label} is selected")
        self.assert_refused([(self.plan, ["Vertex1"]), (self.plan, ["Face0"])], "Face0")

    def test_heights_must_be_finite_numbers_of_mm(self):
        for bad in (math.nan, math.inf, -math.inf, 1e31):
            with self.assertRaises(pins.PinError) as caught:
                pins.pin(self.mesh, [], [0], bad)
            self.assertIn("Height:", str(caught.exception))
            self.assertIn("not a finite height", str(caught.exception))
        with self.assertRaises(pins.PinError) as caught:
            pins.check_height("three metres")
        self.assertIn("'three metres' is not a number of mm", str(caught.exception))

    def test_a_height_typed_in_the_table_is_a_length(self):
        # a quantity of another kind was taken as mm: "2.4 kg" a height of 2.4 mm, "3 m^2"
        # one of 3,000,000 mm
        self.assertEqual(pins.height_from_text("2.4 m"), 2400.0)
        self.assertEqual(pins.height_from_text("2400 mm"), 2400.0)
        self.assertEqual(pins.height_from_text("3500"), 3500.0)
        for text in ("2.4 kg", "3 m^2", "45 deg"):
            with self.assertRaises(pins.PinError) as caught:
                pins.height_from_text(text, "Height of pin 2")
            self.assertIn(f"Height of pin 2: '{text}' is not a length", str(caught.exception))
        for text, said in (("high", "'high' is not a number of mm"),
                           ("1e400", "inf mm is not a finite height")):
            with self.assertRaises(pins.PinError) as caught:
                pins.height_from_text(text)
            self.assertIn(said, str(caught.exception))

    def test_element_names(self):
        self.assertEqual(picked.element_name(picked.VERTEX, 7), "Vertex7")
        self.assertEqual(picked.parse_element("Vertex7"), ("Vertex", 7))
        self.assertEqual(picked.parse_element("Face12"), ("Face", 12))
        self.assertEqual(picked.parse_element("Vertex"), (None, None))
        self.assertEqual(picked.parse_element("Shape"), (None, None))
