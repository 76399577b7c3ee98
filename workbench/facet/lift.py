# SPDX-License-Identifier: LGPL-2.1-or-later
"""Optimal liftings of plan drawings (paper section 6.1).

A *lifting* of a plan gives every plan vertex a height so that every face
is exactly planar; the plan's x and y never move. The liftings form a linear
space that always holds the three affine (trivial) liftings 1, x, y.
:func:`lift` returns the lifting closest to target heights in the weighted
least-squares sense; :class:`LiftingSpace` gives the space's dimension and
bases of it.

The numerics are in the compiled core (``facet._core.Lifter``): one
rank-revealing sparse QR (SuiteSparseQR) of the planarity constraints, kept
by :class:`Lifter` so that later solves and fundamental liftings are two
applications of the stored Q.

>>> result = lift(plan_mesh, targets)              # doctest: +SKIP
>>> result.planarity_max_rel <= 1e-9               # doctest: +SKIP
True
"""

from dataclasses import dataclass, field

import numpy as np

from facet import _core
from facet.errors import Cancelled, FacetError, InputError, from_core, report_progress
from facet.mesh import PolyMesh, next_corners
from facet.plan import FREE_WEIGHT
from facet.report import point_text

__all__ = ["BASES", "LiftResult", "Lifter", "LiftingSpace", "lift", "lifting_space",
           "TargetError", "NearlyLiftResult", "lift_nearly"]

#: Basis kinds by name.
BASES = {
    "fundamental": "fundamental liftings: the lifting closest to a unit height at one vertex",
    "eigen": "eigen-liftings: smoothest first (eigenvectors of P L P)",
    "sparse": "sparse liftings: each supported on a few rings of faces around a vertex",
    "orthonormal": "an orthonormal basis from the QR factorization (fast)",
}

#: Sparse liftings: the largest neighbourhood tried around a vertex, in rings of faces.
SPARSE_MAX_RINGS = 3
#: Sparse liftings are collected densely for the independence test: refused beyond this.
SPARSE_MAX_ENTRIES = 2e7
#: Beyond the core's dense eigen-solver (dimension 2,000, or vertices x dimension 2e7),
#: the smoothest eigen-liftings come from ARPACK instead, this many non-trivial ones at
#: most (see _eigen_liftings).
EIGEN_SPARSE_MAX = 500


class TargetError(InputError):
    """Target heights or weights cannot be used (wrong count, NaN, weight <= 0)."""


def _plan_mesh(plan):
    mesh = getattr(plan, "mesh", plan)
    if not isinstance(mesh, PolyMesh):
        raise InputError(f"a plan must be a PolyMesh or a PlanGraph, not {type(plan).__name__}")
    return mesh


#: The smallest weight a Lifter takes, relative to its largest. Measured on a 20 x 20 plan:
#: faces planar to 4e-16 at 1e-14, 1e-14 at 1e-16, 6e-11 at 1e-20, 0.2 of an edge at 1e-30.
WEIGHT_RATIO_MIN = 1e-16


