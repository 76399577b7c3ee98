# SPDX-License-Identifier: LGPL-2.1-or-later
"""Planarization: the nearest mesh whose faces are flat.

The solver is the penalty method of Poranne, Ovreiu and Gotsman (2013) in the
compiled core, as local/global (``"lg"``: one sparse solve per iteration) or
local/local (``"ll"``: the cheapest iteration, no sparse factorization; it
finishes with its data term anchored at the iterate, so it also reaches
1e-6). ``"auto"``, the default, picks L/G up to 10,000 quads (40,000 face
corners) and L/L above, where L/L reaches the tolerance 6-165 times faster, as
close to the design, in under 1 KB per face (L/G: 1.3-1.8 KB). Without the
staircase schedule (``hold_tol`` 0), with which L/L cannot finish, L/G goes on
up to 50,000 quads. Up to 160,000 quads, when L/L's result keeps a closed panel
or stalls above the tolerance, auto solves by L/G too and keeps that result if
it is planar with fewer closed panels (``STAGE_FALLBACK``).

>>> result = planarize(mesh)                   # doctest: +SKIP
>>> result.planarity.max_rel_all <= 1e-6       # doctest: +SKIP
True
"""

import math
from dataclasses import dataclass, field

import numpy as np

from facet import _core
from facet.errors import Cancelled, FacetError, InputError, MeshError, from_core
from facet.planarity import PlanarityReport, planarity

_INT32_MAX = 2**31 - 1

#: The deepest Anderson history (the ``anderson`` option).
ANDERSON_MAX = _core.ANDERSON_MAX

__all__ = ["METHODS", "STAGE_COMPARE", "STAGE_FINER", "STAGE_FALLBACK", "ANDERSON_MAX", "Planarizer",
           "PlanarizeResult", "planarize"]

#: Solver schemes by name: what the command line and the workbench offer.
#: "auto" solves by local/global up to 10,000 quads and also by local/local,
#: returning the result closer to the design (PlanarizeResult.compared); by
#: local/local alone above.
METHODS = {"auto": "automatic (local/global and local/local up to 10,000 quads, the result "
                   "closer to the design; local/local above)",
           "lg": "local/global", "ll": "local/local"}

#: The `stage` callable's first argument during method "auto"'s comparison
#: solve by local/local (facet.h, FACET_STAGE_COMPARE).
STAGE_COMPARE = _core.STAGE_COMPARE

#: The `stage` callable's first argument during method "auto"'s L/G solve
#: with a finer hold, which follows the comparison when L/L's result was
#: closer but moved the vertices too far (facet.h, FACET_STAGE_FINER).
STAGE_FINER = _core.STAGE_FINER

#: The `stage` callable's first argument during method "auto"'s local/global
#: solve after local/local's result kept a closed panel or stalled above the
#: tolerance, on meshes of 10,000 to 160,000 quads (facet.h,
#: FACET_STAGE_FALLBACK).
STAGE_FALLBACK = _core.STAGE_FALLBACK

#: Data-term presets: how strongly a vertex is held to its control position
#: along the control surface (tangent) and across it (normal), and to the
#: design surface itself (surface). "plane" and "surface" let vertices slide
#: along the design, which brings the result much closer to it, and add a
#: mild as-similar-as-possible term so that panels do not degenerate while
#: sliding (pass shape="none" to drop it). Measured, L/G to 1e-6, RMS
#: distance from the input surface in mean edges (smallest panel angle):
#: tubemesh point 0.139 (27.5 deg), plane 0.115 (34.0), surface 0.075
#: (23.0); hypar point 0.088 (47.4), plane 0.025 (16.5), surface 0.036 (14.3).
DATA_TERMS = {
    "point": {"data_tangent": 1.0, "data_normal": 1.0, "surface_weight": 0.0},
    "plane": {"data_tangent": 0.01, "data_normal": 1.0, "surface_weight": 0.0,
              "shape": "asap", "shape_weight": 0.1},
    "surface": {"data_tangent": 0.01, "data_normal": 0.0, "surface_weight": 1.0,
                "shape": "asap", "shape_weight": 0.1},
}

def preset_shape(shape, data):
    """The shape term a solve runs with: `shape` when given (not None), else the `data`
    preset's (:data:`DATA_TERMS`), else "none"."""
    return shape if shape is not None else DATA_TERMS.get(data or "", {}).get("shape", "none")


#: The solver's terms beyond the schedule, with their value types (see
#: facet.h, facet_planarize_options, for their meaning).
TERMS = {
    "data_tangent": float,
    "data_normal": float,
    "surface_weight": float,
    "laplacian": float,
    "laplacian_weights": ("uniform", "inverse_edge"),
    "normal_laplacian": float,
    "boundary_fairness": float,
    "shape": ("none", "asap", "arap"),
    "shape_weight": float,
    "boundary": ("free", "fixed", "sliding"),
    "circular": float,
    "parallelogram": float,
    "angle_floor": float,
    "quality_angle": float,
    "anderson": int,
    "hold_tol": float,
    "hold_max": int,
    "time_budget": float,
}

