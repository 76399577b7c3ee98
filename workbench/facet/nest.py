# SPDX-License-Identifier: LGPL-2.1-or-later
"""Nesting flat parts on stock sheets with libnest2d (Debian's pynest2d).

libnest2d places convex outlines correctly only (its no-fit polygons of
concave parts let them overlap), so a concave part is nested by its convex
hull. libnest2d works on integer coordinates (Clipper): outlines are scaled so
that the sheet's longer side spans about 2**20 units, and the spacing and
margin are rounded up by two units (a few micrometres on a 3 m sheet), so
the true outlines keep at least the spacing asked for. :func:`verify` checks
the result independently with shapely (GEOS), and :func:`nest` runs that check
itself: a part libnest2d left closer to another than the spacing (it does, for
parts with short edges and at some of the free rotations) is nested again on
sheets of its own, and nothing is returned that fails the check. A part that
fits a sheet only turned a quarter is handed to libnest2d turned (it refuses
such a part before it tries a rotation).

Parts are nested in batches so that progress can be reported and the work
cancelled between batches; the parts of each batch's last, partly filled
sheet go back into the next batch.

>>> result = nest({"A": outline_a, "B": outline_b}, sheet=(2500, 1250),
...               margin=10, spacing=6, rotations="90")   # doctest: +SKIP
>>> result.sheets[0].utilisation                          # doctest: +SKIP
0.41
"""

import itertools
import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from facet.errors import Cancelled, FacetError, InputError

__all__ = ["NestError", "Placement", "Sheet", "NestResult", "nest", "renamed", "verify",
           "ROTATIONS", "DEFAULT_MARGIN_MM", "DEFAULT_SPACING_MM"]

#: The clear border along the sheet's edges and the least distance between parts that
#: ``facet panels`` and FreeCAD's cut sheets use unless told otherwise, in millimetres
#: (converted to the model's units): room for the clamps, and for the kerf of a laser,
#: waterjet or router. With a spacing of 0, neighbours share their cut lines, and the
#: kerf of one part's cut takes its width from the next part.
DEFAULT_MARGIN_MM = 10.0
DEFAULT_SPACING_MM = 6.0

#: Allowed rotations by name: angles tried, radians.
ROTATIONS = {
    "none": (0.0,),
    "90": tuple(k * math.pi / 2 for k in range(4)),
    "free": tuple(k * math.pi / 6 for k in range(12)),
}

_UNITS = float(2 ** 20)
_BATCH = 400
_BATCH_MIN = 8
_BATCH_SHEETS = 1.0
#: parts per independently nested chunk (see nest())
_CHUNK = 500
#: Default worker processes: libnest2d starts and joins a thread for every
#: candidate (even with ``parallel`` off), so a worker spends about half its
#: wall time waiting on them: 4,000 parts on 2 CPUs took 23.0 s with 2
#: workers, 14.0 s with 4, 12.5 s with 8 (the same sheets).
_WORKERS_PER_CPU = 2
_MAX_WORKERS = 8


class NestError(InputError):
    """Bad nesting input: sheet size, margin, spacing, rotations or a part."""


@dataclass
class Placement:
    """Where a part lies: ``sheet_xy = rotate(angle) @ part_xy + (x, y)``,
    with the sheet's lower-left corner at (0, 0)."""

    id: str
    sheet: int
    angle_deg: float
    x: float
    y: float

    def transform(self, points):
        """Part coordinates (k, 2) -> sheet coordinates."""
        a = math.radians(self.angle_deg)
        c, s = math.cos(a), math.sin(a)
        pts = np.asarray(points, dtype=float)
        return pts @ np.array([[c, s], [-s, c]]) + (self.x, self.y)


@dataclass
class Sheet:
    index: int
    width: float
    height: float
    parts: list = field(default_factory=list)
    used_area: float = 0.0

    @property
    def utilisation(self):
        """Area of the parts over the sheet's area."""
        return self.used_area / (self.width * self.height)


@dataclass
class NestResult:
    sheet_size: tuple
    margin: float
    spacing: float
    rotations: str
    sheets: list
    placements: dict
    unplaced: list
    seconds: float = 0.0
    tight: bool = False

    @property
    def utilisation(self):
        """Overall: area of the placed parts over the area of all sheets."""
        if not self.sheets:
            return 0.0
        return sum(s.used_area for s in self.sheets) / (
            len(self.sheets) * self.sheet_size[0] * self.sheet_size[1])


