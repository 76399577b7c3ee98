# SPDX-License-Identifier: LGPL-2.1-or-later
"""Cut files: DXF sheets (ezdxf), the schedule (CSV, JSON), SVG and PNG previews.

DXF layers (each with its meaning as its description, in the file too):

========  =============================================================
CUT       each part's cut outline (its bottom face), closed polylines
LABEL     the part ID, engraving text inside the outline
BEVEL     each bevel angle, engraving text beside its edge (texts only)
TOP       the top face's outline where it differs from the cut (bevelled
          edges, the offset): a closed, dashed reference contour, neither
          cut nor engraved (the upper contour of a tilted cut)
SHEET     sheet borders and sheet names
GRAIN     grain arrows
========  =============================================================

The top face's outline crosses the cut outline where a bevel leans out (394 of heart's
398 parts mitred at 20 mm), so a layer that held it with texts to engrave (BEVEL did)
could not be engraved without it.

The IDs, bevel angles and sheet names are TEXT entities of style FACET_SANS (font DejaVu
Sans, the outlines' and previews'), centred (groups 11, 72, 73) with group 10 at the start of
their baseline, for readers that ignore the alignment (see :func:`_text_starts`).

Units are the model's, declared in $INSUNITS: millimetres unless `units` says
otherwise (see LENGTH_UNITS). Sheets lie in rows
like a book's pages (:func:`sheet_origins`), each named under it on SHEET, in one file,
or one file per sheet (``per_sheet=True``).
"""

import json
import math
import os

import numpy as np

from facet.io.files import when_staged, write_replacing, write_text
from facet.report import count_noun, json_safe

__all__ = ["LAYERS", "LAYER_LINETYPES", "LAYER_MEANINGS", "write_dxf", "schedule_rows",
           "write_schedule_csv", "write_schedule_json", "csv_header", "column_units",
           "write_svg", "write_png", "sheet_origins", "PREVIEW_COLOURS", "PLAUSIBLE_EDGE_MM",
           "implausible_edge_mm"]

#: Layer name -> ACI colour.
LAYERS = {"CUT": 1, "LABEL": 5, "BEVEL": 3, "TOP": 4, "SHEET": 8, "GRAIN": 6}

#: Layer name -> its linetype, where not continuous.
LAYER_LINETYPES = {"TOP": "FACET_DASHED"}

#: The dash and the gap of FACET_DASHED (TOP), millimetres, written in the file's units:
#: ezdxf's DASHED is 1.27 drawing units a dash, 1.27 mm or 1.27 m, both read as a
#: continuous line on parts a metre and 20 cm wide. Its own linetype, made with
#: ``linetypes.add`` as ezdxf 0.18 and 1.x both do, needs no $LTSCALE.
DASH_MM = (12.7, 2.54)

#: Layer name -> what it holds (the layers' descriptions in the DXF).
LAYER_MEANINGS = {
    "CUT": "cut: each part's outline (its bottom face)",
    "LABEL": "engrave: part IDs",
    "BEVEL": "engrave: bevel angles beside their edges",
    "TOP": "reference, do not cut: the top face's outline where bevels or the offset "
           "move it",
    "SHEET": "reference: sheet borders and names",
    "GRAIN": "engrave: grain arrows",
}


#: The font of texts written as outlines (``write_dxf(text_outlines=True)``): with ezdxf
#: 0.18 found by matplotlib, which ships it, so always there; ezdxf 1.1 and later look for
#: it among the system's fonts (/usr/share/fonts...) and take another sans font when it is
#: not there. It has Latin, Greek and Cyrillic letters, not CJK: write_dxf refuses a text
#: with a letter the font lacks (it would be cut as an empty box).
OUTLINE_FONT = "DejaVu Sans"

#: The font file of the TEXT entities' style :data:`TEXT_STYLE` (:data:`OUTLINE_FONT`'s), so
#: that a reader that draws TrueType fonts (ezdxf, AutoCAD) shows the texts in the font of
#: the outlines and the previews, not in whatever it maps the SHX font "txt" to.
TEXT_FONT_FILE = "DejaVuSans.ttf"

#: The text style of the DXF's TEXT entities (the IDs, bevel angles and sheet names).
TEXT_STYLE = "FACET_SANS"

#: The height of :data:`OUTLINE_FONT`'s capitals in ems (its "H": 1493 of 2048 units). A
#: DXF text's height is its capitals' height, a font size (SVG, matplotlib) the em's: the
#: previews set the size to height / this, so their texts are as tall as the DXF's.
OUTLINE_FONT_CAP_HEIGHT = 1493.0 / 2048.0

#: The outlines' curves are flattened to within this fraction of the text height (0.3 mm
#: on a 30 mm ID; the demo's 1,477 texts give a DXF of 8.7 MB against 0.56 MB as TEXT).
OUTLINE_FLATNESS = 0.01


