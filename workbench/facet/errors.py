# SPDX-License-Identifier: LGPL-2.1-or-later
"""Errors raised by Facet.

Every error a designer can cause with a bad file or a bad mesh is a
:class:`MeshError`, whose message is one line naming the file, the line or the
face, and what is wrong, for example::

    tubemesh.off: line 12: face 3 has index 9 out of range (8 vertices)

The command line prints that line and nothing else; the workbench shows it in
a message box. Errors from the compiled core (``facet._core.CoreError``) are
turned into these classes by :func:`from_core`.
"""

import os

__all__ = ["FacetError", "MeshError", "Cancelled", "from_core", "MESH_STATUSES"]

#: Core statuses that mean "the mesh itself is wrong" (raised as MeshError).
MESH_STATUSES = frozenset(
    {
        "FACET_ERROR_EMPTY_MESH",
        "FACET_ERROR_BAD_FACE_START",
        "FACET_ERROR_INDEX_OUT_OF_RANGE",
        "FACET_ERROR_DEGENERATE_FACE",
        "FACET_ERROR_REPEATED_VERTEX",
        "FACET_ERROR_NONFINITE",
        "FACET_ERROR_COORDINATE_RANGE",
    }
)


class FacetError(Exception):
    """Base class of every error Facet raises on purpose.

    Attributes
    ----------
    status_name : str or None
        Name of the core status that caused the error
        (``"FACET_ERROR_NUMERICAL"``), or None when it did not come from the
        compiled core.
    """

    status_name = None


class InputError(FacetError, ValueError):
    """An input cannot be used: a file, a drawing, targets or a parameter.

    The base of every bad-input error (the command line exits with status 2
    for these). Its message names the input and what is wrong, in one line:
    ``"roof.dxf: edge 12 is an arc; split arcs or pass --arc-tolerance"``.
    Subclass it for a family of inputs (:class:`MeshError` for meshes).
    """


class MeshError(InputError):
    """A mesh, or the file it was read from, cannot be used.

    Parameters
    ----------
    message : str
        What is wrong, without the file name or line number, for example
        ``"face 3 has index 9 out of range (8 vertices)"``.
    source : str or os.PathLike, optional
        The file the mesh came from.
    line : int, optional
        Line number in `source` (1-based).
    face : int, optional
        Index of the offending face in the mesh (0-based).
    vertex : int, optional
        Index of the offending vertex in the mesh (0-based).

    Attributes
    ----------
    message, source, line, face, vertex
        As given; absent ones are None.

    Notes
    -----
    ``str(error)`` joins the known parts with ``": "``:
    ``"x.obj: line 7: face 1 has 2 vertices (at least 3 needed)"``.
    """

    def __init__(self, message, *, source=None, line=None, face=None, vertex=None):
        self.message = str(message)
        self.source = source
        self.line = None if line is None else int(line)
        self.face = None if face is None else int(face)
        self.vertex = None if vertex is None else int(vertex)
        super().__init__(str(self))

    def __str__(self):
        parts = []
        if self.source is not None:
            parts.append(os.fspath(self.source))
        if self.line is not None:
            parts.append(f"line {self.line}")
        parts.append(self.message)
        return " ".join(": ".join(parts).splitlines())

    def __reduce__(self):
        return (
            _rebuild_mesh_error,
            (self.message, self.source, self.line, self.face, self.vertex, self.status_name),
        )

    def located(self, source=None, line=None):
        """Return a copy of this error placed in a file.

        Parameters
        ----------
        source : str or os.PathLike, optional
            File name; keeps the current one when None.
        line : int, optional
            Line number; keeps the current one when None.

        Returns
        -------
        MeshError
        """
        error = MeshError(
            self.message,
            source=self.source if source is None else source,
            line=self.line if line is None else line,
            face=self.face,
            vertex=self.vertex,
        )
        error.status_name = self.status_name
        return error


def _rebuild_mesh_error(message, source, line, face, vertex, status_name):
    error = MeshError(message, source=source, line=line, face=face, vertex=vertex)
    error.status_name = status_name
    return error


class Cancelled(FacetError):
    """A long computation was stopped by the designer (cancel button or Ctrl+C).

    ``result`` is what was finished before the stop and may be kept (a planarization
    stopped after a result at the tolerance, in its quality re-solves or method auto's
    comparison or fallback: that result, see :meth:`facet.Planarizer.solve`), or None."""

    result = None


def report_progress(progress, done, total, what):
    """Call ``progress(done, total)`` when given; raise :class:`Cancelled` ("WHAT
    cancelled") when it returns True."""
    if progress is not None and progress(done, total):
        raise Cancelled(f"{what} cancelled")


def _index_or_none(value):
    try:
        value = int(value)
    except (TypeError, ValueError):
        return None
    return value if value >= 0 else None


def from_core(exc, source=None):
    """Turn an error of the compiled core into a Facet error.

    Parameters
    ----------
    exc : facet._core.CoreError
        The core's exception, with attributes ``status``, ``status_name``,
        ``face`` and ``vertex`` (-1 when not about one face or vertex);
        ``str(exc)`` is the core's message.
    source : str or os.PathLike, optional
        File the mesh came from, named in the message.

    Returns
    -------
    FacetError
        A :class:`MeshError` for a wrong mesh (empty, bad face offsets, index
        out of range, degenerate face, repeated vertex, non-finite
        coordinate), :class:`Cancelled` when the designer stopped the solve,
        a plain :class:`FacetError` otherwise. Raise it with
        ``raise from_core(exc) from exc``.
    """
    status_name = getattr(exc, "status_name", None)
    message = str(exc) or (status_name or type(exc).__name__)
    if status_name in MESH_STATUSES:
        error = MeshError(
            message,
            source=source,
            face=_index_or_none(getattr(exc, "face", None)),
            vertex=_index_or_none(getattr(exc, "vertex", None)),
        )
    elif status_name == "FACET_ERROR_CANCELLED" or type(exc).__name__ == "Cancelled":
        error = Cancelled(message)
    else:
        if source is not None:
            message = f"{os.fspath(source)}: {message}"
        error = FacetError(message)
    error.status_name = status_name
    return error
