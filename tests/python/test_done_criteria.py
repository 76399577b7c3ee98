# SPDX-License-Identifier: LGPL-2.1-or-later
"""The first milestone's done criteria, measured independently of the core.

- The libigl tube (tubemesh.off), planarized with default settings, has every
  face within 1e-6 of planar relative to the face's mean edge length, through
  the Python API and through the command line.
- A mesh that is planar already up to file rounding (DOS conical1.obj) moves by
  less than 1e-3 of its mean edge length.
"""

import json

import numpy as np
import pytest

import facet


def planarity_by_numpy(mesh):
    """Largest distance from the best-fit plane over mean edge length, per face."""
    relative = []
    for face in mesh.faces():
        points = mesh.vertices[face]
        centred = points - points.mean(axis=0)
        normal = np.linalg.svd(centred)[2][-1]
        distance = np.abs(centred @ normal).max()
        edges = np.linalg.norm(points - np.roll(points, -1, axis=0), axis=1)
        relative.append(distance / edges.mean())
    return np.array(relative)


@pytest.fixture
def tube(data_dir):
    return facet.read_mesh(data_dir / "tubemesh.off")


def test_numpy_measure_agrees_with_the_core(tube):
    core = facet.planarity(tube).max_rel
    assert np.allclose(planarity_by_numpy(tube), core, rtol=1e-9, atol=1e-12)


def test_tube_planarized_by_the_api(tube):
    before = planarity_by_numpy(tube).max()
    assert before > 1e-2  # the input is far from planar
    result = facet.planarize(tube)
    assert result.converged
    assert result.stop_reason == "tolerance"
    assert result.planarity.max_rel_all <= 1e-6
    assert planarity_by_numpy(result.mesh).max() <= 1e-6 * (1 + 1e-9)
    assert result.mesh.same_topology(tube)
    assert np.isfinite(result.mesh.vertices).all()
    moved = np.linalg.norm(result.mesh.vertices - tube.vertices, axis=1)
    assert result.displacement_max == pytest.approx(moved.max(), rel=1e-12)
    assert result.displacement_rms == pytest.approx(np.sqrt(np.mean(moved**2)), rel=1e-12)
    # the input mesh is left alone
    assert planarity_by_numpy(tube).max() == before


def test_tube_planarized_by_the_command_line(tube, data_dir, tmp_path, facet_command):
    output, report_path = tmp_path / "tube_planar.obj", tmp_path / "tube.json"
    done = facet_command(
        "planarize", data_dir / "tubemesh.off", "-o", output, "--report", report_path
    )
    assert done.returncode == 0, done.stderr
    report = json.loads(report_path.read_text())
    assert report["planarity_max_rel"] <= 1e-6
    assert report["converged"] is True
    assert report["input_planarity_max_rel"] > 1e-2
    text = output.read_text()
    assert "nan" not in text.lower() and "inf" not in text.lower()
    written = facet.read_mesh(output)
    assert planarity_by_numpy(written).max() <= 1e-6 * (1 + 1e-9)
    assert written.faces() == tube.faces()
    # the file holds exactly the vertices the solver gives (round trip is bit-exact)
    in_process = facet.planarize(tube)
    assert written.vertices.tobytes() == in_process.mesh.vertices.tobytes()


def test_nearly_planar_mesh_barely_moves(data_dir):
    mesh = facet.read_mesh(data_dir / "conical1.obj")
    result = facet.planarize(mesh)
    assert result.planarity.max_rel_all <= 1e-6
    moved = np.linalg.norm(result.mesh.vertices - mesh.vertices, axis=1).max()
    assert moved == pytest.approx(result.displacement_max, rel=1e-12)
    assert result.displacement_max / mesh.mean_edge_length() < 1e-3