def _outline_writer(align):
    """A function (msp, s, x, y, height, rotation_deg, layer) that adds the outlines of
    the letters of ``s`` as closed polylines, placed as a TEXT of that height (its capitals'
    height), rotation and alignment would be."""
    from ezdxf.addons import text2path
    from ezdxf.path import single_paths

    try:  # ezdxf 1.x
        from ezdxf.fonts.fonts import FontFace
    except ImportError:  # ezdxf 0.18 (Debian 12)
        from ezdxf.tools.fonts import FontFace
    face = FontFace(family=OUTLINE_FONT)
    # ezdxf before 1.1 draws with matplotlib's TextPath, which takes the text between two
    # $ for mathtext ("A$1$" came out as "A1"): a $ is escaped there
    literal = ((lambda s: s.replace("$", r"\$")) if hasattr(text2path, "TextPath")
               else (lambda s: s))

    def shape(s):  # the flattened contours of s at size 1, as a comparable tuple
        paths = text2path.make_paths_from_str(literal(s), face, size=1.0)
        return tuple(tuple(round(c, 9) for v in p.flattening(0.01) for c in (v.x, v.y))
                     for p in paths)

    notdef = shape("\U0010fffd")  # a character in no font: the font's missing-glyph box
    missing = {}  # character -> whether the font lacks it

    def lacked(s):
        for c in s:
            if c not in missing:
                missing[c] = not c.isspace() and shape(c) == notdef
        return [c for c in dict.fromkeys(s) if missing[c]]

    flat = {}  # text -> its closed contours at size 1, aligned at the origin

    def contours(s):
        """The letters' contours of ``s`` at height 1, flattened once per distinct text
        (bevel angles repeat: the demo's 1,324 texts are 339 distinct), each an (n, 2) array
        without its repeated first point."""
        if s not in flat:
            paths = text2path.make_paths_from_str(literal(s), face, size=1.0, align=align)
            out = []
            for path in single_paths(paths):
                points = np.array([(v.x, v.y) for v in path.flattening(OUTLINE_FLATNESS,
                                                                       segments=1)])
                if len(points) > 3 and np.array_equal(points[0], points[-1]):
                    points = points[:-1]  # a letter's contour ends where it starts
                if len(points) >= 3:
                    out.append(points)
            flat[s] = out
        return flat[s]

    def outline(msp, s, x, y, height, rotation, layer):
        if not s.strip():  # nothing to engrave (and text2path fails on blanks)
            return
        lacking = lacked(s)
        if lacking:  # its outline would be the font's empty box, the text lost
            from facet.errors import InputError

            raise InputError(
                f"text {s!r}: the outline font {OUTLINE_FONT} has no letter for "
                f"{', '.join(repr(c) for c in lacking)}, which would be cut as an empty box; "
                "use other letters (a Latin ID prefix), or write the texts as TEXT "
                "(texts as outlines off)")
        c, si = math.cos(math.radians(rotation)), math.sin(math.radians(rotation))
        turn = height * np.array([[c, si], [-si, c]])  # row vectors: p @ turn turns and scales
        for contour in contours(s):
            msp.add_lwpolyline((contour @ turn + (x, y)).tolist(), format="xy", close=True,
                               dxfattribs={"layer": layer})

    return outline


def _text_starts():
    """``start(s, x, y, height, rotation_deg)``: where a text of :data:`TEXT_FONT_FILE`
    centred at (x, y) (MIDDLE_CENTER, the middle of its capitals) starts on its baseline: the
    point a TEXT's group 10 holds, as AutoCAD writes it. Readers that honour the alignment
    (groups 11, 72, 73: AutoCAD, ezdxf, LibreCAD) place the text by its centre; those that
    ignore it (FreeCAD 0.20's DXF importer, simple CAM importers) put the start of the
    baseline at group 10, which was the centre: the text stood half its width to the right
    and half its height up, across the part's cut line. Widths by ezdxf's font measurement
    (to the ink's right end; ezdxf centres the ink, which starts a left bearing, 0.05 of the
    height, further right), once per distinct text."""
    try:  # ezdxf 1.1 and later
        from ezdxf.fonts.fonts import make_font
    except ImportError:  # ezdxf 0.18 (Debian 12)
        from ezdxf.tools.fonts import make_font
    font = make_font(TEXT_FONT_FILE, 1.0)
    widths = {}

    def start(s, x, y, height, rotation):
        if s not in widths:
            widths[s] = float(font.text_width(s))
        c, si = math.cos(math.radians(rotation)), math.sin(math.radians(rotation))
        half_w, half_h = 0.5 * widths[s] * height, 0.5 * height
        return (x - half_w * c + half_h * si, y - half_w * si - half_h * c)

    return start


