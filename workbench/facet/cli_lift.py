# SPDX-License-Identifier: LGPL-2.1-or-later
"""The ``lift`` and ``lifting-space`` sub-commands of ``python3 -m facet``.

::

    python3 -m facet lift PLAN -o OUT.obj (--targets T | --pin V=H ...)
        [--weights W] [--report R.json] [--snap D] [--arc-tolerance D]
        [--opening X,Y ...] [--rank-tol T] [--move-tolerance D]
    python3 -m facet lifting-space PLAN [--basis fundamental|eigen|orthonormal]
        [--count K] -o DIR [--report R.json] [...plan options]

PLAN is a drawing (.dxf, or a table of segments: .csv, or tab-separated .tsv or
.txt as spreadsheets write them) or a plan mesh (.obj, .off,
.json). T is a mesh (per-vertex targets when it has the plan's vertices in
order, else vertical projection, topmost hit) or a table of x,y,z points
(nearest plan vertex within the snap distance; vertices with no point are
free). W is a text file with one weight per plan vertex. With --move-tolerance D the
plan's vertices may move by up to D (facet.lift.lift_nearly); the exit status is 1 when
more was needed (the result is written all the same).
"""

import contextlib
import os
import sys

__all__ = ["add_commands"]

#: How the plan's messages name the options they advise (facet.plan.OPTION_NAMES). Their
#: lengths are in the drawing's own units (a DXF's $INSUNITS names them): the command line
#: does not scale a plan.
OPTION_NAMES = {"snap": "--snap", "arc_tolerance": "--arc-tolerance", "tolerance": "--snap"}


def _plan_options(parser):
    parser.add_argument("plan", metavar="PLAN", help="plan drawing (.dxf, .csv/.tsv/.txt) or mesh "
                        "(.obj, .off, .json)")
    parser.add_argument("--snap", type=float, metavar="D",
                        help="merge drawing endpoints closer than D, and match target points to plan "
                        "vertices within D (default 1e-6 of its size)")
    parser.add_argument("--arc-tolerance", type=float, metavar="D",
                        help="split arcs and curves into segments with sagitta <= D "
                        "(default: refuse them)")
    parser.add_argument("--opening", action="append", default=[], metavar="X,Y",
                        help="a point inside a face that is an opening (no panel); repeatable")
    parser.add_argument("--rank-tol", type=float, metavar="T",
                        help="constraints dependent on the others to within T are treated as dependent (default 1e-10)")
    parser.add_argument("--report", metavar="R.json", help="write a JSON report")


def _point(text):
    from facet.errors import InputError

    try:
        x, y = (float(v) for v in text.split(","))
    except ValueError:
        raise InputError(f"--opening {text!r}: expected X,Y") from None
    return x, y


#: Basis liftings `lifting-space` writes unless --count says otherwise.
DEFAULT_COUNT = 20


