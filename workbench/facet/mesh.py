# SPDX-License-Identifier: LGPL-2.1-or-later
"""The polygon mesh of a facade: vertices and panels (faces) of any degree.

A :class:`PolyMesh` keeps its faces in compressed rows (CSR), the form the
compiled core reads without copying: face ``j`` has the vertices
``face_vertices[face_start[j]:face_start[j + 1]]`` in order around the panel.
Triangles, quads and hexagons live side by side.

The arrays of a mesh are read-only. A planarized or edited mesh is a new
``PolyMesh`` made by :meth:`PolyMesh.with_vertices`, which shares the topology
arrays of the original.
"""

import numpy as np

from facet.errors import MeshError, from_core

__all__ = ["PolyMesh", "cluster_points", "coincident_vertices", "coincident_text",
           "unwelded_warning", "WELD_ADVICE",
           "duplicate_faces", "opposite_windings", "weld"]

_INT32_MAX = np.iinfo(np.int32).max


def _read_only(array):
    array.flags.writeable = False
    return array


def _as_vertex_array(vertices):
    """Copy `vertices` into a read-only C-contiguous (n, 3) float64 array."""
    try:
        array = np.array(vertices, dtype=np.float64, order="C", copy=True)
    except (TypeError, ValueError) as exc:
        raise MeshError(f"vertices cannot be read as numbers ({exc})") from None
    if array.ndim == 1 and array.size == 0:
        array = array.reshape(0, 3)
    if array.ndim != 2 or array.shape[1] != 3:
        raise MeshError(f"vertices must be an (n, 3) array, got shape {array.shape}")
    return _read_only(array)


def _as_index_array(values, name):
    """Copy `values` into a read-only C-contiguous 1-D int32 array."""
    try:
        array = np.asarray(values)
    except (TypeError, ValueError) as exc:
        raise MeshError(f"{name} cannot be read as integers ({exc})") from None
    if array.ndim != 1:
        raise MeshError(f"{name} must be a 1-D array, got shape {array.shape}")
    if array.size == 0:
        return _read_only(np.zeros(0, dtype=np.int32))
    if array.dtype.kind not in "iu":
        raise MeshError(f"{name} must hold integers, got {array.dtype}")
    low, high = int(array.min()), int(array.max())
    if low < -_INT32_MAX - 1 or high > _INT32_MAX:
        raise MeshError(f"{name} holds values beyond the 32-bit range ({low} .. {high})")
    return _read_only(np.array(array, dtype=np.int32, order="C", copy=True))