#: A term's weight may be at most this many times data_tangent (facet.h,
#: FACET_WEIGHT_SPAN); a face weight at most FACE_WEIGHT_MAX.
WEIGHT_SPAN = _core.WEIGHT_SPAN
FACE_WEIGHT_MAX = _core.FACE_WEIGHT_MAX


def _check_weight_span(options, data, face_weights):
    """The core's limits on weights (facet.h, FACET_WEIGHT_SPAN and FACET_FACE_WEIGHT_MAX),
    said with the names the designer set them by: the preset's data_tangent, not its own
    name, is what a --data plane or surface user never typed."""
    tangent = options.get("data_tangent", 1.0)
    if not (isinstance(tangent, float) and tangent > 0.0 and math.isfinite(tangent)):
        return  # (the core names it)
    for name in ("data_normal", "surface_weight", "laplacian", "normal_laplacian",
                 "boundary_fairness", "shape_weight", "circular", "parallelogram"):
        value = options.get(name)
        if name == "shape_weight" and options.get("shape", "none") == "none":
            continue  # not read
        if isinstance(value, float) and math.isfinite(value) and value > WEIGHT_SPAN * tangent:
            source = f"data={data!r} sets" if data is not None and "data_tangent" in \
                DATA_TERMS.get(data, {}) else "with"
            raise InputError(
                f"{name} {value:g} is too large: at most {WEIGHT_SPAN:g} times data_tangent "
                f"({source} data_tangent {tangent:g}), so at most {WEIGHT_SPAN * tangent:g}; "
                "beside a larger weight the data term is lost to rounding")
    if face_weights is not None:
        try:
            w = np.asarray(face_weights, dtype=np.float64).ravel()
        except (TypeError, ValueError):
            return  # (the core names it)
        over = np.flatnonzero(w > FACE_WEIGHT_MAX)
        if over.size:
            raise InputError(f"face_weights: face {over[0]} has weight {w[over[0]]:g}; at "
                             f"most {FACE_WEIGHT_MAX:g}")


#: First penalty weight of a warm re-solve: small, so the previous (planar)
#: result is not pulled back to the edited control mesh first.
_WARM_MU0 = {"auto": 1e-5, "lg": 1e-5, "ll": 1e-5}

#: Schedule of a live update: its region's control (the previous result moved
#: by the edit) is nearly planar already, so it starts at a small penalty
#: weight and lowers it every step (tools/bench/interactive.py measured
#: 2-3 times fewer iterations than the staircase).
_LIVE_SCHEDULE = {"mu0": 1e-3, "hold_tol": 0.0}


