# SPDX-License-Identifier: LGPL-2.1-or-later
"""Straight plan segments out of FreeCAD objects: Sketches, Draft wires and lines, any Part
shape with edges. Wiring only: the plan graph is built by ``facet.plan``.

Coordinates are global (placements applied), in mm, projected vertically onto the XY plane;
the edges must lie in a horizontal plane. Lines give one segment; other curves (arcs,
circles, splines) are refused unless ``arc_tolerance`` > 0, then split into segments whose
distance from the curve is at most that (OCC's discretization by deflection).
"""

from facet.plan import PlanError


def segments_from_objects(objects, arc_tolerance=0.0):
    """``[((x1, y1), (x2, y2)), ...]`` from the edges of ``objects``."""
    import Part

    segments = []
    for obj in objects:
        shape = getattr(obj, "Shape", None)
        if shape is None or shape.isNull() or not shape.Edges:
            raise PlanError(f"{obj.Label} has no edges to read a plan from")
        box = shape.BoundBox
        size = max(box.XLength, box.YLength)
        if not size > 0:
            raise PlanError(f"{obj.Label}: its edges have no extent in plan")
        if box.ZLength > 1e-6 * size:
            raise PlanError(
                f"{obj.Label}: its edges are not in a horizontal plane (they span "
                f"{box.ZLength:.6g} mm in z): draw the plan on the XY plane")
        for number, edge in enumerate(shape.Edges, 1):
            if isinstance(edge.Curve, (Part.Line, Part.LineSegment)):
                a, b = edge.Vertexes[0].Point, edge.Vertexes[-1].Point
                segments.append(((a.x, a.y), (b.x, b.y)))
                continue
            if not arc_tolerance > 0:
                raise PlanError(
                    f"{obj.Label}: edge {number} is a {type(edge.Curve).__name__}, not a "
                    "straight line: set ArcTolerance to split curves into segments")
            points = edge.discretize(Deflection=float(arc_tolerance))
            segments.extend(((p.x, p.y), (q.x, q.y)) for p, q in zip(points[:-1], points[1:]))
    if not segments:
        raise PlanError("no edges to read a plan from")
    return segments
