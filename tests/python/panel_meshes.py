# SPDX-License-Identifier: LGPL-2.1-or-later
"""Exactly planar quad meshes for the panel tests (also used by the FreeCAD tests)."""

import numpy as np

from facet.mesh import PolyMesh


def grid_faces(nu, nv):
    """Quads of an (nu+1) x (nv+1) vertex grid, row-major, counter-clockwise."""
    faces = []
    for j in range(nv):
        for i in range(nu):
            a = j * (nu + 1) + i
            faces.append([a, a + 1, a + nu + 2, a + nu + 1])
    return faces


def cylinder(nu=6, nv=4, radius=5000.0, angle=0.15, height=900.0, origin=(0.0, 0.0, 0.0)):
    """Planar quads on a cylinder (torsion-free: every node has a straight axis)."""
    pts = []
    for j in range(nv + 1):
        for i in range(nu + 1):
            pts.append([radius * np.cos(i * angle), radius * np.sin(i * angle), j * height])
    return PolyMesh.from_faces(np.array(pts) + np.asarray(origin), grid_faces(nu, nv))


def translational(nu=5, nv=4, step=1000.0):
    """Planar quads (parallelograms) of a translational surface a(u) + b(v):
    doubly curved, so its nodes are not torsion-free."""
    pts = []
    for j in range(nv + 1):
        for i in range(nu + 1):
            x, y = i * step, j * step
            pts.append([x, y, 0.00012 * (x - 2500.0) ** 2 - 0.00009 * (y - 2000.0) ** 2])
    return PolyMesh.from_faces(np.array(pts), grid_faces(nu, nv))


#: heights of the fold lines x = i * step of `folded_grid`
FOLDS = (0.0, 0.3, 0.1, 0.5, 0.2)


def folded_grid(short=None, nv=2, step=1000.0):
    """Planar quads folded along the lines x = i * step (z depends on x alone, so
    every quad is exactly planar whatever the y of its corners), 4 columns by `nv`
    rows, faces numbered row by row. With `short`, the fold-line edge from vertex 2
    (x = 2 step, y = 0) to vertex 7 (the next row's) is `short` long: faces 1 and 2
    lie beside it, faces 6 and 7 touch only vertex 7."""
    nu = len(FOLDS) - 1
    pts = []
    for j in range(nv + 1):
        for i in range(nu + 1):
            y = j * step + (0.1 * step * ((i * 7 + j * 3) % 3) if 0 < j < nv else 0.0)
            if short is not None and i == 2 and j == 1:
                y = short
            pts.append([i * step, y, FOLDS[i] * step])
    return PolyMesh.from_faces(np.array(pts), grid_faces(nu, nv))


def freecad_step():
    """facet.step with FreeCAD imported, or the test skipped when FreeCAD is missing."""
    import pytest

    import facet.step as step

    try:
        step.import_freecad()
    except step.FreeCADMissing:
        pytest.skip("FreeCAD is not installed")
    return step


def write_mesh_file(mesh, path):
    """``mesh`` written to ``path`` (a pathlib.Path) in the format its suffix names; .json in
    the old compas layout ({"vertex": {...}, "face": {...}}), which facet reads but has no
    writer of."""
    import json

    from facet.io import write_mesh

    if path.suffix == ".json":
        path.write_text(json.dumps({
            "vertex": {str(v): dict(zip("xyz", map(float, p))) for v, p in
                       enumerate(mesh.vertices)},
            "face": {str(f): [int(v) for v in face] for f, face in enumerate(mesh.faces())}}))
    else:
        write_mesh(mesh, path)
