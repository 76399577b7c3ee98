# SPDX-License-Identifier: LGPL-2.1-or-later
"""SurfaceMesh: a control polygon mesh sampled from a FreeCAD surface, kept linked to it.

``Source`` is a Part object with faces (a Face, a Shell, a Solid: Part, Surface or Curves
workbench results) or a FreeCAD Mesh. On recompute each face is sampled over its (u, v)
parameter rectangle (``Face.valueAt``) into

- ``quad``: a grid of ``CountU x CountV`` quads, or quads about ``PanelSize`` wide;
- ``hex``: a honeycomb, ``CountU`` hexagons per row and ``CountV`` rows, or hexagons about
  ``PanelSize`` across;
- ``tri-quad``: the face triangulated (edges about ``PanelSize`` long, MeshPart) or the
  Mesh's own triangles, paired into quads (``facet.gridding.pair_triangles``).

The faces of a shell are welded along shared edges (and the seam and poles of closed surfaces
closed up: a face all the way round a periodic u gets a grid that closes around, hexagons
included). Cells of a trimmed face with a corner outside the trim are dropped, so a trimmed
face's mesh stops short of its trim by up to one cell (use tri-quad to follow a trim). Faces follow
the face's orientation. The result is a Facet polygon mesh (Planarize, Panels take it); the
source is never modified. Numerics are in ``facet.gridding``; this module is wiring.
"""

import numpy as np

import facet
from facetwb import compat, conversion, progress
from facetwb.recompute import guarded
from facetwb.objects.polymesh import PolyMesh, set_mesh, set_planarity

TYPE_SURFACEMESH = "Facet::SurfaceMesh"

#: Saved in documents: never change these strings.
PATTERNS = ["quad", "hex", "tri-quad"]


class SurfaceMesh(PolyMesh):
    """Proxy of a control mesh sampled from a surface (App::FeaturePython)."""

    TYPE = TYPE_SURFACEMESH

    def init_source_properties(self, obj):
        add = compat.add_property
        add(obj, "App::PropertyLink", "Source", "Base",
            "The surface: a Part object with faces (Face, Shell, Solid) or a Mesh; never "
            "modified")
        if add(obj, "App::PropertyEnumeration", "Pattern", "Grid",
               "quad: quads along the surface's u and v lines; hex: a honeycomb; tri-quad: "
               "triangles paired into quads where they make good quads"):
            obj.Pattern = PATTERNS
            obj.Pattern = "quad"
        add(obj, "App::PropertyInteger", "CountU", "Grid",
            "Panels along the surface's u direction, per face (used when PanelSize is 0)",
            value=10)
        add(obj, "App::PropertyInteger", "CountV", "Grid",
            "Panels (hex: rows) along the surface's v direction, per face (used when "
            "PanelSize is 0)", value=10)
        add(obj, "App::PropertyLength", "PanelSize", "Grid",
            "Target panel width (quad edge, hexagon across flats, triangle edge); 0: use "
            "CountU and CountV")
        add(obj, "App::PropertyFloat", "MaxCornerDeviation", "Pairing",
            "tri-quad: largest difference of a quad's corner angle from 90 degrees", value=45.0)
        add(obj, "App::PropertyFloat", "MaxFold", "Pairing",
            "tri-quad: largest fold angle between the two triangles of a quad, degrees",
            value=20.0)
        add(obj, "App::PropertyLength", "WeldTolerance", "Grid",
            "Vertices of neighbouring faces closer than this become one (0: 1e-7 of the "
            "bounding box diagonal)")

    @guarded
    def execute(self, obj):
        mesh = surface_control_mesh(obj)
        set_mesh(obj, mesh)
        set_planarity(obj, facet.planarity(mesh))


def _face_sampler(face):
    def evaluate(u, v):
        return np.array([tuple(face.valueAt(float(a), float(b))) for a, b in zip(u, v)],
                        dtype=np.float64).reshape(-1, 3)

    def inside(u, v):
        return np.array([face.isPartOfDomain(float(a), float(b)) for a, b in zip(u, v)],
                        dtype=bool)

    return evaluate, inside


def _is_trimmed(face):
    """True unless the face is its surface's whole parameter rectangle (no inside test)."""
    u0, u1, v0, v1 = face.ParameterRange
    try:
        natural = face.Surface.toShape(u0, u1, v0, v1)
        return abs(natural.Area - face.Area) > 1e-6 * max(face.Area, 1e-300)
    except Exception:  # noqa: BLE001 - when in doubt, test every point
        return True


def _closed_in_u(face):
    """True when the face goes once all the way round its surface's periodic u."""
    surface = face.Surface
    try:
        if not surface.isUPeriodic():
            return False
        u0, u1, _v0, _v1 = face.ParameterRange
        period = surface.UPeriod()
        return abs((u1 - u0) - period) <= 1e-9 * period and not _is_trimmed(face)
    except Exception:  # noqa: BLE001 - not every surface answers: then it is open
        return False


