# SPDX-License-Identifier: LGPL-2.1-or-later
"""Wavefront OBJ: the polygon meshes Rhino, Blender and compas exchange.

Reading keeps what a panel layout needs and ignores the rest:

- ``v x y z [w]`` gives a vertex; a fourth value (the weight ``w``) and
  per-vertex colours (``v x y z r g b``) are ignored.
- ``f a b c ...`` gives a face of any degree >= 3. Each corner may be written
  ``a``, ``a/t``, ``a/t/n`` or ``a//n``: only the vertex index ``a`` is used.
  Indices start at 1; negative indices count back from the last vertex
  defined so far (-1 is the latest). ``fo`` is read like ``f``.
- Normals, texture coordinates, smoothing, lines, points and free-form
  geometry (``vn vt vp s l p ...``) are ignored, as are comments (from ``#``
  to the end of the line). Groups, objects and materials (``g o usemtl
  mtllib``) do not change the mesh, but are kept in its ``info``
  (``obj_sections``, ``obj_mtllib``): :func:`write_obj` writes them back
  before the same faces while the mesh has as many faces as the file had (a
  planarized facade keeps its zones and materials; :func:`facet.cleanup` moves
  them with the faces it keeps).
- A line ending with a backslash continues on the next line.

In error messages faces and vertices are numbered from 0 in the order they
appear (their index in the mesh); a vertex index is quoted as written.
"""

import numpy as np

from facet.errors import MeshError
from facet.io.checks import build_mesh
from facet.io.files import (PROGRESS_EVERY, parse_float, parse_int, read_lines,
                            reading_progress, write_mesh_records)

__all__ = ["read_obj", "write_obj"]

_FACE_KEYWORDS = frozenset({"f", "fo"})
#: Statements kept (in info) and written back before the same faces.
_SECTION_KEYWORDS = frozenset({"g", "o", "usemtl"})


def _statements(lines):
    """Yield (line number, text) with comments cut and continuation lines joined. A
    backslash at the end of a statement joins the next line to it; one at the end of a
    comment (a Windows folder) is part of the comment and joins nothing."""
    pending = None
    pending_line = 0
    for number, line in enumerate(lines, start=1):
        hash_at = line.find("#")
        if hash_at >= 0:
            line = line[:hash_at]
        if pending is not None:
            line = pending + " " + line
            number = pending_line
            pending = None
        stripped = line.rstrip()
        if stripped.endswith("\\"):
            pending = stripped[:-1]
            pending_line = number
            continue
        yield number, line
    if pending is not None:
        yield pending_line, pending


