# SPDX-License-Identifier: LGPL-2.1-or-later
"""The ``facet`` command line: planarize or check a facade mesh file.

::

    python3 -m facet planarize IN -o OUT.obj [--method auto|ll|lg] [--tol T]
        [--tol-abs T] [--max-iter N] [--iterations N] [--threads N]
        [--report R.json] [--strict]
    python3 -m facet check IN [--report R.json]
    python3 -m facet --version

Exit status: 0 done (also when the tolerance was not reached, which is said;
``--strict`` makes that 1), 1 the solver failed, 2 bad input or bad command
line (one line on stderr naming the file, the line or face and what is
wrong), 130 interrupted with Ctrl+C. Ctrl+C stops ``planarize`` (and
``cleanup``'s planarization) at its next iteration: when the solve had already
reached the tolerance (it was re-solving for panel quality, or comparing
methods), that result is written and said, else nothing is; a second Ctrl+C
before it is written discards it.
"""

import argparse
import contextlib
import importlib
import os
import signal
import sys
import threading

from facet.report import count_noun, degrees_text

EXIT_OK = 0
EXIT_NOT_CONVERGED = 1
EXIT_FAILED = 1
EXIT_BAD_INPUT = 2
EXIT_INTERRUPTED = 130

#: Modules that add sub-commands of their own. Each has
#: ``add_commands(commands)``, which adds parsers to the argparse
#: sub-parsers object ``commands`` and sets ``run=function(args) -> exit
#: status`` as each parser's default. Keep their module-level imports light:
#: every ``facet`` command imports them all. Bad input is raised as
#: :class:`facet.errors.InputError` (exit status 2).
COMMAND_MODULES = ("facet.cli_cleanup", "facet.cli_lift", "facet.cli_panels")

#: How each stop reason of the solver is told to the designer.
STOP_REASONS = {
    "tolerance": "tolerance reached",
    "max_iter": "iteration limit reached before the tolerance",
    "iterations": "requested number of iterations done",
    "stagnation": "planarity stopped improving",
    "cancelled": "cancelled",
    "time": "time budget used before the tolerance",
}


def _non_negative_float(text):
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not value >= 0 or value == float("inf"):
        raise argparse.ArgumentTypeError(f"{text!r} must be a finite number >= 0")
    return value


def _positive_float(text):
    value = _non_negative_float(text)
    if value == 0:
        raise argparse.ArgumentTypeError(f"{text!r} must be > 0")
    return value


def _int_in(text, least, most=2**31 - 1):
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if not least <= value <= most:
        raise argparse.ArgumentTypeError(f"{text!r} must be from {least} to {most}")
    return value


def _positive_int(text):
    return _int_in(text, 1)


def _non_negative_int(text):
    return _int_in(text, 0)


def _anderson_depth(text):
    from facet.planarize import ANDERSON_MAX

    return _int_in(text, 0, ANDERSON_MAX)


