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
        if prop in MESH_PROPERTIES:
            # any change of the mesh (set_mesh, a script, undo, redo, a restore): the arrays
            # kept for it are those set_mesh is storing, or none
            self.stored_arrays = getattr(self, "storing_arrays", None)

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
    xyz, face_start, face_vertices = stored_arrays(obj)
    if face_start.size == 0:
        raise ValueError(f"{obj.Label} holds no mesh")
    return facet.PolyMesh(xyz, face_start, face_vertices)


def set_mesh(obj, mesh):
    """Store ``mesh`` (a facet.PolyMesh) in ``obj``, bit for bit.

    Topology first, coordinates last: the view provider redraws once, when the coordinates
    are stored (:func:`mesh_update_pending`). The object's proxy keeps the arrays stored
    (:func:`stored_arrays`), so that reading them back (its recompute, its drawing) does not
    convert the properties again.
    """
    arrays = (_frozen(mesh.vertices, np.float64).reshape(-1, 3),
              _frozen(mesh.face_start, np.int32), _frozen(mesh.face_vertices, np.int32))
    xyz, face_start, face_vertices = arrays
    proxy = _keeper(obj)
    kept = getattr(proxy, "stored_arrays", None)
    # a re-solve moves the vertices only: the 4M indices of a 1M-quad mesh, unchanged, are
    # not stored again (0.2 s); the kept arrays are those of the properties (onChanged)
    same_topology = kept is not None and np.array_equal(kept[1], face_start) \
        and np.array_equal(kept[2], face_vertices)
    previous = getattr(proxy, "storing_arrays", None)  # (None unless set_mesh nests)
    if proxy is not None:
        proxy.storing_arrays = arrays
    stored = False
    try:
        if not same_topology:
            obj.FaceVertices = face_vertices.tolist()
            obj.FaceStart = face_start.tolist()
        set_points(obj, xyz)
        stored = True
    finally:
        if proxy is not None:
            proxy.storing_arrays = previous
            if not stored:  # the properties may be part old, part new: read them again
                proxy.stored_arrays = None
    obj.VertexCount = int(mesh.n_vertices)
    obj.FaceCount = int(mesh.n_faces)


def mesh_update_pending(obj, prop):
    """True while :func:`set_mesh` stores ``obj``'s mesh and ``prop`` is not the last of
    its properties it stores (a view provider redraws once, then)."""
    proxy = _keeper(obj)
    return (proxy is not None and getattr(proxy, "storing_arrays", None) is not None
            and prop != "Points")


def stored_arrays(obj):
    """``(xyz, face_start, face_vertices)``: read-only float64 (n, 3), int32 and int32
    arrays of the mesh properties of ``obj``, bit for bit.

    Kept by the object's proxy until one of the properties changes (its ``onChanged``: set
    by anything, undo and redo included); a PolyMesh recompute and the view provider's
    drawing read them from there instead of converting a million App.Vector again.
    """
    proxy = _keeper(obj)
    if proxy is not None:
        kept = getattr(proxy, "storing_arrays", None) or getattr(proxy, "stored_arrays", None)
        if kept is not None:
            return kept
    arrays = (points_array(obj), _indices(obj, "FaceStart"), _indices(obj, "FaceVertices"))
    if proxy is not None:
        proxy.stored_arrays = arrays
    return arrays


def _keeper(obj):
    """The proxy of ``obj`` that keeps its arrays (a PolyMesh), or None."""
    proxy = getattr(obj, "Proxy", None)
    return proxy if isinstance(proxy, PolyMesh) else None


def _indices(obj, name):
    """The integer list property ``name`` as a read-only int32 array; a ValueError naming it
    when a value is beyond 32 bits (set by a script: it would wrap around)."""
    values = np.asarray(getattr(obj, name), dtype=np.int64)
    if values.size and (values.min() < np.iinfo(np.int32).min
                        or values.max() > np.iinfo(np.int32).max):
        raise ValueError(f"{obj.Label}: {name} holds values beyond the 32-bit range "
                         f"({int(values.min())} .. {int(values.max())})")
    return _frozen(values, np.int32)


def _frozen(values, dtype):
    """``values`` as a read-only C-contiguous array of ``dtype`` (no copy if it is one)."""
    array = np.asarray(values, dtype=dtype)
    if array.flags.writeable or not array.flags.c_contiguous:
        array = np.array(array, dtype=dtype, order="C", copy=True)
        array.flags.writeable = False
    return array