def _vector(values, n, name):
    try:
        array = np.ascontiguousarray(values, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        raise TargetError(f"{name} must be {n} numbers") from None
    if array.shape != (n,):
        raise TargetError(f"{name} has {array.size} values but the plan has {n} vertices")
    bad = np.flatnonzero(~np.isfinite(array))
    if bad.size:
        raise TargetError(f"{name} of vertex {int(bad[0])} is not a finite number")
    return array


def _core_error(exc, source, plan=None):
    name = getattr(exc, "status_name", None)
    if name in ("FACET_ERROR_BAD_WEIGHT", "FACET_ERROR_BAD_TARGET"):
        error = TargetError(str(exc))
        error.status_name = name
        return error
    if name == "FACET_ERROR_PLAN_DEGENERATE_FACE":
        from facet.plan import PlanError

        text = str(exc)
        face = getattr(exc, "face", -1)
        if plan is not None and 0 <= face < plan.n_faces:
            # a drawing's user cannot see face numbers: where it is
            corners = np.asarray(plan.vertices)[plan.face_vertices[
                plan.face_start[face]:plan.face_start[face + 1]], :2]
            x, y = corners.mean(axis=0)
            text += f"; the face is around {point_text((x, y))}"
        error = PlanError(f"{source}: {text}" if source else text)
        error.status_name = name
        return error
    return from_core(exc, source=source)


@dataclass
class LiftResult:
    """The optimal lifting of a plan towards target heights.

    Attributes
    ----------
    mesh : facet.PolyMesh
        The plan's faces with the lifted vertices (x, y from the plan, z the
        heights): every face planar.
    heights, targets, weights : numpy.ndarray
        Per vertex.
    dimension : int
        Dimension of the lifting space.
    trivial_dimension : int
        3: the affine liftings.
    liftable_only_trivially : bool
        The plan admits only the affine liftings; the result is then the
        weighted best-fitting plane of the targets.
    planarity_max_abs, planarity_max_rel : float
        Largest distance of a corner from its face's plane, in model units
        and relative to the face's mean edge length (<= 1e-9 unless a warning
        says otherwise).
    target_rms, target_max : float
        RMS and largest ``|height - target|`` over the vertices given a target (a
        weight above :data:`facet.plan.FREE_WEIGHT`: the free vertices of pins, and
        those no target point fell on, do not count); target_max_vertex is where.
    solve_seconds, factor_seconds : float
        Wall time of the solve and of the factorization.
    warnings : list of str
    """

    mesh: PolyMesh
    heights: np.ndarray
    targets: np.ndarray
    weights: np.ndarray
    dimension: int
    trivial_dimension: int
    planarity_max_abs: float
    planarity_max_rel: float
    target_rms: float
    target_max: float
    target_max_vertex: int
    solve_seconds: float
    factor_seconds: float
    warnings: list = field(default_factory=list)

    @property
    def liftable_only_trivially(self):
        return self.dimension <= self.trivial_dimension

    @property
    def deviation(self):
        """``heights - targets`` per vertex."""
        return self.heights - self.targets

    def far_targets(self, count=10):
        """The vertices whose targets the lifting misses most.

        Returns
        -------
        list of (vertex, height - target), largest miss first.
        """
        dev = self.deviation
        given = np.flatnonzero(_given(self.weights))
        order = given[np.argsort(-np.abs(dev[given]), kind="stable")[:count]]
        return [(int(v), float(dev[v])) for v in order]

    def against(self, targets):
        """This lifting measured against other targets (the weights as they are): a copy
        with ``targets`` and the misses recomputed (over the vertices given a target)."""
        import dataclasses

        t = np.array(targets, dtype=np.float64)
        rms, largest, where = _misses(self.heights, t, self.weights)
        return dataclasses.replace(self, targets=t, target_rms=rms, target_max=largest,
                                   target_max_vertex=where)

    def report(self):
        """The JSON-ready summary (keys of the command line's report)."""
        return {
            "vertices": int(self.mesh.n_vertices),
            "faces": int(self.mesh.n_faces),
            "dimension": int(self.dimension),
            "trivial_dimension": int(self.trivial_dimension),
            "liftable_only_trivially": bool(self.liftable_only_trivially),
            "planarity_max_abs": float(self.planarity_max_abs),
            "planarity_max_rel": float(self.planarity_max_rel),
            "target_rms": float(self.target_rms),
            "target_max": float(self.target_max),
            "target_max_vertex": int(self.target_max_vertex),
            "solve_seconds": float(self.solve_seconds),
            "factor_seconds": float(self.factor_seconds),
            "far_targets": [[v, d] for v, d in self.far_targets(10)],
            "warnings": list(self.warnings),
        }


def _pieces(mesh):
    """Connected pieces of a plan's faces (through shared vertices)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    used = np.unique(mesh.face_vertices)
    if not used.size:
        return 0
    # each corner joined to the next one of its face
    corners = np.asarray(mesh.face_vertices)
    nxt = corners[next_corners(np.asarray(mesh.face_start))]
    n = mesh.n_vertices
    graph = coo_matrix((np.ones(len(nxt)), (corners, nxt)), shape=(n, n))
    _count, labels = connected_components(graph, directed=False)
    return int(np.unique(labels[used]).size)


def _given(weights):
    """Which vertices were given a target (not the free ones of pins or points)."""
    from facet.plan import FREE_WEIGHT

    given = np.asarray(weights) > FREE_WEIGHT
    return given if given.any() else np.ones(len(given), dtype=bool)


def _misses(heights, targets, weights):
    """(RMS, largest, its vertex) of ``|heights - targets|`` over the vertices given a
    target."""
    given = np.flatnonzero(_given(weights))
    miss = np.abs(np.asarray(heights) - np.asarray(targets))[given]
    if not miss.size:
        return 0.0, 0.0, -1
    k = int(np.argmax(miss))
    return float(np.sqrt(np.mean(miss**2))), float(miss[k]), int(given[k])


class Lifter:
    """The lifting solver of one plan with fixed weights.

    It factorizes once (sparse QR); :meth:`solve` and :meth:`fundamental`
    reuse the factorization.

    Parameters
    ----------
    plan : facet.PolyMesh or facet.plan.PlanGraph
        The plan: x and y of its vertices (z is ignored) and its faces.
    weights : array_like, optional
        Per-vertex weights, finite and > 0 (default all 1).
    rank_tol : float, optional
        Rank tolerance on the unit-norm constraint rows (default 1e-10): a
        face constraint dependent on the others to within this is treated
        as dependent (and so violated by about that much, well inside the
        1e-9 planarity promise); the others are enforced exactly.
    progress : callable, optional
        ``progress(done, 3)`` as the factorization's stages end (the sparse QR, the
        search for the directions its rank lost, and between that search's blocks, the
        check); True cancels. The QR itself cannot be interrupted: 2.4 s on a
        100,000-quad plan, 5 s on 300,000; the search takes a minute on a 300,000-site
        Voronoi plan.

    Raises
    ------
    facet.Cancelled
        ``progress`` returned True, or Ctrl+C.
    facet.MeshError
        The plan's faces are not valid.
    facet.plan.PlanError
        A face's corners are collinear in plan.
    TargetError
        A weight is not finite and > 0.
    """

    def __init__(self, plan, weights=None, *, rank_tol=None, progress=None):
        mesh = _plan_mesh(plan)
        self._source = mesh.info.get("source") if mesh.info else None
        self._plan = mesh
        self._plan_warnings = list(getattr(plan, "warnings", None) or [])
        n = mesh.n_vertices
        self._weights = np.ones(n) if weights is None else _vector(weights, n, "weight")
        bad = np.flatnonzero(~(self._weights > 0))
        if bad.size:
            raise TargetError(
                f"weight of vertex {int(bad[0])} is {self._weights[bad[0]]!r}: weights must be > 0"
            )
        low, high = int(np.argmin(self._weights)), int(np.argmax(self._weights))
        if self._weights[low] < WEIGHT_RATIO_MIN * self._weights[high]:
            raise TargetError(
                f"the weight of vertex {low} is {self._weights[low]:.3g}, "
                f"{self._weights[low] / self._weights[high]:.3g} times vertex {high}'s "
                f"({self._weights[high]:.3g}): weights more than {1 / WEIGHT_RATIO_MIN:g} "
                "apart leave the faces' planarity to rounding (a vertex with no target of "
                f"its own weighs {FREE_WEIGHT:g} or less already)")
        xyz = np.ascontiguousarray(mesh.vertices, dtype=np.float64).reshape(-1)
        try:
            self._core = _core.Lifter(
                xyz,
                mesh.face_start,
                mesh.face_vertices,
                None if weights is None else self._weights,
                0.0 if rank_tol is None else float(rank_tol),
                progress,
            )
        except _core.Cancelled:
            raise Cancelled("lifting cancelled") from None
        except _core.CoreError as exc:
            raise _core_error(exc, self._source, mesh) from None
        self._pieces = _pieces(mesh)  # (the core checked the faces)
        self._isolated = int(mesh.n_vertices - np.unique(mesh.face_vertices).size)
        if self._pieces > 1:
            self._plan_warnings.append(
                f"the plan is in {self._pieces} separate pieces that share no vertex: each is "
                f"lifted on its own, with 3 affine liftings of its own ({3 * self._pieces} "
                "in all)")

    @property
    def plan(self):
        """The plan mesh."""
        return self._plan

    @property
    def dimension(self):
        """Dimension of the lifting space (>= 3)."""
        return self._core.dimension

    @property
    def pieces(self):
        """How many separate pieces the plan is in (faces joined through their vertices)."""
        return self._pieces

    @property
    def trivial_dimension(self):
        """The trivial liftings' share of the dimension: 3 affine ones for each piece, and
        the free height of each vertex in no face."""
        return 3 * self._pieces + self._isolated

    @property
    def _unit_weights(self):
        """The weights scaled to mean 1, as the core scales them (by the largest first,
        so that weights near the largest double do not overflow the sum)."""
        w = self._weights / self._weights.max()
        return w * (len(w) / w.sum())

    @property
    def factor_seconds(self):
        return self._core.factor_seconds

    def solve(self, targets):
        """The optimal lifting of per-vertex target heights.

        Returns
        -------
        LiftResult
        """
        n = self._plan.n_vertices
        t = _vector(targets, n, "target height")
        z = np.empty(n)
        try:
            info = self._core.solve(t, z)
        except _core.CoreError as exc:
            raise _core_error(exc, self._source) from None
        warnings = list(self._plan_warnings)
        if info["status"] != "FACET_OK":
            warnings.append(info["message"])
        if not np.all(np.isfinite(z)):  # the core refuses this; never let a NaN out
            raise FacetError("the lifting is not finite")
        xyz = np.array(self._plan.vertices, dtype=np.float64)
        xyz[:, 2] = z
        mesh = self._plan.with_vertices(xyz)
        rms, largest, where = _misses(z, t, self._weights)
        return LiftResult(
            mesh=mesh,
            heights=z,
            targets=t,
            weights=self._weights.copy(),
            dimension=info["dimension"],
            trivial_dimension=self.trivial_dimension,
            planarity_max_abs=info["planarity_max_abs"],
            planarity_max_rel=info["planarity_max_rel"],
            target_rms=rms,
            target_max=largest,
            target_max_vertex=where,
            solve_seconds=info["seconds"],
            factor_seconds=self._core.factor_seconds,
            warnings=warnings,
        )

    def fundamental(self, vertex, out=None):
        """The fundamental lifting of a vertex: the lifting closest to height
        1 there and 0 elsewhere (weighted). Returns heights (n,)."""
        n = self._plan.n_vertices
        z = np.empty(n) if out is None else out
        try:
            self._core.fundamental(int(vertex), z)
        except _core.CoreError as exc:
            raise _core_error(exc, self._source) from None
        return z

    def _sparse_basis(self, count, progress=None):
        return _sparse_liftings(self, count, progress)

    def basis(self, kind="eigen", count=None, progress=None):
        """The first `count` functions of a basis of the lifting space.

        Parameters
        ----------
        kind : {"eigen", "sparse", "orthonormal", "fundamental"}
            Eigen-liftings (smoothest first; the core's dense eigen-solver up to
            dimension 2000, beyond it ARPACK, the smoothest 500 at most), sparse
            liftings (each non-trivial one supported on at most
            three rings of faces around a vertex where the plan allows, scaled
            to peak 1; independent, not orthogonal; collected densely, refused
            beyond 2e7 entries), any orthonormal basis, or the fundamental
            liftings of vertices 0 .. count-1 (these span the space but are not
            independent).
        count : int, optional
            Default: the dimension (eigen, orthonormal) or every vertex
            (fundamental).
        progress : callable, optional
            ``progress(done, total)`` as the sparse liftings are searched
            (vertices), the fundamental ones computed, or ARPACK steps towards
            eigen-liftings beyond the dense limit (total an estimate); True
            cancels (:class:`facet.Cancelled`). The dense eigen and the
            orthonormal bases are one computation each and report nothing.

        Returns
        -------
        (basis, energies) : numpy.ndarray (count, n), numpy.ndarray (count,)
            For eigen and orthonormal, functions 0..2 are the trivial
            liftings 1, x, y (orthonormal in the weighted inner product); the
            rest are orthogonal to them. energies are the Dirichlet energies
            z' L z on the plan's edges.
        """
        n = self._plan.n_vertices
        if kind not in BASES:
            raise InputError(f"unknown basis {kind!r}: use one of {', '.join(BASES)}")
        if kind == "sparse":
            d = self.dimension
            count = d if count is None else int(count)
            if not 0 <= count <= d:
                raise InputError(f"count {count} is not between 0 and the dimension {d}")
            basis = self._sparse_basis(count, progress)
            edges = self._plan.edges()
            energies = np.array([np.sum((b[edges[:, 0]] - b[edges[:, 1]]) ** 2) for b in basis])
            return basis, energies
        if kind == "fundamental":
            count = n if count is None else int(count)
            if not 0 <= count <= n:
                raise InputError(f"count {count} is not between 0 and {n} vertices")
            basis = np.empty((count, n))
            for v in range(count):
                report_progress(progress, v, count, "fundamental liftings")
                self.fundamental(v, basis[v])
            report_progress(progress, count, count, "fundamental liftings")
            edges = self._plan.edges()
            energies = np.array([np.sum((b[edges[:, 0]] - b[edges[:, 1]]) ** 2) for b in basis])
            return basis, energies
        d = self.dimension
        count = d if count is None else int(count)
        if not 0 <= count <= d:
            raise InputError(f"count {count} is not between 0 and the dimension {d}")
        basis = np.empty((count, n))
        energies = np.empty(count)
        try:
            self._core.basis(kind, count, basis, energies)
        except _core.CoreError as exc:
            if kind != "eigen" or getattr(exc, "status_name", None) != "FACET_ERROR_TOO_LARGE":
                raise _core_error(exc, self._source) from None
            if count - 3 > min(EIGEN_SPARSE_MAX, d // 2):
                raise InputError(
                    f"the lifting space has dimension {d}, too large for all its "
                    "eigen-liftings at once: ask for the smoothest "
                    f"{3 + min(EIGEN_SPARSE_MAX, d // 2)} at most (count)") from None
            return _eigen_liftings(self, count, progress)
        return basis, energies


def _eigen_liftings(lifter, count, progress=None):
    """The `count` first eigen-liftings (the affine three, then the smoothest), as the core
    gives them, for lifting spaces beyond its dense eigen-solver.

    The non-trivial ones minimise the Dirichlet energy z' L z over liftings z with
    z' W z = 1, W-orthogonal to the affine ones (W: the weights normalised to mean 1): the
    lowest eigenpairs of L z = lambda W z on that subspace. ARPACK finds them in
    shift-invert mode; its operator solves the constrained system
    [[L + tau W, B'], [B, -delta I]] (B: the planarity constraints and the three
    W-orthogonality rows; delta keeps it quasi-definite where constraints depend on each
    other) by one sparse LU (SuperLU, minimum degree on A + A'). The vectors it returns
    are then made exact liftings by the lifter's own projection and finished by
    Rayleigh-Ritz, so each is a lifting to the projection's accuracy whatever ARPACK's.
    ``progress(done, total)`` between ARPACK's steps (total an estimate); True cancels.
    """
    import scipy.linalg
    import scipy.sparse as sp
    from scipy.sparse.linalg import LinearOperator, eigsh, splu

    mesh = lifter.plan
    n = mesh.n_vertices
    w = lifter._unit_weights
    trivial, trivial_energies = lifter.basis("orthonormal", 3)
    edges = mesh.edges()
    ne = len(edges)
    rows = np.repeat(np.arange(ne), 2)
    incidence = sp.csr_matrix((np.tile([1.0, -1.0], ne), (rows, edges.reshape(-1))),
                              shape=(ne, n))
    laplacian = (incidence.T @ incidence).tocsc()
    r, c, v = [], [], []
    m = 0
    for face, complement in _face_complements(mesh):
        for values in complement:
            r.append(np.full(len(face), m))
            c.append(face)
            v.append(values)
            m += 1
    constraints = sp.csr_matrix(
        (np.concatenate(v) if v else [], (np.concatenate(r) if r else [],
                                          np.concatenate(c) if c else [])), shape=(m, n))
    b = sp.vstack([constraints, sp.csr_matrix(trivial * w)]).tocsc()
    weights = sp.diags(w)
    tau = 1e-6 * float(laplacian.diagonal().mean() or 1.0)
    kkt = sp.bmat([[laplacian + tau * weights, b.T],
                   [b, -1e-8 * sp.identity(b.shape[0])]]).tocsc()
    lu = splu(kkt, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
              options={"SymmetricMode": True})
    k = count - 3
    ncv = min(max(2 * k + 1, 20), n - 1)
    estimate = 3 * ncv
    applied = [0]

    def inverse(x):
        applied[0] += 1
        report_progress(progress, min(applied[0], estimate - 1), estimate, "eigen-liftings")
        rhs = np.zeros(kkt.shape[0])
        rhs[:n] = np.ravel(x)
        return lu.solve(rhs)[:n]

    start = np.random.default_rng(0).standard_normal(n)  # (the same every time)
    _, vectors = eigsh(LinearOperator((n, n), matvec=lambda x: laplacian @ x, dtype=float),
                       k=k, M=weights, sigma=-tau, which="LM", ncv=ncv, v0=start,
                       OPinv=LinearOperator((n, n), matvec=inverse, dtype=float))
    z = np.empty((k, n))
    for i in range(k):
        lifted = np.empty(n)
        lifter._core.solve(np.ascontiguousarray(vectors[:, i]), lifted)
        z[i] = lifted - trivial.T @ (trivial @ (w * lifted))
    energies, coefficients = scipy.linalg.eigh(z @ (laplacian @ z.T), (z * w) @ z.T)
    basis = coefficients.T @ z
    for function in basis:
        if function[np.argmax(np.abs(function))] < 0:
            function *= -1.0
    report_progress(progress, estimate, estimate, "eigen-liftings")
    return np.vstack([trivial, basis]), np.concatenate([trivial_energies, energies])


def _face_complements(mesh):
    """Per face: (vertices, rows) with rows an orthonormal basis ((k-3) x k) of the
    complement of span(1, x, y) over its corners (the planarity constraints)."""
    xy = np.asarray(mesh.vertices, dtype=np.float64)[:, :2]
    out = []
    for face in mesh.faces():
        k = len(face)
        if k <= 3:
            out.append((np.asarray(face), np.zeros((0, k))))
            continue
        p = xy[face] - xy[face].mean(axis=0)
        scale = np.sqrt(np.mean(np.sum(p * p, axis=1))) or 1.0
        a = np.column_stack([np.ones(k), p / scale])
        q, _ = np.linalg.qr(a, mode="complete")
        out.append((np.asarray(face), q[:, 3:].T))
    return out


def _echelon(rows):
    """A reduced row echelon form of a basis (Gauss-Jordan with partial pivoting): the
    same span, with many zeros in each row (sparser liftings than SVD vectors)."""
    a = np.array(rows, dtype=np.float64)
    m, k = a.shape
    r = 0
    for c in range(k):
        if r == m:
            break
        p = r + int(np.argmax(np.abs(a[r:, c])))
        if abs(a[p, c]) <= 1e-9:
            continue
        a[[r, p]] = a[[p, r]]
        a[r] /= a[r, c]
        others = np.arange(m) != r
        a[others] -= np.outer(a[others, c], a[r])
        r += 1
    a[np.abs(a) < 1e-12] = 0.0
    return a[:r]


def _sparse_liftings(lifter, count, progress=None):
    """Sparse liftings (see Lifter.basis): the trivial three, then liftings supported on
    rings of faces around each vertex in turn, kept when independent of those found so far,
    until `count`; any still missing (liftings with no local support) come from the
    orthonormal basis. Each non-trivial one is scaled to peak 1. ``progress(done, n)``
    between vertices (n: the plan's vertices); True cancels."""
    mesh = lifter.plan
    n = mesh.n_vertices
    d = lifter.dimension
    if n * d > SPARSE_MAX_ENTRIES:
        raise FacetError(f"sparse liftings are collected densely: dimension {d} with {n} "
                         f"vertices is over the limit ({SPARSE_MAX_ENTRIES:.0f} entries)")
    trivial, _ = lifter.basis("orthonormal", min(3, count))
    if count <= 3:
        return trivial[:count]
    faces = _face_complements(mesh)
    vertex_faces = [[] for _ in range(n)]
    for f, (vs, _) in enumerate(faces):
        for v in vs:
            vertex_faces[v].append(f)
    sw = np.sqrt(lifter._unit_weights)
    # Orthonormal (in the weighted inner product) span of what is collected, for the test.
    span = [t * sw for t in trivial[:3]]
    found = []
    wanted = count - 3
    for v in range(n):
        if len(found) >= wanted:
            break
        report_progress(progress, v, n, "sparse liftings")
        support = {v}
        for _ in range(SPARSE_MAX_RINGS):
            ring_faces = {f for u in support for f in vertex_faces[u]}
            support = support | {int(u) for f in ring_faces for u in faces[f][0]}
            columns = sorted(support)
            where = {u: j for j, u in enumerate(columns)}
            touched = sorted({f for u in columns for f in vertex_faces[u]})
            rows = []
            for f in touched:
                vs, comp = faces[f]
                if comp.shape[0] == 0:
                    continue
                block = np.zeros((comp.shape[0], len(columns)))
                for i, u in enumerate(vs):
                    if int(u) in where:
                        block[:, where[int(u)]] = comp[:, i]
                rows.append(block)
            matrix = np.vstack(rows) if rows else np.zeros((0, len(columns)))
            if matrix.shape[0]:
                _, sv, vt = np.linalg.svd(matrix)
                rank = int(np.sum(sv > 1e-10 * max(sv[0], 1.0)))
                null = vt[rank:]
            else:
                null = np.eye(len(columns))
            null = _echelon(null)
            added = False
            for vec in null:
                z = np.zeros(n)
                z[columns] = vec
                r = z * sw
                for q in span:
                    r = r - (q @ r) * q
                for q in span:
                    r = r - (q @ r) * q
                if np.linalg.norm(r) > 1e-6 * np.linalg.norm(z * sw):
                    span.append(r / np.linalg.norm(r))
                    found.append(z / np.max(np.abs(z)))
                    added = True
                    if len(found) >= wanted:
                        break
            if added:
                break
    if len(found) < wanted:
        ortho, _ = lifter.basis("orthonormal", d)
        for b in ortho[3:]:
            if len(found) >= wanted:
                break
            r = b * sw
            for q in span:
                r = r - (q @ r) * q
            if np.linalg.norm(r) > 1e-6:
                span.append(r / np.linalg.norm(r))
                found.append(b / np.max(np.abs(b)))
    report_progress(progress, n, n, "sparse liftings")
    signs = [1.0 if z[np.argmax(np.abs(z))] > 0 else -1.0 for z in found]
    return np.vstack([trivial[:3]] + [s * z for s, z in zip(signs, found)])


@dataclass
class LiftingSpace:
    """The lifting space of a plan: its dimension and a basis.

    Attributes
    ----------
    dimension, trivial_dimension : int
    kind : str
        The basis kind.
    basis : numpy.ndarray (count, n)
        Heights per vertex of each basis function.
    energies : numpy.ndarray (count,)
        Dirichlet energy of each.
    """

    dimension: int
    trivial_dimension: int
    kind: str
    basis: np.ndarray
    energies: np.ndarray


def lift(plan, targets, weights=None, *, rank_tol=None, progress=None):
    """The lifting of a plan closest to target heights.

    Minimizes ``sum_v w_v (z_v - t_v)^2`` over heights z that make every
    face exactly planar (x and y fixed). When the plan admits only the
    affine liftings, the answer is the weighted best-fitting plane and
    ``result.liftable_only_trivially`` is True.

    Parameters
    ----------
    plan : facet.PolyMesh or facet.plan.PlanGraph
    targets : array_like (n,)
        Target height per plan vertex (see :mod:`facet.plan` for targets from
        meshes, pinned heights and point files).
    weights : array_like (n,), optional
        Finite and > 0; default all 1.
    rank_tol, progress : optional
        See :class:`Lifter`.

    Returns
    -------
    LiftResult
    """
    return Lifter(plan, weights, rank_tol=rank_tol, progress=progress).solve(targets)


def lifting_space(plan, kind="eigen", count=None, weights=None, *, rank_tol=None,
                  progress=None):
    """The lifting space of a plan and `count` functions of a basis (``progress``: as
    :meth:`Lifter.basis` takes it).

    Returns
    -------
    LiftingSpace
    """
    lifter = Lifter(plan, weights, rank_tol=rank_tol)
    basis, energies = lifter.basis(kind, count, progress=progress)
    return LiftingSpace(lifter.dimension, lifter.trivial_dimension, kind, basis, energies)


@dataclass
class NearlyLiftResult:
    """A lifting of a plan whose vertices were moved a little (:func:`lift_nearly`).

    Attributes
    ----------
    result : LiftResult
        The lifting of the moved plan (its ``mesh`` has the moved x, y).
    moves : numpy.ndarray (n, 2)
        How far each plan vertex moved in x and y.
    max_move : float
        The largest move (model units).
    within_tolerance : bool
        Whether every move is at most the tolerance asked for.
    method : str
        ``"exact"``: the lifting is the least-squares optimum over the moved plan's
        lifting space; ``"planarized"``: the moved plan's lifting space did not resolve
        (its near-dependence is below the rank tolerance), and the heights are those of
        the planarization, faces planar to ``result.planarity_max_rel``; ``"unmoved"``:
        moving did not bring the lifting closer, the plan is kept as drawn.
    moved_vertices : list of (vertex, dx, dy)
        Every vertex that moved by more than 1e-12 of the plan's size, largest first.
    """

    result: LiftResult
    moves: np.ndarray
    max_move: float
    within_tolerance: bool
    method: str
    moved_vertices: list = field(default_factory=list)

    def report(self):
        data = self.result.report()
        data.update({
            "moved_plan": True,
            "move_method": self.method,
            "max_move": float(self.max_move),
            "within_tolerance": bool(self.within_tolerance),
            "moved_vertices": [[v, dx, dy] for v, dx, dy in self.moved_vertices],
        })
        return data


#: Scale of the heights while the plan and heights are planarized together in
#: lift_nearly: a height change then costs 1/100 of a plan move of the same size, so the
#: planarizer bends heights rather than the drawing.
_HEIGHT_SCALE = 0.1


def lift_nearly(plan, targets, weights=None, *, tolerance, progress=None, rank_tol=None):
    """Lift a plan that is liftable only up to rounding: move its vertices a little first.

    A plan drawn and rounded to a few digits usually admits only the planes, far from the
    intended shape. This planarizes the 3D mesh (x, y, 0.1 t) to 1e-12 (``facet.planarize``,
    local/global), which moves the plan x, y little and the heights freely (planarity is
    invariant under scaling z), keeps the moved x, y when no vertex moved more than
    `tolerance`, and then lifts the moved plan exactly towards the targets. When the moved
    plan's extra liftings are still below the rank tolerance, the planarized heights
    themselves are returned (planar to about 1e-11). Best effort: the moves are not
    guaranteed minimal, and weights act on the final lifting only.

    Parameters
    ----------
    plan, targets, weights
        As :func:`lift`.
    tolerance : float
        Largest move of a plan vertex, model units.
    progress : callable, optional
        As for ``facet.planarize``; returning True cancels.
    rank_tol : float, optional
        As :func:`lift`, for the liftings of the plan and of the moved plan.

    Returns
    -------
    NearlyLiftResult
        ``within_tolerance`` False means the moves needed exceed `tolerance`: the moved
        plan and its lifting are returned all the same, for inspection.
    """
    from facet.planarize import planarize

    mesh = _plan_mesh(plan)
    n = mesh.n_vertices
    t = _vector(targets, n, "target height")
    if not (tolerance >= 0 and np.isfinite(tolerance)):
        raise InputError(f"move tolerance must be a finite number >= 0, not {tolerance!r}")
    base = lift(mesh, t, weights, rank_tol=rank_tol)
    xy = np.asarray(mesh.vertices, dtype=np.float64)[:, :2]
    size = float(np.ptp(xy, axis=0).max()) or 1.0
    centre = t.mean()
    xyz = np.column_stack([xy, _HEIGHT_SCALE * (t - centre)])
    flat = planarize(mesh.with_vertices(xyz), tol=1e-12, max_iter=5000, progress=progress)
    moved_xy = flat.mesh.vertices[:, :2]
    moves = moved_xy - xy
    distance = np.hypot(moves[:, 0], moves[:, 1])
    moved_plan = mesh.with_vertices(np.column_stack([moved_xy, np.zeros(n)]))
    exact = lift(moved_plan, t, weights, rank_tol=rank_tol)
    method = "exact"
    result = exact
    planar_heights = flat.mesh.vertices[:, 2] / _HEIGHT_SCALE + centre
    rms, planar_miss, where = _misses(planar_heights, t, exact.weights)
    if exact.target_max > planar_miss and flat.planarity.max_rel_all <= 1e-10:
        method = "planarized"
        lifted = moved_plan.with_vertices(np.column_stack([moved_xy, planar_heights]))
        from facet.planarity import planarity

        report = planarity(lifted)
        result = LiftResult(
            mesh=lifted, heights=planar_heights, targets=t, weights=exact.weights,
            dimension=exact.dimension, trivial_dimension=exact.trivial_dimension,
            planarity_max_abs=float(report.max_abs_all),
            planarity_max_rel=float(report.max_rel_all),
            target_rms=rms, target_max=planar_miss, target_max_vertex=where,
            solve_seconds=float(flat.solve_seconds), factor_seconds=exact.factor_seconds,
            warnings=[])
    if result.target_max >= base.target_max:
        # Moving did not help: keep the drawing as it is.
        moves = np.zeros_like(moves)
        distance = np.zeros(n)
        result, method = base, "unmoved"
    order = np.argsort(-distance, kind="stable")
    moved = [(int(v), float(moves[v, 0]), float(moves[v, 1])) for v in order
             if distance[v] > 1e-12 * size]
    max_move = float(distance.max()) if n else 0.0
    return NearlyLiftResult(result, moves, max_move, max_move <= tolerance, method, moved)
