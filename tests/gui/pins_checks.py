# SPDX-License-Identifier: LGPL-2.1-or-later
"""GUI checks of pinned heights picked in the 3D view and of the Raise vertex marker
(called by gui_test.py; ``g`` is the gui_test module, for its screenshot helpers).

A hipped-roof plan (8 m x 5 m, ridge 3 m long): a click in the 3D view near a plan vertex
picks ``Vertex<n>`` (``view.getObjectInfo`` at the vertex's pixel, which runs FreeCAD's own
pick), elsewhere a face; Lift plan with *Pinned heights*: the eaves clicked (mouse events
on the view, Ctrl+click) and pinned at 2.5 m, the ridge at 4.5 m, a face refused with a message; OK
makes a Lifting meeting those heights, its pins drawn as markers (lift_pins.png,
taskpanel_lift_pins.png). The Pin heights panel of the Lifting: the ridge pinned at 5 m
live, a height edited in the table, a pin removed; Cancel puts the pins back, OK keeps them
in one undo step. Shape lifting: a marker on the vertex of the Raise vertex spin box
follows it (lifting_raise.png) and is gone when the panel closes.
"""

import os

from ui_checks import settle

CORNERS = [(0, 0), (8000, 0), (8000, 5000), (0, 5000)]
RIDGE = [(2500, 2500), (5500, 2500)]


def hipped_plan(doc):
    import FreeCAD as App
    import Part

    import facetwb

    sketch = doc.addObject("Sketcher::SketchObject", "HipPlan")
    lines = [(CORNERS[i], CORNERS[(i + 1) % 4]) for i in range(4)] + [(RIDGE[0], RIDGE[1])]
    lines += [(CORNERS[0], RIDGE[0]), (CORNERS[3], RIDGE[0]), (CORNERS[1], RIDGE[1]),
              (CORNERS[2], RIDGE[1])]
    for a, b in lines:
        sketch.addGeometry(Part.LineSegment(App.Vector(*a, 0), App.Vector(*b, 0)), False)
    plan = facetwb.make_plan_graph([sketch])
    doc.recompute()
    return plan


def vertex_of(obj, xy):
    """The index of the point of ``obj`` at plan position ``xy``."""
    return min(range(len(obj.Points)),
               key=lambda v: (obj.Points[v].x - xy[0]) ** 2 + (obj.Points[v].y - xy[1]) ** 2)


def select(obj, names):
    import FreeCADGui as Gui

    Gui.Selection.clearSelection()
    for name in names:
        Gui.Selection.addSelection(obj.Document.Name, obj.Name, name)


def click(view, point, add=False):
    """A left click (Ctrl+click with ``add``) in ``view`` at the model point ``point``, 3
    pixels right of it, as the mouse gives it (FreeCAD's own pick and selection)."""
    import FreeCAD as App
    from PySide import QtCore, QtGui

    widget = view.graphicsView().viewport()
    x, y = view.getPointOnScreen(App.Vector(*point))
    width, height = view.getSize()
    # (the view's size in pixels of the image, the widget's in the window's: they differ)
    at = QtCore.QPointF((x + 3) * widget.width() / width, (height - y) * widget.height() / height)
    modifier = QtCore.Qt.ControlModifier if add else QtCore.Qt.NoModifier
    QtGui.QApplication.sendEvent(widget, QtGui.QMouseEvent(
        QtCore.QEvent.MouseMove, at, QtCore.Qt.NoButton, QtCore.Qt.NoButton, modifier))
    for kind, buttons in ((QtCore.QEvent.MouseButtonPress, QtCore.Qt.LeftButton),
                          (QtCore.QEvent.MouseButtonRelease, QtCore.Qt.NoButton)):
        QtGui.QApplication.sendEvent(widget, QtGui.QMouseEvent(
            kind, at, QtCore.Qt.LeftButton, buttons, modifier))
    settle(3)


def in_scene(markers):
    import FreeCADGui as Gui

    graph = Gui.ActiveDocument.ActiveView.getSceneGraph()
    return graph.findChild(markers.root) >= 0


