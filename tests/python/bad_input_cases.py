# SPDX-License-Identifier: LGPL-2.1-or-later
"""The bad-input catalogue (docs/bad-input.md): one row per kind of bad input.

Each :class:`Row` writes its input files into a folder, names the command
line that reads them and what the one-line error must contain. Rows with
``works=True`` are inputs that look hostile but are valid (tiny or
georeferenced coordinates, faces with hundreds of vertices, dangling edges in
a drawing): those must succeed. Shared by tests/python/test_bad_input.py and
tests/freecad/test_bad_input_fc.py; plain Python, no pytest, no FreeCAD.
"""

import json
import math
import os
from dataclasses import dataclass, field

__all__ = ["Row", "ROWS", "row", "grid", "obj_text", "off_text", "json_text"]


def grid(nx=3, ny=3, scale=1.0, offset=(0.0, 0.0, 0.0), bump=0.05):
    """Vertices and quad faces of an (nx x ny)-vertex grid, slightly non-planar."""
    vertices = []
    for j in range(ny):
        for i in range(nx):
            z = bump * ((i * j) % 2)
            vertices.append([offset[0] + scale * i, offset[1] + scale * j, offset[2] + scale * z])
    faces = [[j * nx + i, j * nx + i + 1, (j + 1) * nx + i + 1, (j + 1) * nx + i]
             for j in range(ny - 1) for i in range(nx - 1)]
    return vertices, faces


def _number(value):
    if isinstance(value, str):
        return value
    return repr(float(value))


def obj_text(vertices, faces):
    lines = ["# facet bad-input catalogue"]
    lines += ["v " + " ".join(_number(c) for c in v) for v in vertices]
    lines += ["f " + " ".join(str(i + 1) for i in f) for f in faces]
    return "\n".join(lines) + "\n"


def off_text(vertices, faces):
    lines = ["OFF", f"{len(vertices)} {len(faces)} 0"]
    lines += [" ".join(_number(c) for c in v) for v in vertices]
    lines += [f"{len(f)} " + " ".join(str(i) for i in f) for f in faces]
    return "\n".join(lines) + "\n"


def json_text(vertices, faces):
    def coordinate(c):
        if isinstance(c, str):
            return c
        return float(c)

    data = {
        "dtype": "compas.datastructures/Mesh",
        "data": {
            "attributes": {"name": "Mesh"},
            "dva": {"x": 0.0, "y": 0.0, "z": 0.0},
            "dea": {},
            "dfa": {},
            "vertex": {str(k): dict(zip("xyz", map(coordinate, v))) for k, v in enumerate(vertices)},
            "face": {str(k): list(f) for k, f in enumerate(faces)},
            "facedata": {},
            "edgedata": {},
            "max_vertex": len(vertices) - 1,
            "max_face": len(faces) - 1,
        },
    }
    text = json.dumps(data)
    return text.replace('"NaN!"', "NaN").replace('"Infinity!"', "Infinity")


WRITERS = {".obj": obj_text, ".off": off_text, ".json": json_text}


@dataclass
class Row:
    """One kind of bad input.

    name : the row's id (test ids and the table in docs/bad-input.md).
    files : {file name: text or bytes} written into the row's folder.
    argv : the ``facet`` command line; ``{dir}`` is the folder.
    expect : strings the one error line must contain (``{dir}`` allowed).
    works : the input is valid and the command must succeed (exit 0).
    mesh : the file a Python/FreeCAD reader reads, when the row is about a mesh file.
    kind : "mesh", "plan", "targets" or "panels" (what the FreeCAD test does with it).
    """

    name: str
    files: dict
    argv: list
    expect: list
    works: bool = False
    mesh: str = None
    kind: str = "mesh"
    panels: dict = field(default_factory=dict)

    def write(self, folder):
        os.makedirs(folder, exist_ok=True)
        for name, content in self.files.items():
            path = os.path.join(folder, name)
            if isinstance(content, _LazyText):
                content = content.make()
            if isinstance(content, bytes):
                with open(path, "wb") as handle:
                    handle.write(content)
            else:
                with open(path, "w", encoding="utf-8") as handle:
                    handle.write(content)
        return folder

    def command(self, folder):
        return [a.replace("{dir}", str(folder)) for a in self.argv]

    def expected(self, folder):
        return [e.replace("{dir}", str(folder)) for e in self.expect]


