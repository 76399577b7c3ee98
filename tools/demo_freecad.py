# SPDX-License-Identifier: LGPL-2.1-or-later
"""Demo render: planarize a mesh in FreeCAD, save the document and pictures of its planarity.

Run under the FreeCAD GUI (Xvfb is fine), with the checkout loaded as the workbench:

    tests/fc_env.sh demo MESH [OUT_DIR]
    # = FACET_DEMO_MESH=MESH FACET_DEMO_OUT=OUT_DIR \\
    #   xvfb-run -a -s "-screen 0 1600x1000x24" freecad tools/demo_freecad.py

(freecad would open extra command-line arguments as documents, so the inputs come from the
environment.) Writes to OUT_DIR (default build/demo):

- demo.FCStd: the source PolyMesh and the Planarized object, shown in planarity colours;
- planarity.png: the planarized mesh's planarity map with its legend (isometric, fit all);
- source_planarity.png: the source's planarity map, the "before" picture.

Exit status 0 on success, 1 if the mesh cannot be read or the solve fails, 2 on a crash.
"""

import os
import sys
import traceback

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WIDTH, HEIGHT = 1600, 1000


def render(view, obj, path):
    """Isometric, fit all, ``obj`` in Planarity mode; PNG of WIDTH x HEIGHT pixels."""
    import FreeCADGui as Gui

    obj.ViewObject.DisplayMode = "Planarity"
    view.viewIsometric()
    view.fitAll()
    Gui.updateGui()
    view.saveImage(path, WIDTH, HEIGHT, "Current")
    print(f"wrote {path}")


def main():
    import FreeCAD as App

    if not App.GuiUp:
        print("demo_freecad.py needs the FreeCAD GUI (freecad under xvfb-run), not freecadcmd")
        return 2
    import FreeCADGui as Gui

    mesh_path = os.environ.get("FACET_DEMO_MESH")
    out_dir = os.environ.get("FACET_DEMO_OUT") or os.path.join(ROOT, "build", "demo")
    if not mesh_path:
        print("set FACET_DEMO_MESH to the mesh to planarize (OBJ or OFF)")
        return 2
    os.makedirs(out_dir, exist_ok=True)

    if "FacetWorkbench" in Gui.listWorkbenches():
        Gui.activateWorkbench("FacetWorkbench")
    import facetwb
    from facetwb import importer

    importer.SHOW_DIALOGS = False
    doc = App.newDocument("FacetDemo")
    try:
        source = importer.import_mesh(mesh_path, doc)
    except importer.MeshImportError as error:
        print(error)
        return 1
    result = facetwb.make_planarized(source)
    doc.recompute()
    print(facetwb.planarize_summary(result))
    if not result.isValid():
        return 1

    view = Gui.ActiveDocument.ActiveView
    source.ViewObject.Visibility = True
    result.ViewObject.Visibility = False
    render(view, source, os.path.join(out_dir, "source_planarity.png"))
    source.ViewObject.DisplayMode = "Flat Lines"
    source.ViewObject.Visibility = False
    result.ViewObject.Visibility = True
    render(view, result, os.path.join(out_dir, "planarity.png"))
    path = os.path.join(out_dir, "demo.FCStd")
    if os.path.exists(path):  # (a run's own: FreeCAD would keep it as demo.FCStd1)
        os.remove(path)
    doc.saveAs(path)
    print(f"wrote {path}")
    converged = result.Converged
    App.closeDocument(doc.Name)
    return 0 if converged else 1


try:
    status = main()
except BaseException:  # noqa: BLE001 - any breakage must give a nonzero exit status
    traceback.print_exc()
    status = 2
sys.stdout.flush()
sys.stderr.flush()
os._exit(status)