def build_parser():
    """The argument parser of the ``facet`` command.

    Returns
    -------
    argparse.ArgumentParser
    """
    from facet import __version__
    from facet.planarize import ANDERSON_MAX

    parser = argparse.ArgumentParser(
        prog="facet",
        description="Planar panels for freeform facades: planarize or check a polygon mesh "
        "(.obj, .off, compas .json).",
    )
    parser.add_argument("--version", action="version", version=f"facet {__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")
    commands.required = True

    planarize = commands.add_parser(
        "planarize",
        help="move the vertices so that every panel becomes planar",
        description="Move the vertices as little as possible so that every face (panel) "
        "becomes planar, and write the result.",
    )
    planarize.add_argument("input", metavar="IN", help="mesh to planarize (.obj, .off, .json)")
    planarize.add_argument(
        "-o", "--output", metavar="OUT", required=True, help="planarized mesh (.obj or .off)"
    )
    planarize.add_argument(
        "--method",
        choices=("auto", "ll", "lg"),
        default="auto",
        help="auto (default): lg up to 10,000 quads (40,000 face corners), ll above "
        "(and lg again up to 160,000 quads if ll leaves a panel closed); "
        "lg: local normals, global solve; ll: local-local, the paper's algorithm",
    )
    planarize.add_argument(
        "--tol",
        type=_non_negative_float,
        default=1e-6,
        metavar="T",
        help="stop when every face's distance from its best-fit plane is at most T times its "
        "mean edge length (default 1e-6; 0 turns it off)",
    )
    planarize.add_argument(
        "--tol-abs",
        type=_positive_float,
        metavar="T",
        help="stop when every face's distance from its best-fit plane is at most T model units",
    )
    planarize.add_argument("--max-iter", type=_positive_int, metavar="N", help="iteration limit")
    planarize.add_argument(
        "--iterations",
        type=_positive_int,
        metavar="N",
        help="run exactly N iterations, without stopping early",
    )
    planarize.add_argument(
        "--threads", type=_non_negative_int, metavar="N",
        help="threads to use (0: one per 25,000 quads, at most all cores)"
    )
    planarize.add_argument("--report", metavar="R.json", help="write a JSON report")
    planarize.add_argument(
        "--item", metavar="NAME", help="mesh to read from a RhinoVAULT .json session"
    )
    terms = planarize.add_argument_group("what to stay close to, and constraints")
    terms.add_argument(
        "--data",
        choices=("point", "plane", "surface"),
        default="point",
        help="point: each vertex near its control point (default); plane: near its control "
        "tangent plane; surface: on the design surface, free to slide along it",
    )
    terms.add_argument(
        "--reference",
        metavar="MESH",
        help="design surface for --data surface (default: the input mesh's own surface)",
    )
    terms.add_argument(
        "--boundary",
        choices=("free", "fixed", "sliding"),
        default="free",
        help="boundary vertices move freely (default), stay put, or slide along the boundary "
        "(corners stay)",
    )
    terms.add_argument(
        "--fixed",
        metavar="I,J,...",
        help="vertex indices (0-based) that must not move",
    )
    terms.add_argument(
        "--shape",
        choices=("none", "asap", "arap"),
        help="keep each panel a similar (asap) or congruent (arap) copy of its control face "
        "(default: none with --data point, a mild asap with plane and surface)",
    )
    terms.add_argument("--shape-weight", type=_positive_float, metavar="W", help="default 1")
    terms.add_argument("--laplacian", type=_non_negative_float, metavar="W",
                       help="vertex Laplacian fairing weight (default 0)")
    terms.add_argument("--normal-laplacian", type=_non_negative_float, metavar="W",
                       help="face-normal smoothing weight (default 0)")
    terms.add_argument("--boundary-fairness", type=_non_negative_float, metavar="W",
                       help="boundary polyline fairing weight (default 0)")
    terms.add_argument("--circular", type=_non_negative_float, metavar="W",
                       help="make every face's vertices concyclic (weight; default off)")
    terms.add_argument("--parallelogram", type=_non_negative_float, metavar="W",
                       help="make every quad a parallelogram (weight; default off)")
    terms.add_argument("--anderson", type=_anderson_depth, metavar="M",
                       help=f"Anderson acceleration depth (default 5; 0 off; at most "
                       f"{ANDERSON_MAX})")
    terms.add_argument("--time-budget", type=_positive_float, metavar="S",
                       help="stop after S seconds (the result so far is written)")
    planarize.add_argument(
        "--strict",
        action="store_true",
        help="exit with status 1 when the tolerance is not reached",
    )
    planarize.set_defaults(run=run_planarize)

    check = commands.add_parser(
        "check",
        help="validate a mesh and measure the planarity of its panels",
        description="Validate a mesh and measure how far each face is from planar.",
    )
    check.add_argument("input", metavar="IN", help="mesh to check (.obj, .off, .json)")
    check.add_argument("--report", metavar="R.json", help="write a JSON report")
    check.add_argument(
        "--item", metavar="NAME", help="mesh to read from a RhinoVAULT .json session"
    )
    check.set_defaults(run=run_check)
    for name in COMMAND_MODULES:
        importlib.import_module(name).add_commands(commands)
    return parser


# ------------------------------------------------------------------ output


def _g(value, digits=3):
    """A number for the summary: 3 significant digits, 'n/a' for None."""
    if value is None:
        return "n/a"
    return f"{value:.{digits}g}"


def _line(out, label, text):
    print(f"  {label:<13} {text}", file=out)


def _source_lines(out, report):
    if report.get("source_item"):
        _line(out, "read", f"scene item {report['source_item']}")
    openings = report.get("source_openings_skipped")
    if openings:
        _line(out, "openings", f"{count_noun(openings, 'face')} skipped (_is_loaded is false)")
    dropped = report.get("source_unused_vertices_dropped")
    if dropped:
        _line(out, "dropped", f"{count_noun(dropped, 'vertex')} used by no face")


