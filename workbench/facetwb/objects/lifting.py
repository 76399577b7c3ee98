# SPDX-License-Identifier: LGPL-2.1-or-later
"""Lifting: a plan lifted to exactly planar faces, as close as possible to target heights.

Parametric on ``Plan`` (a PlanGraph or any Facet polygon mesh: only its x, y and faces
count) and on the targets: ``Targets`` (a surface: Facet mesh, FreeCAD Mesh or Part object;
each plan vertex takes the height of the surface straight above or below it, the topmost
hit, or the per-vertex heights of a Facet mesh with the plan's vertices), else ``TargetFile``
(a mesh or a .csv of x,y,z points), else ``PinnedPoints`` (x, y find the plan vertex, z is its
height; the rest free). Pins are found by position, not by vertex number, so they stay on
their vertices when the drawing is edited and the graph renumbered. Recompute runs ``facet.lift`` and stores the lifted mesh like a PolyMesh, so the rest
of the workbench (Planarize, panels) takes it as a source.
"""

import numpy as np

import facet
from facet.plan import match_tolerance
from facet.report import point_text
from facetwb import compat, conversion, progress
from facetwb.recompute import guarded
from facetwb.translation import translate
from facetwb.objects.polymesh import PolyMesh, get_mesh, set_mesh, set_planarity

TYPE_LIFTING = "Facet::Lifting"


