# SPDX-License-Identifier: LGPL-2.1-or-later
"""The command line: summaries, reports, exit statuses, one-line errors."""

import json
import sys

import numpy as np
import pytest

import facet
from facet import cli
from facet.errors import Cancelled


def assert_one_line_error(done, *parts):
    """Exit status 2, one line on stderr naming every part, no traceback."""
    assert done.returncode == 2, (done.stdout, done.stderr)
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, done.stderr
    assert "Traceback" not in done.stderr
    for part in parts:
        assert part in lines[0], (part, lines[0])
    return lines[0]


def planarize_with_report(facet_command, tmp_path, *arguments):
    """Run ``facet planarize ... --report``: the finished process and its report."""
    report_path = tmp_path / "r.json"
    done = facet_command("planarize", *arguments, "--report", report_path)
    assert done.returncode == 0, done.stderr
    return done, json.loads(report_path.read_text())


def test_version(facet_command):
    done = facet_command("--version")
    assert done.returncode == 0
    assert done.stdout.strip() == f"facet {facet.__version__}"
    assert facet.__version__ == "0.1.0"


def test_planarize_prints_a_summary(facet_command, data_dir, tmp_path):
    output = tmp_path / "tube.off"
    done = facet_command("planarize", data_dir / "tubemesh.off", "-o", output)
    assert done.returncode == 0, done.stderr
    assert "200 vertices, 171 faces (171 quads)" in done.stdout
    assert "planarity" in done.stdout and "before" in done.stdout and "after" in done.stdout
    assert "tolerance reached" in done.stdout
    assert f"written       {output}" in done.stdout
    assert done.stderr == ""
    assert facet.read_mesh(output).n_faces == 171


def test_planarize_report_and_options(facet_command, data_dir, tmp_path):
    report_path = tmp_path / "r.json"
    done = facet_command(
        "planarize", data_dir / "hypar.obj", "-o", tmp_path / "h.obj", "--method", "ll",
        "--iterations", "3", "--threads", "1", "--report", report_path,
    )
    assert done.returncode == 0, done.stderr
    report = json.loads(report_path.read_text())
    assert report["method"] == "ll"
    assert report["iterations"] == 3
    assert report["stop_reason"] == "iterations"
    assert report["faces"] == 64 and report["vertices"] == 81
    assert "requested number of iterations done" in done.stdout
    assert "NaN" not in report_path.read_text()


def test_a_firmer_hold_is_said_and_reported(facet_command, data_dir, tmp_path):
    # heart.obj with plane data: every re-solve at the preset's data_tangent closes a
    # panel; the one that held the vertices more firmly along the design is returned,
    # and the summary and the report say with which weight
    done, report = planarize_with_report(facet_command, tmp_path, data_dir / "heart.obj", "-o",
                                         tmp_path / "h.obj", "--data", "plane", "--threads", "1")
    assert report["quality_check"] == "recovered" and report["narrow_corners"] == 0
    assert report["options"]["data_tangent"] == 0.01 and report["data_tangent"] == 0.03
    assert ("the last kept every corner open, holding the vertices more firmly along the "
            "design (data_tangent 0.03 instead of 0.01)") in done.stdout
    assert "warning" not in done.stdout


@pytest.mark.parametrize("check, options, used, says", [
    ("recovered", {"data_tangent": 0.01}, 0.03,
     "the last kept every corner open, holding the vertices more firmly along the design "
     "(data_tangent 0.03 instead of 0.01)"),
    ("recovered", {}, 3.0, "(data_tangent 3 instead of 1)"),  # the core's default asked
    ("recovered", {"data_tangent": 0.01}, 0.01, "the last kept every corner open\n"),
    ("ok", {}, 1.0, "then the comparison's result, with every corner open, was kept"),
    ("narrow", {}, 1.0, "none kept every corner open: the first solve's result"),
])
def test_the_resolves_line(capsys, data_dir, check, options, used, says):
    # the summary's re-solves line for each outcome, from a real report with its
    # quality figures set: "ok" after re-solves is method auto's comparison keeping
    # local/local's result
    from facet.report import planarize_report

    mesh = facet.read_mesh(data_dir / "hypar.obj")
    report = planarize_report(mesh, facet.planarize(mesh, threads=1), output_path="h.obj")
    report.update(quality_check=check, quality_resolves=2, data_tangent=used, options=options)
    cli.print_planarize_summary(report)
    out = capsys.readouterr().out
    assert "re-solves" in out and says in out, out