def _quality_lines(out, quality):
    """Summary lines of a report's ``quality`` section (see facet.quality)."""
    if not quality:
        return
    if quality.get("distance_max") is not None:
        _line(
            out,
            "surface",
            f"distance from the input surface rms {_g(quality['distance_rms'])}, "
            f"max {_g(quality['distance_max'])}",
        )
    shape = f"smallest angle {_g(quality.get('min_angle_deg'))} deg"
    if quality.get("input_min_angle_deg") is not None:
        shape += f" (input {_g(quality['input_min_angle_deg'])})"
    if quality.get("ratio_change_max") is not None:
        shape += f", edge ratio change max {_g(quality['ratio_change_max'])}"
    _line(out, "shape", shape)
    count = quality.get("degenerate_faces") or 0
    if count:
        first = ", ".join(map(str, quality.get("degenerate_face_indices") or ()))
        _line(
            out,
            "degenerate",
            f"{count_noun(count, 'face')} with no area, an angle under "
            f"{_g(quality.get('degenerate_min_angle_deg'))} deg or an edge under "
            f"{_g(100 * (quality.get('degenerate_short_edge') or 0))}% of the face's mean edge "
            f"(first: {first})",
        )
    count = quality.get("straight_corner_faces") or 0
    if count:
        first = ", ".join(map(str, quality.get("straight_corner_face_indices") or ()))
        text = (f"{count_noun(count, 'face')} with a corner within "
                f"{_g(quality.get('straight_corner_deg'))} deg of straight (the straightest "
                f"turns {_g(quality.get('straightest_corner_deg'))} deg")
        if quality.get("input_straightest_corner_deg") is not None:
            text += f"; input {_g(quality['input_straightest_corner_deg'])} deg"
        _line(out, "straight", text + f"; first: {first})")


def _compared_line(out, report):
    """The summary line of method auto's comparison (PlanarizeResult.compared)."""
    compared = report.get("compared")
    if not compared:
        return
    kept = report["method"]
    text = f"local/local too ({count_noun(compared['iterations'], 'iteration')})"
    if compared.get(kept) and compared.get("lg") and compared.get("ll"):
        other = "ll" if kept == "lg" else "lg"
        a, b = compared[kept], compared[other]
        text += (f": kept {kept}'s result, distance from the input surface rms "
                 f"{_g(a['distance_rms'])}, vertices moved rms {_g(a['displacement_rms'])}, "
                 f"smallest angle {_g(a['min_angle'])} deg; {other}'s "
                 f"{_g(b['distance_rms'])}, {_g(b['displacement_rms'])}, {_g(b['min_angle'])} deg")
    else:
        text += ": it did not reach the tolerance; kept lg's result"
    finer = compared.get("finer")
    if finer:
        text += (f"; lg again with a finer hold ({count_noun(finer['iterations'], 'iteration')}): "
                 + ("its result kept" if finer["kept"] else "not closer, the first lg result kept"))
    _line(out, "compared", text)


