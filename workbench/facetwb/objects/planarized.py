# SPDX-License-Identifier: LGPL-2.1-or-later
"""Planarized: a parametric polygon mesh whose faces are made planar (flat panels).

It links its ``Source`` (a PolyMesh, another Planarized, a FreeCAD Mesh or a Part shape) and
keeps the solver's parameters as properties; recompute runs ``facet.planarize`` on the
source's mesh again. The source is never modified. The result is stored like a PolyMesh's
mesh (so it can be the source of the next step) with the solver's report in ``Result``.
"""

import math
import time

import FreeCAD as App

import facet
from facet.planarize import (ANDERSON_MAX, DATA_TERMS as _PRESETS, QUAD_LAYOUT_ADVICE,
                             preset_shape)
from facetwb import compat, progress
from facetwb.translation import translate
from facetwb.recompute import failure, guarded
from facetwb import conversion
from facetwb.units import length_text
from facetwb.objects.polymesh import PolyMesh, set_mesh, set_planarity

TYPE_PLANARIZED = "Facet::Planarized"

#: Method enumeration: values passed to facet.planarize, and what the designer reads.
METHODS = ["auto", "lg", "ll"]
METHOD_NAMES = {"auto": "automatic", "lg": "local/global", "ll": "local/local"}

#: facet.planarize stop reasons in the designer's words.
STOP_REASONS = {
    "tolerance": "tolerance reached",
    "max_iter": "iteration limit reached, tolerance NOT reached",
    "iterations": "fixed number of iterations done",
    "stagnation": "no further progress",
    "cancelled": "cancelled",
    "time": "time budget used, tolerance NOT reached",
}

#: Enumerations of the solver's terms (first value is the default).
DATA_TERMS = ["point", "plane", "surface"]
BOUNDARY_MODES = ["free", "fixed", "sliding"]
SHAPE_MODES = ["none", "asap", "arap"]

#: Float properties passed to facet.planarize when non-zero: property, option, tooltip.
TERM_WEIGHTS = [
    ("Laplacian", "laplacian", "Vertex Laplacian fairing weight (0: off)"),
    ("NormalLaplacian", "normal_laplacian", "Face-normal smoothing weight (0: off)"),
    ("BoundaryFairness", "boundary_fairness", "Boundary polyline fairing weight (0: off)"),
    ("Circular", "circular", "Make every panel's corners lie on a circle (weight; 0: off)"),
    ("Parallelogram", "parallelogram", "Make every quad a parallelogram (weight; 0: off)"),
]


#: The Result group's read-only outputs of the last solve: property type, name, tooltip.
RESULT_OUTPUTS = [
    ("App::PropertyInteger", "Iterations", "Iterations the last solve ran"),
    ("App::PropertyString", "StopReason",
     "Why the last solve stopped: tolerance, max_iter, iterations, stagnation"),
    ("App::PropertyBool", "Converged", "True if the last solve reached the tolerance"),
    ("App::PropertyString", "QualityCheck",
     "Whether the last solve left a corner under 5 degrees that the source did not have, and "
     "what it did: ok (none), recovered (solved again without one), narrow (every re-solve "
     "left one, or the solve was stopped before one kept them open), not_checked"),
    ("App::PropertyInteger", "NarrowCorners",
     "Corners under 5 degrees in the result that the source did not have"),
    ("App::PropertyFloat", "DataTangentUsed",
     "The tangential data weight the last result was solved with: the Data preset's (0.01 "
     "for plane and surface, 1 for point), or 3 or 10 times it when a quality re-solve held "
     "the vertices more firmly along the design to keep every corner open"),
    ("App::PropertyLength", "DisplacementMax", "Largest distance a vertex moved from the source"),
    ("App::PropertyLength", "DisplacementRms",
     "Root mean square of the distances the vertices moved"),
    ("App::PropertyStringList", "Warnings",
     "What the last solve found worth telling: non-manifold edges, vertices of no face, "
     "coordinates too far from the origin for the tolerance, corners that closed"),
]


