# SPDX-License-Identifier: LGPL-2.1-or-later
"""The vertex a click would pick, marked while the cursor is near it (preselection).

FreeCAD preselects what is under the cursor as the mouse moves: it asks the view provider
for the element (``ViewProviderPolyMesh.getElementPicked``: ``VertexN`` within
``VERTEX_PICK_PIXELS`` of a corner) and tells the selection observers. On Facet's own Coin
nodes FreeCAD 0.20 can only highlight the whole object, so a designer could not see which
corner a click would pick before clicking. :class:`PreselectionObserver` (one per process,
added by :func:`watch` when the first Facet mesh is drawn) puts a ring on that vertex
(``ViewProviderPolyMesh.preselect``) and takes it away when the preselection goes or moves
to a panel, an edge or another object. ``Gui.Selection.setPreselection(obj, "Vertex5")``
from a script marks it too.
"""

from facetwb.picked import VERTEX, parse_element

#: The observer, once added (one per process).
_observer = []


def watch():
    """Add the observer to Gui.Selection, once; False when there is no GUI."""
    if _observer:
        return True
    try:
        import FreeCADGui as Gui

        observer = PreselectionObserver()
        Gui.Selection.addObserver(observer)
    except Exception:  # noqa: BLE001 - no GUI selection: nothing to mark
        return False
    _observer.append(observer)
    return True


def _proxy(doc_name, obj_name):
    """The view provider proxy of a document's object, or None."""
    import FreeCAD as App

    doc = App.listDocuments().get(doc_name)
    obj = doc.getObject(obj_name) if doc is not None else None
    vobj = getattr(obj, "ViewObject", None) if obj is not None else None
    return getattr(vobj, "Proxy", None) if vobj is not None else None


class PreselectionObserver:
    """Gui.Selection observer: the preselected ``VertexN`` of a Facet mesh ringed."""

    def __init__(self):
        self.marked = None  # the proxy showing the ring

    def unmark(self):
        proxy, self.marked = self.marked, None
        if proxy is not None:
            try:
                proxy.preselect(None)
            except Exception:  # noqa: BLE001 - its object or document is gone
                pass

    def setPreselection(self, doc, obj, sub):  # noqa: N802 - FreeCAD's names
        self.unmark()
        # a subname path ("Part.Mesh.Vertex5") ends with the element
        kind, index = parse_element(str(sub).rsplit(".", 1)[-1])
        if kind != VERTEX:
            return
        proxy = _proxy(doc, obj)
        if hasattr(proxy, "preselect") and proxy.preselect(index):
            self.marked = proxy

    def removePreselection(self, *_args):  # noqa: N802
        self.unmark()