def read_obj(path, *, validate=True, progress=None):
    """Read the vertices and faces of a Wavefront OBJ file.

    Parameters
    ----------
    path : str or os.PathLike
    validate : bool
        Check the mesh fully (:meth:`PolyMesh.validate`). Default True.
    progress : callable, optional
        ``progress(done, total)`` in lines of the file (every
        :data:`facet.io.files.PROGRESS_EVERY`, and at the end); True cancels
        (:class:`facet.Cancelled`, "reading NAME cancelled").

    Returns
    -------
    PolyMesh
        Every vertex of the file (in file order) and every face. ``info``
        holds ``source`` and ``format`` (``"obj"``).

    Raises
    ------
    MeshError
        With the file name and line: ``"bad.obj: line 4: cannot read 'abc' as
        a number"``, ``"x.obj: line 7: face 1 has 2 vertices (at least 3
        needed)"``, ``"x.obj: no faces"``, ``"x.obj: file is empty"``, ``"x.obj: line 3: vertex 2 has a
        non-finite coordinate"``, an index out of range, or what
        :meth:`PolyMesh.validate` finds.
    OSError
        When the file cannot be read.
    """
    source = path
    coordinates = []
    vertex_lines = []
    face_vertices = []
    face_start = [0]
    face_lines = []
    n_polylines = 0
    sections = []  # (faces before it, statement): g, o, usemtl
    mtllib = []
    lines = read_lines(path)
    report = reading_progress(progress, path)
    report(0, len(lines))
    due = PROGRESS_EVERY
    for number, text in _statements(lines):
        if number >= due:
            report(number, len(lines))
            due = number + PROGRESS_EVERY
        tokens = text.split()
        if not tokens:
            continue
        keyword = tokens[0]
        if keyword == "v":
            if len(tokens) < 4:
                raise MeshError(
                    f"vertex {len(vertex_lines)} has {len(tokens) - 1} coordinates (3 needed)",
                    source=source,
                    line=number,
                )
            coordinates.append(parse_float(tokens[1], source, number))
            coordinates.append(parse_float(tokens[2], source, number))
            coordinates.append(parse_float(tokens[3], source, number))
            vertex_lines.append(number)
        elif keyword in _FACE_KEYWORDS:
            corners = tokens[1:]
            if len(corners) < 3:
                raise MeshError(
                    f"face {len(face_lines)} has {len(corners)} vertices (at least 3 needed)",
                    source=source,
                    line=number,
                    face=len(face_lines),
                )
            n_defined = len(vertex_lines)
            for corner in corners:
                index = parse_int(corner.split("/", 1)[0], source, number, "a vertex index")
                if index > 0:
                    face_vertices.append(index - 1)
                elif index < 0:
                    if n_defined + index < 0:
                        raise MeshError(
                            f"face {len(face_lines)} has relative index {index} but only "
                            f"{n_defined} vertices come before it",
                            source=source,
                            line=number,
                            face=len(face_lines),
                        )
                    face_vertices.append(n_defined + index)
                else:
                    raise MeshError(
                        f"face {len(face_lines)} has vertex index 0 (OBJ indices start at 1)",
                        source=source,
                        line=number,
                        face=len(face_lines),
                    )
            face_start.append(len(face_vertices))
            face_lines.append(number)
        elif keyword in ("l", "curv"):
            n_polylines += 1
        elif keyword in _SECTION_KEYWORDS:
            sections.append((len(face_lines), " ".join(tokens)))
        elif keyword == "mtllib":
            mtllib.append(" ".join(tokens))
    if not face_lines and not vertex_lines and not n_polylines:
        if not any(line.strip() for line in lines):
            raise MeshError("file is empty", source=source)
        raise MeshError("not an OBJ file: no 'v' or 'f' lines", source=source)
    if not face_lines and n_polylines:
        raise MeshError(
            f"no faces: the file holds {n_polylines} lines or curves ('l', 'curv'), not panels",
            source=source,
        )
    report(len(lines), len(lines))
    return build_mesh(
        np.array(coordinates, dtype=np.float64).reshape(-1, 3),
        face_start,
        face_vertices,
        source=source,
        info=dict({"format": "obj"},
                  **({"obj_sections": tuple(sections), "obj_faces": len(face_lines)}
                     if sections else {}),
                  **({"obj_mtllib": tuple(mtllib)} if mtllib else {})),
        vertex_lines=vertex_lines,
        face_lines=face_lines,
        index_base=1,
        validate=validate,
    )


def write_obj(mesh, path):
    """Write a mesh as a Wavefront OBJ file.

    Coordinates are written with ``repr`` (at most 17 significant digits), so
    reading the file back gives exactly the same float64 values.

    Parameters
    ----------
    mesh : PolyMesh
    path : str or os.PathLike

    Raises
    ------
    MeshError
        When a coordinate is NaN or infinite (nothing is written).
    OSError
        When the file cannot be written.
    """
    info = mesh.info or {}
    sections = info.get("obj_sections", ()) if info.get("obj_faces") == mesh.n_faces else ()
    before = {}
    for at, statement in sections:
        before.setdefault(at, []).append(statement)
    faces_written = iter(range(mesh.n_faces))

    def face_record(face):
        text = "f " + " ".join(str(index + 1) for index in face)
        ahead = before.get(next(faces_written))
        return "\n".join(ahead + [text]) if ahead else text

    header = f"# Facet mesh: {mesh.n_vertices} vertices, {mesh.n_faces} faces\n"
    header += "".join(f"{line}\n" for line in info.get("obj_mtllib", ()))
    tail = "".join(f"{statement}\n" for statement in before.get(mesh.n_faces, ()))
    write_mesh_records(path, mesh, header=header, vertex_prefix="v ", face_record=face_record,
                       footer=tail)
