# SPDX-License-Identifier: LGPL-2.1-or-later
"""How a staircase level settles on the large meshes: iterations, quality re-solves, angles.

    /usr/bin/python3 tools/bench/settle_levels.py [--threads 2] [--bench PATH] [--trace]
        [--meshes grid1000,torus1000,...] [--variant LABEL=NAME:VALUE,NAME:VALUE ...]

Runs libcore/bench/bench_large (the default options of
`facet_planarize_options_default(FACET_METHOD_AUTO)`, each variant changing some of them
through bench_large's --set NAME=VALUE; a NAME starting with FACET_EXP_ is put into the
environment instead) on the five large meshes of docs/benchmarks.md, "Settling a penalty
level at 1M faces (branch settle7)": the 1M quad grid and torus, the 250k grid and torus,
the 100k hex torus. The meshes are written by tools/bench/dump_mesh.py into --dir (/tmp by
default) when absent; --meshes also takes grid700, torus700, hex250k, level8 and bench_large's
grid:NUxNV. 'default' (no change) always runs first for each mesh.

Prints one row per mesh and variant: all iterations, the first solve's and the quality
re-solves, the smallest corner angle, faces under 5 degrees, the RMS distance from the input
surface in mean edges, wall and CPU seconds, the 1-minute load average when the run started,
and (with --trace) each staircase level's length. Iterations, re-solves and angles do not
depend on the machine's load; the times do.

The candidate settle tests measured for that section are not in the library: they are in
tools/bench/settle7_candidates.patch (hold_rms, the FACET_EXP_* knobs, the trace, and
bench_large's re-solve count), to apply to a scratch checkout (`git apply`, `make build`).
Without it, the fields that bench_large does not print show as '?'. Example (the patch
applied; quality_angle 0 shows whether a re-solve would run: a face newly under 5 degrees):

    settle_levels.py --trace --variant rms.02=quality_angle:0,hold_rms:0.02 \
        --variant stag10=quality_angle:0,FACET_EXP_STAG:10,FACET_EXP_FRAC:0.95
"""

import argparse
import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
MESHES = {  # name: (dump_mesh.py family, size)
    "grid1000": ("quad_grid", 1000),
    "torus1000": ("quad_torus", 1000),
    "torus500": ("quad_torus", 500),
    "grid500": ("quad_grid", 500),
    "hex100k": ("hex_torus", 100000),
}
EXTRA = {  # more large meshes, by --meshes only
    "grid700": ("quad_grid", 700),
    "torus700": ("quad_torus", 700),
    "hex250k": ("hex_torus", 250000),
    "level8": ("level", 8),
}
FIELDS = ("iterations", "first", "resolves", "min_angle", "below_5", "surface_rms", "wall", "cpu",
          "max_rel", "reason")


def mesh_path(name, directory):
    if name.startswith("grid:"):  # bench_large's own generated grid (test_meshes.h)
        return name
    path = Path(directory) / f"facet_settle_{name}.bin"
    if not path.exists():
        family, size = {**MESHES, **EXTRA}[name]
        subprocess.run([sys.executable, str(ROOT / "tools/bench/dump_mesh.py"), family, str(size),
                        str(path)], check=True, stdout=subprocess.DEVNULL)
    return path


def parse_variant(text):
    label, _, sets = text.partition("=")
    pairs = [s.replace(":", "=", 1) for s in sets.split(",") if s]
    for p in pairs:
        if not re.fullmatch(r"[A-Za-z_0-9]+=[-+.eE0-9]+", p):
            raise SystemExit(f"settle_levels.py: bad setting {p!r} in variant {text!r}")
    return label, pairs


def run(bench, path, threads, sets, trace):
    cmd = [bench, str(path), "--threads", str(threads)]
    env = dict(os.environ)
    for s in sets:
        if s.startswith("FACET_EXP_"):
            env[s.split("=")[0]] = s.split("=")[1]
        else:
            cmd += ["--set", s]
    if trace:
        env["FACET_EXP_TRACE"] = "1"
    load = os.getloadavg()[0]
    done = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if done.returncode != 0:
        raise SystemExit(f"settle_levels.py: {' '.join(cmd)} failed: {done.stderr.strip()}")
    line = done.stdout.strip().splitlines()[-1]
    row = {"load": load}
    for key in FIELDS:
        m = re.search(rf"\b{key}=(\S+)", line)
        row[key] = m.group(1) if m else "?"
    levels = [m.group(1) for m in re.finditer(r"level mu \S+ steps (\d+)", done.stderr)]
    row["levels"] = "+".join(levels)
    return row


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--bench", default=str(ROOT / "build/libcore/bench/bench_large"))
    parser.add_argument("--dir", default="/tmp")
    parser.add_argument("--meshes", default=",".join(MESHES))
    parser.add_argument("--variant", action="append", default=[],
                        help="LABEL=NAME:VALUE,... (bench_large --set NAME=VALUE); "
                             "'default=' is always run first")
    parser.add_argument("--trace", action="store_true")
    args = parser.parse_args(argv)
    variants = [("default", [])] + [parse_variant(v) for v in args.variant]
    names = [n for n in args.meshes.split(",") if n]
    for n in names:
        if n not in MESHES and n not in EXTRA and not re.fullmatch(r"grid:\d+x\d+", n):
            raise SystemExit(f"settle_levels.py: unknown mesh {n!r} "
                             f"(one of {', '.join(list(MESHES) + list(EXTRA))})")
    print("mesh       variant              iters  first  resolves  min_angle  below_5  "
          "surf_rms  wall_s  cpu_s  load  levels", flush=True)
    for name in names:
        path = mesh_path(name, args.dir)
        for label, sets in variants:
            r = run(args.bench, path, args.threads, sets, args.trace)
            print(f"{name:10s} {label:20s} {r['iterations']:>5s} {r['first']:>6s} {r['resolves']:>9s} "
                  f"{r['min_angle']:>10s} {r['below_5']:>8s} {r['surface_rms']:>9s} {r['wall']:>7s} "
                  f"{r['cpu']:>6s} {r['load']:5.2f}  {r['levels']}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
