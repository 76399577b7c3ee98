# SPDX-License-Identifier: LGPL-2.1-or-later
"""How flat each panel is.

For every face the vertices are fitted with their least-squares plane; the
largest and the RMS distance of the vertices from it are what a panel
fabricator specifies (a glass supplier accepts so many millimetres). They are
given in model units and divided by the face's mean edge length, so meshes of
any size compare. For quads the figure libigl reports is given too (distance
between the two diagonals over the mean diagonal length).
"""

import dataclasses
from dataclasses import dataclass

import numpy as np

from facet import _core
from facet.errors import from_core

__all__ = ["PlanarityReport", "planarity"]


@dataclass(frozen=True)
class PlanarityReport:
    """Per-face planarity of a mesh.

    Attributes
    ----------
    max_abs, rms_abs : numpy.ndarray
        Largest and RMS distance of each face's vertices from the face's
        least-squares plane, in model units.
    mean_edge : numpy.ndarray
        Mean edge length of each face, model units.
    max_rel, rms_rel : numpy.ndarray
        ``max_abs`` and ``rms_abs`` divided by ``mean_edge`` (0 for a face
        whose edges all have zero length).
    diagonal : numpy.ndarray
        libigl's quad planarity (distance between the diagonals over their
        mean length) for quads, -1 for other faces.
    exempt : numpy.ndarray of bool or None
        Faces left out of the figures over all faces (``*_all``,
        ``worst_faces``): those a planarization exempted (face weight 0),
        which it does not make planar. Their own figures stay in the arrays.
    """

    max_abs: np.ndarray
    rms_abs: np.ndarray
    mean_edge: np.ndarray
    max_rel: np.ndarray
    rms_rel: np.ndarray
    diagonal: np.ndarray
    exempt: np.ndarray = None

    def leaving_out(self, exempt):
        """The same figures with the faces `exempt` (bool per face, or None) left out of
        those over all faces: another mesh's measure over the faces a planarization
        counted."""
        return dataclasses.replace(self, exempt=exempt)

    def _counted(self, values):
        return values if self.exempt is None else values[~self.exempt]

    @property
    def n_exempt(self):
        """Faces left out of the figures over all faces."""
        return 0 if self.exempt is None else int(np.count_nonzero(self.exempt))

    @property
    def n_faces(self):
        """Number of faces measured."""
        return int(self.max_abs.shape[0])

    @property
    def max_abs_all(self):
        """Largest distance from plane over all faces (not exempt), model units."""
        values = self._counted(self.max_abs)
        return float(values.max()) if values.size else 0.0

    @property
    def max_rel_all(self):
        """Largest relative distance from plane over all faces (not exempt)."""
        values = self._counted(self.max_rel)
        return float(values.max()) if values.size else 0.0

    @property
    def rms_rel_all(self):
        """RMS over all faces (not exempt) of each face's relative RMS distance."""
        values = self._counted(self.rms_rel)
        return float(np.sqrt(np.mean(values**2))) if values.size else 0.0

    @property
    def diagonal_max(self):
        """Largest libigl quad measure (faces not exempt), or None when there is no quad."""
        diagonal = self._counted(self.diagonal)
        quads = diagonal[diagonal >= 0.0]
        return float(quads.max()) if quads.size else None

    def worst_faces(self, count=5):
        """Indices of the `count` least planar faces (relative, not exempt), worst first."""
        order = np.argsort(-self.max_rel, kind="stable")
        if self.exempt is not None:
            order = order[~self.exempt[order]]
        return [int(f) for f in order[:count]]


def _relative(values, lengths):
    out = np.zeros_like(values)
    np.divide(values, lengths, out=out, where=lengths > 0.0)
    return out


def planarity(mesh, threads=None):
    """Measure how flat every face of `mesh` is.

    Parameters
    ----------
    mesh : facet.PolyMesh
        The mesh to measure.
    threads : int, optional
        OpenMP threads (default: all). The figures do not depend on it.

    Returns
    -------
    PlanarityReport

    Raises
    ------
    facet.MeshError
        When a face refers to a vertex the mesh does not have.
    """
    n = mesh.n_faces
    max_abs, rms_abs = np.empty(n), np.empty(n)
    mean_edge, diagonal = np.empty(n), np.empty(n)
    try:
        _core.planarity(
            mesh.vertices,
            mesh.face_start,
            mesh.face_vertices,
            max_abs,
            rms_abs,
            mean_edge,
            diagonal,
            threads=int(threads or 0),
        )
    except _core.CoreError as exc:
        raise from_core(exc, source=mesh.info.get("source") if mesh.info else None) from exc
    return PlanarityReport(
        max_abs=max_abs,
        rms_abs=rms_abs,
        mean_edge=mean_edge,
        max_rel=_relative(max_abs, mean_edge),
        rms_rel=_relative(rms_abs, mean_edge),
        diagonal=diagonal,
    )
