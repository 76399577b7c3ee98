# SPDX-License-Identifier: LGPL-2.1-or-later
"""The issue-3 targets against a benchmark run, as a Markdown table.

Reads ``bench.json`` (run_bench.py) and, when present, ``interactive.json``
(interactive.py) from a folder and prints one row per target with the
measured figure, so docs/benchmarks.md is written from data, not by hand.

    /usr/bin/python3 tools/bench/summarize.py out/bench
"""

import json
import statistics
import sys
from pathlib import Path


def results(doc, config, threads):
    for m in doc["meshes"]:
        for rep in m["by_threads"]:
            if rep.get("threads") != threads:
                continue
            for r in rep.get("results", []):
                if r["config"] == config:
                    yield m, r


def ok(rs):
    return [(m, r) for m, r in rs if r.get("status") == "ok"]


def fmt_ns(r, n_faces):
    wall = r["ns_per_face_iteration"]
    cpu = 1e9 * r["median_cpu_seconds"] / (n_faces * r["iterations"])
    return f"{wall:.0f} wall / {cpu:.0f} CPU"


def summarize(folder):
    folder = Path(folder)
    doc = json.loads((folder / "bench.json").read_text())
    rows = []
    # L/L on quads, 1 thread, and 2-thread speed-up
    quads = [m for m in doc["meshes"] if m["family"] in ("quad_grid", "quad_torus")]
    ll1 = {m["name"]: r for m, r in ok(results(doc, "ll100", 1)) if m in quads}
    ll2 = {m["name"]: r for m, r in ok(results(doc, "ll100", 2)) if m in quads}
    faces = {m["name"]: m["faces"] for m in quads}
    if ll1:
        text = "; ".join(f"{n} ({faces[n]:,} faces): {fmt_ns(r, faces[n])}" for n, r in ll1.items())
        rows.append(("L/L <= 30 ns/face/iter, 1 thread, quads", text))
        sp = [f"{n}: {ll1[n]['median_seconds'] / ll2[n]['median_seconds']:.2f}x"
              for n in ll1 if n in ll2]
        rows.append(("L/L >= 1.8x on 2 threads", "; ".join(sp)))
    # L/G x30 on Level 5
    for threads in (1, 2):
        for m, r in ok(results(doc, "lg30", threads)):
            if m["name"] == "Level 5":
                rows.append((f"L/G x30 on Level 5 <= 50 ms ({threads} thread{'s' * (threads > 1)})",
                             f"{1e3 * r['median_seconds']:.0f} ms wall, {1e3 * r['median_cpu_seconds']:.0f} ms CPU"
                             f" (median of {r['runs']}; cold {1e3 * r['cold_seconds']:.0f} ms)"))
    # every mesh to 1e-6
    tol = list(results(doc, "tol", 1))
    reached = [m["name"] for m, r in tol if r.get("status") == "ok" and r.get("reached_tolerance")]
    budget = [f"{m['name']} (> {r['budget_seconds']:g} s, {r['iterations']} it, {r['planarity_max_rel']:.1e})"
              for m, r in tol if r.get("status") == "budget"]
    missed = [f"{m['name']} ({r.get('stop_reason')}, {r.get('planarity_max_rel', float('nan')):.1e})"
              for m, r in tol if r.get("status") == "ok" and not r.get("reached_tolerance")]
    errors = [f"{m['name']} ({r.get('status')}: {r.get('note')})" for m, r in tol
              if r.get("status") not in ("ok", "budget")]
    text = f"{len(reached)} of {len(tol)} reached it (1 thread)"
    if missed:
        text += "; stopped above 1e-6: " + ", ".join(missed)
    if budget:
        text += "; cancelled at the time budget: " + ", ".join(budget)
    if errors:
        text += "; errors: " + ", ".join(errors)
    rows.append(("every mesh to planarity_max_rel <= 1e-6 by default", text))
    iters = [r["iterations"] for m, r in tol if r.get("status") == "ok"]
    if iters:
        rows.append(("iterations to tolerance (default schedule)",
                     f"median {statistics.median(iters):g}, range {min(iters)}-{max(iters)}"))
    # 1M quads on 2 threads
    big = [(m, r) for m, r in results(doc, "tol", 2) if m["faces"] >= 1_000_000]
    for m, r in big:
        if r.get("status") == "ok":
            rows.append((f"1M quads to tolerance < 5 s, 2 threads ({m['name']})",
                         f"{r['median_seconds']:.1f} s, {r['iterations']} it"))
        else:
            rows.append((f"1M quads to tolerance < 5 s, 2 threads ({m['name']})",
                         f"not reached: {r.get('note')}, planarity {r.get('planarity_max_rel', float('nan')):.1e}"))
    # peak memory: issue 3's target is the default solve to tolerance's; since
    # run_bench measures each configuration on its own planarizer, that is the
    # "tol" rows' figure (the L/G x30 rows give the factor's cost for comparison)
    for config, label in (("tol", "default solve to tolerance"), ("lg30", "L/G x30 asked for")):
        mem = []
        for m in doc["meshes"]:
            if m["faces"] < 3_000:  # below, the process's fixed costs dominate a per-face figure
                continue
            peaks = [r["peak_bytes_per_face"] for rep in m["by_threads"]
                     for r in rep.get("results", []) if r["config"] == config
                     and r.get("peak_bytes_per_face") is not None]
            if peaks:
                mem.append((max(peaks), m["faces"], m["name"]))
        if mem:
            over = [n for b, _, n in mem if b >= 1024]
            rows.append((f"peak memory < 1 KB/face, {label} (meshes >= 3,000 faces, RSS growth)",
                         f"{len(mem) - len(over)} of {len(mem)} under; largest {max(mem)[0]:.0f} B/face "
                         f"({max(mem)[2]}); "
                         + ", ".join(f"{n}: {b:.0f}" for b, _, n in sorted(mem, key=lambda t: t[1]))))
    # quality
    q = [(m, r) for m, r in tol if r.get("status") == "ok"]
    if q:
        newly = sum(r["faces_newly_below_5deg"] for m, r in q)
        worst = min(q, key=lambda t: t[1]["min_angle_out"] - t[1]["min_angle_in"])
        rows.append(("quality: no new face with smallest angle < 5 deg",
                     f"{newly} new faces below 5 deg over {len(q)} meshes; largest drop of the smallest "
                     f"angle: {worst[0]['name']} {worst[1]['min_angle_in']:.1f} -> "
                     f"{worst[1]['min_angle_out']:.1f} deg"))
    inter = folder / "interactive.json"
    if inter.exists():
        idoc = json.loads(inter.read_text())
        for w in idoc.get("warm", []):
            rows.append((f"re-solve after a 1% move < 16 ms at 10k faces ({w['mesh']}, {w['threads']} thread, "
                         f"{w.get('mode', 'warm')}, {w.get('edit_pattern', 'random vertices')})",
                         f"median {1e3 * w['median_seconds']:.1f} ms, max {1e3 * w['max_seconds']:.1f} ms;"
                         f" iterations median {w['median_iterations']:g}; {w['reached_tolerance']}/{w['edits']}"
                         f" reached 1e-6"))
        lg = idoc.get("level5_lg30")
        if lg:
            rows.append(("L/G x30 on Level 5 (interactive.py)",
                         f"median {1e3 * lg['median_seconds']:.0f} ms, min {1e3 * lg['min_seconds']:.0f} ms"))
    blas = doc.get("blas_check")
    if blas:
        rows.append(("OPENBLAS_NUM_THREADS effect on L/G x30, Level 5",
                     "; ".join(f"threads={b['threads']} OPENBLAS={b['openblas_num_threads'] or 'unset'}: "
                               f"{1e3 * b['median_seconds']:.0f} ms"
                               for b in blas if b.get("median_seconds") is not None)))
    meta = doc["meta"]
    out = [f"Run: {meta.get('started')} ({meta.get('mode')}), {meta.get('cpu', '?')}, {meta.get('cpus')} CPUs, "
           f"load average before {tuple(round(x, 1) for x in meta.get('load_average', ()))}, after "
           f"{tuple(round(x, 1) for x in meta.get('load_average_after', ()))}", "",
           "| target | measured |", "|---|---|"]
    out += [f"| {a} | {b} |" for a, b in rows]
    return "\n".join(out)


if __name__ == "__main__":
    print(summarize(sys.argv[1] if len(sys.argv) > 1 else "out/bench"))
