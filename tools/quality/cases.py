"""The problem cases of issue 3's quality target (docs/solver-notes.md,
"Quality by default (branch quality5)"): generated benchmark meshes whose
default solve closes a corner. Run with /usr/bin/python3 after `make build`."""
import os, sys
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [os.path.join(HERE, '..', '..', 'workbench'), os.path.join(HERE, '..', 'bench')]
import numpy as np
import facet, families


def fam(b):
    return facet.PolyMesh(b.vertices, b.face_start, b.face_vertices)


CASES = [
    ('hypar32', 'point', lambda: fam(families.hypar(32))),
    ('hypar40', 'point', lambda: fam(families.hypar(40))),
    ('hypar60', 'point', lambda: fam(families.hypar(60))),
    ('hypar63', 'point', lambda: fam(families.hypar(63))),
    ('hypar72', 'point', lambda: fam(families.hypar(72))),
    ('level6', 'point', lambda: fam(families.level_patch(6))),
    ('level5', 'plane', lambda: fam(families.level_patch(5))),
    ('level5', 'surface', lambda: fam(families.level_patch(5))),
    ('hypar64', 'surface', lambda: fam(families.hypar(64))),
    ('hypar64', 'plane', lambda: fam(families.hypar(64))),
    ('hypar64', 'point', lambda: fam(families.hypar(64))),
    ('level5', 'tangent0.01', lambda: fam(families.level_patch(5))),
]


def selected(names):
    """(name, data, mesh) of the cases named (name or name:data; all when
    none), each mesh built once."""
    cache = {}
    for name, data, mk in CASES:
        if names and name not in names and f'{name}:{data}' not in names:
            continue
        yield name, data, cache.setdefault(name, mk())


def data_options(data):
    """planarize keywords of a case's data term: a preset of facet.DATA_TERMS,
    or 'tangent0.01' (point data with data_tangent 0.01 and no shape term,
    the "plane data" of docs/solver-notes.md's earlier sections)."""
    if data == 'tangent0.01':
        return dict(data='point', data_tangent=0.01)
    return dict(data=data)


def corner_angles(vertices, face_start, face_vertices):
    """Every corner's angle in degrees, in face order."""
    out = []
    V = np.asarray(vertices)
    for f in range(len(face_start) - 1):
        idx = face_vertices[face_start[f]:face_start[f + 1]]
        n = len(idx)
        for k in range(n):
            u = V[idx[k - 1]] - V[idx[k]]
            w = V[idx[(k + 1) % n]] - V[idx[k]]
            out.append(np.degrees(np.arctan2(np.linalg.norm(np.cross(u, w)), np.dot(u, w))))
    return np.array(out)


def new_narrow(mesh, result_vertices, floor=5.0):
    """Corners below floor whose input corner was >= floor, or below half of it."""
    a_in = corner_angles(mesh.vertices, mesh.face_start, mesh.face_vertices)
    a_out = corner_angles(result_vertices, mesh.face_start, mesh.face_vertices)
    bad = (a_out < floor) & ((a_in >= floor) | (a_out < 0.5 * a_in))
    return int(bad.sum()), float(a_out.min())
