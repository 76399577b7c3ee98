# SPDX-License-Identifier: LGPL-2.1-or-later
"""Planarization: the nearest mesh whose faces are flat.

The solver is the penalty method of Poranne, Ovreiu and Gotsman (2013) in the
compiled core, as local/global (``"lg"``, the default: one sparse solve per
iteration, reaches 1e-6 and below) or local/local (``"ll"``: the fastest
iteration, for live previews; it stalls near 1e-5).

>>> result = planarize(mesh)                   # doctest: +SKIP
>>> result.planarity.max_rel_all <= 1e-6       # doctest: +SKIP
True
"""

from dataclasses import dataclass, field

import numpy as np

from facet import _core
from facet.errors import FacetError, MeshError, from_core
from facet.planarity import PlanarityReport, planarity

__all__ = ["METHODS", "Planarizer", "PlanarizeResult", "planarize"]

#: Solver schemes by name: what the command line and the workbench offer.
METHODS = {"lg": "local/global", "ll": "local/local"}

#: First penalty weight of a warm re-solve: small, so the previous (planar)
#: result is not pulled back to the edited control mesh first.
_WARM_MU0 = {"lg": 1e-5, "ll": 1e-5}


@dataclass
class PlanarizeResult:
    """What a planarization produced.

    Attributes
    ----------
    mesh : facet.PolyMesh
        The planarized mesh: same faces, new vertex positions.
    method : str
        ``"lg"`` or ``"ll"``.
    iterations : int
        Iterations run.
    stop_reason : str
        ``"tolerance"`` (reached), ``"max_iter"``, ``"iterations"`` (a fixed
        count was asked for) or ``"stagnation"`` (no more progress).
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


def _mesh_warnings(report):
    warnings = []
    if report.get("n_non_manifold_edges"):
        a, b = report["first_non_manifold_edge"]
        warnings.append(
            f"{report['n_non_manifold_edges']} non-manifold edges "
            f"(more than two faces meet at edge {a}-{b})"
        )
    if report.get("n_isolated_vertices"):
        warnings.append(
            f"{report['n_isolated_vertices']} isolated vertices (first: vertex "
            f"{report['first_isolated_vertex']}); they are kept where they are"
        )
    return warnings


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
        self._warnings = _mesh_warnings(report)
        self._topology = mesh
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
        method="lg",
        tol=1e-6,
        tol_abs=None,
        max_iter=None,
        iterations=None,
        threads=None,
        warm=False,
        progress=None,
        mu0=None,
        ratio=None,
        mu_min=None,
    ):
        """Planarize control positions with this solver's topology.

        Parameters
        ----------
        vertices : array_like (n, 3) or PolyMesh, optional
            Control positions (default: the mesh given at construction).
        method : {"lg", "ll"}
            Local/global (default) or local/local.
        tol : float or None
            Stop when every face's largest distance from its plane, divided by
            its mean edge length, is at most `tol` (default 1e-6). None or 0
            turns the relative test off.
        tol_abs : float, optional
            Stop when every face's largest distance from its plane is at most
            this, in model units. With `tol` as well, both must hold.
        max_iter : int, optional
            Iteration limit (default 1000 for lg, 3000 for ll).
        iterations : int, optional
            Run exactly this many iterations with no early stop (benchmarks).
        threads : int, optional
            OpenMP threads (default: all). The result is the same bits for any
            count.
        warm : bool
            Start from the previous result of this solver (live editing).
        progress : callable, optional
            ``progress(iteration, max_iter, planarity_max_rel)``, called once
            per iteration; returning True cancels.
        mu0, ratio, mu_min : float, optional
            The penalty schedule: first weight, factor per iteration, floor.

        Returns
        -------
        PlanarizeResult

        Raises
        ------
        facet.Cancelled
            When `progress` returned True.
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
        if iterations is not None and int(iterations) <= 0:
            raise FacetError(f"iterations must be a positive count, not {iterations}")
        options = {"method": method}
        for name, value in (("mu0", mu0), ("ratio", ratio), ("mu_min", mu_min)):
            if value is not None:
                options[name] = float(value)
        if warm and self._solved and mu0 is None:
            options["mu0"] = _WARM_MU0[method]
        options["tol_rel"] = float(tol) if tol else 0.0
        options["tol_abs"] = float(tol_abs) if tol_abs else 0.0
        if max_iter is not None:
            options["max_iter"] = int(max_iter)
        if iterations is not None:
            options["iterations"] = int(iterations)
        options["threads"] = int(threads or 0)
        xyz_in = control.vertices
        xyz_out = np.empty_like(xyz_in)
        try:
            stats = self._core.solve(
                xyz_in, xyz_out, warm=bool(warm and self._solved), progress=progress, **options
            )
        except _core.CoreError as exc:
            raise from_core(exc, source=self._source) from None
        self._solved = True
        result_mesh = control.with_vertices(xyz_out)
        displacement = np.linalg.norm(xyz_out - xyz_in, axis=1)
        return PlanarizeResult(
            mesh=result_mesh,
            method=method,
            iterations=stats["iterations"],
            stop_reason=stats["stop_reason"],
            converged=stats["converged"],
            solve_seconds=stats["seconds"],
            planarity=planarity(result_mesh, threads=threads),
            displacement=displacement,
            options=options,
            warnings=list(self._warnings),
        )


def planarize(mesh, method="lg", tol=1e-6, tol_abs=None, max_iter=None, iterations=None,
              threads=None, progress=None, **schedule):
    """Find the nearest mesh whose faces are flat.

    Parameters
    ----------
    mesh : facet.PolyMesh
        The control mesh; it is not modified.
    method, tol, tol_abs, max_iter, iterations, threads, progress
        As :meth:`Planarizer.solve`.
    **schedule
        ``mu0``, ``ratio``, ``mu_min``: the penalty schedule.

    Returns
    -------
    PlanarizeResult

    Examples
    --------
    >>> result = planarize(mesh, tol=1e-6)        # doctest: +SKIP
    >>> result.planarity.max_rel_all               # doctest: +SKIP
    8.0e-07
    """
    unknown = set(schedule) - {"mu0", "ratio", "mu_min"}
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
        **schedule,
    )