@dataclass
class PlanarizeResult:
    """What a planarization produced.

    Attributes
    ----------
    mesh : facet.PolyMesh
        The planarized mesh: same faces, new vertex positions.
    method : str
        The method that ran: ``"lg"`` or ``"ll"`` (what ``"auto"`` chose).
    iterations : int
        Iterations run.
    stop_reason : str
        ``"tolerance"`` (reached), ``"max_iter"``, ``"iterations"`` (a fixed
        count was asked for), ``"stagnation"`` (no more progress) or ``"time"``
        (the ``time_budget`` ran out first).
    converged : bool
        Whether the tolerance was reached.
    solve_seconds : float
        Wall time of the compiled solve alone.
    planarity : PlanarityReport
        Planarity of the result.
    displacement : numpy.ndarray
        Distance each vertex moved, model units.
    options : dict
        The options the solve ran with.
    warnings : list of str
        Facts about the input worth telling (non-manifold edges...).
    constraint_max_rel : float
        Largest residual of the circular, parallelogram and sliding
        constraints, relative to the mean edge (0 when none is on).
    anderson : tuple of int
        Accelerated steps (kept, refused by the energy safeguard).
    quality_check : str
        Whether the solve checked its result for new narrow corners (a
        corner below ``quality_angle``, 5 degrees by default, that the
        input did not have; a panel folded over itself, a bowtie, that the
        input did not have counts as one) and what it did: ``"not_checked"`` (off, warm,
        live, a fixed iteration count, the angle floor on, or not
        converged), ``"ok"`` (none), ``"recovered"`` (the first result had
        one; a re-solve along the penalty path has none) or ``"narrow"``
        (every re-solve left one, the solve was stopped before one kept
        them open: ``stopped``, or the time budget ended the re-solves:
        ``quality_timed_out``; the best result is returned).
    narrow_corners : int
        New narrow corners in the result (also counted, with the check on,
        when the solve stopped short of the tolerance, which is not
        re-solved: ``quality_check`` is then ``"not_checked"``).
    quality_resolves : int
        Re-solves run after the first solve (``iterations`` counts them all).
    quality_timed_out : bool
        ``quality_check`` is ``"narrow"`` because ``time_budget`` ended the
        re-solves, not because they all left a narrow corner.
    first_iterations : int
        Iterations of the first solve.
    threads : int
        Threads the solve ran on: ``threads`` when given, else one per
        100,000 face corners (25,000 quads), at most OpenMP's default (a
        live update: its region's size decides).
    compared : dict or None
        Method ``"auto"``'s comparison, where it picked L/G: it also solved
        by L/L and returned the result closer to the design (``method`` says
        whose), unless L/L's had a narrower smallest corner (below L/G's and
        10 degrees), a shorter shortest edge (below L/G's and a quarter of
        its input length), more new narrow corners, or (with point data)
        moved the vertices more than 5% further than L/G's. ``{"iterations":
        n, "lg": {"distance_rms": d, "displacement_rms": m, "min_angle": a,
        "edge_ratio": e}, "ll": {...}}``: the L/L solve's iterations (counted
        in ``iterations``), and each result's RMS distance from the input
        surface and RMS vertex displacement (model units), smallest corner
        angle (degrees) and shortest edge relative to its input length; the
        two dicts are empty when L/L did not reach the tolerance. When L/L's
        result was refused only for moving the vertices further, L/G solved
        again with a finer hold (``hold_tol`` times 0.3): ``"finer":
        {"iterations": n, "kept": bool}``, and when kept, ``"lg"`` holds
        that result's figures (it was closer, its corners and edges as good,
        its vertices moved no more than 5% further); else ``"finer"`` is
        None. None when no comparison ran
        (another method, a warm start, a fixed iteration count, the paper's
        schedule (``hold_tol`` 0), a shape term or a regularizer).
    stopped : bool
        True for the result a stopped solve had reached
        (:class:`facet.Cancelled`'s ``result``): what was still running (a
        quality re-solve, the comparison) did not finish; ``iterations``
        and ``quality_resolves`` count it too, and ``compared`` is None.
    data_tangent : float or None
        The ``data_tangent`` the result was solved with: the options' own,
        unless every re-solve along the penalty path closed a panel while
        vertices slid along the design (plane or surface data) and a last
        re-solve kept every corner open by holding them three or ten times
        more firmly along it (at most as firmly as ``data_normal`` or
        ``surface_weight``); ``quality_check`` is then ``"recovered"``.
    control : facet.PolyMesh or None
        The control mesh the result was solved from.
    reference : facet.Surface or None
        The design surface the solve was held to, if any.
    reference_given : bool
        Whether that surface was given (``reference=``), not the control mesh's own.
    data : str or None
        The data preset asked for (``data=``).
    """

    mesh: object
    method: str
    iterations: int
    stop_reason: str
    converged: bool
    solve_seconds: float
    planarity: PlanarityReport
    displacement: np.ndarray
    options: dict = field(default_factory=dict)
    warnings: list = field(default_factory=list)
    constraint_max_rel: float = 0.0
    anderson: tuple = (0, 0)
    quality_check: str = "not_checked"
    narrow_corners: int = 0
    quality_resolves: int = 0
    first_iterations: int = 0
    threads: int = 0
    compared: object = None
    stopped: bool = False
    quality_timed_out: bool = False
    data_tangent: float = None
    control: object = None
    reference: object = None
    reference_given: bool = False
    data: str = None
    _quality: object = field(default=None, repr=False)

    @property
    def quality(self):
        """The quality report of the result against its control mesh
        (:func:`facet.quality`), computed on first use."""
        if self._quality is None and self.control is not None:
            from facet.quality import quality

            self._quality = quality(self.mesh, input=self.control, reference=self.reference)
        return self._quality

    @property
    def displacement_max(self):
        """Largest vertex displacement, model units."""
        return float(self.displacement.max()) if self.displacement.size else 0.0

    @property
    def displacement_rms(self):
        """RMS vertex displacement, model units."""
        if not self.displacement.size:
            return 0.0
        return float(np.sqrt(np.mean(self.displacement**2)))


def _check_reference(surface, control, source=None):
    """Refuse a reference surface the mesh cannot mean: one with no area, or one farther
    from a vertex than the mesh is wide (another unit, another place: the solve pulls
    every vertex onto it, and reports the tolerance reached). Returns a warning when the
    vertices are, in RMS, more than a mean edge from it (they are pulled onto it)."""
    where = f"{source}: " if source else ""
    xyz = np.asarray(control.vertices, dtype=np.float64)
    used = np.unique(np.asarray(control.face_vertices))
    _, distance, _, normal = surface.closest(xyz[used])
    if not np.any(normal):
        raise InputError(f"{where}the reference surface has no area: each of its triangles "
                         "is a point or a line")
    low, high = xyz[used].min(axis=0), xyz[used].max(axis=0)
    size = float(np.linalg.norm(high - low))
    far = int(np.argmax(distance))
    if distance[far] > size:
        raise InputError(
            f"{where}the reference surface is {distance[far]:.6g} from vertex {int(used[far])}, "
            f"farther than the mesh is wide ({size:.6g}): is it in other units or in another "
            "place? Every vertex would be pulled onto it")
    edge = control.mean_edge_length()
    rms = float(np.sqrt(np.mean(distance**2)))
    if edge and rms > edge:
        return [f"the vertices are {rms:.4g} from the reference surface (RMS, {rms / edge:.3g} "
                "mean edges): they are pulled onto it"]
    return []