class Planarized(PolyMesh):
    """Proxy of a planarized polygon mesh (App::FeaturePython)."""

    TYPE = TYPE_PLANARIZED

    def init_source_properties(self, obj):
        compat.add_property(
            obj, "App::PropertyLink", "Source", "Base",
            "The mesh to planarize (PolyMesh, Planarized, Mesh or Part object); "
            "it is never modified")
        read_only = compat.EDITOR_READ_ONLY
        output = compat.PROP_OUTPUT
        if compat.add_property(
                obj, "App::PropertyEnumeration", "Method", "Planarize",
                "auto: local/global up to 10,000 quads (40,000 corners), local/local above; "
                "lg: local/global (one sparse solve per iteration, converges in few "
                "iterations); ll: local/local (cheap iterations, many of them, little memory)"):
            obj.Method = METHODS
            obj.Method = "auto"
        elif list(obj.getEnumerationsOfProperty("Method")) != METHODS:
            # a document from before "auto": the same method, the new choices
            method = obj.Method
            obj.Method = METHODS
            obj.Method = method
        compat.add_property(
            obj, "App::PropertyFloat", "Tolerance", "Planarize",
            "Stop when every face's vertices are within this fraction of the face's mean edge "
            "length from its best-fit plane", value=1e-6)
        compat.add_property(
            obj, "App::PropertyLength", "ToleranceAbs", "Planarize",
            "Stop when every face's vertices are within this distance of its best-fit plane "
            "(0: use Tolerance only)")
        compat.add_property(
            obj, "App::PropertyInteger", "MaxIterations", "Planarize",
            "Most iterations to run (0: the solver's default)")
        compat.add_property(
            obj, "App::PropertyInteger", "Threads", "Planarize",
            "Threads for the solver (0: one per 25,000 quads, at most all cores)")
        if compat.add_property(
                obj, "App::PropertyEnumeration", "Data", "Terms",
                "What the result stays close to: point (each vertex near its control point), "
                "plane (near its tangent plane) or surface (on the design surface, free to "
                "slide along it); plane and surface add a mild shape term"):
            obj.Data = DATA_TERMS
            obj.Data = "point"
        compat.add_property(
            obj, "App::PropertyLink", "Reference", "Terms",
            "Design surface for Data = surface (a PolyMesh, Mesh or Part object); empty: "
            "the source mesh's own surface")
        if compat.add_property(
                obj, "App::PropertyEnumeration", "Boundary", "Terms",
                "Boundary vertices: free, fixed in place, or sliding along the boundary "
                "(corners stay)"):
            obj.Boundary = BOUNDARY_MODES
            obj.Boundary = "free"
        compat.add_property(
            obj, "App::PropertyIntegerList", "FixedVertices", "Terms",
            "Vertex indices that must not move")
        compat.add_property(
            obj, "App::PropertyFloatList", "FaceWeights", "Terms",
            "Per-panel planarity weights, one per face (0: exempt, e.g. an opening); "
            "empty: all 1")
        if compat.add_property(
                obj, "App::PropertyEnumeration", "Shape", "Terms",
                "Keep each panel a similar (asap) or congruent (arap) copy of its control "
                "face; Default follows Data"):
            obj.Shape = ["default"] + SHAPE_MODES
            obj.Shape = "default"
        compat.add_property(
            obj, "App::PropertyFloat", "ShapeWeight", "Terms",
            "Weight of the shape term (0: the default)")
        for name, _option, tip in TERM_WEIGHTS:
            compat.add_property(obj, "App::PropertyFloat", name, "Terms", tip)
        compat.add_property(
            obj, "App::PropertyInteger", "Anderson", "Planarize",
            "Anderson acceleration depth (0: off)", value=5)
        compat.add_property(
            obj, "App::PropertyFloat", "TimeBudget", "Planarize",
            "Stop after this many seconds (0: no limit)")
        for kind, name, tip in RESULT_OUTPUTS:
            compat.add_property(obj, kind, name, "Result", tip, attr=output, editor_mode=read_only)

    @guarded
    def execute(self, obj):
        if obj.Source is None:
            raise ValueError(f"{obj.Label}: Source is empty, nothing to planarize")
        mesh = conversion.mesh_from_object(obj.Source)
        follow = _Follow.of(obj)
        finished = False
        try:
            result = facet.planarize(
                mesh,
                method=obj.Method,
                tol=non_negative(obj, "Tolerance"),
                tol_abs=non_negative(obj, "ToleranceAbs", obj.ToleranceAbs.Value) or None,
                max_iter=count(obj, "MaxIterations") or None,
                threads=obj.Threads or None,  # any value: <= 0 by mesh size
                progress=follow and follow.progress,
                stage=follow and follow.stage,
                **term_options(obj, mesh),
            )
            finished = True
        except facet.Cancelled as stopped:
            # "Stop and keep" (offered once a result reached the tolerance): that result
            if follow is None or not follow.report.keeps or stopped.result is None:
                raise
            result = stopped.result
            finished = True
        finally:
            if follow is not None:
                # Cancel again, for what follows; a press that kept is spent
                follow.report.withdraw_keep(finished)
                follow.say(None)
        set_mesh(obj, result.mesh)
        set_planarity(obj, result.planarity)
        self.method_ran = result.method  # what "auto" chose; for the report, not saved
        self.compared = result.compared  # and what it compared (the same)
        self.stopped = result.stopped  # Stop and keep (the same)
        # the source's planarity over the faces the result's figure counts (the same)
        self.source_max_abs = float(
            facet.planarity(mesh).leaving_out(result.planarity.exempt).max_abs_all)
        # faces with a nearly straight corner, the result's and the source's: a quad
        # made a triangle with a kink, which the CLI's summary counted and the report
        # view did not (the summary's, not saved)
        from facet.quality import straight_corner_faces

        self.straight_corners = (int(straight_corner_faces(result.mesh).size),
                                 int(straight_corner_faces(mesh).size))
        obj.Iterations = int(result.iterations)
        obj.StopReason = str(result.stop_reason)
        obj.Converged = bool(result.converged)
        obj.QualityCheck = str(result.quality_check)
        obj.NarrowCorners = int(result.narrow_corners)
        obj.DataTangentUsed = float(result.data_tangent)
        obj.DisplacementMax = float(result.displacement_max)
        obj.DisplacementRms = float(result.displacement_rms)
        if list(obj.Warnings) != list(result.warnings):
            obj.Warnings = list(result.warnings)


