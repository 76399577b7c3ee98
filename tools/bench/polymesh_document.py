# SPDX-License-Identifier: LGPL-2.1-or-later
"""A large PolyMesh in a FreeCAD document: how long storing, drawing, recomputing, saving and
reopening it takes (the steps a designer waits through with no progress shown).

The mesh: families.quad_grid(N, N) (default N = 1000: 1,000,000 quads, 1,002,001 vertices),
its unit cells scaled to 1000 mm. Steps timed, each the median of --runs (default 3) in one
FreeCAD process (a new document per run):

``make_polymesh``
    facetwb.make_polymesh(mesh): store the mesh in the object's properties and, in the GUI,
    its view provider's one drawing.
``recompute``
    doc.recompute() of the new PolyMesh: get_mesh, facet.planarity, the colours.
``write-back new``
    set_mesh + set_planarity of a Planarized result into a new Planarized object (what its
    first recompute does after the solve; the solve itself is not timed): in the GUI its
    view draws the new topology.
``write-back re-solve``
    the same into that object again with moved coordinates (a re-solve: same topology).
``save``
    doc.saveAs() of the document (PolyMesh + Planarized).
``reopen``
    App.openDocument of it (closed first, not timed): in the GUI its view providers attach
    and draw.

Each time is of the call alone; in the GUI the events that follow it (the 3D view rendering
the meshes, in software under Xvfb; timers that attach and fit) are timed apart ("then
events").

Run it headless and under the GUI (Xvfb), with the checkout loaded as the workbench::

    tests/fc_env.sh freecadcmd tools/bench/polymesh_document.py
    tests/fc_env.sh xvfb-run -a -s "-screen 0 1600x1000x24" freecad \
        tools/bench/polymesh_document.py

(freecad would open extra command-line arguments as documents, so options come from the
environment: FACET_BENCH_N=1000, FACET_BENCH_RUNS=3, FACET_BENCH_JSON=path.) Prints one
line per step; the machine it runs on is what the figures mean (state it with them).
"""

import json
import os
import statistics
import sys
import tempfile
import time
import traceback

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "workbench"))

STEPS = ("make_polymesh", "recompute", "write-back new", "write-back re-solve", "save",
         "reopen")


def settle():
    """In the GUI, run the pending events (timers that attach and draw); else nothing."""
    import FreeCAD as App

    if App.GuiUp:
        import FreeCADGui as Gui

        for _ in range(3):
            Gui.updateGui()


def one_run(mesh, moved, folder, index):
    import FreeCAD as App

    import facet
    import facetwb
    from facetwb.objects.polymesh import set_mesh, set_planarity

    times = {}

    def timed(step, call):
        start = time.perf_counter()
        result = call()
        called = time.perf_counter()
        settle()
        times[step] = called - start
        if App.GuiUp:  # the events after it: the 3D view rendered, timers (attach, fit)
            times[step + " +events"] = time.perf_counter() - called
        return result

    doc = App.newDocument(f"MeshBench{index}")
    obj = timed("make_polymesh", lambda: facetwb.make_polymesh(mesh, doc=doc))
    timed("recompute", doc.recompute)
    planarized = facetwb.make_planarized(obj)  # not recomputed: the solve is not timed
    report = facet.planarity(moved)

    def write_back(result):
        set_mesh(planarized, result)
        set_planarity(planarized, report)

    timed("write-back new", lambda: write_back(moved))
    timed("write-back re-solve", lambda: write_back(mesh))
    path = os.path.join(folder, f"bench{index}.FCStd")
    timed("save", lambda: doc.saveAs(path))
    name = doc.Name
    App.closeDocument(name)
    settle()
    again = timed("reopen", lambda: App.openDocument(path))
    App.closeDocument(again.Name)
    settle()
    return times


def main():
    import FreeCAD as App
    import numpy as np

    import facet
    import families

    n = int(os.environ.get("FACET_BENCH_N", "1000"))
    runs = int(os.environ.get("FACET_BENCH_RUNS", "3"))
    grid = families.quad_grid(n, n)
    xyz = np.asarray(grid.vertices, dtype=np.float64) * 1000.0
    face_start = np.asarray(grid.face_start, dtype=np.int32)
    face_vertices = np.asarray(grid.face_vertices, dtype=np.int32)
    mesh = facet.PolyMesh(xyz, face_start, face_vertices)
    moved = facet.PolyMesh(xyz + 0.25, face_start, face_vertices)
    if App.GuiUp:
        import FreeCADGui as Gui

        if "FacetWorkbench" in Gui.listWorkbenches():
            Gui.activateWorkbench("FacetWorkbench")
        from facetwb import live_parameters

        # make_planarized's parameters schedule a live re-solve (a timer): it would fire in
        # the events after the write-back and solve the 1M-face mesh there
        live_parameters.ENABLED = False
    mode = "GUI" if App.GuiUp else "headless"
    print(f"{mode}: quad grid {n} x {n} ({mesh.n_faces} faces, {mesh.n_vertices} vertices), "
          f"median of {runs}", flush=True)
    all_times = []
    with tempfile.TemporaryDirectory() as folder:
        for index in range(runs):
            all_times.append(one_run(mesh, moved, folder, index))
            print("  run", index + 1, " ".join(f"{k}={v:.2f}s" for k, v in
                                                all_times[-1].items()), flush=True)
    medians = {step: statistics.median(t[step] for t in all_times) for step in all_times[0]}
    for step in STEPS:
        events = medians.get(step + " +events")
        print(f"{mode} {step:22s} {medians[step]:7.2f} s"
              + ("" if events is None else f"   then events {events:6.2f} s"), flush=True)
    out = os.environ.get("FACET_BENCH_JSON")
    if out:
        with open(out, "w") as stream:
            json.dump({"mode": mode, "n": n, "runs": all_times, "median": medians}, stream,
                      indent=1)
    return 0


try:
    status = main()
except BaseException:  # noqa: BLE001 - a breakage must give a nonzero exit status
    traceback.print_exc()
    status = 2
sys.stdout.flush()
sys.stderr.flush()
os._exit(status)