def _mesh_warnings(report):
    warnings = []
    if report.get("n_non_manifold_edges"):
        a, b = report["first_non_manifold_edge"]
        n = report["n_non_manifold_edges"]
        warnings.append(
            f"{n} non-manifold edge{'s' if n != 1 else ''} "
            f"(more than two faces meet at edge {a}-{b})"
        )
    if report.get("n_isolated_vertices"):
        warnings.append(
            f"{report['n_isolated_vertices']} isolated vertices (first: vertex "
            f"{report['first_isolated_vertex']}); they are kept where they are"
        )
    return warnings


def _coincident_warnings(mesh):
    """Warnings for faces that repeat another (two panels at one place), and for vertices at
    one point that are not one vertex (faces given their own copies by the export): the
    faces there are planarized apart and the seam opens."""
    from facet.mesh import duplicate_faces, unwelded_warning

    warnings = []
    n_copies, first = duplicate_faces(mesh)
    if n_copies:
        warnings.append(
            f"{n_copies} face{'s' if n_copies != 1 else ''} with the same vertices as another "
            f"(first: face {first[1]} repeats face {first[0]}): two panels at one place; "
            "remove the copies")
    seam = unwelded_warning(mesh, "the faces there are not joined, each is made planar on "
                                  "its own and the seam opens")
    return warnings if seam is None else warnings + [seam]


