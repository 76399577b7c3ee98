# SPDX-License-Identifier: LGPL-2.1-or-later
"""``facet panels``: from a planar mesh to panel solids, cut sheets and a schedule.

::

    python3 -m facet panels MESH --thickness T [--offset outer|inner|center]
        [--gap G] [--edge square|bisector] [--flip] [--ids auto|grid|index]
        [--prefix P] [--tol T] [--min-edge F] [--min-edge-abs L] [--sheet WxH]
        [--margin M] [--spacing S]
        [--rotations none|90|free] [--tight] [--grain X,Y,Z] [--dxf OUT.dxf] [--per-sheet]
        [--text-outlines]
        [--step OUT.step] [--schedule OUT.csv|OUT.json] [--svg DIR] [--png DIR]
        [--report R.json]

Exit status 0 done, 1 failed (also: --step without FreeCAD), 2 bad input (a zero
thickness, faces not planar, a gap that consumes a panel, a part that fits on no
sheet: nothing written...), 130 Ctrl+C (the files written before it stay; a file
being written is not left half-written).
"""

import math
import os
import sys
import time

from facet.report import count_noun, first_names

__all__ = ["add_commands", "run_panels", "run_pipeline", "write_schedule"]


def _sheet(text):
    import argparse

    parts = text.lower().replace("*", "x").split("x")
    try:
        w, h = (float(p) for p in parts)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not WIDTHxHEIGHT (e.g. 3000x1500)") from None
    if not (math.isfinite(w) and math.isfinite(h)):
        raise argparse.ArgumentTypeError(f"sheet {text!r} must have a finite width and height "
                                         "(a sheet of stock, e.g. 3000x1500)")
    if not (w > 0 and h > 0):
        raise argparse.ArgumentTypeError(f"sheet {text!r} must have a width and height > 0")
    return w, h


