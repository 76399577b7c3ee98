# SPDX-License-Identifier: LGPL-2.1-or-later
"""Write examples/roof_plan.dxf and examples/roof_heights.csv: the roof example's plan as
an architect's DXF and its pinned heights as points, for the `facet lift` commands.

    /usr/bin/python3 tools/make_example_plan.py

The plan is the one tools/make_examples.py sketches for examples/roof.FCStd (it imports
the constants below): a 3 x 2 grid of 4 m x 3 m bays in millimetres, one bay split by a
diagonal, drawn on the layer PLAN as one closed outline and LINEs. The layer CONSTRUCTION,
turned off, holds the bays' centre lines, as drawings carry; `facet lift` leaves it out
and says so. Coordinates are written as ezdxf writes floats (shortest round-trip text).
"""

import os

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.join(os.path.dirname(HERE), "examples")

#: Grid lines of the bays (mm).
ROOF_XS = (0.0, 4000.0, 8000.0, 12000.0)
ROOF_YS = (0.0, 3000.0, 6000.0)
#: The diagonal that splits the first bay of the second column into two triangles.
ROOF_DIAGONAL = ((ROOF_XS[1], ROOF_YS[0]), (ROOF_XS[2], ROOF_YS[1]))
#: Pinned heights (x, y, z in mm): four corners and one inner node.
ROOF_PINS = ((ROOF_XS[0], ROOF_YS[0], 3000.0), (ROOF_XS[-1], ROOF_YS[0], 3600.0),
             (ROOF_XS[0], ROOF_YS[-1], 4200.0), (ROOF_XS[-1], ROOF_YS[-1], 3300.0),
             (ROOF_XS[1], ROOF_YS[1], 4500.0))


def roof_lines():
    """The plan's lines: the grid's full rows and columns, then the diagonal."""
    xs, ys = ROOF_XS, ROOF_YS
    lines = [((xs[0], y), (xs[-1], y)) for y in ys]
    lines += [((x, ys[0]), (x, ys[-1])) for x in xs]
    return lines + [ROOF_DIAGONAL]


def write_plan_dxf(path):
    import ezdxf

    doc = ezdxf.new("R2010", setup=True)
    doc.units = ezdxf.units.MM
    doc.layers.add("PLAN", color=7)
    doc.layers.add("CONSTRUCTION", color=8, linetype="CENTER").off()
    space = doc.modelspace()
    xs, ys = ROOF_XS, ROOF_YS
    outline = [(xs[0], ys[0]), (xs[-1], ys[0]), (xs[-1], ys[-1]), (xs[0], ys[-1])]
    space.add_lwpolyline(outline, close=True, dxfattribs={"layer": "PLAN"})
    for a, b in roof_lines():
        inner = not (a[0] == b[0] and a[0] in (xs[0], xs[-1])) and \
            not (a[1] == b[1] and a[1] in (ys[0], ys[-1]))
        if inner:  # the outline's own edges are the polyline
            space.add_line(a, b, dxfattribs={"layer": "PLAN"})
    for x0, x1 in zip(xs, xs[1:]):
        x = 0.5 * (x0 + x1)
        space.add_line((x, ys[0] - 500.0), (x, ys[-1] + 500.0),
                       dxfattribs={"layer": "CONSTRUCTION"})
    for y0, y1 in zip(ys, ys[1:]):
        y = 0.5 * (y0 + y1)
        space.add_line((xs[0] - 500.0, y), (xs[-1] + 500.0, y),
                       dxfattribs={"layer": "CONSTRUCTION"})
    doc.saveas(path)


def write_heights_csv(path):
    with open(path, "w", encoding="utf-8", newline="\n") as handle:
        handle.write("x,y,z\n")
        for x, y, z in ROOF_PINS:
            handle.write(f"{x!r},{y!r},{z!r}\n")


def main():
    os.makedirs(EXAMPLES, exist_ok=True)
    write_plan_dxf(os.path.join(EXAMPLES, "roof_plan.dxf"))
    write_heights_csv(os.path.join(EXAMPLES, "roof_heights.csv"))
    for name in ("roof_plan.dxf", "roof_heights.csv"):
        print(f"examples/{name}: {os.path.getsize(os.path.join(EXAMPLES, name))} bytes")


if __name__ == "__main__":
    main()