def print_planarize_summary(report, out=None):
    """Print the human summary of a planarization report.

    Parameters
    ----------
    report : dict
        From :func:`facet.report.planarize_report`.
    out : file, optional
        Default ``sys.stdout``.
    """
    out = out or sys.stdout
    print(f"facet planarize: {report['input']}", file=out)
    _line(
        out,
        "mesh",
        f"{count_noun(report['vertices'], 'vertex')}, {count_noun(report['faces'], 'face')} "
        f"({degrees_text(report['face_degrees'])}), mean edge {_g(report['mean_edge_length'])}",
    )
    _source_lines(out, report)
    _line(
        out,
        "planarity",
        f"before {_g(report['input_planarity_max_abs'])} "
        f"({_g(report['input_planarity_max_rel'])} of the edge), "
        f"after {_g(report['planarity_max_abs'])} ({_g(report['planarity_max_rel'])} of the edge)"
        + (f"; {count_noun(report['exempt_faces'], 'exempt face')} (weight 0) not counted"
           if report.get("exempt_faces") else ""),
    )
    reason = STOP_REASONS.get(report["stop_reason"], report["stop_reason"])
    if report["stop_reason"] != "iterations":
        tolerances = []
        if report.get("tol"):
            tolerances.append(f"{_g(report['tol'])} of the edge")
        if report.get("tol_abs"):
            tolerances.append(f"{_g(report['tol_abs'])} model units")
        if tolerances:
            reason += f" (tolerance {' and '.join(tolerances)})"
    _line(
        out,
        "solve",
        f"{report['method']}, {count_noun(report['iterations'], 'iteration')} in "
        f"{report['solve_seconds']:.3g} s"
        + (f" on {count_noun(report['threads'], 'thread')}" if report.get("threads") else "")
        + f": {reason}",
    )
    resolves = report.get("quality_resolves") or 0
    if resolves:
        check = report.get("quality_check")
        outcome = ("the last kept every corner open" if check == "recovered" else
                   # method auto's comparison then kept local/local's result, with none
                   "then the comparison's result, with every corner open, was kept"
                   if check == "ok" else
                   "stopped before one kept every corner open: the first solve's result"
                   if report.get("stopped") else
                   "the time budget ended them before one kept every corner open: the first "
                   "solve's result" if report.get("quality_timed_out") else
                   "none kept every corner open: the first solve's result")
        # (the core's default when the options leave it out)
        asked = (report.get("options") or {}).get("data_tangent", 1.0)
        used = report.get("data_tangent")
        if used is not None and used > asked:
            outcome += (f", holding the vertices more firmly along the design (data_tangent "
                        f"{_g(used)} instead of {_g(asked)})")
        _line(out, "re-solves", f"{resolves} for panel quality after the first solve's "
              f"{count_noun(report.get('first_iterations', 0), 'iteration')}: {outcome}")
    _compared_line(out, report)
    if report.get("stopped"):
        _line(out, "stopped", "before the solve had finished: this is the result it had reached "
              "at the tolerance before the stop")
    relative = report.get("displacement_max_rel")
    share = "" if relative is None else f" ({relative * 100:.3g}% of the mean edge)"
    _line(
        out,
        "displacement",
        f"rms {_g(report['displacement_rms'])}, max {_g(report['displacement_max'])}{share}",
    )
    _quality_lines(out, report.get("quality"))
    if report.get("reference_distance_max") is not None:
        _line(out, "reference", f"distance from the reference surface rms "
              f"{_g(report['reference_distance_rms'])}, max {_g(report['reference_distance_max'])}")
    for warning in report.get("warnings") or ():
        _line(out, "warning", warning)
    _line(out, "written", report["output"])
    if report.get("report"):
        _line(out, "report", report["report"])


def print_check_summary(report, out=None):
    """Print the human summary of a check report.

    Parameters
    ----------
    report : dict
        From :func:`facet.report.check_report`.
    out : file, optional
        Default ``sys.stdout``.
    """
    out = out or sys.stdout
    print(f"facet check: {report['input']}", file=out)
    _line(
        out,
        "mesh",
        f"{count_noun(report['vertices'], 'vertex')}, {count_noun(report['faces'], 'face')} "
        f"({degrees_text(report['face_degrees'])}), {count_noun(report['edges'], 'edge')} "
        f"({report['boundary_edges']} on the boundary)",
    )
    _source_lines(out, report)
    if report.get("non_manifold_edges"):
        first = "-".join(map(str, report.get("first_non_manifold_edge") or ()))
        count = report["non_manifold_edges"]
        text = f"{count_noun(count, 'edge')} shared by more than two faces (first: {first})"
        _line(out, "warning", text)
    if report.get("isolated_vertices"):
        first = report.get("first_isolated_vertex")
        count = report["isolated_vertices"]
        _line(out, "warning", f"{count_noun(count, 'vertex')} used by no face (first: {first})")
    if report.get("duplicate_faces"):
        earlier, copy = report.get("first_duplicate_faces")
        count = report["duplicate_faces"]
        _line(out, "warning", f"{count_noun(count, 'face')} with the same vertices as another "
              f"(first: face {copy} repeats face {earlier}): two panels at one place")
    if report.get("opposite_windings"):
        f, g = report.get("first_opposite_windings")
        count = report["opposite_windings"]
        _line(out, "warning", f"faces wound opposite ways across {count_noun(count, 'edge')} "
              f"(first: faces {f} and {g}): their normals point to opposite sides, so "
              "FreeCAD shades the turned ones dark; facet panels turns them to their "
              "neighbours' side")
    if report.get("coincident_vertex_pairs"):
        from facet.mesh import WELD_ADVICE

        i, j = report.get("first_coincident_vertices")
        count = report["coincident_vertex_pairs"]
        _line(out, "warning", f"vertices at one point but not one vertex: "
              f"{count_noun(count, 'pair')} (first: {i} and {j}); the faces there are not "
              f"joined: {WELD_ADVICE}")
    low, high = report["bounds"]["min"], report["bounds"]["max"]
    size = " x ".join(_g(b - a) for a, b in zip(low, high))
    _line(out, "size", f"{size}, mean edge {_g(report['mean_edge_length'])}")
    _line(
        out,
        "planarity",
        f"max {_g(report['planarity_max_abs'])} ({_g(report['planarity_max_rel'])} of the "
        f"edge, face {report['worst_face']}), rms {_g(report['planarity_rms_rel'])} of the edge",
    )
    diagonal = report.get("planarity_diagonal_max")
    if diagonal is not None and diagonal >= 0:
        _line(out, "quads", f"diagonal distance max {_g(diagonal)} of the diagonal")
    _quality_lines(out, report.get("quality"))
    if report.get("report"):
        _line(out, "report", report["report"])


