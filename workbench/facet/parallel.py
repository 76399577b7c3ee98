# SPDX-License-Identifier: LGPL-2.1-or-later
"""Chunks of work in worker processes (nesting, panel solids).

Two cores are what the target machines have; libnest2d and OCC release
nothing to Python threads, so the work goes to plain Python processes
started with this package on their path. Inside FreeCAD ``sys.executable``
is FreeCAD itself, so a Python interpreter of the same version is looked
for; without one the work is done in this process.

Worker k takes chunks k, k + workers, ...: which process nests which chunk
never changes a result. Each worker sends one pickled message per chunk on
its stdout; progress is reported as chunks come back, and cancelling kills
the workers.
"""

import os
import pickle
import queue
import subprocess
import sys
import threading

from facet.errors import Cancelled, FacetError

__all__ = ["WorkerError", "python_executable", "default_workers", "run_chunks"]

#: at most this many worker processes by default
MAX_WORKERS = 2


class WorkerError(FacetError):
    """A worker process failed (its message says why)."""


def python_executable():
    """A Python interpreter of this version for worker processes, or None."""
    exe = sys.executable or ""
    if os.path.basename(exe).startswith("python") and os.access(exe, os.X_OK):
        return exe
    v = sys.version_info
    for folder in (os.path.join(sys.base_exec_prefix, "bin"), "/usr/bin", "/usr/local/bin"):
        exe = os.path.join(folder, f"python{v.major}.{v.minor}")
        if os.access(exe, os.X_OK):
            return exe
    return None


def default_workers():
    """min(MAX_WORKERS, CPUs), or 1 when no interpreter is found."""
    if python_executable() is None:
        return 1
    return max(1, min(MAX_WORKERS, os.cpu_count() or 1))


def run_chunks(function, chunks, settings, workers, progress=None, weights=None):
    """``function(chunk, settings)`` for every chunk in ``workers`` processes.

    Parameters
    ----------
    function : str
        "module:name" of a picklable-result function importable in a fresh
        Python with this package on its path.
    chunks : list
    settings : picklable
    workers : int
    progress : callable, optional
        ``progress(done, total)`` in units of ``weights`` (default: 1 per
        chunk) while waiting; True cancels (raises :class:`Cancelled`).

    Returns
    -------
    list
        The results in the order of ``chunks``.
    """
    weights = weights or [1] * len(chunks)
    total = sum(weights)
    package_dir = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (package_dir, env.get("PYTHONPATH")) if p)
    env["OMP_NUM_THREADS"] = "1"
    freecad = sys.modules.get("FreeCAD")
    if freecad is not None and getattr(freecad, "__file__", None) and "FREECAD_LIB" not in env:
        env["FREECAD_LIB"] = os.path.dirname(freecad.__file__)
    exe = python_executable()
    if exe is None:
        raise WorkerError("no Python interpreter found for worker processes")
    events = queue.Queue()
    procs = []

    def read(k, proc):
        try:
            while True:
                msg = pickle.load(proc.stdout)
                events.put((k, msg))
                if msg[0] in ("done", "error"):
                    return
        except Exception as exc:  # a worker that died
            events.put((k, ("error", f"worker process {k} stopped: {exc!r}")))

    results = [None] * len(chunks)
    try:
        for k in range(workers):
            mine = [(i, chunks[i]) for i in range(k, len(chunks), workers)]
            proc = subprocess.Popen(
                [exe, "-c", "from facet.parallel import worker_main; worker_main()"],
                stdin=subprocess.PIPE, stdout=subprocess.PIPE, env=env)
            procs.append(proc)
            pickle.dump((function, mine, settings), proc.stdin,
                        protocol=pickle.HIGHEST_PROTOCOL)
            proc.stdin.close()
            threading.Thread(target=read, args=(k, proc), daemon=True).start()
        running, done = workers, 0
        while running:
            try:
                _, msg = events.get(timeout=0.2)
            except queue.Empty:
                if progress is not None and progress(done, total):
                    raise Cancelled("cancelled") from None
                continue
            if msg[0] == "chunk":
                _, i, result = msg
                results[i] = result
                done += weights[i]
                if progress is not None and progress(done, total):
                    raise Cancelled("cancelled")
            elif msg[0] == "done":
                running -= 1
            else:
                raise WorkerError(msg[1])
    finally:
        for proc in procs:
            if proc.poll() is None:
                proc.kill()
            proc.wait()
            proc.stdout.close()
    return results


def worker_main():
    """Entry point of a worker process: (function, chunks, settings) in on
    stdin, one pickled message per chunk out on stdout."""
    import importlib

    out = sys.stdout.buffer
    # whatever the work prints must not mix with the messages
    sys.stdout = sys.stderr
    try:
        function, chunks, settings = pickle.load(sys.stdin.buffer)
        module, name = function.split(":")
        func = getattr(importlib.import_module(module), name)
        for i, chunk in chunks:
            pickle.dump(("chunk", i, func(chunk, settings)), out)
            out.flush()
        pickle.dump(("done",), out)
    except Exception as exc:  # reported by the parent in one line
        pickle.dump(("error", f"worker process failed: {exc!r}"), out)
    out.flush()
