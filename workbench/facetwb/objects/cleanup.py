# SPDX-License-Identifier: LGPL-2.1-or-later
"""Cleanup: a parametric polygon mesh with the short edges of its source collapsed.

It links its ``Source`` (a PolyMesh or Planarized object, a FreeCAD Mesh or Part object);
recompute first joins, with ``Weld`` on, the source's vertices at one point that are not one
vertex (``facet.mesh.weld``: an unwelded export's seams, which planarization would open and
panels would cut square), then runs ``facet.cleanup`` (edges shorter than ``MinEdge``
collapse; faces lose corners or disappear) and, with ``Planarize`` on,
``facet.planarize`` on the new mesh. The result has a new topology; the source is never
modified.
"""

import facet
from facet.mesh import weld
from facetwb import compat, progress
from facetwb.recompute import guarded
from facetwb import conversion
from facetwb.objects.polymesh import PolyMesh, set_mesh, set_planarity

TYPE_CLEANUP = "Facet::Cleanup"


class Cleanup(PolyMesh):
    """Proxy of a cleaned-up polygon mesh (App::FeaturePython)."""

    TYPE = TYPE_CLEANUP

    def init_source_properties(self, obj):
        add = compat.add_property
        read_only = compat.EDITOR_READ_ONLY
        output = compat.PROP_OUTPUT
        add(obj, "App::PropertyLink", "Source", "Base",
            "The mesh to clean up (PolyMesh, Planarized, Mesh or Part object); it is never "
            "modified")
        add(obj, "App::PropertyFloat", "MinEdge", "Cleanup",
            "Edges shorter than this collapse: a fraction of the source's mean edge length when "
            "Relative is on, else a length in mm", value=0.1)
        add(obj, "App::PropertyBool", "Relative", "Cleanup",
            "MinEdge is a fraction of the mean edge length", value=True)
        add(obj, "App::PropertyBool", "Weld", "Cleanup",
            "First join the vertices at one point that are not one vertex (within 1e-9 of the "
            "mesh's size): an unwelded export's seams, which planarizing would open",
            value=True)
        add(obj, "App::PropertyBool", "Planarize", "Cleanup",
            "Planarize the new mesh after the collapse", value=True)
        add(obj, "App::PropertyFloat", "Tolerance", "Cleanup",
            "Planarity to reach, relative to each face's mean edge length", value=1e-6)
        for name, doc in (("WeldedVertices", "Source vertices joined to another by Weld"),
                          ("CollapsedEdges", "Edges collapsed"),
                          ("RemovedFaces", "Source faces that fell below 3 vertices"),
                          ("SkippedEdges", "Short edges kept because collapsing them would "
                                           "make the mesh non-manifold")):
            add(obj, "App::PropertyInteger", name, "Result", doc, attr=output,
                editor_mode=read_only)
        add(obj, "App::PropertyLength", "Threshold", "Result",
            "The edge length used", attr=output, editor_mode=read_only)
        add(obj, "App::PropertyBool", "Converged", "Result",
            "True if the planarization reached the tolerance", attr=output,
            editor_mode=read_only)

    @guarded
    def execute(self, obj):
        if obj.Source is None:
            raise ValueError(f"{obj.Label}: Source is empty, nothing to clean up")
        mesh = conversion.mesh_from_object(obj.Source)
        welded = 0
        if obj.Weld:
            mesh, welded = weld(mesh)
        cleaned = facet.cleanup(mesh, obj.MinEdge, relative=obj.Relative)
        result_mesh, converged = cleaned.mesh, False
        if obj.Planarize:
            # progress and Cancel: the creation panel's dialog, or the recompute's own
            result = facet.planarize(cleaned.mesh, tol=obj.Tolerance, progress=progress.hook())
            result_mesh, converged = result.mesh, bool(result.converged)
        set_mesh(obj, result_mesh)
        set_planarity(obj, facet.planarity(result_mesh))
        obj.WeldedVertices = int(welded)
        obj.CollapsedEdges = int(len(cleaned.collapsed_edges))
        obj.RemovedFaces = int(len(cleaned.removed_faces))
        obj.SkippedEdges = int(cleaned.skipped)
        obj.Threshold = float(cleaned.threshold)
        obj.Converged = converged


def is_cleanup(obj):
    """True if ``obj`` is a Facet Cleanup object."""
    return getattr(getattr(obj, "Proxy", None), "Type", None) == TYPE_CLEANUP


def cleanup_summary(obj):
    """One line for the report view about a recomputed Cleanup object."""
    if not obj.isValid():
        return f"{obj.Label}: cleanup failed: {obj.getStatusString()}"
    text = (f"{obj.Label}: {obj.CollapsedEdges} short edges collapsed, {obj.RemovedFaces} faces "
            f"removed: {obj.FaceCount} panels, {obj.VertexCount} vertices")
    if getattr(obj, "WeldedVertices", 0):
        text += f"; {obj.WeldedVertices} vertices at one point with another joined first"
    if obj.SkippedEdges:
        text += f"; {obj.SkippedEdges} short edges kept (would break the mesh)"
    return text
