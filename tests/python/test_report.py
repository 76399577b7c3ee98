# SPDX-License-Identifier: LGPL-2.1-or-later
"""JSON reports of planarization and checks."""

import json
import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

import facet
from facet.report import check_report, json_safe, planarize_report, write_json

PLANARIZE_KEYS = {
    "faces", "vertices", "iterations", "solve_seconds", "planarity_max_rel", "planarity_max_abs",
    "planarity_rms_rel", "displacement_rms", "displacement_max", "method", "stop_reason",
    "converged", "tol", "input_planarity_max_rel", "input_planarity_max_abs",
}


def test_json_safe_converts_numpy_paths_and_non_finite():
    value = {
        1: np.float64(0.5),
        "n": np.int32(7),
        "flag": np.bool_(True),
        "nan": float("nan"),
        "inf": np.float64(np.inf),
        "array": np.array([[1.0, np.nan], [2.0, -np.inf]]),
        "pair": (np.int64(3), 4),
        "path": Path("a") / "b.obj",
        "none": None,
    }
    safe = json_safe(value)
    assert safe == {
        "1": 0.5, "n": 7, "flag": True, "nan": None, "inf": None,
        "array": [[1.0, None], [2.0, None]], "pair": [3, 4], "path": str(Path("a") / "b.obj"),
        "none": None,
    }
    assert type(safe["n"]) is int and type(safe["flag"]) is bool
    json.dumps(safe, allow_nan=False)


def test_write_json_never_writes_nan(tmp_path):
    path = tmp_path / "r.json"
    write_json({"planarity_max_rel": float("nan"), "faces": 3}, path)
    text = path.read_text()
    assert "NaN" not in text and "nan" not in text.lower().replace("null", "")
    assert json.loads(text) == {"planarity_max_rel": None, "faces": 3}


def test_check_report_of_the_tube(data_dir):
    mesh = facet.read_mesh(data_dir / "tubemesh.off")
    report = check_report(mesh, facet.planarity(mesh), mesh.validate(), path="tubemesh.off")
    assert report["input"] == "tubemesh.off"
    assert (report["faces"], report["vertices"], report["edges"]) == (171, 200, 370)
    assert report["boundary_edges"] == 56
    assert report["face_degrees"] == {"4": 171}
    assert report["bounds"]["min"] == mesh.vertices.min(axis=0).tolist()
    assert 0.0 < report["planarity_max_rel"] < 1.0
    assert report["planarity_max_abs"] == pytest.approx(
        report["planarity_max_rel"] * facet.planarity(mesh).mean_edge[report["worst_face"]]
    )
    assert report["source_format"] == "off"
    json.dumps(report, allow_nan=False)


def test_check_report_records_openings(data_dir):
    mesh = facet.read_mesh(data_dir / "examples_cross_vault_6.json")
    report = check_report(mesh, facet.planarity(mesh), mesh.validate())
    assert report["source_openings_skipped"] == 4
    assert report["source_item"] == "ThrustDiagram"
    assert report["face_degrees"] == {"3": 40, "4": 80}


def fake_result(mesh, displacement):
    planar = facet.planarity(mesh)
    return SimpleNamespace(
        mesh=mesh, method="lg", iterations=12, stop_reason="max_iter", converged=False,
        solve_seconds=0.5, planarity=planar, displacement=displacement,
        displacement_rms=float(np.sqrt(np.mean(displacement**2))),
        displacement_max=float(displacement.max()), options={"tol_rel": 1e-6, "max_iter": 12},
        warnings=["2 isolated vertices"],
    )


def test_planarize_report_from_any_result(data_dir):
    mesh = facet.read_mesh(data_dir / "hypar.obj")
    displacement = np.full(mesh.n_vertices, 0.25)
    report = planarize_report(mesh, fake_result(mesh, displacement), "in.obj", Path("out.obj"))
    assert PLANARIZE_KEYS <= set(report)
    assert report["input"] == "in.obj" and report["output"] == "out.obj"
    assert report["tol"] == 1e-6 and report["max_iter"] == 12
    assert report["converged"] is False and report["stop_reason"] == "max_iter"
    assert report["displacement_max_rel"] == pytest.approx(0.25 / mesh.mean_edge_length())
    assert report["warnings"] == ["2 isolated vertices"]
    json.dumps(report, allow_nan=False)


def test_planarize_report_turns_nan_into_null(data_dir):
    mesh = facet.read_mesh(data_dir / "hypar.obj")
    result = fake_result(mesh, np.zeros(mesh.n_vertices))
    result.displacement_max = float("nan")
    report = planarize_report(mesh, result)
    assert report["displacement_max"] is None
    assert report["displacement_max_rel"] is None
    json.dumps(report, allow_nan=False)


def test_planarize_report_of_a_real_solve(data_dir):
    mesh = facet.read_mesh(data_dir / "tubemesh.off")
    result = facet.planarize(mesh)
    report = planarize_report(mesh, result, input_path="tubemesh.off", output_path="o.obj")
    assert PLANARIZE_KEYS <= set(report)
    assert report["planarity_max_rel"] == result.planarity.max_rel_all
    assert report["input_planarity_max_rel"] == facet.planarity(mesh).max_rel_all
    assert report["input_planarity_max_rel"] > 100 * report["planarity_max_rel"]
    assert report["iterations"] == result.iterations > 0
    assert report["method"] == result.method  # method auto's pick: test_planarize_compare.py
    assert report["compared"] == result.compared and report["compared"]["iterations"] > 0
    assert all(math.isfinite(report[key]) for key in ("displacement_rms", "solve_seconds"))