class PolyMesh:
    """A polygon mesh: the panels of a facade and the points they share.

    Parameters
    ----------
    vertices : array_like, shape (n, 3)
        Vertex coordinates, model units. Copied to float64.
    face_start : array_like of int, shape (F + 1,)
        Offsets of each face in `face_vertices`; starts at 0, never decreases
        and ends at ``len(face_vertices)``.
    face_vertices : array_like of int, shape (C,)
        Vertex indices of all faces one after the other, each face in order
        around its boundary.
    info : dict, optional
        Facts about where the mesh came from (``source``, ``format``,
        openings skipped, compas keys...), filled by the readers in
        :mod:`facet.io`. Carried over by :meth:`with_vertices` and
        :meth:`copy`.

    Raises
    ------
    MeshError
        When the arrays do not have the shapes above. The constructor checks
        only structure; :meth:`validate` checks indices, repeated vertices,
        degenerate faces and non-finite coordinates.

    Examples
    --------
    >>> mesh = PolyMesh.from_faces([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
    ...                            [[0, 1, 2, 3]])
    >>> mesh.n_faces, mesh.degrees.tolist()
    (1, [4])
    """

    def __init__(self, vertices, face_start, face_vertices, *, info=None):
        vertices = _as_vertex_array(vertices)
        face_start = _as_index_array(face_start, "face_start")
        face_vertices = _as_index_array(face_vertices, "face_vertices")
        if face_start.size == 0:
            raise MeshError("face_start must hold at least one offset (0)")
        if face_start[0] != 0:
            raise MeshError(f"face_start must start at 0, got {int(face_start[0])}")
        steps = np.diff(face_start)
        if steps.size and steps.min() < 0:
            face = int(np.argmax(steps < 0))
            raise MeshError(
                f"face_start decreases at face {face} "
                f"({int(face_start[face])} then {int(face_start[face + 1])})",
                face=face,
            )
        if face_start[-1] != face_vertices.size:
            raise MeshError(
                f"face_start ends at {int(face_start[-1])} but face_vertices holds "
                f"{face_vertices.size} indices"
            )
        self._set(vertices, face_start, face_vertices, info)

    def _set(self, vertices, face_start, face_vertices, info):
        self._vertices = vertices
        self._face_start = face_start
        self._face_vertices = face_vertices
        self._info = dict(info) if info else {}
        self._edges = None

    @classmethod
    def _trusted(cls, vertices, face_start, face_vertices, info):
        """Make a mesh from arrays already checked and read-only."""
        mesh = cls.__new__(cls)
        mesh._set(vertices, face_start, face_vertices, info)
        return mesh

    @classmethod
    def from_faces(cls, vertices, faces, *, info=None):
        """Make a mesh from a list of faces.

        Parameters
        ----------
        vertices : array_like, shape (n, 3)
            Vertex coordinates.
        faces : iterable of sequences of int
            Vertex indices of each face, in order around it.
        info : dict, optional
            As for the constructor.

        Returns
        -------
        PolyMesh
        """
        faces = [list(face) for face in faces]
        degrees = np.fromiter((len(face) for face in faces), dtype=np.int64, count=len(faces))
        face_start = np.zeros(len(faces) + 1, dtype=np.int64)
        np.cumsum(degrees, out=face_start[1:])
        flat = [index for face in faces for index in face]
        face_vertices = np.array(flat) if flat else np.zeros(0, dtype=np.int32)
        return cls(vertices, face_start, face_vertices, info=info)

    # ------------------------------------------------------------------ arrays

    @property
    def vertices(self):
        """ndarray, shape (n, 3): vertex coordinates (read-only float64)."""
        return self._vertices

    @property
    def face_start(self):
        """ndarray, shape (F + 1,): offsets of the faces (read-only int32)."""
        return self._face_start

    @property
    def face_vertices(self):
        """ndarray, shape (C,): vertex indices of all faces (read-only int32)."""
        return self._face_vertices

    @property
    def info(self):
        """dict: facts about where the mesh came from (see the constructor)."""
        return self._info

    @property
    def n_vertices(self):
        """int: number of vertices."""
        return int(self._vertices.shape[0])

    @property
    def n_faces(self):
        """int: number of faces (panels)."""
        return int(self._face_start.size - 1)

    @property
    def degrees(self):
        """ndarray of int32, shape (F,): number of vertices of each face."""
        return np.diff(self._face_start)

    def faces(self):
        """Vertex indices of every face.

        Returns
        -------
        list of list of int
        """
        flat = self._face_vertices.tolist()
        starts = self._face_start.tolist()
        return [flat[a:b] for a, b in zip(starts[:-1], starts[1:])]

    def face(self, j):
        """Vertex indices of face `j`.

        Parameters
        ----------
        j : int
            Face index; negative counts from the end.

        Returns
        -------
        list of int

        Raises
        ------
        IndexError
            When there is no face `j`.
        """
        n = self.n_faces
        j = int(j)
        if j < 0:
            j += n
        if not 0 <= j < n:
            raise IndexError(f"face {j} does not exist ({n} faces)")
        return self._face_vertices[self._face_start[j] : self._face_start[j + 1]].tolist()

    def edges(self):
        """Distinct undirected edges.

        Returns
        -------
        ndarray of int32, shape (E, 2)
            Each edge once, as (smaller index, larger index), sorted. Read-only.
        """
        if self._edges is None:
            self._edges = _read_only(_unique_edges(self._face_start, self._face_vertices))
        return self._edges

    def mean_edge_length(self):
        """Mean length of the distinct edges, model units.

        Returns
        -------
        float

        Raises
        ------
        MeshError
            When the mesh has no edge.
        """
        edges = self.edges()
        if edges.shape[0] == 0:
            raise MeshError("mesh has no edges", source=self._info.get("source"))
        vectors = self._vertices[edges[:, 1]] - self._vertices[edges[:, 0]]
        return float(np.sqrt(np.einsum("ij,ij->i", vectors, vectors)).mean())

    def bounds(self):
        """Axis-aligned bounding box.

        Returns
        -------
        lower, upper : ndarray, shape (3,)
            Smallest and largest coordinates.

        Raises
        ------
        MeshError
            When the mesh has no vertex.
        """
        if self.n_vertices == 0:
            raise MeshError("mesh has no vertices", source=self._info.get("source"))
        return self._vertices.min(axis=0), self._vertices.max(axis=0)

    # ------------------------------------------------------------ new meshes

    def copy(self):
        """Return an independent copy (arrays copied, info copied)."""
        return PolyMesh._trusted(
            _read_only(self._vertices.copy()),
            _read_only(self._face_start.copy()),
            _read_only(self._face_vertices.copy()),
            self._info,
        )

    def with_vertices(self, xyz):
        """Return a mesh with the same panels and new vertex positions.

        Parameters
        ----------
        xyz : array_like, shape (n, 3)
            New coordinates, one row per vertex of this mesh. Copied.

        Returns
        -------
        PolyMesh
            Shares this mesh's (read-only) topology arrays.
        """
        vertices = _as_vertex_array(xyz)
        if vertices.shape != self._vertices.shape:
            raise MeshError(
                f"new vertices have shape {vertices.shape}, the mesh needs "
                f"{self._vertices.shape}"
            )
        mesh = PolyMesh._trusted(vertices, self._face_start, self._face_vertices, self._info)
        mesh._edges = self._edges
        return mesh

    def same_topology(self, other):
        """Whether `other` has the same vertex count and the same faces.

        Parameters
        ----------
        other : PolyMesh

        Returns
        -------
        bool
        """
        if self._face_vertices is other._face_vertices and self._face_start is other._face_start:
            return self.n_vertices == other.n_vertices
        return (
            self.n_vertices == other.n_vertices
            and np.array_equal(self._face_start, other._face_start)
            and np.array_equal(self._face_vertices, other._face_vertices)
        )

    # ------------------------------------------------------------ validation

    def validate(self):
        """Check the mesh fully with the compiled core.

        Returns
        -------
        dict
            ``n_edges``, ``n_boundary_edges``, ``n_non_manifold_edges``,
            ``n_isolated_vertices``, ``first_non_manifold_edge`` (pair or
            None), ``first_isolated_vertex`` (int or None), ``max_degree``:
            facts worth telling the designer that do not stop the work.

        Raises
        ------
        MeshError
            No vertex or no face, bad face offsets, a non-finite coordinate,
            an index out of range, a vertex repeated in a face or a face with
            fewer than 3 distinct vertices. The message names the face or
            vertex (``"face 17 repeats vertex 4"``).
        """
        from facet import _core

        try:
            return _core.validate(
                self._vertices.reshape(-1), self._face_start, self._face_vertices
            )
        except _core.CoreError as exc:
            raise from_core(exc, source=self._info.get("source")) from None

    def __repr__(self):
        return f"<PolyMesh: {self.n_vertices} vertices, {self.n_faces} faces>"


