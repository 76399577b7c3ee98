# SPDX-License-Identifier: LGPL-2.1-or-later
"""GUI test: the designer's path through Facet in a real FreeCAD window (under Xvfb).

    tests/fc_env.sh gui [OUT_DIR]
    # = FACET_GUI_OUT=OUT_DIR xvfb-run -a -s "-screen 0 1600x1000x24" freecad tests/gui/gui_test.py
    #   with the checkout as Mod/Facet in a throw-away FreeCAD user home

Activates the Facet workbench, imports a quad mesh, selects it, runs Facet_Planarize, shows
the result in Planarity mode and saves screenshots of the 3D view to OUT_DIR (default
build/gui): planarity.png (result, planarity colours and legend), source.png (the source in
Flat Lines), source_planarity.png (the warped source in Planarity mode) and lifting.png (a
sketched roof plan lifted by Facet_PlanGraph and Facet_Lift towards a dome). Every check
prints PASS or FAIL; FreeCAD exits with status 0 only if all passed (1 if one failed, 2 if
the test itself broke). It does not run without a GUI: freecadcmd prints SKIP and exits 0.
"""

import os
import sys
import time
import traceback

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ui_checks import settle  # noqa: E402 - (after the path to it)
MESH = os.path.join(ROOT, "tests", "data", "hypar.obj")
WIDTH, HEIGHT = 1600, 1000


class Checks:
    def __init__(self):
        self.failed = []

    def __call__(self, condition, what):
        # to the terminal, not the report view: the tutorial's screenshots show
        # the report view, which should hold Facet's messages, not the test's
        print(("PASS " if condition else "FAIL ") + what, file=sys.__stdout__, flush=True)
        if not condition:
            self.failed.append(what)
        return condition


def image_pixels(path):
    """(height, width, 3) uint8 RGB array of a PNG, read with Qt."""
    import numpy as np
    from PySide import QtGui

    image = QtGui.QImage(path).convertToFormat(QtGui.QImage.Format_RGB888)
    width, height, stride = image.width(), image.height(), image.bytesPerLine()
    data = image.constBits()
    buffer = bytes(data) if not hasattr(data, "asstring") else data.asstring(image.byteCount())
    rows = np.frombuffer(buffer, dtype=np.uint8)[: height * stride].reshape(height, stride)
    return rows[:, : width * 3].reshape(height, width, 3)


def open_example(name):
    """``examples/name`` opened, its view providers attached (they come once the event
    loop runs)."""
    import FreeCAD as App

    doc = App.openDocument(os.path.join(ROOT, "examples", name))
    settle(20)
    return doc


def open_roof_example():
    """``(document, Lifting, PanelSet)`` of examples/roof.FCStd, opened."""
    import facetwb

    doc = open_example("roof.FCStd")
    lifting = [o for o in doc.Objects if facetwb.is_lifting(o)][0]
    panels = [o for o in doc.Objects if facetwb.is_panelset(o)][0]
    return doc, lifting, panels


def near(pixels, rgb, tolerance=40):
    """Boolean mask of the pixels within ``tolerance`` (per channel) of ``rgb`` (0..1)."""
    import numpy as np

    target = np.array(rgb) * 255.0
    return np.all(np.abs(pixels.astype(float) - target) <= tolerance, axis=-1)


