# SPDX-License-Identifier: LGPL-2.1-or-later
"""The cut files as other programs read them (docs/fabrication.md): the properties of the
files that LibreOffice Calc, FreeCAD's DXF importer and LibreCAD depend on, checked on the
files themselves (none of those programs is needed here)."""

import csv
import math

import numpy as np
import pytest

from panel_meshes import translational


def _made(tmp_path, **kw):
    from facet.cli_panels import run_pipeline

    mesh = translational(nu=6, nv=5, step=400.0)
    return run_pipeline(mesh, 18.0, edge="bisector", gap=4, sheet=(1300, 900), margin=15,
                        spacing=8, dxf=str(tmp_path / "cut.dxf"),
                        schedule=str(tmp_path / "schedule.csv"), **kw)


def _split_like_calc(line, separators=",;\t"):
    """A CSV line's cells as LibreOffice Calc's text import cuts them with its default
    separators (comma, semicolon and tab, all three ticked): at any separator outside
    double quotes, a doubled quote inside them standing for one."""
    cells, cell, quoted, i = [], [], False, 0
    while i < len(line):
        c = line[i]
        if quoted:
            if c == '"' and line[i + 1:i + 2] == '"':
                cell.append('"')
                i += 1
            elif c == '"':
                quoted = False
            else:
                cell.append(c)
        elif c == '"':
            quoted = True
        elif c in separators:
            cells.append("".join(cell))
            cell = []
        else:
            cell.append(c)
        i += 1
    cells.append("".join(cell))
    return cells


