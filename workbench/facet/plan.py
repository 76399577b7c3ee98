# SPDX-License-Identifier: LGPL-2.1-or-later
"""Plan graphs from what architects draw, and target heights for them.

A *plan graph* is a planar straight-line graph with faces: the panels of a
roof or canopy seen from above. :func:`read_plan` makes one from

========================  ==================================================
``.dxf``                  LINE, LWPOLYLINE, POLYLINE (through ezdxf); ARC,
                          CIRCLE, ELLIPSE, SPLINE and polyline bulges are
                          refused unless ``arc_tolerance`` is given, then
                          split into segments whose sagitta is at most it;
                          layers that are off or frozen are not read
``.csv``                  segments, one ``x1,y1,x2,y2`` per line
``.obj .off .json``       a mesh lying in a plane (compas form diagrams
                          too): its faces are the plan's faces, projected
                          vertically
========================  ==================================================

A line drawing (DXF, CSV, or :func:`plan_from_segments`) becomes a graph as
follows: endpoints closer than ``snap`` are merged (default 1e-6 of the
drawing's size), crossings and touching segments are split into vertices
and overlapping segments merged (shapely's noding), the bounded faces are
found by shapely's ``polygonize`` (GEOS), and dangling edges (and bridges
with the same face on both sides) are dropped and listed in
``PlanGraph.dangling``. Faces containing one of the ``openings`` points
become openings: no panel. A face with a hole that no edge joins to its
outline cannot be one panel: that is an error naming where it is.

Targets (:func:`targets_from_mesh`, :func:`targets_from_points`,
:func:`pinned_targets`) return ``(targets, weights)`` arrays per plan vertex.
"""

import csv
import itertools
import math
import os
from dataclasses import dataclass, field

import numpy as np

from facet.errors import InputError, report_progress
from facet.report import count_noun, first_names, length_text, point_text
from facet.mesh import PolyMesh, boundary_corners, cluster_points

__all__ = [
    "PlanError",
    "PlanGraph",
    "read_plan",
    "plan_from_segments",
    "plan_from_mesh",
    "read_segments",
    "targets_from_mesh",
    "targets_from_points",
    "pinned_targets",
    "pin_vertices",
    "match_tolerance",
    "read_targets",
    "FREE_WEIGHT",
    "OPTION_NAMES",
]

#: Weight of a vertex with no target of its own (pinned heights, point
#: files): it is pulled, this weakly, towards the best-fitting plane of the
#: given targets, which makes the optimum unique without bending it. With
#: more free vertices than given ones it is lowered in proportion (to at
#: most 1e-4 of itself), so that the free vertices together weigh what the
#: given ones would at this weight: 3,716 free vertices at 1e-6 had pulled
#: five pins 1.8 mm off on a 60 m plan.
FREE_WEIGHT = 1e-6

#: Largest coordinate magnitude accepted (FACET_COORDINATE_MAX of the core).
COORDINATE_MAX = 1e30


#: How the plan's messages name the options they advise (the value follows, in the plan's
#: unit): the Python keywords ("tolerance": the match distance of target points); `facet
#: lift` and the FreeCAD PlanGraph and Lifting give theirs (``option_names=``).
OPTION_NAMES = {"snap": "snap", "arc_tolerance": "arc_tolerance", "tolerance": "tolerance"}

#: The unit of lengths in messages about a plan read in its drawing's own units when the
#: drawing does not say which ($INSUNITS 0, a table, a mesh).
DRAWING_UNITS = "drawing units"


def _option_names(option_names):
    """OPTION_NAMES with the caller's names."""
    return dict(OPTION_NAMES, **(option_names or {}))


class PlanError(InputError):
    """A drawing is not a plan: no bounded face, overlapping faces, a face
    with a loose hole, an arc without a tolerance, an unreadable entity."""


@dataclass
class PlanGraph:
    """A plan: vertices in the xy plane (z = 0) and faces.

    Attributes
    ----------
    mesh : facet.PolyMesh
        Vertices (x, y, 0) and the faces, each counter-clockwise seen from
        above.
    source : str or None
        File it came from.
    snap : float
        Snapping distance used (model units).
    dangling : list of ((x1, y1), (x2, y2))
        Edges dropped because they bound no face.
    openings : int
        Faces dropped as openings.
    snapped : int
        Endpoints moved by snapping (to the mean of their cluster), or splitting a
        segment they lay within the snap distance of.
    warnings : list of str
        What the lifting should know about the plan (a plan mesh whose faces meet in
        plan without sharing their vertices: lifted apart; dangling edges dropped).
    units : str or None
        The unit its lengths are in, as its messages name it ("mm", "m", "drawing
        units"); None: not known (no unit named).
    """

    mesh: PolyMesh
    source: object = None
    snap: float = 0.0
    dangling: list = field(default_factory=list)
    openings: int = 0
    snapped: int = 0
    warnings: list = field(default_factory=list)
    units: object = None

    @property
    def n_vertices(self):
        return self.mesh.n_vertices

    @property
    def n_faces(self):
        return self.mesh.n_faces

    def summary(self):
        return {
            "vertices": int(self.mesh.n_vertices),
            "faces": int(self.mesh.n_faces),
            "dangling_edges": len(self.dangling),
            "openings": int(self.openings),
            "snapped_endpoints": int(self.snapped),
            "snap": float(self.snap),
            "warnings": list(self.warnings),
        }


def _where(source):
    return f"{os.fspath(source)}: " if source is not None else ""


# ------------------------------------------------------------------ segments


#: The most straight segments one curve of a drawing is split into: a face's lifting costs
#: about the cube of its corners (2,000 corners take seconds), and a tiny arc tolerance
#: asked for millions (1e-8 on one arc: ten minutes and 6 GB before it was stopped).
MAX_CURVE_SEGMENTS = 2000


#: Millimetres per drawing unit by a DXF's $INSUNITS (exact; ezdxf's own factor for inches
#: is 25.400000000101603), with the unit's name. 0 (unitless) and the astronomical units
#: are not here: such a drawing is read as drawn.
DXF_UNITS_MM = {1: (25.4, "inches"), 2: (304.8, "feet"), 3: (1609344.0, "miles"),
                4: (1.0, "millimetres"), 5: (10.0, "centimetres"), 6: (1000.0, "metres"),
                7: (1e6, "kilometres"), 8: (2.54e-5, "microinches"), 9: (0.0254, "mils"),
                10: (914.4, "yards"), 11: (1e-7, "angstroms"), 12: (1e-6, "nanometres"),
                13: (1e-3, "micrometres"), 14: (100.0, "decimetres"), 15: (1e4, "decametres"),
                16: (1e5, "hectometres")}

#: The symbols of the common units of DXF_UNITS_MM, by $INSUNITS (messages give lengths in
#: a drawing's unit: "0.354 m"); the others by name.
DXF_UNIT_SYMBOLS = {1: "in", 2: "ft", 4: "mm", 5: "cm", 6: "m", 7: "km", 10: "yd"}