def renamed(result, names):
    """``result`` with its parts renamed by ``names`` (old ID -> new ID, one for each of its
    parts, all different): the same sheets, positions and rotations, for parts whose
    outlines are those nested (new part IDs of the same panels)."""
    from dataclasses import replace

    missing = [pid for pid in list(result.placements) + list(result.unplaced)
               if pid not in names]
    if missing:
        raise NestError(f"no new ID for part {missing[0]} ({len(missing)} parts in all)")
    new = [names[pid] for pid in list(result.placements) + list(result.unplaced)]
    if len(set(new)) != len(new):
        raise NestError("the new part IDs are not all different")
    sheets = [replace(s, parts=[names[pid] for pid in s.parts]) for s in result.sheets]
    placements = {names[pid]: replace(pl, id=names[pid]) for pid, pl in result.placements.items()}
    return replace(result, sheets=sheets, placements=placements,
                   unplaced=[names[pid] for pid in result.unplaced])


def _check(name, value, minimum, strict):
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise NestError(f"{name} must be a number, not {value!r}") from None
    if not math.isfinite(value) or value < minimum or (strict and value == minimum):
        raise NestError(f"{name} must be a finite number {'>' if strict else '>='} "
                        f"{minimum:g}, not {value!r}")
    return value


def nest(parts, sheet, margin=0.0, spacing=0.0, rotations="90", accuracy=0.65,
         progress=None, workers=None, tight=False):
    """Nest flat parts on as many sheets as needed.

    Parameters
    ----------
    parts : dict
        Part ID -> (k, 2) outline (any winding) or shapely Polygon.
    sheet : (width, height)
        Stock sheet size, model units.
    margin : float
        Clear border along every sheet edge, >= 0.
    spacing : float
        Smallest distance between two parts (the kerf and more), >= 0.
    rotations : {"none", "90", "free"}
        None (grain locked), quarter turns, or every 30 degrees.
    accuracy : float
        libnest2d's placer accuracy in (0, 1].
    progress : callable, optional
        ``progress(done, total)`` between batches; True cancels.
    workers : int, optional
        Processes nesting chunks of the parts side by side; default: two
        per CPU, at most eight, when there are several chunks (1 nests in
        this process). The result is the same for any number of workers.
    tight : bool
        Regroup the least-filled sheets after the nesting (slower, often
        fewer sheets): the parts of a few of the least-filled sheets are
        nested again together, and their new sheets kept when they are
        fewer (:func:`_regroup`).

    Returns
    -------
    NestResult
        Parts that fit on no sheet are listed in ``unplaced``.
    """
    import time

    import pynest2d  # noqa: F401  (missing: fail here, before any work)
    from shapely.geometry import Polygon
    from shapely.geometry.polygon import orient

    t0 = time.perf_counter()
    try:
        width, height = (float(v) for v in sheet)
    except (TypeError, ValueError):
        raise NestError(f"sheet must be (width, height), not {sheet!r}") from None
    width = _check("sheet width", width, 0.0, True)
    height = _check("sheet height", height, 0.0, True)
    margin = _check("margin", margin, 0.0, False)
    spacing = _check("spacing", spacing, 0.0, False)
    accuracy = _check("accuracy", accuracy, 0.0, True)
    if rotations not in ROTATIONS:
        raise NestError(f"rotations must be one of {', '.join(ROTATIONS)}, not {rotations!r}")
    if 2 * margin >= min(width, height):
        raise NestError(f"margin {margin:g} leaves nothing of a {width:g} x {height:g} sheet")
    scale = _UNITS / max(width, height)
    dist = max(1, int(math.ceil(spacing * scale)) + 2)
    inner_w = int(math.floor((width - 2 * margin) * scale)) - 2
    inner_h = int(math.floor((height - 2 * margin) * scale)) - 2

    polys = {}
    for pid, outline in parts.items():
        poly = outline if isinstance(outline, Polygon) else Polygon(np.asarray(outline, float))
        if not poly.is_valid or poly.area <= 0:
            raise NestError(f"part {pid}: outline is not a simple polygon with an area")
        polys[pid] = orient(poly, sign=-1.0)  # clockwise, as Clipper wants outer contours

    sheets, placements, unplaced = [], {}, []

    # largest first: what first-fit packs best
    order = sorted(polys, key=lambda k: -polys[k].area)
    # First-fit tries every part on every open sheet, so one libnest2d call
    # costs more than linearly in its parts: parts go in batches of a few
    # sheets' worth.
    mean_area = sum(p.area for p in polys.values()) / max(1, len(polys))
    per_sheet = max(1.0, (width - 2 * margin) * (height - 2 * margin) / max(mean_area, 1e-300))
    batch_size = int(min(_BATCH, max(_BATCH_MIN, _BATCH_SHEETS * per_sheet)))
    items = {}
    box = (inner_w + dist, inner_h + dist)
    turned = {}  # parts given to libnest2d a quarter turn round: degrees
    for pid in order:
        # collinear vertices dropped (the same outline; libnest2d's no-fit
        # polygons cost more with every vertex)
        simple = polys[pid].simplify(0.0, preserve_topology=True)
        if simple.is_empty or simple.geom_type != "Polygon" or not simple.is_valid:
            simple = polys[pid]
        if simple.convex_hull.area > simple.area * (1 + 1e-9):
            # libnest2d's no-fit polygons (Clipper back end, as Debian builds
            # it) are right for convex parts only: concave parts overlapped.
            # A concave part is nested by its convex hull, which holds it.
            simple = simple.convex_hull
        simple = orient(simple, sign=-1.0)
        coords = np.asarray(simple.exterior.coords)
        ring = [(int(round(x * scale)), int(round(y * scale))) for x, y in coords]
        if rotations != "none" and not _fits(ring, box, dist) and _fits(ring, box[::-1], dist):
            # libnest2d refuses a part that does not fit unturned before it tries a
            # rotation: a tall panel on a wide sheet is given to it turned
            ring = [(-y, x) for x, y in ring]
            turned[pid] = 90.0
        items[pid] = (ring, _half_turn_symmetric(ring))
    settings = (box, dist, list(ROTATIONS[rotations]), float(accuracy), batch_size)
    # Chunks of the size order (round robin, so each has large and small
    # parts) are nested independently, each leaving its last, partly filled
    # sheet open; the parts of the open sheets are nested together at the
    # end. The chunks depend only on the parts, never on the number of
    # workers, so the result does not either.
    n_chunks = max(1, len(order) // _CHUNK)
    chunks = [[(pid,) + items[pid] for pid in order[k::n_chunks]] for k in range(n_chunks)]
    total = len(order)
    workers = _workers(workers, n_chunks)
    if workers > 1:
        from facet.parallel import WorkerError, run_chunks

        try:
            results = run_chunks("facet.nest:_nest_chunk_open", chunks, settings, workers,
                                 progress=(None if progress is None else
                                           lambda d, t: progress(d, total)),
                                 weights=[len(c) for c in chunks])
        except WorkerError as exc:
            raise NestError(f"nesting: {exc}") from None
    else:
        results = []
        done = 0
        for chunk in chunks:
            def step(n, base=done):
                return progress is not None and progress(base + n, total)
            results.append(_nest_chunk(chunk, settings, keep_last=n_chunks > 1, progress=step))
            done += len(chunk)
    bins = []
    open_parts = []
    for chunk_bins, rest, chunk_unplaced in results:
        bins.extend(chunk_bins)
        open_parts.extend(rest)
        unplaced.extend(chunk_unplaced)
    if open_parts:
        open_parts.sort(key=lambda pid: -polys[pid].area)
        last_bins, _, last_unplaced = _nest_chunk([(pid,) + items[pid] for pid in open_parts],
                                                  settings, keep_last=False)
        bins.extend(last_bins)
        unplaced.extend(last_unplaced)
    if tight:
        bins = _regroup(bins, items, settings, {pid: p.area for pid, p in polys.items()},
                        progress=(None if progress is None else lambda: progress(total, total)))
    if progress is not None and progress(total, total):
        raise Cancelled("nesting cancelled")
    rank = {pid: k for k, pid in enumerate(order)}
    unplaced.sort(key=rank.__getitem__)
    box_w, box_h = box
    for placed in bins:
        sheet_obj = Sheet(index=len(sheets), width=width, height=height)
        for pid, angle, tx, ty in placed:
            # libnest2d's box is centred on 0; the sheet's corner is at 0;
            # the translation applies to scaled, rotated coordinates
            x = (tx + 0.5 * box_w + 1.0 - 0.5 * dist) / scale + margin
            y = (ty + 0.5 * box_h + 1.0 - 0.5 * dist) / scale + margin
            placements[pid] = Placement(pid, sheet_obj.index,
                                        (math.degrees(angle) + turned.get(pid, 0.0)) % 360.0,
                                        x, y)
            sheet_obj.parts.append(pid)
            sheet_obj.used_area += polys[pid].area
        sheets.append(sheet_obj)
    result = NestResult(sheet_size=(width, height), margin=margin, spacing=spacing,
                        rotations=rotations, sheets=sheets, placements=placements,
                        unplaced=unplaced, seconds=time.perf_counter() - t0, tight=bool(tight))
    _onto_sheets(result, polys, _EDGE_SLACK / scale)
    # libnest2d can leave parts closer than the spacing, or overlapping (parts with short
    # edges, some rotations): every such part goes again, on sheets of its own
    problems = _problems(result, polys)
    crowded = {pid for _message, pids in problems for pid in pids[-1:]}
    if crowded and len(crowded) < len(polys):  # (else it would not end: the check refuses)
        settled = total - len(crowded)  # the bar goes on from the parts that stay; Cancel works
        step = None if progress is None else (lambda d, _t: progress(settled + d, total))
        again = nest({pid: polys[pid] for pid in crowded}, (width, height), margin, spacing,
                     rotations, accuracy, progress=step, workers=1, tight=tight)
        _replace(result, crowded, again, {pid: poly.area for pid, poly in polys.items()})
        problems = _problems(result, polys)
    if problems:  # never a cut sheet with parts too close
        raise FacetError(f"nesting failed its own check ({len(problems)} problems; nothing "
                         f"written): {problems[0][0]}")
    result.seconds = time.perf_counter() - t0
    return result


#: How far past its sheet's edge (less the margin) libnest2d may leave a part, in its
#: integer units (2**-20 of the sheet's longer side): measured up to 1.4 past it at
#: spacing 0 (parallelograms and triangles with a side sloping 2 to 60 degrees), and up
#: to 3.4 when the parts' distance there was 4 units instead of 2. Such a part is moved
#: back onto the sheet (:func:`_onto_sheets`).
_EDGE_SLACK = 8.0


def _onto_sheets(result, polys, slack):
    """Move each part that libnest2d left at most ``slack`` past its sheet's edge less the
    margin back inside, by as much (model units). At spacing 0 its placements of parts
    with a sloping side run up to 1.4 units (4 um on a 3 m sheet) past the edge: the check
    refused the whole nesting (nothing written, "leaves the sheet less its margin") for a
    panel 1,128 x 983 mm alone on a 3,000 x 2,000 sheet. A part moved a few units nearer
    another is caught by the spacing check (and nested again) as before."""
    width, height = result.sheet_size
    m = result.margin
    for pid, pl in result.placements.items():
        placed = pl.transform(np.asarray(polys[pid].exterior.coords))
        lo, hi = placed.min(axis=0), placed.max(axis=0)
        shift = []
        for low, high, size in ((lo[0], hi[0], width), (lo[1], hi[1], height)):
            under, over = m - low, high - (size - m)
            shift.append(under if 0 < under <= slack and over < -under else
                         -over if 0 < over <= slack and under < -over else 0.0)
        pl.x += shift[0]
        pl.y += shift[1]


def _replace(result, moved, again, areas):
    """Take the parts `moved` off `result`'s sheets, add the sheets of `again` (their own
    nesting) and number the sheets anew (a sheet left empty goes)."""
    index, sheets = {}, []
    for sheet in result.sheets:
        if any(pid in moved for pid in sheet.parts):
            sheet.parts = [pid for pid in sheet.parts if pid not in moved]
            sheet.used_area = sum(areas[pid] for pid in sheet.parts)
        if sheet.parts:
            index[sheet.index] = sheet.index = len(sheets)
            sheets.append(sheet)
    placements = {}
    for pid, placement in result.placements.items():
        if pid not in moved:
            placement.sheet = index[placement.sheet]
            placements[pid] = placement
    base = len(sheets)
    for sheet in again.sheets:
        sheet.index += base
        sheets.append(sheet)
    for pid, placement in again.placements.items():
        placement.sheet += base
        placements[pid] = placement
    result.sheets, result.placements = sheets, placements
    result.unplaced.extend(again.unplaced)


def _fits(ring, box, dist):
    """Whether an integer outline's bounding box fits in libnest2d's box as it is."""
    xs = [x for x, _ in ring]
    ys = [y for _, y in ring]
    return max(xs) - min(xs) + dist <= box[0] and max(ys) - min(ys) + dist <= box[1]


def _config(rotations, accuracy):
    import pynest2d

    config = pynest2d.NfpConfig()
    config.rotations = list(rotations)
    config.alignment = pynest2d.NfpConfig.Alignment.BOTTOM_LEFT
    config.starting_point = pynest2d.NfpConfig.Alignment.BOTTOM_LEFT
    config.accuracy = accuracy
    # libnest2d's own parallelism starts a thread per candidate (no TBB in
    # Debian's build): twice as slow as serial; processes share the work
    config.parallel = False
    return config


def _half_turn_symmetric(ring):
    """Whether an integer outline is its own image under a half turn about
    its bounding box's centre (exactly, in the integer coordinates)."""
    pts = set(ring[:-1] if ring and ring[0] == ring[-1] else ring)
    xs = [p[0] for p in pts]
    ys = [p[1] for p in pts]
    cx, cy = min(xs) + max(xs), min(ys) + max(ys)  # twice the centre
    return {(cx - x, cy - y) for x, y in pts} == pts


def _nest_chunk(chunk, settings, keep_last, progress=None):
    """Nest ``chunk`` = [(pid, integer outline, half-turn symmetric)] batch by batch (the parts of
    a batch's last, partly filled sheet go into the next batch).

    Returns ([[(pid, angle, tx, ty)] per full sheet], open, unplaced): with
    ``keep_last`` the parts of the last, partly filled sheet are not placed
    but returned in ``open``.
    """
    import pynest2d

    (box_w, box_h), dist, rotations, accuracy, batch_size = settings
    config = _config(rotations, accuracy)
    # a half turn maps a symmetric part onto itself: when every part of a
    # batch is, the rotations from 180 degrees on add nothing to the search
    half = [r for r in rotations if r < math.pi - 1e-9]
    config_half = _config(half, accuracy) if len(half) < len(rotations) else config
    outlines = {pid: ring for pid, ring, _ in chunk}
    symmetric = {pid: sym for pid, _, sym in chunk}
    order = [pid for pid, _, _ in chunk]
    bins_out, unplaced, pending = [], [], []
    total = len(order)
    while order or pending:
        batch = pending + order[:batch_size]
        order = order[batch_size:]
        items = [pynest2d.Item([pynest2d.Point(x, y) for x, y in outlines[pid]])
                 for pid in batch]
        cfg = config_half if all(symmetric[pid] for pid in batch) else config
        pynest2d.nest(items, pynest2d.Box(box_w, box_h), dist, cfg)
        bins = {}
        for pid, item in zip(batch, items):
            b = item.binId()
            if b < 0:
                unplaced.append(pid)
            else:
                tr = item.translation()
                bins.setdefault(b, []).append((pid, float(item.rotation()), tr.x(), tr.y()))
        keys = sorted(bins)
        pending = []
        if (order or keep_last) and keys:
            # the last sheet is partly filled: its parts go on
            pending = [p[0] for p in bins.pop(keys[-1])]
            keys = keys[:-1]
        bins_out.extend(bins[b] for b in keys)
        if not order:
            break
        if progress is not None and progress(total - len(order)):
            raise Cancelled("nesting cancelled")
    return bins_out, pending, unplaced


#: :func:`_regroup`'s pools: the parts of this many batches (see nest()) at most
_POOL_BATCHES = 4


def _regroup(bins, items, settings, areas, progress=None):
    """Fewer sheets, by nesting the parts of the least-filled sheets again together.

    Batches (and chunks) close their sheets before the parts of later batches are seen,
    so a sheet can keep a hole that a later, smaller part would fill, and a large part
    can stay alone on a sheet beside room for its like. Sheets are taken from the
    least-filled up into a pool of at most :data:`_POOL_BATCHES` batches' parts (two
    sheets at least); the pool is nested in one call (first fit over all its sheets),
    and its new sheets replace the pool's when they are fewer. A pool that saves no
    sheet leaves its sheets as they were, and they are not pooled again; the pass ends
    when fewer than two sheets are left to pool. Each pool either saves a sheet or
    retires two, so it ends; it depends on the bins only (not on the workers).

    ``bins``: [[(pid, angle, tx, ty)] per sheet] as :func:`_nest_chunk` returns them;
    ``items``: pid -> (integer outline, half-turn symmetric). ``progress()`` returning
    True (asked between pools) cancels. Returns the new bins.
    """
    box, dist, rotations, accuracy, batch_size = settings
    pool_size = _POOL_BATCHES * batch_size
    serial = itertools.count()
    tagged = [(next(serial), b) for b in bins]
    settled = set()

    def fill(tb):
        return sum(areas[p[0]] for p in tb[1])

    while True:
        if progress is not None and progress():
            raise Cancelled("nesting cancelled")
        group, pool = [], []
        for tb in sorted((tb for tb in tagged if tb[0] not in settled), key=fill):
            if len(group) >= 2 and len(pool) + len(tb[1]) > pool_size:
                break
            group.append(tb[0])
            pool.extend(p[0] for p in tb[1])
        if len(group) < 2:
            break
        pool.sort(key=lambda pid: -areas[pid])
        pool_settings = (box, dist, rotations, accuracy, len(pool))
        new_bins, _, lost = _nest_chunk([(pid,) + items[pid] for pid in pool], pool_settings,
                                        keep_last=False)
        if not lost and len(new_bins) < len(group):
            gone = set(group)
            tagged = [tb for tb in tagged if tb[0] not in gone]
            tagged.extend((next(serial), b) for b in new_bins)
        else:
            settled.update(group)
    return [b for _, b in tagged]


def _workers(workers, n_chunks):
    from facet.parallel import default_workers

    if workers is None:
        workers = default_workers(per_cpu=_WORKERS_PER_CPU, maximum=_MAX_WORKERS)
    else:
        try:
            workers = int(workers)
        except (TypeError, ValueError):
            raise NestError(f"workers must be a whole number, not {workers!r}") from None
        if workers < 1:
            raise NestError(f"workers must be >= 1, not {workers}")
    return max(1, min(workers, n_chunks))


def _nest_chunk_open(chunk, settings):
    """A worker's chunk: nested with its last sheet left open."""
    return _nest_chunk(chunk, settings, keep_last=True)


def verify(result, parts, tolerance=None):
    """Check a nesting independently with shapely.

    Parameters
    ----------
    result : NestResult
    parts : dict
        The outlines given to :func:`nest`.
    tolerance : float, optional
        Slack for rounding, model units; default 1e-6 of the sheet's size.

    Returns
    -------
    list of str
        What is wrong (empty when every part lies inside its sheet less the
        margin, and every two parts on a sheet are at least the spacing
        apart).
    """
    return [message for message, _pids in _problems(result, parts, tolerance)]


def _problems(result, parts, tolerance=None):
    """:func:`verify`'s findings as (message, the parts it names)."""
    from shapely.geometry import Polygon, box
    from shapely.strtree import STRtree

    width, height = result.sheet_size
    tol = tolerance if tolerance is not None else 1e-6 * max(width, height)
    m = result.margin
    inner = box(m - tol, m - tol, width - m + tol, height - m + tol)
    problems = []
    by_sheet = {}
    for pid, pl in result.placements.items():
        poly = parts[pid] if isinstance(parts[pid], Polygon) else Polygon(parts[pid])
        placed = Polygon(pl.transform(np.asarray(poly.exterior.coords)))
        if not inner.contains(placed):
            problems.append((f"part {pid} on sheet {pl.sheet} leaves the sheet less its margin",
                             (pid,)))
        by_sheet.setdefault(pl.sheet, []).append((pid, placed))
    for sheet, items in by_sheet.items():
        geoms = [g for _, g in items]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # shapely 1.8 announces 2.0's STRtree
            tree = STRtree(geoms)
        index = {id(g): k for k, g in enumerate(geoms)}
        for k, (pid, g) in enumerate(items):
            for other in tree.query(g.buffer(max(result.spacing - tol, 0.0))):
                j = index[id(other)]
                if j <= k:
                    continue
                d = g.distance(other)
                if d < result.spacing - tol:
                    problems.append((f"parts {pid} and {items[j][0]} on sheet {sheet} are "
                                     f"{d:.6g} apart (spacing {result.spacing:g})",
                                     (pid, items[j][0])))
                elif d <= tol and other.intersects(g.buffer(-tol)):
                    # overlapping parts are 0 apart too, which no spacing <= tol refuses
                    # (the default 0: 42 pairs of heart_planar's parts overlapped, by up
                    # to 0.025 m2 of 0.05): one reaches more than tol into the other
                    problems.append((f"parts {pid} and {items[j][0]} on sheet {sheet} "
                                     f"overlap", (pid, items[j][0])))
    return problems