class _Follow:
    """The progress dialog while a Planarized object solves (None without one): the bar
    counts the iterations, through the quality re-solves; the text says which re-solve
    runs and, a few times a second, the planarity reached against the tolerance (the bar
    alone says little: its bound is the whole solve's limit, re-solves included)."""

    #: Seconds between two planarity texts.
    INTERVAL = 0.25

    @classmethod
    def of(cls, obj):
        report, say = progress.hook(), progress.say_hook()
        return None if report is None or say is None else cls(obj, report, say)

    def __init__(self, obj, report, say):
        self.obj, self.report, self.say = obj, report, say
        # (a tolerance in model units stops the solve instead: no relative one to show)
        self.tolerance = None if obj.ToleranceAbs.Value > 0 else float(obj.Tolerance)
        self.stage_text = None
        self.shown = None  # when the last planarity text was shown

    def progress(self, iteration, max_iter, planarity):
        now = time.monotonic()
        if self.shown is None or now - self.shown >= self.INTERVAL:
            self.shown = now
            line = (translate("Facet", "planarity {0:.2g}").format(float(planarity))
                    if self.tolerance is None else
                    translate("Facet", "planarity {0:.2g} (tolerance {1:.2g})").format(
                        float(planarity), self.tolerance))
            self.say(line if self.stage_text is None else f"{self.stage_text}\n{line}")
        return self.report(iteration, max_iter, planarity)

    def stage(self, k, n):
        """facet.planarize's ``stage(k, n)``: the re-solve, or one of method auto's
        comparison solves (k == facet.planarize.STAGE_COMPARE or STAGE_FINER) or its
        fallback (STAGE_FALLBACK), in the text."""
        from facet.planarize import STAGE_COMPARE, STAGE_FALLBACK, STAGE_FINER

        if k == STAGE_COMPARE:
            text = translate(
                "Facet", "Planarize {0}: solving by local/local too, for a result closer to the design")
        elif k == STAGE_FINER:
            text = translate(
                "Facet", "Planarize {0}: solving by local/global again with a finer hold, closer to the design")
        elif k == STAGE_FALLBACK:
            text = translate("Facet", "Planarize {0}: local/local closed a panel, solving by local/global")
        else:
            text = translate("Facet", "Planarize {0}: re-solving for panel quality (stage {1} of {2})")
        if k != STAGE_FALLBACK:
            # a result at the tolerance is in hand. The fallback's L/L result may have
            # stalled short of it; when it had re-solves it had reached it, and their
            # offer stands.
            self.report.offer_keep()
        self.stage_text = text.format(self.obj.Label, k, n)
        self.say(self.stage_text)
        self.shown = None  # and its planarity at its first iteration


