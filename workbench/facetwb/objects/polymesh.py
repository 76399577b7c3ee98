# SPDX-License-Identifier: LGPL-2.1-or-later
"""PolyMesh: a polygon mesh (quads, hexes, triangles side by side) as a document object.

FreeCAD's own Mesh object holds triangles only, so Facet stores its polygon meshes in an
``App::FeaturePython`` with three properties, the CSR form of ``facet.PolyMesh``:

- ``Points`` (App::PropertyVectorList): vertex coordinates, model units (mm);
- ``FaceStart`` (App::PropertyIntegerList): ``n_faces + 1`` offsets into ``FaceVertices``;
- ``FaceVertices`` (App::PropertyIntegerList): the vertex indices of all faces, in order.

Precision: FreeCAD writes App::PropertyVectorList and App::PropertyFloatList into the .FCStd
as binary files of float64, so a saved and reopened mesh keeps every bit of its coordinates
(a planar panel stays planar). tests/freecad/test_polymesh.py proves it on every run.
Scalar App::PropertyFloat and App::PropertyLength values are written as decimal text with 16
digits after the point: a result like PlanarityMaxRel = 9.57e-7 keeps about 10 significant
digits, and a Tolerance of 1e-6 or 1e-9 is kept exactly. Per-face values are float lists,
exact like the coordinates.

A PolyMesh either holds an imported mesh (``Source`` empty) or is derived from a FreeCAD Mesh
or Part object linked in ``Source`` and rebuilt on recompute. Either way, recompute measures
its planarity (``facet.planarity``) into the ``Planarity`` group, which the view provider
draws as a colour map.
"""

import numpy as np

import facet
from facetwb import compat
from facetwb.recompute import guarded, observe_documents
from facetwb import conversion

#: Proxy Type strings: saved in documents, never change them.
TYPE_POLYMESH = "Facet::PolyMesh"

#: Properties that define the mesh; a change to any of them redraws it.
MESH_PROPERTIES = ("Points", "FaceStart", "FaceVertices")


class PolyMesh:
    """Proxy of a polygon mesh document object (App::FeaturePython)."""

    TYPE = TYPE_POLYMESH

    def __init__(self, obj):
        self.Type = self.TYPE
        obj.Proxy = self
        self.init_properties(obj)

    # --- properties -----------------------------------------------------------------------

    def init_properties(self, obj):
        """Add the properties this version has and ``obj`` lacks (idempotent)."""
        self.init_source_properties(obj)
        init_mesh_properties(obj)
        observe_documents()  # (a FreeCAD Mesh in Source replaced: marked for recompute)

    def init_source_properties(self, obj):
        compat.add_property(
            obj, "App::PropertyLink", "Source", "Base",
            "A FreeCAD Mesh or Part object to build this polygon mesh from on recompute "
            "(empty: the mesh was imported and is kept as it is)")
        compat.add_property(
            obj, "App::PropertyLength", "TessellationTolerance", "Base",
            "Largest distance between a curved Part surface and its triangles when Source must "
            "be tessellated (0: 1/1000 of the bounding box diagonal)")

    def onDocumentRestored(self, obj):
        self.init_properties(obj)
        from facetwb.viewproviders import attach

        attach.schedule(obj)  # a document saved without the GUI has no view provider

    # --- recompute ------------------------------------------------------------------------

    @guarded
    def execute(self, obj):
        source = getattr(obj, "Source", None)
        if source is not None:
            mesh = conversion.mesh_from_object(source, obj.TessellationTolerance.Value)
            set_mesh(obj, mesh)
        else:
            mesh = get_mesh(obj)
        set_planarity(obj, facet.planarity(mesh))

    def onChanged(self, obj, prop):
        pass

    # --- saving: FreeCAD 0.21.2+ calls dumps/loads, older versions __getstate__/__setstate__

    def dumps(self):
        return {"Type": self.Type}

    def loads(self, state):
        self.Type = self.TYPE
        if isinstance(state, dict):
            self.Type = state.get("Type", self.TYPE)
        elif isinstance(state, str):
            self.Type = state

    def __getstate__(self):
        return self.dumps()

    def __setstate__(self, state):
        self.loads(state)