def _sheet_number(k, count):
    """Sheet k of `count` as its file is numbered: as many digits as the last has, two at
    least, so that a listing sorts the files as the sheets go ("sheet_100" came before
    "sheet_11" of a 153-sheet run)."""
    return f"{k:0{max(2, len(str(count)))}d}"


def _sheet_title(i, sheet):
    """A preview's title for sheet i (from 0): "sheet 3: 4 parts, 61.2% used"."""
    return (f"sheet {i + 1}: {count_noun(len(sheet.parts), 'part')}, "
            f"{100 * sheet.utilisation:.1f}% used")


def _numbered_in(directory, stem, suffix):
    """``numbered(digits)``: the file of a sheet preview, ``directory/stem_digits.suffix``."""
    return lambda digits: os.path.join(directory, f"{stem}_{digits}{suffix}")


def _remove_stale(numbered, written):
    """Remove the files ``numbered(digits)`` that an earlier run wrote and this one did not
    (not in `written`): with any number of digits from 2 to 6, from 1 on while such a file
    exists. An earlier, longer run's last sheets, or all of a run numbered with other widths
    (12 sheets against 140), would otherwise lie beside the new ones and be cut again; when
    the new ones take their places (:func:`facet.io.files.staged`)."""
    keep = {os.path.abspath(path) for path in written}

    def remove():
        for width in range(2, 7):
            k = 1
            while os.path.isfile(numbered(f"{k:0{width}d}")):
                name = numbered(f"{k:0{width}d}")
                if os.path.abspath(name) not in keep:
                    os.remove(name)
                k += 1

    when_staged(remove)