def test_thread_count_does_not_change_the_result(facet_command, data_dir, tmp_path):
    one, two = tmp_path / "one.obj", tmp_path / "two.obj"
    assert facet_command("planarize", data_dir / "tubemesh.off", "-o", one,
                         "--threads", "1").returncode == 0
    assert facet_command("planarize", data_dir / "tubemesh.off", "-o", two,
                         "--threads", "2").returncode == 0
    assert one.read_bytes() == two.read_bytes()


def test_absolute_tolerance(facet_command, data_dir, tmp_path):
    _done, report = planarize_with_report(facet_command, tmp_path, data_dir / "tubemesh.off",
                                          "-o", tmp_path / "t.obj", "--tol", "0",
                                          "--tol-abs", "1e-3")
    assert report["converged"] is True
    assert report["planarity_max_abs"] <= 1e-3
    assert report["planarity_max_rel"] > 1e-6  # the relative test was off


def test_not_converged_is_said_and_strict_fails(facet_command, data_dir, tmp_path):
    arguments = ["planarize", data_dir / "tubemesh.off", "-o", tmp_path / "t.obj",
                 "--max-iter", "2"]
    done = facet_command(*arguments)
    assert done.returncode == 0
    assert "not converged" in done.stderr
    assert "iteration limit reached" in done.stdout
    strict = facet_command(*arguments, "--strict")
    assert strict.returncode == 1
    assert "not converged" in strict.stderr


def test_check_prints_and_reports(facet_command, data_dir, tmp_path):
    report_path = tmp_path / "c.json"
    done = facet_command("check", data_dir / "examples_cross_vault_6.json", "--report",
                         report_path)
    assert done.returncode == 0, done.stderr
    assert "121 vertices, 120 faces (40 triangles, 80 quads)" in done.stdout
    assert "4 faces skipped" in done.stdout
    report = json.loads(report_path.read_text())
    assert report["edges"] == 240
    assert report["source_openings_skipped"] == 4
    assert report["planarity_max_rel"] > 0


def test_check_other_scene_item(facet_command, data_dir):
    done = facet_command("check", data_dir / "examples_cross_vault_6.json", "--item",
                         "FormDiagram")
    assert done.returncode == 0, done.stderr
    assert "scene item FormDiagram" in done.stdout


def test_missing_input_file(facet_command, tmp_path):
    missing = tmp_path / "absent.obj"
    done = facet_command("check", missing)
    assert_one_line_error(done, str(missing), "No such file")


def test_parse_error(facet_command, write_file, tmp_path):
    path = write_file("bad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 1 abc 0\nf 1 2 3\n")
    done = facet_command("planarize", path, "-o", tmp_path / "out.obj")
    line = assert_one_line_error(done, str(path), "line 4", "cannot read 'abc' as a number")
    assert line == f"facet: error: {path}: line 4: cannot read 'abc' as a number"
    assert not (tmp_path / "out.obj").exists()


def test_invalid_mesh(facet_command, write_file):
    path = write_file("x.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n4 0 2 3 2\n")
    done = facet_command("check", path)
    assert_one_line_error(done, str(path), "line 8", "face 1")


def test_out_of_range_index(facet_command, write_file):
    path = write_file("x.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n")
    done = facet_command("check", path)
    assert_one_line_error(done, str(path), "line 6", "face 0 has vertex index 7 out of range")


