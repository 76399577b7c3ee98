# SPDX-License-Identifier: LGPL-2.1-or-later
"""The large-mesh default: method "auto" (L/G on small meshes, compared with
L/L, L/L above 40,000 face corners) and L/L's finish, through
facet.planarize and the command line. The comparison's rule:
test_planarize_compare.py."""

import json
import math
import os

import numpy as np
import pytest

import facet
from facet import _core
from facet.planarize import METHODS


def grid(n, seed=7):
    """An n x n quad grid on a doubly curved height field, jittered."""
    i, j = np.meshgrid(np.arange(n + 1, dtype=float), np.arange(n + 1, dtype=float), indexing="xy")
    x, y = i.ravel(), j.ravel()
    z = 0.15 * n * np.sin(2.5 * x / n) * np.cos(2.0 * y / n)
    z += 0.05 * np.random.default_rng(seed).uniform(-1.0, 1.0, z.shape)
    a = (np.arange(n)[None, :] + (n + 1) * np.arange(n)[:, None]).ravel()
    faces = np.stack([a, a + 1, a + n + 2, a + n + 1], axis=1)
    return facet.PolyMesh.from_faces(np.stack([x, y, z], axis=1), faces.tolist())


def test_auto_is_the_default_and_solves_by_lg_and_ll_on_small_meshes(data_dir):
    tube = facet.read_mesh(data_dir / "tubemesh.off")
    result = facet.planarize(tube)
    assert result.options["method"] == "auto"
    assert result.converged and result.planarity.max_rel_all <= 1e-6
    lg = facet.planarize(tube, method="lg")
    ll = facet.planarize(tube, method="ll", quality_angle=0)  # the comparison's one L/L solve
    # L/G with L/G's defaults, then L/L: the bits of the one returned
    assert result.iterations == lg.iterations + ll.iterations
    assert result.compared["iterations"] == ll.iterations
    assert result.method == "ll"  # tubemesh: L/L's result is closer, as wide
    assert np.array_equal(result.mesh.vertices, ll.mesh.vertices)