def cluster_points(points, tolerance):
    """Cluster points closer than tolerance (single linkage); each point's representative
    is the lowest index of its cluster."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    n = len(points)
    pairs = cKDTree(points).query_pairs(tolerance, output_type="ndarray")
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, labels = connected_components(graph, directed=False)
    lowest = np.full(labels.max() + 1 if n else 0, n)
    np.minimum.at(lowest, labels, np.arange(n))
    return lowest[labels]


def _used_extent(mesh):
    """(the vertices faces use, the largest extent of those vertices), the scale of the
    relative tolerances of :func:`coincident_vertices` and :func:`weld`; None with fewer
    than two such vertices or one not finite."""
    used = np.unique(np.asarray(mesh.face_vertices))
    if used.size < 2:
        return None
    points = np.asarray(mesh.vertices, dtype=np.float64)[used]
    if not np.isfinite(points).all():
        return None
    return used, float(np.ptp(points, axis=0).max())


def _near_pairs(mesh, rel_tol):
    """Pairs (k, 2) of vertices that faces use and that lie within ``rel_tol`` times the
    largest extent of those vertices of each other; none where a coordinate is not finite."""
    none = np.zeros((0, 2), dtype=np.int64)
    extent = _used_extent(mesh)
    if extent is None:
        return none
    used, size = extent
    from scipy.spatial import cKDTree

    points = np.asarray(mesh.vertices, dtype=np.float64)[used]
    pairs = cKDTree(points).query_pairs(rel_tol * size, output_type="ndarray")
    return used[pairs].astype(np.int64) if pairs.shape[0] else none


#: How a warning of vertices at one point ends: what joins them, from either front end.
WELD_ADVICE = ("weld them where the panels should meet: facet weld, or in FreeCAD Collapse "
               "short edges, which welds first")


def coincident_vertices(mesh, rel_tol=1e-9):
    """Vertices that faces use and that lie where another such vertex lies: the copies an
    export that gives each face (or each part) its own vertices leaves along a seam that
    looks joined but is not. The faces there are solved apart, and the seam opens. The two
    ends of an edge of no length are joined by it, and not counted.

    Parameters
    ----------
    mesh : PolyMesh
    rel_tol : float
        Two vertices coincide when they are this close, times the mesh's largest extent.

    Returns
    -------
    (int, tuple or None)
        The number of coincident pairs and the first pair (lower index first), or
        ``(0, None)``.
    """
    pairs = _near_pairs(mesh, rel_tol)
    if pairs.shape[0] == 0:
        return 0, None
    pairs = np.sort(pairs, axis=1)
    # two ends of one edge are joined (an edge of no length: the quality report's
    # degenerate faces), not a seam
    edges = mesh.edges().astype(np.int64)
    base = int(mesh.n_vertices)
    pairs = pairs[~np.isin(pairs[:, 0] * base + pairs[:, 1], edges[:, 0] * base + edges[:, 1])]
    if pairs.shape[0] == 0:
        return 0, None
    first = pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))[0]]
    return int(pairs.shape[0]), (int(first[0]), int(first[1]))


def weld(mesh, rel_tol=1e-9):
    """The mesh with one vertex for each group of vertices within ``rel_tol`` times its
    largest extent of each other (the seams :func:`coincident_vertices` warns of, joined);
    a corner that then repeats the one before it is dropped. Each group keeps its first
    vertex, where it is, and the others go; a vertex no face uses stays. The faces keep
    their order, so the info about them (OBJ groups, compas face keys) still holds; compas
    vertex keys and support vertices follow the vertices kept (:func:`remapped_info`, as
    :func:`facet.cleanup` does).

    Parameters
    ----------
    mesh : PolyMesh
        Not modified.
    rel_tol : float
        As in :func:`coincident_vertices`.

    Returns
    -------
    (PolyMesh, int)
        The welded mesh and the number of vertices merged into another.

    Raises
    ------
    MeshError
        A face left with fewer than three corners apart, or with one vertex at two corners
        apart (pinched at a point), named.
    """
    info = dict(mesh.info or {})
    points = np.asarray(mesh.vertices, dtype=np.float64)
    n = mesh.n_vertices
    group = np.arange(n)
    extent = _used_extent(mesh)  # (as coincident_vertices finds them)
    if extent is not None:
        used, size = extent
        group[used] = used[cluster_points(points[used], rel_tol * size)]
        # a chain of points each within the tolerance of the next would be one vertex
        # however long (the plan reader refuses such chains too): joined, its ends would
        # move by more than the tolerance asked for
        spread = np.linalg.norm(points - points[group], axis=1)
        if spread.max() > 2.0 * rel_tol * size:
            v = int(np.argmax(spread))
            from facet.report import point_text

            raise MeshError(f"the vertices within {rel_tol:g} of the mesh's size of each other "
                            f"form a chain {spread[v]:.3g} long, from vertex {int(group[v])} to "
                            f"vertex {v} at {point_text(points[v])}: joined, they would move "
                            "by more than that; give a smaller tolerance", vertex=v,
                            source=info.get("source"))
    merged = int(np.count_nonzero(group != np.arange(n)))  # (only used vertices join)
    faces = []
    for f, face in enumerate(mesh.faces()):
        corners = [int(group[v]) for v in face]
        corners = [c for k, c in enumerate(corners) if c != corners[k - 1]]
        if len(corners) < 3:
            raise MeshError(f"face {f} has fewer than 3 corners apart once its vertices "
                            f"within {rel_tol:g} of the mesh's size are one", face=f,
                            source=info.get("source"))
        if len(set(corners)) < len(corners):
            # (a face pinched at a point: the readers refuse it, so a file written so
            # could not be read back)
            raise MeshError(f"face {f} has one vertex at two corners apart once its "
                            f"vertices within {rel_tol:g} of the mesh's size are one",
                            face=f, source=info.get("source"))
        faces.append(corners)
    kept = np.flatnonzero(group == np.arange(n))
    index = np.full(n, -1)
    index[kept] = np.arange(kept.size)
    info = remapped_info(info, index[group], np.arange(mesh.n_faces), mesh.n_faces,
                         kept.size)
    welded = PolyMesh.from_faces(points[kept], [index[face].tolist() for face in faces],
                                 info=info)
    return welded, merged


def remapped_info(info, vertex_map, face_map, n_faces, n_vertices):
    """A reader's per-vertex and per-face lists (the compas reader's ``vertex_keys``,
    ``face_keys`` and ``support_vertices``, the OBJ reader's ``obj_sections``) for the new
    topology, so that results written back by key land on the right elements: a face keeps
    its key (and its group); a vertex takes the key of the first input vertex merged into
    it (``merged_vertex_keys`` lists the others)."""
    if isinstance(info.get("face_keys"), list) and len(info["face_keys"]) == n_faces:
        keys = info["face_keys"]
        info["face_keys"] = [keys[f] for f in face_map.tolist()]
    if info.get("obj_sections") and info.get("obj_faces") == n_faces:
        # the OBJ reader's groups and materials: each before the first face kept after it
        info["obj_sections"] = tuple((int(np.searchsorted(face_map, at)), statement)
                                     for at, statement in info["obj_sections"])
        info["obj_faces"] = len(face_map)
    if isinstance(info.get("vertex_keys"), list) and len(info["vertex_keys"]) == len(vertex_map):
        keys, first, merged = info["vertex_keys"], [None] * n_vertices, {}
        for old, new in enumerate(vertex_map.tolist()):
            if new < 0:
                continue
            if first[new] is None:
                first[new] = keys[old]
            else:
                merged.setdefault(first[new], []).append(keys[old])
        info["vertex_keys"] = first
        if merged:
            info["merged_vertex_keys"] = merged
    if isinstance(info.get("support_vertices"), list):
        info["support_vertices"] = sorted({int(vertex_map[v]) for v in info["support_vertices"]
                                           if 0 <= v < len(vertex_map) and vertex_map[v] >= 0})
    return info


def coincident_text(mesh):
    """What :func:`coincident_vertices` finds, as the start of a warning ("vertices at one
    point but not one vertex: 2 pairs (vertices 1 and 6 at (1, 0, 0))"), for the caller to
    end with what it means there; None when there are none."""
    from facet.report import count_noun, point_text

    n_pairs, first = coincident_vertices(mesh)
    if not n_pairs:
        return None
    i, j = first
    return (f"vertices at one point but not one vertex: {count_noun(n_pairs, 'pair')} "
            f"(vertices {i} and {j} at {point_text(mesh.vertices[i])})")


def unwelded_warning(mesh, consequence):
    """The warning of an unwelded seam: :func:`coincident_text`, then ``consequence`` (what
    that means where it is said: "the faces there are not joined"), then
    :data:`WELD_ADVICE`; None when there is none."""
    seam = coincident_text(mesh)
    return None if seam is None else f"{seam}; {consequence}: {WELD_ADVICE}"


def duplicate_faces(mesh):
    """Faces with the same vertices as an earlier face (in any order or turn): two panels
    at one place, as a Rhino join of overlapping meshes or a double-sided export leaves.
    Each edge of such a face is then shared by more than two faces.

    Parameters
    ----------
    mesh : PolyMesh

    Returns
    -------
    (int, tuple or None)
        The number of faces that repeat an earlier one, and the first such pair (the
        earlier face, the copy), or ``(0, None)``.
    """
    degrees = np.asarray(mesh.degrees)
    starts = np.asarray(mesh.face_start)[:-1]
    corners = np.asarray(mesh.face_vertices)
    count, first = 0, None
    for degree in np.unique(degrees).tolist():
        faces = np.flatnonzero(degrees == degree)
        if faces.size < 2:
            continue
        rows = np.sort(corners[starts[faces][:, None] + np.arange(degree)], axis=1)
        _, index, inverse = np.unique(rows, axis=0, return_index=True, return_inverse=True)
        inverse = inverse.reshape(-1)
        copies = np.flatnonzero(index[inverse] != np.arange(faces.size))
        if copies.size:
            count += int(copies.size)
            pair = (int(faces[index[inverse[copies[0]]]]), int(faces[copies[0]]))
            first = pair if first is None or pair[1] < first[1] else first
    return count, first


def opposite_windings(mesh):
    """Edges between two faces wound opposite ways: both go along the edge in the same
    direction, so their normals (counter-clockwise, by the right hand) point to opposite
    sides of the surface. A mesh joined from pieces drawn apart often has them; FreeCAD
    shades the turned faces dark, and a panel's outer side follows its normal
    (``facet.panels`` turns such faces to their neighbours' side, with a warning).

    Parameters
    ----------
    mesh : PolyMesh

    Returns
    -------
    (int, tuple or None)
        The number of such edges (of those shared by exactly two faces), and the faces
        of the first one (lower face first), or ``(0, None)``.
    """
    if mesh.n_faces == 0:
        return 0, None
    a, b, keys, _ = _edge_keys(mesh.face_start, mesh.face_vertices)
    face = np.repeat(np.arange(mesh.n_faces), np.diff(np.asarray(mesh.face_start)))
    _, inverse, counts = np.unique(keys, return_inverse=True, return_counts=True)
    shared = np.flatnonzero(counts[inverse] == 2)
    order = shared[np.argsort(inverse[shared], kind="stable")]
    first, second = order[0::2], order[1::2]  # the two corners of each edge used twice
    same = (a[first] == a[second]) & (a[first] != b[first])
    if not same.any():
        return 0, None
    pairs = np.sort(np.column_stack([face[first[same]], face[second[same]]]), axis=1)
    pair = pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))[0]]
    return int(same.sum()), (int(pair[0]), int(pair[1]))


def boundary_corners(face_start, face_vertices):
    """For each face corner k, whether the edge from it to the next corner of its face
    belongs to that face alone (a boundary edge, or an edge the faces beside it do not
    share): bool, size face_start[-1]."""
    if np.asarray(face_vertices).size == 0:
        return np.zeros(0, dtype=bool)
    _, inverse, counts = np.unique(_edge_keys(face_start, face_vertices)[2],
                                   return_inverse=True, return_counts=True)
    return counts[inverse] == 1


def _edge_keys(face_start, face_vertices):
    """For each face corner k, the edge from it to the next corner of its face: its two
    vertices (int64 arrays a and b) and one number for the undirected edge, the same
    for (a, b) and (b, a): ``min * base + max`` with ``base`` (returned last) above every
    vertex index. Indices must not be negative."""
    a = np.asarray(face_vertices, dtype=np.int64)
    b = a[next_corners(np.asarray(face_start))]
    base = int(a.max()) + 1 if a.size else 1
    return a, b, np.minimum(a, b) * base + np.maximum(a, b), base


def next_corners(face_start):
    """For each face corner k (an index into face_vertices), the index of the next corner
    of its face: k + 1, and a face's last corner back to its first (int64, size
    face_start[-1])."""
    following = np.arange(1, int(face_start[-1]) + 1, dtype=np.int64)
    starts, ends = face_start[:-1], face_start[1:]
    nonempty = ends > starts
    following[ends[nonempty] - 1] = starts[nonempty]
    return following


def _unique_edges(face_start, face_vertices):
    """Distinct undirected edges of a CSR face list, as a sorted (E, 2) int32 array."""
    if face_vertices.size == 0:
        return np.zeros((0, 2), dtype=np.int32)
    if face_vertices.min() < 0:
        raise MeshError("face_vertices holds a negative index (call validate() first)")
    a, b, keys, base = _edge_keys(face_start, face_vertices)
    keys = np.unique(keys[a != b])
    return np.stack([keys // base, keys % base], axis=1).astype(np.int32)
