# SPDX-License-Identifier: LGPL-2.1-or-later
"""Polygon meshes out of FreeCAD objects: Facet meshes, FreeCAD Meshes and Part shapes.

- a Facet polygon mesh object (PolyMesh, Planarized): its stored mesh;
- a Mesh feature: its triangles;
- a Part shape whose faces are all planar polygons without holes (a facade modelled as
  panels): one polygon face per Part face, from the face's outer wire; vertices that Part faces
  share become one mesh vertex, also where they are a rounding apart (within 1e-9 of the
  shape's size: panels modelled one by one, whose common corners were computed each its own
  way), as they would otherwise not be joined (no bevel between them);
- any other Part shape: a triangulation of the whole shape (MeshPart), welded along edges.

Coordinates are global (placements applied) and in model units (mm).
"""

import numpy as np

import facet
from facet.mesh import weld


class SourceError(ValueError):
    """An object that Facet cannot read a polygon mesh from."""


def has_surface(obj):
    """True if ``obj`` is a FreeCAD Mesh or a shape with faces, not a Facet polygon mesh:
    a surface to sample or to convert (mesh_from_object's other two cases)."""
    from facetwb.objects.polymesh import is_polymesh

    if is_polymesh(obj):
        return False
    return obj.isDerivedFrom("Mesh::Feature") or shape_has(obj, "Faces")


def shape_has(obj, what):
    """Whether ``obj`` has a shape with some ``what`` ("Faces", "Edges"); a
    missing, null or broken shape has none."""
    shape = getattr(obj, "Shape", None)
    try:
        return shape is not None and not shape.isNull() and bool(getattr(shape, what))
    except Exception:  # noqa: BLE001 - a broken shape just has none
        return False


def mesh_from_object(obj, tessellation_tolerance=0.0):
    """A ``facet.PolyMesh`` read from ``obj`` (see the module docstring)."""
    from facetwb.objects.polymesh import get_mesh, is_polymesh

    if is_polymesh(obj):
        return get_mesh(obj)
    if obj.isDerivedFrom("Mesh::Feature"):
        return mesh_from_mesh(obj.Mesh, obj.Label)
    shape = getattr(obj, "Shape", None)
    if shape is not None and not shape.isNull() and shape.Faces:
        return mesh_from_shape(shape, tessellation_tolerance, obj.Label)
    raise SourceError(f"{obj.Label} is neither a polygon mesh, a Mesh nor a shape with faces")


def mesh_from_mesh(mesh, label="mesh", offset=None):
    """A triangle ``facet.PolyMesh`` from a FreeCAD ``Mesh.Mesh`` (its points plus
    ``offset``, added in double precision)."""
    points, facets = mesh.Topology
    return mesh_from_topology([(p.x, p.y, p.z) for p in points], facets, label, offset)


def mesh_from_topology(points, facets, label="mesh", offset=None):
    """:func:`mesh_from_mesh` of a ``Mesh.Mesh``'s ``Topology``, its points as (x, y, z)."""
    if not facets:
        raise SourceError(f"{label} has no triangles")
    xyz = np.array(points, dtype=np.float64).reshape(-1, 3)
    if offset is not None:
        xyz += np.asarray(offset, dtype=np.float64)
    return facet.PolyMesh.from_faces(xyz, [list(f) for f in facets])


def is_polygonal(shape):
    """True if every face of ``shape`` is planar, bounded by straight edges, without holes."""
    import Part

    for face in shape.Faces:
        if not isinstance(face.Surface, Part.Plane) or len(face.Wires) != 1:
            return False
        if not all(isinstance(edge.Curve, (Part.Line, Part.LineSegment)) for edge in face.Edges):
            return False
    return True


def mesh_from_shape(shape, tessellation_tolerance=0.0, label="shape"):
    """A ``facet.PolyMesh`` from a Part shape: polygons if it is polygonal, else triangles."""
    if is_polygonal(shape):
        return _polygons_from_faces(shape, label)
    import MeshPart

    tolerance = tessellation_tolerance
    if tolerance <= 0.0:
        tolerance = shape.BoundBox.DiagonalLength / 1000.0 or 0.1
    # FreeCAD's Mesh holds single-precision points: tessellated where it stands, a
    # shape at georeferenced coordinates (E 512 km in mm) came back rounded to tens of
    # millimetres. Tessellated about its centre, then moved back in double precision.
    centre = shape.BoundBox.Center
    local = shape.copy()
    local.translate(-centre)
    mesh = MeshPart.meshFromShape(Shape=local, LinearDeflection=tolerance,
                                  AngularDeflection=0.5, Relative=False)
    return mesh_from_mesh(mesh, label, offset=(centre.x, centre.y, centre.z))


def _polygons_from_faces(shape, label):
    index = {}
    xyz = []
    faces = []
    for face in shape.Faces:
        polygon = []
        for vertex in face.OuterWire.OrderedVertexes:
            key = (vertex.X, vertex.Y, vertex.Z)
            if key not in index:
                index[key] = len(xyz)
                xyz.append(key)
            polygon.append(index[key])
        if len(polygon) < 3:
            raise SourceError(f"{label}: a face has fewer than 3 corners")
        # Wire order follows the wire, not the face: turn it to match the face's normal.
        u0, u1, v0, v1 = face.ParameterRange
        normal = face.normalAt(0.5 * (u0 + u1), 0.5 * (v0 + v1))
        corners = np.array([xyz[i] for i in polygon])
        area_vector = np.cross(corners, np.roll(corners, -1, axis=0)).sum(axis=0)
        if np.dot(area_vector, (normal.x, normal.y, normal.z)) < 0.0:
            polygon.reverse()
        faces.append(polygon)
    mesh = facet.PolyMesh.from_faces(np.array(xyz, dtype=np.float64), faces)
    try:
        return weld(mesh)[0]
    except facet.MeshError as error:
        raise SourceError(f"{label}: {error}") from None
