# SPDX-License-Identifier: LGPL-2.1-or-later
"""Object File Format (OFF): Geomview's format, used by libigl and CGAL.

What the reader accepts:

- A header keyword ``OFF``, optionally with the prefixes ``ST``, ``C`` and
  ``N`` (``COFF``, ``NOFF``, ``CNOFF``, ``STCNOFF``...). ``4OFF``, ``nOFF``
  and ``OFF BINARY`` are refused. A file that starts directly with the
  counts is read as plain ``OFF``.
- The counts ``n_vertices n_faces [n_edges]``; the edge count is ignored.
- Comments from ``#`` to the end of the line, anywhere.
- Plain ``OFF`` is read free-form: the numbers are a stream of tokens and a
  record may span lines or share a line with the next vertex.
- With a prefix the vertex records carry extra values (normals, colours,
  texture coordinates) whose count is not fixed (a colour has 1, 3 or 4
  values), so each vertex record is read as the first three numbers of it
  and the rest of the line of its third number is skipped: such files need
  one vertex per line, which is what every writer does.
- A face record is ``n i1 ... in`` with 0-based indices, optionally followed
  by a colour on the same line: the rest of the line of the last index is
  always skipped. Faces therefore need one per line (a file with several
  faces on one line fails with "file ends after k of n faces", never
  silently).
- Anything after the last face is refused, so a header that declares too few
  vertices or faces does not silently drop panels.

In error messages faces and vertices are numbered from 0, as in the file.
"""

import numpy as np

from facet.errors import MeshError
from facet.io.checks import build_mesh
from facet.io.files import (PROGRESS_EVERY, parse_float, parse_int, read_lines,
                            reading_progress, write_mesh_records)

__all__ = ["read_off", "write_off"]

_OPTIONAL_PREFIXES = ("ST", "C", "N")


def _tokens(lines):
    """All tokens of the file and the line of each, comments left out."""
    tokens = []
    token_lines = []
    for number, line in enumerate(lines, start=1):
        hash_at = line.find("#")
        if hash_at >= 0:
            line = line[:hash_at]
        for token in line.split():
            tokens.append(token)
            token_lines.append(number)
    return tokens, token_lines


def _header_prefix(keyword, source):
    """Optional-field prefix of an OFF keyword ('' for plain OFF), or None if not OFF."""
    if not keyword.endswith("OFF"):
        return None
    prefix = keyword[:-3]
    rest = prefix
    stripped = True
    while rest and stripped:
        stripped = False
        for part in _OPTIONAL_PREFIXES:
            if rest.startswith(part):
                rest = rest[len(part) :]
                stripped = True
    if rest:
        if "4" in rest or "n" in rest:
            raise MeshError(
                f"{keyword} (4-D or n-D vertices) is not supported; use OFF", source=source, line=1
            )
        return None
    return prefix


class _TokenReader:
    """Walks the token stream, knowing the line of each token."""

    def __init__(self, tokens, token_lines):
        self.tokens = tokens
        self.lines = token_lines
        self.at = 0

    def left(self):
        return len(self.tokens) - self.at

    def take(self):
        token, line = self.tokens[self.at], self.lines[self.at]
        self.at += 1
        return token, line

    def skip_rest_of_line(self, line):
        while self.at < len(self.tokens) and self.lines[self.at] == line:
            self.at += 1