def _read_plan(args, prefix):
    """The plan of ``args``, its stages shown on a terminal (a 40,000-face plan takes
    seconds; Ctrl+C stops it between them)."""
    from facet.cli_progress import ProgressLine
    from facet.plan import PLAN_STAGES, PLAN_STEPS, read_plan

    line = ProgressLine(sys.stderr, prefix=prefix)
    try:
        return read_plan(args.plan, snap=args.snap, arc_tolerance=args.arc_tolerance,
                         openings=[_point(p) for p in args.opening],
                         option_names=OPTION_NAMES, progress=lambda done, total: line.steps(
                             done // PLAN_STEPS, PLAN_STAGES, "reading the plan: stages done"))
    finally:
        line.close()


def _read_weights(path, n):
    import numpy as np

    from facet.errors import InputError

    values = []
    try:
        with open(path, encoding="utf-8") as handle:
            for number, line in enumerate(handle, 1):
                text = line.split("#")[0].strip().rstrip(",")
                if not text:
                    continue
                try:
                    values.append(float(text))
                except ValueError:
                    raise InputError(f"{path}: line {number}: {text[:40]!r} is not a number")
    except OSError as exc:
        raise InputError(f"{path}: cannot read the file ({exc.strerror})") from None
    if len(values) != n:
        raise InputError(f"{path}: {len(values)} weights but the plan has {n} vertices")
    values = np.array(values)
    bad = np.flatnonzero(~(np.isfinite(values) & (values > 0)))
    if bad.size:
        raise InputError(f"{path}: weight of vertex {int(bad[0])} must be finite and > 0")
    return values


@contextlib.contextmanager
def _factorizing(prefix):
    """The progress of a lifter's factorization on a terminal, for the block: a line
    naming its stages (a large plan's takes seconds, a 300,000-site Voronoi plan's a
    minute), erased at the end; Ctrl+C stops it between them."""
    from facet.cli_progress import ProgressLine

    what = "factorizing the planarity constraints: stages done"
    line = ProgressLine(sys.stderr, prefix=prefix)
    line.steps(0, 3, what)
    try:
        yield lambda done, total: line.steps(done, total, what)
    finally:
        line.close()


def _pins(texts):
    from facet.errors import InputError

    pins = {}
    for text in texts:
        try:
            vertex, height = text.split("=")
            vertex, height = int(vertex), float(height)
        except ValueError:
            raise InputError(f"--pin {text!r}: expected VERTEX=HEIGHT") from None
        if vertex in pins and pins[vertex] != height:
            raise InputError(f"--pin {text!r}: vertex {vertex} is pinned at {pins[vertex]:g} "
                             "already")
        pins[vertex] = height
    return pins


def run_lift(args):
    import numpy as np

    from facet.cli import EXIT_OK, check_files
    from facet.errors import InputError
    from facet.io import write_mesh, writer_for
    from facet.lift import lift
    from facet.plan import DRAWING_UNITS, pinned_targets, read_targets
    from facet.report import length_text, write_json

    writer_for(args.output)  # bad output suffix: fail before the work
    check_files(reads=[("PLAN", args.plan), ("--targets", args.targets),
                       ("--weights", args.weights)],
                writes=[("-o", args.output), ("--report", args.report)])
    if (args.targets is None) == (not args.pin):
        raise InputError("give either --targets FILE or --pin VERTEX=HEIGHT (not both)")
    plan = _read_plan(args, "facet lift")
    notes = []  # (target points left out)
    if args.targets is not None:
        from facet.cli_progress import ProgressLine

        # (a target mesh: each plan vertex's ray cast, seconds for 100,000 vertices)
        line = ProgressLine(sys.stderr, prefix="facet lift")  # a terminal only
        try:
            targets, weights = read_targets(
                plan, args.targets, tolerance=args.snap, notes=notes,
                option_names=OPTION_NAMES, progress=lambda done, total: line.steps(done, total,
                                                        "matching the targets: vertices"))
        finally:
            line.close()
    else:
        targets, weights = pinned_targets(plan, _pins(args.pin))
    if args.weights is not None:
        weights = weights * _read_weights(args.weights, plan.n_vertices)
    nearly = None
    if args.move_tolerance is not None:
        from facet.lift import lift_nearly

        from facet.cli_progress import ProgressLine

        line = ProgressLine(sys.stderr, prefix="facet lift: moving the plan")  # a terminal only
        try:
            nearly = lift_nearly(plan, targets, weights, tolerance=args.move_tolerance,
                                 rank_tol=args.rank_tol, progress=line.progress)
        finally:
            line.close()
        result = nearly.result
    else:
        with _factorizing("facet lift") as progress:
            result = lift(plan, targets, weights, rank_tol=args.rank_tol, progress=progress)
    write_mesh(result.mesh, args.output)
    report = {"source": os.fspath(args.plan), "output": os.fspath(args.output)}
    report.update(nearly.report() if nearly is not None else result.report())
    report["warnings"] = notes + list(report.get("warnings", []))
    report["plan"] = plan.summary()
    # the lengths below in the drawing's unit when it names one (a DXF's $INSUNITS: a
    # roof drawn in feet read "RMS miss 0.641" with no unit)
    report["units"] = plan.units if plan.units != DRAWING_UNITS else None
    length = length_text(report["units"])
    report["dangling"] = [[list(a), list(b)] for a, b in plan.dangling]
    if args.report:
        write_json(report, args.report)
    size = float(np.ptp(plan.mesh.vertices[:, :2], axis=0).max())
    print(f"facet lift: {args.plan} -> {args.output}")
    print(f"  plan          {plan.n_vertices} vertices, {plan.n_faces} faces"
          + (f", {len(plan.dangling)} dangling edges dropped" if plan.dangling else "")
          + (f", {plan.openings} openings" if plan.openings else ""))
    print(f"  liftings      dimension {result.dimension} "
          f"({result.trivial_dimension} trivial)")
    if nearly is not None:
        if nearly.method == "unmoved":
            print("  plan          kept as drawn: moving its vertices did not bring the "
                  "lifting closer")
        else:
            print(f"  plan moved    {len(nearly.moved_vertices)} vertices, at most "
                  f"{length(nearly.max_move)} ("
                  f"{'within' if nearly.within_tolerance else 'MORE THAN'} the tolerance "
                  f"{length(args.move_tolerance, 'g')}); every move is in the report")
    if result.liftable_only_trivially:
        print("  note          the plan admits only the trivial (affine) liftings: "
              "the result is the best-fitting plane"
              + (" of each piece" if result.trivial_dimension > 3 else ""))
    print(f"  planarity     {result.planarity_max_rel:.3g} of the mean edge length (max)")
    print(f"  targets       RMS miss {length(result.target_rms)}, max "
          f"{length(result.target_max)} "
          f"at vertex {result.target_max_vertex} ({result.target_max / size:.3g} of the plan "
          "size)")
    print(f"  time          {result.factor_seconds + result.solve_seconds:.3g} s")
    for text in notes + [w for w in result.warnings if "trivial" not in w]:
        print(f"  warning       {text}")
    if args.pin and result.target_max > 1e-6 * size:
        # pins read as exact heights; the lifting meets them in least squares
        print(f"  warning       no planar lifting meets every pin: the closest misses vertex "
              f"{result.target_max_vertex} by {length(result.target_max)}")
    if nearly is not None and not nearly.within_tolerance:
        from facet.cli import EXIT_FAILED

        return EXIT_FAILED
    return EXIT_OK


def run_lifting_space(args):
    import numpy as np

    from facet.cli import EXIT_OK, check_files
    from facet.cli_progress import ProgressLine
    from facet.io import write_mesh
    from facet.lift import Lifter
    from facet.report import write_json

    check_files(reads=[("PLAN", args.plan)], writes=[("--report", args.report)],
                creates=[args.output])
    plan = _read_plan(args, "facet lifting-space")
    with _factorizing("facet lifting-space") as progress:
        lifter = Lifter(plan, rank_tol=args.rank_tol, progress=progress)
    limit = plan.n_vertices if args.basis == "fundamental" else lifter.dimension
    # an OBJ per lifting: every vertex's fundamental lifting of a 961-vertex plan was
    # 961 files and 88 MB (15,000 vertices: some 20 GB)
    count = min(DEFAULT_COUNT, limit) if args.count is None else min(args.count, limit)
    line = ProgressLine(sys.stderr, prefix="facet lifting-space")  # a terminal only
    searched = "vertices searched" if args.basis == "sparse" else "liftings"
    # (shown at once: the dense eigen and orthonormal bases report nothing else, and take
    # seconds on a large plan: 6 s for a 320 x 320 grid's eigen-liftings)
    line.steps(0, count if args.basis != "sparse" else plan.n_vertices, searched)
    try:
        basis, energies = lifter.basis(
            args.basis, count, progress=lambda done, total: line.steps(done, total, searched))
    finally:
        line.close()
    os.makedirs(args.output, exist_ok=True)
    xyz = np.array(plan.mesh.vertices, dtype=np.float64)
    size = float(np.ptp(xyz[:, :2], axis=0).max())
    files = []
    try:
        for k, heights in enumerate(basis):
            line.steps(k, count, "OBJ files written")
            peak = float(np.max(np.abs(heights)))
            xyz[:, 2] = heights * (0.2 * size / peak) if peak > 0 else 0.0
            name = f"{args.basis}_{k:04d}.obj"
            write_mesh(plan.mesh.with_vertices(xyz), os.path.join(args.output, name))
            files.append(name)
    finally:
        line.close()
    table = os.path.join(args.output, f"{args.basis}.csv")
    from facet.io.files import format_float, write_text

    lines = ["vertex,x,y," + ",".join(f"b{k}" for k in range(count)) + "\n"]
    for v in range(plan.n_vertices):
        values = [format_float(float(c)) for c in plan.mesh.vertices[v, :2]]
        values += [format_float(float(b)) for b in basis[:, v]]
        lines.append(f"{v}," + ",".join(values) + "\n")
    write_text(table, lines)
    report = {
        "source": os.fspath(args.plan),
        "vertices": int(plan.n_vertices),
        "faces": int(plan.n_faces),
        "dimension": int(lifter.dimension),
        "trivial_dimension": lifter.trivial_dimension,
        "basis": args.basis,
        "count": int(count),
        "energies": [float(e) for e in energies],
        "factor_seconds": float(lifter.factor_seconds),
        "output": os.fspath(args.output),
        "files": files + [os.path.basename(table)],
        "obj_height_scale": "each OBJ scaled to a peak height of 0.2 x the plan size; "
        "the CSV has the unscaled values",
        "plan": plan.summary(),
    }
    if args.report:
        write_json(report, args.report)
    print(f"facet lifting-space: {args.plan}: dimension {lifter.dimension} "
          f"({lifter.trivial_dimension} trivial); {count} {args.basis} liftings written to "
          f"{args.output}")
    if args.count is None and count < limit:
        print(f"  note          the first {count} of {limit}; --count K writes more")
    for text in plan.warnings:
        print(f"  warning       {text}")
    if lifter.pieces > 1:
        print(f"  warning       the plan is in {lifter.pieces} separate pieces that share no "
              "vertex")
    return EXIT_OK


def add_commands(commands):
    from facet.cli import _positive_int

    lift = commands.add_parser(
        "lift",
        help="give a plan drawing heights so that every face is planar, close to targets",
        description="Lift a plan drawing: heights for every vertex such that every face is "
        "exactly planar, as close as possible (weighted least squares) to the targets.",
    )
    _plan_options(lift)
    lift.add_argument("-o", "--output", metavar="OUT", required=True,
                      help="lifted mesh (.obj or .off)")
    lift.add_argument("--targets", metavar="T", help="target surface (.obj, .off, .json: "
                      "vertical projection or per-vertex) or x,y,z points (.csv/.tsv/.txt)")
    lift.add_argument("--pin", action="append", default=[], metavar="V=H",
                      help="pin vertex V at height H (the rest free); repeatable")
    lift.add_argument("--weights", metavar="W", help="file with one weight per plan vertex")
    lift.add_argument("--move-tolerance", type=float, metavar="D",
                      help="nearly liftable drawings: move plan vertices by at most D so that "
                      "a lifting close to the targets exists (best effort; moves reported)")
    lift.set_defaults(run=run_lift)

    space = commands.add_parser(
        "lifting-space",
        help="the dimension and a basis of every planar lifting of a plan",
        description="Compute the lifting space of a plan (every assignment of heights making "
        "all faces planar): its dimension and basis functions, written as OBJ meshes and a CSV.",
    )
    _plan_options(space)
    space.add_argument("-o", "--output", metavar="DIR", required=True, help="output folder")
    space.add_argument("--basis", choices=("fundamental", "eigen", "orthonormal", "sparse"),
                       default="eigen", help="basis kind (default eigen: smoothest first)")
    space.add_argument("--count", type=_positive_int, metavar="K",
                       help=f"how many basis liftings, one OBJ each (default {DEFAULT_COUNT}; "
                       "at most the dimension, or the vertices for fundamental)")
    space.set_defaults(run=run_lifting_space)
