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

from facetwb.objects.planarized import is_planarized
from facetwb.objects.polymesh import is_polymesh
from facetwb.picked import PickError, mesh_vertex_count, picked_vertices
from facetwb.translation import translate


class SelectionError(PickError):
    """The selection holds no vertex of the object, or something else (one line: what is
    selected and what to do)."""


def vertex_count(obj):
    """Vertices of the Planarized object's Source, the mesh FixedVertices numbers; raises
    SelectionError when its result does not show that mesh (not recomputed since)."""
    if obj.Source is None:
        raise SelectionError(translate("Facet", "{0}: Source is empty, it has no vertices")
                             .format(obj.Label))
    count = mesh_vertex_count(obj.Source)
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
    source = obj.Source

    def accepts(item):
        return item is obj or (item is source and is_polymesh(source))

    count = vertex_count(obj) if selection else 0
    return sorted(picked_vertices(selection, obj, count, accepts, SelectionError))


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