def init_mesh_properties(obj):
    """The mesh and planarity properties every Facet polygon mesh object has."""
    hidden = compat.EDITOR_HIDDEN
    read_only = compat.EDITOR_READ_ONLY
    compat.add_property(obj, "App::PropertyVectorList", "Points", "Mesh",
                        "Vertex coordinates", editor_mode=hidden)
    compat.add_property(obj, "App::PropertyIntegerList", "FaceStart", "Mesh",
                        "Offset of each face's first vertex in FaceVertices, then the total",
                        editor_mode=hidden)
    compat.add_property(obj, "App::PropertyIntegerList", "FaceVertices", "Mesh",
                        "Vertex indices of all faces, face after face", editor_mode=hidden)
    compat.add_property(obj, "App::PropertyInteger", "VertexCount", "Mesh",
                        "Number of vertices", attr=compat.PROP_OUTPUT, editor_mode=read_only)
    compat.add_property(obj, "App::PropertyInteger", "FaceCount", "Mesh",
                        "Number of faces (panels)", attr=compat.PROP_OUTPUT,
                        editor_mode=read_only)
    compat.add_property(obj, "App::PropertyLength", "PlanarityMaxAbs", "Planarity",
                        "Largest distance of a vertex from its face's best-fit plane",
                        attr=compat.PROP_OUTPUT, editor_mode=read_only)
    compat.add_property(obj, "App::PropertyFloat", "PlanarityMaxRel", "Planarity",
                        "Largest distance of a vertex from its face's best-fit plane, "
                        "relative to that face's mean edge length",
                        attr=compat.PROP_OUTPUT, editor_mode=read_only)
    compat.add_property(obj, "App::PropertyFloatList", "FacePlanarity", "Planarity",
                        "Per face: largest distance of its vertices from its best-fit plane, mm",
                        attr=compat.PROP_OUTPUT, editor_mode=hidden)


# --- between document objects and facet.PolyMesh --------------------------------------------


def is_polymesh(obj):
    """True if ``obj`` is a Facet polygon mesh object (PolyMesh, Planarized, ...)."""
    proxy = getattr(obj, "Proxy", None)
    return (str(getattr(proxy, "Type", "")).startswith("Facet::")
            and all(hasattr(obj, name) for name in MESH_PROPERTIES))


def get_mesh(obj):
    """The ``facet.PolyMesh`` stored in a Facet polygon mesh object (a new copy)."""
    points = obj.Points
    xyz = np.array([(p.x, p.y, p.z) for p in points], dtype=np.float64).reshape(-1, 3)
    face_start = np.array(obj.FaceStart, dtype=np.int32)
    face_vertices = np.array(obj.FaceVertices, dtype=np.int32)
    if face_start.size == 0:
        raise ValueError(f"{obj.Label} holds no mesh")
    return facet.PolyMesh(xyz, face_start, face_vertices)


def set_mesh(obj, mesh):
    """Store ``mesh`` (a facet.PolyMesh) in ``obj``, bit for bit.

    Topology first, coordinates last: the view provider redraws once all three agree.
    """
    obj.FaceVertices = np.asarray(mesh.face_vertices).tolist()
    obj.FaceStart = np.asarray(mesh.face_start).tolist()
    obj.Points = [tuple(row) for row in np.asarray(mesh.vertices, dtype=np.float64).tolist()]
    obj.VertexCount = int(mesh.n_vertices)
    obj.FaceCount = int(mesh.n_faces)


def set_planarity(obj, report):
    """Store a ``facet.PlanarityReport`` in the object's Planarity group."""
    obj.PlanarityMaxAbs = float(report.max_abs_all)
    obj.PlanarityMaxRel = float(report.max_rel_all)
    obj.FacePlanarity = np.asarray(report.max_abs, dtype=np.float64).tolist()


def mesh_arrays(obj):
    """``(xyz, face_start, face_vertices)`` numpy arrays of ``obj``'s mesh, or None.

    None unless the three mesh properties agree (sizes and index ranges); they are set one
    after the other, so a view provider sees inconsistent states in between.
    """
    try:
        xyz = np.array([(p.x, p.y, p.z) for p in obj.Points], dtype=np.float64).reshape(-1, 3)
        face_start = np.array(obj.FaceStart, dtype=np.int64)
        face_vertices = np.array(obj.FaceVertices, dtype=np.int64)
    except (AttributeError, ValueError):
        return None
    if face_start.size < 2 or xyz.shape[0] == 0:
        return None
    if face_start[0] != 0 or face_start[-1] != face_vertices.size:
        return None
    if np.any(np.diff(face_start) < 1):
        return None
    if face_vertices.size and (face_vertices.min() < 0 or face_vertices.max() >= xyz.shape[0]):
        return None
    return xyz, face_start, face_vertices