def _positive(value, path, what):
    """`value` as a float, or PlanError naming the file and `what` (it must be a finite
    number > 0)."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if not 0.0 < number < math.inf:
        raise PlanError(f"{path}: {what} must be a finite number > 0, not {value!r}")
    return number


def _unit_name(mm):
    """The name of the unit of `mm` millimetres ("metres"), or "units of {mm} mm"."""
    names = [name for scale, name in DXF_UNITS_MM.values() if scale == mm]
    return names[0] if names else f"units of {mm:g} mm"


def _scaled(segments, scale):
    if scale is None or scale == 1.0:
        return segments
    return [((a[0] * scale, a[1] * scale), (b[0] * scale, b[1] * scale)) for a, b in segments]


def _flatten(path_obj, tolerance, what="a curve", corners=0, said=None):
    """The straight segments of a path; at most MAX_CURVE_SEGMENTS of them besides its
    `corners` (a polyline's own vertices). `said`: the arc tolerance as the user gave it
    ("5 mm (the PlanGraph's ArcTolerance)"), for the message."""
    points = []
    for p in path_obj.flattening(tolerance):
        points.append((float(p.x), float(p.y)))
        if len(points) > MAX_CURVE_SEGMENTS + corners + 1:
            what = what() if callable(what) else what
            raise PlanError(f"{what}: the arc tolerance {said or format(tolerance, 'g')} would "
                            f"split it into more than {MAX_CURVE_SEGMENTS} straight segments; "
                            "give a larger one")
    return list(zip(points[:-1], points[1:]))


def _dxf_segments(path, arc_tolerance, notes=None, to_mm=False, units_mm=None, units=None,
                  option_names=None, info=None):
    """The segments of a DXF (see read_segments); ``info["units"]``, if given, is set to
    the unit they are in as messages name it: `units` when given, else mm when scaled,
    else the drawing's $INSUNITS, else DRAWING_UNITS."""
    try:
        import ezdxf
        from ezdxf import path as ezpath
    except ImportError as exc:  # pragma: no cover - ezdxf is a listed dependency
        raise PlanError(f"{path}: reading DXF needs ezdxf ({exc})") from None
    try:
        if os.path.getsize(path) == 0:
            raise PlanError(f"{path}: file is empty")
        with open(path, "rb"):
            pass
    except OSError as exc:
        raise PlanError(f"{path}: cannot read the file ({exc.strerror})") from None
    try:
        document = ezdxf.readfile(os.fspath(path))
    except IOError:
        # the file opens (checked above): ezdxf says it is not DXF
        raise PlanError(f"{path}: not a DXF file (no DXF header: binary DXF, DWG or "
                        "another format?)") from None
    except ezdxf.DXFStructureError as exc:
        # ezdxf quotes the offending tag, newline included
        raise PlanError(f"{path}: not a valid DXF file ({_one_line(exc)})") from None
    except MemoryError:
        raise
    except Exception as exc:  # noqa: BLE001 - see below
        # ezdxf is the parser here: DXFValueError (a layer name it cannot
        # take), and, on damaged files, whatever its tag
        # reader meets (OverflowError from a group code "inf", ValueError,
        # UnicodeDecodeError, IndexError... found by fuzzing). All of them
        # mean "ezdxf cannot read this file"; say so in one line.
        raise PlanError(f"{path}: not a valid DXF file ({_exception_line(exc)})") from None
    scale = 1.0
    code = document.header.get("$INSUNITS", 0)
    code = code if isinstance(code, int) else 0
    drawn = DXF_UNIT_SYMBOLS.get(code, DXF_UNITS_MM.get(code, (None, DRAWING_UNITS))[1])
    given = arc_tolerance
    if to_mm or units_mm is not None:
        scale, unit = DXF_UNITS_MM.get(code, (1.0, None))
        drawn = "mm" if unit is not None or units_mm is not None else drawn
        if units_mm is not None:
            if unit is not None and scale != units_mm and notes is not None:
                notes.append(f"drawn in {unit} ($INSUNITS {code}) but read in "
                             f"{_unit_name(units_mm)}, as asked")
            scale = units_mm
        elif scale != 1.0 and notes is not None:
            notes.append(f"drawn in {unit} ($INSUNITS {code}): read in millimetres, "
                         f"scaled by {scale:g}")
        if arc_tolerance is not None:
            arc_tolerance = float(arc_tolerance) / scale  # (given in mm)
    units = units or drawn
    if info is not None:
        info["units"] = units
    reader = _DxfReader(path, document, arc_tolerance, ezpath, scale, units,
                        _option_names(option_names))
    if given is not None:
        reader.said = f"{length_text(units)(float(given), 'g')} ({reader.names['arc_tolerance']})"
    try:
        return _scaled(_dxf_model_segments(reader, document, notes), scale)
    except (PlanError, MemoryError):
        raise
    except Exception as exc:  # noqa: BLE001 - an entity ezdxf loaded but cannot answer for
        raise PlanError(f"{path}: a malformed entity ({_exception_line(exc)})") from None


def _one_line(exc):
    """An exception's message on one line, at most 200 characters."""
    text = " ".join(str(exc).split())
    return text[:197] + "..." if len(text) > 200 else text


def _exception_line(exc):
    text = _one_line(exc)
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


def _dxf_model_segments(reader, document, notes=None):
    path, segments, skipped, hidden = reader.path, reader.segments, reader.skipped, reader.hidden
    reader.entities(document.modelspace())
    if hidden and notes is not None:
        ways = (["turn a layer on (and thaw it)"] if set(hidden) - {None} else []) + \
            (["make the entity visible"] if None in hidden else [])
        notes.append(f"left out {_hidden_text(hidden)}: {' or '.join(ways)} to read what is "
                     "drawn there")
    if not segments:
        found = ", ".join(f"{n} {k}" for k, n in sorted(skipped.items())) or "nothing"
        if hidden:
            found += f"; {_hidden_text(hidden)}, left out"
        # a plan drawn on a layout (paper space), which is not read: say where it is
        drawn = "LINE LWPOLYLINE POLYLINE ARC CIRCLE ELLIPSE SPLINE INSERT"
        paper = [(layout.name, len(layout.query(drawn))) for layout in document.layouts
                 if layout.name != "Model"]
        paper = [(name, n) for name, n in paper if n]
        if paper:
            names = first_names((name for name, _ in paper), 3)
            count = sum(n for _, n in paper)
            found += (f"; {count} {'entity' if count == 1 else 'entities'} on the "
                      f"layout{'s' if len(paper) > 1 else ''} {names} (paper space), "
                      "which Facet does not read: draw the plan in the model space")
        raise PlanError(f"{path}: no LINE, LWPOLYLINE or POLYLINE in the model space ({found})")
    return segments


def _hidden_text(hidden):
    """'12 entities on layers that are off or frozen (CONSTRUCTION 10, GRID 2) and
    1 entity flagged invisible' (the invisible ones are counted under None)."""
    def entities(n):
        return f"{n} {'entity' if n == 1 else 'entities'}"

    parts = []
    layers = sorted(((name, n) for name, n in hidden.items() if name is not None),
                    key=lambda item: (-item[1], item[0]))
    if layers:
        named = ", ".join(f"{name} {count}" for name, count in layers[:6])
        more = f", {len(layers) - 6} more layers" if len(layers) > 6 else ""
        parts.append(f"{entities(sum(n for _, n in layers))} on layers that are off or "
                     f"frozen ({named}{more})")
    if hidden.get(None):
        parts.append(f"{entities(hidden[None])} flagged invisible")
    return " and ".join(parts)


#: Blocks inside blocks deeper than this are refused (a block that holds itself).
_DXF_BLOCK_DEPTH = 16


class _DxfReader:
    """Appends the straight segments of DXF entities (in world coordinates) to
    `segments`; the block references' contents too (INSERT, placed as drawn).

    What is not shown is not read, as a CAD program shows it: entities flagged
    invisible, and entities on a layer that is off or frozen, counted by layer
    in `hidden`. An entity of a block on layer 0 takes the layer of the INSERT
    that places it, and everything an INSERT on a frozen layer places is hidden.
    Other entities are counted by type in `skipped`.

    A curve refused is named with its layer and where it is, its points times `scale`
    followed by `units` (the unit the drawing is read in); the arc tolerance it asks for
    by ``names["arc_tolerance"]``."""

    def __init__(self, path, document, arc_tolerance, ezpath, scale=1.0, units=None,
                 names=None):
        self.path, self.arc_tolerance, self.ezpath = path, arc_tolerance, ezpath
        self.segments, self.skipped, self.hidden = [], {}, {}
        self.scale, self.units = scale, units
        self.names = names or dict(OPTION_NAMES)
        self.said = None  # the arc tolerance as given, for messages
        self.layer_state = {}  # by lower-case name: (off, frozen, the table's spelling)
        for layer in document.layers:
            name = layer.dxf.name
            self.layer_state[name.lower()] = (layer.is_off(), layer.is_frozen(), name)

    def _hide(self, layer):
        """Count an entity left out: on `layer` (as the table spells it), or None when it
        is flagged invisible."""
        self.hidden[layer] = self.hidden.get(layer, 0) + 1

    def entities(self, entities, parent_layer=None, depth=0, block=None):
        for entity in entities:
            layer = entity.dxf.get("layer", "0")
            if parent_layer is not None and layer == "0":
                layer = parent_layer  # drawn on layer 0 in the block: the INSERT's layer
            off, frozen, spelled = self.layer_state.get(layer.lower(), (False, False, layer))
            if entity.dxf.get("invisible", 0):
                self._hide(None)
                continue
            kind = entity.dxftype()
            if kind == "INSERT":
                if frozen:
                    self._hide(spelled)
                    continue
                self.insert(entity, layer, depth, block)
            elif off or frozen:
                self._hide(spelled)
            else:
                self.entity(entity, kind, block, spelled)

    def insert(self, entity, layer, depth, block):
        where = self._name(entity, "INSERT", block)
        if depth >= _DXF_BLOCK_DEPTH:
            raise PlanError(f"{self.path}: {where}: blocks nested more than "
                            f"{_DXF_BLOCK_DEPTH} deep (a block that holds itself?)")
        inside = f"block {entity.dxf.get('name', '?')} of {where}"
        # an array of the block (MINSERT: rows x columns): every cell
        cells = entity.multi_insert() if entity.mcount > 1 else (entity,)
        for cell in cells:
            self.entities(cell.virtual_entities(), layer, depth + 1, inside)

    @staticmethod
    def _name(entity, kind, block):
        """'LWPOLYLINE 2F', or for an entity of a block (which has no handle of its own)
        'LWPOLYLINE in block B of INSERT 3A'."""
        handle = entity.dxf.get("handle", None)
        if handle:
            return f"{kind} {handle}"
        return f"{kind} in {block}" if block else kind

    def _place(self, entity, kind, layer):
        """Where a curve is, for a message: "on layer ROOF from (0, 0) to (5, 5) m" (an
        open curve's ends), "... around (2.5, 2.5) m" (a closed one's middle), "... at
        (0, 0) m" (a polyline's first arc segment's start), in the unit the drawing is
        read in."""
        def point(p, units=self.units):
            return point_text((float(p[0]) * self.scale, float(p[1]) * self.scale), units)

        on = f" on layer {layer}" if layer else ""
        try:
            if kind in ("LWPOLYLINE", "POLYLINE"):
                if kind == "LWPOLYLINE":
                    elevation = float(entity.dxf.get("elevation", 0.0))
                    rows = [(x, y, elevation, b) for x, y, b in entity.get_points("xyb")]
                else:
                    rows = [tuple(v.dxf.location) + (v.dxf.get("bulge", 0.0),)
                            for v in entity.vertices]
                first = next(k for k, row in enumerate(rows) if abs(row[3]) > 0)
                corner = [rows[first][:3]]
                if kind == "LWPOLYLINE" or entity.is_2d_polyline:
                    corner = list(entity.ocs().points_to_wcs(corner))
                return f"{on} at {point(corner[0])}"
            path = self.ezpath.make_path(entity)
            start, end = path.start, path.end
            if start.isclose(end):
                middle = self.ezpath.bbox([path]).center
                return f"{on} around {point(middle)}"
            return f"{on} from {point(start, None)} to {point(end)}"
        except Exception:  # noqa: BLE001 - a place is a help; a malformed entity is named
            return on

    def entity(self, entity, kind, block=None, layer=None):
        path, segments, arc_tolerance, ezpath = (self.path, self.segments, self.arc_tolerance,
                                                 self.ezpath)
        name = self._name(entity, kind, block)
        if kind == "LINE":
            s, e = entity.dxf.start, entity.dxf.end
            segments.append(((float(s.x), float(s.y)), (float(e.x), float(e.y))))
        elif kind in ("LWPOLYLINE", "POLYLINE"):
            if kind == "POLYLINE" and (entity.is_polygon_mesh or entity.is_poly_face_mesh):
                raise PlanError(f"{path}: {name} is a mesh, not a line drawing")
            bulges = ([b[0] for b in entity.get_points("b")] if kind == "LWPOLYLINE" else
                      [v.dxf.get("bulge", 0.0) for v in entity.vertices])
            if any(abs(b) > 0 for b in bulges):
                if arc_tolerance is None:
                    raise PlanError(
                        f"{path}: {name}{self._place(entity, kind, layer)} has arc segments "
                        f"(bulges): give an arc tolerance ({self.names['arc_tolerance']}) to "
                        "split arcs into straight segments"
                    )
                segments.extend(_flatten(ezpath.make_path(entity), arc_tolerance,
                                         lambda: f"{path}: {name}"
                                         f"{self._place(entity, kind, layer)}",
                                         corners=len(bulges), said=self.said))
                return
            if kind == "LWPOLYLINE":
                elevation = float(entity.dxf.get("elevation", 0.0))
                points = [(float(x), float(y), elevation) for x, y in entity.get_points("xy")]
                closed = entity.closed
            else:
                # a spline-fit polyline is shown through its fitted vertices; its
                # control frame's (flag 16) are not drawn
                points = [tuple(v.dxf.location) for v in entity.vertices
                          if not v.dxf.get("flags", 0) & 16]
                closed = entity.is_closed
            if kind == "LWPOLYLINE" or entity.is_2d_polyline:
                # in the polyline's own coordinate system (a mirrored one has z down):
                # to world coordinates
                points = list(entity.ocs().points_to_wcs(points))
            points = [(float(p[0]), float(p[1])) for p in points]
            if closed and len(points) > 1:
                points.append(points[0])
            segments.extend(zip(points[:-1], points[1:]))
        elif kind in ("ARC", "CIRCLE", "ELLIPSE", "SPLINE"):
            if arc_tolerance is None:
                raise PlanError(
                    f"{path}: {name}{self._place(entity, kind, layer)} is curved: give an arc "
                    f"tolerance ({self.names['arc_tolerance']}) to split it into straight "
                    "segments"
                )
            segments.extend(_flatten(ezpath.make_path(entity), arc_tolerance,
                                     lambda: f"{path}: {name}"
                                     f"{self._place(entity, kind, layer)}", said=self.said))
        else:
            self.skipped[kind] = self.skipped.get(kind, 0) + 1


#: Tables of numbers (segments or points): comma-separated, or tab-separated as
#: spreadsheets export text ("Unicode Text" is UTF-16 and tab-separated, .txt).
TABLE_SUFFIXES = (".csv", ".tsv", ".txt")


def _csv_rows(path, error):
    """(line number, non-empty stripped cells) of a CSV file, comments and
    blank lines left out. A file that is not text (control bytes beside bytes
    that are not UTF-8, or a NUL) raises `error` naming the first bad byte; in
    a text file, bytes that are not UTF-8 (a Latin-1 header) become U+FFFD, so
    the line is skipped as a header or refused as not numbers, by its number.
    OSError is raised as `error` too."""
    try:
        with open(path, "rb") as handle:
            data = handle.read()
    except OSError as exc:
        raise error(f"{path}: cannot read the file ({exc.strerror})") from None
    from facet.io.files import bom_encoding, split_lines

    encoding = bom_encoding(data)
    if encoding in ("utf-16", "utf-32"):
        # Windows "Unicode" text (Excel's "Unicode Text" export, PowerShell's >): its NULs
        # are the encoding's, not binary data
        text = data.decode(encoding, errors="replace")
    else:
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError as exc:
            if b"\0" in data or any(b < 32 and b not in b"\t\n\r\f" for b in data[:4096]):
                raise error(f"{path}: not a text file: byte {exc.start + 1} is not UTF-8 "
                            "(binary data?)") from None
            text = data.decode("utf-8", errors="replace")
        nul = data.find(b"\0")
        if nul >= 0:
            raise error(f"{path}: not a text file: byte {nul + 1} is NUL (binary data?)")
    for number, line in enumerate(split_lines(text), 1):  # (split_lines drops a BOM)
        delimiter = _delimiter(line)
        try:
            row = next(csv.reader([line], delimiter=delimiter), [])
        except csv.Error as exc:
            raise error(f"{path}: line {number}: not CSV ({exc})") from None
        cells = [c.strip() for c in row]
        while cells and not cells[-1]:
            cells.pop()  # (trailing separators: a row shorter than the widest)
        while cells and not cells[0]:
            cells.pop(0)
        if delimiter != ",":
            cells = [_decimal_comma(c, delimiter) for c in cells]
        # an empty cell between two others stays: a missing value, refused by its line
        # (left out, it moved the next column into its place)
        if cells and not cells[0].startswith("#"):
            yield number, cells


def _delimiter(line):
    """A table line's separator: a semicolon where the line has one, with decimal commas:
    what Excel writes as CSV where the decimal separator is a comma (most of Europe); a tab
    where the line has tabs and no cell between them holds more than one comma or ends or
    starts with one (decimal commas again: what spreadsheets export as text; counting the
    tabs against the commas read '10,5<tab>0,5<tab>1,5' as comma-separated); a comma
    otherwise."""
    if ";" in line:
        return ";"
    if "\t" in line and all(c.count(",") <= 1 and not c.startswith(",") and
                            not c.endswith(",") for c in map(str.strip, line.split("\t"))):
        return "\t"
    return ","


def _decimal_comma(cell, delimiter):
    """A cell's decimal comma as a point ('3,5' -> '3.5'). In a tab-separated table, whose
    locale is not known, not where the comma may group thousands ('1,250': left, refused
    as not a number; '0,125' groups nothing); with semicolons (a comma locale's CSV),
    always."""
    if cell.count(",") != 1 or "." in cell:
        return cell
    whole, _, fraction = cell.partition(",")
    digits = whole.lstrip("+-")
    if (delimiter == "\t" and len(fraction) == 3 and 1 <= len(digits) <= 3
            and not digits.startswith("0")):
        return cell
    return whole + "." + fraction


def _cells_text(cells):
    """A table row's cells in a message: 'A | 0 |  | 3.5' (an empty one shown empty), at
    most 60 characters."""
    text = " | ".join(cells)
    return text if len(text) <= 60 else text[:57] + "..."


def _number_rows(path, error, names):
    """The rows of a table of numbers (:func:`_csv_rows`): (line number, values), as many
    values as ``names`` has ("x,y,z", "x1,y1,x2,y2"). A first line that is not numbers is a
    header, skipped; any other, or a line with another count or a value not finite, is
    ``error`` naming the line and quoting its cells."""
    count = names.count(",") + 1
    word = {3: "three", 4: "four"}[count]
    for number, cells in _csv_rows(path, error):
        try:
            values = [float(c) for c in cells]
        except ValueError:
            if number == 1:  # a header line
                continue
            raise error(f"{path}: line {number}: not {word} numbers {names} "
                        f"({_cells_text(cells)})") from None
        if len(values) != count or not all(np.isfinite(values)):
            raise error(f"{path}: line {number}: need {word} finite numbers {names} "
                        f"({_cells_text(cells)})")
        yield number, values


def _csv_segments(path):
    segments = []
    for _number, values in _number_rows(path, PlanError, "x1,y1,x2,y2"):
        segments.append(((values[0], values[1]), (values[2], values[3])))
    if not segments:
        raise PlanError(f"{path}: no segments")
    return segments


def read_segments(path, *, arc_tolerance=None, notes=None, to_mm=False, units_mm=None,
                  units=None, option_names=None, info=None):
    """The straight segments of a DXF or CSV drawing, ``[((x1, y1), (x2, y2)), ...]``.

    A DXF's entities on layers that are off or frozen, and those flagged
    invisible, are not read; what was left out is appended to the list `notes`
    (if given) as one line of text. With `to_mm` a DXF whose $INSUNITS names a
    length unit (:data:`DXF_UNITS_MM`) is scaled to millimetres (`arc_tolerance`
    is then in millimetres too), and a note says so; a unitless one, a CSV, are read
    as they are. Without it every drawing is read in its own units. `units_mm`
    (millimetres per drawing unit, > 0) reads every drawing at that scale instead,
    whatever its $INSUNITS (a note says where they disagree).

    Messages name lengths and points in `units` (default: the unit the drawing is read in,
    which is also set as ``info["units"]`` when a dict `info` is given: mm when scaled, a
    DXF's $INSUNITS unit ("m"), else DRAWING_UNITS) and the arc tolerance they advise by
    ``option_names["arc_tolerance"]`` (:data:`OPTION_NAMES`)."""
    suffix = os.path.splitext(os.fspath(path))[1].lower()
    if arc_tolerance is not None:
        _positive(arc_tolerance, path, "the arc tolerance")
    scale = None if units_mm is None else _positive(units_mm, path, "the drawing's unit in mm")
    if suffix == ".dxf":
        return _dxf_segments(path, arc_tolerance, notes, to_mm, scale, units, option_names,
                             info)
    if suffix in TABLE_SUFFIXES:
        if info is not None:
            info["units"] = units or ("mm" if scale is not None else DRAWING_UNITS)
        return _scaled(_csv_segments(path), scale)
    raise PlanError(f"{path}: not a line drawing (.dxf, or a .csv, .tsv or .txt table)")


# ------------------------------------------------------------------ plan graphs


def _check_chains(points, roots, snap, where, units=None, names=OPTION_NAMES):
    """Refuse a cluster of snapped endpoints wider than twice the snap distance: points
    joined pairwise within it, in a chain (a curve drawn in steps shorter than the snap
    distance), which would collapse whole edges into one vertex. Lengths in `units`; the
    snap distance named by ``names["snap"]``."""
    length = length_text(units)
    lo = np.full((len(points), 2), np.inf)
    hi = np.full((len(points), 2), -np.inf)
    np.minimum.at(lo, roots, points)
    np.maximum.at(hi, roots, points)
    width = np.hypot(*(hi - lo).T)
    width[~np.isfinite(width)] = 0.0
    for worst in np.flatnonzero(width > 2.0 * snap):
        # the box's diagonal is an upper bound: the two endpoints farthest apart
        members = np.unique(points[roots == worst], axis=0)
        a, b = _farthest_pair(members)
        spread = float(np.hypot(*(b - a)))
        if spread <= 2.0 * snap:
            continue
        a, b = a + 0.0, b + 0.0  # (+ 0.0: no "-0")
        raise PlanError(
            f"{where}the snap distance {length(snap, 'g')} ({names['snap']}) joins "
            f"{len(members)} endpoints in a chain {length(spread, '.6g')} wide, from "
            f"{point_text(a[:2])} to {point_text(b[:2], units)}: each is within the snap "
            "distance of the next, and all would become one vertex; give a snap distance "
            "smaller than the drawing's shortest edge")


def _farthest_pair(points):
    """The two of `points` (distinct, 2D) farthest apart, the one with the smaller x (then
    y) first: among the convex hull's corners (joggled for collinear points; the
    distances are the points' own)."""
    from scipy.spatial import ConvexHull
    from scipy.spatial.distance import cdist

    if len(points) > 16:
        points = points[ConvexHull(points, qhull_options="QJ").vertices]
    distances = cdist(points, points)
    i, j = np.unravel_index(int(np.argmax(distances)), distances.shape)
    a, b = sorted((points[i], points[j]), key=tuple)
    return a, b


#: At most this many (segment, point) candidates are tested at once by _points_inside (a
#: segment more when one alone has more): about 100 bytes each. Where long segments have
#: many endpoints in their balls (a hatch of 5,000 lines across a square, exploded: 25
#: million candidates) all of them at once took 2 GB and 7 s, against 60 MB and 0.9 s one
#: segment at a time.
CANDIDATES_AT_ONCE = 1 << 14


def _points_inside(tree, points, array, tolerance):
    """The `points` (the KD-tree `tree` holds them) within `tolerance` of the inside of a
    segment of `array` ((n, 2, 2)), not of its ends: ``(segment, point)`` index arrays,
    by segment, then along it. The candidates of many segments come from one query (a ball
    around each one's middle), tested together, up to CANDIDATES_AT_ONCE of them: a query
    and a test per segment took 1.8 s of a 200 x 200 grid plan's 8."""
    p, d = array[:, 0], array[:, 1] - array[:, 0]
    length = np.hypot(d[:, 0], d[:, 1])
    long_enough = np.flatnonzero(length > 2 * tolerance)
    none = np.zeros(0, dtype=np.int64)
    if not long_enough.size:
        return none, none
    centres = p[long_enough] + 0.5 * d[long_enough]
    radii = 0.5 * length[long_enough] + tolerance
    total = np.cumsum(tree.query_ball_point(centres, radii, return_length=True))
    found, first = [], 0
    while first < len(long_enough):
        before = int(total[first - 1]) if first else 0
        last = max(first + 1, int(np.searchsorted(total, before + CANDIDATES_AT_ONCE,
                                                  side="right")))
        block = slice(first, last)
        found.append(_inside(tree, points, long_enough[block], centres[block], radii[block],
                             p, d, length, tolerance))
        first = last
    return (np.concatenate([seg for seg, _ in found]),
            np.concatenate([point for _, point in found]))


def _inside(tree, points, segments, centres, radii, p, d, length, tolerance):
    """_points_inside of the segments ``segments`` (indices, ascending), whose balls are
    ``centres`` and ``radii``."""
    near = tree.query_ball_point(centres, radii, return_sorted=False)
    counts = np.fromiter(map(len, near), dtype=np.int64, count=len(near))
    seg = np.repeat(segments, counts)
    point = np.fromiter(itertools.chain.from_iterable(near), dtype=np.int64,
                        count=int(counts.sum()))
    rel = points[point] - p[seg]
    ds, ls = d[seg], length[seg]
    t = (rel[:, 0] * ds[:, 0] + rel[:, 1] * ds[:, 1]) / ls**2
    off = np.abs(rel[:, 0] * ds[:, 1] - rel[:, 1] * ds[:, 0]) / ls
    hit = (t > tolerance / ls) & (t < 1.0 - tolerance / ls) & (off <= tolerance)
    order = np.lexsort((t[hit], seg[hit]))  # (stable: ties keep the query's order)
    return seg[hit][order], point[hit][order]


def _split_at_endpoints(array, tolerance):
    """Segments (n, 2, 2) split at every endpoint within `tolerance` of their inside (not of
    their ends); returns the new segments and how many endpoints split one."""
    from scipy.spatial import cKDTree

    ends = np.unique(array.reshape(-1, 2), axis=0)
    seg, point = _points_inside(cKDTree(ends), ends, array, tolerance)
    if not seg.size:
        return array, 0
    first = np.searchsorted(seg, np.arange(len(array)), side="left")
    last = np.searchsorted(seg, np.arange(len(array)), side="right")
    pieces = []
    for k, (a, b) in enumerate(array):
        if first[k] == last[k]:
            pieces.append((a, b))
            continue
        corners = [a] + list(ends[point[first[k]:last[k]]]) + [b]
        pieces.extend(zip(corners[:-1], corners[1:]))
    return (np.asarray(pieces, dtype=np.float64).reshape(-1, 2, 2),
            int(np.unique(point).size))


#: The stages of reading a plan, as ``progress(done, total)`` counts them: each is
#: PLAN_STEPS steps, total PLAN_STAGES * PLAN_STEPS. A drawing's: reading the file,
#: snapping, splitting at endpoints, noding and finding the faces, the faces' corners, the
#: gap check. A plan mesh's (:func:`plan_from_mesh`): reading the file, dropping z, the
#: faces' outlines in plan, their union (the overlap check), naming an overlap, the joins.
PLAN_STAGES = 6
PLAN_STEPS = 1024


def _stage_reporter(progress):
    """``report(stage, fraction=0.0)`` for `progress` (may be None): ``progress(done,
    total)`` in PLAN_STAGES stages; True from it cancels (facet.Cancelled)."""
    def report(stage, fraction=0.0):
        done = stage * PLAN_STEPS + int(PLAN_STEPS * fraction)
        report_progress(progress, done, PLAN_STAGES * PLAN_STEPS, "reading the plan")

    return report


def _counter_clockwise(ring):
    """A closed ring's coordinates [(x, y), ..., first], reversed if it runs clockwise:
    shapely's ``orient(polygon, 1.0)`` on its outline (the same area sum, in the same
    order), without making a new polygon (40% of the faces' time on large plans)."""
    xs = [c[0] for c in ring] + [ring[1][0]]
    ys = [c[1] for c in ring] + [ring[1][1]]
    area = sum(xs[i] * (ys[i + 1] - ys[i - 1]) for i in range(1, len(ring))) / 2.0
    return ring if area >= 0.0 else ring[::-1]


def plan_from_segments(segments, *, snap=None, openings=(), source=None, progress=None,
                       units=None, option_names=None):
    """A plan graph from straight segments.

    Parameters
    ----------
    segments : iterable of ((x1, y1), (x2, y2))
    snap : float, optional
        Endpoints closer than this are merged, and an endpoint this close to
        another segment's inside splits it there (default 1e-6 of the
        drawing's bounding-box diagonal).
    openings : iterable of (x, y)
        Points inside faces that are openings (no panel).
    source : str, optional
        Named in messages.
    progress : callable, optional
        ``progress(done, total)`` between the stages (:data:`PLAN_STAGES`; the first,
        reading a file, is :func:`read_plan`'s) and through the faces; True cancels
        (:class:`facet.Cancelled`). A 40,000-face plan takes seconds.
    units : str, optional
        The unit of the segments ("mm"), named after every length and point in the
        messages and warnings (none named by default); kept as ``PlanGraph.units``.
    option_names : dict, optional
        How the user sets the options the messages advise (:data:`OPTION_NAMES`'s keys:
        `facet lift` "--snap", the PlanGraph "the PlanGraph's Snap"); the keywords by
        default.

    Dangling edges (they bound no face) are dropped and said in a warning: how many, the
    first three's ends, and what joins them (the nearest gap within 1% of the drawing's
    size and a twentieth of the edge: the snap distance above it).

    Raises
    ------
    PlanError
        No bounded face, a face with a hole not joined to its outline, or
        non-finite coordinates.
    """
    from shapely.geometry import LineString, MultiLineString, Point, Polygon
    from shapely.ops import polygonize_full, unary_union

    where = _where(source)
    names = _option_names(option_names)
    length = length_text(units)

    def at(point):
        return point_text(point, units)

    array = np.asarray(list(segments), dtype=np.float64).reshape(-1, 2, 2)
    if array.shape[0] == 0:
        raise PlanError(f"{where}the drawing has no segments")
    if not np.all(np.isfinite(array)):
        bad = int(np.flatnonzero(~np.all(np.isfinite(array), axis=(1, 2)))[0])
        raise PlanError(f"{where}segment {bad} has a NaN or infinite coordinate")
    beyond = np.abs(array) > COORDINATE_MAX
    if beyond.any():
        # the compiled core refuses them too; here the snapping's KD-tree
        # overflowed first (found by fuzzing: a CSV segment at 1e308)
        bad = int(np.flatnonzero(beyond.any(axis=(1, 2)))[0])
        raise PlanError(f"{where}segment {bad} has a coordinate beyond {COORDINATE_MAX:g} in magnitude")
    try:
        opening_xy = np.array([(float(x), float(y)) for x, y in openings],
                              dtype=np.float64).reshape(-1, 2)
    except (TypeError, ValueError):
        raise PlanError(f"{where}openings must be (x, y) points") from None
    if not np.all(np.isfinite(opening_xy)):
        bad = int(np.flatnonzero(~np.all(np.isfinite(opening_xy), axis=1))[0])
        x, y = opening_xy[bad]
        raise PlanError(f"{where}opening {bad} at {at((x, y))} is not a finite point")
    points = array.reshape(-1, 2)
    lower, upper = points.min(axis=0), points.max(axis=0)
    size = float(np.hypot(*(upper - lower)))
    if not size > 0:
        raise PlanError(f"{where}the drawing has no extent (all points coincide)")
    snap = 1e-6 * size if snap is None else float(snap)
    if not snap >= 0:
        raise PlanError(f"{where}snap distance ({names['snap']}) must be >= 0, not {snap}")
    report = _stage_reporter(progress)
    report(1)
    snapped = 0
    if snap > 0:
        roots = cluster_points(points, snap)
        _check_chains(points, roots, snap, where, units, names)
        # Each cluster goes to its mean position.
        sums = np.zeros_like(points)
        counts = np.zeros(len(points))
        np.add.at(sums, roots, points)
        np.add.at(counts, roots, 1)
        moved = sums[roots] / counts[roots][:, None]
        snapped = int(np.count_nonzero(np.any(moved != points, axis=1)))
        points = moved
    array = points.reshape(-1, 2, 2)
    report(2)
    if snap > 0:
        # an endpoint within the snap distance of another segment's inside (a line
        # drawn just short of the one it meets, or moved off it by the merge above)
        # splits that segment there: otherwise the two never meet and a face is lost
        array, joined = _split_at_endpoints(array, snap)
        snapped += joined
    report(3)
    keep = np.any(array[:, 0] != array[:, 1], axis=1)
    lines = [LineString(s) for s in array[keep]]
    if not lines:
        raise PlanError(f"{where}every segment is shorter than the snap distance "
                        f"{length(snap, 'g')} ({names['snap']})")
    noded = unary_union(MultiLineString(lines))
    polygons, dangles, cuts, invalids = polygonize_full(noded)
    dangling = []
    for geometry in list(getattr(dangles, "geoms", [])) + list(getattr(cuts, "geoms", [])):
        coords = list(geometry.coords)
        dangling.extend((tuple(a), tuple(b)) for a, b in zip(coords[:-1], coords[1:]))
    if len(getattr(invalids, "geoms", [])):
        g = invalids.geoms[0]
        x, y = g.coords[0]
        raise PlanError(f"{where}the edges near {at((x, y))} form a self-crossing ring")
    faces = list(getattr(polygons, "geoms", []))
    opened = set()  # the faces holding an opening point (one each: faces do not overlap)
    for x, y in opening_xy:
        point = Point(x, y)
        face = next((k for k, polygon in enumerate(faces) if polygon.contains(point)), None)
        if face is None:
            raise PlanError(f"{where}the opening at {at((x, y))} lies in no face of the "
                            "drawing (outside it, or on an edge): give a point inside the face "
                            "to leave open")
        opened.add(face)
    kept = [polygon for k, polygon in enumerate(faces) if k not in opened]
    n_openings = len(opened)
    for polygon in kept:
        if len(polygon.interiors):
            hole = polygon.interiors[0]
            x, y = hole.coords[0]
            around = at(polygon.representative_point().coords[0])
            # an opening given inside the hole (the atrium itself) leaves the face around it
            # as it was: the advice to mark "the face around the hole" must say which
            inside = [xy for xy in opening_xy if Polygon(hole).contains(Point(*xy))]
            raise PlanError(
                f"{where}the face around {around} has a hole at {at((x, y))}, "
                "and a face must be a simple polygon: draw two or more edges from the hole "
                "to the outline, which split the ring into faces (one edge is not enough), or "
                "mark the face around the hole as an opening"
                + (f" (a point such as {around}); the opening at {at(inside[0])} is inside "
                   "the hole, which leaves that face as it is" if inside else "")
            )
    if not kept:
        # where: an outline left open ("4 dangling edges" named no place to close it)
        ends = _free_ends(noded) if dangling else []
        raise PlanError(
            f"{where}the drawing has no bounded face"
            + (f" ({len(dangling)} dangling edges)" if dangling else "")
            + (f" besides {n_openings} openings" if n_openings else "")
            + (f"; lines end without meeting another at "
               f"{_and_list([point_text(p) for p in ends[:3]])}{' ' + units if units else ''}"
               + (f" and {len(ends) - 3} more" if len(ends) > 3 else "")
               + f": close the outline there (or give a snap distance ({names['snap']}) that "
               "joins them)"
               if ends else "")
        )
    # Vertices: the exact noded coordinates; faces counter-clockwise.
    index = {}
    vertices = []
    face_lists = []
    def place(polygon):
        point = polygon.representative_point()  # (a GEOS call: once, not for x and y)
        return point.x, point.y

    report(4)
    for k, polygon in enumerate(sorted(kept, key=place)):
        if k % 2048 == 2047:
            report(4, k / len(kept))
        ring = _counter_clockwise(list(polygon.exterior.coords))[:-1]
        face = []
        for xy in ring:
            key = (float(xy[0]), float(xy[1]))
            if key not in index:
                index[key] = len(vertices)
                vertices.append(key)
            face.append(index[key])
        face_lists.append(face)
    xyz = np.zeros((len(vertices), 3))
    xyz[:, :2] = vertices
    info = {"source": os.fspath(source)} if source is not None else {}
    mesh = PolyMesh.from_faces(xyz, face_lists, info=info)
    report(5)
    gap = _nearest_gap(noded, dangling, 0.01 * size, lambda f: report(5, f))
    warnings = [_dangling_warning(dangling, gap, units, names)] if dangling else []
    report(PLAN_STAGES)
    return PlanGraph(mesh, source=source, snap=snap, dangling=dangling, openings=n_openings,
                     snapped=snapped, warnings=warnings, units=units)


#: The dangling edges a warning names by their ends (the rest are counted).
DANGLING_NAMED = 3


def _dangling_warning(dangling, gap, units, names):
    """The warning for the dangling edges dropped: how many, the first DANGLING_NAMED ones'
    ends, and what joins them: where a gap was found (``gap``: (distance, end)), the snap
    distance above it; else extending them or a larger snap distance. A dangling ridge was
    dropped without a word (DanglingEdges 1, nothing drawn there)."""
    length = length_text(units)
    n = len(dangling)
    listed = _and_list([f"from {point_text(a)} to {point_text(b, units)}"
                        for a, b in dangling[:DANGLING_NAMED]])
    more = f" and {n - DANGLING_NAMED} more" if n > DANGLING_NAMED else ""
    text = (f"{count_noun(n, 'dangling edge')} {'bounds' if n == 1 else 'bound'} no face and "
            f"{'was' if n == 1 else 'were'} dropped, not part of the plan: {listed}{more}")
    if gap is not None:
        distance, end = gap
        return (f"{text}; an edge ends {length(distance)} short of another at "
                f"{point_text(end, units)}, and a face there is lost if they should meet: a "
                f"snap distance ({names['snap']}) above {length(distance)} joins them")
    them, they = ("it", "it") if n == 1 else ("them", "they")
    return (f"{text}: extend or join {them} to the lines {they} should meet, or give a "
            f"larger snap distance ({names['snap']}) that joins {'its' if n == 1 else 'their'} "
            "ends to them")


def _free_ends(noded):
    """The ends of the noded drawing's lines that meet no other line, in drawing order."""
    count = {}
    for line in getattr(noded, "geoms", [noded]):
        coords = [tuple(c[:2]) for c in line.coords]
        for p in (coords[0], coords[-1]):
            count[p] = count.get(p, 0) + 1
    return [p for p, n in count.items() if n == 1]


def _and_list(items):
    """'a', 'a and b', 'a, b and c'."""
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


def _nearest_gap(noded, dangling, limit, report=None):
    """(distance, point) of the free end of a dangling edge nearest another edge, when
    that is within `limit` and a twentieth of the edge's length (a line drawn just short of
    the one it meets: a face lost), else None. A free end: an end of one segment of the
    noded drawing only. ``report(fraction)`` now and then (it may raise Cancelled)."""
    if not dangling:
        return None
    pieces = []
    for line in getattr(noded, "geoms", [noded]):
        coords = [tuple(c[:2]) for c in line.coords]
        pieces.extend(zip(coords[:-1], coords[1:]))
    ends = {}
    for a, b in pieces:
        for p in (a, b):
            ends[p] = ends.get(p, 0) + 1
    array = np.asarray(pieces, dtype=np.float64).reshape(-1, 2, 2)
    # the pieces near an end, by their boxes (every piece for every end took 16 s of a
    # 150 x 150 grid's 18 with 3,000 short annotation lines, 2 s before)
    lower, upper = array.min(axis=1), array.max(axis=1)
    order = np.argsort(lower[:, 0], kind="stable")
    lower_x = lower[order, 0]
    span = float((upper[:, 0] - lower[:, 0]).max())
    best = None
    for k, (a, b) in enumerate(dangling):
        if report is not None and k % 512 == 511:
            report(k / len(dangling))
        a, b = tuple(a), tuple(b)
        for end, other in ((a, b), (b, a)):
            if ends.get(end, 0) != 1:
                continue
            # short of the other by a twentieth of its own length at most: a stub that
            # ends near a line it does not meet is not a gap
            own = 0.05 * float(np.hypot(end[0] - other[0], end[1] - other[1]))
            reach = min(limit, own)
            point = np.asarray(end)
            lo = np.searchsorted(lower_x, point[0] - reach - span, side="left")
            hi = np.searchsorted(lower_x, point[0] + reach, side="right")
            near = order[lo:hi]
            near = near[np.all((lower[near] <= point + reach) & (upper[near] >= point - reach),
                               axis=1)]
            if not near.size:
                continue
            start, direction = array[near, 0], array[near, 1] - array[near, 0]
            length2 = np.einsum("ij,ij->i", direction, direction)
            t = np.einsum("ij,ij->i", point - start, direction) / np.where(length2 > 0,
                                                                          length2, 1.0)
            nearest = start + np.clip(t, 0.0, 1.0)[:, None] * direction
            distance = np.hypot(*(nearest - point).T)
            # not the segments it meets already (at its other end: an overhang past an
            # outline is as far from the outline as it is long)
            distance[np.all(array[near, 0] == other, axis=1)
                     | np.all(array[near, 1] == other, axis=1)] = np.inf
            distance[distance == 0] = np.inf
            k = int(np.argmin(distance))
            if distance[k] <= reach and (best is None or distance[k] < best[0]):
                best = (float(distance[k]), end)
    return best


def plan_from_mesh(mesh, *, source=None, check_overlap=True, progress=None, units=None):
    """A plan from a mesh: its faces projected vertically (z is dropped).

    `progress` as :func:`plan_from_segments`'s: ``progress(done, total)`` between the
    stages (:data:`PLAN_STAGES`; the first, reading a file, is :func:`read_plan`'s) and
    through the faces; True cancels (:class:`facet.Cancelled`). A 100,000-face plan mesh
    takes seconds, half of them in the union of its faces (one call: no step inside it).
    `units`: the mesh's unit, named after the points in its warnings.

    Raises
    ------
    PlanError
        When a projected face crosses itself or faces overlap in plan.
    """
    from shapely.geometry import Polygon
    from shapely.ops import unary_union

    where = _where(source)
    report = _stage_reporter(progress)
    report(1)
    xyz = np.array(mesh.vertices, dtype=np.float64)
    xyz[:, 2] = 0.0
    plan = mesh.with_vertices(xyz)
    report(2)
    if check_overlap:
        polygons = []
        n_faces = plan.n_faces
        for f, face in enumerate(plan.faces()):
            if f % 2048 == 2047:
                report(2, f / n_faces)
            polygon = Polygon(xyz[face, :2])
            if not polygon.is_valid or polygon.area <= 0:
                raise PlanError(f"{where}face {f} crosses itself or has no area in plan")
            polygons.append(polygon)
        report(3)
        total = sum(p.area for p in polygons)
        union = unary_union(polygons).area
        report(4)
        if total > union * (1 + 1e-9):
            # Name one overlapping pair (bounding boxes first).
            boxes = np.array([p.bounds for p in polygons])
            for i, p in enumerate(polygons):
                near = np.flatnonzero(
                    (boxes[:, 0] < boxes[i, 2]) & (boxes[:, 2] > boxes[i, 0])
                    & (boxes[:, 1] < boxes[i, 3]) & (boxes[:, 3] > boxes[i, 1])
                )
                for j in near[near > i]:
                    q = polygons[j]
                    if p.intersection(q).area > 1e-9 * min(p.area, q.area):
                        raise PlanError(f"{where}faces {i} and {int(j)} overlap in plan")
            raise PlanError(f"{where}faces overlap in plan")
    report(5)
    warnings = _unjoined(plan, units)
    report(PLAN_STAGES)
    return PlanGraph(plan, source=source, warnings=warnings, units=units)


def _unjoined(plan, units=None):
    """Warnings for faces that meet in plan without sharing a vertex there: a vertex where
    another one is (an export that gives each face its own copies), or one on another
    face's edge (a T-junction). The lifting lifts such faces apart, as at a step in the
    roof: right for a step, a tear where they should meet. The plan mesh's numbering is
    kept (pins and per-vertex targets use it), so nothing is welded here."""
    from scipy.spatial import cKDTree

    xy = np.asarray(plan.vertices, dtype=np.float64)[:, :2]
    used = np.unique(plan.face_vertices)
    if used.size < 2:
        return []
    size = float(np.ptp(xy[used], axis=0).max())
    tol = 1e-9 * size
    warnings = []
    points = xy[used]
    tree = cKDTree(points)
    pairs = sorted(tree.query_pairs(tol))
    if pairs:
        i, j = (int(used[k]) for k in pairs[0])
        warnings.append(
            "vertices at one point in plan but not one vertex: "
            f"{count_noun(len(pairs), 'pair')} (vertices {i} and {j} at "
            f"{point_text(xy[i, :2], units)}); the faces there are "
            "lifted apart, as at a step in the roof: weld them where the faces should meet")
    coincident = {int(used[k]) for pair in pairs for k in pair}
    # a vertex on another face's edge without being its corner leaves that edge to one
    # face (the faces on its other side have the vertex): only such edges are searched
    lone = boundary_corners(plan.face_start, plan.face_vertices)
    edges = [(a, b, f) for f, face in enumerate(plan.faces())
             for c, (a, b) in enumerate(zip(face, face[1:] + face[:1]))
             if lone[int(plan.face_start[f]) + c]]
    on_edge = []
    if edges:
        ends = np.array([(a, b) for a, b, _ in edges])
        seg, hit = _points_inside(tree, points, xy[ends], tol)
        on_edge = [(int(used[k]),) + edges[e] for e, k in zip(seg, hit)
                   if int(used[k]) not in coincident]
    if on_edge:
        v, a, b, f = on_edge[0]
        warnings.append(
            f"vertices on another face's edge but not its corner: {len(on_edge)} (vertex {v} "
            f"on the edge {a}-{b} of face {f}); the faces there are lifted apart: split the "
            "edge at the vertex where they should meet, or draw the plan as lines (.dxf, "
            ".csv), whose meeting points are joined")
    return warnings


def read_plan(path, *, snap=None, arc_tolerance=None, openings=(), to_mm=False,
              units_mm=None, progress=None, units=None, option_names=None):
    """A plan graph from a drawing file (see the module docstring). With `to_mm` a DXF
    drawn in another length unit is read in millimetres, with `units_mm` any drawing at
    that many millimetres a unit (see :func:`read_segments`); `snap`, `arc_tolerance` and
    `openings` are then in millimetres. `progress` as :func:`plan_from_segments`'s (or
    :func:`plan_from_mesh`'s, for a plan mesh). Messages name lengths and points in
    `units` (default: the unit the plan is read in: mm when scaled, a DXF's $INSUNITS unit,
    else DRAWING_UNITS; it is ``PlanGraph.units``) and the options they advise by
    `option_names` (:data:`OPTION_NAMES`)."""
    suffix = os.path.splitext(os.fspath(path))[1].lower()
    if suffix == ".dxf" or suffix in TABLE_SUFFIXES:
        _stage_reporter(progress)(0)
        notes = []
        info = {}
        segments = read_segments(path, arc_tolerance=arc_tolerance, notes=notes, to_mm=to_mm,
                                 units_mm=units_mm, units=units, option_names=option_names,
                                 info=info)
        plan = plan_from_segments(segments, snap=snap, openings=openings, source=path,
                                  progress=progress, units=info["units"],
                                  option_names=option_names)
        plan.warnings[:0] = notes
        return plan
    if suffix in (".obj", ".off", ".json"):
        from facet.io import read_mesh, read_warnings

        report = _stage_reporter(progress)
        report(0)
        mesh = read_mesh(path, progress=None if progress is None else
                         lambda done, total: report(0, done / total if total else 0.0))
        scale = None if units_mm is None else _positive(units_mm, path,
                                                        "the drawing's unit in mm")
        if scale is not None and scale != 1.0:
            mesh = mesh.with_vertices(np.asarray(mesh.vertices, dtype=np.float64) * scale)
        plan = plan_from_mesh(mesh, source=path, progress=progress, units=units or (
            DRAWING_UNITS if scale is None else "mm"))
        plan.warnings[:0] = read_warnings(mesh)  # (a face read with a vertex once)
        return plan
    raise PlanError(f"{path}: cannot read {suffix or 'files without an extension'} plans "
                    "(Facet reads .dxf, .csv, .tsv, .txt, .obj, .off, .json)")


# ------------------------------------------------------------------ targets


def _plan_xy(plan):
    mesh = getattr(plan, "mesh", plan)
    return np.asarray(mesh.vertices, dtype=np.float64)[:, :2], mesh


def _with_free(plan_xy, targets, given):
    """Fill free vertices with the weighted plane through the given ones."""
    if not np.any(given):
        raise InputError("no vertex has a target height")
    n_given, n_free = int(np.count_nonzero(given)), int(np.count_nonzero(~given))
    share = min(1.0, max(n_given / n_free, 1e-4)) if n_free else 1.0
    weights = np.where(given, 1.0, FREE_WEIGHT * share)
    # the plane in coordinates about the given vertices' centroid: at map coordinates in mm
    # (5.7e9) the columns 1, x, y are parallel to 1e-16, and the rank test took three
    # targets spread over 12 m for a line (their mean height filled the free vertices)
    centre = plan_xy[given].mean(axis=0)
    xy = plan_xy - centre
    a = np.column_stack([np.ones(int(given.sum())), xy[given]])
    if np.linalg.matrix_rank(a) == 3:
        coef, *_ = np.linalg.lstsq(a, targets[given], rcond=None)
        fill = coef[0] + xy @ coef[1:]
    else:
        fill = np.full(len(plan_xy), float(np.mean(targets[given])))
    return np.where(given, targets, fill), weights


def pinned_targets(plan, pins):
    """Targets from heights pinned at chosen vertices, the rest free.

    Parameters
    ----------
    plan : PlanGraph or PolyMesh
    pins : dict {vertex: height}

    Returns
    -------
    targets, weights : numpy.ndarray
        Pinned vertices have weight 1; free ones :data:`FREE_WEIGHT` (lowered in
        proportion when they outnumber the pins), with the
        best-fitting plane of the pins as their target.
    """
    xy, mesh = _plan_xy(plan)
    n = len(xy)
    targets = np.zeros(n)
    given = np.zeros(n, dtype=bool)
    for vertex, height in dict(pins).items():
        v = int(vertex)
        if not 0 <= v < n:
            raise InputError(f"pinned vertex {v} is out of range ({n} vertices)")
        h = float(height)
        if not abs(h) <= COORDINATE_MAX:
            raise InputError(f"pinned height of vertex {v} is {h!r}: not a finite number up "
                             f"to {COORDINATE_MAX:g} in magnitude")
        targets[v] = h
        given[v] = True
    return _with_free(xy, targets, given)


def match_tolerance(plan, snap=0.0):
    """The plan distance within which a point is at a plan vertex: ``snap`` when it is
    above 0, else 1e-6 of the plan's size (1e-6 for a plan of no extent)."""
    if snap and snap > 0:
        return float(snap)
    xy, _ = _plan_xy(plan)
    size = float(np.ptp(xy, axis=0).max()) if len(xy) else 0.0
    return 1e-6 * (size or 1.0)


def pin_vertices(plan, points, *, tolerance):
    """The plan vertex at each point's x, y: an int array, -1 where no vertex is within
    ``tolerance`` (in plan) of the point. Only x and y of ``points`` count."""
    from scipy.spatial import cKDTree

    xy, _ = _plan_xy(plan)
    points = np.asarray(points, dtype=np.float64)
    points = points.reshape(len(points), -1) if points.size else np.zeros((0, 2))
    if points.shape[0] == 0 or len(xy) == 0:
        return np.full(points.shape[0], -1, dtype=np.int64)
    finite = np.all(np.isfinite(points[:, :2]), axis=1)
    if not finite.all():
        bad = int(np.flatnonzero(~finite)[0])
        raise InputError(f"pinned point {bad + 1} of {len(points)} has a NaN or infinite x "
                         f"or y ({points[bad, 0]!r}, {points[bad, 1]!r})")
    distance, vertex = cKDTree(xy).query(points[:, :2])
    return np.where(distance <= tolerance, vertex, -1).astype(np.int64)


def targets_from_points(plan, points, *, tolerance, labels=None, notes=None, units=None,
                        option_names=None):
    """Targets from x, y, z points: each plan vertex takes the z of the
    nearest point within `tolerance` (in plan); vertices with none are free
    (see :func:`pinned_targets`). No interpolation. A point beyond `tolerance`
    but within 1% of an edge of a vertex (meant for it, rounded) is an error naming it
    (``labels[k]``, default "point k+1") when no point matches that vertex; points farther
    out, or beside a vertex matched, are left out, and a line saying how many is appended
    to the list `notes` (if given). Lengths and points in the messages are followed by
    `units` (default the plan's ``units``, when it is a PlanGraph), the match distance
    named by ``option_names["tolerance"]`` (:data:`OPTION_NAMES`)."""
    from scipy.spatial import cKDTree

    xy, xy_mesh = _plan_xy(plan)
    units = units or getattr(plan, "units", None)
    in_units = length_text(units)
    match = f"{in_units(tolerance, 'g')} ({_option_names(option_names)['tolerance']})"
    points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    if points.shape[0] == 0:
        raise InputError("no target points")
    if not np.all(np.isfinite(points)):
        raise InputError("a target point has a NaN or infinite coordinate")
    tree = cKDTree(points[:, :2])
    distance, nearest = tree.query(xy)
    given = distance <= tolerance
    if not np.any(given):
        raise InputError(f"no target point lies within the match distance {match} of a plan "
                         "vertex")
    # A point just beyond the match distance of a vertex was meant for it, and would leave
    # it free without a word: a table rounded to 0.1 mm for a 30 m plan (distance 3e-5)
    # gave 37 of 121 vertices their heights and the lifting missed the rest by 5 cm,
    # reported as a success. "Just beyond": within 1% of the vertex's shortest edge, of a
    # vertex that no point matches; points farther out, or beside a vertex matched (a
    # survey denser than the plan), are left out as before.
    edges = xy_mesh.edges()
    length = np.hypot(*(xy[edges[:, 0]] - xy[edges[:, 1]]).T)
    shortest = np.full(len(xy), np.inf)
    np.minimum.at(shortest, edges[:, 0], length)
    np.minimum.at(shortest, edges[:, 1], length)
    shortest[np.isinf(shortest)] = 0.0  # a vertex of no edge: no point is meant for it
    apart, vertex = cKDTree(xy).query(points[:, :2])
    near = np.flatnonzero((apart > tolerance) & (apart <= 0.01 * shortest[vertex])
                          & ~given[vertex])
    if near.size:
        p = int(near[np.argmin(apart[near])])
        raise InputError(
            f"{near.size} of the {len(points)} target points "
            f"{'lies' if near.size == 1 else 'lie'} near a plan vertex but "
            f"farther than the match distance {match}; the nearest of them, "
            f"{_point_label(labels, p)} at {point_text(points[p, :2], units)}, is "
            f"{in_units(apart[p])} from vertex {int(vertex[p])}: give a larger match distance "
            "to match them")
    _check_one_height(points, tree.query_ball_point(xy[given], tolerance),
                      np.flatnonzero(given), labels, units)
    # points left out: said, as a table in other units or another origin matched a vertex
    # or two by chance (a table in metres for a plan in mm: its point at 0, 0 matched, the
    # others fell inside the plan, near no vertex, and the lifting met the one height)
    out = np.flatnonzero(apart > tolerance)
    if out.size and notes is not None:
        p = int(out[np.argmin(apart[out])])
        notes.append(
            f"{out.size} of the {len(points)} target points "
            f"{'lies' if out.size == 1 else 'lie'} farther than the match distance "
            f"{match} from every plan vertex, left out (the nearest of them, "
            f"{_point_label(labels, p)} at {point_text(points[p, :2], units)}, is "
            f"{in_units(apart[p])} from vertex {int(vertex[p])}); "
            f"{int(np.count_nonzero(given))} of the "
            f"{len(xy)} plan vertices {'has' if np.count_nonzero(given) == 1 else 'have'} "
            "a target height" + _units_hint(points[:, :2], xy, units))
    targets = np.where(given, points[np.minimum(nearest, len(points) - 1), 2], 0.0)
    return _with_free(xy, targets, given)


def _units_hint(points, xy, units=None):
    """"; the points span ... and the plan ...: ..." when the points' extent and the plan's
    differ five times or more (a table in metres for a plan in millimetres: the note said
    which points were left out, not why), else ""."""
    span = float(np.ptp(points, axis=0).max())
    plan = float(np.ptp(xy, axis=0).max())
    if span <= 0 or plan <= 0 or 0.2 < span / plan < 5:
        return ""
    ratio = plan / span
    length = length_text(units)
    return (f"; the points span {length(span, '.6g')} and the plan {length(plan, '.6g')}, "
            f"{max(ratio, 1 / ratio):.4g} times {'less' if ratio > 1 else 'more'}: is the "
            "table in other units than the plan (metres for millimetres)?")


def _point_label(labels, k):
    """Target point ``k`` in a message: ``labels[k]`` ("line 12"), else "point k+1"."""
    return labels[k] if labels is not None else f"point {k + 1}"


def _check_one_height(points, matched, vertices, labels, units=None):
    """Refuse two target points at one vertex (within the match distance) whose heights
    differ by more than rounding: the nearest was taken without a word, the other's
    height dropped (a survey's two readings, a table joined from two). ``matched[k]``: the
    points within the match distance of vertex ``vertices[k]``."""
    span = float(np.ptp(points[:, 2])) or 1.0
    for vertex, found in zip(vertices, matched):
        if len(found) < 2:
            continue
        z = points[found, 2]
        if np.ptp(z) <= 1e-9 * max(span, float(np.abs(z).max())):
            continue
        a, b = int(found[np.argmin(z)]), int(found[np.argmax(z)])
        length = length_text(units)
        raise InputError(
            f"two target points at plan vertex {int(vertex)} give it different heights: "
            f"{_point_label(labels, a)} gives {length(points[a, 2], '.10g')} and "
            f"{_point_label(labels, b)} {length(points[b, 2], '.10g')}, both "
            "within the match distance of it: keep the one meant")


def _ray_cast_down(xy, vertices, triangles, report=None):
    """Topmost z of the triangles above each xy point (NaN where none); ``report(done)``
    every 4096 points (it may raise Cancelled)."""
    tri = vertices[triangles]  # (m, 3, 3)
    lo = tri[:, :, :2].min(axis=1)
    hi = tri[:, :, :2].max(axis=1)
    extent = np.maximum(hi.max(axis=0) - lo.min(axis=0), 1e-300)
    cells = max(1, int(np.sqrt(len(triangles))))
    origin = lo.min(axis=0)
    step = extent / cells
    buckets = {}
    clo = np.floor((lo - origin) / step).astype(int)
    chi = np.minimum(np.floor((hi - origin) / step).astype(int), cells - 1)
    for t in range(len(triangles)):
        for i in range(clo[t, 0], chi[t, 0] + 1):
            for j in range(clo[t, 1], chi[t, 1] + 1):
                buckets.setdefault((i, j), []).append(t)
    result = np.full(len(xy), np.nan)
    pc = np.floor((xy - origin) / step).astype(int)
    eps = 1e-9
    for p in range(len(xy)):
        if report is not None and p % 4096 == 4095:
            report(p)
        cand = buckets.get((min(max(pc[p, 0], 0), cells - 1), min(max(pc[p, 1], 0), cells - 1)))
        if not cand:
            continue
        t = tri[cand]
        a, b, c = t[:, 0], t[:, 1], t[:, 2]
        v0 = b[:, :2] - a[:, :2]
        v1 = c[:, :2] - a[:, :2]
        v2 = xy[p] - a[:, :2]
        den = v0[:, 0] * v1[:, 1] - v1[:, 0] * v0[:, 1]
        ok = np.abs(den) > 0
        den = np.where(ok, den, 1.0)
        u = (v2[:, 0] * v1[:, 1] - v1[:, 0] * v2[:, 1]) / den
        w = (v0[:, 0] * v2[:, 1] - v2[:, 0] * v0[:, 1]) / den
        inside = ok & (u >= -eps) & (w >= -eps) & (u + w <= 1 + eps)
        if np.any(inside):
            z = a[:, 2] + u * (b[:, 2] - a[:, 2]) + w * (c[:, 2] - a[:, 2])
            result[p] = float(np.max(z[inside]))
    return result


def _nearest_edge_height(point, vertices, triangles, boxes, tolerance):
    """The height of the target's triangle edges within `tolerance` of `point` in plan,
    the topmost of them (as the ray cast takes the topmost hit); NaN if none is.
    `boxes`: the triangles' (low, high) corners in plan."""
    low, high = boxes
    near = np.all(low - tolerance <= point, axis=1) & np.all(high + tolerance >= point, axis=1)
    candidates = triangles[near]
    height = -math.inf
    for k in range(3):
        a = vertices[candidates[:, k]]
        b = vertices[candidates[:, (k + 1) % 3]]
        d = b[:, :2] - a[:, :2]
        length2 = np.einsum("ij,ij->i", d, d)
        t = np.einsum("ij,ij->i", point - a[:, :2], d) / np.where(length2 > 0, length2, 1.0)
        t = np.clip(t, 0.0, 1.0)
        distance = np.hypot(*(a[:, :2] + t[:, None] * d - point).T)
        z = a[:, 2] + t * (b[:, 2] - a[:, 2])
        within = distance <= tolerance
        if within.any():
            height = max(height, float(z[within].max()))
    return height if height > -math.inf else math.nan


def targets_from_mesh(plan, mesh, *, source=None, tolerance=None, progress=None, units=None):
    """Targets from a mesh.

    When the mesh has the plan's vertices in the same order (same count and
    x, y within 1e-9 of the plan's size) its z are the targets (the paper's
    Fig. 4 case). Otherwise each plan vertex takes the height of the mesh
    straight above or below it, the topmost hit (vertical ray cast against
    the mesh's fan-triangulated faces). A vertex just outside the mesh in plan,
    within `tolerance` of its edge (default 1e-6 of the plan's size: a surface
    drawn on the plan's outline, rounded), takes the height of the nearest
    edge point; a vertex farther out is an error naming it.

    ``progress(done, total)`` through the plan's vertices as they are matched (every
    4096th; a 100,000-vertex plan takes seconds); True cancels (:class:`facet.Cancelled`,
    "matching the targets cancelled"). `units` as :func:`targets_from_points`'s.

    Returns
    -------
    targets, weights : numpy.ndarray (weights all 1)
    """
    where = _where(source)
    xy, plan_mesh = _plan_xy(plan)
    units = units or getattr(plan, "units", None)

    def report(done):
        report_progress(progress, done, len(xy), "matching the targets")

    report(0)
    vertices = np.asarray(mesh.vertices, dtype=np.float64)
    size = float(np.ptp(xy, axis=0).max()) or 1.0
    if len(vertices) == len(xy) and np.max(np.abs(vertices[:, :2] - xy)) <= 1e-9 * size:
        return vertices[:, 2].copy(), np.ones(len(xy))
    triangles = []
    for face in mesh.faces():
        for k in range(1, len(face) - 1):
            triangles.append((face[0], face[k], face[k + 1]))
    triangles = np.asarray(triangles, dtype=np.int64)
    z = _ray_cast_down(xy, vertices, triangles, report)
    tolerance = 1e-6 * size if tolerance is None else float(tolerance)
    uncovered = np.flatnonzero(np.isnan(z))
    if uncovered.size:
        corners = vertices[triangles][:, :, :2]
        boxes = corners.min(axis=1), corners.max(axis=1)
        inside = np.all(xy[uncovered] >= boxes[0].min(axis=0) - tolerance, axis=1) & \
            np.all(xy[uncovered] <= boxes[1].max(axis=0) + tolerance, axis=1)
        for v in uncovered[inside]:  # (a vertex outside the target's box is not near it)
            z[v] = _nearest_edge_height(xy[v], vertices, triangles, boxes, tolerance)
    missing = np.flatnonzero(np.isnan(z))
    if missing.size:
        v = int(missing[0])
        raise InputError(
            f"{where}the target surface does not cover plan vertex {v} at "
            f"{point_text(xy[v, :2], units)} ({missing.size} vertices uncovered, none "
            f"within {length_text(units)(tolerance)} of its edge in plan)"
        )
    report(len(xy))
    return z, np.ones(len(xy))


def read_targets(plan, path, *, tolerance=None, notes=None, progress=None, units=None,
                 option_names=None):
    """Targets from a file: a mesh (.obj, .off, .json; see
    :func:`targets_from_mesh`, and for `progress`) or a CSV of x,y,z points (see
    :func:`targets_from_points`; tolerance default 1e-6 of the plan's size; points left
    out are said in the list `notes`, if given; `units` and `option_names` as its).

    Returns
    -------
    targets, weights : numpy.ndarray
    """
    suffix = os.path.splitext(os.fspath(path))[1].lower()
    xy, _ = _plan_xy(plan)
    if suffix in TABLE_SUFFIXES:
        rows, lines = [], []
        for number, values in _number_rows(path, InputError, "x,y,z"):
            rows.append(values)
            lines.append(f"line {number}")
        if tolerance is None:
            tolerance = 1e-6 * (float(np.ptp(xy, axis=0).max()) or 1.0)
        try:
            found = []
            result = targets_from_points(plan, rows, tolerance=tolerance, labels=lines,
                                         notes=found, units=units, option_names=option_names)
            if notes is not None:
                notes.extend(f"{path}: {text}" for text in found)
            return result
        except InputError as exc:
            raise InputError(f"{path}: {exc}") from None
    if suffix in (".obj", ".off", ".json"):
        from facet.io import read_mesh

        report_progress(progress, 0, len(xy), "matching the targets")
        return targets_from_mesh(plan, read_mesh(path), source=path, tolerance=tolerance,
                                 progress=progress, units=units)
    raise InputError(f"{path}: cannot read targets from {suffix or 'files without an extension'} "
                     "files (Facet reads .obj, .off, .json meshes and .csv, .tsv or .txt points)")
