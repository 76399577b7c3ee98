# SPDX-License-Identifier: LGPL-2.1-or-later
"""Checks every reader makes once a file is parsed.

The readers collect vertices and faces together with the line each came
from; :func:`build_mesh` turns them into a :class:`~facet.mesh.PolyMesh`,
refusing non-finite coordinates and indices out of range with the line of the
offending record, and then runs the full validation of the compiled core,
adding the line (or the compas key) of the face it names.

A face that gives one vertex at two corners in a row ("f 2 3 5 5", Rhino's way of
writing a triangle in a quad, or "f 5 2 3 5" round the end) is read with that vertex
once, when three or more corners remain; the mesh's info counts these faces
(``repeated_corners_merged``) and says where the first is (``repeated_corners_first``),
and :func:`read_warnings` says so. A vertex repeated at corners apart ("f 2 5 3 5")
stays an error: no reading of it is a panel.
"""

import numpy as np

from facet.errors import MeshError
from facet.mesh import PolyMesh

__all__ = ["build_mesh", "read_warnings"]


def _face_of_corner(face_start, corner):
    return int(np.searchsorted(face_start, corner, side="right") - 1)


def _merge_repeated_corners(face_start, face_vertices):
    """Drop a corner whose vertex the next corner repeats (cyclically: the face's first corner
    is kept), in each face left with three corners or more. Returns the new face_start and
    face_vertices and the indices of the faces changed."""
    degrees = np.diff(face_start)
    if face_vertices.size == 0 or (degrees < 1).any():
        return face_start, face_vertices, np.zeros(0, dtype=np.int64)
    corner = np.arange(face_vertices.size)
    face = np.repeat(np.arange(degrees.size), degrees)
    following = np.where(corner == face_start[face + 1] - 1, face_start[face], corner + 1)
    repeat = face_vertices == face_vertices[following]
    if not repeat.any():
        return face_start, face_vertices, np.zeros(0, dtype=np.int64)
    dropped = np.bincount(face[repeat], minlength=degrees.size)
    # a face with fewer than three distinct corners in a row stays as written: the
    # validation names it as the degenerate face it is
    merged = (dropped > 0) & (degrees - dropped >= 3)
    repeat &= merged[face]
    kept = face_vertices[~repeat]
    new_degrees = degrees - np.where(merged, dropped, 0)
    new_start = np.concatenate(([0], np.cumsum(new_degrees))).astype(np.int64)
    return new_start, kept, np.flatnonzero(merged)


def _where(face, face_lines, face_names):
    """Where face `face` is in its file, for a message: its line, its key, or its index."""
    if face_names is not None and face < len(face_names):
        return f"face key {face_names[face]!r}"
    if face_lines is not None and face < len(face_lines):
        return f"face {face}, line {face_lines[face]}"
    return f"face {face}"


def read_warnings(mesh):
    """What a reader changed in reading `mesh` (faces with a vertex at two corners in a row,
    read with it once), as sentences for the user; [] for a mesh read as written."""
    info = getattr(mesh, "info", None) or {}
    merged = info.get("repeated_corners_merged")
    if not merged:
        return []
    from facet.report import count_noun

    return [f"{count_noun(merged, 'face')} gave a vertex at two corners in a row (first: "
            f"{info.get('repeated_corners_first')}): read with it once (a quad written so is "
            "a triangle)"]


