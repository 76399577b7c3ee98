# SPDX-License-Identifier: LGPL-2.1-or-later
"""Frames per second of dragging a control vertex of a 10k-face facade in FreeCAD.

Runs inside the FreeCAD GUI (under Xvfb: ``make bench-drag``)::

    FACET_DRAG_JSON=out/bench/drag_fps.json tests/fc_env.sh \\
        xvfb-run -a -s "-screen 0 1600x1000x24" freecad tools/bench/drag_fps.py

A quad grid of ``FACET_DRAG_N`` x ``FACET_DRAG_N`` panels (default 100 x 100 = 10,000,
tools/bench/families.quad_grid, a doubly curved facade, 1 m panels) becomes a PolyMesh
and a Planarized object (solved cold to 1e-6). An edit session starts on it, and the
middle vertex is dragged in ``FACET_DRAG_STEPS`` (default 60) small steps of 2 pixels
through the session's own mouse callbacks (real SoMouseButtonEvent / SoLocation2Event
objects handed to the functions the 3D view calls). Each frame is rendered: the view's
redraw() and Gui.updateGui() (no image is saved).

Two runs:

- **sequential**: each move solves in the event handler; the frame's time splits into
  solve (LiveSolver.frame: a live update to the object's tolerance, and the planarity of
  the result), scene (the changed coordinates and colours into the Coin nodes) and
  render. Every rendered frame shows the result of the control drawn.
  fps = 1 / median frame time.
- **threaded** (how the workbench runs): the mouse moves 2 pixels every 1/60 s, the
  solve runs on a worker thread while the main thread renders as fast as it can; moves
  that arrive during a solve are merged. fps = rendered frames whose result is the
  solution of the control drawn, per second (a render of a stale result does not count).

Then the release (a whole-mesh solve only if the last frame fell short of the tolerance).
"""

import json
import os
import statistics
import sys
import time
import traceback

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


class _Node:
    """What an SoEventCallback hands to a callback: the event, and setHandled()."""

    def __init__(self, event):
        self.event = event
        self.handled = False

    def getEvent(self):  # noqa: N802 - Coin's name
        return self.event

    def setHandled(self):  # noqa: N802
        self.handled = True


def _button(position, down):
    from pivy import coin

    event = coin.SoMouseButtonEvent()
    event.setButton(coin.SoMouseButtonEvent.BUTTON1)
    event.setState(coin.SoButtonEvent.DOWN if down else coin.SoButtonEvent.UP)
    event.setPosition(coin.SbVec2s(int(position[0]), int(position[1])))
    return _Node(event)


def _move(position):
    from pivy import coin

    event = coin.SoLocation2Event()
    event.setPosition(coin.SbVec2s(int(position[0]), int(position[1])))
    return _Node(event)


def _ms(values):
    return 1e3 * statistics.median(values) if values else float("nan")