class Planarizer:
    """A planarization solver kept for one mesh topology.

    It keeps the solver's workspace (face planes, the sparse factorization's
    analysis), so re-solving after the designer moved vertices is cheap and,
    with ``warm=True``, starts from the previous result.

    Parameters
    ----------
    mesh : facet.PolyMesh
        Gives the topology; validated here.

    Raises
    ------
    facet.MeshError
        When the mesh is not valid (the message names the face or vertex).
    """

    def __init__(self, mesh):
        self._source = mesh.info.get("source") if mesh.info else None
        report = mesh.validate()
        self._warnings = _mesh_warnings(report) + _coincident_warnings(mesh)
        self._topology = mesh
        degrees = np.diff(np.asarray(mesh.face_start))
        self._quads = bool(degrees.size) and np.count_nonzero(degrees == 4) * 2 > degrees.size
        # what the last solve was asked (its result reports them)
        self._data, self._reference_given, self._reference_warnings = None, False, []
        self._exempt = None
        try:
            self._core = _core.Planarizer(mesh.face_start, mesh.face_vertices, mesh.n_vertices)
        except _core.CoreError as exc:
            raise from_core(exc, source=self._source) from None
        self._solved = False

    @property
    def mesh(self):
        """The mesh whose topology this solver holds."""
        return self._topology

    def solve(
        self,
        vertices=None,
        *,
        method="auto",
        tol=1e-6,
        tol_abs=None,
        max_iter=None,
        iterations=None,
        threads=None,
        warm=False,
        live=False,
        rings=None,
        progress=None,
        stage=None,
        mu0=None,
        ratio=None,
        mu_min=None,
        data=None,
        reference=None,
        fixed=None,
        face_weights=None,
        **terms,
    ):
        """Planarize control positions with this solver's topology.

        Parameters
        ----------
        vertices : array_like (n, 3) or PolyMesh, optional
            Control positions (default: the mesh given at construction).
        method : {"auto", "lg", "ll"}
            Automatic (default: local/global up to 40,000 face corners, or
            200,000 with ``hold_tol`` 0, local/local above), local/global or
            local/local.
        tol : float or None
            Stop when every face's largest distance from its plane, divided by
            its mean edge length, is at most `tol` (default 1e-6). None or 0
            turns the relative test off.
        tol_abs : float, optional
            Stop when every face's largest distance from its plane is at most
            this, in model units. With `tol` as well, both must hold.
        max_iter : int, optional
            Iteration limit (default 1000 for auto and lg, 3000 for ll).
        iterations : int, optional
            Run exactly this many iterations with no early stop (benchmarks).
        threads : int, optional
            OpenMP threads (default: all). The result is the same bits for any
            count.
        warm : bool
            Start from the previous result of this solver (live editing).
        live : bool
            A live update while the designer drags control vertices: only the
            vertices whose control position changed since the last solve, and
            their neighbourhood `rings` edges deep (default 4), are re-solved,
            from the previous result moved by the edit; every other vertex
            keeps its previous position exactly, and the region grows when it
            cannot reach `tol` (``facet_planarizer_update`` in facet.h).
            Much cheaper than a warm re-solve; finish a drag with a full
            solve for the globally optimal result. The first solve of a
            solver is always a full one.
        rings : int, optional
            Depth of the live region (default 4).
        progress : callable, optional
            ``progress(iteration, max_iter, planarity_max_rel)``, called once
            per iteration; returning True cancels. The quality re-solves
            (``quality_angle``) count as part of one solve: `iteration` runs
            on through them up to the result's ``iterations``, and
            `max_iter` bounds the whole solve (the limits of the re-solves
            that may still follow included); it never grows, so
            ``iteration / max_iter`` never falls.
        stage : callable, optional
            ``stage(STAGE_COMPARE, stages)`` when method "auto"'s comparison
            solve by local/local starts, ``stage(STAGE_FINER, stages)``
            when its local/global solve with a finer hold starts (see
            ``compared``) and ``stage(STAGE_FALLBACK, stages)`` when its
            local/global solve after a local/local result with a closed panel
            starts; else
            ``stage(stage, stages)``, called when a quality re-solve starts
            (before its first `progress` call): the `stage`-th of at most
            `stages` (4, or up to 5 when vertices slide along the design: 5
            with the presets; they stop at the first that recovers), for a
            progress text such as
            "re-solving for panel quality (stage 2 of 4)". Exceptions it
            raises stop the solve and propagate.
        mu0, ratio, mu_min : float, optional
            The penalty schedule: first weight, factor per step, floor.
        data : {"point", "plane", "surface"}, optional
            The data term (:data:`DATA_TERMS`): distance to the control
            points (default), to their tangent planes, or to the design
            surface (vertices slide along it but do not leave it).
        reference : facet.Surface or facet.PolyMesh, optional
            The design surface of ``data="surface"`` (default: the control
            mesh's own surface).
        fixed : array_like of int, optional
            Vertices held exactly at their control positions.
        face_weights : array_like of float, optional
            Per-face planarity weights in [0, 1e6] (0 exempts a face: an opening).
        **terms
            Any of :data:`TERMS` (each weight at most 1e12 times ``data_tangent``:
            beside a larger one the data term is lost to rounding): regularizers (``laplacian``,
            ``laplacian_weights``, ``normal_laplacian``,
            ``boundary_fairness``, ``shape`` "asap"/"arap" with
            ``shape_weight``), constraints (``boundary``
            "free"/"fixed"/"sliding", ``circular``, ``parallelogram``), the
            data weights, and ``anderson``, ``hold_tol``, ``hold_max``,
            ``time_budget`` (seconds), ``quality_angle`` (degrees, 5; 0
            turns off the re-solve of a result with a new narrow corner).

        Returns
        -------
        PlanarizeResult

        Raises
        ------
        facet.Cancelled
            When `progress` returned True. Cancelled after the solve had a
            result at the tolerance (in a quality re-solve, or in method
            "auto"'s comparison or fallback solve), its ``result`` is that
            result: the one returned had the solve still running found
            nothing better (a PlanarizeResult; its ``quality_check`` and
            ``narrow_corners`` say what the re-solves had not yet
            mended); else ``result`` is None.
        facet.FacetError
            When an option is out of range or the solve failed numerically.
        """
        if method not in METHODS:
            raise FacetError(f"unknown method {method!r}: use one of {', '.join(METHODS)}")
        if vertices is None:
            control = self._topology
        elif hasattr(vertices, "vertices"):
            if not self._topology.same_topology(vertices):
                raise MeshError(
                    "the mesh to planarize does not have the solver's faces", source=self._source
                )
            control = vertices
        else:
            control = self._topology.with_vertices(vertices)
        if iterations is not None:
            iterations = _count("iterations", iterations)
            if iterations <= 0:
                raise FacetError(f"iterations must be a positive count, not {iterations}")
        options = {"method": method}
        for name, value in (("mu0", mu0), ("ratio", ratio), ("mu_min", mu_min)):
            if value is not None:
                options[name] = float(value)
        if warm and self._solved and mu0 is None:
            options["mu0"] = _WARM_MU0[method]
        live = bool(live and self._solved)
        if live:
            for name, value in _LIVE_SCHEDULE.items():
                if name not in options and name not in terms:
                    options[name] = value
        for name, value in (("tol", tol), ("tol_abs", tol_abs)):
            if value is not None and not 0.0 <= _number(name, value) < float("inf"):
                raise FacetError(f"{name} must be a finite number >= 0 (0 or None: not "
                                 f"used), not {value!r}")
        options["tol_rel"] = float(tol) if tol else 0.0
        options["tol_abs"] = float(tol_abs) if tol_abs else 0.0
        if max_iter is not None:
            options["max_iter"] = _count("max_iter", max_iter)
        if iterations is not None:
            options["iterations"] = iterations
        # any whole number: <= 0 by mesh size (docs/CONTRACTS.md), the rest capped by the core
        threads = options["threads"] = max(0, min(_whole("threads", threads or 0), _INT32_MAX))
        unknown = set(terms) - set(TERMS)
        if unknown:
            raise TypeError(f"unknown solver option(s): {', '.join(sorted(unknown))}")
        if data is not None:
            if data not in DATA_TERMS:
                raise FacetError(f"unknown data term {data!r}: use one of {', '.join(DATA_TERMS)}")
            options.update(DATA_TERMS[data])
        for name, value in terms.items():
            kind = TERMS[name]
            if isinstance(kind, tuple):
                if value not in kind:
                    raise FacetError(f"{name} must be one of {', '.join(kind)}, not {value!r}")
                options[name] = value
            elif kind is int:
                options[name] = _count(name, value, ANDERSON_MAX if name == "anderson" else None)
            else:
                options[name] = kind(value)
        _check_weight_span(options, data, face_weights)
        self._data, self._reference_given = data, reference is not None
        if terms.get("shape_weight") and options.get("shape", "none") == "none":
            raise FacetError(
                "shape_weight weighs the shape term, which is off "
                + (f"(data={data!r} sets no shape)" if data is not None and "shape" not in terms
                   else "(shape='none')")
                + ": pass shape='asap' or 'arap' with it, or leave it out")
        surface = None
        if reference is not None and not options.get("surface_weight", 0.0) > 0.0:
            raise FacetError("reference is the design surface of data='surface' (or a "
                             "surface_weight > 0); with these options it would be ignored")
        if options.get("surface_weight", 0.0) > 0.0:
            from facet.surface import Surface

            surface = reference if reference is not None else control
            if not isinstance(surface, Surface):
                surface = Surface(surface)
            info = getattr(reference, "info", None) or {}
            self._reference_warnings = ([] if reference is None else
                                        _check_reference(surface, control, info.get("source")))
            self._core.set_reference(surface._core)
        else:
            self._reference_warnings = []
            self._core.set_reference(None)
        try:
            self._core.set_fixed(None if fixed is None else _vertex_indices("fixed", fixed))
            self._core.set_face_weights(
                None if face_weights is None
                else np.ascontiguousarray(face_weights, dtype=np.float64).ravel()
            )
        except _core.CoreError as exc:
            raise from_core(exc, source=self._source) from None
        except ValueError as exc:
            raise FacetError(str(exc)) from None
        # exempt faces (weight 0) are not made planar: left out of the figures
        self._exempt = (None if face_weights is None else
                        np.asarray(face_weights, dtype=np.float64).ravel() == 0.0)
        if self._exempt is not None and not self._exempt.any():
            self._exempt = None
        elif self._exempt is not None and self._exempt.all():
            raise InputError("face_weights: every face is exempt (weight 0), so there is "
                             "nothing to make planar")
        if fixed is not None and len(fixed):
            used = np.unique(np.asarray(control.face_vertices))
            if np.isin(used, np.asarray(fixed)).all():
                raise InputError(f"fixed holds every vertex of the faces ({used.size}): no "
                                 "vertex can move, so no face can be made flat")
        xyz_in = control.vertices
        xyz_out = np.empty_like(xyz_in)
        try:
            stats = self._core.solve(
                xyz_in, xyz_out, warm=bool(warm and self._solved), progress=progress,
                stage=stage, live=live, rings=_count("rings", rings or 0), **options
            )
        except _core.CoreError as exc:
            error = from_core(exc, source=self._source)
            kept = getattr(exc, "result", None)  # cancelled after a planar result (the core's)
            if isinstance(error, Cancelled) and kept is not None:
                self._solved = True
                error.result = self._result(control, xyz_out, kept, options, threads, surface,
                                            stopped=True)
            raise error from None
        self._solved = True
        return self._result(control, xyz_out, stats, options, threads, surface)

    def _result(self, control, xyz_out, stats, options, threads, surface, stopped=False):
        """The PlanarizeResult of the core's figures `stats` for the vertices xyz_out
        (`stopped`: what a stopped solve had reached)."""
        result_mesh = control.with_vertices(xyz_out)
        displacement = np.linalg.norm(xyz_out - control.vertices, axis=1)
        measured = planarity(result_mesh, threads=threads).leaving_out(self._exempt)
        return PlanarizeResult(
            mesh=result_mesh,
            method=stats["method"],
            iterations=stats["iterations"],
            stop_reason=stats["stop_reason"],
            converged=stats["converged"],
            solve_seconds=stats["seconds"],
            planarity=measured,
            displacement=displacement,
            options=options,
            warnings=(list(self._warnings) + list(self._reference_warnings)
                      + _quality_warnings(stats, options, stopped, self._quads)
                      + _precision_warnings(stats, options, result_mesh, measured)
                      + _outline_warnings(control, xyz_out, options, surface,
                                          self._data)),
            constraint_max_rel=stats["constraint_max_rel"],
            anderson=(stats["anderson_accepted"], stats["anderson_rejected"]),
            quality_check=stats["quality"],
            narrow_corners=stats["narrow_corners"],
            quality_resolves=stats["quality_resolves"],
            first_iterations=stats["first_iterations"],
            threads=int(stats.get("threads", 0)),
            compared=None if stopped else _compared(stats),
            stopped=stopped,
            quality_timed_out=bool(stats.get("quality_timed_out", False)),
            data_tangent=float(stats["data_tangent"]),
            control=control,
            reference=surface,
            reference_given=self._reference_given,
            data=self._data,
        )


