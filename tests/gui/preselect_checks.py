# SPDX-License-Identifier: LGPL-2.1-or-later
"""GUI checks of the vertex a click would pick, ringed while the cursor is near it
(preselection; called by gui_test.py, ``g`` is the gui_test module for its helpers).

The planarized hypar in Planarity mode: the mouse moved (Qt events on the 3D view) 3 pixels
off a corner makes FreeCAD preselect ``VertexN``, and a ring (``ViewProviderPolyMesh.
preselected``) is drawn at that vertex's point, where the result has it (preselect.png);
moved to a panel's middle or off the mesh, the ring goes. ``Gui.Selection.setPreselection``
from a script rings a vertex too, and a re-solve that moves it (the vertex held) moves the
ring with it. On the control mesh (Flat Lines) the ring shows as well
(preselect_control.png).
"""

import os

from ui_checks import settle


def ring_pixels(g, path, view, point, color, reach):
    """Pixels of ``color`` within ``reach`` pixels of ``point`` (x, y, z in mm) in the
    view's image at ``path`` (saved at the view's size, so one image pixel is one screen
    pixel)."""
    import FreeCAD as App

    pixels = g.image_pixels(path)
    x, y = view.getPointOnScreen(App.Vector(*point))
    row, column = pixels.shape[0] - 1 - int(round(y)), int(round(x))
    box = pixels[max(row - reach, 0):row + reach + 1, max(column - reach, 0):column + reach + 1]
    return int(g.near(box, color, 30).sum())


def ringed(proxy):
    """(vertices, points) the view provider rings; ([], []) without a ring."""
    marker = getattr(proxy, "preselected", None)
    return (list(marker.vertices), list(marker.points)) if marker is not None else ([], [])