class Lifting(PolyMesh):
    """Proxy of a lifted plan (App::FeaturePython)."""

    TYPE = TYPE_LIFTING

    def init_source_properties(self, obj):
        compat.add_property(obj, "App::PropertyLink", "Plan", "Lift",
                            "The plan: a PlanGraph or any Facet polygon mesh (x, y and faces)")
        compat.add_property(
            obj, "App::PropertyLink", "Targets", "Lift",
            "Target surface (Facet mesh, Mesh or Part object): heights by vertical projection, "
            "or per vertex when it is a Facet mesh with the plan's vertices")
        compat.add_property(obj, "App::PropertyFile", "TargetFile", "Lift",
                            "Targets from a file when Targets is empty: a mesh, or x,y,z "
                            "points (.csv, nearest plan vertex within Snap)")
        compat.add_property(obj, "App::PropertyVectorList", "PinnedPoints", "Lift",
                            "Pinned heights when there are no other targets: x, y at a plan "
                            "vertex (within Snap), z its height; the other vertices are free")
        compat.add_property(obj, "App::PropertyFloatList", "Weights", "Lift",
                            "Weight of each plan vertex (empty: all 1)")
        compat.add_property(obj, "App::PropertyFloatList", "Mix", "Lift",
                            "Heights (mm, at the peak) of the smoothest non-planar liftings "
                            "(eigen-liftings 1, 2, ...) added to the optimal lifting; faces "
                            "stay exactly planar")
        compat.add_property(obj, "App::PropertyVectorList", "Drags", "Lift",
                            "Vertex drags applied after Mix, in order: x, y find the plan "
                            "vertex (within Snap), z is how far it is raised, mm; the rest of "
                            "the roof follows by the vertex's fundamental lifting")
        compat.add_property(obj, "App::PropertyLength", "Snap", "Lift",
                            "Largest plan distance from a pinned or CSV point to its vertex "
                            "(0: the plan graph's Snap if it has one, else 1e-6 of the plan's "
                            "size)")
        read_only = compat.EDITOR_READ_ONLY
        output = compat.PROP_OUTPUT
        for kind, name, doc in (
                ("App::PropertyInteger", "Dimension",
                 "Dimension of the lifting space (3: only the planes)"),
                ("App::PropertyBool", "OnlyTrivial",
                 "The plan admits only the planes: the result is the best-fitting plane"),
                ("App::PropertyLength", "TargetRms", "RMS distance of the heights from the "
                 "targets"),
                ("App::PropertyLength", "TargetMax", "Largest distance from a target"),
                ("App::PropertyInteger", "TargetMaxVertex", "Where the largest distance is"),
                ("App::PropertyFloat", "SolveSeconds", "Time of the factorization and solve"),
                ("App::PropertyString", "FarTargets",
                 "The targets the lifting misses most: vertex:distance, ..."),
                ("App::PropertyStringList", "Warnings",
                 "What the lifting found worth telling: target points that match no plan "
                 "vertex (left out), faces that meet in plan without sharing a vertex "
                 "(lifted apart), a plan in separate pieces, a solve that missed planarity")):
            compat.add_property(obj, kind, name, "Result", doc, attr=output,
                                editor_mode=read_only)

    def _targets(self, obj, plan, notes):
        """(targets, weights); what reading them left out is appended to `notes`."""
        from facet.plan import read_targets, targets_from_mesh, targets_from_points

        # what is set but not used (Targets comes first, then TargetFile): said, since a
        # heights file typed into the property editor otherwise changed nothing silently
        if obj.Targets is not None:
            unused = {(True, False): "TargetFile is", (False, True): "PinnedPoints are",
                      (True, True): "TargetFile and PinnedPoints are"}.get(
                          (bool(obj.TargetFile), bool(obj.PinnedPoints)))
            if unused:
                notes.append(f"{unused} not used: the targets are {obj.Targets.Label}'s "
                             "surface (empty Targets to use them)")
        elif obj.TargetFile and obj.PinnedPoints:
            notes.append("PinnedPoints are not used: the targets are the points of TargetFile "
                         "(empty it to use them)")
        if obj.Targets is not None:
            surface = conversion.mesh_from_object(obj.Targets)
            # (progress and Cancel: a 100,000-vertex plan's ray cast takes seconds)
            return targets_from_mesh(plan, surface, source=obj.Targets.Label,
                                     progress=progress.hook(), units="mm")
        if obj.TargetFile:
            return read_targets(plan, obj.TargetFile, tolerance=match_snap(obj) or None,
                                notes=notes, progress=progress.hook(), units="mm",
                                option_names=option_names())
        if obj.PinnedPoints:
            tolerance = match_tolerance(plan, match_snap(obj))
            points = [(p.x, p.y, p.z) for p in obj.PinnedPoints]
            targets, weights = targets_from_points(plan, points, tolerance=tolerance,
                                                   units="mm", option_names=option_names())
            found = int(np.count_nonzero(weights == 1.0))
            if found < len(points):
                raise ValueError(f"{obj.Label}: {len(points) - found} of the {len(points)} "
                                 f"pinned points are not within {tolerance:g} mm of a plan "
                                 "vertex")
            return targets, weights
        raise ValueError(f"{obj.Label}: no targets: set Targets, TargetFile or PinnedPoints")

    def _lifter(self, plan, weights):
        """A facet Lifter for this plan and weights, kept between recomputes (not saved), so
        moving a Mix slider re-solves without a new factorization."""
        from facet.lift import Lifter

        key = (np.asarray(plan.vertices[:, :2]).tobytes(), plan.face_start.tobytes(),
               plan.face_vertices.tobytes(), np.asarray(weights).tobytes())
        cache = getattr(self, "_cache", None)
        if cache is None or cache[0] != key:
            # progress and Cancel between the factorization's stages (a large plan's
            # factorization takes seconds: 2.4 s at 100,000 quads)
            cache = (key, Lifter(plan, weights, progress=progress.hook()), {})
            self._cache = cache
        return cache[1], cache[2]

    def mix_basis(self, plan, weights, count):
        """The first ``count`` non-trivial eigen-liftings, each scaled to peak 1 (cached)."""
        lifter, store = self._lifter(plan, weights)
        count = min(int(count), lifter.dimension - 3)
        if count <= 0:
            return np.zeros((0, plan.n_vertices))
        if store.get("count", 0) < count:
            # (progress and Cancel: 10 s for a 100,000-face plan's first Mix value)
            basis, _ = lifter.basis("eigen", 3 + count, progress=progress.hook())
            peaks = np.max(np.abs(basis[3:]), axis=1)
            store["basis"] = basis[3:] / np.where(peaks > 0, peaks, 1.0)[:, None]
            store["count"] = count
        return store["basis"][:count]

    def _dragged(self, obj, plan, weights, lifter, result, targets):
        """Apply the Drags: each raises one vertex by its fundamental lifting, scaled to the
        asked height at that vertex (every fundamental lifting is a lifting: faces stay
        planar)."""
        xy = plan.vertices[:, :2]
        tolerance = match_tolerance(plan, match_snap(obj))
        heights = result.heights.copy()
        for drag in obj.Drags:
            distance = np.hypot(xy[:, 0] - drag.x, xy[:, 1] - drag.y)
            v = int(np.argmin(distance))
            if distance[v] > tolerance:
                raise ValueError(f"{obj.Label}: no plan vertex within {tolerance:g} mm of the "
                                 f"drag at {point_text((drag.x, drag.y))}")
            fundamental = lifter.fundamental(v)
            if not fundamental[v] > 1e-9:
                raise ValueError(f"{obj.Label}: vertex {v} cannot be raised on its own: "
                                 "every lifting of this plan keeps it where the planes put it")
            heights = heights + drag.z * fundamental / fundamental[v]
        # a lifting: returned as it is, planarity measured, the misses against the targets
        return lifter.solve(heights).against(targets)

    @guarded
    def execute(self, obj):
        if obj.Plan is None:
            raise ValueError(f"{obj.Label}: Plan is empty, nothing to lift")
        plan = get_mesh(obj.Plan)
        notes = []  # (target points left out)
        targets, weights = self._targets(obj, plan, notes)
        if obj.Weights:
            if len(obj.Weights) != plan.n_vertices:
                raise ValueError(f"{obj.Label}: {len(obj.Weights)} weights but the plan has "
                                 f"{plan.n_vertices} vertices")
            given = np.asarray(obj.Weights, dtype=np.float64)
            bad = np.flatnonzero(~(np.isfinite(given) & (given > 0)))
            if bad.size:  # (checked as given: the pins' weights multiply them below)
                raise ValueError(f"{obj.Label}: Weights: the weight of vertex {bad[0]} is "
                                 f"{given[bad[0]]:g}: weights must be finite and > 0")
            weights = weights * given
        lifter, _ = self._lifter(plan, weights)
        result = lifter.solve(targets)
        mix = np.asarray(obj.Mix, dtype=np.float64)
        if mix.size and np.any(mix != 0):
            basis = self.mix_basis(plan, weights, mix.size)
            beyond = np.flatnonzero(mix[basis.shape[0]:])
            if beyond.size:
                raise ValueError(
                    f"{obj.Label}: Mix value {basis.shape[0] + int(beyond[0]) + 1} is "
                    f"{mix[basis.shape[0] + beyond[0]]:g}, but the plan has only "
                    f"{basis.shape[0]} liftings that are not planes: set it to 0")
            extra = mix[: basis.shape[0]] @ basis
            # a lifting: returned as it is, the misses against the targets
            result = lifter.solve(result.heights + extra).against(targets)
        if obj.Drags:
            result = self._dragged(obj, plan, weights, lifter, result, targets)
        set_mesh(obj, result.mesh)
        set_planarity(obj, facet.planarity(result.mesh))
        obj.Dimension = int(result.dimension)
        obj.OnlyTrivial = bool(result.liftable_only_trivially)
        obj.TargetRms = float(result.target_rms)
        obj.TargetMax = float(result.target_max)
        obj.TargetMaxVertex = int(result.target_max_vertex)
        obj.SolveSeconds = float(result.factor_seconds + result.solve_seconds)
        obj.FarTargets = ", ".join(f"{v}:{d:.6g}" for v, d in result.far_targets(5))
        warnings = notes + self._unjoined(obj, plan) + list(result.warnings)
        if list(obj.Warnings) != warnings:
            obj.Warnings = warnings

    def _unjoined(self, obj, plan):
        """The plan's warnings as `facet lift` gives them for a plan mesh (faces that meet
        in plan without sharing a vertex), kept between recomputes of the same plan."""
        from facet.plan import plan_from_mesh

        key = (np.asarray(plan.vertices[:, :2]).tobytes(), plan.face_start.tobytes(),
               plan.face_vertices.tobytes())
        cached = getattr(self, "_unjoined_cache", None)
        if cached is None or cached[0] != key:
            graph = plan_from_mesh(plan, source=obj.Plan.Label, check_overlap=False,
                                   units="mm")
            cached = self._unjoined_cache = (key, list(graph.warnings))
        return list(cached[1])


