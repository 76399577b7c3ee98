# SPDX-License-Identifier: LGPL-2.1-or-later
"""Planarization benchmark driver: the paper's families and the public meshes.

For every mesh (see ``families.py``) and every thread count, a fresh Python
subprocess loads the mesh and runs the solve configurations (:data:`CONFIGS`),
each on a ``facet._core.Planarizer`` of its own: L/L x100, L/G x30 and the default
to-tolerance solve, each with and without Anderson acceleration when the
installed core knows the ``anderson`` keyword. The subprocess runs with
``OPENBLAS_NUM_THREADS=1``: the solves call no BLAS (CHOLMOD's factorization
is simplicial), and OpenBLAS's worker threads, which may spin for about 0.1 s
after numpy loads it, would share the cores with the first two-thread solves
(quad grid 10k, L/L x100 on 2 threads: 'first' 35 ms against 14 ms, medians
13.5-15.1 against 13.1-13.2 ms). The full run's ``blas_check`` still compares
unset, 1 and 2 on L/G x30.

Recorded per (mesh, threads, configuration): the solve seconds measured in C
(first "cold" run, which includes the symbolic analysis, then the median of
the timed runs), the process CPU seconds of the same runs, ns per face per
iteration, iterations, stop reason, final planarity_max_rel, the peak
resident-memory growth per face of the configuration alone (each has its own
``Planarizer``, created after the previous one is freed and the heap trimmed;
the kernel's high-water mark VmHWM is reset before it, and the mesh and the
output arrays are resident before it: the figure is the planarizer's
topology and its solves, every transient included), displacement and the
smallest face angle before and after.

Outputs: ``<out>/bench.json`` (every float in full precision), ``<out>/bench.png``
(log-log time against faces) and a table beside the paper's Table 1 on stdout.

    /usr/bin/python3 tools/bench/run_bench.py            # full (make bench)
    /usr/bin/python3 tools/bench/run_bench.py --quick    # smoke run, < 1 min

The machine is shared: figures are medians, and the JSON keeps the load
average before and after so a noisy run can be recognised.
"""

import argparse
import ctypes
import gc
import json
import math
import os
import platform
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(ROOT / "workbench"))

import numpy as np  # noqa: E402

import families  # noqa: E402

#: Solve configurations: keyword arguments of Planarizer.solve. ``kind`` is
#: "fixed" (a fixed iteration count: ns/face/iter is meaningful) or
#: "tolerance" (default stopping: time to tolerance). ``max_faces`` skips the
#: configuration on bigger meshes (overridable from the command line for L/G).
#: Add a configuration here to benchmark a new option.
#: The paper's schedules (Table 1): L/L r = 0.9 x100, L/G r = 0.7 x30, with and
#: without Anderson acceleration; to tolerance with the default (staircase
#: schedule + Anderson) and with issue 2's geometric schedule (r = 0.95, no
#: acceleration) for comparison.
_PAPER_LL = {"method": "ll", "iterations": 100, "ratio": 0.9, "hold_tol": 0.0}
_PAPER_LG = {"method": "lg", "iterations": 30, "ratio": 0.7, "hold_tol": 0.0}
CONFIGS = [
    {"name": "ll100", "kind": "fixed", "kwargs": dict(_PAPER_LL, anderson=0)},
    {"name": "ll100_aa5", "kind": "fixed", "kwargs": dict(_PAPER_LL, anderson=5)},
    {"name": "lg30", "kind": "fixed", "kwargs": dict(_PAPER_LG, anderson=0), "lg": True},
    {"name": "lg30_aa5", "kind": "fixed", "kwargs": dict(_PAPER_LG, anderson=5), "lg": True},
    {"name": "tol", "kind": "tolerance", "kwargs": {}},
    {"name": "tol_geometric", "kind": "tolerance",
     "kwargs": {"ratio": 0.95, "hold_tol": 0.0, "anderson": 0}},
]

TOLERANCE = 1e-6  # the default tol_rel of the core; a solve "reaches" it when max_rel <= this


# ---------------------------------------------------------------------------
# Measurements
# ---------------------------------------------------------------------------


