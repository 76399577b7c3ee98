# SPDX-License-Identifier: LGPL-2.1-or-later
"""``facet cleanup``: collapse short edges, then planarize the new mesh; ``facet weld``:
join the vertices at one point that are not one vertex.

::

    python3 -m facet cleanup IN -o OUT --min-edge L [--relative] [--method auto|ll|lg]
        [--tol T] [--threads N] [--report R.json]
    python3 -m facet weld IN -o OUT [--tol REL]

``--min-edge`` is in model units, or a fraction of the mean edge length with
``--relative``. The report holds the cleanup (threshold, collapsed edges,
removed faces), the planarization of the new mesh and its quality, with the
distance measured from the surface of the original input.
"""

import sys

__all__ = ["add_commands", "run_cleanup", "run_weld"]


def add_commands(commands):
    """Add the ``cleanup`` sub-command to the argparse sub-parsers `commands`."""
    from facet.cli import _non_negative_float, _non_negative_int, _positive_float

    parser = commands.add_parser(
        "cleanup",
        help="collapse edges shorter than a length, then planarize again",
        description="Collapse every edge shorter than --min-edge (faces lose corners, faces "
        "left with fewer than 3 vertices go), then planarize the new mesh and write it.",
    )
    parser.add_argument("input", metavar="IN", help="mesh to clean up (.obj, .off, .json)")
    parser.add_argument("-o", "--output", metavar="OUT", required=True,
                        help="cleaned and planarized mesh (.obj or .off)")
    parser.add_argument("--min-edge", type=_positive_float, required=True, metavar="L",
                        help="collapse edges shorter than L (model units, or a fraction of the "
                        "mean edge length with --relative)")
    parser.add_argument("--relative", action="store_true",
                        help="--min-edge is a fraction of the mean edge length")
    parser.add_argument("--method", choices=("auto", "ll", "lg"), default="auto",
                        help="planarization method (default auto: lg up to 40,000 face "
                        "corners, ll above)")
    parser.add_argument("--tol", type=_non_negative_float, default=1e-6, metavar="T",
                        help="planarity tolerance relative to each face's mean edge "
                        "(default 1e-6)")
    parser.add_argument("--threads", type=_non_negative_int, metavar="N",
                        help="threads to use (0: one per 25,000 quads, at most all cores)")
    parser.add_argument("--report", metavar="R.json", help="write a JSON report")
    parser.add_argument("--item", metavar="NAME",
                        help="mesh to read from a RhinoVAULT .json session")
    parser.set_defaults(run=run_cleanup)

    parser = commands.add_parser(
        "weld",
        help="join the vertices at one point that are not one vertex",
        description="Join the vertices that lie within --tol times the mesh's size of each "
        "other into one (an export that gives each face or part its own vertices leaves "
        "seams that look joined and are not: planarize opens them, panels cuts them square "
        "with no bevel), and write the mesh. Faces keep their order; nothing else moves.",
    )
    parser.add_argument("input", metavar="IN", help="mesh to weld (.obj, .off, .json)")
    parser.add_argument("-o", "--output", metavar="OUT", required=True,
                        help="welded mesh (.obj or .off)")
    parser.add_argument("--tol", type=_positive_float, default=1e-9, metavar="REL",
                        help="largest distance joined, times the mesh's largest extent "
                        "(default 1e-9, the seams planarize and panels warn of)")
    parser.add_argument("--item", metavar="NAME",
                        help="mesh to read from a RhinoVAULT .json session")
    parser.set_defaults(run=run_weld)


def run_cleanup(args):
    """Run ``facet cleanup``; return the exit status."""
    from facet import cleanup, planarity
    from facet.cli import (EXIT_OK, _line, _read, check_files, planarize_stoppable,
                           print_planarize_summary, stopped_with_result)
    from facet.io import write_mesh, writer_for
    from facet.quality import quality
    from facet.report import count_noun, planarize_report, write_json
    from facet.surface import Surface

    writer_for(args.output)
    check_files(reads=[("IN", args.input)],
                writes=[("-o", args.output), ("--report", args.report)])
    mesh = _read(args)
    cleaned = cleanup(mesh, args.min_edge, relative=args.relative)
    before = planarity(cleaned.mesh, threads=args.threads)
    result, stopped = planarize_stoppable(cleaned.mesh, prefix="facet cleanup",
                                          method=args.method, tol=args.tol,
                                          threads=args.threads)
    write_mesh(result.mesh, args.output)
    report = planarize_report(
        cleaned.mesh, result, input_path=args.input, output_path=args.output,
        input_planarity=before,
    )
    report["command"] = "cleanup"
    report["cleanup"] = cleaned.as_dict()
    report["cleanup"]["input_vertices"] = mesh.n_vertices
    report["cleanup"]["input_faces"] = mesh.n_faces
    report["cleanup"]["min_edge"] = args.min_edge
    report["cleanup"]["relative"] = bool(args.relative)
    # distance from the original design surface, not from the collapsed mesh
    report["quality"] = quality(result, input=cleaned.mesh, reference=Surface(mesh),
                                threads=args.threads).as_dict()
    if args.report:
        report["report"] = args.report
        write_json(report, args.report)
    c = report["cleanup"]
    print(f"facet cleanup: {args.input}")
    _line(sys.stdout, "cleanup",
          f"{count_noun(c['collapsed_edges'], 'edge')} shorter than {c['threshold']:.3g} "
          f"collapsed, {count_noun(c['removed_faces'], 'face')} removed: "
          f"{mesh.n_vertices} -> {c['vertices']} vertices, "
          f"{mesh.n_faces} -> {c['faces']} faces")
    if c["skipped_edges"]:
        _line(sys.stdout, "warning",
              f"{c['skipped_edges']} short edges kept: collapsing them would make the mesh "
              "non-manifold")
    print_planarize_summary(report)
    if stopped:
        return stopped_with_result(args.output)
    return EXIT_OK


def run_weld(args):
    """Run ``facet weld``; return the exit status."""
    from facet.cli import EXIT_OK, _line, _read, check_files
    from facet.io import write_mesh, writer_for
    from facet.mesh import weld
    from facet.report import count_noun

    writer_for(args.output)
    check_files(reads=[("IN", args.input)], writes=[("-o", args.output)])
    mesh = _read(args)
    welded, merged = weld(mesh, args.tol)
    write_mesh(welded, args.output)
    print(f"facet weld: {args.input}")
    _line(sys.stdout, "welded",
          f"{count_noun(merged, 'vertex')} joined to another: {mesh.n_vertices} -> "
          f"{welded.n_vertices} vertices, {count_noun(welded.n_faces, 'face')}")
    _line(sys.stdout, "written", args.output)
    return EXIT_OK
