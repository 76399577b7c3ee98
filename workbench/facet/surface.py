# SPDX-License-Identifier: LGPL-2.1-or-later
"""Closest points on a triangle surface: distances from a design surface.

A :class:`Surface` is built once from a polygon mesh (each face triangulated:
quads along the shorter diagonal, larger faces as a fan from their centroid)
or from triangles, and answers closest-point queries through an AABB tree in
the compiled core. Coordinates are centred and scaled inside, so
georeferenced models keep their precision.

>>> surface = Surface(mesh)                                  # doctest: +SKIP
>>> closest, distance, triangle, normal = surface.closest(points)  # doctest: +SKIP
"""

import numpy as np

from facet import _core
from facet.errors import Cancelled, InputError, from_core
from facet.mesh import PolyMesh

__all__ = ["Surface"]

#: Queries per call into the core between progress reports (and Ctrl+C checks).
_CHUNK = 1 << 16


class Surface:
    """A triangle surface for closest-point queries.

    Parameters
    ----------
    mesh_or_vertices : PolyMesh or array_like, shape (n, 3)
        A polygon mesh, or the vertices of `triangles`.
    triangles : array_like of int, shape (m, 3), optional
        Vertex indices of each triangle; required with vertices, not allowed
        with a mesh.

    Raises
    ------
    facet.InputError
        When the vertices or triangles cannot be used (the message names the
        triangle or face and vertex).
    """

    def __init__(self, mesh_or_vertices, triangles=None):
        try:
            if isinstance(mesh_or_vertices, PolyMesh):
                if triangles is not None:
                    raise InputError("Surface: give a mesh or vertices and triangles, not both")
                mesh = mesh_or_vertices
                self._core = _core.Surface(
                    mesh.vertices, face_start=mesh.face_start, face_vertices=mesh.face_vertices
                )
                faces = np.empty(self._core.n_triangles, dtype=np.int32)
                self._core.triangle_faces(faces)
                self._faces = faces
            else:
                if triangles is None:
                    raise InputError("Surface: triangles are needed with vertices")
                vertices = np.ascontiguousarray(mesh_or_vertices, dtype=np.float64)
                tri = np.ascontiguousarray(triangles)
                if vertices.ndim != 2 or vertices.shape[1] != 3:
                    raise InputError(
                        f"Surface: vertices must be an (n, 3) array, got shape {vertices.shape}"
                    )
                if tri.ndim != 2 or tri.shape[1] != 3 or (tri.size and tri.dtype.kind not in "iu"):
                    raise InputError(
                        f"Surface: triangles must be an (m, 3) integer array, got shape "
                        f"{tri.shape} of {tri.dtype}"
                    )
                self._core = _core.Surface(vertices, np.ascontiguousarray(tri, dtype=np.int32))
                self._faces = None
        except _core.CoreError as exc:
            error = from_core(exc)
            if not isinstance(error, InputError):
                raise error from None
            raise InputError(f"Surface: {exc}") from None

    @property
    def n_triangles(self):
        """Number of triangles."""
        return self._core.n_triangles

    @property
    def triangle_faces(self):
        """The mesh face of each triangle (int32 array), or None for a triangle surface."""
        return None if self._faces is None else self._faces.copy()

    def closest(self, points, threads=None, progress=None):
        """Closest points on the surface.

        Parameters
        ----------
        points : array_like, shape (n, 3)
            Query points, model units; NaN or infinite ones are refused.
        threads : int, optional
            OpenMP threads (default: all). Results do not depend on it.
        progress : callable, optional
            ``progress(done, total)`` after each block of 65536 points; a true
            return value cancels (:class:`facet.Cancelled`).

        Returns
        -------
        closest : numpy.ndarray, shape (n, 3)
        distance : numpy.ndarray, shape (n,)
        triangle : numpy.ndarray of int32, shape (n,)
            Index of the triangle the closest point lies on (see
            :attr:`triangle_faces` for its mesh face).
        normal : numpy.ndarray, shape (n, 3)
            Unit normal of that triangle (0 0 0 for a zero-area one). On a
            corner or an edge that triangles share, the one with the lowest
            index among them (after those with area) is reported, in any
            units or place.
        """
        query = np.ascontiguousarray(points, dtype=np.float64)
        if query.ndim == 1 and query.size == 3:
            query = query.reshape(1, 3)
        if query.ndim != 2 or query.shape[1] != 3:
            raise InputError(f"points must be an (n, 3) array, got shape {query.shape}")
        n = query.shape[0]
        closest = np.empty((n, 3))
        distance = np.empty(n)
        triangle = np.empty(n, dtype=np.int32)
        normal = np.empty((n, 3))
        if not np.isfinite(query).all():
            bad = int(np.flatnonzero(~np.isfinite(query).all(axis=1))[0])
            raise InputError(f"points: point {bad} has a non-finite coordinate {query[bad].tolist()}")
        for start in range(0, n, _CHUNK):
            stop = min(n, start + _CHUNK)
            try:
                self._core.closest(query[start:stop], closest[start:stop], distance[start:stop],
                                   triangle[start:stop], normal[start:stop],
                                   threads=int(threads or 0))
            except _core.CoreError as exc:
                raise InputError(f"points: {exc}") from None
            if progress is not None and progress(stop, n):
                raise Cancelled(f"closest points cancelled after {stop} of {n} points")
        return closest, distance, triangle, normal