# ---------------------------------------------------------------- commands


def _read(args):
    """The input mesh, its reading shown on a terminal (a 100,000-face compas JSON takes
    seconds); what the reader changed in reading it is warned about."""
    from facet.cli_progress import ProgressLine
    from facet.io import read_mesh, read_warnings

    options = {}
    if args.item is not None:
        if os.path.splitext(args.input)[1].lower() != ".json":
            raise _UsageError("--item applies to .json files only")
        options["item"] = args.item
    command = getattr(args, "command", None)
    line = ProgressLine(sys.stderr, prefix=f"facet {command}" if command else "facet")
    what = f"reading {os.path.basename(args.input)}"
    try:
        mesh = read_mesh(args.input, progress=lambda done, total: line.steps(
            done, total, what), **options)
    finally:
        line.close()
    for warning in read_warnings(mesh):
        print(f"facet: warning: {args.input}: {warning}", file=sys.stderr)
    return mesh


def _term_options(args, mesh):
    """The solver terms asked for on the command line, checked against `mesh`."""
    from facet.io import read_mesh
    from facet.planarize import preset_shape

    options = {"data": args.data, "boundary": args.boundary}
    for name in ("shape", "shape_weight", "laplacian", "normal_laplacian", "boundary_fairness",
                 "circular", "parallelogram", "anderson", "time_budget"):
        value = getattr(args, name)
        if value is not None:
            options[name] = value
    if args.shape_weight and preset_shape(args.shape, args.data) == "none":
        raise _UsageError("--shape-weight weighs the shape term, which is off: give --shape "
                          "asap or arap with it (or --data plane or surface, which set asap)")
    if args.reference:
        if args.data != "surface":
            raise _UsageError("--reference needs --data surface")
        options["reference"] = read_mesh(args.reference)
    if args.fixed:
        try:
            fixed = [int(text) for text in args.fixed.split(",") if text.strip()]
        except ValueError:
            raise _UsageError(f"--fixed takes vertex indices separated by commas, not "
                              f"{args.fixed!r}") from None
        bad = [i for i in fixed if not 0 <= i < mesh.n_vertices]
        if bad:
            raise _UsageError(f"--fixed: vertex {bad[0]} is out of range ({mesh.n_vertices} "
                              f"vertices in {args.input})")
        options["fixed"] = fixed
    return options


