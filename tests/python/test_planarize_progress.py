# SPDX-License-Identifier: LGPL-2.1-or-later
"""Progress across the quality re-solves (facet.h: facet_progress_fn and
facet_planarizer_stage; facet.Planarizer.solve's ``progress`` and ``stage``).

A solve that re-solves for panel quality reads as one solve to its
``progress`` callable: the iteration counts on to the result's iterations,
the bound never grows (a bar never runs backwards), and ``stage(k, n)`` says
when the k-th re-solve starts. The 8 x 8 hypar with ``quality_angle=40``
re-solves in every stage (none keeps its corners above 40 degrees)."""

import hashlib
import os
import sys

import numpy as np
import pytest

import facet

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tools", "bench"))
import families  # noqa: E402


def _hypar(n):
    b = families.hypar(n)
    return facet.PolyMesh(b.vertices, b.face_start, b.face_vertices)


def _solve(mesh, **options):
    """The result and every call, in order: ("progress", iteration, max_iter) and
    ("stage", stage, stages). L/G unless `method` is given (method auto's comparison
    solve: test_planarize_compare.py)."""
    options.setdefault("method", "lg")
    events = []

    def progress(iteration, max_iter, planarity):
        assert np.isfinite(planarity)
        events.append(("progress", iteration, max_iter))

    def stage(k, n):
        events.append(("stage", k, n))

    result = facet.planarize(mesh, threads=1, progress=progress, stage=stage, **options)
    return result, events


def _digest(result):
    return hashlib.sha1(np.ascontiguousarray(result.mesh.vertices).tobytes()).hexdigest()


def _check_one_solve(result, events, stages):
    calls = [e for e in events if e[0] == "progress"]
    iterations = [e[1] for e in calls]
    bounds = [e[2] for e in calls]
    assert iterations == list(range(1, result.iterations + 1))
    assert all(b >= i for i, b in zip(iterations, bounds))
    assert all(b1 <= b0 for b0, b1 in zip(bounds, bounds[1:]))
    fractions = [i / b for i, b in zip(iterations, bounds)]
    assert all(f1 >= f0 for f0, f1 in zip(fractions, fractions[1:]))
    said = [e for e in events if e[0] == "stage"]
    assert said == [("stage", k, stages) for k in range(1, result.quality_resolves + 1)]
    # each stage is said just before the first iteration of its re-solve
    first = events.index(said[0])
    assert len([e for e in events[:first] if e[0] == "progress"]) == result.first_iterations
    assert events[first + 1][0] == "progress"


def test_progress_counts_through_all_four_stages():
    mesh = _hypar(8)
    plain = facet.planarize(mesh, method="lg", threads=1, quality_angle=40.0)
    result, events = _solve(mesh, quality_angle=40.0)
    assert result.quality_resolves == 4 and result.quality_check == "narrow"
    _check_one_solve(result, events, 4)
    # the bound of the first solve: its 1000 and the four stages' 1000, 1000, 4000, 1000
    assert events[0] == ("progress", 1, 8000)
    # the plumbing changes no bit
    assert result.iterations == plain.iterations and _digest(result) == _digest(plain)


def test_sliding_data_has_five_stages():
    # the exact penalty path and the angle floor's recipe, then the vertices held more
    # firmly along the design: the default's schedule and the floor's recipe at three
    # times the preset's data_tangent, the floor's at ten times
    result, events = _solve(_hypar(8), quality_angle=40.0, data="plane")
    assert result.quality_resolves == 5 and result.quality_check == "narrow"
    assert result.data_tangent == 0.01  # none kept the corners: the first result
    _check_one_solve(result, events, 5)
    assert events[0] == ("progress", 1, 1000 + 4000 + 1000 + 1000 + 1000 + 1000)


def test_a_firmer_stage_that_would_repeat_one_is_skipped():
    # data_tangent 0.5 of data_normal 1: held three times or ten times as firmly is
    # held as firmly as across the design (1.0) either way, so the floor's recipe at
    # ten times would repeat the one at three times: four stages
    result, events = _solve(_hypar(8), quality_angle=40.0, data_tangent=0.5)
    assert result.quality_resolves == 4
    _check_one_solve(result, events, 4)
    assert events[0] == ("progress", 1, 1000 + 4000 + 1000 + 1000 + 1000)