# --- Points in bulk ----------------------------------------------------------------------------
#
# App::PropertyVectorList takes and gives App.Vector objects one by one: 1M vertices took
# 1 s to store and 0.7 s to read back. Its content (``dumpPropertyContent``,
# ``restorePropertyContent``) is what FreeCAD saves in a .FCStd: a zip of an XML element
# naming a file, and that file: the count (uint32) then x, y, z of every vector (float64, in
# the machine's byte order; older formats: float32). Read and written that way it takes a few
# hundredths of a second. Each bulk write is read back and compared bit for bit; should a
# FreeCAD version write or read anything else, the Vector path is used from then on.

_bulk_points = {"write": True}


def points_array(obj):
    """``obj.Points`` as a read-only (n, 3) float64 array, bit for bit."""
    xyz = _dumped_points(obj)
    if xyz is None:
        xyz = np.array([(p.x, p.y, p.z) for p in obj.Points], dtype=np.float64).reshape(-1, 3)
        xyz.flags.writeable = False
    return xyz


def set_points(obj, xyz):
    """Store ``xyz`` ((n, 3) float64) in ``obj.Points``, bit for bit."""
    xyz = np.ascontiguousarray(xyz, dtype=np.float64).reshape(-1, 3)
    if _bulk_points["write"]:
        import FreeCAD as App

        # FreeCAD's reader shows its progress ("Importing project files"): in the GUI its
        # progress bar ran the event loop, and a pending live re-solve of this very object
        # ran inside this store. A progress already running (this one, or a recompute's)
        # makes the reader's a silent no-op.
        indicator = App.Base.ProgressIndicator()
        try:
            indicator.start("", 0)
            try:
                obj.restorePropertyContent("Points", _points_content(xyz))
            finally:
                indicator.stop()
            back = _dumped_points(obj)
            if back is not None and back.shape == xyz.shape and np.array_equal(
                    back.view(np.uint64), xyz.view(np.uint64)):
                return
        except Exception:  # noqa: BLE001 - any failure: the Vector path below, from now on
            pass
        _bulk_points["write"] = False
    obj.Points = list(zip(*(xyz[:, k].tolist() for k in range(3))))


def _points_content(xyz):
    import io
    import zipfile

    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_STORED) as archive:
        archive.writestr("Persistence.xml", '<Content>\n<VectorList file="Points"/>\n</Content>')
        archive.writestr("Points", np.array([xyz.shape[0]], dtype=np.uint32).tobytes()
                         + xyz.astype(np.float64).tobytes())
    return buffer.getvalue()


def _dumped_points(obj):
    """``obj.Points`` read from the property's content, or None when it is not the format
    above."""
    import io
    import re
    import zipfile

    try:
        content = bytes(obj.dumpPropertyContent("Points", Compression=0))
        archive = zipfile.ZipFile(io.BytesIO(content))
        names = re.findall(r'<VectorList\s+file="([^"]+)"',
                           archive.read("Persistence.xml").decode("utf-8", "replace"))
        if len(names) != 1:
            return None
        raw = archive.read(names[0])
    except Exception:  # noqa: BLE001 - no such method, another format: the Vector path
        return None
    if len(raw) < 4:
        return None
    count = int(np.frombuffer(raw, dtype=np.uint32, count=1)[0])
    if len(raw) != 4 + 24 * count:
        return None
    return np.frombuffer(raw, dtype=np.float64, offset=4).reshape(count, 3)


def set_planarity(obj, report):
    """Store a ``facet.PlanarityReport`` in the object's Planarity group."""
    obj.PlanarityMaxAbs = float(report.max_abs_all)
    obj.PlanarityMaxRel = float(report.max_rel_all)
    obj.FacePlanarity = np.asarray(report.max_abs, dtype=np.float64).tolist()


def mesh_arrays(obj):
    """``(xyz, face_start, face_vertices)`` arrays of ``obj``'s mesh (:func:`stored_arrays`,
    read-only), or None.

    None unless the three mesh properties agree (sizes and index ranges); they are set one
    after the other, so a view provider sees inconsistent states in between.
    """
    try:
        xyz, face_start, face_vertices = stored_arrays(obj)
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