def build_mesh(
    vertices,
    face_start,
    face_vertices,
    *,
    source,
    info,
    vertex_lines=None,
    face_lines=None,
    index_base=0,
    face_names=None,
    vertex_names=None,
    validate=True,
):
    """Make a checked mesh from parsed records.

    Parameters
    ----------
    vertices : array_like, shape (n, 3)
    face_start, face_vertices : array_like of int
        Faces in compressed rows (see :class:`~facet.mesh.PolyMesh`), indices
        already 0-based.
    source : str or os.PathLike
        File name for messages.
    info : dict
        Stored in the mesh (``source`` is added).
    vertex_lines, face_lines : sequence of int, optional
        Line of each vertex and face in the file.
    index_base : int
        Added to an index when it is quoted in a message, so that it reads as
        written in the file (1 for OBJ).
    face_names, vertex_names : sequence, optional
        Keys of faces and vertices in the file (compas JSON), quoted in
        messages instead of a line number.
    validate : bool
        Run :meth:`PolyMesh.validate` (the compiled core). Default True.

    Returns
    -------
    PolyMesh

    Raises
    ------
    MeshError
        No vertices, no faces, a non-finite coordinate, an index out of range
        or any error :meth:`PolyMesh.validate` finds, located in the file.
    """
    vertices = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
    face_start = np.asarray(face_start, dtype=np.int64)
    n_vertices = vertices.shape[0]
    try:
        face_vertices = np.asarray(face_vertices, dtype=np.int64)
    except OverflowError:  # an index beyond 64 bits, out of range whatever the mesh
        corner = next(c for c, index in enumerate(face_vertices) if abs(index) >= 2**63)
        raise _out_of_range(
            face_start, corner, face_vertices[corner] + index_base, n_vertices, source,
            face_lines, face_names,
        ) from None
    if face_start.size <= 1:
        raise MeshError("no faces", source=source)
    if n_vertices == 0:
        raise MeshError("no vertices", source=source)

    finite = np.isfinite(vertices).all(axis=1)
    if not finite.all():
        vertex = int(np.argmin(finite))
        raise MeshError(
            f"vertex {vertex} has a non-finite coordinate" + _named(vertex_names, vertex, "vertex"),
            source=source,
            line=None if vertex_lines is None else vertex_lines[vertex],
            vertex=vertex,
        )

    outside = (face_vertices < 0) | (face_vertices >= n_vertices)
    if outside.any():
        corner = int(np.argmax(outside))
        raise _out_of_range(
            face_start, corner, int(face_vertices[corner]) + index_base, n_vertices, source,
            face_lines, face_names,
        )

    face_start, face_vertices, merged = _merge_repeated_corners(face_start, face_vertices)
    info = dict(info)
    info["source"] = source
    if merged.size:
        info["repeated_corners_merged"] = int(merged.size)
        info["repeated_corners_first"] = _where(int(merged[0]), face_lines, face_names)
    mesh = PolyMesh(vertices, face_start, face_vertices, info=info)
    if validate:
        try:
            mesh.validate()
        except MeshError as error:
            raise _locate(
                error, source, face_lines, vertex_lines, face_names, vertex_names, index_base
            ) from None
    return mesh


def _out_of_range(face_start, corner, shown_index, n_vertices, source, face_lines, face_names):
    """The error for an index out of range at `corner` of the face list."""
    face = _face_of_corner(face_start, corner)
    return MeshError(
        f"face {face} has vertex index {shown_index} out of range ({n_vertices} vertices)"
        + _named(face_names, face, "face"),
        source=source,
        line=None if face_lines is None else face_lines[face],
        face=face,
    )


def _named(names, index, what):
    if names is None or index is None or not 0 <= index < len(names):
        return ""
    return f" ({what} key {names[index]!r} in the file)"


def _locate(error, source, face_lines, vertex_lines, face_names, vertex_names, index_base=0):
    """Add the file, line and file keys to an error of the core. Where the file counts its
    vertices from `index_base` (1 in OBJ), a vertex that a face's line repeats is quoted as
    that line writes it too: "face 5 repeats vertex 12" on the line "f 7 8 13 13" named a
    vertex the line does not show."""
    line = None
    keys = []
    if error.face is not None:
        if face_lines is not None and error.face < len(face_lines):
            line = face_lines[error.face]
        if face_names is not None and error.face < len(face_names):
            keys.append(f"face key {face_names[error.face]!r}")
    if error.vertex is not None:
        if line is None and vertex_lines is not None and error.vertex < len(vertex_lines):
            line = vertex_lines[error.vertex]
        if vertex_names is not None and error.vertex < len(vertex_names):
            keys.append(f"vertex key {vertex_names[error.vertex]!r}")
    message = error.message
    if (index_base and error.vertex is not None and error.face is not None and not keys
            and error.status_name == "FACET_ERROR_REPEATED_VERTEX"):
        message += f" (written {error.vertex + index_base} in the file)"
    if keys:
        message += f" ({', '.join(keys)} in the file)"
    located = MeshError(message, source=source, line=line, face=error.face, vertex=error.vertex)
    located.status_name = error.status_name
    return located