def option_names():
    """How the plan's messages name the option they advise (facet.plan.OPTION_NAMES): the
    Lifting's Snap, within which its points are matched."""
    return {"tolerance": translate("Facet", "the Lifting's Snap")}


def pins_in_use(obj):
    """True when ``obj``'s PinnedPoints are its targets (no Targets, no TargetFile)."""
    return bool(obj.PinnedPoints) and obj.Targets is None and not obj.TargetFile


def match_snap(obj):
    """The distance within which a pinned, CSV or drag point is at a plan vertex: the
    Lifting's Snap, else its plan graph's (its vertices moved by up to that as their
    endpoints were merged: pins typed at the drawn corners, 0.1 mm off the merged ones,
    failed with "no target point lies within 0.021 of a plan vertex"), else 0 (the
    default, 1e-6 of the plan's size)."""
    if obj.Snap.Value > 0:
        return obj.Snap.Value
    snap = getattr(obj.Plan, "Snap", None)  # (a PlanGraph's)
    return float(snap.Value) if snap is not None else 0.0


def is_lifting(obj):
    """True if ``obj`` is a Facet Lifting."""
    return getattr(getattr(obj, "Proxy", None), "Type", None) == TYPE_LIFTING


def lifting_summary(obj):
    """A few lines for the report view about a recomputed Lifting."""
    if not obj.isValid():
        return f"{obj.Label}: lifting failed: {obj.getStatusString()}"
    lines = [f"{obj.Label}: {obj.FaceCount} panels, {obj.VertexCount} vertices, lifting space "
             f"of dimension {obj.Dimension}"]
    if obj.OnlyTrivial:
        lines.append("  the plan admits only planes: the result is the best-fitting plane")
    from facetwb.units import length_text

    # (three significant digits in the user's unit: the schema's own text said "missed by
    # 0.00 in RMS", and Building US's eighths of an inch "0")
    lines.append(f"  planarity max {obj.PlanarityMaxRel:.2g} of the edge length; targets missed "
                 f"by {length_text(obj.TargetRms.Value)} RMS, {length_text(obj.TargetMax.Value)} "
                 f"max at vertex {obj.TargetMaxVertex}")
    lines.extend(f"  warning: {text}" for text in getattr(obj, "Warnings", ()))
    return "\n".join(lines)
