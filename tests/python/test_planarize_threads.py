# SPDX-License-Identifier: LGPL-2.1-or-later
"""The solve's thread count (facet.h, FACET_CORNERS_PER_THREAD): by default one thread
per 100,000 face corners, the count asked for otherwise; the result and the report say
which, and the bits do not depend on it."""

import json

import numpy as np

import facet


def _grid(n):
    faces = [[j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i]
             for j in range(n) for i in range(n)]
    i, j = np.meshgrid(np.arange(n + 1.0), np.arange(n + 1.0), indexing="xy")
    z = 0.3 * np.sin(0.4 * i.ravel()) * np.cos(0.3 * j.ravel())
    return facet.PolyMesh.from_faces(np.stack([i.ravel(), j.ravel(), z], axis=1), faces)


def test_a_small_mesh_solves_on_one_thread_by_default():
    mesh = _grid(12)
    default = facet.planarize(mesh)
    two = facet.planarize(mesh, threads=2)
    assert default.threads == 1 and two.threads == 2
    assert np.array_equal(default.mesh.vertices, two.mesh.vertices)


def test_the_report_and_summary_name_the_threads(facet_command, tmp_path):
    path = tmp_path / "g.obj"
    facet.write_mesh(_grid(6), str(path))
    report = tmp_path / "r.json"
    done = facet_command("planarize", path, "-o", tmp_path / "o.obj", "--report", report)
    assert done.returncode == 0, done.stderr
    assert json.loads(report.read_text())["threads"] == 1
    assert " s on 1 thread: " in done.stdout
