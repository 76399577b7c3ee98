# SPDX-License-Identifier: LGPL-2.1-or-later
"""Unfolding: each panel laid flat with its engraving.

Every panel's outline is laid flat in its own frame (the first edge of its
face along +x; rotated so that the grain runs along +x when a grain
direction is given), with its ID at the centroid of the outline or its pole of
inaccessibility (:func:`label_point`, the point polylabel finds), whichever holds the
larger text on the part's top face (where it is engraved; the centroid where both hold
it), each bevel angle written
beside its edge, on that face, nearer that edge than any other and clear of the ID and
the other angles, and a grain arrow inside the part when a grain direction is set.

>>> drawings = unfold(panel_set, grain=(0, 0, 1))   # doctest: +SKIP
>>> drawings[0].label                              # doctest: +SKIP
'P-R01C01'
"""

import math
from dataclasses import dataclass, field

import numpy as np

from facet.errors import report_progress
from facet.panels import PanelError

__all__ = ["PartDrawing", "unfold", "small_text_warnings", "MIN_TEXT_MM"]

#: The least text height, millimetres, that an engraver cuts legibly: texts placed smaller
#: (beside a short edge, on a narrow part) are warned about (:func:`small_text_warnings`).
MIN_TEXT_MM = 3.0


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
    bevels_left_out : list of str
        The bevel angles of edges beside which no text fits inside the part (a
        short edge at a sharp corner): left out of the drawing, not written
        outside the part (the schedule's bevel_deg gives every angle).
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
    bevels_left_out: list = field(default_factory=list)

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
    """Even-odd test of points (P, m, 2) against closed outlines (P, k, 2)."""
    x, y = pts[:, :, None, 0], pts[:, :, None, 1]
    a, b = poly[:, None, :, :], np.roll(poly, -1, axis=1)[:, None, :, :]
    ya, yb = a[..., 1], b[..., 1]
    crosses = (ya > y) != (yb > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        xc = a[..., 0] + (y - ya) * (b[..., 0] - a[..., 0]) / (yb - ya)
    return np.count_nonzero(crosses & (x < xc), axis=2) % 2 == 1


def _edge_distance(poly, pts):
    """Distance of points (P, m, 2) from the outlines (P, k, 2): (P, m)."""
    a = poly[:, None, :, :]
    d = (np.roll(poly, -1, axis=1) - poly)[:, None, :, :]
    p = pts[:, :, None, :]
    dd = np.maximum(np.sum(d * d, axis=3), 1e-300)
    t = np.clip(np.sum((p - a) * d, axis=3) / dd, 0.0, 1.0)
    q = a + t[..., None] * d
    return np.sqrt(np.min(np.sum((p - q) ** 2, axis=3), axis=2))


def _convex(poly):
    """(P, k, 2) -> (P,) bool: counter-clockwise, strictly convex outlines
    (every turn to the left, once around)."""
    d = np.roll(poly, -1, axis=1) - poly
    dn = np.roll(d, -1, axis=1)
    cross = d[..., 0] * dn[..., 1] - d[..., 1] * dn[..., 0]
    turn = np.arctan2(cross, np.sum(d * dn, axis=2))
    return (cross > 0).all(axis=1) & (np.abs(turn.sum(axis=1) - 2 * np.pi) < 1e-6)


def _convex_depth(poly, pts):
    """Distance of points (P, m, 2) from convex counter-clockwise outlines
    (P, k, 2) when inside, else -1: the smallest distance to an edge's line."""
    d = np.roll(poly, -1, axis=1) - poly
    normal = np.stack([d[..., 1], -d[..., 0]], axis=2)  # outward
    normal /= np.maximum(np.sqrt(np.sum(normal * normal, axis=2)), 1e-300)[..., None]
    offset = np.sum(normal * poly, axis=2)  # (P, k)
    depth = (offset[:, None, :] - np.einsum("pmi,pki->pmk", pts, normal)).min(axis=2)
    return np.where(depth > 0, depth, -1.0)


def label_points(outlines, rounds=4, n=16):
    """The point inside each outline farthest from its edges (the pole of
    inaccessibility, as shapely's polylabel finds it), by a grid search
    refined around the best point; vectorised over outlines of the same
    vertex count, for thousands of parts.

    Parameters
    ----------
    outlines : list of (k, 2) arrays

    Returns
    -------
    list of ((x, y), depth)
    """
    out = [None] * len(outlines)
    groups = {}
    for i, o in enumerate(outlines):
        groups.setdefault(len(o), []).append(i)
    u = np.linspace(-1.0, 1.0, n)
    gx, gy = np.meshgrid(u, u)
    grid = np.column_stack([gx.ravel(), gy.ravel()])  # (m, 2)
    for k, members in groups.items():
        for c0 in range(0, len(members), 512):
            idx = members[c0:c0 + 512]
            poly = np.array([np.asarray(outlines[i], dtype=float) for i in idx])  # (P, k, 2)
            lo, hi = poly.min(axis=1), poly.max(axis=1)
            centre, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
            best = poly.mean(axis=1)
            depth = np.full(len(idx), -1.0)
            # inside a convex outline the distance to the outline is the
            # smallest distance to an edge's line: much cheaper
            convex = _convex(poly)
            for _ in range(rounds):
                pts = centre[:, None, :] + grid[None, :, :] * half[:, None, :]
                dist = np.empty(pts.shape[:2])
                if convex.any():
                    dist[convex] = _convex_depth(poly[convex], pts[convex])
                if not convex.all():
                    other = ~convex
                    inside = _inside(poly[other], pts[other])
                    dist[other] = np.where(inside, _edge_distance(poly[other], pts[other]), -1.0)
                j = np.argmax(dist, axis=1)
                found = dist[np.arange(len(idx)), j]
                better = found > depth
                best[better] = pts[np.arange(len(idx)), j][better]
                depth[better] = found[better]
                centre = best.copy()
                half = half * (2.5 / (n - 1))
            for m, i in enumerate(idx):
                out[i] = ((float(best[m, 0]), float(best[m, 1])), float(max(depth[m], 0.0)))
    return out


#: A character's width as a fraction of the text height, generously: a DXF text's height
#: is its capitals' (an ID measures 0.78-0.85 of it per character in ezdxf's font, the
#: fallback for AutoCAD's txt.shx); SVG and PNG text is narrower.
_CHAR_WIDTH = 0.9


def _half_width(n_chars, height):
    """Half the width of a text of ``n_chars`` characters ``height`` high, as the texts
    are fitted: ``_CHAR_WIDTH`` of the height per character and a tenth of it at each end."""
    return 0.5 * (_CHAR_WIDTH * n_chars + 0.2) * height


def _label_box(x, y, height, n_chars):
    """The box of an ID centred at (x, y): 0.9 of its height above and below its middle,
    for the descenders (below the capitals' middle: 0.5 of them and the descenders)."""
    from shapely.geometry import box

    half_w, half_h = _half_width(n_chars, height), 0.9 * height
    return box(x - half_w, y - half_h, x + half_w, y + half_h)


#: Where along its edge a bevel text may sit, as fractions of the edge from its start: the
#: middle first.
_BEVEL_ALONG = (0.5, 0.4, 0.6, 0.3, 0.7)


def _place_bevel(inside, outline, i, a, u, length, text, height, taken=(), inset=0.0):
    """Where the bevel text of edge ``i`` of an outline (its start ``a``, direction ``u``,
    ``length``) goes and how high, at most 0.6 ``height`` and no longer than the edge: its
    box (``_CHAR_WIDTH`` of the height per character, a fifth more; middle-aligned, as the
    DXF writes it) 1.5 of its height from the edge, inside the part and no nearer any other
    edge of the outline than its own, so that it is read as that edge's. Beside a short
    edge at a sharp corner the middle is too near the neighbouring edge (on heart_planar 45
    of 1,510 texts were nearer it, 20 ran outside the part): a smaller text, then a place
    along the edge nearer its wider end. The text, with its descenders (0.9 of its height
    below its middle, towards its edge), clears the boxes ``taken`` (the ID's, the other
    bevel texts'), which it was written over (conical1 planarized: 623 of 4,188). Returns
    (middle, height, the text's box); None where none fits (the smallest was put at the
    edge's middle, outside the part: a 0.03 mm text 0.08 mm past the cut outline of a
    planarized hex mesh's part). ``inside``: the prepared face the texts go on (the cut
    outline within the top face), ``outline``: the cut outline's edges as LineStrings;
    ``inset``: how far inside the edge the face the text is engraved on begins (the top
    face, where the bevel narrows it), which the text keeps off. On the sheet the text is
    turned half a turn about its middle where it would read upside down
    (``facet.cutsheets._upright``): a bevel angle ("+12.5\u00b0") has no descender, its
    letters reach 0.52 of its height either side of its middle, so turned it takes the
    same place."""
    from shapely.geometry import Polygon

    ux, uy = float(u[0]), float(u[1])
    nx, ny = -uy, ux  # inside of a counter-clockwise outline

    def rectangle(mid, half_w, below, above):  # (plain floats: numpy's were half the time)
        mx, my = mid
        return Polygon([(mx + sx * half_w * ux + sy * nx, my + sx * half_w * uy + sy * ny)
                        for sx, sy in ((-1, -below), (1, -below), (1, above), (-1, above))])

    def middle(t, bh):
        along, off = t * length, inset + 1.5 * bh
        return (float(a[0]) + along * ux + off * nx, float(a[1]) + along * uy + off * ny)

    bh = min(0.6 * height, 0.8 * length / (_CHAR_WIDTH * len(text)))
    others = [edge for j, edge in enumerate(outline) if j != i]
    for attempt in range(5):
        if attempt:
            bh *= 0.5
        half_w = _half_width(len(text), bh)
        for along in _BEVEL_ALONG:
            if not (half_w <= along * length and half_w <= (1.0 - along) * length):
                continue  # (past the edge's end)
            mid = middle(along, bh)
            # the box is inset + bh from its own edge
            box = rectangle(mid, half_w, 0.5 * bh, 0.5 * bh)
            if not inside.contains(box) or any(edge.distance(box) <= inset + bh
                                               for edge in others):
                continue
            text_box = rectangle(mid, half_w, 0.9 * bh, 0.5 * bh)
            if not any(text_box.intersects(other) for other in taken):
                return np.array(mid), bh, text_box
    return None


def _fit_label(polygon, inside, pole, height, n_chars):
    """Where an ID of ``n_chars`` characters goes and how high, at most ``height``: its box
    (``_CHAR_WIDTH`` of the height per character wide and a tenth of the height at each
    end; 0.9 of the height above and below its middle, for the descenders) inside the
    outline. At the centroid or the pole of inaccessibility, whichever takes the larger
    text: the pole of a long strip lies near one end, where a text as high as the strip ran
    past the end, and off the sheet. The centroid where both take it: it moves with the
    outline, while the pole is picked among nearly equal depths across a near-rectangle's
    middle (from the pole, a 1e-9 change of the model moved 118 of conical1's 1,080 IDs,
    the wave facade's by up to 117 mm). ``polygon``: the outline's shapely Polygon,
    ``inside``: the same prepared."""
    from shapely.geometry import Point

    centroid = polygon.centroid
    candidates = ([(centroid.x, centroid.y)] if inside.contains(Point(centroid)) else []) + [pole]

    def fits(point, h):
        return inside.contains(_label_box(point[0], point[1], h, n_chars))

    best = (pole, 0.0)
    for point in candidates:
        if fits(point, height):
            h = height
        else:  # the largest height that fits, by bisection
            lo, hi = 0.0, height
            for _ in range(12):
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if fits(point, mid) else (lo, mid)
            h = lo
        if h > best[1]:
            best = ((float(point[0]), float(point[1])), h)
        if h == height:
            break
    if best[1] == 0.0:  # (no box fits even 4096 times smaller: the pole is on an edge)
        best = (pole, height / 4096.0)
    return best


def _place_grain(inside, label_box, lx, ly, height, width):
    """Where the grain arrow goes: ((x0, y0), (x1, y1)) along +x, a quarter of the part's
    ``width`` long, 1.5 ``height`` below the ID at (``lx``, ``ly``), else above it, else
    half and a quarter as long; with its head (as the DXF draws it, 0.075 of the length
    either side) inside the part and clear of the ID's ``label_box``. Below the ID it ran
    out of 8 of heart_planar's 400 parts (grain 1,0,0), engraved on the sheet beyond the
    part, where another part may lie. Where none fits, the first tried. Returns the arrow
    and the box it takes."""
    from shapely.geometry import box

    def placed(fraction, side):
        half, y0 = 0.5 * fraction * width, ly + side * 1.5 * height
        return ((lx - half, y0), (lx + half, y0)), box(lx - half, y0 - 0.15 * half,
                                                       lx + half, y0 + 0.15 * half)

    for fraction in (0.25, 0.125, 0.0625):
        for side in (-1, 1):
            arrow, shape = placed(fraction, side)
            if inside.contains(shape) and not shape.intersects(label_box):
                return arrow, shape
    return placed(0.25, -1)


def label_point(outline, rounds=4, n=16):
    """:func:`label_points` for one outline: ((x, y), depth)."""
    return label_points([outline], rounds, n)[0]


def _convex_footprints(panels):
    """The footprint (what :meth:`facet.panels.Panel.footprint` gives) of each
    panel whose flat top and bottom are convex, vectorised; None for the
    others.

    The solid of such a panel is convex, so its footprint is the convex hull
    of its corners: along each edge the outer of the top edge and the bottom
    edge (they are parallel: the side face is planar and meets two parallel
    planes), and where the next edge's outer line is on the other face, the
    side edge between them. Returns a list of (m, 2) arrays or None.
    """
    out = [None] * len(panels)
    groups = {}
    for i, p in enumerate(panels):
        groups.setdefault(len(p.flat_bottom), []).append(i)
    for k, idx in groups.items():
        bottom = np.array([panels[i].flat_bottom for i in idx], dtype=float).reshape(-1, k, 2)
        top = np.array([panels[i].flat_top for i in idx], dtype=float).reshape(-1, k, 2)
        if top.shape != bottom.shape:
            continue
        scale = np.maximum(np.abs(bottom).max(axis=(1, 2)), 1.0)
        db = np.roll(bottom, -1, axis=1) - bottom
        dt = np.roll(top, -1, axis=1) - top
        lb = np.sqrt(np.sum(db * db, axis=2))
        lt = np.sqrt(np.sum(dt * dt, axis=2))
        parallel = (np.abs(db[..., 0] * dt[..., 1] - db[..., 1] * dt[..., 0])
                    <= 1e-9 * lb * lt) & (np.sum(db * dt, axis=2) > 0)
        ok = _convex(bottom) & _convex(top) & parallel.all(axis=1)
        normal = np.stack([db[..., 1], -db[..., 0]], axis=2) / np.maximum(lb, 1e-300)[..., None]
        # the top's edge is the outer one where it lies farther out
        use_top = (np.sum(normal * (top - bottom), axis=2) > 1e-9 * scale[:, None])
        prev_top = np.roll(use_top, 1, axis=1)  # the edge ending at corner j
        for m in np.flatnonzero(ok):
            pts = []
            for j in range(k):
                pts.append(top[m, j] if prev_top[m, j] else bottom[m, j])
                if use_top[m, j] != prev_top[m, j]:
                    pts.append(top[m, j] if use_top[m, j] else bottom[m, j])
            out[idx[m]] = np.array(pts)
    return out


#: Parts unfolded between two progress calls.
PROGRESS_EVERY = 64


def unfold(panel_set, grain=None, label_height=None, bevel_tolerance_deg=1e-6,
           progress=None):
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
        Bevels smaller than this are not written, nor any whose text (one decimal)
        reads 0.0.
    progress : callable, optional
        ``progress(done, total)`` in parts, every :data:`PROGRESS_EVERY` and at the end
        (5,041 parts took 2.4 s); True cancels (:class:`facet.errors.Cancelled`,
        "unfolding cancelled").

    Returns
    -------
    list of PartDrawing
        In panel order.

    Raises
    ------
    PanelError
        A grain direction that is zero or perpendicular to a panel.
    """
    from shapely.geometry import LineString, Polygon
    from shapely.prepared import prep

    g = None
    if grain is not None:
        g = np.asarray(grain, dtype=float).reshape(-1)
        if g.shape != (3,) or not np.all(np.isfinite(g)) or np.linalg.norm(g) == 0:
            raise PanelError(f"grain must be a non-zero 3D direction, not {grain!r}")
        g = g / np.linalg.norm(g)
    drawings = []
    angles = []
    for p in panel_set.panels:
        angle = 0.0
        if g is not None:
            gl = p.frame[:, :3] @ g
            if math.hypot(gl[0], gl[1]) < 1e-6:
                raise PanelError(f"panel {p.id}: the grain direction is perpendicular to it")
            # the grain lies at this angle in the panel's frame: turned back by it, it
            # runs along +x
            angle = -math.atan2(gl[1], gl[0])
        angles.append(angle)
    labels = label_points([_rot(p.flat_bottom, a) for p, a in zip(panel_set.panels, angles)])
    convex_feet = _convex_footprints(panel_set.panels)
    total = len(panel_set.panels)
    for k, (p, angle, ((lx, ly), depth), fp) in enumerate(
            zip(panel_set.panels, angles, labels, convex_feet)):
        if k % PROGRESS_EVERY == 0:
            report_progress(progress, k, total, "unfolding")
        cut = _rot(p.flat_bottom, angle)
        top = _rot(p.flat_top, angle)
        if fp is None:
            fp = p.footprint()
            if fp.geom_type != "Polygon":
                fp = fp.convex_hull
            fp = np.asarray(fp.exterior.coords)[:-1]
        foot = _ccw(_rot(fp, angle))
        area = 0.5 * abs(np.dot(cut[:, 0], np.roll(cut[:, 1], -1)) -
                         np.dot(cut[:, 1], np.roll(cut[:, 0], -1)))
        h = label_height if label_height is not None else 0.1 * math.sqrt(area)
        shape = Polygon(cut)
        # the texts are engraved from above, on the top face: where a bevel narrows it they
        # ran off it, onto the slope (heart_planar 20 mm mitred: 34 of 1,510 bevel texts and
        # 5 of 400 IDs), so they go inside the part's cut and top outlines both
        face, insets = shape, np.zeros(len(cut))
        if len(top) == len(cut) and Polygon(top).is_valid:
            both = shape.intersection(Polygon(top))
            if both.geom_type == "Polygon" and not both.is_empty:
                face = both
                d = np.roll(cut, -1, axis=0) - cut
                normal = np.stack([-d[:, 1], d[:, 0]], axis=1)  # inward, unnormalised
                insets = np.maximum(np.sum((top - cut) * normal, axis=1)
                                    / np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-300), 0.0)
        inside = prep(face)
        outline = [LineString([cut[i], cut[(i + 1) % len(cut)]]) for i in range(len(cut))]
        (lx, ly), h = _fit_label(face, inside, (lx, ly), min(h, 1.2 * depth), len(p.id))
        bevels, left_out = [], []
        # the ID's box as _fit_label fits it: the bevel texts keep off it and each other
        taken = [_label_box(lx, ly, h, len(p.id))]
        arrow = None
        if g is not None:
            width = cut[:, 0].max() - cut[:, 0].min()
            arrow, arrow_box = _place_grain(inside, taken[0], lx, ly, h, width)
            taken.append(arrow_box)
        k = len(cut)
        for i in range(k):
            b = p.bevel_deg[i]
            text = f"{b:+.1f}\u00b0"
            # (a bevel that reads "+0.0°" or "-0.0°" is not worth engraving)
            if abs(b) < bevel_tolerance_deg or text[1:] == "0.0\u00b0":
                continue
            a, c = cut[i], cut[(i + 1) % k]
            d = c - a
            length = float(np.hypot(*d))
            if length == 0:
                continue
            u = d / length
            placed = _place_bevel(inside, outline, i, a, u, length, text, h, taken,
                                  float(insets[i]))
            if placed is None:
                left_out.append(text)
                continue
            mid, bh, text_box = placed
            taken.append(text_box)
            bevels.append((text, float(mid[0]), float(mid[1]),
                           math.degrees(math.atan2(u[1], u[0])), bh))
        drawings.append(PartDrawing(id=p.id, cut=cut, top=top, footprint=foot,
                                    label_position=(lx, ly),
                                    label_height=float(h), bevels=bevels, grain=arrow,
                                    rotation_deg=math.degrees(angle), bevels_left_out=left_out))
    report_progress(progress, total, total, "unfolding")
    return drawings


def small_text_warnings(drawings, mm_per_unit=1.0, min_mm=MIN_TEXT_MM, units=None):
    """Warnings, one per kind of text (IDs, bevel angles), when some are under `min_mm`
    millimetres high: a text is made as large as its place on the part allows, and beside
    a short edge or on a narrow part that can be too small to engrave (heart_planar in
    metres, mitred at 5 mm with a 10 mm gap: 23 of 1,517 bevel texts, down to 0.62 mm),
    which went unsaid. Each names the smallest and the parts that have such texts. One
    more counts the bevel texts left out for want of room (:attr:`PartDrawing.bevels_left_out`).

    Parameters
    ----------
    drawings : list of PartDrawing
    mm_per_unit : float
        Millimetres per model unit (:data:`facet.cutsheets.LENGTH_UNITS`).
    min_mm : float
    units : str, optional
        The unit the warnings give the heights in when it is an imperial one ("in",
        "ft"; the least in mm too: "under 0.118 in (3 mm) high"), as a user in inches
        reads them (they said "the smallest 2.87 mm" of a model in inches); else mm.
        ``facet panels`` passes the model's unit, FreeCAD's CutSheets (its model in mm)
        "in" when FreeCAD shows inches.

    Returns
    -------
    list of str
    """
    from facet.report import count_noun, first_names

    from facet.cutsheets import length_unit

    limit = min_mm / mm_per_unit
    said, said_mm = (units, length_unit(units)[0]) if units in ("in", "ft") else ("mm", 1.0)
    least = (f"{min_mm:g} mm" if said == "mm"
             else f"{min_mm / said_mm:.3g} {said} ({min_mm:g} mm)")

    def smallest(h):
        return f"{h * mm_per_unit / said_mm:.3g} {said}"
    found = {"ID": [], "bevel": []}
    for d in drawings:
        if d.label_height < limit:
            found["ID"].append((d.label_height, d.id))
        found["bevel"] += [(bh, d.id) for *_, bh in d.bevels if bh < limit]
    totals = {"ID": len(drawings), "bevel": sum(len(d.bevels) for d in drawings)}
    advice = {"ID": "an ID is a tenth of its part's size at most, less on a narrow part (a "
                    "shorter ID prefix helps there)",
              "bevel": "beside short edges; the schedule's bevel_deg gives every angle"}
    out = []
    for kind, small in found.items():
        if not small:
            continue
        height, pid = min(small)
        parts = list(dict.fromkeys(p for _, p in small))
        shown = first_names(parts, 5)
        noun = "part ID" if kind == "ID" else "bevel angle text"
        out.append(f"{len(small)} of {count_noun(totals[kind], noun)} "
                   f"{'is' if len(small) == 1 else 'are'} under {least} high, too small to "
                   f"engrave legibly (the smallest {smallest(height)}, on {pid}; on "
                   f"{count_noun(len(parts), 'part')}: {shown}): {advice[kind]}")
    left_out = [d.id for d in drawings for _ in d.bevels_left_out]
    if left_out:
        one = len(left_out) == 1
        out.append(f"{count_noun(len(left_out), 'bevel angle text')} found no room inside "
                   f"{'its part' if one else 'their parts'} and {'is' if one else 'are'} left "
                   f"out ({first_names(list(dict.fromkeys(left_out)), 5)}): beside a short "
                   "edge at a sharp corner; the schedule's bevel_deg gives every angle")
    return out