ROWS = []


def row(*args, **kwargs):
    ROWS.append(Row(*args, **kwargs))


def _mesh_rows(suffix):
    write = WRITERS[suffix]
    tag = suffix[1:]
    name = "in" + suffix
    v, f = grid()

    def mesh_row(label, vertices, faces, expect, command="check", works=False, extra=()):
        row(f"{label}_{tag}", {name: write(vertices, faces)},
            [command, "{dir}/" + name, *extra], ["{dir}/" + name, *expect], works=works,
            mesh=name)

    nan = [list(p) for p in v]
    nan[4][2] = "NaN!" if suffix == ".json" else "nan"
    mesh_row("nan", nan, f, ["vertex 4", "finite"])
    inf = [list(p) for p in v]
    inf[5][0] = "Infinity!" if suffix == ".json" else "inf"
    mesh_row("inf", inf, f, ["vertex 5", "finite"])
    mesh_row("index_out_of_range", v, f[:-1] + [[4, 5, 9, 7]],
             ["face", "9", "out of range" if suffix != ".json" else "does not define"])
    mesh_row("repeated_vertex", v, f[:-1] + [[4, 5, 8, 5]], ["face 3", "repeats vertex 5"])
    mesh_row("two_vertex_face", v, f[:-1] + [[4, 5]], ["face", "3", "2 vertices"])
    # Zero area: three collinear vertices (0, 1, 2 lie on the x axis). The planarizer
    # keeps it (it is planar) and says so; panels refuse it (panels_zero_area_face).
    mesh_row("zero_area_face", v, f + [[0, 1, 2]], [],
             command="planarize", extra=("-o", "{dir}/out.obj"), works=True)
    row(f"empty_{tag}", {name: ""}, ["check", "{dir}/" + name],
        ["{dir}/" + name, "file is empty"],
        mesh=name)
    full = write(v, f)
    row(f"truncated_{tag}", {name: full[: int(len(full) * 0.6)]}, ["check", "{dir}/" + name],
        ["{dir}/" + name], mesh=name)
    garbage = bytes((i * 73 + 11) % 256 for i in range(512))
    row(f"binary_garbage_{tag}", {name: garbage}, ["check", "{dir}/" + name],
        ["{dir}/" + name], mesh=name)
    # Non-manifold: three quads share the edge 1-4 of a 3x3 grid's first row.
    nm_v = v + [[1.0, 0.5, 1.0], [1.0, 1.5, 1.0]]
    nm_f = f + [[1, 4, 10, 9]]
    mesh_row("non_manifold", nm_v, nm_f, [], command="planarize",
             extra=("-o", "{dir}/out.obj"), works=True)
    mesh_row("isolated_vertex", v + [[5.0, 5.0, 5.0]], f, [], command="planarize",
             extra=("-o", "{dir}/out.obj"), works=True)
    tiny, _ = grid(scale=1e-6)
    mesh_row("tiny_coordinates", tiny, f, [], command="planarize",
             extra=("-o", "{dir}/out.obj"), works=True)
    geo, _ = grid(scale=1.0, offset=(2.6e6, 1.2e6, 4.5e2))
    mesh_row("georeferenced_coordinates", geo, f, [], command="planarize",
             extra=("-o", "{dir}/out.obj"), works=True)
    big, _ = grid(scale=1e7)
    mesh_row("huge_coordinates", big, f, [], command="planarize",
             extra=("-o", "{dir}/out.obj"), works=True)
    # One face with 300 vertices on a wavy circle, and a fan of quads around it would be
    # heavy for a test; a single 300-gon plus a triangle on its edge is enough.
    n = 300
    ring = [[math.cos(2 * math.pi * k / n), math.sin(2 * math.pi * k / n),
             0.02 * math.sin(6 * math.pi * k / n)] for k in range(n)]
    mesh_row("face_with_300_vertices", ring + [[1.5, 0.0, 0.0]],
             [list(range(n)), [0, n, 1]], [], command="planarize",
             extra=("-o", "{dir}/out.obj"), works=True)


for _suffix in (".obj", ".off", ".json"):
    _mesh_rows(_suffix)


# ------------------------------------------------------------------ plans

def _segments_text(segments):
    return "".join(",".join(_number(c) for c in s) + "\n" for s in segments)