def run(check, out_dir, g):
    import FreeCAD as App
    import FreeCADGui as Gui
    import numpy as np

    import facet
    import facetwb
    from facetwb.objects.polymesh import get_mesh
    from facetwb.viewproviders.view_polymesh import (PRESELECTED_COLOR, PRESELECTED_HALO,
                                                      VERTEX_PICK_PIXELS)

    doc = App.newDocument("Preselect")
    mesh = facet.read_mesh(g.MESH)
    control = facetwb.make_polymesh(mesh, label="Control mesh")
    result = facetwb.make_planarized(control, tolerance=1e-3)
    doc.recompute()
    settle(10)
    view = Gui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    settle(5)
    width, height = view.getSize()
    proxy = result.ViewObject.Proxy
    solved = get_mesh(result).vertices.copy()
    reach = VERTEX_PICK_PIXELS + 2

    def shot(name):
        path = os.path.join(out_dir, name)
        view.saveImage(path, width, height, "Current")
        return path

    # vertices whose 3-pixel-off pick names them (not hidden behind a panel in front)
    seen = []
    for vertex in (40, 30, 50, 22, 58):
        x, y = view.getPointOnScreen(App.Vector(*solved[vertex]))
        info = view.getObjectInfo((int(x) + 3, int(y) + 3)) or {}
        if info.get("Object") == result.Name and info.get("Component") == f"Vertex{vertex}":
            seen.append((vertex, (int(x) + 3, int(y) + 3)))
    if not check(len(seen) >= 3, f"vertices to hover over ({[v for v, _ in seen]})"):
        App.closeDocument(doc.Name)
        return
    path = shot("preselect_none.png")
    before = ring_pixels(g, path, view, solved[seen[0][0]], PRESELECTED_COLOR, reach)
    wrong = []
    for vertex, at in seen:
        g.hover(view, at)
        presel = Gui.Selection.getPreselection()
        vertices, points = ringed(proxy)
        if not (presel.ObjectName == result.Name
                and tuple(presel.SubElementNames) == (f"Vertex{vertex}",)
                and vertices == [vertex]
                and np.allclose(points[0], solved[vertex], rtol=0, atol=1e-3)):
            wrong.append((vertex, presel.ObjectName, tuple(presel.SubElementNames), vertices,
                          points))
    check(not wrong, f"the mouse 3 px off a corner preselects VertexN and rings it at the "
                     f"result's point ({len(seen)} vertices; wrong: {wrong[:2]})")
    vertex, at = seen[0]
    g.hover(view, at)
    path = shot("preselect.png")
    drawn = ring_pixels(g, path, view, solved[vertex], PRESELECTED_COLOR, reach)
    check(before == 0 and drawn >= 60,
          f"the ring shows around vertex {vertex} in {path} ({drawn} pixels of its colour "
          f"within {reach} px, {before} before)")
    centre = solved[mesh.face_vertices[mesh.face_start[27]:mesh.face_start[28]]].mean(axis=0)
    x, y = view.getPointOnScreen(App.Vector(*centre))
    g.hover(view, (int(x), int(y)))
    presel = Gui.Selection.getPreselection()
    path = shot("preselect_face.png")
    check(tuple(presel.SubElementNames) == ("Face27",) and ringed(proxy) == ([], [])
          and ring_pixels(g, path, view, solved[vertex], PRESELECTED_COLOR, reach) == 0,
          f"a panel's middle preselects the panel, no ring ({presel.SubElementNames})")
    g.hover(view, at)
    g.hover(view, (5, 5))  # the background
    check(Gui.Selection.getPreselection().ObjectName == "" and ringed(proxy) == ([], []),
          "off the mesh: nothing preselected, no ring")

    # from a script, then a re-solve that moves the vertex (the one planarizing moved
    # most, held back at the control mesh's point): the ring follows it
    vertex = max((v for v, _ in seen), key=lambda v: np.linalg.norm(solved[v] - mesh.vertices[v]))
    Gui.Selection.setPreselection(result, f"Vertex{vertex}")
    settle(2)
    check(ringed(proxy)[0] == [vertex],
          f"Gui.Selection.setPreselection(result, 'Vertex{vertex}') rings it")
    result.FixedVertices = [vertex]
    doc.recompute()
    settle(2)
    moved = get_mesh(result).vertices[vertex]
    vertices, points = ringed(proxy)
    check(vertices == [vertex] and np.allclose(points[0], moved, rtol=0, atol=1e-3)
          and np.linalg.norm(moved - solved[vertex]) > 1e-2,
          f"held, the vertex moves {np.linalg.norm(moved - solved[vertex]):.3g} mm and the "
          f"ring with it")
    Gui.Selection.clearPreselection()
    settle(2)
    check(ringed(proxy) == ([], []), "Gui.Selection.clearPreselection() takes the ring away")

    # the control mesh (a PolyMesh, Flat Lines) rings its vertices too
    result.ViewObject.Visibility = False
    control.ViewObject.Visibility = True
    settle(5)
    x, y = view.getPointOnScreen(App.Vector(*mesh.vertices[vertex]))
    g.hover(view, (5, 5))
    dark_before = ring_pixels(g, shot("preselect_control_none.png"), view,
                              mesh.vertices[vertex], PRESELECTED_HALO, reach + 2)
    g.hover(view, (int(x) + 3, int(y) + 3))
    path = shot("preselect_control.png")
    check(ringed(control.ViewObject.Proxy)[0] == [vertex]
          and ring_pixels(g, path, view, mesh.vertices[vertex], PRESELECTED_COLOR,
                          reach) >= 60,
          f"on the control mesh too ({path}: "
          f"{Gui.Selection.getPreselection().SubElementNames})")
    # white on the light grey faces was faint: a dark halo sets the ring off
    dark = ring_pixels(g, path, view, mesh.vertices[vertex], PRESELECTED_HALO, reach + 2)
    check(dark - dark_before >= 60,
          f"a dark halo around the ring on the light grey faces ({dark} dark pixels within "
          f"{reach + 2} px, {dark_before} before)")
    g.hover(view, (5, 5))
    App.closeDocument(doc.Name)
