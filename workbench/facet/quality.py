# SPDX-License-Identifier: LGPL-2.1-or-later
"""The quality report of a planarization: how flat, how far moved, what shape.

:func:`quality` measures a result mesh, optionally against the `input` it
was made from (same topology) and a `reference` surface:

- planarity per face (largest distance of its vertices from the face's
  best-fit plane), in model units and relative to the face's mean edge;
- displacement of each vertex from `input`, model units;
- distance of each result vertex from the reference surface (`reference`,
  else the surface of `input`), model units;
- face shape: the smallest interior angle of each face (degrees; a reflex
  corner of a concave panel counts as more than 180, and a face folded over
  itself, two of its edges crossing like a bowtie's, counts 0: it has no
  interior, and a panel cannot be cut from it), and the change of edge
  length ratios against `input`: with ``r_e = l_e / mean_l`` the length of
  edge e over the face's mean edge length, per face
  ``max_e |r_e(result) / r_e(input) - 1|`` (edges of zero input length left
  out), so 0 means the panel kept its proportions and a uniform scale
  changes nothing;
- nearly straight corners: per face, how far its straightest corner turns
  the outline (degrees, the angle between the edges in and out of it: 0 is
  a corner on a straight line, whether the face is convex there or not);
  faces whose straightest corner turns less than `straight_corner` degrees
  are counted. Planarizing makes them where a skew quad is best made a
  triangle with a vertex on one edge: to a fabricator the panel is that
  triangle with a kink, and the mitres of its two edges there meet far
  beyond the panel (facet.panels cuts them as butt joints);
- degenerate faces: zero area (below ``1e-12`` times the squared mean edge
  of the face), smallest angle below `min_angle` degrees, or an edge shorter
  than :data:`DEFAULT_SHORT_EDGE` of the face's mean edge (a quad whose edge
  has shrunk to nothing is a triangle to the fabricator, whatever its angles
  say: the angles at a vanishing edge are those of its ends).

Every figure in :meth:`QualityReport.as_dict` is a finite float or None.
"""

from dataclasses import dataclass

import numpy as np

from facet import _core
from facet.errors import InputError, from_core
from facet.mesh import PolyMesh, next_corners
from facet.planarity import PlanarityReport, planarity
from facet.surface import Surface

__all__ = ["QualityReport", "quality", "straight_corner_faces", "DEFAULT_MIN_ANGLE",
           "DEFAULT_SHORT_EDGE", "DEFAULT_STRAIGHT_CORNER"]

#: Faces with a smaller interior angle (degrees) count as degenerate.
DEFAULT_MIN_ANGLE = 5.0

#: Faces with an edge shorter than this fraction of their mean edge count as degenerate.
DEFAULT_SHORT_EDGE = 0.01

#: Faces with a corner that turns the outline by less than this (degrees) have a
#: nearly straight corner (an interior angle within this of 180 degrees).
DEFAULT_STRAIGHT_CORNER = 5.0

#: Relative area under which a face counts as having none.
_ZERO_AREA = 1e-12


def _max(values):
    return float(np.max(values)) if values is not None and values.size else None


def _rms(values):
    return float(np.sqrt(np.mean(values**2))) if values is not None and values.size else None


def _min(values):
    return float(np.min(values)) if values is not None and values.size else None


