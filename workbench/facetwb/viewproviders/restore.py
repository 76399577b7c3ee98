# SPDX-License-Identifier: LGPL-2.1-or-later
"""View providers for the Facet objects of documents saved without the GUI.

A document saved by ``freecadcmd`` (a script, ``tools/make_examples.py``) holds no
``GuiDocument.xml``. Opened in the GUI, its Facet objects had no view provider: nothing
drawn, no colour map or legend, no task panel on double-click. Each Facet object's
``onDocumentRestored`` calls :func:`schedule`. Once the document has loaded, and its
``GuiDocument.xml`` with it, an object still without a view provider gets its own, as
the ``make_*`` functions give it.
"""

import FreeCAD as App

_pending = []


def schedule(obj):
    """Attach ``obj``'s view provider after the document has loaded, if it has none then.
    Headless: nothing to do."""
    if not App.GuiUp:
        return
    _pending.append((obj.Document.Name, obj.Name))
    if len(_pending) == 1:
        from PySide import QtCore

        QtCore.QTimer.singleShot(0, attach_pending)


def _objects(items):
    for doc_name, name in items:
        try:
            obj = App.getDocument(doc_name).getObject(name)
            view = obj.ViewObject if obj is not None else None
        except (NameError, ReferenceError):  # the document was closed meanwhile
            continue
        if view is not None:
            yield obj, view


def attach_pending():
    """Attach the view providers of the objects scheduled since the last call; their
    display modes and the sources they hide come next (the modes exist only once the
    view providers have been attached)."""
    items = list(_pending)
    _pending.clear()
    attached = []
    for obj, view in _objects(items):
        # (FreeCAD gives such a view object the placeholder Proxy 1)
        if isinstance(getattr(view, "Proxy", None), (type(None), int)):
            try:
                attach(obj)
                attached.append((obj.Document.Name, obj.Name))
            except Exception as error:  # noqa: BLE001 - one object must not stop the rest
                App.Console.PrintError(f"Facet: {obj.Label}: no view provider: {error}\n")
    if attached:
        from PySide import QtCore

        QtCore.QTimer.singleShot(0, lambda: _finish(attached))


def _finish(items):
    for obj, view in _objects(items):
        proxy = view.Proxy
        if not view.DisplayMode and hasattr(proxy, "getDefaultDisplayMode"):
            try:
                # FreeCAD left the restored property's list of modes empty: the
                # provider's own, then its default
                view.DisplayMode = list(view.listDisplayModes())
                view.DisplayMode = proxy.getDefaultDisplayMode()
            except (ValueError, TypeError) as error:
                App.Console.PrintWarning(f"Facet: {obj.Label}: display mode: {error}\n")
        # what the make_* functions hide: the source under its result
        for name in HIDDEN_SOURCES.get(obj.Proxy.Type, ()):
            for source in _links(getattr(obj, name, None)):
                if getattr(source, "ViewObject", None) is not None:
                    source.ViewObject.Visibility = False


def attach(obj):
    """Give ``obj`` the view provider of its Facet type."""
    kind = getattr(getattr(obj, "Proxy", None), "Type", None)
    view = obj.ViewObject
    if kind == "Facet::PanelSet" or kind == "Facet::CutSheets":
        from facetwb.objects.panelset import ViewProviderPanels

        ViewProviderPanels(view, "Facet_PanelSet" if kind == "Facet::PanelSet"
                           else "Facet_CutSheets")
        return
    providers = {
        "Facet::PolyMesh": ("view_polymesh", "ViewProviderPolyMesh"),
        "Facet::Planarized": ("view_planarized", "ViewProviderPlanarized"),
        "Facet::PlanGraph": ("view_lifting", "ViewProviderPlanGraph"),
        "Facet::Lifting": ("view_lifting", "ViewProviderLifting"),
        "Facet::Cleanup": ("view_cleanup", "ViewProviderCleanup"),
        "Facet::SurfaceMesh": ("view_surfacemesh", "ViewProviderSurfaceMesh"),
    }
    if kind in providers:
        import importlib

        module, name = providers[kind]
        getattr(importlib.import_module(f"facetwb.viewproviders.{module}"), name)(view)


#: The links whose objects a result's make_* function hides, by type.
HIDDEN_SOURCES = {
    "Facet::Planarized": ("Source",),
    "Facet::Cleanup": ("Source",),
    "Facet::SurfaceMesh": ("Source",),
    "Facet::PlanGraph": ("Sources",),
    "Facet::Lifting": ("Plan", "Targets"),
}


def _links(value):
    if value is None:
        return []
    return list(value) if isinstance(value, (list, tuple)) else [value]
