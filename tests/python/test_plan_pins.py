# SPDX-License-Identifier: LGPL-2.1-or-later
"""facet.plan.pin_vertices and match_tolerance: the plan vertex at each pinned point."""

import math

import numpy as np
import pytest

from facet.errors import InputError
from facet.plan import match_tolerance, pin_vertices, plan_from_segments

SQUARE = [((0, 0), (4000, 0)), ((4000, 0), (4000, 3000)), ((4000, 3000), (0, 3000)),
          ((0, 3000), (0, 0)), ((0, 0), (4000, 3000))]


def test_each_point_finds_its_vertex_within_the_tolerance():
    plan = plan_from_segments(SQUARE)
    xy = plan.mesh.vertices[:, :2]
    far = (2000.0, 1500.0, 7.0)  # in a face, on no vertex
    points = [tuple(xy[2]) + (1.0,), far, (xy[0, 0] + 0.3, xy[0, 1], 2.0)]
    assert list(pin_vertices(plan, points, tolerance=0.5)) == [2, -1, 0]
    assert list(pin_vertices(plan, points, tolerance=0.1)) == [2, -1, -1]
    # x, y alone do too; none at all: an empty array
    assert list(pin_vertices(plan.mesh, [tuple(xy[3])], tolerance=1e-9)) == [3]
    assert pin_vertices(plan, [], tolerance=1.0).shape == (0,)


def test_a_point_with_nan_is_refused():
    # (naming which of them: it said "a pinned point")
    plan = plan_from_segments(SQUARE)
    with pytest.raises(InputError, match=r"pinned point 2 of 2 has a NaN or infinite x or y "
                                         r"\(nan, 0\.0\)"):
        pin_vertices(plan, [(0.0, 0.0, 1.0), (math.nan, 0.0, 1.0)], tolerance=1.0)


def test_match_tolerance_is_the_snap_or_a_millionth_of_the_plan():
    plan = plan_from_segments(SQUARE)
    assert match_tolerance(plan, 2.5) == 2.5
    assert match_tolerance(plan) == pytest.approx(4000 * 1e-6, rel=1e-15)
    assert match_tolerance(plan, 0.0) == match_tolerance(plan)
    assert np.isfinite(match_tolerance(plan, -1.0))
