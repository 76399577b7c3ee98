# SPDX-License-Identifier: LGPL-2.1-or-later
"""The benchmark meshes (tools/bench/families.py): counts, validity, determinism."""

import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools" / "bench"))

import families  # noqa: E402
from facet import PolyMesh  # noqa: E402


def edge_counts(mesh):
    """(undirected edge -> number of faces, directed edge -> number of faces)."""
    undirected, directed = {}, {}
    for face in mesh.faces():
        for a, b in zip(face, face[1:] + face[:1]):
            directed[(a, b)] = directed.get((a, b), 0) + 1
            key = (min(a, b), max(a, b))
            undirected[key] = undirected.get(key, 0) + 1
    return undirected, directed


def check_manifold(mesh):
    undirected, directed = edge_counts(mesh)
    assert max(undirected.values()) <= 2, f"{mesh.name}: an edge has more than two faces"
    assert max(directed.values()) == 1, f"{mesh.name}: faces are not consistently oriented"
    used = np.bincount(mesh.face_vertices, minlength=mesh.n_vertices)
    assert used.min() >= 1, f"{mesh.name}: a vertex is used by no face"
    return undirected


@pytest.mark.parametrize(
    "level, faces, vertices",
    [(1, 12, 20), (2, 48, 63), (3, 192, 221), (4, 768, 825), (5, 3072, 3185)],
)
def test_levels_have_the_papers_face_counts(level, faces, vertices):
    mesh = families.level_patch(level)
    assert mesh.n_faces == faces
    assert mesh.n_vertices == vertices
    undirected = check_manifold(mesh)
    # an open disk: V - E + F = 1
    assert mesh.n_vertices - len(undirected) + mesh.n_faces == 1
    assert (np.diff(mesh.face_start) == 4).all()


def test_level_6_and_paper_table():
    assert families.level_patch(6).n_faces == 12_288
    table = {row[0]: row[1] for row in families.PAPER_TABLE1}
    assert table["Level 5"] == families.level_patch(5).n_faces


def test_catmull_clark_keeps_corners_and_boundary_midpoints():
    # a flat 2 x 2 grid: refinement stays flat, corners stay, faces quadruple
    v = np.array([[x, y, 0.0] for y in range(3) for x in range(3)], dtype=float)
    faces = np.array([[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]])
    nv, nf = families.catmull_clark(v, faces)
    assert nf.shape == (16, 4)
    assert nv.shape == (9 + 12 + 4, 3)
    assert np.allclose(nv[:, 2], 0.0)
    for corner in (0, 2, 6, 8):
        assert np.allclose(nv[corner], v[corner])
    # the centre of a regular grid stays put
    assert np.allclose(nv[4], v[4])


@pytest.mark.parametrize("name, a, b", [("Torus1", 45, 24), ("Torus2", 54, 36)])
def test_hex_tori_have_the_papers_counts(name, a, b):
    mesh = families.hex_torus(a, b, name=name)
    paper = {row[0]: row for row in families.PAPER_TABLE1}[name]
    assert (mesh.n_faces, mesh.n_vertices) == (paper[1], paper[2])
    assert (np.diff(mesh.face_start) == 6).all()
    undirected = check_manifold(mesh)
    assert min(edge_counts(mesh)[0].values()) == 2  # closed
    assert mesh.n_vertices - len(undirected) + mesh.n_faces == 0  # torus
    assert (np.bincount(mesh.face_vertices) == 3).all()  # valence 3


def test_hex_torus_rejects_odd_b():
    with pytest.raises(ValueError, match="even b"):
        families.hex_torus(10, 5)


def test_quad_torus_grid_hypar():
    torus = families.quad_torus(20, 10)
    assert (torus.n_faces, torus.n_vertices) == (200, 200)
    assert min(check_manifold(torus).values()) == 2
    grid = families.quad_grid(30, 20)
    assert (grid.n_faces, grid.n_vertices) == (600, 651)
    check_manifold(grid)
    hyp = families.hypar(8)
    assert hyp.n_faces == 64
    check_manifold(hyp)
    assert np.allclose(hyp.vertices[:, 2], hyp.vertices[:, 0] * hyp.vertices[:, 1])


def test_specs_cover_the_families_and_cap_sizes():
    specs = families.family_specs()
    names = {s["family"] for s in specs}
    assert names == {"level", "hex_torus", "quad_grid", "quad_torus", "hypar"}
    assert max(s["faces"] for s in specs) == 1_000_000
    assert max(s["faces"] for s in specs if s["family"] == "hex_torus") >= 100_000
    small = families.family_specs(max_faces=5_000)
    assert max(s["faces"] for s in small) <= 5_000
    assert [s["faces"] for s in small] == sorted(s["faces"] for s in small)


def test_generated_meshes_are_valid_and_not_planar():
    from facet.planarity import planarity

    for spec in families.family_specs(max_faces=12_288):
        mesh = families.generate(spec)
        assert mesh.n_faces == spec["faces"]
        poly = PolyMesh(mesh.vertices, mesh.face_start, mesh.face_vertices)
        poly.validate()
        assert np.isfinite(mesh.vertices).all()
        report = planarity(poly)
        assert report.max_rel_all > 1e-3, f"{mesh.name} is already planar"


def test_generation_is_deterministic():
    for spec in families.family_specs(max_faces=2_000):
        a, b = families.generate(spec), families.generate(spec)
        assert np.array_equal(a.vertices, b.vertices), spec["name"]
        assert np.array_equal(a.face_vertices, b.face_vertices)


def test_perturbation_is_seeded_and_scaled():
    mesh = families.quad_grid(10, 10, noise=0.0)
    v, faces = mesh.vertices, mesh.face_vertices.reshape(-1, 4)
    p1 = families.perturb(v, faces, 0.05, seed=7)
    p2 = families.perturb(v, faces, 0.05, seed=7)
    p3 = families.perturb(v, faces, 0.05, seed=8)
    assert np.array_equal(p1, p2)
    assert not np.array_equal(p1, p3)
    h = families._mean_edge_length(v, faces)
    assert np.abs(p1 - v).max() <= 0.05 * h * (1 + 1e-12)
    assert np.abs(p1 - v).max() > 0.01 * h


def test_public_meshes_from_tests_data_only():
    specs, notes = families.public_meshes(include_shared=False)
    names = {s["name"] for s in specs}
    assert {"hypar.obj", "tubemesh.off", "conical1.obj"} <= names
    assert not any(n.startswith("bad_") for n in names)
    assert any("funicular.obj" in n and "no faces" in n for n in notes)


def test_public_meshes_absent_shared_folder_is_skipped(tmp_path):
    specs, notes = families.public_meshes(shared_root=tmp_path / "absent")
    assert all(s["source"] == "tests/data" for s in specs)
    assert any("absent" in n for n in notes)
