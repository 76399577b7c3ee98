# SPDX-License-Identifier: LGPL-2.1-or-later
"""Part types: panels that are the same part, within a tolerance.

A facade's cost follows its number of different parts (templates, jigs,
glass orders), not only its panels: on a cylinder or a translational surface
hundreds of panels can be one part. Two panels are the same type when one
solid, turned and moved in its plane, lies on the other: every corner of the
cut (bottom) and top outlines within the tolerance of the other's once the
one is fitted to the other (least squares). A mirror image is another type,
also where turning the panel over makes it (square edges): a finish, a
coating or a bevel has a side.
Corners on a straight edge (a T-junction) do not make a type of their own.
"""

import bisect
from collections import Counter

import numpy as np

#: Default tolerance, millimetres: within the cutting tolerance of glass and
#: of sheet metal.
DEFAULT_TOL_MM = 0.5


def check_tolerance(tol, units=None):
    """``tol`` as a float when it is a part type tolerance (a finite length >= 0, model
    units); else an :class:`facet.errors.InputError` (a ValueError) that names it and,
    when given, the model's length unit ``units``: "the part type tolerance must be a
    finite length >= 0, not -1 mm"."""
    from .errors import InputError

    try:
        value = float(tol)
    except (TypeError, ValueError):
        raise InputError(f"the part type tolerance must be a finite length >= 0, not "
                         f"{tol!r}") from None
    if not (value >= 0.0 and np.isfinite(value)):
        raise InputError(f"the part type tolerance must be a finite length >= 0, not "
                         f"{value:g}{' ' + units if units else ''}")
    return value


def _shape(panel, tol):
    """(k, 4) the panel's bottom and top corners side by side, its corners on
    a straight edge (within tol / 2 of its neighbours' line, in both
    outlines) left out: their neighbours' edges are one cut."""
    pts = np.hstack([np.asarray(panel.flat_bottom, float), np.asarray(panel.flat_top, float)])
    while len(pts) > 3:
        prev, nxt = np.roll(pts, 1, axis=0), np.roll(pts, -1, axis=0)
        straight = np.ones(len(pts), bool)
        for o in (0, 2):
            a, b, c = prev[:, o:o + 2], pts[:, o:o + 2], nxt[:, o:o + 2]
            ac = c - a
            cross = np.abs(ac[:, 0] * (b - a)[:, 1] - ac[:, 1] * (b - a)[:, 0])
            straight &= cross <= 0.5 * tol * np.linalg.norm(ac, axis=1)
        if not straight.any():
            break
        pts = np.delete(pts, int(np.flatnonzero(straight)[0]), axis=0)
    return pts


def _edge_lengths(shape):
    """The bottom and the top outline's edge lengths, each sorted: within 2 tol of
    another panel's where every corner is within tol of its match."""
    return tuple(np.concatenate([np.sort(np.linalg.norm(
        np.diff(shape[:, o:o + 2], axis=0, append=shape[:1, o:o + 2]), axis=1))
        for o in (0, 2)]).tolist())


def _fits(p, q, tol):
    """Whether shape q, its corners taken from some start in the same turning
    order, lies on shape p within tol after a rotation and a move in the
    plane."""
    k = len(p)
    pp = np.vstack([p[:, :2], p[:, 2:]])
    pc = pp - pp.mean(axis=0)
    for s in range(k):
        r = np.roll(q, -s, axis=0)
        qq = np.vstack([r[:, :2], r[:, 2:]])
        qc = qq - qq.mean(axis=0)
        # the rotation that best turns pc onto qc (2-D Kabsch)
        angle = np.arctan2(np.sum(pc[:, 0] * qc[:, 1] - pc[:, 1] * qc[:, 0]),
                           np.sum(pc[:, 0] * qc[:, 0] + pc[:, 1] * qc[:, 1]))
        c, sn = np.cos(angle), np.sin(angle)
        turned = np.column_stack([c * pc[:, 0] - sn * pc[:, 1], sn * pc[:, 0] + c * pc[:, 1]])
        if np.max(np.linalg.norm(turned - qc, axis=1)) <= tol:
            return True
    return False


def part_types(panels, tol, progress=None):
    """The part type of every panel.

    Parameters
    ----------
    panels : sequence of facet.panels.Panel
        Panels of one thickness (a PanelSet's).
    tol : float
        Largest distance between matching corners of two panels of one type,
        model units, >= 0.
    progress : callable, optional
        ``progress(done, total)`` every 256 panels and at the end; returning
        True cancels (raises :class:`facet.Cancelled`).

    Raises
    ------
    facet.errors.InputError
        A ``tol`` NaN, infinite, negative or no number (:func:`check_tolerance`).

    Returns
    -------
    list of str
        Per panel, its type: ``"T1"`` the type with the most panels, then
        ``"T2"``... (ties in the order of their first panel).
    """
    from .errors import Cancelled

    tol = check_tolerance(tol)
    panels = list(panels)
    first = []  # per type, its first panel's index
    shapes = []  # per type, its first panel's shape and edge lengths
    windows = {}  # corners -> sorted [(perimeter, type)]
    found = []
    for i, panel in enumerate(panels):
        shape = _shape(panel, tol)
        k, lengths = len(shape), _edge_lengths(shape)
        # matching corners within tol: each edge within 2 tol, the perimeter within 2 k tol
        per, slack = sum(lengths[:k]), 2 * tol + 1e-12 * max(lengths)
        window = windows.setdefault(k, [])
        lo = bisect.bisect_left(window, (per - k * slack, -1))
        hit = None
        for other_per, t in window[lo:]:
            if other_per > per + k * slack:
                break
            other, other_lengths = shapes[t]
            if (all(abs(a - b) <= slack for a, b in zip(lengths, other_lengths))
                    and _fits(other, shape, tol)):
                hit = t
                break
        if hit is None:
            hit = len(first)
            first.append(i)
            shapes.append((shape, lengths))
            bisect.insort(window, (per, hit))
        found.append(hit)
        if (progress is not None and ((i & 255) == 255 or i + 1 == len(panels))
                and progress(i + 1, len(panels))):
            raise Cancelled("part types cancelled")
    counts = np.bincount(np.asarray(found, dtype=np.int64), minlength=len(first))
    order = sorted(range(len(first)), key=lambda t: (-counts[t], first[t]))
    name = {t: f"T{n + 1}" for n, t in enumerate(order)}
    return [name[t] for t in found]


def type_counts(types):
    """{type: how many panels are of it}, from T1 (the most) on."""
    counts = Counter(types)
    return {t: counts[t] for t in sorted(counts, key=lambda t: int(t[1:]))}