@pytest.mark.parametrize("argv, says", [
    (["planarize", "in.obj", "-o", "in.obj"], "-o in.obj is the input IN"),
    (["planarize", "in.obj", "-o", "sub/../in.obj"], "is the input IN"),
    (["planarize", "in.obj", "-o", "link.obj"], "-o link.obj is the input IN"),
    (["planarize", "in.obj", "-o", "out.obj", "--report", "in.obj"],
     "--report in.obj is the input IN"),
    (["planarize", "in.obj", "-o", "out.obj", "--report", "out.obj"],
     "--report out.obj is also the output -o"),
    (["planarize", "in.obj", "-o", "ref.obj", "--data", "surface", "--reference", "ref.obj"],
     "-o ref.obj is the input --reference"),
    (["planarize", "in.obj", "-o", "out.obj", "--report", "nowhere/r.json"],
     "--report nowhere/r.json: the folder"),
    (["cleanup", "in.obj", "-o", "in.obj", "--min-edge", "0.01"], "-o in.obj is the input IN"),
    (["check", "in.obj", "--report", "in.obj"], "--report in.obj is the input IN"),
    (["panels", "in.obj", "--thickness", "0.01", "--schedule", "in.obj"],
     "--schedule in.obj is the input MESH"),
])
def test_no_file_is_written_over_and_nothing_is_written(data_dir, tmp_path, monkeypatch, capsys,
                                                        argv, says):
    # before: the input, the reference or the result itself was replaced, exit status 0;
    # a missing report folder failed after the result was written
    source = (data_dir / "hypar.obj").read_bytes()
    for name in ("in.obj", "ref.obj"):
        (tmp_path / name).write_bytes(source)
    (tmp_path / "sub").mkdir()
    (tmp_path / "link.obj").symlink_to(tmp_path / "in.obj")
    monkeypatch.chdir(tmp_path)
    assert cli.main(argv) == 2
    error = capsys.readouterr().err.strip().splitlines()
    assert len(error) == 1 and error[0].startswith("facet: error: ") and says in error[0], error
    assert (tmp_path / "in.obj").read_bytes() == source
    assert (tmp_path / "ref.obj").read_bytes() == source
    assert sorted(p.name for p in tmp_path.iterdir()) == ["in.obj", "link.obj", "ref.obj", "sub"]


def test_unknown_output_format_fails_before_solving(facet_command, data_dir, tmp_path):
    done = facet_command("planarize", data_dir / "tubemesh.off", "-o", tmp_path / "t.stl")
    assert_one_line_error(done, "t.stl", "cannot write .stl files")
    assert done.stdout == ""


def test_unknown_input_format(facet_command, write_file):
    path = write_file("roof.ply", "ply\n")
    assert_one_line_error(facet_command("check", path), "roof.ply", "cannot read .ply files")


def test_item_only_for_json(facet_command, data_dir):
    done = facet_command("check", data_dir / "hypar.obj", "--item", "ThrustDiagram")
    assert_one_line_error(done, "--item applies to .json files only")


@pytest.mark.parametrize(
    "arguments",
    [
        ["planarize", "in.obj"],  # no -o
        ["planarize", "in.obj", "-o", "o.obj", "--method", "fast"],
        ["planarize", "in.obj", "-o", "o.obj", "--tol", "-1"],
        ["planarize", "in.obj", "-o", "o.obj", "--max-iter", "0"],
        [],
    ],
)
def test_usage_errors_exit_2(facet_command, arguments):
    done = facet_command(*arguments)
    assert done.returncode == 2
    assert "usage: facet" in done.stderr


def test_ctrl_c_exits_130(monkeypatch, capsys, data_dir, tmp_path):
    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(facet, "planarize", interrupted)
    status = cli.main(["planarize", str(data_dir / "hypar.obj"), "-o", str(tmp_path / "o.obj")])
    assert status == 130
    assert capsys.readouterr().err == "facet: error: interrupted\n"
    assert not (tmp_path / "o.obj").exists()


