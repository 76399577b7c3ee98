# SPDX-License-Identifier: LGPL-2.1-or-later
"""GUI checks of how a lifted roof reads (called by gui_test.py; ``g`` is the gui_test
module, for its screenshot helpers).

- Shape lifting: a line under the intro says how far the roof is from its pins (largest,
  where, RMS, in model units) and follows the sliders (taskpanel_lifting_mix_distance.png).
- Pins table: at the task pane's default width its cells read in full and a refusal
  shows without scrolling (taskpanel_pins_table.png).
- Shading: the hipped roof of pins_checks (all four slopes of one pitch) in its default look
  (Flat Lines), isometric: under FreeCAD's headlight alone, which shines along the line of
  sight, the slopes facing -y and +x were one flat grey (lifting_shading.png); each slope is
  shaded by the way it faces, none washed out, and the Planarity colours and pin markers
  are unchanged.
"""

import os

from ui_checks import settle


def face_colours(g, view, obj, path):
    """The colour drawn at the middle of each face of ``obj`` in the screenshot ``path``
    (saved isometric, all in view, at the view's size), as (r, g, b) 0..255, or None for a
    face not seen there (behind another: a pick there is not the face)."""
    import FreeCAD as App

    from facetwb.objects.polymesh import get_mesh

    import FreeCADGui as Gui

    view.viewIsometric()
    view.fitAll()
    Gui.updateGui()
    width, height = view.getSize()
    # (at the view's size: at another the image's pixels are not the view's)
    view.saveImage(path, width, height, "Current")
    pixels = g.image_pixels(path)
    mesh = get_mesh(obj)
    colours = []
    for f in range(mesh.face_start.size - 1):
        middle = mesh.vertices[mesh.face(f)].mean(axis=0)
        x, y = view.getPointOnScreen(App.Vector(*middle))
        info = view.getObjectInfo((int(x), int(y)))
        if not info or info.get("Component") != f"Face{f}":
            colours.append(None)
            continue
        col, row = int(x), int(height - y)
        colours.append(tuple(pixels[row - 2:row + 3, col - 2:col + 3].reshape(-1, 3)
                             .mean(axis=0).round().astype(int).tolist()))
    return colours


def check_shading(check, out_dir, g):
    import FreeCAD as App
    import FreeCADGui as Gui

    import pins_checks

    doc = App.newDocument("Shading")
    try:
        lifting = pinned_roof(doc)
        Gui.Selection.clearSelection()  # (selected: drawn in the highlight colour)
        view = Gui.ActiveDocument.ActiveView
        check(lifting.ViewObject.DisplayMode == "Flat Lines", "shading: the roof shows in "
              "Flat Lines")
        path = os.path.join(out_dir, "lifting_shading.png")
        colours = face_colours(g, view, lifting, path)
        # the slopes seen from above the +x, -y corner: facing -y and +x, which the
        # headlight lit alike, and the one facing +y at a grazing angle
        seen = [c for c in colours if c is not None]
        brightness = sorted(sum(c) / 3.0 for c in seen)
        gaps = [b - a for a, b in zip(brightness, brightness[1:])]
        check(len(seen) >= 3 and min(gaps) >= 20.0,
              f"shading: each slope of the roof (one pitch) is shaded by the way it faces "
              f"(grey levels {[round(b) for b in brightness]}, 20 apart at least)")
        check(all(max(c) < 245 for c in seen) and all(max(c) - min(c) < 12 for c in seen),
              f"shading: the slopes are grey, none washed out to white ({seen})")
        pins_checks.check_markers_drawn(check, g, path, "lifting_shading.png")
        # the Planarity colours are those of the headlight alone, as before (the key light
        # lights the faces in Flat Lines and Shaded only)
        lifting.ViewObject.DisplayMode = "Planarity"
        path = os.path.join(out_dir, "lifting_shading_planarity.png")
        g.save_view(view, path)
        g.check_screenshot(check, path, "lifting shading planarity", legend=True)
        planar = face_colours(g, view, lifting, path)
        light = getattr(lifting.ViewObject.Proxy, "key_light", None)
        if check(light is not None and light.on.getValue(),
                 "shading: the Lifting has a key light"):
            light.on = False
            headlight_only = face_colours(g, view, lifting, path)
            light.on = True
            check(planar == headlight_only,
                  f"shading: the Planarity colours are unchanged ({planar})")
    finally:
        App.closeDocument(doc.Name)


def pinned_roof(doc):
    """The hipped roof of pins_checks lifted to its pins: eaves 2.5 m, ridge 4.5 m."""
    import facetwb
    import pins_checks

    plan = pins_checks.hipped_plan(doc)
    pinned = [(x, y, 2500.0) for x, y in pins_checks.CORNERS] + \
        [(x, y, 4500.0) for x, y in pins_checks.RIDGE]
    lifting = facetwb.make_lifting(plan, pins=pinned)
    doc.recompute()
    settle()
    return lifting


