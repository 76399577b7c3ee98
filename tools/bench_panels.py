# SPDX-License-Identifier: LGPL-2.1-or-later
"""Benchmark of the panel pipeline: mesh -> panels -> solids, outlines, nesting, DXF, STEP,
schedule, each stage timed (wall clock, perf_counter). Not a test: it asserts nothing about
speed; it prints the figures and writes them as JSON.

    /usr/bin/python3 tools/bench_panels.py [--panels 10000] [--out DIR] [--no-step]
                                           [--repeat N] [--workers W] [--sequential]

The mesh is a planar-quad grid on a cylinder (radius 40 m, panels about 600 x 450 mm), so
every face is exactly planar; edges are mitred with a 6 mm gap, 30 mm thick; sheets
3000 x 1500 with a 10 mm margin and 6 mm spacing, quarter-turn rotations. With --repeat N
the pipeline runs N times and each stage's median is reported (all runs are in the JSON);
the load average before and after is recorded, since the machine may be shared.

Solids and STEP do not depend on the nesting, so (as ``facet panels`` does) a worker process
makes them while the nesting runs; the total is the end-to-end wall clock, and the
overlapped stages are listed with their own times. ``--sequential`` runs every stage
one after the other in this process (the earlier way), for comparison.
"""

import argparse
import json
import math
import os
import platform
import statistics
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "workbench"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--panels", type=int, default=10000)
    parser.add_argument("--out", default=os.path.join(os.path.dirname(HERE), "out", "bench_panels"))
    parser.add_argument("--no-step", action="store_true", help="skip solids and STEP")
    parser.add_argument("--repeat", type=int, default=1, help="runs; medians reported")
    parser.add_argument("--workers", type=int, default=None,
                        help="nesting worker processes (default: facet.nest's)")
    parser.add_argument("--sequential", action="store_true",
                        help="solids and STEP after the other stages, in this process "
                             "(default: in a worker process while nesting runs)")
    args = parser.parse_args()

    import numpy as np

    from facet.cutsheets import schedule_rows, write_dxf, write_schedule_csv
    from facet.mesh import PolyMesh
    from facet.nest import nest, verify
    from facet.panels import panels
    from facet.unfold import unfold

    os.makedirs(args.out, exist_ok=True)
    n = int(round(math.sqrt(args.panels)))
    nu, nv = n, max(1, args.panels // n)
    radius, height = 40000.0, 450.0
    angle = 600.0 / radius
    pts = [[radius * math.cos(i * angle), radius * math.sin(i * angle), j * height]
           for j in range(nv + 1) for i in range(nu + 1)]
    faces = []
    for j in range(nv):
        for i in range(nu):
            a = j * (nu + 1) + i
            faces.append([a, a + 1, a + nu + 2, a + nu + 1])
    mesh = PolyMesh.from_faces(np.array(pts), faces)

    def run():
        times = {}
        t_start = time.perf_counter()

        t = time.perf_counter()
        ps = panels(mesh, 30.0, edge="bisector", gap=6.0)
        times["panels (core geometry + Python objects)"] = time.perf_counter() - t
        times["  of which core facet_panels"] = ps.seconds
        job = None
        if not args.no_step and not args.sequential:
            from facet.step import start_step

            # solids and STEP do not depend on the nesting: a worker process
            # makes them while nesting's workers wait on libnest2d's threads
            job = start_step(os.path.join(args.out, "panels.step"), ps)
        t = time.perf_counter()
        drawings = unfold(ps)
        times["outlines (unfold, labels, footprints)"] = time.perf_counter() - t
        parts = {d.id: d.footprint for d in drawings}
        t = time.perf_counter()
        result = nest(parts, (3000.0, 1500.0), margin=10.0, spacing=6.0, rotations="90",
                      workers=args.workers)
        times["nesting (libnest2d)"] = time.perf_counter() - t
        t = time.perf_counter()
        write_dxf(os.path.join(args.out, "sheets.dxf"), result, drawings)
        times["DXF (ezdxf, audited)"] = time.perf_counter() - t
        t = time.perf_counter()
        write_schedule_csv(os.path.join(args.out, "schedule.csv"), schedule_rows(ps, result, drawings))
        times["schedule CSV"] = time.perf_counter() - t
        if job is not None:
            t = time.perf_counter()
            job.wait()
            times["waiting for solids + STEP after the schedule"] = time.perf_counter() - t
            times["  solids (OCC, BRepCheck; worker, overlapped)"] = job.seconds["solids"]
            times["  STEP (worker, overlapped)"] = job.seconds["step"]
        elif not args.no_step:
            from facet.step import panel_solids, write_step

            t = time.perf_counter()
            solids = panel_solids(ps)
            times["solids (OCC, BRepCheck)"] = time.perf_counter() - t
            t = time.perf_counter()
            write_step(os.path.join(args.out, "panels.step"), solids)
            times["STEP (FreeCAD Import, no pcurves)"] = time.perf_counter() - t
        times["total (wall clock, end to end)"] = time.perf_counter() - t_start
        t = time.perf_counter()
        problems = verify(result, parts)
        times["  nesting check (shapely; after, not in the total)"] = time.perf_counter() - t
        return times, ps, result, problems

    load_before = os.getloadavg()
    runs = [run() for _ in range(max(1, args.repeat))]
    load_after = os.getloadavg()
    times = {k: statistics.median(r[0][k] for r in runs) for k in runs[0][0]}
    _, ps, result, problems = runs[-1]
    total = times["total (wall clock, end to end)"]
    report = {
        "panels": len(ps), "sheets": len(result.sheets), "unplaced": len(result.unplaced),
        "utilisation": result.utilisation, "nesting_problems": len(problems),
        "seconds": times, "total_seconds": total,
        "runs": [r[0] for r in runs], "median_of": len(runs),
        "load_average_before": load_before, "load_average_after": load_after,
        "machine": {"cpus": os.cpu_count(), "python": platform.python_version()},
    }
    for k, v in times.items():
        print(f"{k:<50} {v:9.2f} s")
    print(f"(median of {len(runs)}; load average {load_before[0]:.1f} before, "
          f"{load_after[0]:.1f} after, {os.cpu_count()} CPUs; "
          f"{'stages one after another' if args.sequential else 'solids + STEP overlapped'})")
    print(f"{len(ps)} panels on {len(result.sheets)} sheets, utilisation "
          f"{100 * result.utilisation:.1f}%, {len(result.unplaced)} unplaced, "
          f"{len(problems)} nesting problems")
    with open(os.path.join(args.out, "bench_panels.json"), "w", encoding="utf-8") as f:
        json.dump(report, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
