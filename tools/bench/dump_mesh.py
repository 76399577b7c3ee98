# SPDX-License-Identifier: LGPL-2.1-or-later
"""Write a benchmark mesh as the raw binary that libcore/bench/bench_large reads.

    /usr/bin/python3 tools/bench/dump_mesh.py quad_grid 1000 OUT.bin
    /usr/bin/python3 tools/bench/dump_mesh.py quad_torus 1000 OUT.bin
    /usr/bin/python3 tools/bench/dump_mesh.py hex_torus 100000 OUT.bin   # about 100k faces
    /usr/bin/python3 tools/bench/dump_mesh.py level 5 OUT.bin

The meshes are those of tools/bench/families.py (same bits). Layout: int64
n_vertices, n_faces, n_corners; float64 xyz (3 n_vertices); int32 face_start
(n_faces + 1); int32 face_vertices (n_corners); native byte order.
"""

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import families  # noqa: E402

GENERATORS = {
    "quad_grid": lambda n: families.quad_grid(n, n),
    "quad_torus": lambda n: families.quad_torus(n, n),
    "hex_torus": lambda n: families.hex_torus(*families.hex_torus_faces(n)),
    "level": families.level_patch,
}


def write(mesh, path):
    with open(path, "wb") as f:
        np.array([mesh.n_vertices, mesh.n_faces, mesh.face_vertices.shape[0]], dtype=np.int64).tofile(f)
        np.ascontiguousarray(mesh.vertices, dtype=np.float64).tofile(f)
        np.ascontiguousarray(mesh.face_start, dtype=np.int32).tofile(f)
        np.ascontiguousarray(mesh.face_vertices, dtype=np.int32).tofile(f)


def main(argv):
    if len(argv) != 3 or argv[0] not in GENERATORS:
        print(f"usage: dump_mesh.py {{{'|'.join(GENERATORS)}}} SIZE OUT.bin", file=sys.stderr)
        return 2
    try:
        size = int(argv[1])
    except ValueError:
        print(f"dump_mesh.py: SIZE must be an integer, not {argv[1]!r}", file=sys.stderr)
        return 2
    mesh = GENERATORS[argv[0]](size)
    write(mesh, argv[2])
    print(f"{mesh.name}: {mesh.n_vertices} vertices, {mesh.n_faces} faces -> {argv[2]}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