def check_mix_distance(check, out_dir, g):
    """Shape lifting says how far the sliders take the roof from its pins (the markers stay
    at the pinned heights), in mm, as they move."""
    import FreeCAD as App
    import FreeCADGui as Gui

    import ui_checks
    from facetwb.taskpanels import forms, lift_mix

    doc = App.newDocument("MixDistance")
    try:
        lifting = pinned_roof(doc)
        if not check(lift_mix.edit(lifting), "mix distance: the Shape lifting panel opens"):
            return
        settle()
        panel = lift_mix.active
        try:
            label = forms.widget(panel.form, "distance")
        except KeyError:
            label = None
        text = label.text() if label is not None else ""
        zero = App.Units.Quantity(0.0, App.Units.Length).UserString
        check(label is not None and label.isVisible() and "pins" in text
              and f"{zero} at most" in text,
              f"mix distance: the panel says the roof meets its pins ({text!r})")
        panel.sliders[0].setValue(40)
        settle()
        text = label.text() if label is not None else ""
        far = lifting.TargetMax
        check(far.Value > 100.0 and far.UserString in text
              and f"vertex {lifting.TargetMaxVertex}" in text
              and lifting.TargetRms.UserString in text,
              f"mix distance: moved by a slider, the roof is {far.UserString} from its pins, "
              f"and the panel says so ({text!r})")
        Gui.Selection.clearSelection()
        view = Gui.ActiveDocument.ActiveView
        view.viewIsometric()
        view.fitAll()
        settle()
        ui_checks.window_shot(os.path.join(out_dir, "taskpanel_lifting_mix_distance.png"))
        panel.reject()
        settle()
    finally:
        if lift_mix.active is not None:
            lift_mix.active.reject()
        App.closeDocument(doc.Name)


def grid_plan(doc):
    """A plan of 2 x 2 panels 10 m x 8 m: nine vertices, x up to 20000 mm, y to 16000.17
    (as drawn in metres, the Roof designer's)."""
    import FreeCAD as App
    import Part

    import facetwb

    sketch = doc.addObject("Sketcher::SketchObject", "GridPlan")
    xs, ys = (0.0, 10000.0, 20000.0), (0.0, 8000.0 + 1 / 6, 16000.0 + 1 / 6)
    for x in xs:
        for a, b in zip(ys, ys[1:]):
            sketch.addGeometry(Part.LineSegment(App.Vector(x, a, 0), App.Vector(x, b, 0)))
    for y in ys:
        for a, b in zip(xs, xs[1:]):
            sketch.addGeometry(Part.LineSegment(App.Vector(a, y, 0), App.Vector(b, y, 0)))
    plan = facetwb.make_plan_graph([sketch])
    doc.recompute()
    return plan


def check_pins_table(check, out_dir, g):
    """The Lift plan panel's pins table at the task pane's default width: a plan 20 m x
    16 m (:func:`grid_plan`), its nine vertices pinned, a face refused: every cell reads in
    full (y was cut to "160...") and the refusal shows without scrolling (it was below the
    fold)."""
    import FreeCAD as App
    import FreeCADGui as Gui

    import pins_checks
    import ui_checks
    from facetwb.compat import qt_gui
    from facetwb.taskpanels import derive_panels, forms

    QtGui = qt_gui()
    doc = App.newDocument("PinsTable")
    panel = None
    try:
        plan = grid_plan(doc)
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(plan)
        Gui.runCommand("Facet_Lift")
        settle()
        panel = derive_panels.active
        if not check(panel is not None and hasattr(panel, "pins"),
                     "pins table: the Lift plan panel opens"):
            return
        combo = forms.widget(panel.form, "Target")
        combo.setCurrentIndex(combo.count() - 1)
        editor = panel.pins
        middle = pins_checks.vertex_of(plan, (10000.0, 8000.0 + 1 / 6))
        for vertices, height in (([v for v in range(len(plan.Points)) if v != middle], 3000.0),
                                 ([middle], 7000.0)):
            pins_checks.select(plan, [f"Vertex{v}" for v in vertices])
            editor.height.setProperty("rawValue", height)
            editor.pin_selection()
        pins_checks.select(plan, ["Face0"])
        refused = editor.pin_selection() is False
        settle()
        table = editor.table
        metrics = table.fontMetrics()
        cut = []
        for row in range(table.rowCount()):
            for column in range(table.columnCount()):
                text = table.item(row, column).text()
                # (Qt's cell margins: 3 px each side, and the grid line)
                if metrics.boundingRect(text).width() + 8 > table.columnWidth(column):
                    cut.append(text)
        check(table.rowCount() == 9 and not cut,
              f"pins table: every cell reads in full at the default width "
              f"({table.viewport().width()} px; cut: {cut})")
        area = editor.widget.parent()
        while area is not None and not isinstance(area, QtGui.QScrollArea):
            area = area.parent()
        message = editor.message
        top = message.mapTo(area.viewport(), message.rect().topLeft()).y() if area else -1
        bottom = top + message.height()
        check(refused and "is a face, not a vertex" in message.text() and area is not None
              and 0 <= top and bottom <= area.viewport().height(),
              f"pins table: the refusal shows without scrolling (rows {top}..{bottom} of "
              f"{area.viewport().height() if area else '?'} px: {message.text()!r})")
        view = Gui.ActiveDocument.ActiveView
        view.viewTop()
        view.fitAll()
        settle()
        ui_checks.window_shot(os.path.join(out_dir, "taskpanel_pins_table.png"))
    finally:
        if derive_panels.active is not None:
            derive_panels.active.reject()
            settle()
        App.closeDocument(doc.Name)


def run(check, out_dir, g):
    check_shading(check, out_dir, g)
    check_mix_distance(check, out_dir, g)
    check_pins_table(check, out_dir, g)
