# SPDX-License-Identifier: LGPL-2.1-or-later
"""Unfolding: each panel laid flat with its engraving.

Every panel's outline is laid flat in its own frame (the first edge of its
face along +x; rotated so that the grain runs along +x when a grain
direction is given), with its ID placed at the pole of inaccessibility of
the outline (:func:`label_point`, the point polylabel finds), each bevel angle written beside its edge
and a grain arrow when a grain direction is set.

>>> drawings = unfold(panel_set, grain=(0, 0, 1))   # doctest: +SKIP
>>> drawings[0].label                              # doctest: +SKIP
'P-R01C01'
"""

import math
from dataclasses import dataclass, field

import numpy as np

from facet.panels import PanelError

__all__ = ["PartDrawing", "unfold"]


@dataclass
class PartDrawing:
    """A panel's flat drawing, in the part's own frame (model units).

    Attributes
    ----------
    id : str
    cut : numpy.ndarray
        (k, 2) the cut outline: the bottom face, counter-clockwise.
    top : numpy.ndarray
        (k, 2) the top face's outline seen from above (differs from `cut`
        where edges are bevelled or offset).
    footprint : numpy.ndarray
        (m, 2) the outline of the whole solid seen from above
        (counter-clockwise): what the sheet must hold; nesting uses it.
    label_position : tuple
        (x, y) where the ID goes, inside the outline.
    label_height : float
        Text height of the ID.
    bevels : list of tuple
        (text, x, y, angle_deg, height) per bevelled edge: the bevel angle
        written beside the edge, inside the part, along the edge.
    grain : tuple or None
        ((x0, y0), (x1, y1)) a grain arrow along +x, or None.
    rotation_deg : float
        Rotation applied to the panel's unfold frame (for the grain).
    """

    id: str
    cut: np.ndarray
    top: np.ndarray
    footprint: np.ndarray
    label_position: tuple
    label_height: float
    bevels: list = field(default_factory=list)
    grain: tuple = None
    rotation_deg: float = 0.0

    def polygon(self):
        """The footprint as a shapely Polygon."""
        from shapely.geometry import Polygon

        return Polygon(self.footprint)


def _rot(points, angle):
    c, s = math.cos(angle), math.sin(angle)
    return points @ np.array([[c, s], [-s, c]])


def _ccw(p):
    x, y = p[:, 0], p[:, 1]
    area = np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))
    return p if area >= 0 else p[::-1]