def run(check, out_dir, g):
    import FreeCAD as App
    import FreeCADGui as Gui

    import facetwb
    from facetwb.taskpanels import derive_panels, lift_pins

    doc = App.newDocument("Pins")
    plan = hipped_plan(doc)
    check(plan.isValid() and plan.FaceCount == 4, "pins: the hipped plan has 4 faces")
    eaves = [vertex_of(plan, p) for p in CORNERS]
    ridge = [vertex_of(plan, p) for p in RIDGE]
    view = Gui.ActiveDocument.ActiveView
    view.viewTop()
    view.fitAll()
    settle()

    # a click near a plan vertex picks Vertex<n>; in a face, the face (FreeCAD's own pick)
    names = []
    for v in eaves + ridge:
        x, y = view.getPointOnScreen(plan.Points[v])
        info = view.getObjectInfo((int(x) + 3, int(y) - 2))
        names.append(info and info.get("Component"))
    check(names == [f"Vertex{v}" for v in eaves + ridge],
          f"a click 3 px from a plan vertex picks it ({names})")
    x, y = view.getPointOnScreen(App.Vector(4000, 1000, 0))
    info = view.getObjectInfo((int(x), int(y)))
    check(info is not None and str(info.get("Component", "")).startswith("Face"),
          f"a click inside a face picks the face ({info and info.get('Component')})")

    # Lift plan with pinned heights picked in the 3D view: the eaves clicked (Ctrl+click
    # for the second and later)
    Gui.Selection.clearSelection()
    for k, v in enumerate(eaves):
        click(view, plan.Points[v], add=k > 0)
    picked = [(s.ObjectName, tuple(s.SubElementNames)) for s in Gui.Selection.getSelectionEx()]
    check(picked == [(plan.Name, tuple(f"Vertex{v}" for v in eaves))],
          f"clicks near the eaves select their vertices ({picked})")
    Gui.runCommand("Facet_Lift")
    settle()
    panel = derive_panels.active
    if not check(panel is not None and hasattr(panel, "pins"),
                 "pins: the Lift plan panel opens with the pin controls"):
        App.closeDocument(doc.Name)
        return
    from facetwb.taskpanels import forms

    combo = forms.widget(panel.form, "Target")
    combo.setCurrentIndex(combo.count() - 1)
    check(panel.from_pins() and panel.pins.widget.isVisible() and not panel.from_file(),
          "the last target is Pinned heights, which shows the pin controls")
    names = [o.Name for o in doc.Objects]
    check(panel.accept() is False and [o.Name for o in doc.Objects] == names
          and "no pinned height" in forms.widget(panel.form, "message").text(),
          "OK without a pin: nothing added, the panel asks for pins")
    editor = panel.pins
    editor.height.setProperty("rawValue", 2500.0)
    check(editor.pin_selection() and editor.table.rowCount() == 4
          and [p[2] for p in editor.pins] == [2500.0] * 4,
          f"the four eaves picked are pinned at 2.5 m ({editor.message.text()!r})")
    select(plan, ["Face1"])
    check(editor.pin_selection() is False and editor.table.rowCount() == 4
          and "is a face, not a vertex" in editor.message.text(),
          f"a face picked is refused, saying to click a corner ({editor.message.text()!r})")
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(plan)
    check(editor.pin_selection() is False and "selected as a whole" in editor.message.text(),
          f"the plan picked in the tree is refused ({editor.message.text()!r})")
    select(plan, [f"Vertex{v}" for v in ridge])
    editor.height.setProperty("rawValue", 4500.0)
    check(editor.pin_selection() and editor.table.rowCount() == 6,
          "the ridge is pinned at 4.5 m")
    table = [editor.table.item(r, 0).text() for r in range(editor.table.rowCount())]
    check(table == [str(v) for v in eaves + ridge],
          f"the table lists the pinned vertices ({table})")
    cells = [editor.table.item(4, c).text() for c in range(1, 4)]
    check(cells == ["2500", "2500", "4500"], f"and their x, y, height in mm ({cells})")
    flat = [tuple(plan.Points[v]) for v in eaves + ridge]
    check(in_scene(editor.markers) and editor.markers.points == flat
          and editor.markers.texts.count(App.Units.Quantity(4500.0, App.Units.Length)
                                         .UserString) == 2,
          f"the pins are drawn on the plan's vertices while picking, labelled with their "
          f"heights ({editor.markers.texts})")
    Gui.Selection.clearSelection()
    view.viewIsometric()
    view.fitAll()
    settle()
    import ui_checks

    ui_checks.window_shot(os.path.join(out_dir, "taskpanel_lift_pins.png"))
    markers = editor.markers
    check(panel.accept() and derive_panels.active is None and not in_scene(markers),
          "Lift plan: OK makes the Lifting and takes the picking markers away")
    liftings = [o for o in doc.Objects if facetwb.is_lifting(o)]
    lifting = liftings[0] if len(liftings) == 1 else None
    if not check(lifting is not None and lifting.isValid(),
                 f"a Lifting is made from the pins "
                 f"({lifting and lifting.getStatusString()})"):
        App.closeDocument(doc.Name)
        return
    pinned = [(p.x, p.y, p.z) for p in lifting.PinnedPoints]
    z = [p.z for p in lifting.Points]
    miss = max([abs(z[v] - 2500.0) for v in eaves] + [abs(z[v] - 4500.0) for v in ridge])
    check(len(pinned) == 6 and miss < 1e-2 and lifting.PlanarityMaxRel <= 1e-9,
          f"the roof meets the pinned heights (off by {miss:.2g} mm), faces planar")
    drawn = lifting.ViewObject.Proxy.pins
    check(drawn.points == pinned and len(drawn.texts) == 6,
          f"the Lifting draws its {len(drawn.points)} pins")
    Gui.Selection.clearSelection()
    path = os.path.join(out_dir, "lift_pins.png")
    g.save_view(view, path)
    check_markers_drawn(check, g, path, "lift_pins.png")

    # the Pin heights panel of the Lifting: the ridge raised to 5 m, live; Cancel; OK
    select(lifting, [f"Vertex{ridge[0]}", f"Vertex{ridge[1]}"])
    check("Facet_LiftPins" in Gui.listCommands(), "command Facet_LiftPins is registered")
    Gui.runCommand("Facet_LiftPins")
    settle()
    panel = lift_pins.active
    if not check(panel is not None, "the Pin heights panel opens on the Lifting"):
        App.closeDocument(doc.Name)
        return
    editor = panel.editor
    check(editor.table.rowCount() == 6, "it lists the Lifting's six pins")
    editor.height.setProperty("rawValue", 5000.0)
    check(editor.pin_selection() and editor.table.rowCount() == 6,
          "the ridge picked on the roof is pinned again at 5 m (same rows)")
    z = [p.z for p in lifting.Points]
    check(abs(z[ridge[0]] - 5000.0) < 1e-2 and abs(z[ridge[1]] - 5000.0) < 1e-2
          and lifting.PlanarityMaxRel <= 1e-9,
          f"the roof follows at once: ridge at {z[ridge[0]]:.1f} mm, faces planar")
    row = editor.vertices().index(eaves[0])
    editor.table.item(row, 3).setText("2.4 m")
    check(abs(lifting.PinnedPoints[row].z - 2400.0) < 1e-9,
          f"a height edited in the table ('2.4 m') is written "
          f"({lifting.PinnedPoints[row].z} mm)")
    for text, said in (("high", "is not a number of mm"), ("2.4 kg", "is not a length")):
        editor.table.item(row, 3).setText(text)
        check(abs(lifting.PinnedPoints[row].z - 2400.0) < 1e-9
              and said in editor.message.text(),
              f"a height that is not a length ({text!r}) is refused "
              f"({editor.message.text()!r})")
    editor.table.selectRow(row)
    check(editor.remove_selected() and len(lifting.PinnedPoints) == 5
          and editor.table.rowCount() == 5, "Remove pin takes the selected pin away")
    check(len(lifting.ViewObject.Proxy.pins.points) == 5, "the markers follow (5)")
    panel.reject()
    settle()
    check(lift_pins.active is None
          and [(p.x, p.y, p.z) for p in lifting.PinnedPoints] == pinned
          and max(abs(p.z - q) for p, q in zip(lifting.Points, z_before(pinned, lifting,
                                                                         eaves, ridge)))
          < 1e-2, "Cancel puts the pins and the roof back")
    undo = len(doc.UndoNames)
    select(lifting, [f"Vertex{v}" for v in ridge])
    Gui.runCommand("Facet_LiftPins")
    settle()
    panel = lift_pins.active
    if panel is not None:
        panel.editor.height.setProperty("rawValue", 5000.0)
        panel.editor.pin_selection()
        panel.accept()
        settle()
    z = [p.z for p in lifting.Points]
    check(panel is not None and lift_pins.active is None and abs(z[ridge[0]] - 5000.0) < 1e-2
          and len(doc.UndoNames) == undo + 1 and doc.UndoNames[0] == "Pin heights",
          f"OK keeps the ridge at 5 m in one undo step ({list(doc.UndoNames)[:2]})")

    # Shape lifting: the Raise vertex row's vertex is marked in the 3D view
    from facetwb.taskpanels import lift_mix

    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(lifting)
    Gui.runCommand("Facet_LiftMix")
    settle()
    panel = lift_mix.active
    if check(panel is not None, "the Shape lifting panel opens"):
        marker = panel.marker
        v = ridge[1]
        panel.vertex.setValue(v)
        p = lifting.Points[v]
        check(in_scene(marker) and marker.points == [(p.x, p.y, p.z)]
              and marker.texts == [f"vertex {v}"],
              f"a marker on vertex {v}, labelled, follows the spin box ({marker.texts})")
        panel.drag.setValue(20)
        Gui.Selection.clearSelection()  # selected objects are drawn in the highlight colour
        settle()
        p = lifting.Points[v]
        check(marker.points == [(p.x, p.y, p.z)] and p.z > 5000.0 + 1.0,
              f"the marker rises with the vertex ({p.z:.0f} mm)")
        path = os.path.join(out_dir, "lifting_raise.png")
        g.save_view(view, path)
        check_markers_drawn(check, g, path, "lifting_raise.png", color=lift_mix.RAISE_COLOR)
        panel.reject()
        settle()
        check(lift_mix.active is None and not in_scene(marker),
              "the raise marker is gone when the panel closes")
    App.closeDocument(doc.Name)
    check_cancel_keeps_what_is_made(check)


