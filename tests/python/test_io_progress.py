# SPDX-License-Identifier: LGPL-2.1-or-later
"""Mesh readers' progress and Cancel."""

import re

import numpy as np
import pytest

from facet import PolyMesh, read_mesh, write_mesh
from facet.errors import Cancelled
from panel_meshes import write_mesh_file


def grid(n):
    k = np.arange(n + 1, dtype=np.float64)
    xyz = np.array([(x, y, 0.25 * x) for y in k for x in k])
    faces = [[j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1,
              (j + 1) * (n + 1) + i] for j in range(n) for i in range(n)]
    return PolyMesh.from_faces(xyz, faces)


@pytest.mark.parametrize("suffix", [".obj", ".off", ".json"])
def test_reading_a_mesh_reports_progress_and_can_be_cancelled(tmp_path, suffix):
    """A 100,000-face mesh took 0.6 s (OBJ) to 2.3 s (compas JSON) to read with no progress
    and no way to stop it (the command line, File > Import, a plan or target file): the
    readers count lines or records, and True from progress cancels."""
    mesh = grid(130)  # 17,161 vertices, 16,900 faces: steps between start and end
    path = tmp_path / f"grid{suffix}"
    write_mesh_file(mesh, path)
    calls = []
    read = read_mesh(path, progress=lambda done, total: calls.append((done, total)) and False)
    np.testing.assert_array_equal(read.vertices, read_mesh(path).vertices)
    np.testing.assert_array_equal(read.face_vertices, mesh.face_vertices)
    totals = {t for _, t in calls}
    assert len(totals) == 1
    done = [d for d, _ in calls]
    assert done == sorted(done) and done[0] == 0 and done[-1] == totals.pop()
    assert len(calls) >= 4
    for stop in (1, 2, len(calls)):
        seen = []
        with pytest.raises(Cancelled, match=f"reading grid{suffix} cancelled"):
            read_mesh(path, progress=lambda done, total: seen.append(done) or len(seen) == stop)
        assert len(seen) == stop


def test_the_command_line_shows_the_reading_on_a_terminal(tmp_path, monkeypatch):
    # `facet check` (planarize, cleanup, weld, panels) read its input with no line
    import io
    import sys

    from facet.cli import main
    from facet.cli_progress import ProgressLine

    class Terminal(io.StringIO):
        def isatty(self):
            return True

    write_mesh(grid(130), tmp_path / "grid.obj")
    terminal = Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    monkeypatch.setattr(ProgressLine, "_due", lambda self, at_once=False: True)  # (fast)
    assert main(["check", str(tmp_path / "grid.obj")]) == 0
    shown = terminal.getvalue()
    lines = re.search(r"facet check: reading grid\.obj 0 of (\d+)", shown).group(1)
    assert int(lines) > 34000  # (the file's lines)
    assert f"facet check: reading grid.obj {lines} of {lines}" in shown
