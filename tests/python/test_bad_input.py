# SPDX-License-Identifier: LGPL-2.1-or-later
"""The bad-input catalogue (docs/bad-input.md), on the command line and in Python.

One row of :mod:`bad_input_cases` is one kind of bad input; each row is one
``test_command_line[row]`` and one ``test_python_api[row]``:

- command line: exit status 2 and ONE line on stderr naming the file, the
  element and the problem, no traceback, no output file; rows marked
  ``works`` (tiny and georeferenced coordinates, faces with hundreds of
  vertices, dangling edges, ...) exit 0 and write finite numbers;
- Python: the same input raises a :class:`facet.InputError` whose message is
  the same one line (without the ``facet: error:`` prefix), or, for the
  ``works`` rows, gives a finite result.
"""

import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import facet
from facet import cli
from facet.errors import InputError

sys.path.insert(0, os.path.dirname(__file__))
import bad_input_cases as cases  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
ROWS = {row.name: row for row in cases.ROWS}


def _outputs(row, folder):
    """Files the command would write (-o, --dxf, ...)."""
    argv = row.command(folder)
    return [argv[i + 1] for i, a in enumerate(argv) if a in ("-o", "--dxf", "--schedule")]


@pytest.mark.parametrize("name", list(ROWS))
def test_command_line(name, facet_command, tmp_path):
    row = ROWS[name]
    row.write(tmp_path)
    done = facet_command(*row.command(tmp_path))
    assert "Traceback" not in done.stderr, done.stderr
    if row.works:
        assert done.returncode == 0, done.stderr
        for path in _outputs(row, tmp_path):
            text = Path(path).read_text()
            assert not re.search(r"\b(nan|inf)\b", text, re.IGNORECASE), path
        return
    assert done.returncode == 2, (done.stdout, done.stderr)
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, done.stderr
    assert lines[0].startswith("facet: error: "), lines[0]
    for part in row.expected(tmp_path):
        assert part in lines[0], (part, lines[0])
    for path in _outputs(row, tmp_path):
        assert not os.path.exists(path), f"{path} written despite the error"


def _panel_options(argv):
    """The facet.cli_panels.run_pipeline options of a ``panels`` command line."""
    args = cli.build_parser().parse_args(argv)
    return dict(thickness=args.thickness, gap=args.gap, sheet=args.sheet, margin=args.margin)


def _python(row, folder):
    """Do with the Python API what the row's command line does; return vertex arrays."""
    argv = row.command(folder)
    command = argv[0]
    if command in ("check", "planarize"):
        mesh = facet.read_mesh(argv[1])
        if command == "check":
            return [facet.planarity(mesh).max_abs]
        return [facet.planarize(mesh).mesh.vertices]
    if command == "lift":
        from facet.plan import read_targets

        plan = facet.read_plan(argv[1])
        targets, weights = read_targets(plan, argv[argv.index("--targets") + 1])
        return [facet.lift(plan, targets, weights).mesh.vertices]
    if command == "panels":
        from facet.cli_panels import run_pipeline

        mesh = facet.read_mesh(argv[1])
        options = _panel_options(argv)
        thickness = options.pop("thickness")
        _report, ps, _drawings, _result = run_pipeline(mesh, thickness, **options)
        return [p.top for p in ps.panels] + [p.bottom for p in ps.panels]
    raise AssertionError(f"no Python call for {command}")


@pytest.mark.parametrize("name", list(ROWS))
def test_python_api(name, tmp_path):
    row = ROWS[name]
    row.write(tmp_path)
    if row.works:
        for array in _python(row, tmp_path):
            assert np.all(np.isfinite(np.asarray(array, dtype=float)))
        return
    with pytest.raises(InputError) as caught:
        _python(row, tmp_path)
    message = str(caught.value)
    assert "\n" not in message
    for part in row.expected(tmp_path):
        assert part in message, (part, message)


def test_georeferenced_result_stays_in_place(tmp_path):
    """The georeferenced row must not only succeed: the planar result stays within
    a small fraction of a panel of the input (normalization inside the solver)."""
    for name in ("georeferenced_coordinates_obj", "tiny_coordinates_obj",
                 "huge_coordinates_obj"):
        row = ROWS[name]
        folder = tmp_path / name
        row.write(folder)
        mesh = facet.read_mesh(folder / row.mesh)
        result = facet.planarize(mesh)
        edge = float(np.linalg.norm(mesh.vertices[1] - mesh.vertices[0]))
        moved = float(np.abs(result.mesh.vertices - mesh.vertices).max())
        assert moved < 0.2 * edge, (name, moved, edge)
        assert result.planarity.max_rel.max() <= 1e-5, name


def test_catalogue_document_lists_every_row():
    """docs/bad-input.md has one table row per catalogue row, naming its tests."""
    text = (ROOT / "docs" / "bad-input.md").read_text(encoding="utf-8")
    missing = [name for name in ROWS if f"`{name}`" not in text]
    assert not missing, f"rows missing from docs/bad-input.md: {missing}"
    documented = set(re.findall(r"^\| `([a-z0-9_]+)` \|", text, re.MULTILINE))
    extra = documented - set(ROWS)
    assert not extra, f"docs/bad-input.md lists rows with no test: {sorted(extra)}"


def test_coordinates_too_far_from_the_origin_for_the_panels_are_named():
    """At 1e12 model units a unit panel keeps about 1e-4 of its size in float64: the solve
    reaches its tolerance in its centred coordinates, the result cannot hold it, and the
    result says so (it said nothing); at 2.6e6 (georeferenced) it holds and says nothing."""
    rng = np.random.default_rng(0)
    vertices = np.array([[i, j, 0.1 * rng.standard_normal()] for j in range(5) for i in range(5)])
    faces = [[5 * j + i, 5 * j + i + 1, 5 * (j + 1) + i + 1, 5 * (j + 1) + i]
             for j in range(4) for i in range(4)]
    near = facet.planarize(facet.PolyMesh.from_faces(vertices + 2.6e6, faces), threads=1)
    assert near.converged and near.planarity.max_rel_all <= 1e-6 and not near.warnings
    far = facet.planarize(facet.PolyMesh.from_faces(vertices + 1e12, faces), threads=1)
    assert far.converged and far.planarity.max_rel_all > 1e-5
    assert any("move the model near the origin" in w and "1e+12" in w for w in far.warnings)
