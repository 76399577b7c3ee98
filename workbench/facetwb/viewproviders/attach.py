# SPDX-License-Identifier: LGPL-2.1-or-later
"""The view provider of each Facet object type, given at creation and on restore.

:func:`give` is what the ``make_*`` functions call: the object's view provider, its
colours, and its sources hidden under it. A document saved by ``freecadcmd`` (a script,
``tools/make_examples.py``) holds no ``GuiDocument.xml``. Opened in the GUI, its Facet
objects had no view provider: nothing drawn, no colour map or legend, no task panel on
double-click. Each Facet object's ``onDocumentRestored`` calls :func:`schedule`. Once the
document has loaded, and its ``GuiDocument.xml`` with it, an object still without a view
provider gets the same as :func:`give` gives, and its ``attach`` is called when FreeCAD
does not call it (it attached the placeholder Proxy it restored instead), and the
document's 3D view is fitted to it (it had no saved camera either).
"""

import FreeCAD as App

#: View provider (module in facetwb.viewproviders, class) by Facet type.
PROVIDERS = {
    "Facet::PolyMesh": ("view_polymesh", "ViewProviderPolyMesh"),
    "Facet::Planarized": ("view_planarized", "ViewProviderPlanarized"),
    "Facet::PlanGraph": ("view_lifting", "ViewProviderPlanGraph"),
    "Facet::Lifting": ("view_lifting", "ViewProviderLifting"),
    "Facet::Cleanup": ("view_cleanup", "ViewProviderCleanup"),
    "Facet::SurfaceMesh": ("view_surfacemesh", "ViewProviderSurfaceMesh"),
}

#: The links whose objects are hidden under the object, by Facet type.
HIDDEN_SOURCES = {
    "Facet::PolyMesh": ("Source",),
    "Facet::Planarized": ("Source",),
    "Facet::Cleanup": ("Source",),
    "Facet::SurfaceMesh": ("Source",),
    "Facet::PlanGraph": ("Sources",),
    "Facet::Lifting": ("Plan", "Targets"),
}

_pending = []


def give(obj):
    """A new object's view provider, and its sources hidden (headless: nothing)."""
    if App.GuiUp:
        attach(obj)
        hide_sources(obj)


def attach(obj):
    """Give ``obj`` the view provider of its Facet type (and a PanelSet's or CutSheets'
    colours)."""
    kind = getattr(getattr(obj, "Proxy", None), "Type", None)
    view = obj.ViewObject
    if kind in ("Facet::PanelSet", "Facet::CutSheets"):
        from facetwb.objects.panelset import ViewProviderPanels

        if kind == "Facet::PanelSet":
            ViewProviderPanels(view, "Facet_PanelSet")
            view.ShapeColor = (0.78, 0.84, 0.91)
        else:
            ViewProviderPanels(view, "Facet_CutSheets")
            view.LineColor = (0.8, 0.0, 0.0)
    elif kind in PROVIDERS:
        import importlib

        module, name = PROVIDERS[kind]
        getattr(importlib.import_module(f"facetwb.viewproviders.{module}"), name)(view)


def hide_sources(obj):
    """Hide the objects ``obj`` is made from (HIDDEN_SOURCES)."""
    for name in HIDDEN_SOURCES.get(obj.Proxy.Type, ()):
        value = getattr(obj, name, None)
        for source in value if isinstance(value, (list, tuple)) else [value]:
            if getattr(source, "ViewObject", None) is not None:
                source.ViewObject.Visibility = False


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
                proxy = view.Proxy
                if getattr(proxy, "ViewObject", None) is None and hasattr(proxy, "attach"):
                    # FreeCAD attached the placeholder Proxy and does not attach the one
                    # set after it: the provider had no scene graph (nothing drawn, no
                    # legend, Edit control mesh failed on it)
                    proxy.attach(view)
                attached.append((obj.Document.Name, obj.Name))
            except Exception as error:  # noqa: BLE001 - one object must not stop the rest
                App.Console.PrintError(f"Facet: {obj.Label}: no view provider: {error}\n")
    if attached:
        from PySide import QtCore

        QtCore.QTimer.singleShot(0, lambda: _finish(attached))


def _finish(items):
    documents = []
    for obj, view in _objects(items):
        if obj.Document.Name not in documents:
            documents.append(obj.Document.Name)
        proxy = view.Proxy
        if not view.DisplayMode and hasattr(proxy, "getDefaultDisplayMode"):
            try:
                # FreeCAD left the restored property's list of modes empty: the
                # provider's own, then its default
                view.DisplayMode = list(view.listDisplayModes())
                view.DisplayMode = proxy.getDefaultDisplayMode()
            except (ValueError, TypeError) as error:
                App.Console.PrintWarning(f"Facet: {obj.Label}: display mode: {error}\n")
        hide_sources(obj)
    fit_views(documents)


def fit_views(documents):
    """Fit the 3D views of ``documents`` to what they show: with no GuiDocument.xml there
    was no camera either, and examples/roof.FCStd opened on an empty view (the default
    camera's few millimetres about the origin, the 12 m roof out of sight)."""
    for name in documents:
        view = _active_view(name)
        if view is not None and hasattr(view, "fitAll"):
            view.fitAll()


def view_pose(name):
    """Where document ``name``'s 3D view looks from, as the designer moves it: its
    camera's type, position, orientation, focal distance and height (angle); None
    without a view. (Not the near and far planes, which Coin sets itself at each
    redraw.)"""
    view = _active_view(name)
    camera = view.getCameraNode() if hasattr(view, "getCameraNode") else None
    if camera is None:
        return None
    pose = [camera.getTypeId().getName().getString(),
            tuple(camera.position.getValue().getValue()),
            tuple(camera.orientation.getValue().getValue()),
            camera.focalDistance.getValue()]
    for field in ("height", "heightAngle"):
        if camera.getField(field) is not None:
            pose.append(camera.getField(field).getValue())
    return tuple(pose)


def fit_view_unmoved(name, pose):
    """Fit document ``name``'s 3D view (:func:`fit_views`) if it still looks from ``pose``
    (:func:`view_pose`): a designer who has turned, panned or zoomed it since keeps the
    view they chose."""
    if pose is not None and view_pose(name) == pose:
        fit_views([name])


def _active_view(name):
    """Document ``name``'s active 3D view, or None (closed, no GUI document, no view)."""
    import FreeCADGui as Gui

    try:
        gui_doc = Gui.getDocument(name)
    except (NameError, ReferenceError):
        return None
    return getattr(gui_doc, "ActiveView", None) if gui_doc is not None else None