def run():
    import FreeCAD as App
    import FreeCADGui as Gui

    sys.path.insert(0, HERE)
    import families

    import facet
    import facetwb
    from facetwb import edit_control

    n = int(os.environ.get("FACET_DRAG_N", "100"))
    steps = int(os.environ.get("FACET_DRAG_STEPS", "60"))
    Gui.activateWorkbench("FacetWorkbench")
    grid = families.quad_grid(n, n)
    mesh = facet.PolyMesh(grid.vertices * 1000.0, grid.face_start, grid.face_vertices)
    doc = App.newDocument("DragFps")
    control = facetwb.make_polymesh(mesh)
    planarized = facetwb.make_planarized(control)
    t0 = time.perf_counter()
    doc.recompute()
    cold = time.perf_counter() - t0
    view = Gui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    Gui.updateGui()
    vertex = (n // 2) * (n + 1) + n // 2
    out = {"lp_num_threads": os.environ.get("LP_NUM_THREADS", ""), "mesh": grid.name,
           "faces": mesh.n_faces, "vertices": mesh.n_vertices,
           "steps": steps, "step_pixels": 2, "view_pixels": list(view.getSize()),
           "cold_recompute_seconds": cold, "planarized_max_rel": planarized.PlanarityMaxRel,
           "frame_threads": 1, "load_average": os.getloadavg()}

    def render():
        view.redraw()
        Gui.updateGui()

    # --- sequential: the split ---------------------------------------------------------------
    session = edit_control.start(planarized, threaded=False, panel=False)
    out["frame_seconds"] = session.live.frame_seconds
    x, y = session.screen_position(vertex)
    session._on_button(_button((x, y), True))
    if session.live.drag_vertex is None:
        raise RuntimeError(f"the press at {x}, {y} on vertex {vertex} picked nothing")
    vertex = session.live.drag_vertex  # a neighbour when vertices are under a pixel apart
    out["vertex"] = vertex
    frames, renders, cpu = [], [], []
    for k in range(1, steps + 1):
        t0 = time.perf_counter()
        session._on_move(_move((x, y + 2 * k)))
        t1 = time.perf_counter()
        c1 = time.process_time()
        render()
        t2 = time.perf_counter()
        cpu.append(time.process_time() - c1)
        frames.append(t2 - t0)
        renders.append(t2 - t1)
    solve, scene = session.stats["solve"][-steps:], session.stats["scene"][-steps:]
    frame_planarity = session.stats["planarity"][-steps:]
    t0 = time.perf_counter()
    session._on_button(_button((x, y + 2 * steps), False))
    settle = time.perf_counter() - t0
    result = session.live.result
    out["sequential"] = {
        "fps": 1.0 / statistics.median(frames),
        "frame_ms": _ms(frames), "solve_ms": _ms(solve), "scene_ms": _ms(scene),
        "render_ms": _ms(renders),
        "render_cpu_ms": _ms(cpu),
        "frame_max_rel_worst": max(frame_planarity),
        "settle_seconds": settle, "settle_iterations": int(result.iterations),
        "settled_max_rel": float(result.planarity.max_rel_all),
        "control_moved_mm": float(((session.live.control[vertex] - mesh.vertices[vertex])**2)
                                  .sum()**0.5),
    }
    session.cancel()

    # --- threaded: what the designer sees ---------------------------------------------------
    # The mouse moves 2 pixels every 1/60 s (a steady hand-speed drag) while the main
    # thread renders as fast as it can and the worker solves; a rendered frame counts
    # only if the result drawn is the solution of the control positions drawn.
    session = edit_control.start(planarized, threaded=True, panel=False)
    x, y = session.screen_position(vertex)
    session._on_button(_button((x, y), True))
    renders = current = 0
    moves, period = 0, 1.0 / 60.0
    loop = []
    last_loop = time.perf_counter()
    shown0 = session.stats["frames"]
    t0 = last_move = time.perf_counter()
    while moves < steps:
        now = time.perf_counter()
        if renders:
            loop.append(now - last_loop)
        last_loop = now
        if now - last_move >= period or moves == 0:
            moves += 1
            last_move = now
            session._on_move(_move((x, y + 2 * moves)))
        session.poll()
        render()
        renders += 1
        current += bool(session.current)
    wall = time.perf_counter() - t0
    shown = session.stats["frames"] - shown0
    session.wait()
    out["threaded"] = {"fps": current / wall,
                       "median_fps": 1.0 / statistics.median(loop) if loop else 0.0,
                       "renders": renders, "current_renders": current,
                       "results_shown": shown, "moves": steps, "wall_seconds": wall,
                       "solve_ms": _ms(session.stats["solve"])}
    session._on_button(_button((x, y + 2 * steps), False))
    session.wait(300.0)
    session.cancel()

    # --- qt: real Qt mouse events to the 3D view's GL widget ---------------------------------
    # Through FreeCAD's own event path (navigation style, SoEventManager, the scene's event
    # callbacks), one move per rendered frame; the session as the workbench runs it.
    from PySide import QtCore, QtGui

    widgets = [w for w in Gui.getMainWindow().findChildren(QtGui.QWidget)
               if type(w).__name__ == "QOpenGLWidget" and w.isVisible()]
    if widgets:
        widget = widgets[0]
        ratio = float(widget.devicePixelRatioF())
        height = view.getSize()[1]
        session = edit_control.start(planarized, threaded=True, panel=False)
        x, y = session.screen_position(vertex)

        def send(kind, px, py, button, buttons):
            pos = QtCore.QPoint(int(round(px / ratio)), int(round((height - 1 - py) / ratio)))
            event = QtGui.QMouseEvent(kind, pos, widget.mapToGlobal(pos), button, buttons,
                                      QtCore.Qt.NoModifier)
            QtGui.QApplication.sendEvent(widget, event)

        left = QtCore.Qt.LeftButton
        send(QtCore.QEvent.MouseButtonPress, x, y, left, left)
        picked = session.live.drag_vertex
        frames, events, current = [], [], 0
        for k in range(1, steps + 1):
            t0 = time.perf_counter()
            send(QtCore.QEvent.MouseMove, x, y + 2 * k, QtCore.Qt.NoButton, left)
            t1 = time.perf_counter()
            render()
            frames.append(time.perf_counter() - t0)
            events.append(t1 - t0)
            current += bool(session.current)
        send(QtCore.QEvent.MouseButtonRelease, x, y + 2 * steps, left, QtCore.Qt.NoButton)
        session.wait(300.0)
        out["qt"] = {"fps": 1.0 / statistics.median(frames), "frame_ms": _ms(frames),
                     "event_ms": _ms(events), "render_ms": _ms([f - e for f, e in
                                                                 zip(frames, events)]),
                     "solve_ms": _ms(session.stats["solve"][-steps:]),
                     "scene_ms": _ms(session.stats["scene"][-steps:]),
                     "current_renders": current, "moves": session.stats["moves"],
                     "picked": picked}
        session.cancel()
    return out


def main():
    import FreeCAD as App

    if not App.GuiUp:
        print("SKIP: drag_fps needs the FreeCAD GUI (run it with freecad under xvfb-run)")
        return 0
    out = run()
    path = os.environ.get("FACET_DRAG_JSON") or os.path.join(ROOT, "out", "bench",
                                                             "drag_fps.json")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as handle:
        json.dump(out, handle, indent=1)
    s, t = out["sequential"], out["threaded"]
    print(f"drag_fps: {out['mesh']}, {out['faces']} faces, view {out['view_pixels']} px, "
          f"frame solves on 1 thread, load average {out['load_average'][0]:.1f}")
    print(f"  sequential: {s['fps']:.1f} fps (frame {s['frame_ms']:.1f} ms = solve "
          f"{s['solve_ms']:.1f} + scene {s['scene_ms']:.1f} + render {s['render_ms']:.1f}; "
          f"render CPU of FreeCAD's threads {s['render_cpu_ms']:.1f})")
    print(f"  sequential frames planar to {s['frame_max_rel_worst']:.2g} (worst frame)")
    print(f"  threaded:   {t['fps']:.1f} fps, {t['median_fps']:.1f} from the median frame "
          f"({t['current_renders']} current of "
          f"{t['renders']} renders, {t['results_shown']} results shown for {t['moves']} moves "
          f"at 60 Hz in {t['wall_seconds']:.2f} s)")
    q = out.get("qt")
    if q:
        print(f"  qt events:  {q['fps']:.1f} fps (frame {q['frame_ms']:.1f} ms = event "
              f"{q['event_ms']:.1f} (solve {q['solve_ms']:.1f} + scene {q['scene_ms']:.1f} + "
              f"FreeCAD's event path) + render {q['render_ms']:.1f}; {q['current_renders']} "
              f"current of {q['moves']} moves, picked vertex {q['picked']})")
    print(f"  release: {s['settle_seconds']:.2f} s, {s['settle_iterations']} iterations, "
          f"planarity {s['settled_max_rel']:.2g}")
    print(f"  written {path}")
    return 0


try:
    status = main()
except BaseException:  # noqa: BLE001 - any breakage must give a nonzero exit status
    traceback.print_exc()
    status = 2
sys.stdout.flush()
sys.stderr.flush()
os._exit(status)