def _oriented(mesh, reverse):
    if not reverse:
        return mesh
    return facet.PolyMesh.from_faces(mesh.vertices, [list(f)[::-1] for f in mesh.faces()])


def surface_control_mesh(obj):
    """The ``facet.PolyMesh`` a SurfaceMesh's properties give for its Source."""
    from facet import gridding

    source = obj.Source
    if source is None:
        raise ValueError(f"{obj.Label}: Source is empty, no surface to panelize")
    size = float(obj.PanelSize.Value)
    pattern = obj.Pattern
    if size < 0:
        raise ValueError(f"{obj.Label}: PanelSize is {size}; it must be 0 or more")
    hook = progress.hook()
    if source.isDerivedFrom("Mesh::Feature"):
        if pattern != "tri-quad":
            raise ValueError(f"{obj.Label}: a Mesh source ({source.Label}) has no (u, v) "
                             "parameters: use the tri-quad pattern")
        triangles = conversion.mesh_from_mesh(source.Mesh, source.Label)
        return gridding.pair_triangles(triangles, obj.MaxCornerDeviation, obj.MaxFold, hook)
    shape = getattr(source, "Shape", None)
    if shape is None or shape.isNull() or not shape.Faces:
        raise ValueError(f"{obj.Label}: Source {source.Label} has no faces")
    diagonal = shape.BoundBox.DiagonalLength or 1.0
    weld_tol = float(obj.WeldTolerance.Value) or 1e-7 * diagonal
    if pattern == "tri-quad":
        from facetwb.tessellation import triangles_from_shape

        length = size or diagonal / max(obj.CountU, obj.CountV, 1)
        # (progress and Cancel: FreeCAD's mesher took minutes for 130,000 triangles)
        triangles = triangles_from_shape(shape, length, source.Label, hook)
        triangles = gridding.weld([triangles], weld_tol)
        return gridding.pair_triangles(triangles, obj.MaxCornerDeviation, obj.MaxFold, hook)
    parts = []
    for number, face in enumerate(shape.Faces, start=1):
        u0, u1, v0, v1 = face.ParameterRange
        evaluate, inside = _face_sampler(face)
        try:
            if size > 0:
                nu, nv = gridding.grid_counts(evaluate, (u0, u1), (v0, v1), size, pattern)
            else:
                nu, nv = int(obj.CountU), int(obj.CountV)
            closed = _closed_in_u(face) and nu >= 3
            mesh = gridding.sample_surface(evaluate, (u0, u1), (v0, v1), pattern, nu, nv,
                                           inside=inside if _is_trimmed(face) else None,
                                           progress=hook, periodic_u=closed)
        except facet.InputError as error:
            raise ValueError(f"{obj.Label}: face {number} of {source.Label}: {error}") from None
        parts.append(_oriented(mesh, face.Orientation == "Reversed"))
    return gridding.weld(parts, weld_tol)


def is_surface_mesh(obj):
    """True if ``obj`` is a Facet SurfaceMesh."""
    return getattr(getattr(obj, "Proxy", None), "Type", None) == TYPE_SURFACEMESH


def make_surface_mesh(source, pattern="quad", count_u=10, count_v=10, panel_size=0.0,
                      name="SurfaceMesh"):
    """Add a SurfaceMesh sampling ``source`` (scripting API, runs headless); recompute to
    build it.

    Parameters
    ----------
    source : App.DocumentObject
        A Part object with faces, or a Mesh (then ``pattern`` must be "tri-quad").
    pattern : {"quad", "hex", "tri-quad"}
    count_u, count_v : int
        Panels per face along u and v, used when ``panel_size`` is 0.
    panel_size : float
        Target panel width in mm (0: use the counts).
    """
    if pattern not in PATTERNS:
        raise ValueError(f"pattern must be one of {PATTERNS}, not {pattern!r}")
    for label, count in (("count_u", count_u), ("count_v", count_v)):
        if not isinstance(count, int) or count < 1:
            raise ValueError(f"{label} is {count!r}; it must be a whole number, 1 or more")
    if not panel_size >= 0:
        raise ValueError(f"panel_size is {panel_size!r}; it must be 0 or more")
    doc = source.Document
    obj = doc.addObject("App::FeaturePython", name)
    SurfaceMesh(obj)
    obj.Label = f"{source.Label} {pattern} mesh"
    obj.Source = source
    obj.Pattern = pattern
    obj.CountU = count_u
    obj.CountV = count_v
    obj.PanelSize = float(panel_size)
    from facetwb.viewproviders import attach

    attach.give(obj)
    return obj