def term_options(obj, mesh):
    """The facet.planarize options of a Planarized object's Terms properties.

    Raises ValueError naming the object and the property when one does not fit the mesh.
    """
    options = {"data": obj.Data, "boundary": obj.Boundary,
               "anderson": count(obj, "Anderson", most=ANDERSON_MAX)}
    if obj.Shape != "default":
        options["shape"] = obj.Shape
    shape_weight = non_negative(obj, "ShapeWeight")
    if shape_weight > 0:
        if preset_shape(options.get("shape"), obj.Data) == "none":
            raise ValueError(f"{obj.Label}: ShapeWeight weighs the shape term, which is off "
                             f"(Shape {obj.Shape}, Data {obj.Data}): set Shape to asap or arap, "
                             "or ShapeWeight to 0")
        options["shape_weight"] = shape_weight
    for name, option, _tip in TERM_WEIGHTS:
        value = non_negative(obj, name)
        if value > 0:
            options[option] = value
    time_budget = non_negative(obj, "TimeBudget")
    if time_budget > 0:
        options["time_budget"] = time_budget
    fixed = list(obj.FixedVertices)
    bad = [v for v in fixed if not 0 <= v < mesh.n_vertices]
    if bad:
        raise ValueError(f"{obj.Label}: FixedVertices has vertex {bad[0]}, out of range "
                         f"({mesh.n_vertices} vertices)")
    if fixed:
        options["fixed"] = fixed
    weights = list(obj.FaceWeights)
    if weights:
        if len(weights) != mesh.n_faces:
            raise ValueError(f"{obj.Label}: FaceWeights has {len(weights)} values for "
                             f"{mesh.n_faces} faces")
        from facet.planarize import FACE_WEIGHT_MAX

        bad = [f for f, w in enumerate(weights) if not 0.0 <= w <= FACE_WEIGHT_MAX]
        if bad:
            raise ValueError(f"{obj.Label}: FaceWeights: face {bad[0]} has weight "
                             f"{weights[bad[0]]:g}; weights must be in [0, {FACE_WEIGHT_MAX:g}]")
        options["face_weights"] = weights
    if obj.Reference is not None:
        if obj.Data != "surface":
            raise ValueError(f"{obj.Label}: Reference is the design surface that Data surface "
                             f"holds the vertices to; with Data {obj.Data} it would be "
                             "ignored: set Data to surface, or clear Reference")
        options["reference"] = conversion.mesh_from_object(obj.Reference)
    return options


def non_negative(obj, name, value=None):
    """Property `name` of `obj` (or its `value`), refused unless a finite number >= 0: a NaN
    weight was taken for 0 (term off) and saved with the document."""
    value = float(getattr(obj, name) if value is None else value)
    if not 0.0 <= value < math.inf:
        raise ValueError(f"{obj.Label}: {name} is {value}; it must be a finite number, 0 or "
                         "more")
    return value


def count(obj, name, most=2**31 - 1):
    """Integer property `name` of `obj`, refused unless from 0 to `most`."""
    value = int(getattr(obj, name))
    if not 0 <= value <= most:
        raise ValueError(f"{obj.Label}: {name} is {value}; it must be from 0 to {most}")
    return value


def is_planarized(obj):
    """True if ``obj`` is a Facet Planarized object."""
    return getattr(getattr(obj, "Proxy", None), "Type", None) == TYPE_PLANARIZED


def method_text(obj):
    """The Method as the designer reads it; for auto, with what it chose (e.g. 'automatic:
    local/global') once the object was solved in this session."""
    text = METHOD_NAMES.get(obj.Method, obj.Method)
    ran = getattr(getattr(obj, "Proxy", None), "method_ran", None)
    if obj.Method == "auto" and ran in METHOD_NAMES:
        text += f": {METHOD_NAMES[ran]}"
    return text