def _vector(text):
    import argparse

    try:
        v = tuple(float(p) for p in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not X,Y,Z") from None
    if len(v) != 3:
        raise argparse.ArgumentTypeError(f"{text!r} is not X,Y,Z")
    return v


def add_commands(commands):
    """Add the ``panels`` sub-command to the argparse sub-parsers object."""
    from facet.cli import _non_negative_float
    from facet.nest import DEFAULT_MARGIN_MM, DEFAULT_SPACING_MM
    from facet.panels import DEFAULT_GAP_MM, DEFAULT_MIN_EDGE
    from facet.part_types import DEFAULT_TOL_MM

    p = commands.add_parser(
        "panels",
        help="panel solids, nested cut sheets (DXF), STEP and a schedule from a planar mesh",
        description="Turn every planar face into a panel of the given thickness with square or "
        "mitred edges, lay the panels flat with their IDs and bevel angles, nest them on "
        "stock sheets and write DXF, STEP, a schedule and previews.",
    )
    p.add_argument("input", metavar="MESH", help="planar mesh (.obj, .off, .json)")
    p.add_argument("--item", metavar="NAME", help="mesh to read from a RhinoVAULT .json session")
    p.add_argument("--thickness", type=float, required=True, help="panel thickness (model units)")
    p.add_argument("--offset", choices=("outer", "inner", "center"), default="outer",
                   help="panel on the outer side of the surface (default), inner, or centred")
    p.add_argument("--gap", type=float,
                   help=f"joint width between panels (default {DEFAULT_GAP_MM:g} mm, in "
                   "--units; 0 puts the panels' edges on the mesh's, and square cuts then "
                   "overlap on every valley)")
    p.add_argument("--edge", choices=("square", "bisector"), default="square",
                   help="edge cuts square to the panel (default) or mitred")
    p.add_argument("--flip", action="store_true", help="swap the outer and inner sides")
    p.add_argument("--ids", choices=("auto", "grid", "index"), default="auto",
                   help="part IDs from grid row/column or face index (default auto: grid "
                   "when the mesh is a grid, else index)")
    p.add_argument("--prefix", default="P-", help="part ID prefix (default P-)")
    p.add_argument("--tol", type=_non_negative_float, default=1e-6,
                   help="planarity tolerance relative to each face's mean edge (default 1e-6)")
    p.add_argument("--tol-abs", type=_non_negative_float, default=0.0,
                   help="planarity tolerance in model units (the larger one applies)")
    p.add_argument("--min-edge", type=_non_negative_float, default=DEFAULT_MIN_EDGE,
                   help="an edge shorter than this fraction of a face's mean edge vanishes: its "
                   "ends become one corner (a quad whose edge vanished is built as a triangle; "
                   f"default {DEFAULT_MIN_EDGE:g}, 0 keeps every edge)")
    p.add_argument("--min-edge-abs", type=_non_negative_float, default=0.0,
                   help="the same in model units (the larger one applies)")
    p.add_argument("--sheet", type=_sheet, metavar="WxH", help="stock sheet size: nest the parts")
    p.add_argument("--margin", type=float,
                   help=f"clear border along sheet edges (default {DEFAULT_MARGIN_MM:g} mm, "
                   "in --units)")
    p.add_argument("--spacing", type=float,
                   help="least distance between parts: the kerf and more (default "
                   f"{DEFAULT_SPACING_MM:g} mm, in --units; 0 lets parts share a cut line)")
    p.add_argument("--rotations", choices=("none", "90", "free"), default="90",
                   help="rotations allowed in nesting (default 90: quarter turns; none "
                   "with --grain)")
    p.add_argument("--tight", action="store_true",
                   help="slower nesting, often on fewer sheets: the parts of the least-filled "
                   "sheets are nested again together")
    p.add_argument("--grain", type=_vector, metavar="X,Y,Z",
                   help="grain direction in model space: parts turned to it, rotations locked")
    p.add_argument("--dxf", metavar="OUT.dxf", help="cut sheets as DXF (needs --sheet)")
    p.add_argument("--per-sheet", action="store_true", help="one DXF file per sheet")
    p.add_argument("--text-outlines", action="store_true",
                   help="IDs and bevel angles in the DXF as the outlines of their letters "
                        "(closed polylines), for CAM programs that import no TEXT")
    p.add_argument("--step", metavar="OUT.step", help="panel solids as STEP (needs FreeCAD)")
    p.add_argument("--schedule", metavar="OUT.csv", help="schedule as .csv or .json")
    p.add_argument("--svg", metavar="DIR", help="SVG preview of each sheet")
    p.add_argument("--png", metavar="DIR", help="PNG preview of each sheet")
    p.add_argument("--report", metavar="R.json", help="JSON report")
    p.add_argument("--density", type=float, metavar="KG_M3",
                   help="the panels' material in kg/m³ (glass 2500, aluminium 2700, steel "
                   "7850): each panel's mass in the schedule (mass_kg), the total and the "
                   "heaviest in the summary")
    p.add_argument("--type-tol", type=_non_negative_float, metavar="D",
                   help="panels whose corners all lie within D of another's, turned and moved, "
                   f"are one part type: T1 (the most panels), T2, ... in the schedule (default "
                   f"{DEFAULT_TOL_MM:g} mm, in --units)")
    p.add_argument("--units", choices=("mm", "cm", "m", "in", "ft"), default="mm",
                   help="the mesh's length unit, and every length given here (default mm): "
                   "the DXF declares it ($INSUNITS), the STEP file is written in mm from it")
    p.set_defaults(run=run_panels)


#: How the panels' errors name the options they advise (facet.panels.OPTION_NAMES).
OPTION_NAMES = {"min_edge": "--min-edge", "min_edge_abs": "--min-edge-abs", "ids": "--ids"}


def run_pipeline(mesh, thickness, offset="outer", gap=None, edge="square", flip=False,
                 ids="auto", prefix="P-", tol=1e-6, tol_abs=0.0, min_edge=None,
                 min_edge_abs=0.0, sheet=None, margin=None,
                 spacing=None, rotations="90", grain=None, dxf=None, per_sheet=False,
                 tight=False,
                 step=None, schedule=None, svg=None, png=None, progress=None,
                 cancelled=None, panel_set=None, solids=None, allow_unplaced=False,
                 units="mm", text_outlines=False, density=None, nested=None,
                 option_names=None, type_tol=None, types=None):
    """Everything ``facet panels`` does, as a function (also used by the
    benchmark). Returns (report dict, PanelSet, drawings, NestResult or None).

    ``progress(stage, done, total)`` returning True cancels, and so does ``cancelled()``
    returning True before the unplaced parts are judged and before each file is written
    (the command line's Ctrl+C, :func:`facet.cli.interrupted`). ``units``: the mesh's
    length unit (:data:`facet.cutsheets.LENGTH_UNITS`), declared in the DXF and the
    reports; the STEP file is scaled from it to millimetres. With ``step``
    (and no ``solids``) the solids and the STEP file are made in a worker
    process while the other stages run (:func:`facet.step.start_step`);
    their times in the report are the worker's, and ``total`` is the wall
    clock of the whole. ``panel_set``
    (a facet PanelSet already computed from ``mesh`` with these options) and
    ``solids`` (its [(id, Part.Solid)], for STEP) are reused when given.
    Parts that fit on no sheet raise :class:`facet.errors.InputError`
    (nothing written) unless `allow_unplaced` is true. ``text_outlines``: the DXF's IDs
    and bevel angles as letter outlines (:func:`facet.cutsheets.write_dxf`). ``margin``
    and ``spacing`` (model units) default to :data:`facet.nest.DEFAULT_MARGIN_MM` and
    :data:`facet.nest.DEFAULT_SPACING_MM` in ``units``, ``gap`` to
    :data:`facet.panels.DEFAULT_GAP_MM` (FreeCAD's PanelSet's too). ``density`` (kg/m³, optional):
    the schedule's and the report's masses (:func:`facet.panels.mass_kg`).
    ``option_names``: how the user sets the options the panels' errors advise
    (:func:`facet.panels.panels`; the command line's: :data:`OPTION_NAMES`).
    ``nested`` (optional): ``(panel_set, drawings, result)`` of an earlier run with the
    same ``sheet``, ``margin``, ``spacing``, ``rotations`` and ``grain``: its drawings and
    nesting are reused when ``panel_set`` is the PanelSet of this run, and its nesting,
    under the new part IDs (:func:`facet.nest.renamed`), when this run's panels (in the
    same order) unfold to the same cut outlines and footprints (other part IDs of the same
    panels: their texts change, not their outlines); else the parts are nested again. The
    report's ``nested`` says whether they were. ``tight``: the slower nesting that
    regroups the least-filled sheets (:func:`facet.nest.nest`'s ``tight``). ``type_tol``
    (model units; default :data:`facet.part_types.DEFAULT_TOL_MM` in ``units``): panels
    whose corners all lie within it of another's are one part type
    (:func:`facet.part_types.part_types`), in the schedule and the report; ``types`` (one
    per panel of ``panel_set``, found within ``type_tol``) are reused when given.
    """
    from facet.cutsheets import length_unit
    from facet.errors import InputError
    from facet.nest import DEFAULT_MARGIN_MM, DEFAULT_SPACING_MM
    from facet.panels import (DEFAULT_GAP_MM, DEFAULT_MIN_EDGE, PanelError, check_density,
                              panels)
    from facet.part_types import DEFAULT_TOL_MM, check_tolerance

    mm_per_unit = length_unit(units)[0]
    if density is not None:
        density = check_density(density)
    if min_edge is None:
        min_edge = DEFAULT_MIN_EDGE
    margin_said = margin is not None
    if margin is None:
        margin = DEFAULT_MARGIN_MM / mm_per_unit
    if spacing is None:
        spacing = DEFAULT_SPACING_MM / mm_per_unit
    type_tol = (DEFAULT_TOL_MM / mm_per_unit if type_tol is None
                else check_tolerance(type_tol, units))
    gap_said = gap is not None
    if gap is None:
        gap = DEFAULT_GAP_MM / mm_per_unit
    if (sheet is not None and not margin_said and all(math.isfinite(v) for v in sheet)
            and 2 * margin >= min(sheet)):
        # (nest() says it too, but of a margin that nobody gave, and of no file)
        raise InputError(_of_source(
            mesh, f"the default margin, {DEFAULT_MARGIN_MM:g} mm"
            + ("" if units == "mm" else f" ({margin:g} {units})")
            + f", leaves nothing of a {sheet[0]:g} x {sheet[1]:g} sheet: "
            f"give a smaller --margin, or the mesh's --units if they are not {units}"))
    if dxf and sheet is None:
        raise InputError("--dxf needs --sheet WxH (the DXF holds nested sheets)")
    if (svg or png) and sheet is None:
        raise InputError("--svg and --png need --sheet WxH (they preview nested sheets)")
    if schedule and os.path.splitext(schedule)[1].lower() not in (".csv", ".json"):
        raise InputError(f"{schedule}: the schedule must be .csv or .json")
    if grain is not None and rotations != "none":
        rotations = "none"

    def stage_progress(stage):
        if progress is None:
            return None
        return lambda done, total: progress(stage, done, total)

    times = {}
    t_start = t = time.perf_counter()
    if panel_set is not None:
        ps = panel_set
    else:
        try:
            ps = panels(mesh, thickness, offset=offset, gap=gap, edge=edge, flip=flip,
                        ids=ids, prefix=prefix, tol=tol, tol_abs=tol_abs, min_edge=min_edge,
                        min_edge_abs=min_edge_abs, progress=stage_progress("panels"),
                        units=units, option_names=option_names)
        except PanelError as error:
            # a mesh in metres taken as millimetres: the default gap (6 mm) consumes its
            # 1.5 mm panels, and the error named a face and a gap, not the units
            units_said = [] if gap_said or "gap" not in str(error) else _units_warnings(
                mesh, units)
            if not units_said:
                raise
            raise PanelError(f"{error}; {units_said[0]}", error.faces) from None
    times["panels"] = time.perf_counter() - t
    t = time.perf_counter()
    if types is None:
        from facet.part_types import part_types

        types = part_types(ps.panels, type_tol, progress=stage_progress("types"))
    times["types"] = time.perf_counter() - t
    job = None
    if step and (solids is None or len(solids) != len(ps.panels)):
        from facet.step import start_step

        # solids and STEP do not depend on the rest: a worker process makes
        # them while this one unfolds, nests and writes the DXF
        job = start_step(step, ps, scale=mm_per_unit)
    from facet.io.files import staged

    try:
        # the DXF, schedule and previews take their places only once the STEP file is
        # written too: a STEP that fails leaves the files of the last whole run
        with staged():
            return _rest_of_pipeline(
                mesh, ps, job, times, t_start, sheet=sheet, margin=margin, spacing=spacing,
                rotations=rotations, grain=grain, dxf=dxf, per_sheet=per_sheet, tight=tight,
                text_outlines=text_outlines, step=step,
                schedule=schedule, svg=svg, png=png, allow_unplaced=allow_unplaced,
                solids=solids, stage_progress=stage_progress, cancelled=cancelled, units=units,
                density=density, nested=nested, types=(types, type_tol))
    except BaseException:
        if job is not None:
            job.cancel()
        raise


def _of_source(mesh, message):
    """``message`` after the name of the file ``mesh`` was read from, if any."""
    source = mesh.info.get("source") if mesh.info else None
    return f"{source}: {message}" if source else message


def write_schedule(path, ps, rows, density=None, units="mm"):
    """Write the schedule ``rows`` (:func:`facet.cutsheets.schedule_rows` of the PanelSet
    ``ps``) to ``path``: JSON when it ends with .json (``ps``'s options, ``units``,
    ``density`` and the columns' units as its meta), else CSV (the columns' units in its
    header)."""
    from facet.cutsheets import write_schedule_csv, write_schedule_json

    if path.lower().endswith(".json"):
        write_schedule_json(path, rows, meta=dict(ps.options, units=units, density=density),
                            units=units)
    else:
        write_schedule_csv(path, rows, units)


def _rest_of_pipeline(mesh, ps, job, times, t_start, sheet, margin, spacing, rotations, grain,
                      tight, dxf, per_sheet, text_outlines, step, schedule, svg, png,
                      allow_unplaced, solids, stage_progress, cancelled, units, density,
                      nested, types):
    from facet.cutsheets import length_unit, schedule_rows, write_dxf, write_png, write_svg
    from facet.errors import Cancelled, InputError
    from facet.nest import nest
    from facet.part_types import type_counts
    from facet.unfold import small_text_warnings, unfold

    def check():
        if cancelled is not None and cancelled():
            raise Cancelled("cancelled")

    t = time.perf_counter()
    drawings = (nested[1] if nested is not None and nested[0] is ps
                else unfold(ps, grain=grain, progress=stage_progress("unfold")))
    # the texts are in the DXF and the previews only: no warning about a text not written
    text_warnings = (small_text_warnings(drawings, length_unit(units)[0], units=units)
                     if dxf or svg or png else [])
    times["unfold"] = time.perf_counter() - t
    result, nested_now = None, False
    if sheet is not None:
        t = time.perf_counter()
        result = _kept_nesting(nested, ps, drawings, sheet, margin, spacing, rotations, tight)
        nested_now = result is None
        if nested_now:
            result = nest({d.id: d.footprint for d in drawings}, sheet, margin=margin,
                          spacing=spacing, rotations=rotations, tight=tight,
                          progress=stage_progress("nest"))
        times["nest"] = time.perf_counter() - t
        check()
        if result.unplaced and not allow_unplaced:
            raise InputError(_of_source(
                mesh, f"{len(result.unplaced)} of {len(drawings)} parts fit on no "
                f"{sheet[0]:g} x {sheet[1]:g} {units} sheet (margin {margin:g} {units}): "
                f"{first_names(result.unplaced, 4)}; use a larger sheet or a smaller margin"))
    files = {}
    if dxf:
        check()
        t = time.perf_counter()
        files["dxf"] = write_dxf(dxf, result, drawings, per_sheet=per_sheet, units=units,
                                 text_outlines=text_outlines, progress=stage_progress("dxf"))
        times["dxf"] = time.perf_counter() - t
    rows = None
    if schedule:
        check()
        t = time.perf_counter()
        rows = schedule_rows(ps, result, drawings, density=density, units=units,
                             types=types[0])
        write_schedule(schedule, ps, rows, density=density, units=units)
        files["schedule"] = [schedule]
        times["schedule"] = time.perf_counter() - t
    if svg:
        check()
        t = time.perf_counter()
        files["svg"] = write_svg(svg, result, drawings, units=units,
                                 progress=stage_progress("svg"))
        times["svg"] = time.perf_counter() - t
    if png:
        check()
        t = time.perf_counter()
        files["png"] = write_png(png, result, drawings, progress=stage_progress("png"))
        times["png"] = time.perf_counter() - t
    if job is not None:
        t = time.perf_counter()
        job.wait(progress=stage_progress("step"))
        times["step_wait"] = time.perf_counter() - t
        # the worker's own times, overlapping the stages above
        times["solids"] = job.seconds["solids"]
        times["step"] = job.seconds["step"]
        files["step"] = [step]
    elif step:
        from facet.step import write_step

        check()
        times["solids"] = 0.0  # reused
        t = time.perf_counter()
        write_step(step, solids, scale=length_unit(units)[0])
        times["step"] = time.perf_counter() - t
        files["step"] = [step]
    times["total"] = time.perf_counter() - t_start

    report = {
        "kind": "panels",
        "input": mesh.info.get("source") if mesh.info else None,
        "options": dict(ps.options, sheet=sheet, margin=margin, spacing=spacing,
                        rotations=rotations, grain=grain, tight=tight),
        "units": units,
        "n_panels": len(ps),
        "id_scheme": ps.id_scheme,
        "grid_shape": ps.grid_shape,
        "panels": rows if rows is not None else schedule_rows(
            ps, result, drawings, density=density, units=units, types=types[0]),
        "part_types": type_counts(types[0]),
        "part_type_tolerance": types[1],
        "sheets": [] if result is None else [
            {"index": s.index + 1, "parts": s.parts, "utilisation": s.utilisation}
            for s in result.sheets],
        "unplaced": [] if result is None else list(result.unplaced),
        "utilisation": None if result is None else result.utilisation,
        "max_node_deviation": ps.max_node_deviation_deg,
        "max_node_deviation_unit": "degrees",
        "worst_node": ps.worst_node,
        "max_planarity": float(ps.planarity.max()),
        "n_vanished_panels": len(ps.vanished_panels),
        "vanished_edges": ps.vanished_edges,
        "short_edges_kept": ps.short_edges_kept,
        "narrowest_joint": ps.narrowest_joint,
        "narrowest_joint_panels": ps.narrowest_joint_panels,
        "overlapping_joints": ps.overlapping_joints,
        "clearing_gap": ps.clearing_gap,
        "node_clash_pairs": ps.node_clash_pairs,
        "deepest_node_clash_panels": ps.deepest_node_clash_panels,
        "node_clashes": ps.node_clashes,
        "warnings": ps.warnings + text_warnings,
        "text_warnings": text_warnings,
        "files": files,
        "seconds": times,
        "nested": nested_now,
    }
    if density is not None:
        masses = [row["mass_kg"] for row in report["panels"]]
        heaviest = max(range(len(masses)), key=masses.__getitem__, default=None)
        report.update(density=density, total_mass_kg=float(sum(masses)),
                      heaviest_panel=None if heaviest is None else
                      {"id": report["panels"][heaviest]["id"], "mass_kg": masses[heaviest]})
    return report, ps, drawings, result


def _kept_nesting(nested, ps, drawings, sheet, margin, spacing, rotations, tight=False):
    """The nesting of ``nested`` (run_pipeline's) for ``ps``'s ``drawings``, under their
    IDs, when it still holds: nested on this sheet with this margin, spacing, rotations
    and ``tight``,
    and of the same panels (``ps`` itself) or of panels whose drawings have the same cut
    outlines and footprints, in the same order. None when the parts must be nested again."""
    import numpy as np

    from facet.nest import renamed

    if nested is None:
        return None
    ps0, drawings0, result = nested
    if (result is None or tuple(result.sheet_size) != tuple(float(v) for v in sheet)
            or result.margin != margin or result.spacing != spacing
            or result.rotations != rotations or result.tight != tight):
        return None
    if ps0 is ps:
        return result
    if len(drawings0) != len(drawings) or not all(
            np.array_equal(a.cut, b.cut) and np.array_equal(a.footprint, b.footprint)
            for a, b in zip(drawings0, drawings)):
        return None
    if all(a.id == b.id for a, b in zip(drawings0, drawings)):
        return result
    return renamed(result, {a.id: b.id for a, b in zip(drawings0, drawings)})


#: What each stage of run_pipeline counts, on the progress line.
_STAGE_WORDS = {"panels": "building the panels", "types": "comparing the parts",
                "unfold": "unfolding the parts",
                "nest": "nesting the parts",
                "step": "making the STEP solids", "dxf": "drawing the DXF's parts",
                "svg": "writing the SVG sheets", "png": "writing the PNG sheets"}


def panels_progress(line, cancelled):
    """run_pipeline's ``progress(stage, done, total)`` that shows each stage's count on
    ``line`` (a :class:`facet.cli_progress.ProgressLine`) and cancels when ``cancelled()``."""
    def progress(stage, done, total):
        line.steps(done, total, _STAGE_WORDS.get(stage, stage))
        return cancelled()

    return progress


def run_panels(args):
    """Run ``facet panels``; return the exit status."""
    from facet.cli import EXIT_OK, _read, check_files, interrupted
    from facet.cli_progress import ProgressLine
    from facet.panels import length_text
    from facet.report import write_json

    check_files(reads=[("MESH", args.input)],
                writes=[("--dxf", args.dxf), ("--step", args.step),
                        ("--schedule", args.schedule), ("--report", args.report)],
                creates=[args.svg, args.png])
    mesh = _read(args)
    line = ProgressLine(sys.stderr, prefix="facet panels")  # a terminal only
    try:
        report, ps, drawings, result = run_pipeline(
            mesh, args.thickness, offset=args.offset, gap=args.gap, edge=args.edge,
            flip=args.flip, ids=args.ids, prefix=args.prefix, tol=args.tol,
            tol_abs=args.tol_abs, min_edge=args.min_edge, min_edge_abs=args.min_edge_abs,
            sheet=args.sheet, margin=args.margin, spacing=args.spacing,
            rotations=args.rotations, tight=args.tight, grain=args.grain, dxf=args.dxf,
            per_sheet=args.per_sheet, text_outlines=args.text_outlines, step=args.step,
            schedule=args.schedule, svg=args.svg, png=args.png,
            progress=panels_progress(line, interrupted), cancelled=interrupted,
            units=args.units, density=args.density, option_names=OPTION_NAMES,
            type_tol=args.type_tol)
    finally:
        line.close()  # (before the summary, or an error's message)
    report["input"] = args.input
    if args.report:
        write_json(report, args.report)
    out = sys.stdout
    print(f"  panels        {len(ps)} ({ps.id_scheme} IDs"
          + (f", {ps.grid_shape[0]} x {ps.grid_shape[1]} grid" if ps.grid_shape else "") + ")",
          file=out)
    if ps.vanished_edges or ps.short_edges_kept:
        vanished = ps.vanished_panels
        shown = first_names((p.id for p in vanished), 4)
        print(f"  vanished      {count_noun(len(vanished), 'panel')} built with fewer corners "
              f"({count_noun(len(ps.vanished_edges), 'edge')} under min_edge merged to a corner"
              + (f"; {len(ps.short_edges_kept)} kept" if ps.short_edges_kept else "") + ")"
              + (f": {shown}" if shown else ""), file=out)
    length = length_text(args.units)
    print(f"  types         {part_types_text(report, length)}", file=out)
    if ps.narrowest_joint is not None:
        a, b = ps.narrowest_joint_panels
        if ps.overlapping_joints:
            # (with node clashes too, ClearingGap is the gap that clears those as well: the
            # joints' warning gives the smaller one for the joints alone)
            clears = (f"a gap of {length(ps.clearing_gap, '.4g')} clears them"
                      + (" and the nodes' overlaps" if ps.node_clashes else "")
                      if ps.clearing_gap is not None else "no gap found that clears every overlap")
            print(f"  joints        {ps.overlapping_joints} overlap, the deepest by "
                  f"{length(-ps.narrowest_joint, '.4g')} ({a} and {b}); {clears}", file=out)
        else:
            print(f"  joints        narrowest {length(ps.narrowest_joint, '.4g')} "
                  f"(gap {length(ps.options['gap'], '.4g')}), between {a} and {b}", file=out)
    print(f"  nodes         largest deviation from a common axis "
          f"{ps.max_node_deviation_deg:.3g} degrees"
          + (f"; {count_noun(ps.node_clash_pairs, 'pair')} of panels "
             f"overlap at {count_noun(len(ps.node_clashes), 'node')}, "
             f"the deepest by {length(ps.node_clashes[0]['depth'], '.4g')} "
             f"({' and '.join(ps.deepest_node_clash_panels)})"
             + (f"; a gap of {length(ps.clearing_gap, '.4g')} clears every overlap"
                if ps.clearing_gap is not None else "") if ps.node_clashes else ""),
          file=out)
    if report.get("heaviest_panel"):
        heaviest = report["heaviest_panel"]
        print(f"  mass          {report['total_mass_kg']:,.1f} kg in all at "
              f"{report['density']:g} kg/m³, the heaviest {heaviest['id']} "
              f"{heaviest['mass_kg']:,.1f} kg", file=out)
    if result is not None:
        print(f"  sheets        {len(result.sheets)}, utilisation {100 * result.utilisation:.1f}%"
              f", {len(result.unplaced)} unplaced", file=out)
        if result.unplaced:
            shown = first_names(result.unplaced, 8)
            print(f"facet: warning: {len(result.unplaced)} parts fit on no sheet: {shown}",
                  file=sys.stderr)
    for kind, paths in report["files"].items():
        print(f"  {kind:<13} {', '.join(paths[:3])}" + (" ..." if len(paths) > 3 else ""),
              file=out)
    for w in report["warnings"] + _units_warnings(mesh, args.units):
        print(f"facet: warning: {w}", file=sys.stderr)
    return EXIT_OK


def part_types_text(report, length):
    """How many part types run_pipeline's ``report`` found, and the largest:
    "2 part types within 0.5 mm: T1 132 panels, T2 24". ``length``:
    :func:`facet.panels.length_text`'s."""
    counts = report["part_types"]
    within = f"within {length(report['part_type_tolerance'], '.3g')}"
    if len(counts) == report["n_panels"] > 1:
        return f"{count_noun(len(counts), 'part type')} {within}: every panel its own"
    shown = [f"{t} {n}" for t, n in list(counts.items())[:4]]
    shown[0] += " panels" if counts["T1"] > 1 else " panel"
    return (f"{count_noun(len(counts), 'part type')} {within}: {', '.join(shown)}"
            + (", ..." if len(counts) > 4 else ""))


def _units_warnings(mesh, units):
    """A warning when the panels' size in the declared units is far from any facade's: a
    mesh in metres cut as millimetres gives parts a thousandth of their size."""
    from facet.cutsheets import implausible_edge_mm

    edge = implausible_edge_mm(mesh.mean_edge_length(), units)
    if edge is None:
        return []
    return [f"the panels' edges are {edge:.3g} mm long on average, taking the mesh to be in "
            f"{units} (--units): if it is in other units, say which, or the DXF and STEP "
            "files give parts of the wrong size"]