def current_rss_bytes():
    """Resident set size now (Linux /proc), bytes."""
    with open("/proc/self/statm") as f:
        pages = int(f.read().split()[1])
    return pages * os.sysconf("SC_PAGE_SIZE")


def reset_peak_rss():
    """Reset the kernel's high-water mark of this process (Linux >= 4.0); False if refused."""
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
        return True
    except OSError:
        return False


def trim_heap():
    """Give freed heap back to the kernel (glibc's malloc_trim), so that the next
    measurement's growth is not hidden by reused pages; a no-op elsewhere."""
    gc.collect()
    try:
        ctypes.CDLL(None).malloc_trim(0)
    except (OSError, AttributeError):
        pass


def peak_rss_bytes():
    """Peak resident set size: VmHWM (since the last reset), else ru_maxrss."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024


def cpu_seconds():
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def face_angles_min(vertices, face_start, face_vertices):
    """Smallest interior corner angle of each face, degrees (3D, between the two edges)."""
    fs = face_start.astype(np.int64)
    fv = face_vertices.astype(np.int64)
    deg = np.diff(fs)
    face_of = np.repeat(np.arange(deg.size), deg)
    pos = np.arange(fv.size) - fs[face_of]
    nxt = fv[fs[face_of] + (pos + 1) % deg[face_of]]
    prv = fv[fs[face_of] + (pos - 1) % deg[face_of]]
    a = vertices[nxt] - vertices[fv]
    b = vertices[prv] - vertices[fv]
    na = np.linalg.norm(a, axis=1)
    nb = np.linalg.norm(b, axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        c = np.einsum("ij,ij->i", a, b) / (na * nb)
    ang = np.degrees(np.arccos(np.clip(np.nan_to_num(c, nan=1.0), -1.0, 1.0)))
    out = np.full(deg.size, 180.0)
    np.minimum.at(out, face_of, ang)
    return out


def median(values):
    return float(statistics.median(values)) if values else None


# ---------------------------------------------------------------------------
# Worker: one mesh, one thread count, in its own process
# ---------------------------------------------------------------------------


def worker(args):
    from facet import _core

    data = np.load(args.worker)
    v = np.ascontiguousarray(data["vertices"])
    fs = np.ascontiguousarray(data["face_start"])
    fv = np.ascontiguousarray(data["face_vertices"])
    spec = json.loads(args.spec)
    n_faces = fs.size - 1
    angle_in = data["angle_in"]  # computed by the parent: no big temporaries here
    out = np.zeros_like(v)  # written now: the caller's arrays are not the planarizer's memory
    scratch = np.zeros_like(v)  # output of the timed runs
    planarizer = None
    create_seconds = None
    results = []
    for config in spec["configs"]:
        # each configuration on a planarizer of its own, so that its peak is its own
        # (an earlier L/G's factor would otherwise count in a later L/L's figure)
        del planarizer
        trim_heap()
        peak_reset = reset_peak_rss()
        rss0 = current_rss_bytes()
        t0 = time.perf_counter()
        planarizer = _core.Planarizer(fs, fv, v.shape[0])
        if create_seconds is None:
            create_seconds = time.perf_counter() - t0
        kwargs = dict(config["kwargs"], threads=args.threads)
        entry = {"config": config["name"], "kind": config["kind"], "kwargs": kwargs}
        runs = config["runs"]
        budget = config.get("budget")
        seconds, cpus = [], []
        stats = None
        state = {"last": None}

        def progress(iteration, max_iter, planarity, _state=state, _budget=budget):
            _state["last"] = (iteration, planarity)
            return bool(_budget) and time.perf_counter() - _state["start"] > _budget

        try:
            for k in range(runs + 1):  # run 0 is the cold run
                state["start"] = time.perf_counter()
                c0 = cpu_seconds()
                try:
                    # the cold run's result (in `out`) is the one measured for quality
                    r = planarizer.solve(v, out if k == 0 else scratch, progress=progress, **kwargs)
                except _core.Cancelled:
                    if k == 0:
                        raise
                    break  # a timed run hit the budget (a busy machine): keep the runs so far
                stats = r if k == 0 else stats
                c1 = cpu_seconds()
                if k == 0:
                    entry["cold_seconds"] = stats["seconds"]
                    entry["cold_cpu_seconds"] = c1 - c0
                    # a slow configuration: its cold run is the only run
                    if config["kind"] == "tolerance" and budget and stats["seconds"] > budget / 4:
                        seconds.append(stats["seconds"])
                        cpus.append(c1 - c0)
                        break
                    continue
                seconds.append(r["seconds"])
                cpus.append(c1 - c0)
                if sum(seconds) > spec["time_cap"]:
                    break  # enough: more runs of a slow configuration add little
        except TypeError as exc:
            entry["status"] = "skipped"
            entry["note"] = f"the installed core rejects the options ({exc})"
            results.append(entry)
            continue
        except _core.Cancelled:
            it, pl = state["last"]
            entry.update(status="budget", note=f"time budget of {budget} s exceeded at iteration {it}",
                         iterations=it, planarity_max_rel=pl, budget_seconds=budget,
                         seconds_at_stop=time.perf_counter() - state["start"],
                         peak_bytes_per_face=(peak_rss_bytes() - rss0) / n_faces)
            results.append(entry)
            continue
        except _core.CoreError as exc:
            entry.update(status="error", note=str(exc))
            results.append(entry)
            continue
        if not seconds:  # every timed run was cancelled: the cold run is the figure
            seconds.append(entry["cold_seconds"])
            cpus.append(entry["cold_cpu_seconds"])
        med = median(seconds)
        entry.update(
            status="ok",
            runs=len(seconds),
            seconds=seconds,
            median_seconds=med,
            median_cpu_seconds=median(cpus),
            iterations=stats["iterations"],
            stop_reason=stats["stop_reason"],
            converged=bool(stats["converged"]),
            planarity_max_rel=stats["planarity_max_rel"],
            planarity_max_abs=stats["planarity_max_abs"],
            ns_per_face_iteration=1e9 * med / (n_faces * max(stats["iterations"], 1)),
            peak_bytes_per_face=(peak_rss_bytes() - rss0) / n_faces,
        )
        if config["kind"] == "tolerance":
            d = np.linalg.norm(out - v, axis=1)
            angle_out = face_angles_min(out, fs, fv)
            scale = float(np.linalg.norm(v.max(axis=0) - v.min(axis=0))) or 1.0
            entry.update(
                displacement_max=float(d.max()),
                displacement_rms=float(np.sqrt(np.mean(d * d))),
                displacement_rms_rel_diagonal=float(np.sqrt(np.mean(d * d))) / scale,
                min_angle_in=float(angle_in.min()),
                min_angle_out=float(angle_out.min()),
                faces_newly_below_5deg=int(np.count_nonzero((angle_out < 5.0) & (angle_in >= 5.0))),
                reached_tolerance=bool(stats["planarity_max_rel"] <= TOLERANCE),
            )
        results.append(entry)
    report = {
        "threads": args.threads,
        "openblas_num_threads": os.environ.get("OPENBLAS_NUM_THREADS"),
        "create_seconds": create_seconds,
        "rss_before_bytes": rss0,
        "peak_rss_reset": peak_reset,
        "peak_rss_bytes": peak_rss_bytes(),
        "results": results,
    }
    json.dump(report, sys.stdout)


def run_worker(npz, spec_json, threads, blas_threads, timeout):
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT / "workbench")] + (
        [env["PYTHONPATH"]] if env.get("PYTHONPATH") else []))
    # A fixed mmap threshold: big blocks come from mmap and go back on free,
    # so RSS growth is not hidden by reused heap memory.
    env.setdefault("MALLOC_MMAP_THRESHOLD_", "131072")
    if blas_threads is None:
        env.pop("OPENBLAS_NUM_THREADS", None)
    else:
        env["OPENBLAS_NUM_THREADS"] = str(blas_threads)
    cmd = [sys.executable, str(Path(__file__).resolve()), "--worker", str(npz),
           "--threads", str(threads), "--spec", spec_json]
    try:
        p = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"threads": threads, "error": f"worker timed out after {timeout} s"}
    if p.returncode != 0:
        tail = p.stderr.strip().splitlines()[-1:] or ["(no message)"]
        return {"threads": threads, "error": f"worker failed (exit {p.returncode}): {tail[0]}"}
    return json.loads(p.stdout)


# ---------------------------------------------------------------------------
# Parent: plan, run, report
# ---------------------------------------------------------------------------


def runs_for(faces, quick, runs_max):
    if quick:
        base = 3 if faces < 20_000 else 1
    elif faces < 5_000:
        base = 9
    elif faces < 50_000:
        base = 5
    elif faces < 500_000:
        base = 3
    else:
        base = 1
    return max(1, min(base, runs_max)) if runs_max else base


def plan_configs(faces, args, configs):
    plan = []
    for c in configs:
        if c.get("lg") and faces > args.lg_max_faces:
            continue
        if c["kind"] == "tolerance" and faces > args.tol_max_faces:
            continue
        if args.configs and c["name"] not in args.configs:
            continue
        runs = runs_for(faces, args.quick, args.runs)
        if c["kind"] == "tolerance":
            runs = max(1, min(runs, 3))
        plan.append(dict(c, runs=runs, budget=args.tol_budget if c["kind"] == "tolerance" else None))
    return plan


def machine_info():
    info = {"python": sys.version.split()[0], "platform": platform.platform(),
            "cpus": os.cpu_count(), "load_average": os.getloadavg()}
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    info["cpu"] = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    try:
        info["git_commit"] = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "HEAD"],
                                            capture_output=True, text=True).stdout.strip()
    except OSError:
        pass
    return info


def select_specs(args):
    notes = []
    if args.only:  # named meshes, whatever the mode
        specs = families.family_specs(max_faces=args.max_faces)
    elif args.quick:
        specs = [s for s in families.family_specs(max_faces=args.max_faces)
                 if s["name"] in ("Level 1", "Level 5", "Torus1") or
                 s["family"] == "quad_grid" and s["faces"] <= 10_000]
    else:
        specs = families.family_specs(max_faces=args.max_faces)
    if args.no_families:
        specs = []
    if not args.no_public:
        public, pnotes = families.public_meshes(include_shared=not (args.no_shared or args.quick))
        notes += pnotes
        if args.quick:
            public = [p for p in public if p["source"] == "tests/data"][:2]
        specs += public
    if args.only:
        specs = [s for s in specs if any(o.lower() in s["name"].lower() for o in args.only)]
    return specs, notes


def save_mesh(path, mesh):
    np.savez(path, vertices=mesh.vertices, face_start=mesh.face_start,
             face_vertices=mesh.face_vertices,
             angle_in=face_angles_min(mesh.vertices, mesh.face_start, mesh.face_vertices))


def blas_check(tmp, timeout, quick):
    """L/G x30 on Level 5 with OPENBLAS_NUM_THREADS unset, 1 and 2 (threads=1 and 2)."""
    mesh = families.level_patch(5)
    npz = Path(tmp) / "blas_check.npz"
    save_mesh(npz, mesh)
    cfg = dict(CONFIGS[2], runs=3 if quick else 7, budget=None)
    spec = json.dumps({"configs": [cfg], "time_cap": 10.0})
    rows = []
    for threads in (1, 2):
        for blas in (None, 1, 2):
            rep = run_worker(npz, spec, threads, blas, timeout)
            r = (rep.get("results") or [{}])[0]
            rows.append({"mesh": mesh.name, "config": "lg30", "threads": threads,
                         "openblas_num_threads": blas, "median_seconds": r.get("median_seconds"),
                         "median_cpu_seconds": r.get("median_cpu_seconds"), "error": rep.get("error")})
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="smoke run (< 1 minute)")
    ap.add_argument("--out", default=str(ROOT / "out" / "bench"), help="output folder")
    ap.add_argument("--threads", default="1,2", help="thread counts, comma separated")
    ap.add_argument("--max-faces", type=int, default=None, help="largest mesh (default 1M; quick 10k)")
    ap.add_argument("--lg-max-faces", type=int, default=None,
                    help="largest mesh for L/G x30 (default 20k: ~50 s per run at 100k here; quick 4k)")
    ap.add_argument("--tol-max-faces", type=int, default=None,
                    help="largest mesh for to-tolerance solves (default 1M; quick 4k)")
    ap.add_argument("--tol-budget", type=float, default=None,
                    help="seconds before a to-tolerance solve is cancelled (default 10; quick 2)")
    ap.add_argument("--time-cap", type=float, default=None,
                    help="stop timing a configuration after this many seconds of runs "
                         "(at least one run; default 4, quick 1)")
    ap.add_argument("--runs", type=int, default=0, help="at most this many timed runs (0: by size)")
    ap.add_argument("--configs", default="", help="configuration names, comma separated (default all)")
    ap.add_argument("--only", action="append", default=[], help="meshes whose name contains this")
    ap.add_argument("--no-public", action="store_true", help="generated families only")
    ap.add_argument("--no-families", action="store_true", help="public meshes only")
    ap.add_argument("--no-shared", action="store_true", help="leave out /work/shared/data")
    ap.add_argument("--no-plot", action="store_true")
    ap.add_argument("--no-blas-check", action="store_true",
                    help="skip the OPENBLAS_NUM_THREADS comparison (never run in --quick)")
    ap.add_argument("--timeout", type=float, default=900, help="seconds per worker process")
    # internal: one worker
    ap.add_argument("--worker", help=argparse.SUPPRESS)
    ap.add_argument("--spec", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        args.threads = int(args.threads)
        worker(args)
        return 0
    defaults = (10_000, 4_000, 4_000, 2.0, 1.0) if args.quick else (1_000_000, 20_000, 1_000_000, 10.0, 4.0)
    args.time_cap = args.time_cap if args.time_cap is not None else defaults[4]
    args.max_faces = args.max_faces or defaults[0]
    args.lg_max_faces = args.lg_max_faces if args.lg_max_faces is not None else defaults[1]
    args.tol_max_faces = args.tol_max_faces if args.tol_max_faces is not None else defaults[2]
    args.tol_budget = args.tol_budget if args.tol_budget is not None else defaults[3]
    args.configs = [c for c in args.configs.split(",") if c]
    try:
        thread_counts = [int(t) for t in args.threads.split(",")]
        if not thread_counts or min(thread_counts) < 1:
            raise ValueError
    except ValueError:
        print(f"run_bench: --threads must be positive integers separated by commas, "
              f"not {args.threads!r}", file=sys.stderr)
        return 2
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    specs, notes = select_specs(args)
    doc = {"meta": dict(machine_info(), mode="quick" if args.quick else "full",
                        started=time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
                        options={k: v for k, v in vars(args).items() if k not in ("worker", "spec")}),
           "paper": {"machine": families.PAPER_MACHINE, "table1": [
               dict(zip(("name", "faces", "vertices", "lg30_ms", "ll100_ms"), row))
               for row in families.PAPER_TABLE1]},
           "configs": CONFIGS, "notes": notes, "meshes": []}
    t_start = time.time()
    with tempfile.TemporaryDirectory(prefix="facet-bench-") as tmp:
        if not args.no_blas_check and not args.quick:
            print("OPENBLAS_NUM_THREADS check (Level 5, L/G x30)...", flush=True)
            doc["blas_check"] = blas_check(tmp, args.timeout, args.quick)
        for spec in specs:
            mesh = families.generate(spec)
            npz = Path(tmp) / "mesh.npz"
            save_mesh(npz, mesh)
            entry = {"name": mesh.name, "family": mesh.family, "faces": mesh.n_faces,
                     "vertices": mesh.n_vertices, "source": spec.get("source", mesh.source),
                     "params": mesh.params, "by_threads": []}
            plan = plan_configs(mesh.n_faces, args, CONFIGS)
            for threads in thread_counts:
                rep = run_worker(npz, json.dumps({"configs": plan, "time_cap": args.time_cap}),
                                 threads, 1, args.timeout)
                entry["by_threads"].append(rep)
                print(summary_line(entry, rep), flush=True)
            doc["meshes"].append(entry)
            # keep what is measured so far
            write_json(doc, out / "bench.json")
    doc["meta"]["seconds"] = time.time() - t_start
    doc["meta"]["load_average_after"] = os.getloadavg()
    write_json(doc, out / "bench.json")
    print()
    print(paper_table(doc))
    print()
    print(full_table(doc))
    if doc.get("blas_check"):
        print()
        print(blas_table(doc["blas_check"]))
    for n in notes:
        print("note:", n)
    if not args.no_plot:
        plot(doc, out / "bench.png")
        print(f"\nwrote {out / 'bench.json'} and {out / 'bench.png'}")
    else:
        print(f"\nwrote {out / 'bench.json'}")
    return 0


def write_json(doc, path):
    tmp = path.with_suffix(".json.tmp")
    with open(tmp, "w") as f:
        json.dump(doc, f, indent=1, allow_nan=False, default=_jsonable)
    os.replace(tmp, path)


def _jsonable(x):
    if isinstance(x, (np.floating,)):
        return float(x)
    if isinstance(x, (np.integer,)):
        return int(x)
    raise TypeError(f"not JSON: {type(x)}")


# ---------------------------------------------------------------------------
# Reports
# ---------------------------------------------------------------------------


def result_of(entry, threads, config):
    for rep in entry["by_threads"]:
        if rep.get("threads") == threads:
            for r in rep.get("results", []):
                if r["config"] == config:
                    return r
    return None


def _ms(r):
    if not r or r.get("status") != "ok":
        return "-"
    return f"{1e3 * r['median_seconds']:.1f}"


def summary_line(entry, rep):
    if rep.get("error"):
        return f"{entry['name']:<28} {entry['faces']:>8} t={rep['threads']}  {rep['error']}"
    parts = []
    for r in rep["results"]:
        if r.get("status") == "ok":
            if r["kind"] == "fixed":
                parts.append(f"{r['config']} {r['ns_per_face_iteration']:.0f}ns")
            else:
                parts.append(f"{r['config']} {r['median_seconds']:.3g}s/{r['iterations']}it "
                             f"{r['planarity_max_rel']:.1e}")
        elif r.get("status") == "budget":
            parts.append(f"{r['config']} >{r['budget_seconds']:g}s@{r['iterations']}it")
        else:
            parts.append(f"{r['config']} {r.get('status')}")
    return f"{entry['name']:<28} {entry['faces']:>8} t={rep['threads']}  " + "  ".join(parts)


def paper_table(doc):
    by_name = {m["name"]: m for m in doc["meshes"]}
    lines = [f"Beside the paper's Table 1 ({doc['paper']['machine']}), milliseconds; "
             "ours on this machine, threads 1 / 2:",
             f"{'model':<12} {'faces':>6} {'verts':>6} | {'paper L/G30':>11} {'ours L/G30 1/2':>17} |"
             f" {'paper L/L100':>12} {'ours L/L100 1/2':>17}"]
    for name, faces, verts, lg, ll in families.PAPER_TABLE1:
        m = by_name.get(name)
        if m is None:
            lines.append(f"{name:<12} {faces:>6} {verts:>6} | {lg:>11} {'(mesh not public)':>17} |"
                         f" {ll:>12} {'':>17}")
            continue
        ours_lg = f"{_ms(result_of(m, 1, 'lg30'))} / {_ms(result_of(m, 2, 'lg30'))}"
        ours_ll = f"{_ms(result_of(m, 1, 'll100'))} / {_ms(result_of(m, 2, 'll100'))}"
        lines.append(f"{name:<12} {m['faces']:>6} {m['vertices']:>6} | {lg:>11} {ours_lg:>17} |"
                     f" {ll:>12} {ours_ll:>17}")
    return "\n".join(lines)


def full_table(doc):
    head = (f"{'mesh':<34} {'faces':>8} {'thr':>3} {'config':<10} {'median ms':>10} {'ns/f/it':>8}"
            f" {'iters':>5} {'max_rel':>8} {'B/face':>7}")
    lines = [head, "-" * len(head)]
    for m in doc["meshes"]:
        for rep in m["by_threads"]:
            if rep.get("error"):
                lines.append(f"{m['name'][:34]:<34} {m['faces']:>8} {rep['threads']:>3} {rep['error']}")
                continue
            for r in rep["results"]:
                st = r.get("status")
                if st == "ok":
                    lines.append(
                        f"{m['name'][:34]:<34} {m['faces']:>8} {rep['threads']:>3} {r['config']:<10}"
                        f" {1e3 * r['median_seconds']:>10.2f} {r['ns_per_face_iteration']:>8.0f}"
                        f" {r['iterations']:>5} {r['planarity_max_rel']:>8.1e}"
                        f" {r['peak_bytes_per_face']:>7.0f}")
                elif st == "budget":
                    lines.append(
                        f"{m['name'][:34]:<34} {m['faces']:>8} {rep['threads']:>3} {r['config']:<10}"
                        f" {'>' + format(1e3 * r['budget_seconds'], '.0f'):>10} {'':>8}"
                        f" {r['iterations']:>5} {r['planarity_max_rel']:>8.1e}"
                        f" {r['peak_bytes_per_face']:>7.0f}  (budget)")
    skipped = sorted({r["config"] for m in doc["meshes"] for rep in m["by_threads"]
                      for r in rep.get("results", []) if r.get("status") == "skipped"})
    if skipped:
        lines.append(f"skipped (the installed core rejects their options): {', '.join(skipped)}")
    return "\n".join(lines)


def blas_table(rows):
    lines = ["OPENBLAS_NUM_THREADS and L/G x30 on Level 5 (median ms; CPU ms):"]
    for r in rows:
        blas = "unset" if r["openblas_num_threads"] is None else r["openblas_num_threads"]
        if r.get("error") or r.get("median_seconds") is None:
            lines.append(f"  threads={r['threads']} OPENBLAS_NUM_THREADS={blas}: {r.get('error')}")
        else:
            lines.append(f"  threads={r['threads']} OPENBLAS_NUM_THREADS={blas:<5} "
                         f"{1e3 * r['median_seconds']:8.1f} ms  cpu {1e3 * r['median_cpu_seconds']:8.1f} ms")
    return "\n".join(lines)


def plot(doc, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 6.5), dpi=110)
    styles = {1: "-", 2: "--"}
    markers = {"level": "o", "hex_torus": "h", "quad_grid": "s", "quad_torus": "D", "hypar": "x"}
    palette = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    families_seen = []
    for ci, cfg in enumerate(c["name"] for c in CONFIGS):
        color = palette[ci % len(palette)]
        for threads in (1, 2):
            labelled = False
            for family, marker in markers.items():
                pts = []
                for m in doc["meshes"]:
                    if m["family"] != family:
                        continue
                    r = result_of(m, threads, cfg)
                    if r and r.get("status") == "ok":
                        pts.append((m["faces"], r["median_seconds"]))
                if not pts:
                    continue
                if family not in families_seen:
                    families_seen.append(family)
                pts.sort()
                x, y = zip(*pts)
                ax.plot(x, y, styles.get(threads, ":"), marker=marker, ms=4, color=color,
                        label=None if labelled else f"{cfg}, {threads} thread{'s' * (threads > 1)}")
                labelled = True
    for family in families_seen:  # marker key
        ax.plot([], [], "k" + markers[family], ls="none", ms=4, label=family.replace("_", " "))
    px = [row[1] for row in families.PAPER_TABLE1]
    ax.plot(px, [row[3] / 1e3 for row in families.PAPER_TABLE1], "k^", ms=5, label="paper L/G x30 (2012)")
    ax.plot(px, [row[4] / 1e3 for row in families.PAPER_TABLE1], "kv", ms=5, label="paper L/L x100 (2012)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("faces")
    ax.set_ylabel("solve time, s (C-measured, median)")
    ax.set_title("Facet planarization: time against faces (generated families)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