def plan_grid_segments(n=2):
    """An n x n grid of unit squares as x1,y1,x2,y2 segments."""
    segments = []
    for k in range(n + 1):
        segments.append((0.0, float(k), float(n), float(k)))
        segments.append((float(k), 0.0, float(k), float(n)))
    return segments


def _targets_text(n=2):
    return "".join(f"{i!r},{j!r},{0.1 * (i + j * j)!r}\n"
                   for j in (0.0, 1.0, 2.0) for i in (0.0, 1.0, 2.0)[: n + 1])


def dxf_text(segments, layer=None):
    """A DXF drawing (ezdxf, R2010) of the segments as LINE entities; on `layer`, turned
    off, if given."""
    import io

    import ezdxf

    doc = ezdxf.new("R2010")
    msp = doc.modelspace()
    attributes = {}
    if layer:
        doc.layers.add(layer).off()
        attributes["layer"] = layer
    for x1, y1, x2, y2 in segments:
        msp.add_line((x1, y1), (x2, y2), dxfattribs=attributes)
    stream = io.StringIO()
    doc.write(stream)
    return stream.getvalue()


class _LazyText:
    """File content made when written (DXF needs ezdxf, imported late)."""

    def __init__(self, make):
        self.make = make


def _plan_rows():
    good = plan_grid_segments()
    targets = _targets_text()
    lift = ["lift", "{dir}/plan.csv", "-o", "{dir}/roof.obj", "--targets", "{dir}/t.csv"]

    def plan_row(name, content, expect, works=False, plan="plan.csv", extra_files=None):
        files = {plan: content, "t.csv": targets}
        files.update(extra_files or {})
        argv = [a.replace("plan.csv", plan) for a in lift]
        row(name, files, argv, ["{dir}/" + plan, *expect] if not works else [], works=works,
            mesh=plan, kind="plan")

    nan = list(map(list, good))
    nan[3][1] = "nan"
    plan_row("plan_nan_csv", _segments_text(nan), ["line 4", "finite"])
    plan_row("plan_empty_csv", "", ["no segments"])
    text = _segments_text(good)
    plan_row("plan_truncated_csv", text[: text.index("\n", len(text) // 2) + 5],
             ["line 5", "four finite numbers"])
    plan_row("plan_binary_garbage_csv", bytes((i * 73 + 11) % 256 for i in range(512)),
             ["not a text file"])
    # Two diagonals crossing in the middle of a square: split at the crossing, 4 triangles.
    plan_row("plan_crossing_edges_csv",
             _segments_text([(0, 0, 2, 0), (2, 0, 2, 2), (2, 2, 0, 2), (0, 2, 0, 0),
                             (0, 0, 2, 2), (2, 0, 0, 2)]), [], works=True)
    plan_row("plan_dangling_edges_csv", _segments_text(good + [(2.0, 2.0, 3.0, 3.0)]), [],
             works=True)
    plan_row("plan_no_bounded_face_csv",
             _segments_text([(0, 0, 1, 0), (1, 0, 1, 1), (1, 1, 2, 1)]), ["no bounded face"])
    # A plan mesh whose two faces overlap when seen from above.
    plan_row("plan_overlapping_faces_obj",
             obj_text([[0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0],
                       [1, 1, 0], [3, 1, 0], [3, 3, 0], [1, 3, 0]],
                      [[0, 1, 2, 3], [4, 5, 6, 7]]),
             ["faces 0 and 1 overlap"], plan="plan.obj")
    plan_row("plan_self_crossing_face_obj",
             obj_text([[0, 0, 0], [2, 0, 0], [0, 2, 0], [2, 2, 0]], [[0, 1, 2, 3]]),
             ["face 0", "crosses itself"], plan="plan.obj")
    plan_row("plan_empty_dxf", "", ["file is empty"], plan="plan.dxf")
    dxf = _LazyText(lambda: dxf_text(good))
    plan_row("plan_truncated_dxf", _LazyText(lambda: dxf.make()[: len(dxf.make()) // 2]),
             ["DXF"], plan="plan.dxf")
    plan_row("plan_binary_garbage_dxf", bytes((i * 73 + 11) % 256 for i in range(512)),
             ["not a DXF file"], plan="plan.dxf")
    # every line on a layer that is turned off: nothing is shown, nothing is read
    plan_row("plan_every_layer_off_dxf", _LazyText(lambda: dxf_text(good, layer="OLD")),
             ["no LINE", "on layers that are off or frozen (OLD"], plan="plan.dxf")

    def target_row(name, content, expect):
        row(name, {"plan.csv": text, "t.csv": content}, lift, ["{dir}/t.csv", *expect],
            mesh="t.csv", kind="targets")

    target_row("targets_nan_csv", targets.replace("0.2", "nan", 1), ["line", "finite"])
    target_row("targets_short_line_csv", "0.0,0.0\n" + targets, ["line 1", "x,y,z"])
    target_row("targets_empty_csv", "", ["no target"])
    target_row("targets_binary_garbage_csv", bytes((i * 73 + 11) % 256 for i in range(512)),
               ["not a text file"])


_plan_rows()


# ------------------------------------------------------------------ panels

def _panel_rows():
    v, f = grid(bump=0.0)
    mesh = obj_text(v, f)

    def panel_row(name, options, expect, files=None, works=False):
        argv = ["panels", "{dir}/flat.obj", *options]
        row(name, files or {"flat.obj": mesh}, argv,
            [] if works else expect, works=works, mesh="flat.obj", kind="panels")

    panel_row("panels_zero_thickness", ["--thickness", "0"], ["thickness", "not 0.0 mm"])
    panel_row("panels_negative_thickness", ["--thickness", "-1"], ["thickness", "not -1.0 mm"])
    panel_row("panels_nan_thickness", ["--thickness", "nan"], ["thickness", "nan"])
    panel_row("panels_sheet_smaller_than_panel", ["--thickness", "0.01", "--gap", "0",
                                                  "--sheet", "0.5x0.5", "--margin", "0.01"],
              ["{dir}/flat.obj", "fit on no 0.5 x 0.5 mm sheet (margin 0.01 mm)", "P-",
               "use a larger sheet or a smaller margin"])  # (the workbench says it too)
    # a mesh in metres read as millimetres: the default margin (10 mm) is larger than the
    # sheet; it was refused as "margin 10 leaves nothing", a margin the user never gave
    panel_row("panels_default_margin_larger_than_sheet",
              ["--thickness", "0.01", "--sheet", "3x1.5"],
              ["{dir}/flat.obj", "the default margin, 10 mm, leaves", "3 x 1.5 sheet",
               "--margin", "--units"])
    panel_row("panels_gap_larger_than_panel", ["--thickness", "0.01", "--gap", "3"],
              ["{dir}/flat.obj", "face 0", "gap 3"])
    panel_row("panels_gap_closes_a_notch", ["--thickness", "8", "--gap", "10"],
              # (in mm from the command line and FreeCAD, model units from Python)
              ["{dir}/flat.obj", "face 0", "crosses itself", "gap (10"],
              files={"flat.obj": obj_text([[0, 0, 0], [1000, 0, 0], [1000, 1000, 0],
                                           [510, 1000, 0], [500, 300, 0], [490, 1000, 0],
                                           [0, 1000, 0]], [[0, 1, 2, 3, 4, 5, 6]])})
    # the core names faces and a vertex by index, which a designer cannot find in a
    # modeller: the vertex's point is said too
    panel_row("panels_faces_fold_back", ["--thickness", "8"],
              ["{dir}/flat.obj", "faces 0 and 1 fold back onto each other at vertex 1 "
               "(1000, 0, 0)"],
              files={"flat.obj": obj_text([[0, 0, 0], [1000, 0, 0], [1000, 1000, 0],
                                           [0, 1000, 0], [500, 0, 0], [500, 1000, 0]],
                                          [[0, 1, 2, 3], [2, 1, 4, 5]])})
    panel_row("panels_zero_area_face", ["--thickness", "0.01"],
              ["{dir}/flat.obj", "face 4", "no area"],
              files={"flat.obj": obj_text(v, f + [[0, 1, 2]])})
    panel_row("panels_not_planar", ["--thickness", "0.01"],
              ["{dir}/flat.obj", "not planar"],
              files={"flat.obj": obj_text(*grid(bump=0.05))})
    nm_v = v + [[1.0, 0.5, 1.0], [1.0, 1.5, 1.0]]
    panel_row("panels_non_manifold", ["--thickness", "0.01", "--gap", "0"], [],
              files={"flat.obj": obj_text(nm_v, f + [[1, 4, 10, 9]])}, works=True)


_panel_rows()
