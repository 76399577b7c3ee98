# SPDX-License-Identifier: LGPL-2.1-or-later
"""GUI checks of how a lifted roof reads (called by gui_test.py; ``g`` is the gui_test
module, for its screenshot helpers).

- Shape lifting: a line under the intro says how far the roof is from its pins (largest,
  where, RMS, in model units) and follows the sliders (taskpanel_lifting_mix_distance.png).
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
    (saved isometric, all in view, at the view's size), as (r, g, b) 0..255, or None for a face not seen
    there (behind another: a pick there is not the face)."""
    import FreeCAD as App
    import numpy as np

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

    import facetwb
    import pins_checks
    from facetwb.viewproviders import colormap

    doc = App.newDocument("Shading")
    try:
        plan = pins_checks.hipped_plan(doc)
        pinned = [(x, y, 2500.0) for x, y in pins_checks.CORNERS] + \
            [(x, y, 4500.0) for x, y in pins_checks.RIDGE]
        lifting = facetwb.make_lifting(plan, pins=pinned)
        doc.recompute()
        settle()
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


def run(check, out_dir, g):
    check_shading(check, out_dir, g)
    check_mix_distance(check, out_dir, g)
