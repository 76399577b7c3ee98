# SPDX-License-Identifier: LGPL-2.1-or-later
"""Edit and observe: move control vertices and re-planarize at interactive rates.

A :class:`LiveSolver` keeps one :class:`facet.Planarizer` alive for a control
mesh. The designer picks a vertex; :func:`soft_weights` spreads the move over
its neighbours within a radius (soft selection); every frame of a drag is a
*live update* (:meth:`LiveSolver.frame`): the region around the moved vertices
is re-solved to the full tolerance and the rest of the result keeps its
positions, so every frame is planar. :meth:`LiveSolver.settle` re-solves the
whole mesh (the nearest planar mesh to the edited control mesh, not only a
local repair), for when the frames could not reach the tolerance.

The solver never touches the caller's mesh: the control positions live in
:attr:`LiveSolver.control` (a copy).

>>> live = LiveSolver(mesh)                           # doctest: +SKIP
>>> live.begin_drag(17, radius=2.0, falloff="smooth")  # doctest: +SKIP
>>> live.drag([0.0, 0.0, 0.3])                         # doctest: +SKIP
>>> result = live.frame()                              # doctest: +SKIP
>>> live.end_drag(); final = live.settle()             # doctest: +SKIP
"""

import math

import numpy as np

from facet.errors import InputError
from facet.planarize import METHODS, Planarizer

__all__ = ["FALLOFFS", "EditError", "LiveSolver", "panel_triangles", "soft_weights"]

#: Soft-selection falloff curves, weight as a function of t = distance / radius
#: in [0, 1]: smooth (1 - 3t^2 + 2t^3, flat at the picked vertex and at the
#: rim), linear (1 - t), constant (1 inside the radius).
FALLOFFS = ("smooth", "linear", "constant")

#: Seconds of solving per drag frame that is not a live update (the rest of a
#: 33 ms frame is for the scene update and the redraw).
FRAME_SECONDS = 0.015

#: Time limit of one live update (seconds). Measured on a 100 x 100 quad grid
#: (1 m panels, 13 vertices moved per step by the soft selection): 5-20 ms.
LIVE_BUDGET = 0.25


class EditError(InputError):
    """A live-edit input cannot be used (vertex index, radius, falloff, move)."""


def soft_weights(vertices, center, radius, falloff="smooth"):
    """Weights with which the vertices follow a move of vertex ``center``.

    Parameters
    ----------
    vertices : array_like (n, 3)
        Positions the distances are measured at (the control mesh at the start
        of the drag).
    center : int
        The picked vertex; its weight is 1.
    radius : float
        Vertices closer than this (straight-line distance, model units) move
        too; 0 moves the picked vertex alone.
    falloff : {"smooth", "linear", "constant"}
        How the weight falls from 1 at the picked vertex to 0 at the radius.

    Returns
    -------
    numpy.ndarray (n,)
        Weights in [0, 1].

    Raises
    ------
    EditError
        When the vertex is out of range, the radius negative or not finite, or
        the falloff unknown.
    """
    xyz = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
    n = xyz.shape[0]
    center = _vertex_index(center, n)
    radius = _radius(radius)
    if falloff not in FALLOFFS:
        raise EditError(f"falloff must be one of {', '.join(FALLOFFS)}, not {falloff!r}")
    weights = np.zeros(n)
    if radius > 0.0:
        # Distances relative to the radius: the same weights in mm, m or georeferenced
        # coordinates (the difference is taken before squaring).
        t = np.linalg.norm((xyz - xyz[center]) / radius, axis=1)
        inside = t < 1.0
        ti = t[inside]
        if falloff == "smooth":
            weights[inside] = 1.0 - ti * ti * (3.0 - 2.0 * ti)
        elif falloff == "linear":
            weights[inside] = 1.0 - ti
        else:
            weights[inside] = 1.0
    weights[center] = 1.0
    return weights