def _count(name, value, most=None):
    """A whole-number option as given: refused (FacetError naming it) when it is not a whole
    number from 0 to `most` (default 2**31 - 1), rather than cut (6.9 -> 6) or wrapped
    around."""
    most = _INT32_MAX if most is None else most
    number = _whole(name, value)
    if not 0 <= number <= most:
        raise FacetError(f"{name} must be from 0 to {most}, not {number}")
    return number


def _number(name, value):
    try:
        return float(value)
    except (TypeError, ValueError):
        raise FacetError(f"{name} must be a number, not {value!r}") from None


def _whole(name, value):
    """`value` as an int, refused (FacetError naming `name`) unless it is a whole number."""
    if isinstance(value, (bool, np.bool_)):
        raise FacetError(f"{name} must be a whole number, not {value!r}")
    try:
        number = int(value)
        whole = number == value
    except (TypeError, ValueError, OverflowError):
        whole = False
    if not whole:
        raise FacetError(f"{name} must be a whole number, not {value!r}")
    return number


def _vertex_indices(name, values):
    """Vertex indices for the core (int32, 1-D), refused unless they are whole numbers in
    the 32-bit range (the core then refuses one beyond the mesh): a cast would pin other
    vertices than the ones meant (6.9 -> 6, 2**32 + 3 -> 3, a mask -> 0 and 1)."""
    array = np.asarray(values)
    if array.size == 0:
        return np.zeros(0, dtype=np.int32)
    if array.dtype.kind == "b":
        raise FacetError(f"{name} takes vertex indices, not a mask of booleans "
                         "(np.flatnonzero(mask) gives the indices)")
    if array.dtype.kind not in "iu":
        if array.dtype.kind != "f" or not np.all(np.isfinite(array)) or np.any(array % 1):
            raise FacetError(f"{name} takes vertex indices (whole numbers), not {array.dtype} "
                             "values")
    if array.min() < -_INT32_MAX - 1 or array.max() > _INT32_MAX:
        raise FacetError(f"{name} holds indices beyond the 32-bit range "
                         f"({array.min()} .. {array.max()})")
    return np.ascontiguousarray(array, dtype=np.int32).ravel()