def check_cancel_keeps_what_is_made(check):
    """The Pin heights panel's Cancel re-solves the Lifting alone: the panels made from the
    roof, up to date when the panel opened, are neither rebuilt nor marked (a Cancel that
    recomputed the document rebuilt them, and rewrote cut sheets' files, for nothing); after
    a Recompute pressed with the panel open, Cancel rebuilds them from the roof it puts
    back."""
    import FreeCAD as App

    import facetwb
    from facetwb.recompute import Recomputes
    from facetwb.taskpanels import lift_pins

    doc = App.newDocument("PinsCancel")
    plan = hipped_plan(doc)
    ridge = [vertex_of(plan, p) for p in RIDGE]
    pinned = [(x, y, 2500.0) for x, y in CORNERS] + [(x, y, 4500.0) for x, y in RIDGE]
    lifting = facetwb.make_lifting(plan, pins=pinned)
    panels = facetwb.make_panelset(lifting, thickness=20.0)
    doc.recompute()
    volumes = list(panels.Volumes)
    recorded = Recomputes(doc)
    try:
        for pressed in (False, True):
            recorded.take()
            if not check(lift_pins.edit(lifting), "the Pin heights panel opens"):
                break
            panel = lift_pins.active
            select(lifting, [f"Vertex{v}" for v in ridge])
            panel.editor.height.setProperty("rawValue", 5000.0)
            panel.editor.pin_selection()
            if pressed:
                doc.recompute()  # Recompute pressed with the panel open
            changed = list(panels.Volumes)
            recorded.take()
            panel.reject()
            settle()
            rebuilt = recorded.take()
            check(panels.Name in rebuilt if pressed else panels.Name not in rebuilt,
                  f"Pin heights' Cancel {'rebuilds' if pressed else 'leaves'} the panels "
                  f"made from the roof{' after a Recompute' if pressed else ''} "
                  f"(recomputed: {sorted(rebuilt)})")
            check("Touched" not in panels.State and list(panels.Volumes) == volumes
                  and (changed != volumes) == pressed,
                  f"the panels are those of the pins put back, up to date ({panels.State})")
    finally:
        recorded.stop()
        App.closeDocument(doc.Name)


def z_before(pinned, lifting, eaves, ridge):
    """The roof's heights for the six pins as first made: eaves 2.5 m, ridge 4.5 m (a
    hipped roof: planes through them)."""
    return [2500.0 if v in eaves else 4500.0 if v in ridge else p.z
            for v, p in enumerate(lifting.Points)]


def check_markers_drawn(check, g, path, what, color=None):
    """The screenshot shows markers of ``color`` (default the pins' colour)."""
    from facetwb.viewproviders.view_lifting import PIN_COLOR

    pixels = g.image_pixels(path)
    count = int(g.near(pixels, color or PIN_COLOR, 30).sum())
    check(count > 40, f"{what}: markers are drawn ({count} pixels of their colour)")