def _compared_text(compared, kept):
    """The summary line of method auto's comparison (facet.PlanarizeResult.compared)."""
    if not (compared.get("lg") and compared.get("ll")) or kept not in ("lg", "ll"):
        return "  local/local also tried: it did not reach the tolerance; local/global kept"
    other = "ll" if kept == "lg" else "lg"
    a, b = compared[kept], compared[other]
    text = (f"  local/global and local/local compared: {METHOD_NAMES[kept]} kept, "
            f"distance from the source surface rms {length_text(a['distance_rms'])}, "
            f"vertices moved rms {length_text(a['displacement_rms'])}, smallest corner "
            f"{a['min_angle']:.1f} deg; {METHOD_NAMES[other]}: "
            f"{length_text(b['distance_rms'])}, {length_text(b['displacement_rms'])}, "
            f"{b['min_angle']:.1f} deg")
    finer = compared.get("finer")
    if finer:
        text += (f"; local/global again with a finer hold ({finer['iterations']} iterations): "
                 + ("its result kept" if finer["kept"] else "not closer, the first result kept"))
    return text


def planarize_summary(obj):
    """A few lines for the report view about a recomputed Planarized object."""
    if not obj.isValid():
        return failure(obj)
    exempt = sum(1 for w in obj.FaceWeights if w == 0.0)
    # measured by the last recompute; in a document just opened, the source's own figure
    # (over all its faces: not with exempt faces)
    source_max_abs = getattr(obj.Proxy, "source_max_abs", None)
    if source_max_abs is None and not exempt and hasattr(obj.Source, "PlanarityMaxAbs"):
        source_max_abs = obj.Source.PlanarityMaxAbs.Value
    lines = [
        f"{obj.Label}: {obj.FaceCount} panels, {obj.VertexCount} vertices, "
        f"{method_text(obj)}, {obj.Iterations} iterations, "
        f"stopped: {STOP_REASONS.get(obj.StopReason, obj.StopReason)}",
        f"  planarity max {length_text(obj.PlanarityMaxAbs.Value)} "
        f"({obj.PlanarityMaxRel:.2g} of the edge length)"
        + (f", source {length_text(source_max_abs)}" if source_max_abs is not None else "")
        + (f"; {exempt} exempt face{'s' if exempt != 1 else ''} (FaceWeights 0) not counted"
           if exempt else ""),
        f"  vertices moved: max {length_text(obj.DisplacementMax.Value)}, "
        f"rms {length_text(obj.DisplacementRms.Value)}",
    ]
    proxy = getattr(obj, "Proxy", None)
    if getattr(proxy, "stopped", False):
        lines.append("  stopped (Stop and keep): the result that had reached the tolerance is "
                     "kept; what ran after it did not finish")
    compared = getattr(proxy, "compared", None)
    if obj.Method == "auto" and compared:
        lines.append(_compared_text(compared, getattr(proxy, "method_ran", None)))
    check = getattr(obj, "QualityCheck", "")
    if check == "recovered":
        # held more firmly than the Data preset asks (DataTangentUsed: 0 in a document
        # from before it, which never says so)
        asked = _PRESETS.get(obj.Data, {}).get("data_tangent")
        used = getattr(obj, "DataTangentUsed", 0.0)
        lines.append("  a panel corner closed below 5 degrees; solved again without it"
                     + (f", holding the vertices more firmly along the design (data tangent "
                        f"{used:g} instead of {asked:g})" if asked and used > asked else ""))
    elif check == "narrow" or obj.NarrowCorners:
        # narrow: no re-solve kept them open; else the solve stopped short of the
        # tolerance, and such a result is not re-solved
        why = ("" if check == "narrow" else
               ", not re-solved: the solve stopped short of the tolerance")
        lines.append(f"  {obj.NarrowCorners} panel corners under 5 degrees that the source "
                     f"did not have{why} (see the quality report)")
    straight, source_straight = getattr(proxy, "straight_corners", None) or (0, 0)
    if straight > source_straight:
        from facet.quality import DEFAULT_STRAIGHT_CORNER

        lines.append(f"  {straight} panel{'s' if straight != 1 else ''} with a corner within "
                     f"{DEFAULT_STRAIGHT_CORNER:g} degrees of straight (the source had "
                     f"{source_straight}): triangles with a kink to a fabricator, where "
                     "mitred panel edges may not fit; ColorBy Straightest corner shows them")
    for text in getattr(obj, "Warnings", ()):
        if "that the input did not have" in text:  # said above; its advice is not
            if QUAD_LAYOUT_ADVICE in text:
                lines.append(f"  {QUAD_LAYOUT_ADVICE}")
        else:
            lines.append(f"  warning: {text}")
    return "\n".join(lines)