def test_schedule_csv_keeps_its_columns_in_a_spreadsheet(tmp_path):
    """The list cells (edge lengths, bevel angles, ... joined with ';') were written bare:
    LibreOffice Calc, whose import splits at ';' too by default, cut each into as many
    cells, so that every column after edge_lengths stood under another's header (the sheet
    number under "joint_widths"). They are quoted now; Python's csv reads the same rows."""
    _, ps, _, result = _made(tmp_path)
    text = (tmp_path / "schedule.csv").read_text(encoding="utf-8")
    lines = text.splitlines()
    header = _split_like_calc(lines[0])
    assert "edge_lengths_mm" in header and "sheet" in header
    for line in lines[1:]:
        cells = _split_like_calc(line)
        assert len(cells) == len(header), line
        row = dict(zip(header, cells))
        p = ps.by_id(row["id"])
        assert [float(x) for x in row["edge_lengths_mm"].split(";")] == list(p.edge_lengths)
        assert int(row["sheet"]) == result.placements[p.id].sheet + 1
        float(row["x_mm"]), float(row["rotation_deg"])  # numbers with a point, not text
    with open(tmp_path / "schedule.csv", newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    assert [r["id"] for r in rows] == [_split_like_calc(line)[0] for line in lines[1:]]
    assert all(";" in r["bevel_deg"] for r in rows)


def test_schedule_headers_give_the_units(tmp_path):
    """The CSV's headers named no units ("area", "width", "x"): a fabricator opening it in
    Calc could not tell mm from m, mm² from m². They give the model's unit (--units), its
    square and cube (ASCII: area_mm2, volume_m3); the values keep all their digits. The
    JSON schedule keeps its keys and gives their units in meta.column_units."""
    import json

    from facet.cli_panels import run_pipeline
    from facet.cutsheets import csv_header

    _, ps, _, result = _made(tmp_path)
    for units, area, volume in (("mm", "area_mm2", "volume_mm3"), ("m", "area_m2", "volume_m3"),
                                ("in", "area_in2", "volume_in3")):
        header = csv_header(units)
        assert {area, f"area_top_{area[5:]}", volume, f"width_{units}", f"height_{units}",
                f"perimeter_{units}", f"thickness_{units}", f"edge_lengths_{units}",
                f"joint_widths_{units}", f"narrowest_joint_{units}", f"clash_{units}",
                f"x_{units}", f"y_{units}", "mass_kg", "bevel_deg", "rotation_deg", "id",
                "sheet", "corners"} <= set(header), header
        assert not {"area", "width", "x", "volume"} & set(header)
    with open(tmp_path / "schedule.csv", newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    for row in rows:
        p = ps.by_id(row["id"])
        assert float(row["area_mm2"]) == p.area and float(row["volume_mm3"]) == p.volume
        assert float(row["width_mm"]) == p.size[0]
    mesh = translational(nu=3, nv=2, step=0.4)  # the same panels in metres
    run_pipeline(mesh, 0.018, units="m", schedule=str(tmp_path / "m.csv"))
    run_pipeline(mesh, 0.018, units="m", schedule=str(tmp_path / "m.json"))
    with open(tmp_path / "m.csv", newline="", encoding="utf-8") as f:
        header = next(csv.reader(f))
    assert header == csv_header("m") and "area_m2" in header and "width_m" in header
    meta = json.loads((tmp_path / "m.json").read_text(encoding="utf-8"))["meta"]
    assert meta["units"] == "m"
    assert meta["column_units"]["area"] == "m2" and meta["column_units"]["x"] == "m"
    assert meta["column_units"]["volume"] == "m3" and "mass_kg" not in meta["column_units"]


def test_csv_field_quotes_what_a_spreadsheet_splits_at():
    from facet.cutsheets import _csv_field

    assert _csv_field("P-R01C01") == "P-R01C01"
    assert _csv_field("1.5;2.5") == '"1.5;2.5"'
    assert _csv_field('a "b", c') == '"a ""b"", c"'
    assert next(csv.reader([_csv_field('a "b", c\td')])) == ['a "b", c\td']


def _ink_box(text_entity):
    """The bounding box (xmin, ymin, xmax, ymax) of a TEXT's letters as ezdxf draws them."""
    from ezdxf import path
    from ezdxf.addons import text2path

    box = path.bbox(text2path.make_paths_from_entity(text_entity), fast=True)
    return np.array([box.extmin.x, box.extmin.y, box.extmax.x, box.extmax.y])


def _cut_dxf(tmp_path, units):
    """The test mesh's cut sheets as DXF in `units` (the mesh, sheet and lengths scaled)."""
    import ezdxf

    from facet.cli_panels import run_pipeline

    scale = {"mm": 1.0, "m": 1e-3}[units]
    # (scaled after: translational's heights are a function of millimetres, so a mesh
    # made with a 0.4 step is all but flat, its bevels all "+0.0°", which are not written)
    mesh = translational(nu=6, nv=5, step=400.0)
    mesh = mesh.with_vertices(mesh.vertices * scale)
    run_pipeline(mesh, 18.0 * scale, edge="bisector", gap=4 * scale,
                 sheet=(1300 * scale, 900 * scale), margin=15 * scale, spacing=8 * scale,
                 dxf=str(tmp_path / "cut.dxf"), units=units)
    return ezdxf.readfile(tmp_path / "cut.dxf")


@pytest.mark.parametrize("units", ["mm", "m"])
def test_dxf_texts_start_where_they_are_drawn(tmp_path, units):
    """A centred TEXT's group 10 was its centre (ezdxf writes the alignment point there
    too): FreeCAD 0.20's DXF importer, which places a text by group 10 alone, put every ID
    and bevel angle half its width to the right and half its height up, across the cut
    line. Group 10 now holds the start of its baseline, as AutoCAD writes it: a text drawn
    from there left-aligned covers what the centred one covers."""
    from ezdxf.enums import TextEntityAlignment

    doc = _cut_dxf(tmp_path, units)
    texts = doc.modelspace().query("TEXT")
    assert {t.dxf.layer for t in texts} == {"LABEL", "BEVEL", "SHEET"}
    turned = 0
    for t in texts:
        assert t.get_align_enum() == TextEntityAlignment.MIDDLE_CENTER
        height = t.dxf.height
        left = t.copy()
        left.set_placement(t.dxf.insert, align=TextEntityAlignment.LEFT)
        # (within a tenth of the height: ezdxf centres a text's ink, the start is put by
        # the ink's right end, the first letter's left bearing, 0.05 of the height, apart)
        assert np.allclose(_ink_box(left), _ink_box(t), rtol=0, atol=0.1 * height), t.dxf.text
        turned += not math.isclose(math.sin(math.radians(t.dxf.rotation)), 0.0, abs_tol=1e-9)
    assert turned > 0  # (bevel angles along slanted edges: the start turned with the text)


def test_dxf_texts_are_in_the_outline_font(tmp_path):
    """The TEXTs' style was ezdxf's Standard, font "txt" (an SHX font each reader maps to
    one of its own); it is a style of the outlines' and previews' font now."""
    from ezdxf.tools.fonts import find_font_face

    from facet.cutsheets import OUTLINE_FONT, TEXT_FONT_FILE, TEXT_STYLE

    doc = _cut_dxf(tmp_path, "mm")
    assert doc.styles.get(TEXT_STYLE).dxf.font == TEXT_FONT_FILE
    assert doc.header["$TEXTSTYLE"] == TEXT_STYLE
    assert find_font_face(TEXT_FONT_FILE).family == OUTLINE_FONT
    assert {t.dxf.style for t in doc.modelspace().query("TEXT")} == {TEXT_STYLE}
