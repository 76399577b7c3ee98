# SPDX-License-Identifier: LGPL-2.1-or-later
"""Cleanup (paper section 5): collapse edges too short to build, then planarize again.

Planarization can shrink edges until a panel has a corner a fabricator cannot
make. :func:`cleanup` collapses every edge shorter than a threshold (absolute,
or relative to the mesh's mean edge length), shortest first, each to its
midpoint (or onto the boundary when one end lies on it). Faces lose the
merged corners (a quad becomes a triangle); faces left with fewer than three
vertices disappear. A collapse that would make the mesh non-manifold (an edge
in three faces, two fans of faces meeting at one vertex, two faces on the
same vertices) or turn a face over (its normal no longer on the side of the
input face's) is skipped and counted. The result is a new mesh with a new
topology; planarize it again (``python3 -m facet cleanup`` does).
"""

from dataclasses import dataclass

import numpy as np

from facet import _core
from facet.errors import InputError, MeshError, from_core
from facet.mesh import PolyMesh, remapped_info

__all__ = ["CleanupResult", "cleanup"]


@dataclass(frozen=True)
class CleanupResult:
    """What :func:`cleanup` did.

    Attributes
    ----------
    mesh : PolyMesh
        The new mesh. Its ``info`` is the input's, with the compas reader's
        ``vertex_keys``, ``face_keys`` and ``support_vertices`` mapped to the new
        vertices and faces (a merged vertex keeps its first key; the others are in
        ``merged_vertex_keys``).
    collapsed_edges : numpy.ndarray of int32, shape (k, 2)
        The input vertex pairs collapsed, in order.
    removed_faces : numpy.ndarray of int32
        Input faces that fell below three vertices.
    vertex_map : numpy.ndarray of int32
        For each input vertex, its vertex in the new mesh (-1 when it was
        left without a face).
    threshold : float
        The edge length used, model units.
    skipped : int
        Short edges kept because collapsing them would break the mesh.
    face_map : numpy.ndarray of int32
        For each new face, the input face it came from.
    """

    mesh: PolyMesh
    collapsed_edges: np.ndarray
    removed_faces: np.ndarray
    vertex_map: np.ndarray
    threshold: float
    skipped: int
    face_map: np.ndarray

    def as_dict(self):
        """A JSON-safe summary (counts, threshold and the collapsed pairs)."""
        from facet.report import json_safe

        return json_safe(
            {
                "threshold": self.threshold,
                "collapsed_edges": len(self.collapsed_edges),
                "removed_faces": len(self.removed_faces),
                "skipped_edges": self.skipped,
                "vertices": self.mesh.n_vertices,
                "faces": self.mesh.n_faces,
                "collapsed_pairs": self.collapsed_edges.tolist(),
                "removed_face_indices": self.removed_faces.tolist(),
            }
        )


def cleanup(mesh, min_edge, relative=True):
    """Collapse the edges of `mesh` shorter than `min_edge`.

    Parameters
    ----------
    mesh : PolyMesh
        Never modified.
    min_edge : float
        Shortest edge to keep: a fraction of the mean edge length when
        `relative` (default), else model units. Must be > 0.
    relative : bool

    Returns
    -------
    CleanupResult

    Raises
    ------
    facet.InputError
        For a `min_edge` that is not a finite number > 0, or one longer than
        every edge (nothing would be left).
    facet.MeshError
        For an invalid mesh.
    """
    try:
        value = float(min_edge)
    except (TypeError, ValueError):
        raise InputError(f"min_edge must be a number, not {min_edge!r}") from None
    if not np.isfinite(value) or value <= 0.0:
        raise InputError(f"min_edge must be a finite number > 0, not {min_edge!r}")
    source = mesh.info.get("source") if mesh.info else None
    try:
        out = _core.cleanup(
            mesh.vertices, mesh.face_start, mesh.face_vertices, value, relative=bool(relative)
        )
    except _core.CoreError as exc:
        if getattr(exc, "status_name", None) == "FACET_ERROR_NOTHING_LEFT":
            raise MeshError(str(exc), source=source) from None
        raise from_core(exc, source=source) from None
    xyz = np.frombuffer(out["xyz"], dtype=np.float64).reshape(-1, 3)
    face_start = np.frombuffer(out["face_start"], dtype=np.int32)
    face_vertices = np.frombuffer(out["face_vertices"], dtype=np.int32)
    removed = np.frombuffer(out["removed_faces"], dtype=np.int32).copy()
    keep = np.ones(mesh.n_faces, dtype=bool)
    keep[removed] = False
    vertex_map = np.frombuffer(out["vertex_map"], dtype=np.int32).copy()
    info = remapped_info(dict(mesh.info or {}), vertex_map, np.flatnonzero(keep),
                         mesh.n_faces, len(xyz))
    info["cleanup"] = {"threshold": out["threshold"], "collapsed": len(out["collapsed_edges"]) // 8}
    new_mesh = PolyMesh(xyz, face_start, face_vertices, info=info)
    return CleanupResult(
        mesh=new_mesh,
        collapsed_edges=np.frombuffer(out["collapsed_edges"], dtype=np.int32).reshape(-1, 2).copy(),
        removed_faces=np.sort(removed),
        vertex_map=vertex_map,
        threshold=float(out["threshold"]),
        skipped=int(out["skipped"]),
        face_map=np.flatnonzero(keep).astype(np.int32),
    )