def read_off(path, *, validate=True, progress=None):
    """Read the vertices and faces of an OFF file.

    Parameters
    ----------
    path : str or os.PathLike
    validate : bool
        Check the mesh fully (:meth:`PolyMesh.validate`). Default True.
    progress : callable, optional
        ``progress(done, total)`` in vertices and faces read (every
        :data:`facet.io.files.PROGRESS_EVERY`, and at the end); True cancels
        (:class:`facet.Cancelled`, "reading NAME cancelled").

    Returns
    -------
    PolyMesh
        ``info`` holds ``source``, ``format`` (``"off"``) and ``header`` (the
        header keyword, ``"OFF"``, ``"COFF"``...).

    Raises
    ------
    MeshError
        With the file name and line where known:
        ``"x.off: file ends after 3 of 8 vertices"``,
        ``"tubemesh.off: line 12: face 3 has index 9 out of range (8
        vertices)"``, ``"x.off: line 5: cannot read 'abc' as a number"``...
    OSError
        When the file cannot be read.
    """
    source = path
    tokens, token_lines = _tokens(read_lines(path))
    if not tokens:
        raise MeshError("file is empty", source=source)
    stream = _TokenReader(tokens, token_lines)

    keyword, line = tokens[0], token_lines[0]
    prefix = _header_prefix(keyword, source)
    if prefix is not None:
        stream.take()
        header = keyword
        if stream.left() and tokens[stream.at].upper() == "BINARY":
            raise MeshError("binary OFF is not supported; save as text", source=source, line=line)
    else:
        try:
            int(keyword)
        except ValueError:
            raise MeshError(
                f"not an OFF file: it starts with {keyword[:20]!r} instead of 'OFF'",
                source=source,
                line=line,
            ) from None
        prefix = ""
        header = None

    counts = []
    for what in ("vertex count", "face count"):
        if not stream.left():
            raise MeshError(f"file ends before the {what}", source=source)
        token, line = stream.take()
        count = parse_int(token, source, line, f"a {what}")
        if count < 0:
            raise MeshError(f"negative {what} {count}", source=source, line=line)
        counts.append(count)
    n_vertices, n_faces = counts
    if stream.left() and stream.lines[stream.at] == line:
        stream.take()  # the edge count, unused

    coordinates = []
    vertex_lines = []
    line_structured = prefix != ""
    report = reading_progress(progress, path)
    total = n_vertices + n_faces
    for vertex in range(n_vertices):
        if vertex % PROGRESS_EVERY == 0:
            report(vertex, total)
        if stream.left() < 3:
            raise MeshError(f"file ends after {vertex} of {n_vertices} vertices", source=source)
        for axis in range(3):
            token, line = stream.take()
            if axis == 0:
                vertex_lines.append(line)
            coordinates.append(parse_float(token, source, line))
        if line_structured:
            stream.skip_rest_of_line(line)

    face_start = [0]
    face_vertices = []
    face_lines = []
    for face in range(n_faces):
        if face % PROGRESS_EVERY == 0:
            report(n_vertices + face, total)
        if not stream.left():
            raise MeshError(f"file ends after {face} of {n_faces} faces", source=source)
        token, first_line = stream.take()
        degree = parse_int(token, source, first_line, "a face's vertex count")
        if degree < 3:
            raise MeshError(
                f"face {face} has {degree} vertices (at least 3 needed)",
                source=source,
                line=first_line,
                face=face,
            )
        if stream.left() < degree:
            raise MeshError(
                f"file ends in face {face} ({stream.left()} of its {degree} indices)",
                source=source,
            )
        for _ in range(degree):
            token, line = stream.take()
            face_vertices.append(parse_int(token, source, line, "a vertex index"))
        stream.skip_rest_of_line(line)
        face_start.append(len(face_vertices))
        face_lines.append(first_line)

    if stream.left():
        from facet.report import count_noun

        token, line = stream.take()
        raise MeshError(
            f"unexpected {token[:20]!r} after the last face (the header declares "
            f"{count_noun(n_vertices, 'vertex')} and {count_noun(n_faces, 'face')})",
            source=source,
            line=line,
        )

    report(total, total)
    return build_mesh(
        np.array(coordinates, dtype=np.float64).reshape(-1, 3),
        face_start,
        face_vertices,
        source=source,
        info={"format": "off", "header": header or "OFF"},
        vertex_lines=vertex_lines,
        face_lines=face_lines,
        validate=validate,
    )


def write_off(mesh, path):
    """Write a mesh as a plain OFF file (one vertex and one face per line).

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
    write_mesh_records(
        path,
        mesh,
        header=f"OFF\n{mesh.n_vertices} {mesh.n_faces} {mesh.edges().shape[0]}\n",
        vertex_prefix="",
        face_record=lambda face: f"{len(face)} " + " ".join(map(str, face)),
    )
