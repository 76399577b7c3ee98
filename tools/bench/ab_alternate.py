#!/usr/bin/python3
"""Alternate two (or more) bench_large builds on one mesh, A B A B ..., and
print each run and the medians of wall and CPU time, with the load average
before each run: the wall times on a shared machine move with the load, so
builds are compared within the same minutes (docs/benchmarks.md, "1M faces:
scheduling (branch dyn8)").

  ab_alternate.py --pairs 5 --mesh /tmp/grid1000.bin --threads 2 \
      [--set iterations=60 ...] [--env NAME=VALUE ...] [--spin-cpu C] \
      NAME=BENCH_LARGE NAME=BENCH_LARGE ...

--spin-cpu C runs a busy loop pinned to CPU C (taskset) during each run, a
controlled stand-in for a core that the host or another process slows: the
solve's threads then share that core with it.
"""
import argparse
import os
import re
import statistics
import subprocess
import sys


def run(binary, args, env, spin_cpu=None):
    spinner = None
    if spin_cpu is not None:
        spinner = subprocess.Popen(['taskset', '-c', str(spin_cpu), 'sh', '-c', 'while :; do :; done'])
    try:
        out = subprocess.run([binary] + args, capture_output=True, text=True, env=env, check=True).stdout
    finally:
        if spinner:
            spinner.kill()
            spinner.wait()
    wall = float(re.search(r'wall=([0-9.]+)', out).group(1))
    cpu = float(re.search(r'cpu=([0-9.]+)', out).group(1))
    iters = int(re.search(r'iterations=(\d+)', out).group(1))
    disp = re.search(r'disp_rms=(\S+)', out).group(1)
    return wall, cpu, iters, disp


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument('--pairs', type=int, default=5)
    p.add_argument('--mesh', default='/tmp/grid1000.bin')
    p.add_argument('--threads', type=int, default=2)
    p.add_argument('--set', action='append', default=[])
    p.add_argument('--method', default=None, help='auto, ll or lg (default: auto)')
    p.add_argument('--runs', type=int, default=1, help="bench_large's runs per call (it reports their median)")
    p.add_argument('--env', action='append', default=[])
    p.add_argument('--spin-cpu', type=int, default=None)
    p.add_argument('builds', nargs='+', help='NAME=path/to/bench_large')
    a = p.parse_args()
    builds = [b.split('=', 1) for b in a.builds]
    args = [a.mesh, '--threads', str(a.threads), '--runs', str(a.runs)]
    if a.method:
        args += ['--method', a.method]
    for s in a.set:
        args += ['--set', s]
    env = dict(os.environ)
    for e in a.env:
        k, v = e.split('=', 1)
        env[k] = v
    walls = {n: [] for n, _ in builds}
    cpus = {n: [] for n, _ in builds}
    loads = []
    for i in range(a.pairs):
        order = builds if i % 2 == 0 else builds[::-1]  # A B, B A, ...
        for name, binary in order:
            load = os.getloadavg()[0]
            loads.append(load)
            wall, cpu, iters, disp = run(binary, args, env, a.spin_cpu)
            walls[name].append(wall)
            cpus[name].append(cpu)
            print(f'{i} {name:8s} load {load:4.2f} wall {wall:6.3f} cpu {cpu:6.3f} cpu/wall {cpu / wall:4.2f} '
                  f'it {iters} disp_rms {disp}',
                  flush=True)
    ref = builds[0][0]
    for name, _ in builds:
        mw, mc = statistics.median(walls[name]), statistics.median(cpus[name])
        ratios = [w / r for w, r in zip(walls[name], walls[ref])]
        print(f'{name:8s} median wall {mw:6.3f} cpu {mc:6.3f}  wall/{ref} per pair median '
              f'{statistics.median(ratios):.3f} (min {min(ratios):.3f} max {max(ratios):.3f})')
    print(f'load {min(loads):.2f}-{max(loads):.2f}')


if __name__ == '__main__':
    sys.exit(main())
