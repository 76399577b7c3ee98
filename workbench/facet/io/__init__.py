# SPDX-License-Identifier: LGPL-2.1-or-later
"""Reading and writing facade meshes.

:func:`read_mesh` and :func:`write_mesh` choose the format from the file
extension:

========  ===========================  =====  =====
suffix    format                       read   write
========  ===========================  =====  =====
``.obj``  Wavefront OBJ                yes    yes
``.off``  Object File Format           yes    yes
``.json`` compas / RhinoVAULT mesh     yes    no
========  ===========================  =====  =====

Every reader returns a validated :class:`~facet.mesh.PolyMesh` and raises
:class:`~facet.errors.MeshError` naming the file, the line (or face) and what
is wrong. Writers write coordinates with ``repr`` so a file read back gives
the same bits, and refuse NaN.
"""

import os

from facet.errors import MeshError
from facet.io.checks import read_warnings
from facet.io.compas_json import read_compas_json
from facet.io.obj import read_obj, write_obj
from facet.io.off import read_off, write_off

__all__ = [
    "read_mesh",
    "write_mesh",
    "read_obj",
    "read_off",
    "read_compas_json",
    "write_obj",
    "write_off",
    "READERS",
    "WRITERS",
    "reader_for",
    "writer_for",
    "read_warnings",
]

#: Reader for each file suffix.
READERS = {".obj": read_obj, ".off": read_off, ".json": read_compas_json}

#: Writer for each file suffix.
WRITERS = {".obj": write_obj, ".off": write_off}


def _suffix(path):
    return os.path.splitext(os.fspath(path))[1].lower()


def _chosen(table, path, verb):
    function = table.get(_suffix(path))
    if function is None:
        kind = f"{_suffix(path)} files" if _suffix(path) else "files without an extension"
        raise MeshError(
            f"cannot {verb} {kind} (Facet {verb}s {', '.join(sorted(table))})",
            source=path,
        )
    return function


def reader_for(path):
    """The reader for `path`'s extension; MeshError naming the file when there is none."""
    return _chosen(READERS, path, "read")


def writer_for(path):
    """The writer for `path`'s extension; MeshError naming the file when there is none.

    Call it before a long computation to refuse an output name early.
    """
    return _chosen(WRITERS, path, "write")


def read_mesh(path, **options):
    """Read a mesh file, choosing the format from its extension.

    Parameters
    ----------
    path : str or os.PathLike
        A ``.obj``, ``.off`` or ``.json`` file.
    **options
        Passed to the reader: ``validate`` and ``progress`` (``progress(done, total)``,
        True cancels: :class:`facet.Cancelled`) for all, ``item`` for compas JSON.

    Returns
    -------
    PolyMesh

    Raises
    ------
    MeshError
        For an unknown extension or anything wrong in the file.
    OSError
        When the file cannot be read.
    """
    reader = reader_for(path)
    return reader(path, **options)


def write_mesh(mesh, path):
    """Write a mesh file, choosing the format from its extension.

    Parameters
    ----------
    mesh : PolyMesh
    path : str or os.PathLike
        A ``.obj`` or ``.off`` file; replaced if it exists.

    Raises
    ------
    MeshError
        For an unknown extension, or a NaN or infinite coordinate (nothing is
        written then).
    OSError
        When the file cannot be written.
    """
    writer = writer_for(path)
    writer(mesh, path)