def _precision_warnings(stats, options, mesh, measured):
    """A warning when the solve reached its tolerance (in the solver's centred and scaled
    coordinates) but the result, in the model's own coordinates, is well above it: float64
    cannot hold these panels planar so far from the origin (a 1 m panel at 1e12 m
    carries about 1e-4 of its size in rounding)."""
    if not stats["converged"] or not mesh.n_faces:
        return []
    over = []
    if options["tol_rel"] > 0 and measured.max_rel_all > 2.0 * options["tol_rel"]:
        over.append(f"{measured.max_rel_all:.2g} of the edge (tolerance {options['tol_rel']:g})")
    if options["tol_abs"] > 0 and measured.max_abs_all > 2.0 * options["tol_abs"]:
        over.append(f"{measured.max_abs_all:.2g} model units (tolerance "
                    f"{options['tol_abs']:g})")
    if not over:
        return []
    reach = float(np.abs(mesh.vertices).max())
    return [f"the solve reached its tolerance, but in the model's coordinates the result's "
            f"planarity is {' and '.join(over)}: coordinates up to {reach:.3g} leave too few "
            f"digits for panels of {mesh.mean_edge_length():.3g}; move the model near the "
            "origin"]


def _compared(stats):
    """PlanarizeResult.compared from the core's compare_* figures."""
    if not stats.get("compare_iterations"):
        return None
    distance, angle = stats["compare_distance_rms"], stats["compare_min_angle"]
    moved, edge = stats["compare_displacement_rms"], stats["compare_edge_ratio"]
    measured = any(v > 0.0 for v in (*distance, *angle, *moved, *edge))
    finer = int(stats.get("finer_iterations", 0))
    return {"iterations": int(stats["compare_iterations"]),
            "finer": {"iterations": finer, "kept": bool(stats["finer_kept"])} if finer else None,
            **{name: ({"distance_rms": float(distance[k]), "displacement_rms": float(moved[k]),
                       "min_angle": float(angle[k]), "edge_ratio": float(edge[k])}
                      if measured else {})
               for k, name in enumerate(("ll", "lg"))}}