def planarize_stoppable(mesh, prefix="facet planarize", **options):
    """:func:`facet.planarize` for a command: its progress line on a terminal, and Ctrl+C
    stopping it at its next iteration. A result the solve had reached at the tolerance
    before the stop (a quality re-solve or method auto's comparison was running) is kept,
    as the workbench's Stop keeps it; else the stop raises :class:`facet.Cancelled`.

    Returns
    -------
    (PlanarizeResult, bool)
        The result, and whether Ctrl+C stopped the solve (also when it came after the
        solve's last progress check and the solve reached the tolerance: the result is
        then whole; short of the tolerance that raises KeyboardInterrupt). A stopped
        command writes its result and ends with :func:`stopped_with_result`.
    """
    from facet import planarize
    from facet.cli_progress import ProgressLine
    from facet.errors import Cancelled

    line = ProgressLine(sys.stderr, prefix=prefix)  # a terminal only; says when it re-solves

    def progress(iteration, max_iter, planarity):
        line.progress(iteration, max_iter, planarity)
        return interrupted()

    try:
        with _CTRL_C.stop_gently():
            result = planarize(mesh, progress=progress,
                               stage=line.stage if line.enabled else None, **options)
    except Cancelled as error:
        if error.result is None or not _CTRL_C.seen:
            raise
        result = error.result
    finally:
        line.close()
    stopped = _CTRL_C.seen
    if stopped and not result.converged:
        # Ctrl+C after the solve's last progress check, which ended short of the
        # tolerance: as any interrupt, nothing is written
        raise KeyboardInterrupt
    # taken: the command writes the result, then says it was interrupted; an error
    # while it writes is that error, not an interrupt
    _CTRL_C.seen = False
    return result, stopped


def stopped_with_result(output):
    """The end of a command that Ctrl+C stopped after it wrote `output`: says so on
    stderr; the exit status (interrupted)."""
    print(f"facet: interrupted: {output} holds the result the solve had reached",
          file=sys.stderr)
    return EXIT_INTERRUPTED


def run_planarize(args):
    """Run ``facet planarize``; return the exit status."""
    from facet import planarity
    from facet.io import write_mesh, writer_for
    from facet.report import planarize_report, write_json

    writer_for(args.output)  # refuse an unknown output format before the solve
    if args.iterations is not None and args.max_iter is not None:
        raise _UsageError("give --iterations (exactly N, no tolerance) or --max-iter (a limit "
                          "on a solve to the tolerance), not both")
    check_files(reads=[("IN", args.input), ("--reference", args.reference)],
                writes=[("-o", args.output), ("--report", args.report)])
    mesh = _read(args)
    options = _term_options(args, mesh)
    before = planarity(mesh, threads=args.threads)
    result, stopped = planarize_stoppable(
        mesh,
        method=args.method,
        tol=args.tol,
        tol_abs=args.tol_abs,
        max_iter=args.max_iter,
        iterations=args.iterations,
        threads=args.threads,
        **options,
    )
    write_mesh(result.mesh, args.output)
    report = planarize_report(
        mesh, result, input_path=args.input, output_path=args.output, input_planarity=before
    )
    if args.reference:
        report["reference"] = args.reference
    if args.fixed:
        report["fixed"] = options.get("fixed", [])
    if args.report:
        report["report"] = args.report
        write_json(report, args.report)
    print_planarize_summary(report)
    if stopped:
        return stopped_with_result(report["output"])
    if not report["converged"]:
        if report["stop_reason"] != "iterations":
            print(
                f"facet: warning: not converged: {report['output']} has planarity "
                f"{_g(report['planarity_max_rel'])} of the edge "
                f"({_g(report['planarity_max_abs'])} model units) after "
                f"{report['iterations']} iterations: "
                f"{STOP_REASONS.get(report['stop_reason'], report['stop_reason'])}",
                file=sys.stderr,
            )
        if args.strict:
            return EXIT_NOT_CONVERGED
    return EXIT_OK


def run_check(args):
    """Run ``facet check``; return the exit status."""
    from facet import planarity
    from facet.report import check_report, write_json

    check_files(reads=[("IN", args.input)], writes=[("--report", args.report)])
    mesh = _read(args)
    validation = mesh.validate()
    report = check_report(mesh, planarity(mesh), validation, path=args.input)
    if args.report:
        report["report"] = args.report
        write_json(report, args.report)
    print_check_summary(report)
    return EXIT_OK


class _UsageError(Exception):
    """A command-line option that does not fit the input."""


def _same_file(a, b):
    if os.path.normcase(os.path.realpath(a)) == os.path.normcase(os.path.realpath(b)):
        return True
    try:
        return os.path.samefile(a, b)  # hard links
    except OSError:
        return False