@dataclass(frozen=True)
class QualityReport:
    """Per-face and per-vertex quality figures of a mesh.

    Attributes
    ----------
    planarity : PlanarityReport
    displacement : numpy.ndarray or None
        Distance each vertex moved from the input (None without input).
    distance : numpy.ndarray or None
        Distance of each vertex from the reference surface (None without
        input or reference).
    min_angle : numpy.ndarray
        Smallest interior angle of each face, degrees.
    area : numpy.ndarray
        Area of each face (length of its vector area), model units squared.
    ratio_change : numpy.ndarray or None
        Change of edge length ratios of each face against the input.
    degenerate : numpy.ndarray of int
        Indices of degenerate faces.
    min_angle_threshold : float
        The angle (degrees) under which a face counts as degenerate.
    input_min_angle : numpy.ndarray or None
        The input's smallest angles, degrees.
    mesh : PolyMesh or None
        The mesh measured (for :meth:`per_face`).
    short_edge_threshold : float
        The fraction of a face's mean edge under which an edge makes the face
        degenerate.
    straight_corner : numpy.ndarray or None
        How far each face's straightest corner turns its outline, degrees (0:
        a corner on a straight line; 180 for a face with an edge of no length).
    straight_corner_threshold : float
        The turn (degrees) under which a corner counts as nearly straight.
    input_straight_corner : numpy.ndarray or None
        The input's, degrees.
    """

    planarity: PlanarityReport
    displacement: object
    distance: object
    min_angle: np.ndarray
    area: np.ndarray
    ratio_change: object
    degenerate: np.ndarray
    min_angle_threshold: float
    input_min_angle: object = None
    mesh: object = None
    short_edge_threshold: float = DEFAULT_SHORT_EDGE
    straight_corner: object = None
    straight_corner_threshold: float = DEFAULT_STRAIGHT_CORNER
    input_straight_corner: object = None

    #: Names :meth:`per_face` knows.
    PER_FACE = ("planarity", "planarity_rel", "displacement", "distance", "min_angle",
                "ratio_change", "straight_corner")

    @property
    def straight_corner_faces(self):
        """Indices of the faces with a nearly straight corner."""
        if self.straight_corner is None:
            return np.zeros(0, dtype=np.int64)
        return np.flatnonzero(self.straight_corner < self.straight_corner_threshold)

    def per_face(self, name):
        """One value per face, for colour maps.

        Parameters
        ----------
        name : str
            ``planarity`` (model units), ``planarity_rel``, ``displacement`` and
            ``distance`` (per face the largest of its vertices', model units),
            ``min_angle`` (degrees), ``ratio_change`` or ``straight_corner``
            (degrees).

        Returns
        -------
        numpy.ndarray or None
            None when the figure was not measured (no input or reference).
        """
        if name not in self.PER_FACE:
            raise InputError(f"per_face: {name!r} is not one of {', '.join(self.PER_FACE)}")
        if name in ("displacement", "distance"):
            values = getattr(self, name)
            if values is None or self.mesh is None:
                return None
            corners = np.asarray(values, dtype=np.float64)[self.mesh.face_vertices]
            return np.maximum.reduceat(corners, self.mesh.face_start[:-1])
        return {
            "planarity": self.planarity.max_abs,
            "planarity_rel": self.planarity.max_rel,
            "min_angle": self.min_angle,
            "ratio_change": self.ratio_change,
            "straight_corner": self.straight_corner,
        }[name]

    def as_dict(self, worst=5):
        """The summary as plain JSON types; NaN never appears (None instead).

        Keys: ``planarity_max_abs``, ``planarity_rms_abs``,
        ``planarity_max_rel``, ``planarity_rms_rel``, ``displacement_max``,
        ``displacement_rms``, ``distance_max``, ``distance_rms``,
        ``min_angle_deg`` (smallest over all faces), ``input_min_angle_deg``,
        ``ratio_change_max``, ``ratio_change_rms``, ``degenerate_faces``
        (count), ``degenerate_face_indices`` (the first `worst` * 4),
        ``degenerate_min_angle_deg`` and ``degenerate_short_edge`` (the
        thresholds), ``straightest_corner_deg`` (the least turn over all
        faces), ``input_straightest_corner_deg``, ``straight_corner_faces``
        (count), ``straight_corner_face_indices`` (the first `worst` * 4),
        ``straight_corner_deg`` (the threshold), ``worst_planarity_faces``.
        """
        from facet.report import json_safe

        p = self.planarity
        report = {
            "planarity_max_abs": _max(p.max_abs),
            "planarity_rms_abs": _rms(p.rms_abs),
            "planarity_max_rel": _max(p.max_rel),
            "planarity_rms_rel": _rms(p.rms_rel),
            "displacement_max": _max(self.displacement),
            "displacement_rms": _rms(self.displacement),
            "distance_max": _max(self.distance),
            "distance_rms": _rms(self.distance),
            "min_angle_deg": _min(self.min_angle),
            "input_min_angle_deg": _min(self.input_min_angle),
            "ratio_change_max": _max(self.ratio_change),
            "ratio_change_rms": _rms(self.ratio_change),
            "degenerate_faces": int(self.degenerate.size),
            "degenerate_face_indices": [int(f) for f in self.degenerate[: 4 * worst]],
            "degenerate_min_angle_deg": float(self.min_angle_threshold),
            "degenerate_short_edge": float(self.short_edge_threshold),
            "straightest_corner_deg": _min(self.straight_corner),
            "input_straightest_corner_deg": _min(self.input_straight_corner),
            "straight_corner_faces": int(self.straight_corner_faces.size),
            "straight_corner_face_indices": [int(f) for f in
                                             self.straight_corner_faces[: 4 * worst]],
            "straight_corner_deg": float(self.straight_corner_threshold),
            "worst_planarity_faces": p.worst_faces(worst),
        }
        return json_safe(report)


def _shape(mesh, xyz_input, threads):
    n = mesh.n_faces
    angle, area = np.empty(n), np.empty(n)
    change = np.empty(n) if xyz_input is not None else None
    try:
        _core.face_shape(
            mesh.vertices,
            mesh.face_start,
            mesh.face_vertices,
            xyz_input,
            angle,
            area,
            change,
            threads=int(threads or 0),
        )
    except _core.CoreError as exc:
        raise from_core(exc, source=mesh.info.get("source") if mesh.info else None) from exc
    return np.degrees(angle), area, change


def _edge_vectors(mesh):
    """Each face corner's edge to the next corner of its face, model units."""
    fv = mesh.face_vertices
    return mesh.vertices[fv[next_corners(mesh.face_start)]] - mesh.vertices[fv]