def panel_triangles(mesh, vertices=None):
    """Triangles covering each face of a polygon mesh, for drawing.

    Each face is split in its own plane (the Newell normal of its corners):
    a triangle is kept, a quad is cut along the diagonal from its reflex
    corner (the shorter diagonal when it is convex), a larger polygon is
    ear-clipped. The triangles depend on the topology and on the positions
    they were computed from only through that choice of diagonals, so they
    stay valid while the corners move a little (a drag): a viewer can draw
    them without re-tessellating the polygons every time coordinates change.

    Parameters
    ----------
    mesh : facet.PolyMesh
    vertices : array_like (n, 3), optional
        Positions to choose the diagonals with (default: the mesh's).

    Returns
    -------
    triangles : numpy.ndarray of int32 (m, 3)
        Vertex indices, in the winding of their face.
    face : numpy.ndarray of int32 (m,)
        The face of each triangle; the triangles of a face are consecutive
        and the faces in order, so ``face`` is sorted.
    """
    xyz = np.asarray(mesh.vertices if vertices is None else vertices,
                     dtype=np.float64).reshape(-1, 3)
    start = np.asarray(mesh.face_start, dtype=np.int64)
    corners = np.asarray(mesh.face_vertices, dtype=np.int64)
    degree = np.diff(start)
    # Triangles and quads (the bulk of a facade) vectorized.
    tri_faces = np.flatnonzero(degree == 3)
    quad_faces = np.flatnonzero(degree == 4)
    out_tri = np.empty((0, 3), dtype=np.int64)
    out_face = np.empty(0, dtype=np.int64)
    pieces_tri, pieces_face = [], []
    if tri_faces.size:
        idx = start[tri_faces][:, None] + np.arange(3)
        pieces_tri.append(corners[idx])
        pieces_face.append(tri_faces)
    if quad_faces.size:
        q = corners[start[quad_faces][:, None] + np.arange(4)]  # (k, 4)
        p = xyz[q] - xyz[q].mean(axis=1, keepdims=True)  # centred: georeferenced input
        normal = np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1])  # Newell normal of a quad
        turn = np.empty(q.shape)
        for k in range(4):
            a, b, c = p[:, k - 1], p[:, k], p[:, (k + 1) % 4]
            turn[:, k] = np.einsum("ij,ij->i", np.cross(b - a, c - b), normal)
        reflex = turn < 0.0
        d02 = np.einsum("ij,ij->i", p[:, 2] - p[:, 0], p[:, 2] - p[:, 0])
        d13 = np.einsum("ij,ij->i", p[:, 3] - p[:, 1], p[:, 3] - p[:, 1])
        # diagonal 1-3 when corner 1 or 3 is reflex, 0-2 when 0 or 2 is; else the shorter
        use13 = (reflex[:, 1] | reflex[:, 3]) | (~(reflex[:, 0] | reflex[:, 2]) & (d13 < d02))
        first = np.where(use13[:, None], q[:, [0, 1, 3]], q[:, [0, 1, 2]])
        second = np.where(use13[:, None], q[:, [1, 2, 3]], q[:, [0, 2, 3]])
        pieces_tri.append(np.stack([first, second], axis=1).reshape(-1, 3))
        pieces_face.append(np.repeat(quad_faces, 2))
    for f in np.flatnonzero(degree > 4):
        ring = corners[start[f]:start[f + 1]]
        for t in _ear_clip(xyz[ring]):
            pieces_tri.append(ring[np.asarray(t)][None, :])
            pieces_face.append(np.array([f]))
    if pieces_tri:
        out_tri = np.concatenate(pieces_tri)
        out_face = np.concatenate(pieces_face)
        order = np.argsort(out_face, kind="stable")
        out_tri, out_face = out_tri[order], out_face[order]
    return out_tri.astype(np.int32), out_face.astype(np.int32)


def _ear_clip(points):
    """Triangles (corner index triples) of one polygon (k, 3), k > 3, ear-clipped in
    the plane of its Newell normal; a fan when no ear is found (degenerate)."""
    p = points - points.mean(axis=0)
    k = p.shape[0]
    normal = np.zeros(3)
    for i in range(k):
        a, b = p[i], p[(i + 1) % k]
        normal += np.array([(a[1] - b[1]) * (a[2] + b[2]), (a[2] - b[2]) * (a[0] + b[0]),
                            (a[0] - b[0]) * (a[1] + b[1])])
    axis = int(np.argmax(np.abs(normal)))
    uv = np.delete(p, axis, axis=1)
    if normal[axis] < 0.0:
        uv = uv[:, ::-1]  # counter-clockwise seen along the normal
    ring = list(range(k))
    out = []

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    guard = 0
    while len(ring) > 3 and guard < 4 * k * k:
        guard += 1
        for j in range(len(ring)):
            i0, i1, i2 = ring[j - 1], ring[j], ring[(j + 1) % len(ring)]
            a, b, c = uv[i0], uv[i1], uv[i2]
            if cross(a, b, c) <= 0.0:
                continue  # reflex or flat corner: not an ear
            inside = False
            for m in ring:
                if m in (i0, i1, i2):
                    continue
                q = uv[m]
                if cross(a, b, q) >= 0.0 and cross(b, c, q) >= 0.0 and cross(c, a, q) >= 0.0:
                    inside = True
                    break
            if not inside:
                out.append((i0, i1, i2))
                ring.pop(j)
                break
        else:
            break  # no ear: degenerate polygon, fan the rest
    for j in range(1, len(ring) - 1):
        out.append((ring[0], ring[j], ring[j + 1]))
    return out


