# SPDX-License-Identifier: LGPL-2.1-or-later
"""make_plan_graph() and make_lifting(): create PlanGraph and Lifting objects (scripting API,
runs headless)."""

import FreeCAD as App

from facetwb.objects.lifting import Lifting
from facetwb.objects.plangraph import PlanGraph
from facetwb.viewproviders import attach


def make_plan_graph(sources=(), file=None, snap=0.0, arc_tolerance=0.0, openings=(),
                    doc=None, name="PlanGraph"):
    """Add a PlanGraph built from ``sources`` (Sketches, Draft wires, Part objects with edges)
    or, when there are none, from ``file`` (.dxf, .csv, .obj, .off, .json).

    Returns the new object; recompute the document to build the graph.
    """
    sources = list(sources)
    if not sources and not file:
        raise ValueError("make_plan_graph needs sources or a file")
    doc = doc or (sources[0].Document if sources else App.ActiveDocument) or App.newDocument()
    obj = doc.addObject("App::FeaturePython", name)
    PlanGraph(obj)
    obj.Label = f"{sources[0].Label} plan" if sources else "Plan"
    obj.Sources = sources
    if file:
        obj.File = str(file)
    obj.Snap = snap
    obj.ArcTolerance = arc_tolerance
    obj.Openings = [App.Vector(float(x), float(y), 0.0) for x, y in openings]
    attach.give(obj)
    return obj


def make_lifting(plan, targets=None, target_file=None, pins=None, weights=None, name="Lifting"):
    """Add a Lifting of ``plan`` (a PlanGraph or Facet mesh) towards ``targets`` (a surface
    object), ``target_file`` or ``pins`` ([(x, y, height), ...] in mm, x and y at plan
    vertices; the other vertices free).

    Returns the new object; recompute the document to solve.
    """
    doc = plan.Document
    obj = doc.addObject("App::FeaturePython", name)
    Lifting(obj)
    obj.Label = f"{plan.Label} lifted"
    obj.Plan = plan
    if targets is not None:
        obj.Targets = targets
    if target_file:
        obj.TargetFile = str(target_file)
    if pins:
        obj.PinnedPoints = [App.Vector(float(x), float(y), float(z)) for x, y, z in pins]
    if weights is not None:
        obj.Weights = [float(w) for w in weights]
    attach.give(obj)
    return obj