def test_auto_picks_ll_above_the_threshold():
    assert _core.AUTO_LG_MAX_CORNERS == 40_000  # 10,000 quads, as the docs say
    largest = math.isqrt(_core.AUTO_LG_MAX_CORNERS // 4)  # 100 x 100 quads: the last L/G mesh
    result = facet.planarize(grid(largest + 1), iterations=2)
    assert result.method == "ll"
    at_limit = facet.planarize(grid(largest), iterations=2)
    assert at_limit.method == "lg"


@pytest.mark.parametrize("terms", [dict(data="plane"), dict(laplacian=0.1), dict(hold_tol=0.0)])
def test_auto_above_the_threshold_with_terms(terms):
    """L/L finishes with every term (plane data carries a shape term), so auto takes it above
    40,000 corners whatever the terms; not without the staircase (hold_tol 0), with which
    L/L cannot finish: L/G up to 200,000 corners (facet.h,
    FACET_AUTO_LG_MAX_CORNERS_STAIRCASE)."""
    mesh = grid(math.isqrt(_core.AUTO_LG_MAX_CORNERS // 4) + 1)
    result = facet.planarize(mesh, iterations=2, **terms)
    assert result.method == ("lg" if terms.get("hold_tol") == 0.0 else "ll")


def test_ll_default_reaches_the_tolerance():
    mesh = grid(60)  # 3,600 quads: L/L stalled near 1e-5 before its finish
    result = facet.planarize(mesh, method="ll")
    assert result.method == "ll"
    assert result.converged, result.stop_reason
    assert result.stop_reason == "tolerance"
    assert result.planarity.max_rel_all <= 1e-6
    # no panel collapses and the result stays near the design surface
    quality = result.quality.as_dict()
    assert quality["min_angle_deg"] > 5.0
    _, distance, _, _ = facet.Surface(mesh).closest(result.mesh.vertices)
    assert np.sqrt(np.mean(distance**2)) < 0.05 * mesh.mean_edge_length()


def test_unknown_method_names_the_choices():
    with pytest.raises(facet.FacetError, match="unknown method 'fast': use one of auto, lg, ll"):
        facet.planarize(grid(4), method="fast")
    assert list(METHODS) == ["auto", "lg", "ll"]


def test_command_line_auto(facet_command, data_dir, tmp_path):
    report_path = tmp_path / "r.json"
    done = facet_command(
        "planarize", data_dir / "tubemesh.off", "-o", tmp_path / "t.obj", "--method", "auto",
        "--report", report_path,
    )
    assert done.returncode == 0, done.stderr
    report = json.loads(report_path.read_text())
    assert report["method"] == "ll" and report["compared"]["iterations"] > 0
    assert report["stop_reason"] == "tolerance"
    assert "compared      local/local too (" in done.stdout and "kept ll's result" in done.stdout
    assert "finer hold" not in done.stdout and report["compared"]["finer"] is None
    bad = facet_command("planarize", data_dir / "tubemesh.off", "-o", tmp_path / "u.obj",
                        "--method", "fast")
    assert bad.returncode == 2
    assert "'auto', 'll', 'lg'" in bad.stderr


def test_ll_finish_after_a_stall_at_the_floor(data_dir):
    # hypar.obj's last level sits 4e-16 above the floor and stalls at 2.7e-6
    # before it settles: the finish must start there, not a stagnation stop
    hypar = facet.read_mesh(data_dir / "hypar.obj")
    result = facet.planarize(hypar, method="ll", threads=1)
    assert result.stop_reason == "tolerance"
    assert result.planarity.max_rel_all <= 1e-6


@pytest.mark.parametrize("name", ["cmc1.obj", "hypar.obj"])
def test_ll_finish_with_surface_data_is_not_held_by_the_surface(data_dir, name):
    """L/L's finish anchors the reference surface's pull at the iterate, as it anchors the
    data, shape and regularizer terms: with its target on the surface, at the floor's
    weight, it held the planarity at 1.1e-7 (cmc1) and 1.0e-6 (hypar.obj) and the solve
    stopped on stagnation above a tighter tolerance (on the 20,034-hex torus, at 2.1e-6
    above the default's 1e-6). The finish moves the vertices by about the residual, so the
    result stays as close to the surface."""
    mesh = facet.read_mesh(data_dir / name)
    for tol in (1e-6, 1e-10):
        result = facet.planarize(mesh, data="surface", method="ll", tol=tol, threads=1,
                                 quality_angle=0)
        assert result.stop_reason == "tolerance", (tol, result.planarity.max_rel_all)
        assert result.planarity.max_rel_all <= tol
        if tol == 1e-6:
            at_default = result
    _, d6, _, _ = facet.Surface(mesh).closest(at_default.mesh.vertices)
    _, d10, _, _ = facet.Surface(mesh).closest(result.mesh.vertices)
    rms6, rms10 = np.sqrt(np.mean(d6**2)), np.sqrt(np.mean(d10**2))
    assert abs(rms10 - rms6) <= 0.01 * rms6 + 1e-6 * mesh.mean_edge_length()


def test_command_line_names_the_finer_solve(facet_command, tmp_path):
    # the demo facade: L/L's result refused for moving the vertices further, then L/G
    # with a finer hold, whose result is kept
    demo = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "wave_facade.obj")
    report_path = tmp_path / "r.json"
    done = facet_command("planarize", demo, "-o", tmp_path / "w.obj", "--report", report_path)
    assert done.returncode == 0, done.stderr
    finer = json.loads(report_path.read_text())["compared"]["finer"]
    assert finer["kept"] and finer["iterations"] > 0
    assert (f"; lg again with a finer hold ({finer['iterations']} iterations): its result kept"
            in done.stdout)
