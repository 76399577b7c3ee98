# SPDX-License-Identifier: LGPL-2.1-or-later
"""Planarized: a parametric polygon mesh whose faces are made planar (flat panels).

It links its ``Source`` (a PolyMesh, another Planarized, a FreeCAD Mesh or a Part shape) and
keeps the solver's parameters as properties; recompute runs ``facet.planarize`` on the
source's mesh again. The source is never modified. The result is stored like a PolyMesh's
mesh (so it can be the source of the next step) with the solver's report in ``Result``.
"""

import FreeCAD as App

import facet
from facetwb import compat
from facetwb import conversion
from facetwb.objects.polymesh import PolyMesh, set_mesh, set_planarity

TYPE_PLANARIZED = "Facet::Planarized"

#: Method enumeration: values passed to facet.planarize, and what the designer reads.
METHODS = ["lg", "ll"]
METHOD_NAMES = {"lg": "local/global", "ll": "local/local"}

#: facet.planarize stop reasons in the designer's words.
STOP_REASONS = {
    "tolerance": "tolerance reached",
    "max_iter": "iteration limit reached, tolerance NOT reached",
    "iterations": "fixed number of iterations done",
    "stagnation": "no further progress",
    "cancelled": "cancelled",
}


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
                "lg: local/global (one sparse solve per iteration, converges in few "
                "iterations); ll: local/local (cheap iterations, many of them)"):
            obj.Method = METHODS
            obj.Method = "lg"
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
            "Threads for the solver (0: all cores)")
        compat.add_property(obj, "App::PropertyInteger", "Iterations", "Result",
                            "Iterations the last solve ran", attr=output, editor_mode=read_only)
        compat.add_property(obj, "App::PropertyString", "StopReason", "Result",
                            "Why the last solve stopped: tolerance, max_iter, iterations, "
                            "stagnation", attr=output, editor_mode=read_only)
        compat.add_property(obj, "App::PropertyBool", "Converged", "Result",
                            "True if the last solve reached the tolerance", attr=output,
                            editor_mode=read_only)
        compat.add_property(obj, "App::PropertyLength", "DisplacementMax", "Result",
                            "Largest distance a vertex moved from the source", attr=output,
                            editor_mode=read_only)
        compat.add_property(obj, "App::PropertyLength", "DisplacementRms", "Result",
                            "Root mean square of the distances the vertices moved",
                            attr=output, editor_mode=read_only)

    def execute(self, obj):
        if obj.Source is None:
            raise ValueError(f"{obj.Label}: Source is empty, nothing to planarize")
        mesh = conversion.mesh_from_object(obj.Source)
        result = facet.planarize(
            mesh,
            method=obj.Method,
            tol=obj.Tolerance,
            tol_abs=obj.ToleranceAbs.Value or None,
            max_iter=obj.MaxIterations or None,
            threads=obj.Threads or None,
        )
        set_mesh(obj, result.mesh)
        set_planarity(obj, result.planarity)
        obj.Iterations = int(result.iterations)
        obj.StopReason = str(result.stop_reason)
        obj.Converged = bool(result.converged)
        obj.DisplacementMax = float(result.displacement_max)
        obj.DisplacementRms = float(result.displacement_rms)


def is_planarized(obj):
    """True if ``obj`` is a Facet Planarized object."""
    return getattr(getattr(obj, "Proxy", None), "Type", None) == TYPE_PLANARIZED


def format_length(value):
    """A length in mm as FreeCAD shows lengths (the user's unit schema), e.g. '2.31 mm'."""
    return App.Units.Quantity(float(value), App.Units.Length).UserString


def planarize_summary(obj):
    """A few lines for the report view about a recomputed Planarized object."""
    if not obj.isValid():
        return f"{obj.Label}: planarize failed: {obj.getStatusString()}"
    source = obj.Source
    lines = [
        f"{obj.Label}: {obj.FaceCount} panels, {obj.VertexCount} vertices, "
        f"{METHOD_NAMES.get(obj.Method, obj.Method)}, {obj.Iterations} iterations, "
        f"stopped: {STOP_REASONS.get(obj.StopReason, obj.StopReason)}",
        f"  planarity max {format_length(obj.PlanarityMaxAbs.Value)} "
        f"({obj.PlanarityMaxRel:.2g} of the edge length)"
        + (f", source {format_length(source.PlanarityMaxAbs.Value)}"
           if source is not None and hasattr(source, "PlanarityMaxAbs") else ""),
        f"  vertices moved: max {format_length(obj.DisplacementMax.Value)}, "
        f"rms {format_length(obj.DisplacementRms.Value)}",
    ]
    return "\n".join(lines)