def _inside(poly, pts):
    """Even-odd test of points (m, 2) against a closed outline (k, 2)."""
    x, y = pts[:, 0:1], pts[:, 1:2]
    a, b = poly, np.roll(poly, -1, axis=0)
    ya, yb = a[:, 1][None, :], b[:, 1][None, :]
    crosses = (ya > y) != (yb > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        xc = a[:, 0][None, :] + (y - ya) * (b[:, 0] - a[:, 0])[None, :] / (yb - ya)
    return np.count_nonzero(crosses & (x < xc), axis=1) % 2 == 1


def _edge_distance(poly, pts):
    """Distance of points (m, 2) from the outline (k, 2)."""
    a = poly[None, :, :]
    d = (np.roll(poly, -1, axis=0) - poly)[None, :, :]
    p = pts[:, None, :]
    dd = np.maximum(np.sum(d * d, axis=2), 1e-300)
    t = np.clip(np.sum((p - a) * d, axis=2) / dd, 0.0, 1.0)
    q = a + t[:, :, None] * d
    return np.sqrt(np.min(np.sum((p - q) ** 2, axis=2), axis=1))


def label_point(outline, rounds=4, n=16):
    """The point inside an outline farthest from its edges (the pole of
    inaccessibility, as shapely's polylabel finds it), by a grid search
    refined around the best point; vectorised, for thousands of parts.

    Returns
    -------
    ((x, y), depth)
    """
    poly = np.asarray(outline, dtype=float)
    lo, hi = poly.min(axis=0), poly.max(axis=0)
    centre, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
    best, depth = None, -1.0
    for _ in range(rounds):
        u = np.linspace(-1.0, 1.0, n)
        gx, gy = np.meshgrid(centre[0] + u * half[0], centre[1] + u * half[1])
        pts = np.column_stack([gx.ravel(), gy.ravel()])
        inside = _inside(poly, pts)
        if inside.any():
            pts = pts[inside]
            dist = _edge_distance(poly, pts)
            k = int(np.argmax(dist))
            if dist[k] > depth:
                best, depth = pts[k], float(dist[k])
        if best is None:
            break
        centre, half = best, half * (2.5 / (n - 1))
    if best is None:  # degenerate: fall back to the vertex mean
        best = poly.mean(axis=0)
        depth = 0.0
    return (float(best[0]), float(best[1])), depth


def unfold(panel_set, grain=None, label_height=None, bevel_tolerance_deg=1e-6):
    """Flat drawings of every panel.

    Parameters
    ----------
    panel_set : facet.panels.PanelSet
    grain : sequence of 3 floats, optional
        A direction in model space (e.g. (0, 0, 1) for vertical grain).
        Each part is turned so that this direction, projected into its
        plane, runs along +x; nesting must then keep rotations off.
    label_height : float, optional
        Largest ID text height; by default a tenth of the square root of the
        part's area. Smaller where the outline is too narrow for the text.
    bevel_tolerance_deg : float
        Bevels smaller than this are not written.

    Returns
    -------
    list of PartDrawing
        In panel order.

    Raises
    ------
    PanelError
        A grain direction that is zero or perpendicular to a panel.
    """
    g = None
    if grain is not None:
        g = np.asarray(grain, dtype=float).reshape(-1)
        if g.shape != (3,) or not np.all(np.isfinite(g)) or np.linalg.norm(g) == 0:
            raise PanelError(f"grain must be a non-zero 3D direction, not {grain!r}")
        g = g / np.linalg.norm(g)
    drawings = []
    for p in panel_set.panels:
        angle = 0.0
        if g is not None:
            R = p.frame[:, :3]
            gl = R @ g
            if math.hypot(gl[0], gl[1]) < 1e-6:
                raise PanelError(f"panel {p.id}: the grain direction is perpendicular to it")
            angle = math.atan2(gl[1], gl[0])
        cut = _rot(p.flat_bottom, angle)
        top = _rot(p.flat_top, angle)
        fp = p.footprint()
        if fp.geom_type != "Polygon":
            fp = fp.convex_hull
        foot = _ccw(_rot(np.asarray(fp.exterior.coords)[:-1], angle))
        (lx, ly), depth = label_point(cut)
        area = 0.5 * abs(np.dot(cut[:, 0], np.roll(cut[:, 1], -1)) -
                         np.dot(cut[:, 1], np.roll(cut[:, 0], -1)))
        h = label_height if label_height is not None else 0.1 * math.sqrt(area)
        # fit the text: width about 0.6 h per character, height within the depth
        h = min(h, 1.2 * depth, 1.6 * depth / max(1.0, 0.3 * len(p.id)))
        bevels = []
        k = len(cut)
        bh = 0.6 * h
        for i in range(k):
            b = p.bevel_deg[i]
            if abs(b) < bevel_tolerance_deg:
                continue
            a, c = cut[i], cut[(i + 1) % k]
            d = c - a
            length = float(np.hypot(*d))
            if length == 0:
                continue
            u = d / length
            n_in = np.array([-u[1], u[0]])  # inside of a counter-clockwise outline
            mid = 0.5 * (a + c) + n_in * (1.5 * bh)
            text = f"{b:+.1f}\u00b0"
            bevels.append((text, float(mid[0]), float(mid[1]),
                           math.degrees(math.atan2(u[1], u[0])), bh))
        arrow = None
        if g is not None:
            x0, y0 = lx, ly - 1.5 * h
            length = 0.25 * (cut[:, 0].max() - cut[:, 0].min())
            arrow = ((x0 - 0.5 * length, y0), (x0 + 0.5 * length, y0))
        drawings.append(PartDrawing(id=p.id, cut=cut, top=top, footprint=foot,
                                    label_position=(lx, ly),
                                    label_height=float(h), bevels=bevels, grain=arrow,
                                    rotation_deg=math.degrees(angle)))
    return drawings