def noisy_grid(path, n=100):
    """An n x n grid of quads with random heights: slow enough to interrupt."""
    x, y = np.meshgrid(np.arange(n + 1.0), np.arange(n + 1.0))
    z = np.random.default_rng(7).normal(0.0, 0.3, x.size)
    corner = (np.arange(n)[:, None] * (n + 1) + np.arange(n)[None, :]).ravel()
    faces = np.stack([corner, corner + 1, corner + n + 2, corner + n + 1], axis=1)
    facet.write_mesh(facet.PolyMesh.from_faces(np.c_[x.ravel(), y.ravel(), z], faces), path)


@pytest.mark.skipif(sys.platform == "win32", reason="SIGINT is POSIX")
def test_real_ctrl_c_during_a_solve_exits_130(tmp_path, facet_interrupt):
    source, output = tmp_path / "grid.obj", tmp_path / "out.obj"
    noisy_grid(source)
    done = facet_interrupt("planarize", source, "-o", output, "--iterations", "1000000",
                           "--threads", "1")
    assert done.returncode == 130, done.stderr
    assert done.stderr == "facet: error: interrupted\n"
    assert not output.exists()


@pytest.mark.skipif(sys.platform == "win32", reason="SIGINT is POSIX")
def test_ctrl_c_in_a_resolve_writes_the_result_at_the_tolerance(
        monkeypatch, capsys, data_dir, tmp_path, request):
    """A real Ctrl+C at the first iteration of the first quality re-solve (heart.obj with
    plane data: its first solve closes panels): the solve stops there, and the result its
    first solve had reached at the tolerance is written, said to be stopped, with its
    narrow corners; exit status 130."""
    import os
    import signal

    import facet.cli_progress

    previous = signal.signal(signal.SIGINT, signal.default_int_handler)  # as in a terminal
    request.addfinalizer(lambda: signal.signal(signal.SIGINT, previous))
    source = str(data_dir / "heart.obj")
    mesh = facet.read_mesh(source)
    first = facet.planarize(mesh, data="plane", threads=1, quality_angle=0)
    assert first.converged and first.data_tangent == 0.01
    shown = facet.cli_progress.ProgressLine.progress
    sent = []

    def progress(line, iteration, max_iter, planarity):
        if iteration == first.iterations + 1 and not sent:  # the re-solve's first step
            sent.append(iteration)
            os.kill(os.getpid(), signal.SIGINT)
        return shown(line, iteration, max_iter, planarity)

    monkeypatch.setattr(facet.cli_progress.ProgressLine, "progress", progress)
    output, report_path = tmp_path / "out.obj", tmp_path / "r.json"
    status = cli.main(["planarize", source, "-o", str(output), "--data", "plane",
                       "--threads", "1", "--report", str(report_path)])
    out, err = capsys.readouterr()
    assert sent and status == 130
    assert err == f"facet: interrupted: {output} holds the result the solve had reached\n"
    assert "  stopped" in out and "before the solve had finished" in out
    assert "stopped before one kept every corner open: the first solve's result" in out
    report = json.loads(report_path.read_text())
    assert report["stopped"] is True and report["converged"] is True
    assert report["quality_check"] == "narrow" and report["narrow_corners"] > 0
    assert report["iterations"] == first.iterations + 1
    assert report["data_tangent"] == 0.01  # the first solve's weight, not a firmer stage's
    written = facet.read_mesh(output)
    assert np.array_equal(written.vertices, first.mesh.vertices)
    assert cli.interrupted() is False  # told, and not again by main


def test_a_second_ctrl_c_raises():
    """Within stop_gently the first Ctrl+C is remembered for the progress check, the next
    raises; outside it, the first raises."""
    ctrl_c = cli._CtrlC()
    with ctrl_c.stop_gently():
        try:
            ctrl_c._handle(2, None)
        except KeyboardInterrupt:  # (not let out: it would stop the whole test run)
            pytest.fail("the first Ctrl+C within stop_gently raised")
        assert ctrl_c.seen
        with pytest.raises(KeyboardInterrupt):
            ctrl_c._handle(2, None)
    ctrl_c.seen = False
    with pytest.raises(KeyboardInterrupt):
        ctrl_c._handle(2, None)
    assert ctrl_c.seen