def check_files(reads=(), writes=(), creates=()):
    """Refuse, before any work, a command that would write over a file it reads or write
    two of its outputs to one file, or whose output folder does not exist.

    Parameters
    ----------
    reads, writes : iterable of (str, str or None)
        Each file as (how the command line names it, path); a path None was not given.
    creates : iterable of str or None
        Folders the command makes (``-o DIR``, ``--svg DIR``): an output may go into one.

    Raises
    ------
    _UsageError
        ``"-o in.obj is the input IN: it would be written over; give another file"``.
    """
    taken = [(option, path, "is the input") for option, path in reads if path]
    made = {os.path.abspath(folder) for folder in creates if folder}
    for option, path in writes:
        if not path:
            continue
        folder = os.path.dirname(os.path.abspath(path))
        if not os.path.isdir(folder) and folder not in made:
            raise _UsageError(f"{option} {path}: the folder {folder} does not exist")
        for other_option, other, role in taken:
            if _same_file(path, other):
                raise _UsageError(f"{option} {path} {role} {other_option}: it would be "
                                  "written over; give another file")
        taken.append((option, path, "is also the output"))


def _os_error_text(error):
    if error.filename is not None:
        return f"{os.fspath(error.filename)}: {error.strerror or error}"
    return str(error)


def _fail(message):
    print(f"facet: error: {message}", file=sys.stderr)


class _CtrlC:
    """Ctrl+C while a command runs: KeyboardInterrupt as Python raises it by default, and
    remembered. Python swallows an exception raised inside a ``__del__`` (it prints
    "Exception ignored in ..."), and shapely's geometries run one whenever they are freed:
    an interrupt that lands there was lost and the command went on to its end. Remembered,
    it cancels the command at its next progress check (:func:`interrupted`). Within
    :meth:`stop_gently` the first Ctrl+C is only remembered."""

    def __init__(self):
        self.seen = False
        self.gentle = False
        self._previous = None

    def _handle(self, signum, frame):
        first = not self.seen
        self.seen = True
        if not (self.gentle and first):
            raise KeyboardInterrupt

    @contextlib.contextmanager
    def stop_gently(self):
        """Within: the first Ctrl+C is only remembered, for a progress check to stop a
        computation that can keep what it finished (:func:`interrupted`); a second one
        raises KeyboardInterrupt as usual (at the next progress check while the core
        solves: the kept result is then discarded)."""
        self.gentle = True
        try:
            yield
        finally:
            self.gentle = False

    def __enter__(self):
        self.seen = False
        # only where Python's own handler is in place (not when SIGINT is ignored, as for
        # a background job, nor outside the main thread, where no handler can be set)
        if (threading.current_thread() is threading.main_thread()
                and signal.getsignal(signal.SIGINT) is signal.default_int_handler):
            self._previous = signal.signal(signal.SIGINT, self._handle)
        return self

    def __exit__(self, *exc):
        if self._previous is not None:
            signal.signal(signal.SIGINT, self._previous)
            self._previous = None
        return False


_CTRL_C = _CtrlC()


def interrupted(*_progress):
    """Whether Ctrl+C was pressed during the running command; takes and ignores any
    progress arguments, so that it serves as a cancelling ``progress`` callable."""
    return _CTRL_C.seen


def main(argv=None):
    """Run the ``facet`` command.

    Parameters
    ----------
    argv : list of str, optional
        Arguments without the program name; default ``sys.argv[1:]``.

    Returns
    -------
    int
        The exit status (see the module documentation).
    """
    from facet.errors import Cancelled, FacetError, InputError

    parser = build_parser()
    try:
        args = parser.parse_args(argv)
        with _CTRL_C:
            try:
                status = args.run(args)
            except Exception:
                if _CTRL_C.seen:  # what failed ran on after an interrupt Python swallowed
                    raise KeyboardInterrupt from None
                raise
        if _CTRL_C.seen:  # swallowed after the command's last check
            raise KeyboardInterrupt
        return status
    except KeyboardInterrupt:
        _fail("interrupted")
        return EXIT_INTERRUPTED
    except Cancelled:
        _fail("interrupted")
        return EXIT_INTERRUPTED
    except InputError as error:
        _fail(str(error))
        return EXIT_BAD_INPUT
    except _UsageError as error:
        _fail(str(error))
        return EXIT_BAD_INPUT
    except OSError as error:
        _fail(_os_error_text(error))
        return EXIT_BAD_INPUT
    except FacetError as error:
        _fail(str(error))
        return EXIT_FAILED
    except ImportError as error:
        _fail(str(error))
        return EXIT_FAILED
