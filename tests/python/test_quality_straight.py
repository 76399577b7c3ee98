"""The quality report's nearly straight corners (QualityReport.straight_corner)."""
import io
import math

import numpy as np
import pytest

import facet
from facet.cli import _quality_lines
from facet.quality import DEFAULT_STRAIGHT_CORNER, quality


def _kinked(turn_deg, offset=(0.0, 0.0, 0.0)):
    """Face 0: a unit square. Face 1: a quad whose corner at vertex 5 turns its
    outline by `turn_deg` (convex there); face 2: a quad whose corner at vertex 10
    turns it as much the other way (reflex there)."""
    h = math.tan(math.radians(turn_deg))
    k = math.tan(math.radians(turn_deg / 2))
    pts = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
           (3, 0, 0), (4, 0, 0), (5, h, 0), (3, 1, 0),
           (6, -1, 0), (8, 0, 0), (7, -k, 0), (6, 0, 0)]
    pts = np.array(pts, dtype=float) + np.array(offset)
    return facet.PolyMesh.from_faces(pts, [[0, 1, 2, 3], [4, 5, 6, 7], [8, 9, 10, 11]])


@pytest.mark.parametrize("offset", [(0.0, 0.0, 0.0), (2.5e6, 1.2e6, 350.0)])
def test_a_corner_on_a_nearly_straight_line_is_found_convex_or_reflex(offset):
    q = quality(_kinked(2.0, offset))
    # the square's corners turn 90 degrees; each kinked quad's straightest turns 2
    assert q.straight_corner[0] == pytest.approx(90.0, abs=1e-6)
    assert q.straight_corner[1] == pytest.approx(2.0, abs=1e-6)
    assert q.straight_corner[2] == pytest.approx(2.0, abs=1e-6)
    assert list(q.straight_corner_faces) == [1, 2]
    assert np.array_equal(q.per_face("straight_corner"), q.straight_corner)
    d = q.as_dict()
    assert d["straight_corner_faces"] == 2
    assert d["straight_corner_face_indices"] == [1, 2]
    assert d["straightest_corner_deg"] == pytest.approx(2.0, abs=1e-6)
    assert d["straight_corner_deg"] == DEFAULT_STRAIGHT_CORNER
    assert d["input_straightest_corner_deg"] is None
    # the straight corners are not degenerate faces: the angles are all fine
    assert d["degenerate_faces"] == 0


def test_the_threshold_and_the_inputs_corners():
    bent, straight = _kinked(40.0), _kinked(2.0)
    q = quality(straight, input=bent, straight_corner=1.0)
    assert q.straight_corner_faces.size == 0
    q = quality(straight, input=bent, straight_corner=3.0)
    assert list(q.straight_corner_faces) == [1, 2]
    assert q.as_dict()["input_straightest_corner_deg"] == pytest.approx(40.0, abs=1e-9)
    for bad in (-1.0, 180.0, "x", float("nan")):
        with pytest.raises(facet.InputError, match="straight_corner must be a number"):
            quality(straight, straight_corner=bad)


def test_an_edge_of_no_length_is_not_a_straight_corner():
    # a quad whose last two corners coincide: degenerate for its short edge, and
    # the corners beside the empty edge do not count as straight
    pts = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (1, 1, 0)]
    q = quality(facet.PolyMesh.from_faces(pts, [[0, 1, 2, 3]]))
    assert q.straight_corner[0] == pytest.approx(90.0)
    assert q.straight_corner_faces.size == 0
    assert q.as_dict()["degenerate_faces"] == 1


def test_the_summary_line_names_the_straight_corners():
    out = io.StringIO()
    _quality_lines(out, quality(_kinked(2.0), input=_kinked(40.0)).as_dict())
    line = [t for t in out.getvalue().splitlines() if t.strip().startswith("straight")]
    assert line == ["  straight      2 faces with a corner within 5 deg of straight (the "
                    "straightest turns 2 deg; input 40 deg; first: 1, 2)"]
    out = io.StringIO()
    _quality_lines(out, quality(_kinked(40.0)).as_dict())
    assert "straight " not in out.getvalue()