#: Why re-solves cannot keep a quad mesh's corners open, and the remedy (docs/solver-notes.md,
#: "The 100 x 100 hypar"): what the warning adds on meshes of mostly quads.
QUAD_LAYOUT_ADVICE = (
    "planar quads follow conjugate directions of the surface, such as its principal "
    "curvature lines; a quad mesh laid far from them (along a saddle's straight rulings, "
    "say) cannot be made planar without collapsing some panels: remesh along curvature "
    "lines there")


#: Boundary vertices farther than this many mean edges off the design surface make
#: the plane and surface presets warn (their vertices slide along it, and with a free
#: boundary they slide past its edge).
OUTLINE_DRIFT = 0.25


def _outline_warnings(control, xyz_out, options, surface, data):
    """A warning when the `plane` or `surface` preset, with a free boundary, moved boundary
    vertices off the design surface, past its edge: the facade's outline moved
    (examples/wave_facade.obj: 0.75 mean edges). ``boundary='sliding'`` keeps them on it."""
    if data not in ("plane", "surface") or options.get("boundary", "free") != "free":
        return []
    from facet.mesh import boundary_corners, next_corners

    lone = boundary_corners(control.face_start, control.face_vertices)
    corners = np.asarray(control.face_vertices)
    ends = corners[next_corners(np.asarray(control.face_start))]
    boundary = np.unique(np.concatenate([corners[lone], ends[lone]]))
    if boundary.size == 0:
        return []
    if surface is None:
        from facet.surface import Surface

        surface = Surface(control)
    distance = surface.closest(np.asarray(xyz_out)[boundary])[1]
    edge = control.mean_edge_length()
    far = int(np.argmax(distance))
    if not edge or distance[far] <= OUTLINE_DRIFT * edge:
        return []
    return [f"boundary vertices slid off the design surface, past its edge: vertex "
            f"{int(boundary[far])} by {distance[far]:.4g} ({distance[far] / edge:.2g} mean "
            f"edges); boundary='sliding' (--boundary sliding, Boundary sliding) keeps the "
            "outline on it"]


def _quality_warnings(stats, options, stopped=False, quads=False):
    """A warning when the result has corners under ``quality_angle`` that the input did not
    have: no re-solve kept them open, the solve was stopped first, or it stopped short of
    the tolerance, and is not re-solved (see PlanarizeResult.quality_check). When every
    re-solve ran and failed on a mesh of mostly quads, it says why that usually is."""
    n = int(stats.get("narrow_corners", 0))
    if not n or stats.get("quality") not in ("narrow", "not_checked"):
        return []
    angle = float(options.get("quality_angle", 5.0))
    it = "them" if n != 1 else "it"
    why = ("the solve stopped short of the tolerance, and such a result is not re-solved"
           if stats.get("quality") == "not_checked" else
           f"the solve was stopped before a re-solve kept {it} open" if stopped else
           f"the time budget ended the re-solves before one kept {it} open"
           if stats.get("quality_timed_out") else
           f"{int(stats['quality_resolves'])} re-solves did not keep {it} open")
    text = (f"{n} panel corner{'s' if n != 1 else ''} under {angle:g} degrees that the input "
            f"did not have ({why})")
    every_resolve_failed = (stats.get("quality") == "narrow" and not stopped
                            and not stats.get("quality_timed_out"))
    if quads and every_resolve_failed:
        text += f"; {QUAD_LAYOUT_ADVICE}"
    return [text]


def planarize(mesh, method="auto", tol=1e-6, tol_abs=None, max_iter=None, iterations=None,
              threads=None, progress=None, stage=None, **options):
    """Find the nearest mesh whose faces are flat.

    Parameters
    ----------
    mesh : facet.PolyMesh
        The control mesh; it is not modified.
    method, tol, tol_abs, max_iter, iterations, threads, progress, stage
        As :meth:`Planarizer.solve`.
    **options
        The schedule (``mu0``, ``ratio``, ``mu_min``), ``data``,
        ``reference``, ``fixed``, ``face_weights`` and the terms of
        :meth:`Planarizer.solve`.

    Returns
    -------
    PlanarizeResult

    Examples
    --------
    >>> result = planarize(mesh, tol=1e-6)        # doctest: +SKIP
    >>> result.planarity.max_rel_all               # doctest: +SKIP
    8.0e-07
    """
    known = {"mu0", "ratio", "mu_min", "data", "reference", "fixed", "face_weights"} | set(TERMS)
    unknown = set(options) - known
    if unknown:
        raise TypeError(f"planarize() got unexpected arguments: {', '.join(sorted(unknown))}")
    return Planarizer(mesh).solve(
        method=method,
        tol=tol,
        tol_abs=tol_abs,
        max_iter=max_iter,
        iterations=iterations,
        threads=threads,
        progress=progress,
        stage=stage,
        **options,
    )