def _straightest_corners(mesh, after):
    """Per face, the least angle (degrees) between the edges into and out of one
    of its corners (`after`: _edge_vectors): 0 at a corner on a straight line. A
    corner beside an edge of no length turns 180 (the face is degenerate for its
    short edge)."""
    fs = mesh.face_start
    before = np.empty_like(after)  # the edge into each corner: the previous corner's
    before[1:] = after[:-1]
    before[fs[:-1]] = after[fs[1:] - 1]
    den = np.linalg.norm(before, axis=1) * np.linalg.norm(after, axis=1)
    cos = np.einsum("ij,ij->i", before, after) / np.where(den > 0.0, den, 1.0)
    turn = np.where(den > 0.0, np.degrees(np.arccos(np.clip(cos, -1.0, 1.0))), 180.0)
    return np.minimum.reduceat(turn, fs[:-1])


def straight_corner_faces(mesh, threshold=DEFAULT_STRAIGHT_CORNER):
    """Indices of the faces of ``mesh`` with a nearly straight corner (one that turns the
    outline by less than ``threshold`` degrees), as :class:`QualityReport` counts them,
    without the rest of the quality measures."""
    return np.flatnonzero(_straightest_corners(mesh, _edge_vectors(mesh)) < float(threshold))


def _shortest_edges(mesh, after):
    """The shortest edge of each face (`after`: _edge_vectors), model units."""
    return np.minimum.reduceat(np.linalg.norm(after, axis=1), mesh.face_start[:-1])


def quality(result, input=None, reference=None, threads=None, min_angle=DEFAULT_MIN_ANGLE,
            progress=None, straight_corner=DEFAULT_STRAIGHT_CORNER):
    """Measure the quality of `result` (a mesh, or what :func:`facet.planarize` returned).

    Parameters
    ----------
    result : PolyMesh or PlanarizeResult
        The mesh to measure (``result.mesh`` of a PlanarizeResult).
    input : PolyMesh, optional
        The mesh `result` was made from, with the same faces: gives
        displacement, ratio change and (without `reference`) the surface.
    reference : Surface or PolyMesh, optional
        The design surface distances are measured to.
    threads : int, optional
        OpenMP threads; the figures do not depend on it.
    min_angle : float
        Faces with a smaller interior angle (degrees) are degenerate.
    progress : callable, optional
        ``progress(done, total)`` while distances are measured (the long
        part); a true return value cancels (:class:`facet.Cancelled`).
    straight_corner : float
        Faces with a corner that turns the outline by less than this
        (degrees) have a nearly straight corner.

    Returns
    -------
    QualityReport

    Raises
    ------
    facet.InputError
        When `input` has another topology, or `min_angle` or `straight_corner`
        is not a number in [0, 180).
    """
    mesh = getattr(result, "mesh", result)
    if not isinstance(mesh, PolyMesh):
        raise InputError(f"quality: result must be a PolyMesh or a PlanarizeResult, not "
                         f"{type(result).__name__}")
    for name, value in (("min_angle", min_angle), ("straight_corner", straight_corner)):
        try:
            angle_ok = 0.0 <= float(value) < 180.0
        except (TypeError, ValueError):
            angle_ok = False
        if not angle_ok:
            raise InputError(f"{name} must be a number in [0, 180) degrees, not {value!r}")
    if input is not None and not mesh.same_topology(input):
        raise InputError(
            f"input has another topology ({input.n_vertices} vertices, {input.n_faces} faces) "
            f"than the result ({mesh.n_vertices} vertices, {mesh.n_faces} faces)"
        )
    report = getattr(result, "planarity", None)
    if not isinstance(report, PlanarityReport):
        report = planarity(mesh, threads=threads)
    xyz_input = None if input is None else input.vertices
    angle, area, change = _shape(mesh, xyz_input, threads)
    input_angle = input_straight = None
    displacement = None
    if input is not None:
        displacement = np.linalg.norm(mesh.vertices - input.vertices, axis=1)
        input_angle, _, _ = _shape(input, None, threads)
        input_straight = _straightest_corners(input, _edge_vectors(input))
    surface = reference
    if surface is None and input is not None:
        surface = Surface(input)
    elif isinstance(surface, PolyMesh):
        surface = Surface(surface)
    distance = None
    if surface is not None:
        if not isinstance(surface, Surface):
            raise InputError(f"reference must be a Surface or a PolyMesh, not "
                             f"{type(reference).__name__}")
        _, distance, _, _ = surface.closest(mesh.vertices, threads=threads, progress=progress)
    degrees = np.diff(mesh.face_start)
    # squared mean edge from the planarity report: zero area relative to the face's size
    size2 = report.mean_edge**2 * np.maximum(degrees, 3)
    edges = _edge_vectors(mesh)
    short = _shortest_edges(mesh, edges) < DEFAULT_SHORT_EDGE * report.mean_edge
    degenerate = np.flatnonzero((area <= _ZERO_AREA * size2) | (angle < float(min_angle)) | short)
    return QualityReport(
        planarity=report,
        displacement=displacement,
        distance=distance,
        min_angle=angle,
        area=area,
        ratio_change=change,
        degenerate=degenerate.astype(np.int64),
        min_angle_threshold=float(min_angle),
        input_min_angle=input_angle,
        mesh=mesh,
        straight_corner=_straightest_corners(mesh, edges),
        straight_corner_threshold=float(straight_corner),
        input_straight_corner=input_straight,
    )
