# SPDX-License-Identifier: LGPL-2.1-or-later
"""Hold vertices of a Planarized object in place: the 3D view's selection to FixedVertices.

A designer clicks corners of the planarized mesh in the 3D view (Ctrl+click for more): the
view provider names each "VertexN" (N: the vertex's index, from 0, the numbering
FixedVertices uses; ViewProviderPolyMesh.getElementPicked). The Planarize edit panel's Hold
and Free buttons pass the selection to :func:`selected_vertices`, then :func:`hold` or
:func:`free`. The planarized mesh and its Source share the numbering (the solver moves
vertices, it never renumbers them), so corners picked on the control mesh (a Facet polygon
mesh) count too. Runs headless: a selection is a list of ``(object, sub-element names)``.
"""

import re

from facetwb.objects.planarized import is_planarized
from facetwb.objects.polymesh import is_polymesh
from facetwb.translation import translate

_VERTEX = re.compile(r"^Vertex(\d+)$")


class SelectionError(ValueError):
    """The selection holds no vertex of the object, or something else (one line: what is
    selected and what to do)."""


def gui_selection():
    """The 3D view's selection as ``[(object, sub-element names), ...]``."""
    import FreeCADGui as Gui

    return [(s.Object, tuple(s.SubElementNames)) for s in Gui.Selection.getSelectionEx()]


def vertex_count(obj):
    """Vertices of the Planarized object's Source, the mesh FixedVertices numbers; raises
    SelectionError when its result does not show that mesh (not recomputed since)."""
    from facetwb import conversion

    if obj.Source is None:
        raise SelectionError(translate("Facet", "{0}: Source is empty, it has no vertices")
                             .format(obj.Label))
    count = conversion.mesh_from_object(obj.Source).n_vertices
    if obj.VertexCount != count:
        raise SelectionError(translate(
            "Facet", "{0} shows {1} vertices, its Source {2} has {3}: recompute it, then "
                     "select its vertices").format(obj.Label, obj.VertexCount,
                                                   obj.Source.Label, count))
    return count


def selected_vertices(obj, selection):
    """Sorted indices of the vertices of Planarized ``obj`` in ``selection`` (pairs of an
    object and its sub-element names): vertices picked on ``obj`` or on its Source when
    that is a Facet polygon mesh. Raises SelectionError naming the first item that is not
    such a vertex (a panel, an edge, a whole object, another object) or when nothing is
    selected."""
    if not is_planarized(obj):
        raise SelectionError(f"{getattr(obj, 'Label', obj)} is not a Planarized object")
    if not selection:
        raise SelectionError(translate(
            "Facet", "Nothing is selected: click corners of {0} in the 3D view (Ctrl+click "
                     "for more)").format(obj.Label))
    count = vertex_count(obj)
    source = obj.Source
    vertices = set()
    for item, names in selection:
        if item is not obj and not (item is source and is_polymesh(source)):
            raise SelectionError(translate(
                "Facet", "{0} is selected: select vertices of {1} (its corners in the 3D "
                         "view)").format(item.Label, obj.Label))
        if not names:
            raise SelectionError(translate(
                "Facet", "{0} is selected as a whole: click on its corners to select "
                         "vertices").format(item.Label))
        for name in names:
            match = _VERTEX.match(name)
            if match is None:
                raise SelectionError(translate(
                    "Facet", "{0} of {1} is not a vertex: click nearer a panel's "
                             "corner").format(name, item.Label))
            vertex = int(match.group(1))
            if vertex >= count:
                raise SelectionError(translate(
                    "Facet", "{0} of {1}: the mesh has {2} vertices (0 to {3})").format(
                    name, item.Label, count, count - 1))
            vertices.add(vertex)
    return sorted(vertices)


def hold(obj, vertices):
    """Add ``vertices`` to ``obj.FixedVertices`` (sorted, each once); returns how many
    were not held before. The property is set only when it changes (which re-solves)."""
    fixed = set(obj.FixedVertices)
    new = sorted(fixed | set(vertices))
    if new != list(obj.FixedVertices):
        obj.FixedVertices = new
    return len(new) - len(fixed)


def free(obj, vertices=None):
    """Remove ``vertices`` (None: all) from ``obj.FixedVertices``; returns how many were
    held."""
    fixed = list(obj.FixedVertices)
    new = [] if vertices is None else sorted(set(fixed) - set(vertices))
    if new != fixed:
        obj.FixedVertices = new
    return len(set(fixed)) - len(new)


def held_text(obj):
    """"3 vertices held" (or "no vertex held"), for the panel."""
    count = len(set(obj.FixedVertices))
    if count == 0:
        return translate("Facet", "No vertex held")
    if count == 1:
        return translate("Facet", "1 vertex held")
    return translate("Facet", "{0} vertices held").format(count)