def check_screenshot(check, path, what, legend):
    import numpy as np

    from facetwb.viewproviders import colormap, legend as legend_layout

    check(os.path.isfile(path) and os.path.getsize(path) > 1000, f"{what}: {path} written")
    pixels = image_pixels(path)
    check(pixels.shape[:2] == (HEIGHT, WIDTH), f"{what}: {WIDTH}x{HEIGHT} pixels")
    colours = np.unique(pixels.reshape(-1, 3)[::7], axis=0).shape[0]
    check(colours > 50, f"{what}: not a uniform image ({colours} colours)")
    # The mesh fills the middle of the view (fit all) with colours of the map, or grey.
    middle = pixels[HEIGHT // 4: 3 * HEIGHT // 4, WIDTH // 4: 3 * WIDTH // 4]
    spread = middle.max(axis=-1).astype(int) - middle.min(axis=-1).astype(int)
    colourful = int((spread > 70).sum())  # the background and grey faces are not
    if legend:
        check(colourful > 0.05 * middle.size / 3,
              f"{what}: the mesh is drawn in planarity colours ({colourful} pixels)")
        # The legend's bar: sample its centre line where each colour stop is drawn.
        x = int((1.0 + sum(legend_layout.BAR_X) / 2.0) / 2.0 * WIDTH)
        y0, y1 = legend_layout.BAR_Y
        for position, rgb in colormap.STOPS:
            y_view = y0 + (0.03 + 0.94 * position) * (y1 - y0)
            y = int((1.0 - y_view) / 2.0 * HEIGHT)
            sample = pixels[y - 1: y + 2, x - 1: x + 2].reshape(-1, 3).mean(axis=0) / 255.0
            check(np.all(np.abs(sample - np.array(rgb)) < 0.12),
                  f"{what}: legend bar at {position:.2f} is {tuple(np.round(rgb, 2))} "
                  f"(found {tuple(np.round(sample, 2))})")
        (px0, py0), (px1, py1) = legend_layout.PANEL
        panel = pixels[int((1 - py1) / 2 * HEIGHT): int((1 - py0) / 2 * HEIGHT),
                       int((1 + px0) / 2 * WIDTH): int((1 + px1) / 2 * WIDTH)]
        text = near(panel, legend_layout.TEXT_COLOR, 60).sum()
        check(text > 200, f"{what}: legend labels drawn ({text} light pixels on the panel)")
    else:
        grey = int((spread < 12).sum())
        check(grey > 0.05 * middle.size / 3 and colourful < 0.001 * middle.size / 3,
              f"{what}: the mesh is drawn in grey ({grey} grey, {colourful} coloured pixels)")


def save_view(view, path):
    import FreeCADGui as Gui

    view.viewIsometric()
    view.fitAll()
    Gui.updateGui()
    view.saveImage(path, WIDTH, HEIGHT, "Current")


def run(out_dir):
    import FreeCAD as App
    import FreeCADGui as Gui
    import numpy as np

    check = Checks()
    os.makedirs(out_dir, exist_ok=True)

    if not check("FacetWorkbench" in Gui.listWorkbenches(), "Facet workbench is listed"):
        return check
    Gui.activateWorkbench("FacetWorkbench")
    check(Gui.activeWorkbench().name() == "FacetWorkbench", "Facet workbench is active")
    for name in ("Facet_ImportMesh", "Facet_ToPolyMesh", "Facet_Planarize"):
        check(name in Gui.listCommands(), f"command {name} is registered")

    import facetwb
    from facetwb import importer

    importer.SHOW_DIALOGS = False
    check_import_command(check)
    doc = importer.open(MESH)
    check(doc is not None and len(doc.Objects) == 1, "the mesh is imported as one object")
    source = doc.Objects[0]
    check(facetwb.is_polymesh(source), "it is a Facet PolyMesh")
    check(source.ViewObject.DisplayMode == "Flat Lines", "the source shows in Flat Lines")
    view = Gui.ActiveDocument.ActiveView
    save_view(view, os.path.join(out_dir, "source.png"))
    check_screenshot(check, os.path.join(out_dir, "source.png"), "source", legend=False)
    source.ViewObject.DisplayMode = "Planarity"
    save_view(view, os.path.join(out_dir, "source_planarity.png"))
    check_screenshot(check, os.path.join(out_dir, "source_planarity.png"), "source planarity",
                     legend=True)
    source.ViewObject.DisplayMode = "Flat Lines"

    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(source)
    command = Gui.Command.get("Facet_Planarize") if hasattr(Gui, "Command") else None
    if command is not None and hasattr(command, "isActive"):
        check(command.isActive(), "Facet_Planarize is active with a PolyMesh selected")
    accept_panel(check, "Facet_Planarize")
    results = [obj for obj in doc.Objects if facetwb.is_planarized(obj)]
    if not check(len(results) == 1, "Facet_Planarize added one Planarized object"):
        return check
    result = results[0]
    check(result.isValid(), f"the Planarized object is valid ({result.getStatusString()})")
    check(result.Source is source, "it links the source")
    check(result.PlanarityMaxRel <= result.Tolerance,
          f"planarity {result.PlanarityMaxRel:.3g} is below the tolerance {result.Tolerance:g}")
    check(not source.ViewObject.Visibility, "the source is hidden")
    check(result.ViewObject.DisplayMode == "Planarity", "the result shows planarity colours")
    check([obj.Name for obj in Gui.Selection.getSelection()] == [result.Name],
          "the result is selected")
    doc.undo()
    check(not any(facetwb.is_planarized(obj) for obj in doc.Objects),
          "undo removes the Planarized object")
    doc.redo()
    result = doc.getObject(result.Name)
    check(result is not None, "redo brings it back")
    doc.recompute()

    result.ViewObject.DisplayMode = "Planarity"
    low, high = bounding_box(result.ViewObject.RootNode)
    mesh = facetwb.get_mesh(result)
    check(np.allclose(low, mesh.vertices.min(axis=0), atol=1e-4)
          and np.allclose(high, mesh.vertices.max(axis=0), atol=1e-4),
          f"Fit all sees the mesh, not the legend (bounding box {low} .. {high})")
    path = os.path.join(out_dir, "planarity.png")
    save_view(view, path)
    check_screenshot(check, path, "planarity", legend=True)
    for mode in ("Flat Lines", "Shaded", "Wireframe"):
        result.ViewObject.DisplayMode = mode
        Gui.updateGui()
        check(result.ViewObject.DisplayMode == mode, f"display mode {mode}")
    result.ViewObject.DisplayMode = "Planarity"

    # Saved and reopened, the document shows the same planarity map.
    path = os.path.join(out_dir, "planarity.FCStd")
    name = result.Name
    doc.saveAs(path)
    App.closeDocument(doc.Name)
    doc = App.openDocument(path)
    Gui.updateGui()
    result = doc.getObject(name)
    check(result is not None and result.ViewObject.DisplayMode == "Planarity",
          "reopened: the result is still shown in Planarity mode")
    check(result.ViewObject.Proxy.__class__.__name__ == "ViewProviderPlanarized",
          "reopened: its view provider is restored")
    view = Gui.ActiveDocument.ActiveView
    path = os.path.join(out_dir, "reopened.png")
    save_view(view, path)
    check_screenshot(check, path, "reopened", legend=True)
    check_color_by(check, view, result, out_dir)
    source = result.Source

    # Facet_ToPolyMesh on a Part box: six quads, kept linked to the box.
    box = doc.addObject("Part::Box", "Box")
    doc.recompute()
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(box)
    before = set(doc.Objects)
    Gui.runCommand("Facet_ToPolyMesh")
    added = [obj for obj in doc.Objects if obj not in before]
    check(len(added) == 1 and facetwb.is_polymesh(added[0]) and added[0].Source is box
          and added[0].FaceCount == 6, "Facet_ToPolyMesh makes a 6-quad PolyMesh of a box")
    check(not box.ViewObject.Visibility, "the box is hidden")
    App.closeDocument(doc.Name)
    check_lifting(check, out_dir)
    check_lift_from_file(check, out_dir)
    check_plan_fitted_once_fixed(check, out_dir)
    check_lift_failed_plan(check)
    check_panels_from_failed_lifting(check)
    check_lift_mix_states(check, out_dir)
    import pins_checks

    pins_checks.run(check, out_dir, sys.modules[__name__])
    import lift_look_checks

    lift_look_checks.run(check, out_dir, sys.modules[__name__])
    check_panels(check, out_dir)
    check_panel_clashes(check, out_dir)
    check_edit_control(check, out_dir)
    check_edit_linked_control(check)
    check_edit_region(check)
    check_edit_planarized(check, out_dir)
    check_hold_vertices(check, out_dir)
    import preselect_checks

    preselect_checks.run(check, out_dir, sys.modules[__name__])
    check_recompute_in_edit_then_cancel(check, out_dir)
    import lifecycle_checks

    lifecycle_checks.run(check, out_dir, sys.modules[__name__])
    check_recompute_in_lifting_panels_then_cancel(check, out_dir)
    check_recompute_cancel_and_failed_create(check)
    check_planarize_progress(check, out_dir)
    check_stop_and_keep(check)
    check_keep_press_order(check)
    check_busy_progress(check)
    check_planarize_progress_finer(check, out_dir)
    check_examples_open_with_view_providers(check, out_dir)
    import ui_checks

    ui_checks.run(check, out_dir, sys.modules[__name__])
    return check


def recompute_recording_dialog(doc, out_dir, shots, buttons=None):
    """Recompute `doc` under a progress dialog shown at once; returns the (dialog text,
    bar value) pairs whenever the text changed, and the screenshots saved: for each
    (key, file name) of `shots`, the dialog the first time its text holds the key and a
    planarity line. `buttons`, a list, gets the dialog's button text with each pair."""
    from facetwb import progress
    from facetwb.compat import qt_gui

    shown, saved = [], []
    with progress.reporting("Planarize ...", minimum_seconds=0) as reporter:
        say = reporter.say

        def recording_say(text=None):
            say(text)
            shown.append((reporter.dialog.labelText(), reporter.dialog.value()))
            if buttons is not None:
                button = reporter.dialog.findChild(qt_gui().QPushButton)
                buttons.append(None if button is None else button.text())
            for key, name in shots:
                path = os.path.join(out_dir, name)
                if key in shown[-1][0] and "planarity" in shown[-1][0] and path not in saved:
                    saved.append(path)
                    reporter.dialog.grab().save(path)

        reporter.say = recording_say
        doc.recompute()
    return shown, saved


def check_examples_open_with_view_providers(check, out_dir):
    """The example documents are saved by freecadcmd (tools/make_examples.py), without
    GuiDocument.xml: opened in the GUI, their Facet objects had no view provider (nothing
    drawn, no colour map, no task panel). They get their own once the document loads."""
    import FreeCAD as App
    import FreeCADGui as Gui

    wanted = {"Facet::PolyMesh": "ViewProviderPolyMesh",
              "Facet::Planarized": "ViewProviderPlanarized",
              "Facet::PlanGraph": "ViewProviderPlanGraph",
              "Facet::Lifting": "ViewProviderLifting",
              "Facet::PanelSet": "ViewProviderPanels", "Facet::CutSheets": "ViewProviderPanels"}
    for name in ("facade.FCStd", "roof.FCStd"):
        doc = open_example(name)
        facet_objects = [o for o in doc.Objects
                         if getattr(getattr(o, "Proxy", None), "Type", "").startswith("Facet::")]
        missing = [o.Label for o in facet_objects
                   if type(o.ViewObject.Proxy).__name__ != wanted.get(o.Proxy.Type)]
        check(facet_objects and not missing,
              f"{name}: every Facet object has its view provider ({missing or 'all'})")
        planarized = [o for o in facet_objects if o.Proxy.Type in ("Facet::Planarized",
                                                                      "Facet::Lifting")]
        check(all(o.ViewObject.DisplayMode for o in planarized)
              and all("Planarity" in o.ViewObject.listDisplayModes() for o in planarized),
              f"{name}: its results offer the planarity map")
        # FreeCAD attached the placeholder Proxy it restored, not the provider set after
        # it: the providers had no scene graph, the results were not drawn at all
        undrawn = [o.Label for o in facet_objects if o.Proxy.Type not in (
            "Facet::PanelSet", "Facet::CutSheets") and not hasattr(o.ViewObject.Proxy, "coords")]
        check(not undrawn, f"{name}: every Facet mesh has its scene graph ({undrawn or 'all'})")
        # no GuiDocument.xml, no camera: the view showed the default few millimetres about
        # the origin, the results out of sight, until Fit all
        view = Gui.ActiveDocument.ActiveView
        size = view.getSize()
        corners = [tuple(view.getPointOnScreen(p)) for o in planarized
                   for p in (min(o.Points, key=lambda q: q.x + q.y + q.z),
                             max(o.Points, key=lambda q: q.x + q.y + q.z))]
        check(corners and all(0 <= x <= size[0] and 0 <= y <= size[1] for x, y in corners),
              f"{name}: opened, its results are in view ({corners} in {tuple(size)} px)")
        for o in doc.Objects:  # the results alone, in the planarity map
            o.ViewObject.Visibility = o in planarized
        # the roof is lifted to pinned heights: they are drawn (markers with labels), and
        # hidden by ShowPins for the check of the roof's grey below
        pinned = [o for o in planarized if o.Proxy.Type == "Facet::Lifting" and o.PinnedPoints]
        for o in pinned:
            drawn = o.ViewObject.Proxy.pins
            check(len(drawn.points) == len(o.PinnedPoints) == len(drawn.texts),
                  f"{name}: {o.Label} draws its {len(o.PinnedPoints)} pins")
            o.ViewObject.ShowPins = False
            check(not drawn.points, f"{name}: ShowPins off hides them")
        Gui.Selection.clearSelection()
        path = os.path.join(out_dir, f"example_{name.split('.')[0]}.png")
        save_view(Gui.ActiveDocument.ActiveView, path)
        # the planarized facade in its planarity map; the lifted roof in grey, as made
        check_screenshot(check, path, f"{name}: its result", legend=name == "facade.FCStd")
        if name == "facade.FCStd":
            from facetwb import edit_control

            Gui.Selection.addSelection(planarized[0])
            Gui.runCommand("Facet_EditControlMesh")
            check(edit_control.active_session() is not None,
                  f"{name}: Edit control mesh starts on its result")
            if edit_control.active_session() is not None:
                edit_control.finish(False)
        App.closeDocument(doc.Name)


def check_planarize_progress(check, out_dir):
    """A Planarized recompute that re-solves for panel quality (the 32 x 32 hypar) and
    then, method auto, solves by L/L too: the progress dialog's text names the re-solve
    and the comparison, and its bar never runs backwards; the dialog in the first
    re-solve and in the comparison (name, planarity) is saved as progress_resolve.png and
    progress_compare.png."""
    import FreeCAD as App

    import facet
    import facetwb

    sys.path.insert(0, os.path.join(ROOT, "tools", "bench"))
    import families

    b = families.hypar(32)
    doc = App.newDocument("ProgressCheck")
    source = facetwb.make_polymesh(facet.PolyMesh(b.vertices, b.face_start, b.face_vertices),
                                   doc=doc, label="hypar 32")
    result = facetwb.make_planarized(source)
    buttons = []
    shown, saved = recompute_recording_dialog(
        doc, out_dir, (("re-solving", "progress_resolve.png"),
                       ("local/local too", "progress_compare.png")), buttons)
    check(result.isValid(), f"the hypar 32 planarizes ({result.getStatusString()})")
    resolving = [(text, value) for text, value in shown if "re-solving" in text]
    comparing = [(text, value) for text, value in shown if "local/local too" in text]
    if resolving:  # L/G's first solve of this hypar closes corners (test_planarize_quality)
        check(resolving[0][0] == "Planarize ...\nPlanarize "
              f"{result.Label}: re-solving for panel quality (stage 1 of 4)",
              f"the progress dialog says it re-solves ({resolving[:1]})")
        check(any("\nplanarity " in text for text, _value in resolving),
              "the dialog shows the re-solve's planarity under its name")
        # the first solve's result reached the tolerance: the button keeps it
        first = shown.index(resolving[0])
        check(buttons[0] == "Cancel" and "re-solving" not in shown[0][0]
              and set(buttons[first:first + len(resolving)]) == {"Stop and keep"},
              f"the button reads Cancel, then Stop and keep in the re-solves "
              f"({buttons[0]}, {buttons[first]})")
    # method auto (the default) then solves by L/L too: named after the re-solves
    check(bool(comparing) and comparing[0][0] == "Planarize ...\nPlanarize "
          f"{result.Label}: solving by local/local too, for a result closer to the design"
          and shown.index(comparing[0]) > max([shown.index(r) for r in resolving], default=-1),
          f"the progress dialog names auto's comparison after any re-solve ({comparing[:1]})")
    check(any("\nplanarity " in text for text, _value in comparing),
          "the dialog shows the comparison's planarity under its name")
    values = [value for _text, value in resolving + comparing]
    check(values == sorted(values) and 0 < values[0] < 1000,
          f"the progress bar does not run backwards across re-solves and comparison ({values})")
    check(len(saved) == 1 + bool(resolving) and all(os.path.getsize(p) > 1000 for p in saved),
          f"the dialog's screenshots ({saved})")
    check(shown and shown[-1][0] == "Planarize ...", "the title alone after the solve")
    check(buttons and buttons[-1] == "Cancel",
          f"the button reads Cancel again after the solve ({buttons[-1:]})")
    App.closeDocument(doc.Name)


def check_busy_progress(check):
    """A stage that has done nothing yet shows a busy bar, not 0%: nesting 3,200 parts
    sat at 0% for the 44 s of its first batch as if nothing ran; then the bar counts."""
    from facetwb import progress
    from facetwb.objects.panelset import _stage_progress

    with progress.reporting("Cut sheets ...", minimum_seconds=0) as reporter:
        stage = _stage_progress(reporter, reporter.say)
        stage("nest", 0, 3200)
        busy = reporter.dialog.maximum()
        stage("nest", 800, 3200)
        counting = reporter.dialog.maximum(), reporter.dialog.value()
    check(busy == 0 and counting == (1000, 250),
          f"a stage with nothing done shows a busy bar, then counts ({busy}, {counting})")


def check_keep_press_order(check):
    """A press not yet seen when the button's label changes counts as what it read: Cancel
    pressed before the offer to keep cancels; Stop and keep pressed before the operation
    ended (which then finished with its result) is spent, and nothing is cancelled."""
    from facetwb import progress
    from facetwb.compat import qt_gui

    with progress.reporting("Press order ...", minimum_seconds=0) as reporter:
        reporter(1, 10)
        reporter.dialog.cancel()  # the button, as its click does; not yet seen
        reporter.offer_keep()
        button = reporter.dialog.findChild(qt_gui().QPushButton)
        check(reporter.cancelled and not reporter.keeps and button.text() == "Cancel",
              f"Cancel pressed before the offer to keep cancels ({button.text()})")
    with progress.reporting("Press order ...", minimum_seconds=0) as reporter:
        reporter(1, 10)
        reporter.offer_keep()
        reporter.dialog.cancel()
        reporter.withdraw_keep(True)
        check(not reporter.cancelled and not reporter(2, 10) and not reporter.keeps,
              "Stop and keep pressed as the operation finished: spent, nothing cancelled")
    with progress.reporting("Press order ...", minimum_seconds=0) as reporter:
        reporter(1, 10)
        reporter.offer_keep()
        reporter.dialog.cancel()
        reporter.withdraw_keep(False)
        check(reporter.cancelled and reporter(2, 10),
              "Stop and keep pressed when nothing could be kept: cancelled")


def check_stop_and_keep(check):
    """The dialog's button pressed in the first re-solve of the 32 x 32 hypar (L/G), when it
    reads Stop and keep: the object keeps the first solve's planar result."""
    import FreeCAD as App

    import facet
    import facetwb
    from facetwb import progress
    from facetwb.compat import qt_gui

    sys.path.insert(0, os.path.join(ROOT, "tools", "bench"))
    import families

    b = families.hypar(32)
    mesh = facet.PolyMesh(b.vertices, b.face_start, b.face_vertices)
    first = facet.planarize(mesh, method="lg", quality_angle=0.0)
    doc = App.newDocument("StopCheck")
    source = facetwb.make_polymesh(mesh, doc=doc, label="hypar 32")
    result = facetwb.make_planarized(source, method="lg")
    pressed = []
    with progress.reporting("Planarize ...", minimum_seconds=0) as reporter:
        say = reporter.say

        def pressing_say(text=None):
            say(text)
            if text and "re-solving" in text and not pressed:
                button = reporter.dialog.findChild(qt_gui().QPushButton)
                pressed.append(button.text())
                button.click()

        reporter.say = pressing_say
        doc.recompute()
    check(pressed == ["Stop and keep"], f"the button in the re-solve reads Stop and keep ({pressed})")
    kept = facetwb.get_mesh(result).vertices
    check(result.isValid() and result.QualityCheck == "narrow" and result.Converged
          and (kept == first.mesh.vertices).all() and not reporter.cancelled,
          f"Stop and keep: the first solve's planar result is kept ({result.getStatusString()}, "
          f"{result.QualityCheck}, {result.NarrowCorners} narrow corners)")
    App.closeDocument(doc.Name)


def check_planarize_progress_finer(check, out_dir):
    """The demo facade, method auto: L/L's result moves the vertices too far and L/G
    solves again with a finer hold; the progress dialog names that solve after the
    comparison, with its planarity, and is saved as progress_finer.png."""
    import FreeCAD as App

    import facetwb
    from facetwb import importer

    doc = App.newDocument("FinerCheck")
    source = importer.import_mesh(os.path.join(ROOT, "examples", "wave_facade.obj"), doc)
    doc.recompute()
    result = facetwb.make_planarized(source)
    shown, saved = recompute_recording_dialog(doc, out_dir, (("finer hold", "progress_finer.png"),))
    check(result.isValid(), f"the demo facade planarizes ({result.getStatusString()})")
    comparing = [s for s in shown if "local/local too" in s[0]]
    finer = [s for s in shown if "finer hold" in s[0]]
    check(bool(comparing) and bool(finer) and finer[0][0] == "Planarize ...\nPlanarize "
          f"{result.Label}: solving by local/global again with a finer hold, closer to the design"
          and shown.index(finer[0]) > shown.index(comparing[-1]),
          f"the progress dialog names the finer L/G solve after the comparison ({finer[:1]})")
    values = [value for _text, value in comparing + finer]
    check(values == sorted(values), f"the progress bar does not run backwards ({values})")
    check(len(saved) == 1 and os.path.getsize(saved[0]) > 1000, f"the dialog's screenshot ({saved})")
    App.closeDocument(doc.Name)


def legend_strings(vobj):
    """The strings of the legend's labels (title, ticks, max) of a Facet view provider."""
    from pivy import coin

    search = coin.SoSearchAction()
    search.setType(coin.SoText2.getClassTypeId())
    search.setInterest(coin.SoSearchAction.ALL)
    search.apply(vobj.Proxy.legend.labels)
    paths = search.getPaths()
    return [paths[i].getTail().string.getValues()[0] for i in range(paths.getLength())]


def check_color_by(check, view, result, out_dir):
    """The Planarized view provider's ColorBy: smallest angle in degrees, red for small."""
    import FreeCADGui as Gui
    import numpy as np

    import facet
    import facetwb
    from facetwb.viewproviders import colormap

    vobj = result.ViewObject
    check("Smallest angle" in vobj.getEnumerationsOfProperty("ColorBy"),
          "ColorBy offers Smallest angle")
    planarity_colours = np.array(vobj.Proxy.planarity_material.diffuseColor.getValues())
    vobj.ColorBy = "Smallest angle"
    Gui.updateGui()
    angle_colours = np.array(vobj.Proxy.planarity_material.diffuseColor.getValues())
    check(angle_colours.shape == planarity_colours.shape
          and not np.allclose(angle_colours, planarity_colours),
          "ColorBy Smallest angle recolours the faces")
    labels = legend_strings(vobj)
    check(any(label.startswith("Smallest angle") for label in labels)
          and any(label.endswith(" deg") for label in labels),
          f"the legend is titled Smallest angle and labelled in degrees ({labels})")
    angles = facet.quality(facetwb.get_mesh(result)).min_angle
    expected = colormap.colors(angles, angles.max(), reverse=True)
    check(np.allclose(angle_colours, expected, atol=1e-6),
          "faces coloured by smallest angle, small angles red (reversed map)")
    path = os.path.join(out_dir, "smallest_angle.png")
    save_view(view, path)
    check_screenshot(check, path, "smallest angle", legend=True)
    vobj.ColorBy = "Straightest corner"
    Gui.updateGui()
    turns = facet.quality(facetwb.get_mesh(result)).straight_corner
    expected = colormap.colors(turns, turns.max(), reverse=True)
    check(np.allclose(np.array(vobj.Proxy.planarity_material.diffuseColor.getValues()), expected,
                      atol=1e-6),
          "faces coloured by how far their straightest corner turns, nearly straight red")
    labels = legend_strings(vobj)
    check(any(label.startswith("Straightest corner") for label in labels),
          f"the legend is titled Straightest corner ({labels})")
    path = os.path.join(out_dir, "straightest_corner.png")
    save_view(view, path)
    check_screenshot(check, path, "straightest corner", legend=True)
    vobj.ColorBy = "Distance to input"
    Gui.updateGui()
    labels = legend_strings(vobj)
    check(any(label.startswith("Distance to input") for label in labels)
          and not any("not computed" in label for label in labels),
          f"ColorBy Distance to input is computed from the source ({labels})")
    # the distance to a Reference given (the design surface of Data surface): not computed
    # without one; with one, each face's farthest corner from it
    vobj.ColorBy = "Distance to reference"
    Gui.updateGui()
    check(any("not computed" in label for label in legend_strings(vobj)),
          "ColorBy Distance to reference says not computed without a Reference")
    from facetwb import live_parameters

    live_parameters.ENABLED = False  # (the property alone, no re-solve)
    try:
        result.Reference = result.Source
        vobj.ColorBy = "Planarity"
        vobj.ColorBy = "Distance to reference"
        Gui.updateGui()
        far = facet.quality(facetwb.get_mesh(result),
                            reference=facetwb.get_mesh(result.Source)).per_face("distance")
        colours = np.array(vobj.Proxy.planarity_material.diffuseColor.getValues())
        check(np.allclose(colours, colormap.colors(far, far.max()), atol=1e-6)
              and any(label.startswith("Distance to reference")
                      for label in legend_strings(vobj)),
              "ColorBy Distance to reference colours each face by its distance from it")
        result.Reference = None
        result.purgeTouched()
    finally:
        live_parameters.ENABLED = True
    vobj.ColorBy = "Planarity"
    Gui.updateGui()
def check_lifting(check, out_dir):
    """Facet_PlanGraph on a sketched hipped-roof plan, Facet_Lift towards a dome; lifting.png."""
    import FreeCAD as App
    import FreeCADGui as Gui
    import Part

    import facetwb

    for name in ("Facet_PlanGraph", "Facet_Lift"):
        check(name in Gui.listCommands(), f"command {name} is registered")
    doc = App.newDocument("Lifting")
    sketch = doc.addObject("Sketcher::SketchObject", "RoofPlan")
    corners = [(0, 0), (8000, 0), (8000, 5000), (0, 5000)]
    ridge = [(2500, 2500), (5500, 2500)]
    lines = [(corners[i], corners[(i + 1) % 4]) for i in range(4)] + [(ridge[0], ridge[1])]
    lines += [(corners[0], ridge[0]), (corners[3], ridge[0]), (corners[1], ridge[1]),
              (corners[2], ridge[1])]
    for a, b in lines:
        sketch.addGeometry(Part.LineSegment(App.Vector(*a, 0), App.Vector(*b, 0)), False)
    dome = doc.addObject("Part::Sphere", "Dome")
    dome.Radius = 6000
    dome.Placement.Base = App.Vector(4000, 2500, -3000)
    doc.recompute()
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(sketch)
    before = set(doc.Objects)
    Gui.runCommand("Facet_PlanGraph")
    plans = [obj for obj in doc.Objects if obj not in before and facetwb.is_plan_graph(obj)]
    check(len(plans) == 1 and plans[0].isValid() and plans[0].FaceCount == 4,
          "Facet_PlanGraph makes a 4-face plan of the sketch")
    if not plans:
        return
    plan = plans[0]
    check(not sketch.ViewObject.Visibility, "the sketch is hidden")
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(plan)
    Gui.Selection.addSelection(dome)
    before = set(doc.Objects)
    accept_panel(check, "Facet_Lift")
    liftings = [obj for obj in doc.Objects if obj not in before and facetwb.is_lifting(obj)]
    check(len(liftings) == 1, "Facet_Lift makes a Lifting")
    if not liftings:
        return
    lifting = liftings[0]
    check(lifting.isValid() and lifting.Dimension == 4 and lifting.PlanarityMaxRel <= 1e-9,
          f"the lifting is planar (dimension {lifting.Dimension}, planarity "
          f"{lifting.PlanarityMaxRel:.2g})")
    check(lifting.ViewObject.Proxy.__class__.__name__ == "ViewProviderLifting",
          "the lifting has its view provider")
    check(not dome.ViewObject.Visibility and not plan.ViewObject.Visibility,
          "the dome and the plan are hidden")
    heights = [p.z for p in lifting.Points]
    check(max(heights) - min(heights) > 100, "the roof is not flat")
    Gui.Selection.clearSelection()  # selected objects are drawn in the highlight colour
    path = os.path.join(out_dir, "lifting.png")
    save_view(Gui.ActiveDocument.ActiveView, path)
    check_screenshot(check, path, "lifting", legend=False)

    # a double-click on a Lifting that follows a surface opens its Shape lifting panel (it
    # opened Pin heights, which said the pins were not used)
    from facetwb.taskpanels import lift_mix, lift_pins

    Gui.Selection.clearSelection()
    lifting.ViewObject.Proxy.doubleClicked(lifting.ViewObject)
    Gui.updateGui()
    opened = lift_mix.active
    check(opened is not None and lift_pins.active is None,
          "a double-click on a Lifting that follows a surface opens Shape lifting")
    if opened is not None:
        opened.reject()
    Gui.updateGui()
    check(lift_mix.active is None and not Gui.Control.activeDialog()
          and Gui.ActiveDocument.getInEdit() is None,
          "its Cancel closes it and leaves no object in edit")

    # Facet_LiftMix: a slider reshapes the roof live; faces stay planar; Cancel restores.
    check("Facet_LiftMix" in Gui.listCommands(), "command Facet_LiftMix is registered")
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(lifting)
    before = [p.z for p in lifting.Points]
    # a designer's label: in the title ("Shape Roof over ...") it widened the panel to
    # 502 px in the 258 px pane, Cancel and the slider values cut off
    label = lifting.Label
    lifting.Label = "Roof over the north wing of the community centre lifted"
    Gui.runCommand("Facet_LiftMix")
    Gui.updateGui()
    from facetwb.taskpanels import lift_mix

    panel = lift_mix.active
    check(bool(Gui.Control.activeDialog()) and panel is not None,
          "the Shape lifting panel is open")
    if panel is not None:
        check(len(panel.sliders) == 1, f"one slider for dimension 4 ({len(panel.sliders)})")
        # "the plan admits 1 non-planar liftings ...; every face stays exactly planar":
        # liftings that are not one plane, read as faces that are not planar
        from PySide import QtGui

        intro = [w.text() for w in panel.form.findChildren(QtGui.QLabel)
                 if "slider" in w.text() and "admits" in w.text()]
        check(len(intro) == 1 and "non-planar" not in intro[0]
              and "one other shape of the roof with planar faces" in intro[0],
              f"the Shape lifting panel says what its sliders add ({intro})")
        # it fits the task pane: a one-line text made it 479 px wide in a 258 px pane,
        # with Cancel and the slider values off the screen
        from PySide import QtGui

        settle(20)  # the task pane is laid out once the event loop runs
        panes = [w for w in Gui.getMainWindow().findChildren(QtGui.QScrollArea)
                 if w.isVisible() and w.widget() and w.widget().isAncestorOf(panel.form)]
        width = max(panel.form.minimumSizeHint().width(),
                    panes[0].widget().width() if panes else 0)
        check(panes and width <= panes[0].viewport().width(),
              f"the Shape lifting panel fits the task pane ({width} px in "
              f"{panes[0].viewport().width() if panes else '?'} px)")
        # beside their labels the sliders were 66 to 99 px, the height slider a 32 px stub
        short = [s.width() for s in panel.sliders + [panel.drag] if s.width() < 150]
        check(not short, f"the panel's sliders are long enough to drag (short: {short} px)")
        # a plan graph made while the panel is open: its transaction committed the panel's,
        # and after Cancel the undo list held a 'Shape lifting' step
        from facetwb.commands.lift import CommandPlanGraph

        check(not CommandPlanGraph().IsActive(),
              "while the Shape lifting panel is open, Plan graph is inactive")
        width = panel.sliders[0].width()
        panel.sliders[0].setValue(60)
        Gui.updateGui()
        # the value label beside it grew with the value ("0.00 mm" to "1200.00 mm")
        check(panel.sliders[0].width() == width,
              f"the slider keeps its length as its value grows ({width} -> "
              f"{panel.sliders[0].width()} px)")
        after = [p.z for p in lifting.Points]
        moved = max(abs(a - b) for a, b in zip(after, before))
        check(moved > 100 and lifting.PlanarityMaxRel <= 1e-9,
              f"the slider reshapes the roof ({moved:.0f} mm), faces stay planar")
        Gui.Selection.clearSelection()  # selected objects are drawn in the highlight colour
        path = os.path.join(out_dir, "lifting_mix.png")
        save_view(Gui.ActiveDocument.ActiveView, path)
        check_screenshot(check, path, "lifting mix", legend=False)
        mixed = [p.z for p in lifting.Points]
        panel.vertex.setValue(4)
        panel.drag.setValue(-100)  # the widest value beside the vertex box
        for _ in range(10):
            Gui.updateGui()
            time.sleep(0.01)
        check(panes[0].widget().width() <= panes[0].viewport().width(),
              f"the panel fits the task pane at the lowest vertex height "
              f"({panes[0].widget().width()} px in {panes[0].viewport().width()} px)")
        panel.drag.setValue(20)
        Gui.updateGui()
        dragged = [p.z for p in lifting.Points]
        raised = dragged[4] - mixed[4]
        check(abs(raised - 0.2 * panel.range) < 1e-6 and lifting.PlanarityMaxRel <= 1e-9,
              f"dragging vertex 4 raises it by {raised:.0f} mm, faces stay planar")
        panel.reject()
        Gui.updateGui()
        restored = [p.z for p in lifting.Points]
        check(max(abs(a - b) for a, b in zip(restored, before)) < 1e-6 and not lifting.Mix
              and not lifting.Drags, "Cancel restores the roof")
    lifting.Label = label
    if Gui.Control.activeDialog():
        Gui.Control.closeDialog()


def check_lift_mix_states(check, out_dir):
    """The Shape lifting panel on a Lifting that failed says why there is nothing to shape;
    Cancel without a change leaves what is made from the Lifting as it was."""
    import FreeCAD as App
    import FreeCADGui as Gui

    from facetwb.taskpanels import lift_mix

    doc, lifting, panels = open_roof_example()
    doc.recompute()
    # Cancel of an unchanged panel set Mix and Drags again and recomputed: the panels
    # (and cut sheets, which rewrite their files) were rebuilt for nothing
    stamp = panels.Shape.hashCode() if hasattr(panels.Shape, "hashCode") else None
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(lifting)
    Gui.runCommand("Facet_LiftMix")
    Gui.updateGui()
    panel = lift_mix.active
    if panel is not None:
        panel.reject()
        Gui.updateGui()
    check(panel is not None and "Touched" not in lifting.State
          and "Touched" not in panels.State
          and (stamp is None or panels.Shape.hashCode() == stamp),
          f"Cancel of an unchanged Shape lifting panel recomputes nothing ({panels.State})")
    points = [tuple(p) for p in lifting.Points]
    volume = panels.Shape.Volume

    def opened_and_moved():
        """The Shape lifting panel, opened and its first slider moved to 40 (or None)."""
        Gui.runCommand("Facet_LiftMix")
        Gui.updateGui()
        opened = lift_mix.active
        if opened is not None:
            opened.sliders[0].setValue(40)
            Gui.updateGui()
        return opened

    panel = opened_and_moved()
    if panel is not None:
        moved = [tuple(p) for p in lifting.Points] != points
        panel.reject()
        Gui.updateGui()
        check(moved and [tuple(p) for p in lifting.Points] == points and not lifting.Mix
              and abs(panels.Shape.Volume - volume) < 1e-9 * volume
              and "Touched" not in lifting.State and "Touched" not in panels.State,
              f"Cancel after a slider's move puts the roof back, up to date "
              f"({lifting.State}, {panels.State})")
    # Recompute pressed with the panel open rebuilt the panels from the moved roof; Cancel
    # put the roof back and left them so, marked up to date
    panel = opened_and_moved()
    if panel is not None:
        doc.recompute()  # Recompute pressed
        rebuilt = abs(panels.Shape.Volume - volume) > 1e-6 * volume
        panel.reject()
        Gui.updateGui()
        # (the transaction put the Shape back; the panels the cut sheets take, and their
        # files, stayed those of the moved roof)
        computed = panels.Proxy.computed(panels)[0]
        area = sum(p.area for p in computed.panels)
        check(rebuilt and abs(panels.Shape.Volume - volume) < 1e-9 * volume
              and abs(area - sum(panels.Areas)) < 1e-9 * area
              and "Touched" not in panels.State,
              f"Cancel after a Recompute with the Shape lifting panel open rebuilds the "
              f"panels from the roof put back (their area {area:.9g}, the PanelSet's "
              f"{sum(panels.Areas):.9g}; {panels.State})")
    # the sliders re-solve the Lifting alone: recomputing what is made from it at every
    # step took 10 s a step with 5,000 panels; OK recomputes it, in the same undo step
    shown = (lifting.ViewObject.Visibility, panels.ViewObject.Visibility)
    Gui.runCommand("Facet_LiftMix")
    Gui.updateGui()
    panel = lift_mix.active
    if panel is not None:
        undo = len(doc.UndoNames)
        panel.sliders[0].setValue(40)
        Gui.updateGui()
        moved = [tuple(p) for p in lifting.Points] != points
        waiting = "Touched" in panels.State and abs(panels.Shape.Volume - volume) < 1e-9 * volume
        check(moved and waiting and "Touched" not in lifting.State,
              f"a slider re-solves the roof live; its panels wait for OK ({panels.State})")
        check(lifting.ViewObject.Visibility and not panels.ViewObject.Visibility,
              "meanwhile the roof is shown and the waiting panels hidden")
        panel.accept()
        Gui.updateGui()
        check((lifting.ViewObject.Visibility, panels.ViewObject.Visibility) == shown,
              "after OK the roof and the panels are shown as before")
        check("Touched" not in panels.State and panels.isValid()
              and abs(panels.Shape.Volume - volume) > 1e-6 * volume
              and len(doc.UndoNames) == undo + 1 and doc.UndoNames[0] == "Shape lifting",
              f"OK recomputes the panels, one undo step ({doc.UndoNames[:2]})")
        doc.undo()
        doc.recompute()
        check(not lifting.Mix and max(abs(p.z - q[2]) for p, q in zip(lifting.Points, points))
              < 1e-6, "undo puts the roof back")
    # a Lifting with no targets: its Dimension is 0, and the panel said "this plan admits
    # only planes: there is nothing to mix"
    lifting.PinnedPoints = []
    doc.recompute()
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(lifting)
    Gui.runCommand("Facet_LiftMix")
    Gui.updateGui()
    panel = lift_mix.active
    if check(panel is not None, "the Shape lifting panel opens on a Lifting that failed"):
        text = panel.form.findChildren(type(panel.labels[0]) if panel.labels else
                                       __import__("PySide").QtGui.QLabel)[0].text()
        check(not panel.sliders and "no targets" in text and "only planes" not in text,
              f"it says why there is nothing to shape ({text!r})")
        panel.reject()
        Gui.updateGui()
    check(not Gui.Control.activeDialog(), "its Cancel closes it")
    App.closeDocument(doc.Name)


def plan_graph_from_file(path):
    """Facet_PlanGraph with nothing selected, its file dialog answered with ``path``."""
    import FreeCADGui as Gui
    from PySide import QtGui

    ask = QtGui.QFileDialog.getOpenFileName
    try:
        QtGui.QFileDialog.getOpenFileName = staticmethod(lambda *args, **kw: (path, ""))
        Gui.Selection.clearSelection()
        Gui.runCommand("Facet_PlanGraph")
    finally:
        QtGui.QFileDialog.getOpenFileName = ask


def check_plan_fitted_once_fixed(check, out_dir):
    """A drawing whose first read fails (an arc, refused without ArcTolerance) into an
    empty document: the view was fitted to nothing then, and once ArcTolerance was set the
    plan showed as a corner at the default camera's few millimetres about the origin. It
    is fitted when the fix first draws it; unless the designer has moved the view since
    (it was fitted all the same, the view they chose taken from them)."""
    import tempfile

    import ezdxf
    import FreeCAD as App
    import FreeCADGui as Gui

    import facetwb
    from facetwb.viewproviders import attach

    folder = tempfile.mkdtemp()
    path = os.path.join(folder, "arc_plan.dxf")
    drawing = ezdxf.new()
    drawing.header["$INSUNITS"] = 4
    msp = drawing.modelspace()
    for a, b in (((0, 0), (12000, 0)), ((12000, 0), (12000, 8000)),
                 ((12000, 8000), (0, 8000)), ((0, 0), (12000, 8000))):
        msp.add_line(a, b)
    msp.add_arc((4000, 4000), 4000 * 2 ** 0.5, 135, 225)  # (0, 8000) round to (0, 0)
    drawing.saveas(path)
    for moved in (False, True):
        doc = App.newDocument("ArcPlan")
        plan_graph_from_file(path)
        settle(5)
        plans = [o for o in doc.Objects if facetwb.is_plan_graph(o)]
        if not check(len(plans) == 1 and not plans[0].isValid() and "ARC" in
                     plans[0].getStatusString(), "a plan with an arc is refused at first"):
            App.closeDocument(doc.Name)
            return
        plan = plans[0]
        view = Gui.ActiveDocument.ActiveView
        if moved:  # the designer pans the view (as a drag does: the camera moves)
            camera = view.getCameraNode()
            x, y, z = camera.position.getValue().getValue()
            camera.position.setValue(x + 250.0, y - 100.0, z)
            settle(2)
        chosen = attach.view_pose(doc.Name)
        plan.ArcTolerance = 50.0
        doc.recompute()
        settle(10)
        size = view.getSize()
        if moved:
            check(plan.isValid() and plan.FaceCount >= 2
                  and attach.view_pose(doc.Name) == chosen,
                  "a view the designer moved before the fix drew the plan is left as they "
                  f"chose ({chosen} before, {attach.view_pose(doc.Name)} after)")
        else:
            corners = [tuple(view.getPointOnScreen(p)) for p in plan.Points]
            view.saveImage(os.path.join(out_dir, "plan_fitted_once_fixed.png"), size[0],
                           size[1], "Current")
            check(plan.isValid() and plan.FaceCount >= 2 and corners
                  and all(0 <= x <= size[0] and 0 <= y <= size[1] for x, y in corners),
                  f"the plan drawn once ArcTolerance is set is in view ({plan.FaceCount} "
                  f"faces, {min(corners, default=None)}, {max(corners, default=None)} in "
                  f"{tuple(size)} px)")
        App.closeDocument(doc.Name)


def check_lift_from_file(check, out_dir):
    """The bundled roof without a surface: Facet_PlanGraph on examples/roof_plan.dxf (the
    file dialog answered), then Facet_Lift with the plan alone to the heights of
    examples/roof_heights.csv, chosen in its panel; neither file is changed."""
    import hashlib

    import FreeCAD as App
    import FreeCADGui as Gui
    from PySide import QtGui

    import facetwb
    from facetwb.commands.lift import CommandLift
    from facetwb.taskpanels import derive_panels, forms

    dxf = os.path.join(ROOT, "examples", "roof_plan.dxf")
    csv = os.path.join(ROOT, "examples", "roof_heights.csv")

    def digest(path):
        with open(path, "rb") as handle:
            return hashlib.sha256(handle.read()).hexdigest()

    before = {path: digest(path) for path in (dxf, csv)}
    doc = App.newDocument("RoofFromFiles")
    ask = QtGui.QFileDialog.getOpenFileName
    try:
        plan_graph_from_file(dxf)
        plans = [o for o in doc.Objects if facetwb.is_plan_graph(o)]
        if not check(len(plans) == 1 and plans[0].isValid() and plans[0].FaceCount == 7,
                     "Facet_PlanGraph reads examples/roof_plan.dxf: 7 faces"):
            App.closeDocument(doc.Name)
            return
        plan = plans[0]
        # read into an empty document, the plan is in view
        view = Gui.ActiveDocument.ActiveView
        size = view.getSize()
        corners = [tuple(view.getPointOnScreen(p)) for p in plan.Points]
        check(all(0 <= x <= size[0] and 0 <= y <= size[1] for x, y in corners),
              f"the plan read into an empty document is in view "
              f"({min(corners)}, {max(corners)} in {tuple(size)} px)")
        # with the plan alone selected Lift plan was inactive: a table of heights had no
        # way into the GUI
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(plan)
        check(CommandLift().IsActive(), "Lift plan: active with the plan alone")
        Gui.runCommand("Facet_Lift")
        Gui.updateGui()
        panel = derive_panels.active
        if not check(panel is not None and panel.from_file(),
                     "its panel opens with the points file as the target"):
            App.closeDocument(doc.Name)
            return
        names = [o.Name for o in doc.Objects]
        check(panel.accept() is False and [o.Name for o in doc.Objects] == names
              and "points file" in forms.widget(panel.form, "message").text(),
              "OK without a file: nothing added, the panel asks for one")
        forms.widget(panel.form, "TargetFile").setText(csv[:-4])
        check(not forms.widget(panel.form, "message").text(),
              "a path typed in the field clears that message (it stayed until OK)")
        QtGui.QFileDialog.getOpenFileName = staticmethod(lambda *args, **kw: (csv, ""))
        panel.browse.click()
        check(forms.get_value(panel.form, "TargetFile") == csv
              and not forms.widget(panel.form, "message").text(),
              "Browse fills the points file")
        settle(20)
        panes = [w for w in Gui.getMainWindow().findChildren(QtGui.QScrollArea)
                 if w.isVisible() and w.widget() and w.widget().isAncestorOf(panel.form)]
        check(panes and panes[0].widget().width() <= panes[0].viewport().width(),
              f"the Lift plan panel fits the task pane "
              f"({panes[0].widget().width() if panes else '?'} px in "
              f"{panes[0].viewport().width() if panes else '?'} px)")
        import ui_checks

        ui_checks.window_shot(os.path.join(out_dir, "taskpanel_lift_file.png"))
        check(panel.accept() and derive_panels.active is None,
              "Lift plan: OK applies and closes the panel")
    finally:
        QtGui.QFileDialog.getOpenFileName = ask
    liftings = [o for o in doc.Objects if facetwb.is_lifting(o)]
    lifting = liftings[0] if len(liftings) == 1 else None
    check(lifting is not None and lifting.isValid() and lifting.TargetFile == csv
          and lifting.Targets is None and lifting.Dimension == 7
          and lifting.TargetMax.Value < 1e-2 and lifting.PlanarityMaxRel <= 1e-9,
          f"the plan is lifted to the file's five heights, planar "
          f"({lifting and lifting.getStatusString()})")
    check({path: digest(path) for path in (dxf, csv)} == before,
          "the DXF and the heights file are not changed")
    doc.undo()
    check(not any(facetwb.is_lifting(o) for o in doc.Objects), "undo removes the Lifting")
    App.closeDocument(doc.Name)


def report_view_text():
    """What the report view holds now."""
    import FreeCADGui as Gui
    from PySide import QtGui

    return "\n".join(report.toPlainText() for report in
                     Gui.getMainWindow().findChildren(QtGui.QTextEdit, "Report view"))


def check_lift_failed_plan(check):
    """Lift plan on a plan whose drawing failed to read (a face with a hole) says so in the
    report view and opens no panel: it broke with a traceback ending "Plan holds no mesh"."""
    import tempfile

    import FreeCAD as App
    import FreeCADGui as Gui

    import facetwb
    from facetwb.taskpanels import derive_panels

    doc = App.newDocument("HolePlan")
    with tempfile.TemporaryDirectory() as tmp:
        drawing = os.path.join(tmp, "hole.csv")
        with open(drawing, "w") as handle:
            for ring in ([(0, 0), (9000, 0), (9000, 6000), (0, 6000)],
                         [(3000, 2000), (6000, 2000), (6000, 4000), (3000, 4000)]):
                for a, b in zip(ring, ring[1:] + ring[:1]):
                    handle.write(f"{a[0]},{a[1]},{b[0]},{b[1]}\n")
        plan = facetwb.make_plan_graph(file=drawing, doc=doc)
        doc.recompute()
    check(not plan.isValid() and not plan.FaceStart, "a plan with a hole fails to read")
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(plan)
    settle(5)  # (the recompute's messages reach the report view)
    before = len(report_view_text())
    Gui.runCommand("Facet_Lift")
    settle(5)
    said = report_view_text()[before:]
    lines = [line for line in said.splitlines() if "holds no plan to lift" in line]
    check(derive_panels.active is None and not Gui.Control.activeDialog()
          and len(lines) == 1 and "has a hole" in lines[0] and "Traceback" not in said,
          f"Lift plan on the failed plan says why, no panel, no traceback ({said.strip()!r})")
    Gui.Selection.clearSelection()
    App.closeDocument(doc.Name)


def check_panels_from_failed_lifting(check):
    """Panels on a Lifting in error (its pin near no plan vertex) is refused in its panel,
    naming the Lifting: it made an empty PanelSet and said "0 panels"."""
    import FreeCAD as App
    import FreeCADGui as Gui

    import facetwb
    from facetwb.taskpanels import derive_panels, forms

    doc = App.newDocument("FailedLifting")
    plan = facetwb.make_plan_graph(doc=doc, file=os.path.join(ROOT, "examples", "roof_plan.dxf"))
    doc.recompute()
    lifting = facetwb.make_lifting(plan, pins=[(123.0, 456.0, 3000.0)])
    doc.recompute()
    check(plan.isValid() and not lifting.isValid(), "a Lifting whose pin is at no vertex fails")
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(lifting)
    names = [o.Name for o in doc.Objects]
    Gui.runCommand("Facet_PanelSet")
    Gui.updateGui()
    panel = derive_panels.active
    if check(panel is not None, "Panels opens on it"):
        refused = panel.accept() is False
        # (accepted, the panel is closed and its form gone)
        message = forms.widget(panel.form, "message").text() if refused else ""
        check(refused and [o.Name for o in doc.Objects] == names
              and lifting.Label in message and "in error" in message.lower(),
              f"Panels on the failed Lifting is refused, nothing added ({message!r}, "
              f"{[o.Label for o in doc.Objects]})")
        if derive_panels.active is panel:
            panel.reject()
    Gui.updateGui()
    Gui.Selection.clearSelection()
    App.closeDocument(doc.Name)


def check_panels(check, out_dir):
    """Facet_PanelSet and Facet_CutSheets on a planar quad mesh, with screenshots."""
    import FreeCAD as App
    import FreeCADGui as Gui
    import numpy as np

    import facetwb

    sys.path.insert(0, os.path.join(ROOT, "tests", "python"))
    from panel_meshes import translational

    for name in ("Facet_PanelSet", "Facet_CutSheets"):
        check(name in Gui.listCommands(), f"command {name} is registered")
    doc = App.newDocument("Panels")
    source = facetwb.make_polymesh(translational(), label="translational")
    doc.recompute()
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(source)
    accept_panel(check, "Facet_PanelSet")
    sets = [obj for obj in doc.Objects if facetwb.is_panelset(obj)]
    if not check(len(sets) == 1, "Facet_PanelSet added one PanelSet"):
        return
    ps = sets[0]
    check(ps.isValid(), f"the PanelSet is valid ({ps.getStatusString()})")
    check(len(ps.Shape.Solids) == 20 and all(s.isValid() for s in ps.Shape.Solids),
          "it holds 20 valid solids")
    check(ps.ViewObject.Proxy.getIcon().endswith("Facet_PanelSet.svg"), "it has its icon")
    # a half turn maps the translational surface's panels onto each other in pairs
    said = [line for line in report_view_text().splitlines() if "20 panels" in line]
    check(ps.PartTypeCount == 10 and said and "20 panels, 10 part types within 0.5 mm" in said[-1],
          f"the panel's OK says how many part types ({said[-1:]})")
    source.ViewObject.Visibility = False
    Gui.Selection.clearSelection()
    ps.ViewObject.DisplayMode = "Flat Lines"
    view = Gui.ActiveDocument.ActiveView
    path = os.path.join(out_dir, "panels.png")
    save_view(view, path)
    pixels = image_pixels(path)
    colours = np.unique(pixels.reshape(-1, 3)[::7], axis=0).shape[0]
    check(colours > 50, f"panels: not a uniform image ({colours} colours)")
    middle = pixels[HEIGHT // 4: 3 * HEIGHT // 4, WIDTH // 4: 3 * WIDTH // 4].astype(int)
    # the panels are grey to light blue-grey, or red where they overlap another (square
    # cuts 40 mm thick overlap across these sharp valleys up to a gap of 9.4 mm: with the
    # default 6 mm, all of them);
    # FreeCAD's background gradient is a clearly blue-violet (blue channel 25+ above
    # red) in the middle of the view
    greyish = int((np.abs(middle[..., 2] - middle[..., 0]) < 20).sum())
    red = int(((middle[..., 0] > 2 * middle[..., 2]) & (middle[..., 0] > 40)).sum())
    from facet.panels import DEFAULT_GAP_MM

    check(ps.Gap.Value == DEFAULT_GAP_MM and list(ps.ClashingPanels) == list(ps.PartIds)
          and ps.ClearingGap.Value > DEFAULT_GAP_MM,
          f"with the default gap ({ps.Gap.Value} mm) every panel still overlaps a neighbour "
          f"({len(ps.ClashingPanels)} of 20; ClearingGap {ps.ClearingGap.Value:.3g} mm)")
    check(greyish + red > 0.15 * middle.size / 3,
          f"panels: the solids are drawn ({greyish} grey and {red} red pixels)")
    # each part type a colour of its own: 10 types, panel f alike to panel 19 - f
    ps.ViewObject.ShowClashes = False
    ps.ViewObject.ShowPartTypes = True
    Gui.updateGui()
    faces = [len(s.Faces) for s in ps.Shape.Solids]
    starts = np.cumsum([0] + faces[:-1])
    per_panel = [tuple(round(c, 3) for c in ps.ViewObject.DiffuseColor[k][:3]) for k in starts]
    check(len(ps.ViewObject.DiffuseColor) == sum(faces) and len(set(per_panel)) == 10
          and all(per_panel[f] == per_panel[19 - f] for f in range(20)),
          f"ShowPartTypes: one colour per part type ({len(set(per_panel))} colours)")
    path = os.path.join(out_dir, "panel_types.png")
    save_view(view, path)
    rgb = image_pixels(path).reshape(-1, 3).astype(float)
    hi, lo = rgb.max(axis=1), rgb.min(axis=1)
    coloured = rgb[(hi - lo > 40) & (hi > 60)]
    r, g, b = coloured.T
    # hue in degrees of the coloured pixels; FreeCAD's background is blue-violet (210-270)
    hue = np.degrees(np.arctan2(np.sqrt(3) * (g - b), 2 * r - g - b)) % 360
    bins = np.bincount((hue[(hue < 210) | (hue > 270)] // 30).astype(int), minlength=12)
    check(int((bins > 300).sum()) >= 4,
          f"panel_types: the types' colours are drawn (pixels per 30-degree hue: {list(bins)})")
    ps.ViewObject.ShowPartTypes = False
    ps.ViewObject.ShowClashes = True
    Gui.updateGui()
    check(len(ps.ViewObject.DiffuseColor) == sum(faces),
          "ShowPartTypes off: the clashes' red again, per face")

    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(ps)
    accept_panel(check, "Facet_CutSheets")
    sheets = [obj for obj in doc.Objects if facetwb.is_cutsheets(obj)]
    if not check(len(sheets) == 1, "Facet_CutSheets added one CutSheets object"):
        return
    cut = sheets[0]
    check(cut.isValid(), f"the CutSheets object is valid ({cut.getStatusString()})")
    check(cut.SheetCount > 0 and not cut.Unplaced, f"{cut.SheetCount} sheets, none unplaced")
    ps.ViewObject.Visibility = False
    Gui.Selection.clearSelection()  # selected outlines are drawn in the highlight colour
    view.viewTop()
    view.fitAll()
    Gui.updateGui()
    path = os.path.join(out_dir, "cutsheets.png")
    view.saveImage(path, WIDTH, HEIGHT, "Current")
    pixels = image_pixels(path).astype(int)
    red = int(((pixels[..., 0] > 150) & (pixels[..., 1] < 90) & (pixels[..., 2] < 90)).sum())
    check(red > 500, f"cutsheets: the red cut outlines are drawn ({red} pixels)")
    App.closeDocument(doc.Name)


def check_panel_clashes(check, out_dir):
    """A PanelSet whose square-cut panels overlap across a valley shows them in red
    (ShowClashes), the others in its colour; panel_clashes.png."""
    import FreeCAD as App
    import FreeCADGui as Gui
    import numpy as np

    import facetwb
    from facetwb.objects.panelset import CLASH_COLOR

    sys.path.insert(0, os.path.join(ROOT, "tests", "python"))
    from panel_meshes import folded_grid

    doc = App.newDocument("Clashes")
    source = facetwb.make_polymesh(folded_grid(), label="folded")
    ps = facetwb.make_panelset(source, thickness=200.0, gap=10.0)
    doc.recompute()
    source.ViewObject.Visibility = False
    clashing = set(ps.ClashingPanels)
    check(ps.OverlappingJoints == 2 and clashing == {"P-R01C02", "P-R01C03", "P-R02C02",
                                                     "P-R02C03"},
          f"the valley's four panels clash ({sorted(clashing)})")
    colours = [tuple(round(c, 3) for c in col[:3]) for col in ps.ViewObject.DiffuseColor]
    expected = []
    for part_id, solid in zip(ps.PartIds, ps.Shape.Solids):
        rgb = CLASH_COLOR if part_id in clashing else ps.ViewObject.ShapeColor[:3]
        expected += [tuple(round(c, 3) for c in rgb)] * len(solid.Faces)
    check(colours == expected, "the clashing panels' faces are red, the others the shape colour")
    view = Gui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    Gui.Selection.clearSelection()
    path = os.path.join(out_dir, "panel_clashes.png")
    save_view(view, path)
    pixels = image_pixels(path).astype(int)
    red = int(((pixels[..., 0] > 150) & (pixels[..., 1] < 90) & (pixels[..., 2] < 90)).sum())
    grey = int((np.abs(pixels[..., 2] - pixels[..., 0]) < 20).sum())
    check(red > 5000 and grey > 5000,
          f"panel_clashes: red and grey panels are drawn ({red} and {grey} pixels)")
    ps.ViewObject.ShowClashes = False
    Gui.updateGui()
    check(len(ps.ViewObject.DiffuseColor) == 1, "ShowClashes off: one colour for every face")
    path = os.path.join(out_dir, "panel_clashes_off.png")
    save_view(view, path)
    pixels = image_pixels(path).astype(int)
    red = int(((pixels[..., 0] > 150) & (pixels[..., 1] < 90) & (pixels[..., 2] < 90)).sum())
    check(red < 100, f"panel_clashes: no red panel with ShowClashes off ({red} pixels)")
    # one object per panel: each clashing panel's own object red, the others not
    ps.ViewObject.ShowClashes = True
    ps.OnePerPanel = True
    doc.recompute()
    Gui.updateGui()
    children = list(ps.PanelObjects)
    shades = {c.Label: tuple(round(x, 3) for x in c.ViewObject.ShapeColor[:3]) for c in children}
    red_ids = {label for label, rgb in shades.items()
               if rgb == tuple(round(x, 3) for x in CLASH_COLOR)}
    check(len(children) == 8 and red_ids == clashing,
          f"OnePerPanel: the clashing panels' objects are red ({sorted(red_ids)})")
    ps.ViewObject.ShowClashes = False
    check(not any(tuple(round(x, 3) for x in c.ViewObject.ShapeColor[:3])
                  == tuple(round(x, 3) for x in CLASH_COLOR) for c in children),
          "OnePerPanel: none red with ShowClashes off")
    App.closeDocument(doc.Name)


def accept_panel(check, command, fields=(), shot=None):
    """Run ``command``, check that its task panel opened with a tooltip on every field, set
    ``fields`` ((name, value, choices), ...), save the main window to ``shot`` (a path) if
    given, and press OK. Returns the panel."""
    import FreeCADGui as Gui

    from facetwb.taskpanels import derive_panels, forms

    Gui.runCommand(command)
    Gui.updateGui()
    panel = derive_panels.active
    if not check(panel is not None and bool(Gui.Control.activeDialog()),
                 f"{command} opens its task panel"):
        return None
    missing = [name for name, *_ in panel.FIELDS if not forms.widget(panel.form, name).toolTip()]
    check(not missing, f"{command}: every field has a tooltip (missing: {missing})")
    for name, value, choices in fields:
        forms.set_value(panel.form, name, value, choices)
    if shot:
        import ui_checks

        ui_checks.window_shot(shot)
        check(os.path.getsize(shot) > 10000, f"{command}: window screenshot {shot} written")
    check(panel.accept() and derive_panels.active is None
          and not Gui.Control.activeDialog(), f"{command}: OK applies and closes the panel")
    Gui.updateGui()
    return panel


def _mouse(kind, position, down=True):
    """A stand-in for the SoEventCallback node a 3D view hands to its callbacks."""
    from pivy import coin

    if kind == "button":
        event = coin.SoMouseButtonEvent()
        event.setButton(coin.SoMouseButtonEvent.BUTTON1)
        event.setState(coin.SoButtonEvent.DOWN if down else coin.SoButtonEvent.UP)
    else:
        event = coin.SoLocation2Event()
    event.setPosition(coin.SbVec2s(int(position[0]), int(position[1])))

    class Node:
        handled = False

        def getEvent(self):  # noqa: N802 - Coin's name
            return event

        def setHandled(self):  # noqa: N802
            Node.handled = True

    return Node()


def check_edit_control(check, out_dir):
    """Facet_EditControlMesh: drag a control vertex with the mouse callbacks, the planar
    result follows and stays planar; Done writes the control mesh in one undoable step,
    Cancel leaves it alone."""
    import FreeCAD as App
    import FreeCADGui as Gui
    import numpy as np

    import facet
    import facetwb
    from facetwb import edit_control
    from facetwb.objects.polymesh import get_mesh

    check("Facet_EditControlMesh" in Gui.listCommands(), "command Facet_EditControlMesh is "
          "registered")
    doc = App.newDocument("EditControl")
    mesh = facet.read_mesh(MESH)
    control = facetwb.make_polymesh(mesh)
    result = facetwb.make_planarized(control)
    doc.recompute()
    view = Gui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    Gui.updateGui()
    original = get_mesh(control).vertices.copy()
    solved = get_mesh(result).vertices.copy()
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(result)
    Gui.runCommand("Facet_EditControlMesh")
    session = edit_control.active_session()
    if not check(session is not None and bool(Gui.Control.activeDialog()),
                 "Edit control mesh starts a session with its task panel"):
        App.closeDocument(doc.Name)
        return
    vertex = 40  # the middle of the 8 x 8 hypar
    # the radius is a length in the user's units (it always said "mm"), read back in mm
    radius = session.panel.radius
    check(radius.metaObject().className() == "Gui::QuantitySpinBox",
          "the edit panel's Radius is a quantity box")
    radius.setProperty("rawValue", 2.5 * session.radius)
    check(abs(session.radius - float(radius.property("rawValue"))) < 1e-9,
          f"setting Radius sets the session's radius ({session.radius:g} mm)")
    radius.setProperty("rawValue", 0.4 * session.radius)
    Gui.updateGui()
    # the Radius box without a maximum asked for room for DBL_MAX and pushed the panel
    # past the task pane (285 px in 258 px), its text and boxes cut off at the right
    from PySide import QtGui

    panes = [w for w in Gui.getMainWindow().findChildren(QtGui.QScrollArea)
             if w.isVisible() and w.widget() and w.widget().isAncestorOf(session.panel.form)]
    check(panes and panes[0].widget().width() <= panes[0].viewport().width(),
          f"the Edit control mesh panel fits the task pane "
          f"({panes[0].widget().width() if panes else '?'} px in "
          f"{panes[0].viewport().width() if panes else '?'} px)")
    proxy = result.ViewObject.Proxy
    n_tri = session.triangles.shape[0]
    check(n_tri == 2 * mesh.n_faces and proxy.faces.coordIndex.getNum() == 4 * n_tri,
          f"while editing the result is drawn as {n_tri} triangles (computed once)")
    viewer = view.getViewer()
    cube = viewer.isEnabledNaviCube()
    highlight = view.getSceneGraph().getField("highlightMode")
    preselection = highlight.get().getString()
    x, y = session.screen_position(vertex)
    press = _mouse("button", (x, y), True)
    session._on_button(press)
    check(press.handled and session.live.drag_vertex == vertex,
          f"a press on vertex {vertex}'s marker picks it")
    still, live_tri = proxy.faces.coordIndex.getNum() // 4, \
        session.region_faces.coordIndex.getNum() // 4
    check(live_tri > 0 and still + live_tri == n_tri
          and proxy.planarity_material.diffuseColor.getNum() == still
          and session.region_material.diffuseColor.getNum() == live_tri,
          f"during the drag the live region draws {live_tri} triangles, the object's nodes "
          f"the other {still}, each with its colour")
    check(not viewer.isEnabledNaviCube() and highlight.get().getString() == "OFF",
          "the navigation cube is hidden and preselection off while dragging")
    frames0 = len(session.stats["planarity"])
    current = 0
    for k in range(1, 16):
        session._on_move(_mouse("move", (x, y + 4 * k)))
        session.poll()
        Gui.updateGui()
        current += bool(session.current)
    check(current == 15, f"every redraw during the drag shows the result of the control "
          f"drawn ({current} of 15)")
    worst = max(session.stats["planarity"][frames0:] or [float("nan")])
    check(len(session.stats["planarity"]) - frames0 >= 15 and worst <= result.Tolerance,
          f"every frame of the drag is planar to the tolerance (worst {worst:.2g})")
    region_xyz = np.array([tuple(p.getValue()) for p in session.region_coords.point])
    check(np.allclose(region_xyz, session.live.result.mesh.vertices, atol=1e-3),
          "the live region draws the latest result")
    session._on_button(_mouse("button", (x, y + 60), False))
    check(session.wait(120.0), "the solves finish after the release")
    check(viewer.isEnabledNaviCube() == cube and highlight.get().getString() == preselection
          and preselection != "OFF",
          "the navigation cube and preselection are back after the release")
    check(proxy.faces.coordIndex.getNum() == 4 * n_tri
          and session.region_faces.coordIndex.getNum() == 0
          and proxy.planarity_material.diffuseColor.getNum() == n_tri,
          "after the release the object's nodes draw all the triangles again")
    live = session.live.result
    moved = np.linalg.norm(live.mesh.vertices[vertex] - solved[vertex])
    check(moved > 0.2 * mesh.mean_edge_length(),
          f"the planar result followed the dragged vertex ({moved:.3g} mm)")
    check(live.planarity.max_rel_all <= result.Tolerance,
          f"and stays planar after the release ({live.planarity.max_rel_all:.2g})")
    drawn = np.array([tuple(p.getValue()) for p in result.ViewObject.Proxy.coords.point])
    check(np.allclose(drawn, live.mesh.vertices, atol=1e-3),
          "the 3D view draws the moved result")
    check(np.array_equal(get_mesh(control).vertices, original),
          "the control PolyMesh is untouched while editing")
    path = os.path.join(out_dir, "edit_control.png")
    save_view(view, path)
    check_screenshot(check, path, "edit control", legend=True)
    # Done while a solve still runs: its result, arriving while the session closes, is
    # neither drawn nor told to the panel, whose widgets Qt may have deleted already (a
    # run lost the edit so: "Internal C++ object (QLabel) already deleted")
    told = []

    def closed_panel(_session):
        told.append(True)
        raise RuntimeError("Internal C++ object (PySide2.QtWidgets.QLabel) already deleted.")

    session.listeners.append(closed_panel)
    session._start(session.live.settle)  # a solve that does not stop for Done
    check(edit_control.finish(True) and not told, "Done writes the moved control vertices")
    after = get_mesh(control).vertices
    check(np.allclose(after, session.live.control) and not np.allclose(after, original),
          "the control PolyMesh holds the moved vertices")
    check(result.isValid() and result.PlanarityMaxRel <= result.Tolerance,
          "the Planarized object is recomputed from them, planar")
    check(edit_control.active_session() is None, "the session has ended")
    check(proxy.faces.coordIndex.getNum() == len(mesh.face_vertices) + mesh.n_faces,
          "after the edit the object draws its panels as polygons again")
    doc.undo()
    doc.recompute()
    check(np.array_equal(get_mesh(control).vertices, original), "undo restores the control mesh")
    # Cancel: nothing is written.
    session = edit_control.start(result)
    x, y = session.screen_position(vertex)
    session._on_button(_mouse("button", (x, y), True))
    session._on_move(_mouse("move", (x, y + 30)))
    session._on_button(_mouse("button", (x, y + 30), False))
    session.wait(120.0)
    edit_control.finish(False)
    check(np.array_equal(get_mesh(control).vertices, original)
          and edit_control.active_session() is None, "Cancel leaves the control mesh alone")
    # a parameter changed during a session that moved nothing: the session solved it live,
    # and the stored result kept the old one, Touched, once the session ended
    tolerance = result.Tolerance
    session = edit_control.start(result)
    result.Tolerance = tolerance * 1e-3
    session.wait(120.0)
    edit_control.finish(False)
    wait_for_live_resolve(result)
    check("Touched" not in result.State and result.PlanarityMaxRel <= tolerance * 1e-3,
          f"a Tolerance set during a session is solved when it ends "
          f"({result.PlanarityMaxRel:.2g}, {result.State})")
    result.Tolerance = tolerance
    wait_for_live_resolve(result)
    check_live_parameters(check, result)
    App.closeDocument(doc.Name)


def check_edit_linked_control(check):
    """Edit control mesh on the tutorial's facade (a SurfaceMesh on a B-spline surface,
    planarized), as the tutorial says: it was refused with 'Facade quad mesh is rebuilt from
    Facade on recompute'. The panel says what OK does; OK puts the moved vertices in a new
    PolyMesh which the result follows; the surface and the SurfaceMesh are unchanged; undo
    takes it all back."""
    import FreeCAD as App
    import FreeCADGui as Gui
    import numpy as np

    import facetwb
    import ui_checks
    from facetwb import edit_control
    from facetwb.objects.polymesh import get_mesh

    doc = App.newDocument("EditLinked")
    surface = ui_checks.facade_surface(doc)
    doc.recompute()
    control = facetwb.make_surface_mesh(surface, "quad", count_u=12, count_v=6)
    result = facetwb.make_planarized(control)
    doc.recompute()
    area, points = surface.Shape.Area, get_mesh(control).vertices.copy()
    view = Gui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(result)
    Gui.runCommand("Facet_EditControlMesh")
    session = edit_control.active_session()
    if not check(session is not None, "Edit control mesh starts on the tutorial's facade"):
        App.closeDocument(doc.Name)
        return
    note = getattr(session.panel, "linked", None)
    check(note is not None and "OK puts the moved vertices in a new polygon mesh"
          in note.text(), f"the panel says what OK does ({note.text() if note else None})")
    x, y = session.screen_position(45)
    session._on_button(_mouse("button", (x, y), True))
    for k in range(1, 6):
        session._on_move(_mouse("move", (x, y + 8 * k)))
        session.poll()
    session._on_button(_mouse("button", (x, y + 40), False))
    session.wait(120.0)
    names = [o.Name for o in doc.Objects]
    check(edit_control.finish(True), "OK keeps the edit")
    edited = result.Source
    check(edited is not control and facetwb.is_polymesh(edited) and edited.Source is None
          and edited.Label == f"{control.Label} edited" and not edited.ViewObject.Visibility,
          f"the moved vertices are in a new, hidden PolyMesh ({edited.Label})")
    check(not np.array_equal(get_mesh(edited).vertices, points)
          and np.array_equal(get_mesh(control).vertices, points)
          and abs(surface.Shape.Area - area) < 1e-9 * area,
          "the SurfaceMesh and the surface are unchanged")
    check(result.isValid() and result.PlanarityMaxRel <= result.Tolerance,
          f"the result follows the edited mesh, planar ({result.getStatusString()})")
    doc.undo()
    doc.recompute()
    check(result.Source is control and [o.Name for o in doc.Objects] == names,
          "undo puts the SurfaceMesh back as the result's source, the new mesh gone")
    App.closeDocument(doc.Name)


def check_edit_region(check):
    """During a drag of a larger facade only the live region is drawn from changing
    coordinates: the Planarized object's own nodes keep the positions they had when the
    drag began (Coin keeps their caches) and take the result again at the release."""
    import FreeCAD as App
    import FreeCADGui as Gui
    import numpy as np

    import facet
    import facetwb
    from facetwb import edit_control

    n = 24
    faces = [[j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1,
              (j + 1) * (n + 1) + i] for j in range(n) for i in range(n)]
    i, j = np.meshgrid(np.arange(n + 1.0), np.arange(n + 1.0), indexing="xy")
    x, y = i.ravel(), j.ravel()
    z = 0.3 * np.sin(0.4 * x) * np.cos(0.3 * y)
    mesh = facet.PolyMesh.from_faces(np.stack([x, y, z], axis=1) * 1000.0, faces)
    doc = App.newDocument("EditRegion")
    result = facetwb.make_planarized(facetwb.make_polymesh(mesh))
    doc.recompute()
    view = Gui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    Gui.updateGui()
    session = edit_control.start(result, threaded=False, panel=False)
    proxy = result.ViewObject.Proxy
    vertex = 12 * (n + 1) + 12

    def points(field):
        return np.array([tuple(p.getValue()) for p in field])

    before = points(proxy.coords.point)
    px, py = session.screen_position(vertex)
    session._on_button(_mouse("button", (px, py), True))
    frames = []  # (stop reason, iterations, frame count): printed, for a failure's diagnosis
    for k in range(1, 6):
        session._on_move(_mouse("move", (px, py + 5 * k)))
        Gui.updateGui()
        frames.append((session.live.result.stop_reason, session.live.result.iterations,
                       session.live.frames))
    live = session.live.result.mesh.vertices
    still = proxy.faces.coordIndex.getNum() // 4
    region = session.region_faces.coordIndex.getNum() // 4
    check(session.live.drag_vertex == vertex and still > region > 0,
          f"a drag of a {n * n}-panel facade redraws {region} triangles from changing "
          f"coordinates, {still} from still ones")
    moved = np.linalg.norm(live - before, axis=1) > 0.05  # mm; Coin holds float32
    outside = int(np.count_nonzero(moved & ~session.region_vertices))
    print(f"  (edit region: {int(moved.sum())} moved, {outside} outside the region, object "
          f"coordinates still: {np.array_equal(points(proxy.coords.point), before)}, "
          f"frames {frames})", file=sys.__stdout__)
    check(moved.any() and np.array_equal(points(proxy.coords.point), before)
          and np.allclose(points(session.region_coords.point), live, atol=1e-3)
          and np.all(session.region_vertices[moved]),
          f"the object's coordinates stay still during the drag; the {int(moved.sum())} "
          "vertices that moved are all in the live region, drawn from its coordinates")
    session._on_button(_mouse("button", (px, py + 25), False))
    session.wait(60.0)
    check(np.allclose(points(proxy.coords.point), session.live.result.mesh.vertices,
                      atol=1e-3) and proxy.faces.coordIndex.getNum() == 4 * 2 * n * n,
          "at the release the object's nodes draw the whole moved result again")
    edit_control.finish(False)
    App.closeDocument(doc.Name)


def wait_for_live_resolve(obj, seconds=120.0):
    """Process events until the live re-solve of ``obj`` a parameter change scheduled
    (facetwb.live_parameters) has run, or ``seconds`` passed."""
    import time

    import FreeCADGui as Gui

    from facetwb import live_parameters

    end = time.monotonic() + seconds
    while ("Touched" in obj.State or live_parameters.pending()) and time.monotonic() < end:
        Gui.updateGui()
        time.sleep(0.02)


def check_live_parameters(check, result):
    """A solver parameter changed in the property editor re-solves the object by itself,
    once for a burst of changes."""
    import numpy as np

    from facetwb import live_parameters
    from facetwb.objects.polymesh import get_mesh

    control = get_mesh(result.Source).vertices
    corner = 0
    before = get_mesh(result).vertices[corner].copy()
    result.Tolerance = 1e-7
    result.Boundary = "fixed"  # boundary vertices stay on the control mesh
    check(live_parameters.pending() == 1, "two quick parameter changes schedule one re-solve")
    wait_for_live_resolve(result)
    after = get_mesh(result).vertices[corner]
    check("Touched" not in result.State and result.isValid(),
          "the Planarized object re-solved without a recompute command")
    check(np.allclose(after, control[corner]) and not np.allclose(before, control[corner]),
          "with the new parameter: its boundary corner sits on the control mesh")


def check_import_command(check):
    """Facet_ImportMesh with the file dialog answered by the test."""
    import FreeCAD as App
    import FreeCADGui as Gui
    from PySide import QtGui

    import facetwb

    doc = App.newDocument("ImportCommand")
    dialog = QtGui.QFileDialog.getOpenFileName
    try:
        for name, count in (("panels.off", 1), ("bad_index.off", 1)):
            path = os.path.join(ROOT, "tests", "data", name)
            QtGui.QFileDialog.getOpenFileName = staticmethod(lambda *args, **kw: (path, ""))
            Gui.runCommand("Facet_ImportMesh")
            meshes = [obj for obj in doc.Objects if facetwb.is_polymesh(obj)]
            check(len(meshes) == count, f"Facet_ImportMesh of {name}: {len(meshes)} PolyMesh")
    finally:
        QtGui.QFileDialog.getOpenFileName = dialog
    check(meshes and meshes[0].FaceCount == 7, "the imported mesh has its 7 faces")
    App.closeDocument(doc.Name)
    check_import_units(check)
    check_import_units_imperial(check)
    check_import_progress(check)
    check_new_polymesh_drawn_once(check)
    check_stored_mesh_drawn_once(check)


def check_import_progress(check):
    """An import shows a progress dialog with Cancel (a 1M-face OBJ read for 14 s with
    none); Cancel in Facet_ImportMesh, while reading or after the mesh was added, leaves
    the document as it was, nothing to undo, no dialog left open and no mesh kept."""
    import FreeCAD as App
    import FreeCADGui as Gui
    from PySide import QtGui

    from facetwb import importer, progress
    from facetwb.commands import import_mesh

    path = os.path.join(ROOT, "tests", "data", "panels.off")
    doc = App.newDocument("ImportProgress")
    closed = []
    close = progress._Reporter.close

    def record(reporter):
        closed.append((reporter.dialog is not None, reporter.texts[0], reporter.calls))
        close(reporter)

    dialogs = QtGui.QFileDialog.getOpenFileName, import_mesh.ask_units
    progress._Reporter.close = record
    try:
        obj = importer.insert(path, doc.Name)
        check(obj is not None and closed and closed[0][:2] == (True, "Importing panels.off ...")
              and closed[0][2] >= 5,
              f"File > Import shows a progress dialog, Importing panels.off ... ({closed})")
        doc.removeObject(obj.Name)
        doc.recompute()
        with progress.reporting("reading") as reading:
            importer.read_kept(path)
        importer.forget_kept()
        QtGui.QFileDialog.getOpenFileName = staticmethod(lambda *args, **kw: (path, ""))
        import_mesh.ask_units = lambda filename, edge, likely: "mm"  # (panels.off: in m)
        importer.SHOW_DIALOGS = True
        # Cancel at the first call (the command's reading) and at the last of its insert
        # (the PolyMesh added and recomputed; the insert takes the mesh read)
        added = closed[0][2] - reading.calls
        for cancel_at in (1, added):
            del closed[:]
            undo = list(doc.UndoNames)
            progress.cancel_after(cancel_at)
            try:
                Gui.runCommand("Facet_ImportMesh")
            finally:
                progress.cancel_after(0)
            Gui.updateGui()
            left = [w for w in QtGui.QApplication.topLevelWidgets()
                    if isinstance(w, (QtGui.QProgressDialog, QtGui.QMessageBox))
                    and w.isVisible()]
            check(not doc.Objects and list(doc.UndoNames) == undo and not left
                  and not importer._KEPT and closed and all(c[0] for c in closed),
                  f"Cancel at progress call {cancel_at} of Facet_ImportMesh changes nothing "
                  f"({[o.Name for o in doc.Objects]}, {doc.UndoNames}, {left}, {closed})")
        # no document open: the one the command made for the mesh is closed again (an
        # empty "Unnamed" was left)
        class NoDocumentOpen:  # (the command's App, the test's documents left open)
            ActiveDocument = None

            def __getattr__(self, name):
                return getattr(App, name)

        documents = set(App.listDocuments())
        progress.cancel_after(added)
        import_mesh.App = NoDocumentOpen()
        try:
            Gui.runCommand("Facet_ImportMesh")
        finally:
            import_mesh.App = App
            progress.cancel_after(0)
        Gui.updateGui()
        check(set(App.listDocuments()) == documents,
              f"Cancel in Facet_ImportMesh with no document open leaves none open "
              f"({sorted(set(App.listDocuments()) - documents)})")
    finally:
        progress._Reporter.close = close
        QtGui.QFileDialog.getOpenFileName, import_mesh.ask_units = dialogs
        importer.SHOW_DIALOGS = False
    App.closeDocument(doc.Name)


def check_new_polymesh_drawn_once(check):
    """A new PolyMesh is drawn once: FreeCAD's updateData of every property after attach
    drew it three more times (a 1M-face import: 7.8 s, the dialog frozen)."""
    import FreeCAD as App

    import facet
    import facetwb
    from facetwb.viewproviders import view_polymesh

    doc = App.newDocument("DrawnOnce")
    path = os.path.join(ROOT, "tests", "data", "panels.off")
    redraws = []
    redraw = view_polymesh.ViewProviderPolyMesh.redraw_mesh
    view_polymesh.ViewProviderPolyMesh.redraw_mesh = \
        lambda self, obj: (redraws.append(obj.Name), redraw(self, obj))[1]
    try:
        obj = facetwb.make_polymesh(facet.read_mesh(path), doc=doc)
    finally:
        view_polymesh.ViewProviderPolyMesh.redraw_mesh = redraw
    check(redraws == [obj.Name] and obj.ViewObject.Proxy.face_count == 7
          and obj.ViewObject.Proxy.coords.point.getNum() == obj.VertexCount,
          f"a new PolyMesh is drawn once, whole ({redraws})")
    App.closeDocument(doc.Name)


def check_stored_mesh_drawn_once(check):
    """set_mesh into a drawn PolyMesh (what a Planarized recompute does with its result) draws
    it once, whole: FreeCAD's updateData of each of its three mesh properties drew it three
    times (a 1M-face write-back: 3 x 1 s). The drawing holds the stored arrays (Coin's
    float32 of the coordinates, the faces' corners)."""
    import FreeCAD as App
    import numpy as np

    import facet
    import facetwb
    from facetwb.objects.polymesh import set_mesh
    from facetwb.viewproviders import view_polymesh

    doc = App.newDocument("StoredOnce")
    mesh = facet.read_mesh(os.path.join(ROOT, "tests", "data", "panels.off"))
    other = facet.read_mesh(os.path.join(ROOT, "tests", "data", "hypar.obj"))
    obj = facetwb.make_polymesh(mesh, doc=doc)
    proxy = obj.ViewObject.Proxy
    redraws = []
    redraw = view_polymesh.ViewProviderPolyMesh.redraw_mesh
    view_polymesh.ViewProviderPolyMesh.redraw_mesh = \
        lambda self, obj: (redraws.append(obj.Name), redraw(self, obj))[1]
    drawn = []
    try:
        for stored in (mesh.with_vertices(mesh.vertices + 0.1), other):  # a re-solve; new
            set_mesh(obj, stored)
            point = proxy.coords.point
            xyz = np.array([point[i].getValue() for i in range(point.getNum())],
                           dtype=np.float32)
            index = [proxy.faces.coordIndex[i] for i in range(proxy.faces.coordIndex.getNum())]
            corners = [v for face in stored.faces() for v in list(face) + [-1]]
            drawn.append(len(redraws) == 1 and proxy.face_count == stored.n_faces
                         and np.array_equal(xyz.view(np.uint32),
                                            stored.vertices.astype(np.float32).view(np.uint32))
                         and index == corners)
            del redraws[:]
    finally:
        view_polymesh.ViewProviderPolyMesh.redraw_mesh = redraw
    check(drawn == [True, True], f"set_mesh draws a PolyMesh once, what it stored ({drawn})")
    App.closeDocument(doc.Name)


def check_import_units(check):
    """Facet_ImportMesh of a facade in metres (edges 0.566 of its units): read as millimetres
    it came in a thousand times too small, silently. The command asks for the units,
    metres offered first, and scales it; Cancel there imports nothing."""
    import tempfile

    import FreeCAD as App
    import FreeCADGui as Gui
    import numpy as np
    from PySide import QtGui

    import facet
    import facetwb
    from facet.gridding import sample_surface
    from facetwb import importer

    doc = App.newDocument("ImportUnits")
    path = os.path.join(tempfile.mkdtemp(prefix="facet-gui-units-"), "facade_m.obj")
    facet.write_mesh(sample_surface(lambda u, v: np.column_stack([u, 0.1 * u * v, v]),
                                    (0.0, 12.0), (0.0, 6.0), "quad", 24, 12), path)
    asked = []

    def answer(choice):
        def get_item(parent, title, text, items, current, editable):
            asked.append((text, items[current]))
            return (items[[i.endswith("(m)") for i in items].index(True)], True) \
                if choice else (items[current], False)
        return staticmethod(get_item)

    dialogs = QtGui.QFileDialog.getOpenFileName, QtGui.QInputDialog.getItem
    importer.SHOW_DIALOGS = True
    try:
        QtGui.QFileDialog.getOpenFileName = staticmethod(lambda *args, **kw: (path, ""))
        for choice in (False, True):
            QtGui.QInputDialog.getItem = answer(choice)
            Gui.runCommand("Facet_ImportMesh")
    finally:
        QtGui.QFileDialog.getOpenFileName, QtGui.QInputDialog.getItem = dialogs
        importer.SHOW_DIALOGS = False
    meshes = [obj for obj in doc.Objects if facetwb.is_polymesh(obj)]
    check(len(asked) == 2 and "edges are 0.566 of its units long on average" in asked[0][0]
          and asked[0][1] == "metres (m)",
          f"Facet_ImportMesh of a facade in metres asks for its units, metres first ({asked})")
    width = max(p.x for p in meshes[0].Points) if meshes else 0
    check(len(meshes) == 1 and abs(width - 12000.0) < 1e-6,
          f"Cancel imports nothing; metres chosen, the facade is 12 m wide ({width} mm)")
    App.closeDocument(doc.Name)


def check_import_units_imperial(check):
    """FreeCAD set to inches (Imperial decimal): Facet_ImportMesh of a 40 ft facade in
    inches (edges of 35 units, a facade's in millimetres too) read it as millimetres,
    25.4 times too small, and asked nothing. It asks now, inches offered first; the report
    view gives the size in inches. The schema is put back."""
    import tempfile

    import FreeCAD as App
    import FreeCADGui as Gui
    from PySide import QtGui

    import facet
    import facetwb
    from facetwb import importer

    doc = App.newDocument("ImportInches")
    path = os.path.join(tempfile.mkdtemp(prefix="facet-gui-inches-"), "facade_in.obj")
    grid = [(40.0 * i, 30.0 * j, 0.0) for j in range(9) for i in range(13)]
    faces = [[13 * j + i, 13 * j + i + 1, 13 * j + i + 14, 13 * j + i + 13]
             for j in range(8) for i in range(12)]
    facet.write_mesh(facet.PolyMesh.from_faces(grid, faces), path)
    asked = []

    def get_item(parent, title, text, items, current, editable):
        asked.append((text, items[current]))
        return items[current], True

    dialogs = QtGui.QFileDialog.getOpenFileName, QtGui.QInputDialog.getItem
    schema = App.Units.getSchema()
    importer.SHOW_DIALOGS = True
    try:
        App.Units.setSchema(3)
        QtGui.QFileDialog.getOpenFileName = staticmethod(lambda *args, **kw: (path, ""))
        QtGui.QInputDialog.getItem = staticmethod(get_item)
        Gui.runCommand("Facet_ImportMesh")
        Gui.updateGui()
        said = report_view_text()
    finally:
        QtGui.QFileDialog.getOpenFileName, QtGui.QInputDialog.getItem = dialogs
        importer.SHOW_DIALOGS = False
        App.Units.setSchema(schema)
    meshes = [obj for obj in doc.Objects if facetwb.is_polymesh(obj)]
    check(len(asked) == 1 and asked[0][1] == "inches (in)" and "inches or feet" in asked[0][0],
          f"Facet_ImportMesh under an imperial schema asks the units, inches first ({asked})")
    width = max(p.x for p in meshes[0].Points) if meshes else 0
    check(len(meshes) == 1 and abs(width - 480.0 * 25.4) < 1e-6
          and "480 x 240 x 0 in, its numbers read as inches" in said,
          f"the facade is 480 in wide ({width} mm), said in inches")
    App.closeDocument(doc.Name)


def bounding_box(node):
    """(min, max) corners of what Coin's SoGetBoundingBoxAction (used by Fit all) sees."""
    import numpy as np
    from pivy import coin

    action = coin.SoGetBoundingBoxAction(coin.SbViewportRegion(WIDTH, HEIGHT))
    action.apply(node)
    box = action.getBoundingBox()
    return np.array(box.getMin().getValue()), np.array(box.getMax().getValue())

def check_edit_planarized(check, out_dir):
    """Double-click on a Planarized object: its Planarize panel; a changed field re-solves the
    result live (no Recompute pressed); Cancel puts values and result back; OK is one undo
    step."""
    import FreeCAD as App
    import FreeCADGui as Gui
    import numpy as np

    import facet
    import facetwb
    from facetwb.objects.polymesh import get_mesh
    from facetwb.objects.planarized import METHODS
    from facetwb.taskpanels import edit_panels, forms

    doc = App.newDocument("EditPlanarized")
    control = facetwb.make_polymesh(facet.read_mesh(MESH), label="Control mesh")
    result = facetwb.make_planarized(control, tolerance=1e-3)  # "Control mesh planarized"
    panels = facetwb.make_panelset(result, thickness=0.5, gap=0.0)
    panels.Tolerance = 1e-2  # the result is planar to 1e-3 only
    doc.recompute()
    panels.ViewObject.Visibility = False
    Gui.ActiveDocument.ActiveView.fitAll()
    before = get_mesh(result).vertices.copy()
    loose = result.PlanarityMaxRel
    vobj = result.ViewObject

    vobj.Proxy.doubleClicked(vobj)  # what a double-click in the tree calls
    panel = edit_panels.active
    if not check(panel is not None and bool(Gui.Control.activeDialog()),
                 "a double-click on a Planarized opens its Planarize panel"):
        App.closeDocument(doc.Name)
        return
    check(forms.get_value(panel.form, "Tolerance", None, True) == 1e-3
          and forms.get_value(panel.form, "Method", METHODS) == result.Method == "auto",
          "the panel shows the object's parameters")
    Gui.updateGui()
    # the label in the title ("Planarize: Control mesh planarized") widened the panel past
    # the task pane: its fields, spin buttons and the note were cut off at the right
    from PySide import QtGui

    panes = [w for w in Gui.getMainWindow().findChildren(QtGui.QScrollArea)
             if w.isVisible() and w.widget() and w.widget().isAncestorOf(panel.form)]
    check(panes and panes[0].widget().width() <= panes[0].viewport().width()
          and result.Label in forms.widget(panel.form, "note").text(),
          f"the edit panel of {result.Label!r} fits the task pane and names it "
          f"({panes[0].widget().width() if panes else '?'} px in "
          f"{panes[0].viewport().width() if panes else '?'} px)")
    field = forms.widget(panel.form, "Tolerance")
    field.setText("1e-09")
    field.editingFinished.emit()
    check(result.Tolerance == 1e-9, "a changed field is set on the object at once")
    wait_for_live_resolve(result)
    tight = result.PlanarityMaxRel
    check(not np.array_equal(get_mesh(result).vertices, before) and tight <= 1e-9 < loose,
          f"the result follows the panel without Recompute (planarity {loose:.2g} -> {tight:.2g})")
    import ui_checks

    shot = os.path.join(out_dir, "edit_planarized.png")
    ui_checks.window_shot(shot)
    check(os.path.getsize(shot) > 10000, f"edit panel screenshot {shot} written")
    check("Touched" in panels.State, "the live re-solve marks the panels made from it")
    # Collapse short edges committed the panel's transaction, and Edit control mesh closed
    # the panel without its Cancel: either way Cancel no longer took the changes back
    from facetwb.commands.cleanup import CommandCleanup
    from facetwb.commands.edit_control import CommandEditControlMesh
    from facetwb.commands.import_mesh import CommandImportMesh
    from facetwb.commands.to_polymesh import CommandToPolyMesh

    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(result)
    check(not CommandCleanup().IsActive() and not CommandEditControlMesh().IsActive(),
          "while the panel is open, Collapse short edges and Edit control mesh are inactive")
    box = doc.addObject("Part::Box", "Box")
    box.ViewObject.Visibility = False
    Gui.Selection.addSelection(box)
    check(not CommandToPolyMesh().IsActive() and not CommandImportMesh().IsActive(),
          "and so are To polygon mesh and Import polygon mesh")
    Gui.Selection.clearSelection()
    panel.reject()
    wait_for_live_resolve(result)
    check(edit_panels.active is None and not Gui.Control.activeDialog()
          and result.Tolerance == 1e-3 and np.array_equal(get_mesh(result).vertices, before)
          and result.PlanarityMaxRel == loose,
          "Cancel puts the previous parameters and the previous result back")
    check("Touched" not in panels.State,
          f"after Cancel the panels made from the result are up to date ({panels.State})")
    vobj.Proxy.doubleClicked(vobj)
    panel = edit_panels.active
    forms.set_value(panel.form, "MaxIterations", 7)
    field = forms.widget(panel.form, "Tolerance")
    field.setText("1e-08")
    said = []
    keep, forms.report_summary = forms.report_summary, lambda obj, text: said.append(text)
    try:
        accepted = panel.accept()
    finally:
        forms.report_summary = keep
    check(accepted and result.Tolerance == 1e-8 and result.MaxIterations == 7
          and "Touched" not in result.State and f"Edit {result.Label}" in doc.UndoNames,
          "OK keeps the changes, recomputed, as one undo step")
    check(len(said) == 1 and said[0].startswith(f"{result.Source.Label} planarized:")
          and f"{result.Iterations} iterations" in said[0],
          f"OK says the result in the report view ({said[:1]})")
    doc.undo()
    wait_for_live_resolve(result)
    check(result.Tolerance == 1e-3 and result.MaxIterations == 0,
          "undo restores the parameters of before the panel")
    # a value above the old spin box's 100,000 is kept by OK, not clamped
    result.MaxIterations = 250000
    wait_for_live_resolve(result)
    vobj.Proxy.doubleClicked(vobj)
    check(edit_panels.active.accept() and result.MaxIterations == 250000,
          f"OK keeps MaxIterations 250000 (now {result.MaxIterations})")
    App.closeDocument(doc.Name)


def view_widget_point(view, position):
    """``(GL widget, QPoint)`` of ``position`` (pixels, Coin's convention: origin bottom
    left) in the 3D view: the widget's own, device independent, pixels."""
    from PySide import QtCore

    widget = view.graphicsView().viewport()  # this view's GL widget, not another one's
    ratio = float(widget.devicePixelRatioF())
    height = view.getSize()[1]
    return widget, QtCore.QPoint(int(round(position[0] / ratio)),
                                 int(round((height - 1 - position[1]) / ratio)))


def hover(view, position):
    """The mouse moved (no button) to ``position`` (pixels, origin bottom left) in the 3D
    view, through Qt: FreeCAD preselects what is under it."""
    from PySide import QtCore, QtGui

    widget, pos = view_widget_point(view, position)
    event = QtGui.QMouseEvent(QtCore.QEvent.MouseMove, pos, widget.mapToGlobal(pos),
                              QtCore.Qt.NoButton, QtCore.Qt.NoButton, QtCore.Qt.NoModifier)
    QtGui.QApplication.sendEvent(widget, event)
    settle(3)


def click(view, position, ctrl=False):
    """A left click (press and release) of the mouse at ``position`` (pixels, Coin's
    convention: origin bottom left) in the 3D view's GL widget, through Qt: FreeCAD's own
    event path selects what is under it (Ctrl: adds it)."""
    from PySide import QtCore, QtGui
    import FreeCADGui as Gui

    widget, pos = view_widget_point(view, position)
    modifiers = QtCore.Qt.ControlModifier if ctrl else QtCore.Qt.NoModifier
    left = QtCore.Qt.LeftButton
    for kind, buttons in ((QtCore.QEvent.MouseButtonPress, left),
                          (QtCore.QEvent.MouseButtonRelease, QtCore.Qt.NoButton)):
        event = QtGui.QMouseEvent(kind, pos, widget.mapToGlobal(pos), left, buttons, modifiers)
        QtGui.QApplication.sendEvent(widget, event)
    Gui.updateGui()


def check_hold_vertices(check, out_dir):
    """The Planarize edit panel's Held vertices: a click near a corner of the planarized mesh
    in the 3D view selects "VertexN" (N: the control mesh's vertex index), Ctrl+click adds
    one; Hold selected puts them in FixedVertices and the live re-solve keeps them at the
    control mesh's points; magenta markers show them; a panel selected instead gets a
    message; Free selected, Cancel, OK and undo."""
    import FreeCAD as App
    import FreeCADGui as Gui
    import numpy as np

    import facet
    import facetwb
    from facetwb.objects.polymesh import get_mesh
    from facetwb.taskpanels import edit_panels
    from facetwb.viewproviders.view_planarized import HELD_COLOR

    doc = App.newDocument("HoldVertices")
    mesh = facet.read_mesh(MESH)
    control = facetwb.make_polymesh(mesh, label="Control mesh")
    result = facetwb.make_planarized(control, tolerance=1e-3)
    doc.recompute()
    before = get_mesh(result).vertices.copy()
    # the panel first: it narrows the 3D view, and moves what is drawn on the screen
    result.ViewObject.Proxy.doubleClicked(result.ViewObject)
    panel = edit_panels.active
    view = Gui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    Gui.updateGui()
    from facetwb.viewproviders.view_polymesh import VERTEX_PICK_PIXELS

    # a pick 3 pixels off a corner names that vertex; a panel's middle names the panel
    named, wrong = [], []
    for vertex, point in enumerate(before):
        x, y = view.getPointOnScreen(App.Vector(*point))
        info = view.getObjectInfo((int(x) + 3, int(y) + 3))
        component = info.get("Component") if info and info.get("Object") == result.Name \
            else None
        if component == f"Vertex{vertex}":
            named.append((vertex, (int(x), int(y))))
        elif component and component.startswith("Vertex"):
            # a hidden corner's pick lands on a panel in front: one of its corners if near
            other = view.getPointOnScreen(App.Vector(*before[int(component[6:])]))
            if np.hypot(other[0] - x - 3, other[1] - y - 3) > VERTEX_PICK_PIXELS + 1:
                wrong.append((vertex, component))
    check(len(named) >= before.shape[0] // 2 and not wrong,
          f"a pick near a corner of the planarized mesh is that vertex, VertexN "
          f"({len(named)} of {before.shape[0]} named, hidden ones aside; wrong: {wrong[:3]})")
    centre = before[mesh.face_vertices[mesh.face_start[27]:mesh.face_start[28]]].mean(axis=0)
    x, y = view.getPointOnScreen(App.Vector(*centre))
    info = view.getObjectInfo((int(x), int(y))) or {}
    check(str(info.get("Component", "")).startswith("Face"),
          f"a pick in a panel's middle is the panel, FaceN ({info.get('Component')!r})")
    if len(named) < 3:
        panel.reject()
        App.closeDocument(doc.Name)
        return
    Gui.Selection.clearSelection()
    (a, at_a), (b, at_b), (c, _) = named[0], named[len(named) // 2], named[-1]
    click(view, (at_a[0] + 3, at_a[1] + 3))  # where the pick named them
    click(view, (at_b[0] + 3, at_b[1] + 3), ctrl=True)
    picked = [(s.ObjectName, tuple(s.SubElementNames)) for s in Gui.Selection.getSelectionEx()]
    check(picked == [(result.Name, (f"Vertex{a}", f"Vertex{b}"))]
          and panel.selected_label.text() == "2 vertices selected"
          and result.ViewObject.Proxy.selected.vertices == sorted([a, b]),
          f"a click near a corner, then Ctrl+click near another, select both vertices; the "
          f"panel counts them and marks them ({picked}, {panel.selected_label.text()!r})")
    path = os.path.join(out_dir, "hold_selected.png")
    view.saveImage(path, WIDTH, HEIGHT, "Current")
    magenta_before = int(near(image_pixels(path), HELD_COLOR, 30).sum())
    panel.buttons["HoldSelected"].click()
    wait_for_live_resolve(result)
    after = get_mesh(result).vertices
    held = sorted([a, b])
    check(list(result.FixedVertices) == held and panel.held_label.text() == "2 vertices held"
          and "Touched" not in result.State and result.PlanarityMaxRel <= 1e-3
          and np.array_equal(after[held], mesh.vertices[held])
          and not np.array_equal(before[held], mesh.vertices[held]),
          f"Hold selected: FixedVertices {list(result.FixedVertices)}, and the re-solve keeps "
          f"them at the control mesh's points (they had moved "
          f"{np.abs(before[held] - mesh.vertices[held]).max():.3g} mm to planarize), planarity "
          f"{result.PlanarityMaxRel:.2g}")
    Gui.Selection.clearSelection()
    path = os.path.join(out_dir, "hold_vertices.png")
    view.saveImage(path, WIDTH, HEIGHT, "Current")
    magenta = int(near(image_pixels(path), HELD_COLOR, 30).sum())
    check(magenta_before == 0 and magenta >= 2 * 80,
          f"the held vertices show as magenta markers in {path} ({magenta} pixels, "
          f"{magenta_before} before)")
    Gui.Selection.addSelection(doc.Name, result.Name, "Face3")
    check(not panel.hold_selected() and list(result.FixedVertices) == held
          and "Face3" in panel.held_message.text()
          and "is a face, not a vertex" in panel.held_message.text(),
          f"a panel selected: Hold says so and holds nothing ({panel.held_message.text()!r})")
    Gui.Selection.clearSelection()
    x, y = view.getPointOnScreen(App.Vector(*after[a]))  # held: it moved back
    click(view, (int(x) + 3, int(y) + 3))
    panel.buttons["FreeSelected"].click()
    check(list(result.FixedVertices) == [b] and panel.held_label.text() == "1 vertex held",
          f"Free selected lets it move again ({list(result.FixedVertices)})")
    Gui.Selection.clearSelection()
    panel.reject()
    wait_for_live_resolve(result)
    check(list(result.FixedVertices) == [] and np.array_equal(get_mesh(result).vertices, before)
          and result.ViewObject.Proxy.held.vertices == [],
          "Cancel frees them again and puts the previous result back")
    result.ViewObject.Proxy.doubleClicked(result.ViewObject)
    panel = edit_panels.active
    Gui.Selection.addSelection(doc.Name, result.Name, f"Vertex{c}")
    Gui.Selection.addSelection(doc.Name, control.Name, f"Vertex{a}")
    panel.buttons["HoldSelected"].click()
    Gui.Selection.clearSelection()
    check(panel.accept() and list(result.FixedVertices) == sorted([a, c])
          and "Touched" not in result.State
          and np.array_equal(get_mesh(result).vertices[[a, c]], mesh.vertices[[a, c]]),
          "vertices picked on the result and on its control mesh, held, kept by OK")
    doc.undo()
    wait_for_live_resolve(result)
    check(list(result.FixedVertices) == [] and result.ViewObject.Proxy.held.vertices == [],
          "undo frees them, the markers go")
    App.closeDocument(doc.Name)


def check_recompute_in_edit_then_cancel(check, out_dir):
    """Recompute pressed while the Planarize edit panel is open rebuilds the panels and
    rewrites the cut sheets' files from the panel's values; Cancel then rebuilds them from
    the result it puts back: the files are those of before the panel, not stale ones."""
    import hashlib

    import FreeCAD as App

    import facet
    import facetwb
    from facetwb.taskpanels import edit_panels

    doc = App.newDocument("RecomputeThenCancel")
    files = os.path.join(out_dir, "recompute_then_cancel")
    control = facetwb.make_polymesh(facet.read_mesh(MESH), label="Control mesh")
    result = facetwb.make_planarized(control, tolerance=1e-3)
    panels = facetwb.make_panelset(result, thickness=0.5, gap=0.0)  # (a 1 mm mesh)
    panels.Tolerance = 1e-2  # the result is planar to 1e-3 only
    sheets = facetwb.make_cutsheets(panels, sheet=(10.0, 10.0), margin=0.1, spacing=0.1,
                                    output_dir=files, write_step=False)
    doc.recompute()

    def digest():
        with open(os.path.join(files, "schedule.csv"), "rb") as f:
            return hashlib.sha256(f.read()).hexdigest()

    before = digest()
    result.ViewObject.Proxy.doubleClicked(result.ViewObject)
    panel = edit_panels.active
    field = panel.form.findChild(__import__("PySide").QtGui.QLineEdit, "Tolerance")
    field.setText("1e-09")
    field.editingFinished.emit()
    wait_for_live_resolve(result)
    doc.recompute()  # Recompute pressed with the panel open
    changed = digest()
    panel.reject()
    wait_for_live_resolve(result)
    after = digest()
    check(changed != before and after == before and result.Tolerance == 1e-3
          and "Touched" not in panels.State and "Touched" not in sheets.State,
          f"Recompute with the Planarize panel open rewrote the cut sheets' files; Cancel "
          f"writes them again from the result it puts back (schedule.csv "
          f"{before[:8]} -> {changed[:8]} -> {after[:8]}; {panels.State}, {sheets.State})")
    App.closeDocument(doc.Name)


def check_recompute_in_lifting_panels_then_cancel(check, out_dir):
    """The Shape lifting and Pin heights panels: Recompute pressed while one is open
    rebuilds the panels and rewrites the cut sheets' files from the moved roof; Cancel
    rebuilds them from the roof it puts back (they stayed those of the cancelled values).
    A Cancel after a change without Recompute writes nothing (the Pin heights panel solved
    the roof put back again and rebuilt the panels and files, 1e-12 mm off)."""
    import hashlib

    import FreeCAD as App
    import FreeCADGui as Gui

    import facetwb
    from facetwb.taskpanels import lift_mix, lift_pins

    doc, lifting, panels = open_roof_example()
    files = os.path.join(out_dir, "lifting_recompute_then_cancel")
    sheets = facetwb.make_cutsheets(panels, sheet=(20000.0, 20000.0), output_dir=files,
                                    write_step=False)
    doc.recompute()
    schedule = os.path.join(files, "schedule.csv")

    def digest():
        with open(schedule, "rb") as f:
            return hashlib.sha256(f.read()).hexdigest(), os.stat(schedule).st_mtime_ns

    def change(name):
        """Open the panel ``name`` and move the roof: a slider, a pin's height."""
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(lifting)
        Gui.runCommand(name)
        Gui.updateGui()
        if name == "Facet_LiftMix":
            panel = lift_mix.active
            if panel is not None:
                panel.sliders[0].setValue(40)
        else:
            panel = lift_pins.active
            if panel is not None:
                panel.editor.set_height(0, "5000 mm")
        Gui.updateGui()
        return panel

    roof = [tuple(p) for p in lifting.Points]
    for name, title in (("Facet_LiftMix", "Shape lifting"), ("Facet_LiftPins", "Pin heights")):
        before = digest()
        panel = change(name)
        if not check(panel is not None, f"the {title} panel opens"):
            continue
        doc.recompute()  # Recompute pressed with the panel open
        changed = digest()
        panel.reject()
        Gui.updateGui()
        after = digest()
        check(changed[0] != before[0] and after[0] == before[0]
              and "Touched" not in panels.State and "Touched" not in sheets.State,
              f"Recompute with the {title} panel open rewrote the cut sheets' files; Cancel "
              f"writes them again from the roof it puts back (schedule.csv "
              f"{before[0][:8]} -> {changed[0][:8]} -> {after[0][:8]}; {panels.State}, "
              f"{sheets.State})")
        panel = change(name)
        if panel is not None:
            panel.reject()
            Gui.updateGui()
        check(digest() == after and [tuple(p) for p in lifting.Points] == roof
              and "Touched" not in panels.State and "Touched" not in lifting.State,
              f"Cancel of the {title} panel after a change (no Recompute) puts the roof back "
              f"as it was and writes no file (schedule.csv rewritten: "
              f"{digest()[1] != after[1]}; {lifting.State}, {panels.State})")
    App.closeDocument(doc.Name)


def check_recompute_cancel_and_failed_create(check):
    """A re-solve that no command reports on (a changed property's live re-solve) shows
    progress with Cancel, which keeps the previous result; the Planarize panel's OK on a
    source that cannot be planarized leaves the document as it was and says why."""
    import FreeCAD as App
    import FreeCADGui as Gui
    import numpy as np

    import facet
    import facetwb
    from facetwb import progress
    from facetwb.objects.polymesh import get_mesh
    from facetwb.taskpanels import derive_panels

    mesh = facet.read_mesh(MESH)
    doc = App.newDocument("CancelAndFail")
    control = facetwb.make_polymesh(mesh, label="control")
    result = facetwb.make_planarized(control, tolerance=1e-3)
    doc.recompute()
    before = get_mesh(result).vertices.copy()
    from facetwb import live_parameters

    progress.cancel_after(2)  # Cancel pressed at the dialog's second progress call
    try:
        result.Tolerance = 1e-9
        end = time.monotonic() + 120
        while live_parameters.pending() and time.monotonic() < end:  # then it has run
            Gui.updateGui()
            time.sleep(0.02)
    finally:
        progress.cancel_after(0)
    check(not result.isValid() and "cancel" in result.getStatusString().lower()
          and np.array_equal(get_mesh(result).vertices, before),
          f"Cancel in a live re-solve's dialog keeps the previous result "
          f"({result.getStatusString()!r})")
    doc.recompute()
    check(result.isValid() and result.PlanarityMaxRel <= 1e-9, "a recompute then solves it")

    collapsed = facetwb.make_polymesh(mesh.with_vertices(np.zeros_like(mesh.vertices)),
                                      label="collapsed")
    doc.recompute()
    names = sorted(obj.Name for obj in doc.Objects)
    undo = list(doc.UndoNames)
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(collapsed)
    Gui.runCommand("Facet_Planarize")
    Gui.updateGui()
    panel = derive_panels.active
    accepted = panel.accept() if panel is not None else None
    Gui.updateGui()
    from facetwb.taskpanels import forms

    message = forms.widget(panel.form, "message").text() if panel is not None else ""
    check(accepted is False and derive_panels.active is panel
          and sorted(obj.Name for obj in doc.Objects) == names and list(doc.UndoNames) == undo
          and collapsed.ViewObject.Visibility and message.startswith("collapsed planarized: ")
          and message.count("collapsed planarized") == 1,
          f"OK on a source that fails: nothing added, the source shown, the panel open "
          f"saying why ({message!r})")
    if panel is not None:
        panel.reject()
    App.closeDocument(doc.Name)



def main():
    import FreeCAD as App

    if not App.GuiUp:
        print("SKIP: the GUI test needs the FreeCAD GUI (run it with freecad, not freecadcmd)")
        return 0
    out_dir = os.environ.get("FACET_GUI_OUT") or os.path.join(ROOT, "build", "gui")
    check = run(out_dir)
    print(f"{len(check.failed)} check(s) failed" if check.failed else "all checks passed",
          flush=True)
    return 1 if check.failed else 0


try:
    status = main()
except BaseException:  # noqa: BLE001 - any breakage must give a nonzero exit status
    traceback.print_exc()
    status = 2
sys.stdout.flush()
sys.stderr.flush()
os._exit(status)