class _DropsCtrlC:
    """An object whose ``__del__`` receives a real SIGINT: Python raises the KeyboardInterrupt
    inside the ``__del__`` and swallows it ("Exception ignored in ..."), as it did in
    shapely's geometries while ``facet panels`` nested."""

    def __del__(self):
        import os
        import signal

        os.kill(os.getpid(), signal.SIGINT)


@pytest.mark.skipif(sys.platform == "win32", reason="SIGINT is POSIX")
@pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning")
@pytest.mark.parametrize("then", ["checks", "fails", "finishes"])
def test_ctrl_c_that_python_swallows_still_interrupts(monkeypatch, capsys, data_dir, request, then):
    """The lost Ctrl+C cancels at the command's next progress check; an error that follows it
    or the command's end is reported as the interrupt (exit status 130)."""
    import signal

    import facet.cli_panels

    # Python's own handler, as in a terminal: a suite run as a background job (sh's `cmd &`)
    # inherits SIGINT ignored, and the CLI rightly leaves an ignored SIGINT alone
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    request.addfinalizer(lambda: signal.signal(signal.SIGINT, previous))
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    went_on = []

    def pipeline(mesh, thickness, progress=None, cancelled=None, **options):
        _DropsCtrlC()  # freed at once: the Ctrl+C is lost in its __del__
        went_on.append(True)
        if then == "checks":
            assert progress("nest", 1, 2) is True and cancelled() is True
            raise Cancelled("nesting cancelled")
        raise facet.errors.InputError("1576 of 3600 parts fit on no sheet")

    def command(args):
        _DropsCtrlC()
        went_on.append(True)
        return cli.EXIT_OK

    monkeypatch.setattr(facet.cli_panels, "run_pipeline", pipeline)
    monkeypatch.setattr(facet.cli_panels, "run_panels", command if then == "finishes" else
                        facet.cli_panels.run_panels)
    status = cli.main(["panels", str(data_dir / "hypar.obj"), "--thickness", "18"])
    assert went_on == [True]  # the interrupt was swallowed, not raised
    assert status == 130
    assert capsys.readouterr().err.endswith("facet: error: interrupted\n")
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler  # put back


def test_no_ctrl_c_no_interrupt(capsys, data_dir):
    assert cli.main(["check", str(data_dir / "hypar.obj")]) == 0
    assert not cli.interrupted("nest", 1, 2)


def test_cancelled_solve_exits_130(monkeypatch, capsys, data_dir, tmp_path):
    def cancelled(*args, **kwargs):
        raise Cancelled("cancelled")

    monkeypatch.setattr(facet, "planarize", cancelled)
    status = cli.main(["planarize", str(data_dir / "hypar.obj"), "-o", str(tmp_path / "o.obj")])
    assert status == 130


def test_main_returns_zero_in_process(capsys, data_dir):
    assert cli.main(["check", str(data_dir / "hypar.obj")]) == 0
    assert "81 vertices, 64 faces (64 quads)" in capsys.readouterr().out


def test_help_names_the_default_of_every_choice():
    """`facet COMMAND --help` names the default of every option with choices, as the README
    says ("`facet --help` and `facet COMMAND --help` list every option"): `panels
    --rotations` and `--ids` did not (90 and auto), and a reader of --help alone could not
    tell what a run without them does."""
    import argparse

    commands = next(a for a in cli.build_parser()._actions
                    if isinstance(a, argparse._SubParsersAction))
    missing = [(name, action.option_strings[0], action.default)
               for name, parser in commands.choices.items() for action in parser._actions
               if action.option_strings and action.choices and action.default is not None
               and not ("default" in (action.help or "")
                        and str(action.default) in action.help)]
    assert not missing
