# SPDX-License-Identifier: LGPL-2.1-or-later
"""Write the example documents examples/facade.FCStd and examples/roof.FCStd.

Run in FreeCAD's command line (the Makefile's environment loads the workbench):

    sh tests/fc_env.sh freecadcmd tools/make_examples.py

facade.FCStd -- from a design surface to cut sheets:
    DesignSurface  a Part B-spline surface through a 7 x 5 grid of points (a 12 m x 6 m
                   wave, millimetres)
    Control        a PolyMesh: the surface sampled on a 4 x 8 grid of quads (u up the
                   facade, v along it, evenly spaced in the surface's parameters). Sampled here, in this script, with the Part API: the
                   "Panelize surface" command that makes such control meshes parametric
                   is not in the workbench yet; this PolyMesh is a plain (imported-style)
                   mesh, not linked to the surface.
    Planarized     the control mesh planarized (tolerance 1e-9 of the edge)
    PanelSet       40 mm panels on the outer side, square edges, 6 mm joints
    CutSheets      nested on 3210 x 2250 mm sheets (no files written: OutputDir empty)

roof.FCStd -- from a plan to panels:
    Plan           a Sketch: a 3 x 2 grid of 4 m x 3 m bays, one bay split by a diagonal
                   (the plan of examples/roof_plan.dxf: tools/make_example_plan.py)
    PlanGraph      the sketch as a plan graph
    Lifting        the optimal lifting to four pinned corner heights (a warped, planar-
                   paneled roof)
    PanelSet       30 mm panels on the lifted roof

The documents are deterministic: running the script again gives the same geometry bits.
tests/freecad/test_examples.py reopens both, recomputes them and checks the results.
"""

import math
import os
import sys

import FreeCAD as App
import Part

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
EXAMPLES = os.path.join(ROOT, "examples")

#: Control net of the design surface (mm): 7 columns along the facade, 5 rows up it.
SURFACE_COLUMNS, SURFACE_ROWS = 7, 5
WIDTH, HEIGHT = 12000.0, 6000.0
#: Quads of the control mesh along the surface's u (up the facade: the interpolation runs
#: through the rows of the control net) and v (along it): panels of about 1.5 m.
QUADS_U, QUADS_V = 4, 8
#: Joint between facade panels (mm).
GAP = float(os.environ.get("FACET_EXAMPLE_GAP", "6"))


def surface_points():
    rows = []
    for j in range(SURFACE_ROWS):
        v = j / (SURFACE_ROWS - 1)
        row = []
        for i in range(SURFACE_COLUMNS):
            u = i / (SURFACE_COLUMNS - 1)
            depth = 400.0 * math.sin(math.pi * u) * math.cos(0.8 * math.pi * (v - 0.3))
            depth += 150.0 * math.sin(2.0 * math.pi * u + 1.2 * v)
            row.append(App.Vector(WIDTH * u, depth, HEIGHT * v))
        rows.append(row)
    return rows


def design_surface(doc):
    surface = Part.BSplineSurface()
    surface.interpolate(surface_points())
    feature = doc.addObject("Part::Feature", "DesignSurface")
    feature.Shape = surface.toShape()
    feature.Label = "Design surface"
    return feature


def sampled_grid(face, nu, nv):
    """A facet.PolyMesh: ``face`` sampled at (nu + 1) x (nv + 1) evenly spaced (u, v)."""
    import facet

    u0, u1, v0, v1 = face.ParameterRange
    vertices = []
    for j in range(nv + 1):
        for i in range(nu + 1):
            p = face.Surface.value(u0 + (u1 - u0) * i / nu, v0 + (v1 - v0) * j / nv)
            vertices.append((p.x, p.y, p.z))
    faces = [[j * (nu + 1) + i, j * (nu + 1) + i + 1, (j + 1) * (nu + 1) + i + 1,
              (j + 1) * (nu + 1) + i] for j in range(nv) for i in range(nu)]
    return facet.PolyMesh.from_faces(vertices, faces)


def make_facade(path):
    import facetwb

    doc = App.newDocument("facade")
    surface = design_surface(doc)
    control = facetwb.make_polymesh(sampled_grid(surface.Shape.Faces[0], QUADS_U, QUADS_V),
                                    name="Control", label="Control mesh", doc=doc)
    planarized = facetwb.make_planarized(control, tolerance=1e-9)
    panels = facetwb.make_panelset(planarized, thickness=40.0, gap=GAP)
    sheets = facetwb.make_cutsheets(panels, sheet=(3210.0, 2250.0), margin=10.0, spacing=8.0,
                                    write_step=False)
    doc.recompute()
    _check(doc)
    doc.saveAs(path)
    App.closeDocument(doc.Name)
    return sheets


def make_roof(path):
    import Sketcher  # noqa: F401 - registers the Sketch type

    import facetwb

    # the plan and pins that examples/roof_plan.dxf and roof_heights.csv hold
    from make_example_plan import ROOF_PINS, roof_lines

    doc = App.newDocument("roof")
    sketch = doc.addObject("Sketcher::SketchObject", "Plan")
    sketch.Label = "Roof plan"
    for (x1, y1), (x2, y2) in roof_lines():
        sketch.addGeometry(Part.LineSegment(App.Vector(x1, y1, 0), App.Vector(x2, y2, 0)),
                           False)
    plan = facetwb.make_plan_graph([sketch], doc=doc)
    lifting = facetwb.make_lifting(plan, pins=[tuple(p) for p in ROOF_PINS])
    # 20 mm joints: square-cut 30 mm panels overlap across the roof's valley below 18.3 mm
    facetwb.make_panelset(lifting, thickness=30.0, gap=20.0)
    doc.recompute()
    _check(doc)
    doc.saveAs(path)
    App.closeDocument(doc.Name)


def _check(doc):
    bad = [f"{o.Label}: {o.getStatusString()}" for o in doc.Objects if not o.isValid()]
    if bad:
        raise RuntimeError("; ".join(bad))


def main():
    os.makedirs(EXAMPLES, exist_ok=True)
    make_facade(os.path.join(EXAMPLES, "facade.FCStd"))
    make_roof(os.path.join(EXAMPLES, "roof.FCStd"))
    for name in ("facade.FCStd", "roof.FCStd"):
        size = os.path.getsize(os.path.join(EXAMPLES, name))
        print(f"examples/{name}: {size // 1024} KB")


try:
    main()
    status = 0
except BaseException:  # noqa: BLE001 - freecadcmd would exit 0 on an exception
    import traceback

    traceback.print_exc()
    status = 1
sys.stdout.flush()
sys.stderr.flush()
os._exit(status)