def _vertex_index(vertex, n):
    try:
        index = int(vertex)
    except (TypeError, ValueError):
        raise EditError(f"vertex must be an index, not {vertex!r}") from None
    if index != vertex or not 0 <= index < n:
        raise EditError(f"vertex {vertex} is out of range ({n} vertices)")
    return index


def _radius(radius):
    try:
        value = float(radius)
    except (TypeError, ValueError):
        raise EditError(f"radius must be a length, not {radius!r}") from None
    if not math.isfinite(value) or value < 0.0:
        raise EditError(f"radius must be 0 or a positive length, not {radius!r}")
    return value


class LiveSolver:
    """A planarization that follows edits of the control mesh.

    Parameters
    ----------
    mesh : facet.PolyMesh
        The control mesh (topology and starting positions; not modified).
    method : {"lg", "ll"}
        Scheme of the final solve (:meth:`settle`).
    live_method : {"lg", "ll"}
        Scheme of the drag frames (default "lg": a live update re-solves a
        small region, where local/global reaches 1e-6 in a few milliseconds;
        local/local stalls near 1e-5).
    tol, tol_abs, max_iter, threads
        As :meth:`facet.Planarizer.solve`, for :meth:`settle` and as the goal
        of the frames.
    frame_seconds : float
        Solve time per frame when a frame cannot be a live update
        (:data:`FRAME_SECONDS`): such frames run as many iterations as the
        last ones took in that time (at least one).
    live_budget : float
        Time limit of one live update, seconds (:data:`LIVE_BUDGET`): a
        region that needs longer stops short of the tolerance and the frames
        after it continue with whole-mesh re-solves.
    frame_threads : int
        Threads of the frames (default 1: a frame's few short iterations lose
        more to waking threads than they gain; measured at 10k faces on a
        loaded 2-core machine, 1 thread 22 ms a frame, 2 threads 220 ms).
    result : facet.PlanarizeResult, facet.PolyMesh or array_like (n, 3), optional
        A solution of ``mesh`` to start the frames from (e.g. the planarized
        object the designer is looking at). Default: solved here (cold).
    **options
        Terms and data options of :meth:`facet.Planarizer.solve` (``data``,
        ``fixed``, ``boundary``...), used by every solve.
    """

    def __init__(self, mesh, *, method="lg", live_method="lg", tol=1e-6, tol_abs=None,
                 max_iter=None, threads=None, frame_seconds=FRAME_SECONDS, frame_threads=1,
                 live_budget=None, result=None, progress=None, **options):
        for name, value in (("method", method), ("live_method", live_method)):
            if value not in METHODS:
                raise EditError(f"{name} must be one of {', '.join(METHODS)}, not {value!r}")
        frame_seconds = float(frame_seconds)
        if not math.isfinite(frame_seconds) or frame_seconds <= 0.0:
            raise EditError(f"frame_seconds must be a positive time, not {frame_seconds!r}")
        live_budget = LIVE_BUDGET if live_budget is None else float(live_budget)
        if not math.isfinite(live_budget) or live_budget <= 0.0:
            raise EditError(f"live_budget must be a positive time, not {live_budget!r}")
        options.pop("time_budget", None)  # frames are sized by frame_seconds instead
        self.live_budget = live_budget
        # A data="surface" term measures the distance to the control mesh's own
        # surface (or a reference): the live update's region data (the previous
        # result moved by the drag) does not apply; those frames re-solve warm.
        self._live_usable = options.get("data") != "surface" and \
            not options.get("surface_weight")
        self._offset = None  # live updates solve control + offset (see frame())
        self._live_input = None  # positions given to the last live update
        self.method = method
        self.live_method = live_method
        self.frame_seconds = frame_seconds
        self.frame_threads = int(frame_threads or 0)
        self._goal = {"tol": tol, "tol_abs": tol_abs, "threads": threads}
        self._max_iter = max_iter
        self._options = options
        self._planarizer = Planarizer(mesh)
        self.mesh = mesh
        self.control = np.array(mesh.vertices, dtype=np.float64)
        self.original = self.control.copy()
        self._drag = None
        self.frames = 0
        self._iteration_seconds = frame_seconds / 3.0  # first guess; measured by frame()
        if result is not None:
            positions = getattr(result, "mesh", result)
            positions = np.asarray(getattr(positions, "vertices", positions), dtype=np.float64)
            if positions.shape != self.control.shape or not np.all(np.isfinite(positions)):
                raise EditError(f"the result to start from must be {self.control.shape[0]} "
                                "finite points (the control mesh's vertex count)")
            # Start the frames from the result the designer sees: one iteration
            # from it (it is planar already, so it stays where it is) leaves it
            # as the solver's previous result. Live updates then solve the
            # control positions plus this offset: a vertex the drag has not
            # moved is given the very bits of this seed, so it is not re-solved.
            offset = positions - self.control
            seed = self.control + offset
            seeded = self._planarizer.solve(seed, method="ll", iterations=1,
                                            threads=self.frame_threads, **options)
            self._set_result(result if hasattr(result, "planarity") else seeded)
            self._offset, self._live_input = offset, seed
        else:
            self._solve(warm=False, method=method, progress=progress)
        self.settled = True

    # --- drags ------------------------------------------------------------------------------

    def begin_drag(self, vertex, radius=0.0, falloff="smooth"):
        """Start moving ``vertex`` with its neighbours within ``radius``.

        Returns the soft-selection weights (n,)."""
        weights = soft_weights(self.control, vertex, radius, falloff)
        moving = np.flatnonzero(weights > 0.0)
        self._drag = (int(vertex), self.control.copy(), moving, weights[moving])
        return weights

    @property
    def dragging(self):
        """True between :meth:`begin_drag` and :meth:`end_drag`."""
        return self._drag is not None

    @property
    def drag_vertex(self):
        """The picked vertex of the current drag, or None."""
        return None if self._drag is None else self._drag[0]

    def drag(self, offset):
        """Move the picked vertex by ``offset`` (from where the drag began) and
        its neighbours by their weights. Returns the indices of the vertices
        that moved."""
        if self._drag is None:
            raise EditError("drag() without begin_drag(): pick a vertex first")
        delta = np.asarray(offset, dtype=np.float64).reshape(-1)
        if delta.shape != (3,) or not np.all(np.isfinite(delta)):
            raise EditError(f"the move must be three finite numbers, not {offset!r}")
        _vertex, base, moving, weights = self._drag
        self.control[moving] = base[moving] + weights[:, None] * delta
        self.settled = False
        return moving

    def drag_to(self, position):
        """Move the picked vertex to ``position`` (see :meth:`drag`)."""
        if self._drag is None:
            raise EditError("drag_to() without begin_drag(): pick a vertex first")
        target = np.asarray(position, dtype=np.float64).reshape(-1)
        if target.shape != (3,):
            raise EditError(f"the position must be three numbers, not {position!r}")
        vertex, base = self._drag[0], self._drag[1]
        return self.drag(target - base[vertex])

    def end_drag(self):
        """End the current drag (the moved control positions stay)."""
        self._drag = None

    def set_control(self, vertices):
        """Replace all control positions (e.g. restore them)."""
        xyz = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
        if xyz.shape != self.control.shape or not np.all(np.isfinite(xyz)):
            raise EditError(f"control positions must be {self.control.shape[0]} finite points")
        self.control[:] = xyz
        self._drag = None
        self.settled = False

    @property
    def moved(self):
        """True if a control vertex differs from where the session started."""
        return not np.array_equal(self.control, self.original)

    # --- solves ----------------------------------------------------------------------------

    def frame(self):
        """One drag frame: re-planarize the current control positions. Returns the
        PlanarizeResult.

        A frame is a *live update* (:meth:`facet.Planarizer.solve` with ``live=True``,
        ``facet_planarizer_update``): only the vertices the drag moved and their
        neighbourhood a few edges deep are re-solved, from the previous result moved
        by the drag, to the full tolerance; every other vertex keeps its previous
        position bit for bit. The data term of that region is the previous result
        moved by the drag, so the result follows the hand at once. The update is
        given the control positions plus :attr:`_offset` (the result the session
        started from minus its control mesh), so the first frame continues from the
        result the designer sees, not from a re-solve of the whole mesh.

        When the live update cannot be used (a ``data="surface"`` term: its reference
        is the moving control mesh) or the last update stopped short of the tolerance
        with nothing moved since, the frame is a warm re-solve of the whole mesh sized
        to about :attr:`frame_seconds` (later frames continue from it)."""
        control = self.control.copy()  # a drag on another thread may move it meanwhile
        if self._live_usable:
            xyz = control if self._offset is None else control + self._offset
            if self._live_input is None or self.result.converged or \
                    not np.array_equal(xyz, self._live_input):
                result = self._planarizer.solve(
                    xyz, method=self.live_method, live=True, threads=self.frame_threads,
                    time_budget=self.live_budget, **self._goal_no_threads(), **self._options)
                self._live_input = xyz
                self._set_result(result, control, keep_offset=True)
                self.frames += 1
                return result
        self._predict(control)
        count = max(1, int(self.frame_seconds / self._iteration_seconds))
        if self._max_iter:
            count = min(count, int(self._max_iter))
        result = self._solve(warm=True, method=self.live_method, max_iter=count,
                             threads=self.frame_threads, control=control)
        if result.iterations > 0:
            per = result.solve_seconds / result.iterations
            self._iteration_seconds = 0.5 * self._iteration_seconds + 0.5 * per
        self.frames += 1
        return result

    def _goal_no_threads(self):
        return {"tol": self._goal["tol"], "tol_abs": self._goal["tol_abs"],
                "max_iter": self._max_iter}

    @property
    def live_updates(self):
        """True when the next frame will be a live update (cheap, local): not with a
        ``data="surface"`` term, nor right after a frame that fell short with nothing
        moved since."""
        if not self._live_usable:
            return False
        xyz = self.control if self._offset is None else self.control + self._offset
        return self._live_input is None or bool(self.result.converged) or \
            not np.array_equal(xyz, self._live_input)

    @property
    def result_control(self):
        """The control positions :attr:`result` was solved for (a copy taken then)."""
        return self._result_control

    @property
    def converged(self):
        """True once the last result of the current control positions reached the
        tolerance."""
        return bool(self.result.converged)

    def settle(self, progress=None):
        """Solve the current control positions to the full tolerance with
        :attr:`method`, warm from the last frame (``progress`` as
        :meth:`facet.Planarizer.solve`; raises facet.Cancelled)."""
        control = self.control.copy()
        self._predict(control)
        self._solve(warm=True, method=self.method, progress=progress, control=control)
        self.settled = np.array_equal(control, self.control)
        return self.result

    def _predict(self, control):
        """Make the previous result moved by the control's moves since then the solver's
        warm start."""
        moved = control - self._result_control
        if np.any(moved):
            start = np.ascontiguousarray(self.result.mesh.vertices + moved)
            # One iteration from the predicted positions leaves them (slightly
            # flattened) as the solver's previous result: the warm start.
            self._planarizer._core.solve(  # noqa: SLF001 (same package)
                start, np.empty_like(start), method=self.live_method, iterations=1,
                threads=self.frame_threads)

    def _solve(self, warm, method, progress=None, max_iter=None, threads=None, control=None):
        control = self.control.copy() if control is None else control
        goal = dict(self._goal)
        if threads is not None:
            goal["threads"] = threads
        result = self._planarizer.solve(
            control, method=method, warm=warm, max_iter=max_iter or self._max_iter,
            progress=progress, **goal, **self._options)
        self._set_result(result, control)
        return result

    def _set_result(self, result, control=None, keep_offset=False):
        self.result = result
        self._result_control = (self.control if control is None else control).copy()
        if not keep_offset:
            # The solver's previous control is the control mesh itself now.
            self._offset = self._live_input = None
        if keep_offset and bool(result.converged) and \
                np.array_equal(self._result_control, self.control):
            self.settled = True  # planar to the tolerance at the current positions
