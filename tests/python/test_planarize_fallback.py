# SPDX-License-Identifier: LGPL-2.1-or-later
"""Method auto's fallback (facet.h, FACET_STAGE_FALLBACK): above 10,000 quads auto
solves by local/local, which on a flat facade with a local saddle stalls above the
tolerance or leaves a panel closed; auto then solves by local/global and returns
that result. Through the Python API: the result, the stage callback, the CLI's
progress text."""

import io
import math

import numpy as np
import pytest

import facet
from facet.cli_progress import ProgressLine
from facet.planarize import STAGE_FALLBACK


def _saddle(n, r, amplitude):
    """n x n unit quads, flat but for a saddle of radius r in the middle
    (libcore/tests/test_meshes.h, test_saddle)."""
    c = 0.5 * n
    y, x = np.meshgrid(np.arange(n + 1, dtype=float), np.arange(n + 1, dtype=float), indexing="ij")
    d2 = (x - c) ** 2 + (y - c) ** 2
    # math.exp, the C library's, as test_meshes.h (numpy's own exp may differ in
    # the last bit, and the outcome of local/local here is chaotic in the bits)
    e = np.array([math.exp(t) for t in (-d2 / (r * r)).ravel()]).reshape(d2.shape)
    z = amplitude * (x - c) * (y - c) / r * e
    vertices = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    j, i = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    v = (j * (n + 1) + i).ravel()
    faces = np.stack([v, v + 1, v + n + 2, v + n + 1], axis=1).ravel()
    return facet.PolyMesh(vertices, np.arange(0, 4 * n * n + 1, 4), faces)


def test_saddle_falls_back_on_local_global():
    mesh = _saddle(101, 8.0, 0.4)
    alone = facet.planarize(mesh, method="ll", threads=1)
    assert not alone.converged  # local/local stalls above the tolerance here
    stages = []
    result = facet.planarize(mesh, threads=1, stage=lambda k, n: stages.append(k))
    assert result.method == "lg"
    assert result.converged and result.planarity.max_rel_all <= 1e-6
    assert result.quality_check == "recovered"
    assert np.min(result.quality.min_angle) > 5.0
    assert stages and stages[-1] == STAGE_FALLBACK
    assert np.all(np.isfinite(result.mesh.vertices))
    # the source mesh is not touched
    assert np.array_equal(mesh.vertices, _saddle(101, 8.0, 0.4).vertices)


def test_cli_progress_names_the_fallback():
    out = io.StringIO()
    progress = ProgressLine(out=out, force=True)
    progress.stage(STAGE_FALLBACK, 4)
    assert "local/global" in progress.stage_text and "closed a panel" in progress.stage_text


def test_cancelled_in_the_fallback_after_a_stall_keeps_nothing():
    # local/local stalled short of the tolerance: no result is worth keeping
    mesh = _saddle(101, 8.0, 0.4)
    stages = []
    with pytest.raises(facet.Cancelled) as stopped:
        facet.planarize(mesh, threads=1, stage=lambda k, n: stages.append(k),
                        progress=lambda iteration, max_iter, rel: bool(stages))
    assert stages == [STAGE_FALLBACK]
    assert stopped.value.result is None


def test_stopped_in_the_fallback_keeps_the_local_local_result():
    # local/local reached the tolerance with a closed panel (its re-solves did not open
    # it): stopped in the fallback, that result is the one kept
    mesh = _saddle(101, 10.0, 0.15)
    stages = []
    with pytest.raises(facet.Cancelled) as stopped:
        facet.planarize(mesh, threads=1, stage=lambda k, n: stages.append(k),
                        progress=lambda i, n, rel: bool(stages) and stages[-1] == STAGE_FALLBACK)
    assert stages[-1] == STAGE_FALLBACK and len(stages) > 1
    kept = stopped.value.result
    alone = facet.planarize(mesh, threads=1, method="ll")
    assert alone.quality_check == "narrow"
    assert kept is not None and kept.stopped and kept.method == "ll"
    assert (kept.stop_reason, kept.quality_check) == ("tolerance", "narrow")
    assert np.array_equal(kept.mesh.vertices, alone.mesh.vertices)


def test_a_stalled_result_counts_its_narrow_corners():
    # local/local alone stalls above the tolerance here with a corner under 5 degrees:
    # not re-solved, but counted and said
    mesh = _saddle(101, 8.0, 0.4)
    stalled = facet.planarize(mesh, method="ll", threads=1)
    assert not stalled.converged and stalled.quality_check == "not_checked"
    new = (stalled.quality.min_angle < 5.0) & (stalled.quality.input_min_angle >= 5.0)
    assert stalled.narrow_corners > 0 and np.any(new)
    assert [w for w in stalled.warnings if "stopped short of the tolerance" in w]
    # with the check off, nothing is counted
    assert facet.planarize(mesh, method="ll", threads=1, quality_angle=0.0).narrow_corners == 0
