# SPDX-License-Identifier: LGPL-2.1-or-later
"""Vertices picked in the 3D view: a selection to vertex indices, one set of messages for
what is not a vertex of the object asked for.

Every Facet mesh's view provider names what a click hits (``ViewProviderPolyMesh.
getElementPicked``): ``Vertex<n>`` near vertex n (from 0), else ``Face<f>`` or ``Edge<e>``.
A selection is ``[(object, [sub-element names])]``, what ``Gui.Selection.getSelectionEx``
gives (:func:`gui_selection`), so all but that runs headless. The names are made and read
here (:func:`element_name`, :func:`parse_element`), by the view providers too. Used by the
Planarize edit panel's held vertices (``fixed_vertices``) and the Lifting's pinned heights
(``pins``). :func:`mesh_vertex_count`, the number a picked vertex is checked against, reads
a mesh once and keeps the count until a document changes (the edit panel asks on every
selection event).
"""

from facetwb.translation import translate

#: The kinds of sub-element names the view providers give.
VERTEX, EDGE, FACE = "Vertex", "Edge", "Face"


class PickError(ValueError):
    """The selection holds something other than vertices of the object asked for (one
    line: what is selected and what to click)."""


def element_name(kind, index):
    """``Vertex5``: the sub-element name of vertex (edge, face) ``index``."""
    return f"{kind}{int(index)}"


def parse_element(name):
    """``(kind, index)`` of a sub-element name such as ``Vertex5``, or ``(None, None)``."""
    for kind in (VERTEX, EDGE, FACE):
        if name.startswith(kind) and name[len(kind):].isdigit():
            return kind, int(name[len(kind):])
    return None, None


#: mesh_vertex_count's counts, {(document name, object name): vertices}; emptied when any
#: document object changes (_CountsObserver).
_counts = {}
#: The document observer that empties _counts, once added.
_observer = []


class _CountsObserver:
    """Empties the counts on every change of a document object (a property set by an edit,
    a recompute, undo or redo), a deletion or a document closed: a count never outlives
    the mesh it was read from, whatever that mesh is made from (a Link's target, a
    shape's inputs), and stays for a run of selection events."""

    def slotChangedObject(self, _obj, _prop):  # noqa: N802 - FreeCAD's names
        _counts.clear()

    def slotDeletedObject(self, _obj):  # noqa: N802
        _counts.clear()

    def slotDeletedDocument(self, _doc):  # noqa: N802
        _counts.clear()

    def slotUndoDocument(self, _doc):  # noqa: N802
        _counts.clear()

    def slotRedoDocument(self, _doc):  # noqa: N802
        _counts.clear()


def mesh_vertex_count(obj):
    """The number of vertices of ``obj``'s mesh (``conversion.mesh_from_object``: a Facet
    polygon mesh, a Mesh, a shape with faces), read once and kept until a document object
    changes (reading a 10,000-face mesh took 7.5 ms, on every selection event)."""
    from facetwb import conversion

    key = (obj.Document.Name, obj.Name)
    if key in _counts:
        return _counts[key]
    count = conversion.mesh_from_object(obj).n_vertices
    if not _observer:
        try:
            import FreeCAD as App

            observer = _CountsObserver()
            App.addDocumentObserver(observer)
            _observer.append(observer)
        except Exception:  # noqa: BLE001 - no observer: nothing is kept, every call reads
            return count
    _counts[key] = count
    return count


def gui_selection():
    """The 3D view's selection as ``[(object, [sub-element names]), ...]``."""
    import FreeCADGui as Gui

    return [(s.Object, list(s.SubElementNames)) for s in Gui.Selection.getSelectionEx()]


def picked_vertices(selection, target, count, accepts, error=PickError):
    """The vertices picked in ``selection``, in the order picked, each once: ``VertexN``
    of an object ``accepts(object)`` takes, N below ``count``. ``target`` (the object the
    vertices are for) is named in the messages. Raises ``error`` (a PickError) about the
    first entry that is not such a vertex: nothing selected, another object, an object
    selected whole (in the tree), a face or an edge, a vertex the target does not have."""
    if not selection:
        raise error(translate("Facet", "Nothing is selected: click vertices of {0} in the 3D "
                                       "view (Ctrl+click for more)").format(target.Label))
    found = []
    for item, names in selection:
        if not accepts(item):
            raise error(translate("Facet", "{0} is selected: click vertices of {1}").format(
                item.Label, target.Label))
        names = [name for name in names if name]
        if not names:
            raise error(translate("Facet", "{0} is selected as a whole (in the tree?): click "
                                           "its vertices in the 3D view").format(item.Label))
        for name in names:
            kind, index = parse_element(name)
            if kind != VERTEX:
                what = {EDGE: translate("Facet", "an edge"),
                        FACE: translate("Facet", "a face")}.get(kind)
                raise error(translate("Facet", "{0} of {1} is {2}, not a vertex: click closer "
                                               "to a corner (within a few pixels)").format(
                    name, item.Label, what or translate("Facet", "something else")))
            if index >= count:
                raise error(translate("Facet", "{0} of {1}: {2} has {3} vertices (0 to {4})")
                            .format(name, item.Label, target.Label, count, count - 1))
            if index not in found:
                found.append(index)
    return found