def sheet_origins(nest_result, sheet_gap=None):
    """The lower-left corner (x, y) of each sheet where a whole run's layout lays it (the
    DXF in one file, the FreeCAD CutSheets' Shape): in rows read like a book's pages, sheet
    1 at the origin, then left to right and row under row; ``sheet_gap`` apart across
    (default a tenth of the sheet's width) and a tenth of its height more down, where each
    sheet's name stands under it; as many sheets a row as make the whole about as wide as
    high. The sheets lay in one row: 161 sheets 3000 mm wide were a line 483 m long, a thin
    line in a view of it all."""
    w, h = nest_result.sheet_size
    count = len(nest_result.sheets)
    across = 0.1 * w if sheet_gap is None else sheet_gap
    down = across + 0.1 * h
    columns = max(1, min(count, math.ceil(math.sqrt(count * (h + down) / (w + across)))))
    return [(float(i % columns * (w + across)), float(-(i // columns) * (h + down)))
            for i in range(count)]


def _placed(nest_result, drawings):
    by_id = {d.id: d for d in drawings}
    for pid, pl in nest_result.placements.items():
        yield pl, by_id[pid]


def _by_sheet(nest_result, drawings):
    """{sheet index: [(placement, drawing)]}."""
    by_sheet = {}
    for pl, d in _placed(nest_result, drawings):
        by_sheet.setdefault(pl.sheet, []).append((pl, d))
    return by_sheet


def _reporter(progress, total, what):
    """``report(done)``: calls ``progress(done, total)`` (if given) and raises Cancelled
    ("writing the WHAT cancelled") when it returns True."""
    from facet.errors import report_progress

    def report(done):
        report_progress(progress, done, total, f"writing the {what}")

    return report


#: How far past vertical, degrees, a text still reads from the sheet's right side before it
#: is turned half a turn (Civil 3D's "readability bias" of 110 degrees): the texts of the
#: near-vertical edges of a part (a left edge at -88 degrees, a right one at 88) all read
#: from the right, not some from the left.
READABLE_PAST_VERTICAL = 20.0


def _upright(deg):
    """A text's angle on the sheet (degrees, counter-clockwise) turned by half a turn where
    it would read upside down: into (-70, 110] (:data:`READABLE_PAST_VERTICAL`), so that
    it reads from the sheet's bottom or its right side, as a drawing's texts do. A part
    nested turned by 180 or 270 degrees had its ID written upside down, and the bevel
    angles of its edges that run left or down too (the fabricator reads them off the
    sheet). Turned about its middle, where the DXF places it (MIDDLE_CENTER) and the
    outlines and previews centre it, the text stays on its place: the ID's box
    (``facet.unfold._label_box``) is the same either way up, and a bevel angle
    ("+12.5\u00b0", no descender) is as high either side of its middle."""
    high = 90.0 + READABLE_PAST_VERTICAL
    return high - (high - deg) % 180.0


def _preview_text(x, y, height, rotation_deg):
    """A DXF text centred at (x, y) (MIDDLE_CENTER: the middle of its capitals), as a
    preview draws it: ``(bx, by, size)``, the point on its baseline below the centre and
    the font size in model units. Placed by the baseline, which every SVG viewer and
    matplotlib put in the same place (SVG's dominant-baseline "middle" is half the
    lower-case letters' height, and some viewers ignore it)."""
    turn = np.radians(rotation_deg)
    half = 0.5 * height
    return (x + half * np.sin(turn), y - half * np.cos(turn),
            height / OUTLINE_FONT_CAP_HEIGHT)


def _drawn(pl, d, sheet_size, off=0.0):
    """A placed part as the cut files draw it, on the sheet moved by ``off`` (x, y):
    ``(cut, top, texts, grain)``: the cut ring; the top face's ring, or None where it is
    the cut's (within 1e-9 of the sheet's size); the texts ``(text, x, y, height,
    rotation_deg, layer)``, the ID (LABEL) and the bevel angles (BEVEL), rotation
    counter-clockwise, upright on the sheet (:func:`_upright`); and the grain arrow's
    segments ``(a, b)`` (none without a grain). The DXF, SVG and PNG draw these."""
    cut = pl.transform(d.cut) + off
    same = np.allclose(d.top, d.cut, rtol=0, atol=1e-9 * max(sheet_size))
    top = None if same else pl.transform(d.top) + off
    lx, ly = pl.transform([d.label_position])[0] + off
    texts = [(d.id, lx, ly, d.label_height, _upright(pl.angle_deg), "LABEL")]
    for s, bx, by, ang, bh in d.bevels:
        px, py = pl.transform([(bx, by)])[0] + off
        texts.append((s, px, py, bh, _upright(ang + pl.angle_deg), "BEVEL"))
    grain = []
    if d.grain is not None:
        a, b = pl.transform(d.grain) + off
        grain.append((a, b))
        u = (b - a) / max(np.linalg.norm(b - a), 1e-300)
        n = np.array([-u[1], u[0]])
        size = 0.15 * np.linalg.norm(b - a)
        grain += [(b, b - size * u + sgn * 0.5 * size * n) for sgn in (1, -1)]
    return cut, top, texts, grain


#: The model units a fabrication run can be in: millimetres per unit, the DXF's
#: $INSUNITS code and $MEASUREMENT (1 metric, 0 imperial).
LENGTH_UNITS = {"mm": (1.0, 4, 1), "cm": (10.0, 5, 1), "m": (1000.0, 6, 1),
                "in": (25.4, 1, 0), "ft": (304.8, 2, 0)}

#: The mean edge lengths, in mm, of the meshes taken to be in the units they are read in:
#: a facade drawn in metres and read as millimetres has edges of a few millimetres at most
#: (``facet panels`` warns outside it; FreeCAD's import asks for the units, its PanelSet
#: warns).
PLAUSIBLE_EDGE_MM = (10.0, 50000.0)


def implausible_edge_mm(mean_edge, units="mm"):
    """``mean_edge`` (a mesh's or panels' mean edge length, in ``units``) in millimetres
    when it is outside :data:`PLAUSIBLE_EDGE_MM`, no facade's (a mesh in metres read as
    millimetres), else None: the one test of ``facet panels``' units warning and FreeCAD's
    import and PanelSet."""
    edge = mean_edge * length_unit(units)[0]
    return None if PLAUSIBLE_EDGE_MM[0] <= edge <= PLAUSIBLE_EDGE_MM[1] else edge


def length_unit(units):
    """(mm per unit, $INSUNITS, $MEASUREMENT) of `units`, one of LENGTH_UNITS."""
    from facet.errors import InputError

    if units not in LENGTH_UNITS:
        raise InputError(f"units {units!r}: use one of {', '.join(LENGTH_UNITS)}")
    return LENGTH_UNITS[units]


def write_dxf(path, nest_result, drawings, per_sheet=False, sheet_gap=None, units="mm",
              text_outlines=False, progress=None):
    """Write the nested sheets as DXF (ezdxf; audited before saving).

    Parameters
    ----------
    path : str or os.PathLike
        The file; with ``per_sheet`` a pattern whose ``{sheet}`` is replaced
        by the sheet number (1-based), or ``name.dxf`` -> ``name_01.dxf``; with as many
        digits as the last sheet's, two at least (``name_001.dxf`` from 100 sheets), so
        that a listing sorts them. Numbered files of an earlier run that this one did not
        write are removed (they would be cut again); so are write_svg's and write_png's.
    nest_result : facet.nest.NestResult
    drawings : list of facet.unfold.PartDrawing
    per_sheet : bool
    sheet_gap : float, optional
        Distance between the sheets of one file (:func:`sheet_origins`; default a tenth
        of the width).
    units : str
        The model's length unit (a key of LENGTH_UNITS), declared in $INSUNITS and
        $MEASUREMENT; the coordinates are written as they are.
    text_outlines : bool
        Write the IDs and bevel angles as the outlines of their letters (closed polylines,
        font :data:`OUTLINE_FONT`, on the same layers) instead of TEXT entities, for the
        CAM programs that import no TEXT (many laser and router importers skip it). The
        sheet names stay TEXT, on SHEET. A text with a letter that font lacks (CJK) raises
        :class:`facet.errors.InputError`, nothing written; a blank one is left out.
    progress : callable, optional
        ``progress(done, total)`` after each part drawn; returning True cancels
        (:class:`facet.errors.Cancelled`, nothing written). Texts as outlines take about
        6 ms a part (the demo's 280: 1.7 s, against 0.15 s as TEXT).

    Returns
    -------
    list of str
        The files written.
    """
    import ezdxf
    from ezdxf import bbox, zoom
    from ezdxf.enums import TextEntityAlignment

    mm_per_unit, insunits, measurement = length_unit(units)
    w, h = nest_result.sheet_size
    origins = sheet_origins(nest_result, sheet_gap)
    path = os.fspath(path)

    def new_doc():
        doc = ezdxf.new("R2010", setup=True)
        doc.units = insunits
        doc.header["$MEASUREMENT"] = measurement
        dash, gap = (length / mm_per_unit for length in DASH_MM)
        doc.linetypes.add("FACET_DASHED", pattern=[dash + gap, dash, -gap],
                          description=f"Dashed, {dash:.3g} {units} __  __  __")
        if TEXT_STYLE not in doc.styles:
            doc.styles.add(TEXT_STYLE, font=TEXT_FONT_FILE)
        doc.header["$TEXTSTYLE"] = TEXT_STYLE
        for name, colour in LAYERS.items():
            layer = doc.layers.add(name, color=colour,
                                   linetype=LAYER_LINETYPES.get(name, "Continuous"))
            layer.description = LAYER_MEANINGS[name]
        return doc

    starts = _text_starts()

    def text(msp, s, x, y, height, rotation, layer):
        t = msp.add_text(s, dxfattribs={"height": height, "rotation": rotation, "layer": layer,
                                        "style": TEXT_STYLE})
        t.set_placement((x, y), align=TextEntityAlignment.MIDDLE_CENTER)
        t.dxf.insert = (*starts(s, x, y, height, rotation), 0.0)  # (see _text_starts)

    # the IDs and bevel angles: TEXT, or their letters' outlines (the sheet names stay TEXT)
    engraved = _outline_writer(TextEntityAlignment.MIDDLE_CENTER) if text_outlines else text

    docs = {}
    for i, sheet in enumerate(nest_result.sheets):
        key = i if per_sheet else 0
        if key not in docs:
            docs[key] = new_doc()
        msp = docs[key].modelspace()
        x0, y0 = (0.0, 0.0) if per_sheet else origins[i]
        msp.add_lwpolyline([(x0, y0), (x0 + w, y0), (x0 + w, y0 + h), (x0, y0 + h)],
                           close=True, dxfattribs={"layer": "SHEET"})
        text(msp, f"SHEET {i + 1}", x0 + 0.5 * w, y0 - 0.04 * h, 0.02 * h, 0.0, "SHEET")
    placed = list(_placed(nest_result, drawings))
    report = _reporter(progress, len(placed), "DXF")
    for done, (pl, d) in enumerate(placed):
        if done % 16 == 0:
            report(done)
        msp = docs[pl.sheet if per_sheet else 0].modelspace()
        off = np.array((0.0, 0.0) if per_sheet else origins[pl.sheet])
        cut, top, texts, grain = _drawn(pl, d, (w, h), off)
        msp.add_lwpolyline(cut.tolist(), close=True, dxfattribs={"layer": "CUT"})
        if top is not None:
            msp.add_lwpolyline(top.tolist(), close=True, dxfattribs={"layer": "TOP"})
        for t in texts:
            engraved(msp, *t)
        for a, b in grain:
            msp.add_line(a.tolist(), b.tolist(), dxfattribs={"layer": "GRAIN"})
    report(len(placed))
    if not docs:  # nothing placed: still a valid (empty) drawing, so no stale file remains
        docs[0] = new_doc()

    def numbered(digits):
        if "{sheet}" in path:
            return path.replace("{sheet}", digits)
        root, ext = os.path.splitext(path)
        return f"{root}_{digits}{ext or '.dxf'}"

    written = []
    for key in sorted(docs):
        doc = docs[key]
        # the drawing's extents and the view it opens with: its sheets (the extents were
        # left unset, +-1e20, and the view a 1000 units high window at the origin, which
        # showed a drawing in metres as a dot)
        # (the sheets hold every part: their borders and names are the drawing's extents,
        # found without going through thousands of letter contours)
        extents = bbox.extents(doc.modelspace().query("*[layer=='SHEET']"), fast=True)
        if extents.has_data:
            doc.modelspace().reset_extents(extents.extmin, extents.extmax)  # ($EXTMIN/MAX)
            zoom.center(doc.modelspace(), extents.center, extents.size)
        auditor = doc.audit()
        if auditor.has_errors:
            raise RuntimeError(f"ezdxf audit found {len(auditor.errors)} errors in the DXF")
        target = numbered(_sheet_number(key + 1, len(docs))) if per_sheet else path
        write_replacing(target, doc.saveas)
        written.append(target)
    if per_sheet:
        _remove_stale(numbered, written)
    return written


def schedule_rows(panel_set, nest_result=None, drawings=None, density=None, units="mm",
                  types=None):
    """The schedule: one dict per panel (see :meth:`facet.panels.Panel.schedule_row`)
    with its part type (``types``, :func:`facet.part_types.part_types` of the panels,
    one per panel, else a ValueError; by default within
    :data:`facet.part_types.DEFAULT_TOL_MM` in ``units``), sheet (1-based, None when not
    nested or unplaced), x, y and
    rotation_deg on the sheet: ``sheet_xy = rotate(rotation_deg) @ flat_xy + (x, y)``
    for the panel's flat outline (``Panel.flat_bottom``). ``drawings``
    (:func:`facet.unfold.unfold`'s) carry the turn that lays each part's grain along x,
    which the rotation includes; without them it is the nesting's alone. ``mass_kg``: the
    panel's mass in kg from its volume (model units cubed, `units`) and ``density``
    (kg/m³), None without a density."""
    from facet.panels import mass_kg
    from facet.part_types import DEFAULT_TOL_MM, part_types

    mm_per_unit = length_unit(units)[0]
    if types is None:
        types = part_types(panel_set.panels, DEFAULT_TOL_MM / mm_per_unit)
    elif len(types) != len(panel_set.panels):
        # (zip would leave the last panels out of the schedule without a word)
        raise ValueError(f"{count_noun(len(types), 'part type')} for "
                         f"{count_noun(len(panel_set.panels), 'panel')}: one per panel")
    turned = {d.id: d.rotation_deg for d in drawings or ()}
    rows = []
    for p, part_type in zip(panel_set.panels, types):
        row = p.schedule_row()
        row["type"] = part_type
        row["mass_kg"] = (None if density is None
                          else float(mass_kg(row["volume"], density, mm_per_unit)))
        pl = nest_result.placements.get(p.id) if nest_result is not None else None
        row["sheet"] = None if pl is None else pl.sheet + 1
        row["x"] = None if pl is None else pl.x
        row["y"] = None if pl is None else pl.y
        row["rotation_deg"] = (None if pl is None
                               else (pl.angle_deg + turned.get(p.id, 0.0)) % 360.0)
        rows.append(row)
    return rows


_CSV_COLUMNS = ["id", "type", "face", "corners", "input_corners", "area", "area_top", "perimeter",
                "width", "height", "thickness", "volume", "mass_kg",
                "edge_lengths", "bevel_deg", "dihedral_deg", "dropped_edges",
                "squared_edges", "butt_edges", "joint_widths", "narrowest_joint", "clash",
                "sheet", "x", "y",
                "rotation_deg"]

#: The schedule's columns measured in the model's length unit, by its power: lengths
#: (1), areas (2), volumes (3). The others are IDs, counts or name their unit (mass_kg,
#: bevel_deg, ...).
_COLUMN_POWERS = {"area": 2, "area_top": 2, "perimeter": 1, "width": 1, "height": 1,
                  "thickness": 1, "volume": 3, "edge_lengths": 1, "joint_widths": 1,
                  "narrowest_joint": 1, "clash": 1, "x": 1, "y": 1}


def column_units(units="mm"):
    """{schedule column: its unit} for the columns in the model's length unit ``units``
    (a key of LENGTH_UNITS) or its square or cube: ``"mm"``, ``"mm2"``, ``"mm3"`` (ASCII,
    which any spreadsheet's import reads whatever character set it assumes). The JSON
    schedule's ``meta.column_units``; the CSV's headers append them (:func:`csv_header`)."""
    length_unit(units)  # a unit it knows
    return {c: units + ("" if k == 1 else str(k)) for c, k in _COLUMN_POWERS.items()}


def csv_header(units="mm"):
    """The CSV schedule's column names: each row key, with its unit (:func:`column_units`)
    for a length, area or volume: ``area_mm2``, ``width_mm``, ``x_mm`` (``area_m2`` with
    ``--units m``). A fabricator opening the file in a spreadsheet sees mm or m, mm² or
    m², in the header; the bare names said nothing of it."""
    named = column_units(units)
    return [f"{c}_{named[c]}" if c in named else c for c in _CSV_COLUMNS]


def _cell(value):
    if value is None:
        return ""
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) else ""
    if isinstance(value, (list, tuple)):
        return ";".join(_cell(v) for v in value)
    return str(value)


#: The characters a spreadsheet may split a CSV line at: LibreOffice Calc's text import
#: splits at a comma, a semicolon and a tab unless told otherwise (its default separators),
#: Excel at the list separator of its locale (a semicolon in much of Europe).
_CSV_SEPARATORS = ",;\t"


def _csv_field(text):
    """A CSV field: quoted (its quotes doubled) when it holds a separator of
    :data:`_CSV_SEPARATORS`, a quote or a line break, so that a spreadsheet splitting at any
    of them keeps it one cell (the list cells, "1471.1;1474.5;...", were cut into as many
    cells by LibreOffice's default import, every later column moved to the right)."""
    if any(c in text for c in _CSV_SEPARATORS + '"\r\n'):
        return '"' + text.replace('"', '""') + '"'
    return text


def write_schedule_csv(path, rows, units="mm"):
    """CSV, one row per panel, comma-separated, the header the column names with the
    units of the model's length unit ``units`` (:func:`csv_header`); list cells joined with
    ';' and quoted (see :func:`_csv_field`); floats as repr (17 significant digits where
    needed), a point as the decimal separator."""
    lines = [",".join(_csv_field(c) for c in csv_header(units))]
    for row in rows:
        lines.append(",".join(_csv_field(_cell(row.get(c))) for c in _CSV_COLUMNS))
    write_text(path, ["\n".join(lines) + "\n"])


def write_schedule_json(path, rows, meta=None, units="mm"):
    """JSON: {"meta": ..., "panels": rows}; ``meta`` gains ``column_units``
    (:func:`column_units` of the model's length unit ``units``)."""
    meta = dict(meta or {}, column_units=column_units(units))
    text = json.dumps(json_safe({"meta": meta, "panels": rows}), allow_nan=False,
                      indent=1) + "\n"
    write_text(path, [text])


def _svg_path(points):
    return "M " + " L ".join(f"{x!r} {y!r}" for x, y in points) + " Z"


#: Layer name -> its colour in the SVG and PNG previews (the DXF's ACI colours: red, blue,
#: green, cyan, grey, magenta).
PREVIEW_COLOURS = {"CUT": "#c00", "LABEL": "#003", "BEVEL": "#070", "TOP": "#089",
                   "SHEET": "#777", "GRAIN": "#a0a"}


def write_svg(directory, nest_result, drawings, stem="sheet", units="mm", progress=None):
    """One SVG preview per sheet (``stem_01.svg``...), in model units with y up, at true
    size: the drawing's width and height are the sheet's in millimetres, from `units` (the
    model's length unit, a key of LENGTH_UNITS), so that a laser cutter's software or
    Inkscape opens a sheet at the size it is cut (it was 1000 pixels wide whatever the
    sheet). It holds what the DXF holds, each DXF layer an Inkscape layer (a group named
    and labelled by the layer, its meaning as its title), in :data:`PREVIEW_COLOURS`:
    the cut outlines, the top outlines dashed, the IDs, the bevel angles, the grain arrows.
    ``progress`` as :func:`write_png`'s.

    Returns
    -------
    list of str
    """
    from xml.sax.saxutils import escape

    mm = length_unit(units)[0]
    os.makedirs(directory, exist_ok=True)
    numbered = _numbered_in(directory, stem, ".svg")
    w, h = nest_result.sheet_size
    by_sheet = _by_sheet(nest_result, drawings)
    report = _reporter(progress, len(nest_result.sheets), "SVG previews")
    written = []
    stroke = max(w, h) / 1500.0
    dashes = " ".join(repr(length / mm) for length in DASH_MM)
    font = f'font-family="{OUTLINE_FONT}, sans-serif" text-anchor="middle"'
    # each layer's group: its look, then its elements
    looks = {"SHEET": f'fill="#f4f1ea" stroke="{PREVIEW_COLOURS["SHEET"]}"',
             "CUT": f'fill="#c9d8e8" stroke="{PREVIEW_COLOURS["CUT"]}"',
             "TOP": f'fill="none" stroke="{PREVIEW_COLOURS["TOP"]}" '
                    f'stroke-dasharray="{dashes}"',
             "GRAIN": f'fill="none" stroke="{PREVIEW_COLOURS["GRAIN"]}"',
             # (the font of the DXF's texts as outlines, not the viewer's serif default)
             "LABEL": f'fill="{PREVIEW_COLOURS["LABEL"]}" {font}',
             "BEVEL": f'fill="{PREVIEW_COLOURS["BEVEL"]}" {font}'}
    for i, sheet in enumerate(nest_result.sheets):
        report(i)
        layers = {name: [] for name in looks}
        layers["SHEET"].append(f'<rect x="0" y="0" width="{w!r}" height="{h!r}"/>')
        for pl, d in by_sheet.get(i, []):
            cut, top, texts, grain = _drawn(pl, d, (w, h))
            layers["CUT"].append(f'<path d="{_svg_path(cut)}"/>')
            if top is not None:
                layers["TOP"].append(f'<path d="{_svg_path(top)}"/>')
            for a, b in grain:
                layers["GRAIN"].append(f'<line x1="{a[0]!r}" y1="{a[1]!r}" x2="{b[0]!r}" '
                                       f'y2="{b[1]!r}"/>')
            for text, x, y, height, rotation, layer in texts:
                x, y, size = map(float, _preview_text(x, y, height, rotation))
                # upright (scale), then turned as in the DXF: counter-clockwise on the
                # sheet is a negative angle in the text's y-down frame
                turn = -rotation
                layers[layer].append(
                    f'<text x="{x!r}" y="{-y!r}" '
                    f'transform="scale(1 -1) rotate({turn!r} {x!r} {-y!r})" '
                    f'font-size="{size!r}">{escape(text)}</text>')
        out = [f'<svg xmlns="http://www.w3.org/2000/svg" '
               'xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" '
               f'viewBox="0 0 {w!r} {h!r}" '
               # (ten digits: 1219.2mm, not 1219.1999999999998mm, for a 48 in sheet)
               f'width="{w * mm:.10g}mm" height="{h * mm:.10g}mm">',
               f'<title>{_sheet_title(i, sheet)}</title>']
        for name, elements in layers.items():
            if not elements:
                continue
            out.append(f'<g id="{name}" inkscape:groupmode="layer" inkscape:label="{name}" '
                       f'transform="matrix(1 0 0 -1 0 {h!r})" {looks[name]} '
                       f'stroke-width="{stroke!r}">')
            out.append(f"<title>{escape(LAYER_MEANINGS[name])}</title>")
            out += elements
            out.append("</g>")
        out.append("</svg>\n")
        target = numbered(_sheet_number(i + 1, len(nest_result.sheets)))
        write_text(target, ["\n".join(out)])
        written.append(target)
    report(len(nest_result.sheets))
    _remove_stale(numbered, written)
    return written


def write_png(directory, nest_result, drawings, stem="sheet", dpi=100, progress=None):
    """One PNG preview per sheet (matplotlib, Agg): the cut outlines, the top outlines
    dashed, the IDs, the bevel angles at their size and the grain arrows, in
    :data:`PREVIEW_COLOURS`. ``progress(done, total)`` before each
    sheet and at the end, True cancels (:class:`facet.errors.Cancelled`; the sheets written
    so far stay, unless in :func:`facet.io.files.staged`, as ``facet panels`` writes).

    Returns
    -------
    list of str
    """
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from matplotlib.patches import Polygon as MplPolygon
    from matplotlib.patches import Rectangle

    os.makedirs(directory, exist_ok=True)
    numbered = _numbered_in(directory, stem, ".png")
    w, h = nest_result.sheet_size
    by_sheet = _by_sheet(nest_result, drawings)
    report = _reporter(progress, len(nest_result.sheets), "PNG previews")
    written = []
    colour = PREVIEW_COLOURS
    for i, sheet in enumerate(nest_result.sheets):
        report(i)
        fig, ax = plt.subplots(figsize=(10, 10 * h / w + 0.6))
        ax.set_xlim(-0.02 * w, 1.02 * w)
        ax.set_ylim(-0.02 * h, 1.02 * h)
        ax.set_aspect("equal")
        ax.set_title(_sheet_title(i, sheet))
        ax.add_patch(Rectangle((0, 0), w, h, facecolor="#f4f1ea", edgecolor=colour["SHEET"]))
        # points per model unit: the texts at their size on the part, as in the DXF
        ax.apply_aspect()
        x0, x1 = ax.transData.transform([(0.0, 0.0), (1.0, 0.0)])[:, 0]
        points = (x1 - x0) * 72.0 / fig.dpi
        for pl, d in by_sheet.get(i, []):
            cut, top, texts, grain = _drawn(pl, d, (w, h))
            ax.add_patch(MplPolygon(cut, closed=True, facecolor="#c9d8e8",
                                    edgecolor=colour["CUT"], linewidth=0.6))
            if top is not None:
                ax.add_patch(MplPolygon(top, closed=True, fill=False, edgecolor=colour["TOP"],
                                        linewidth=0.4, linestyle=(0, (4, 1))))
            for a, b in grain:
                ax.plot([a[0], b[0]], [a[1], b[1]], color=colour["GRAIN"], linewidth=0.6)
            for text, x, y, height, rotation, layer in texts:
                x, y, size = _preview_text(x, y, height, rotation)
                if size * points >= 1.0:  # (smaller is a dot at this resolution)
                    ax.text(x, y, text, ha="center", va="baseline", fontsize=size * points,
                            rotation=rotation, rotation_mode="anchor", color=colour[layer])
        target = numbered(_sheet_number(i + 1, len(nest_result.sheets)))
        try:
            write_replacing(target, lambda tmp: fig.savefig(tmp, dpi=dpi), ".png")
        finally:
            plt.close(fig)
        written.append(target)
    report(len(nest_result.sheets))
    _remove_stale(numbered, written)
    return written