def test_no_resolve_no_stage():
    result, events = _solve(_hypar(8), quality_angle=0.0, max_iter=700)
    assert all(e[0] == "progress" and e[2] == 700 for e in events)
    assert [e[1] for e in events] == list(range(1, result.iterations + 1))


def test_cancel_in_a_resolve():
    mesh = _hypar(8)
    seen = []

    def progress(iteration, max_iter, planarity):
        return bool(seen) and seen[-1] == 2

    with pytest.raises(facet.Cancelled):
        facet.planarize(mesh, quality_angle=40.0, threads=1, progress=progress,
                        stage=lambda k, n: seen.append(k))
    assert seen == [1, 2]


def test_stage_errors():
    mesh = _hypar(8)

    def boom(k, n):
        raise RuntimeError(f"stage {k} of {n}")

    with pytest.raises(RuntimeError, match="stage 1 of 4"):
        facet.planarize(mesh, quality_angle=40.0, threads=1, stage=boom)
    with pytest.raises(TypeError, match="stage must be callable"):
        facet.planarize(mesh, stage=3)
    # the Planarizer keeps working after either
    assert facet.Planarizer(mesh).solve(quality_angle=0.0).converged


def test_cli_progress_line():
    import io

    from facet.cli_progress import ProgressLine

    out = io.StringIO()
    quiet = ProgressLine(out)  # not a terminal: nothing
    assert not quiet.enabled
    quiet.progress(1, 10, 0.5)
    assert out.getvalue() == ""
    line = ProgressLine(out, interval=0.0, force=True)
    result = facet.planarize(_hypar(8), quality_angle=40.0, threads=1, progress=line.progress,
                             stage=line.stage)
    line.close()
    shown = out.getvalue().split("\r")
    # method auto: 1000 for L/G, 7000 for its four re-solves, 1000 for L/L's comparison
    # and 1000 for the finer L/G solve that may follow it
    assert "facet planarize: iteration 1 of at most 10000, planarity" in shown[1]
    resolving = [s for s in shown if "re-solving for panel quality (stage 4 of 4): iteration" in s]
    comparing = [s for s in shown if "solving by local/local too, for a result closer to the "
                 "design: iteration" in s]
    assert resolving and comparing and result.compared["iterations"] > 0
    assert f"iteration {result.iterations - result.compared['iterations']} of at most" in resolving[-1]
    assert f"iteration {result.iterations} of at most" in comparing[-1]
    assert shown[-1] == "" and shown[-2].strip() == ""  # erased at the end
    assert not any("stage" in s for s in shown[:result.first_iterations + 1])


def test_cli_progress_line_names_the_finer_solve():
    import io

    from facet.cli_progress import ProgressLine

    out = io.StringIO()
    line = ProgressLine(out, interval=0.0, force=True)
    demo = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "wave_facade.obj")
    result = facet.planarize(facet.read_mesh(demo), threads=1, progress=line.progress,
                             stage=line.stage)
    line.close()
    shown = out.getvalue().split("\r")
    finer = [s for s in shown if "solving by local/global again with a finer hold, closer to the "
             "design: iteration" in s]
    assert len(finer) == result.compared["finer"]["iterations"] > 0
    assert f"iteration {result.iterations} of at most" in finer[-1]


def test_cli_planarize_prints_no_progress_to_a_pipe(tmp_path):
    """Into a pipe: no progress line; the summary says how many re-solves ran."""
    import subprocess

    mesh = _hypar(32)
    path = tmp_path / "hypar32.obj"
    facet.write_mesh(mesh, str(path))
    run = subprocess.run([sys.executable, "-m", "facet", "planarize", str(path), "-o",
                          str(tmp_path / "out.obj"), "--threads", "1"], capture_output=True,
                         text=True,
                         env=dict(os.environ, PYTHONPATH=os.path.dirname(facet.__path__[0])))
    assert run.returncode == 0, run.stderr
    assert "\r" not in run.stderr and "iteration" not in run.stderr
    expected = facet.planarize(facet.read_mesh(str(path)), threads=1)
    if expected.quality_resolves:
        assert (f"re-solves     {expected.quality_resolves} for panel quality after the first "
                f"solve's {expected.first_iterations} iterations") in run.stdout
    else:
        assert "re-solves" not in run.stdout
