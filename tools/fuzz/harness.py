# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Python side of Facet's parser fuzzing.

:func:`one_input` takes the fuzz bytes: the first byte picks a reader
(:data:`KINDS`), the rest is the file's content. The file is written under
a private temporary directory with the reader's extension and read the way
the command line and the workbench read it. A successful read is fed on to
the compiled core (planarity, a few planarize iterations, quality, cleanup,
panels, lift), so fuzzed meshes reach the C extension too.

Outcomes:

* :class:`facet.errors.InputError` (and subclasses) from a reader: the
  file was refused with a message -- fine;
* :class:`facet.errors.FacetError` from a solver on a mesh that was read:
  fine (e.g. a numerical failure reported as such);
* anything else (IndexError, UnicodeDecodeError, MemoryError,
  RecursionError, a NaN in a result, ...): a finding -- the exception
  propagates, and the C driver (libcore/fuzz/fuzz_python.c) prints it and
  aborts.

It is also a script: ``PYTHONPATH=workbench python3 tools/fuzz/harness.py
FILE_OR_DIR...`` replays inputs and lists the findings (the regression test
tests/python/test_fuzz_regressions.py does the same). The structure-aware
mutator is on the C side (LLVMFuzzerCustomMutator in fuzz_python.c).
"""

import os
import sys
import tempfile
import warnings

import numpy as np

from facet.errors import FacetError, InputError

#: Reader chosen by the first byte (modulo the count): (name, suffix).
KINDS = (
    ("mesh", ".obj"),
    ("mesh", ".off"),
    ("mesh", ".json"),
    ("plan", ".dxf"),
    ("plan", ".csv"),
    ("plan", ".obj"),
    ("targets", ".csv"),
    ("plan", ".json"),
)

#: The largest mesh handed on to the solvers (bigger ones are only read).
SOLVE_LIMIT = 300

_DIR = tempfile.mkdtemp(prefix="facet-fuzz-")


class Finding(AssertionError):
    """An oracle broke that is not an exception of its own (a NaN, ...)."""


def kind_of(data):
    """The (name, suffix) the first byte selects."""
    return KINDS[data[0] % len(KINDS)] if data else KINDS[0]


def _finite(name, values):
    array = np.asarray(values, dtype=np.float64)
    if array.size and not np.all(np.isfinite(array)):
        raise Finding(f"{name} holds a non-finite value")


def _check_mesh(mesh, where):
    v = np.asarray(mesh.vertices)
    if v.ndim != 2 or v.shape[1] != 3 or v.dtype != np.float64:
        raise Finding(f"{where}: vertices of shape {v.shape} dtype {v.dtype}")
    _finite(f"{where}: vertices", v)
    mesh.validate()


def _plan():
    from facet.mesh import PolyMesh
    from facet.plan import PlanGraph

    square = PolyMesh.from_faces(
        [(0, 0, 0), (1, 0, 0), (2, 0, 0), (0, 1, 0), (1, 1, 0), (2, 1.5, 0)],
        [(0, 1, 4, 3), (1, 2, 5, 4)],
    )
    return PlanGraph(square)




def _solve(mesh):
    """The compiled core on a mesh that was read: every result finite."""
    import facet

    if mesh.n_vertices > SOLVE_LIMIT or mesh.n_faces > SOLVE_LIMIT:
        return
    try:
        report = facet.planarity(mesh, threads=1)
        _finite("planarity", report.max_abs)
        result = facet.planarize(mesh, iterations=3, threads=1)
        _check_mesh(result.mesh, "planarize")
        facet.quality(result)
        cleaned = facet.cleanup(mesh, 0.05)
        _check_mesh(cleaned.mesh, "cleanup")
        facet.panels(result.mesh, 0.01, tol=0.5)
    except FacetError:
        pass


def _run(kind, suffix, path):
    from facet.io import read_mesh
    from facet.plan import read_plan, read_targets

    if kind == "mesh":
        mesh = read_mesh(path)
        _check_mesh(mesh, "read_mesh")
        _solve(mesh)
    elif kind == "plan":
        plan = read_plan(path)
        _check_mesh(plan.mesh, "read_plan")
        if plan.mesh.n_faces <= SOLVE_LIMIT:
            from facet.lift import lift

            xy = np.asarray(plan.mesh.vertices)[:, :2]
            try:
                result = lift(plan, xy[:, 0] * 0.1 + np.sin(xy[:, 1]))
            except FacetError:
                return
            _finite("lift", result.heights)
            _check_mesh(result.mesh, "lift")
    else:
        targets, weights = read_targets(_plan(), path)
        _finite("targets", targets)
        _finite("weights", weights)


def one_input(data):
    """Read `data` (selector byte + file) with the chosen reader; see the module doc."""
    data = bytes(data)
    kind, suffix = kind_of(data)
    path = os.path.join(_DIR, "input" + suffix)
    with open(path, "wb") as handle:
        handle.write(data[1:])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            _run(kind, suffix, path)
        except InputError as exc:
            message = str(exc)
            if "\n" in message.strip() or not message.strip():
                raise Finding(f"InputError message is not one line: {message!r}") from exc


def replay(paths):
    """Run one_input on files (directories: every file); return the failures."""
    failures = []
    files = []
    for p in paths:
        if os.path.isdir(p):
            files += [os.path.join(p, n) for n in sorted(os.listdir(p))
                      if not n.startswith(".") and n != "README.md"]
        else:
            files.append(p)
    for f in files:
        with open(f, "rb") as handle:
            data = handle.read()
        try:
            one_input(data)
        except Exception as exc:  # a finding: report, go on
            failures.append((f, f"{type(exc).__name__}: {exc}"))
    return failures


def main(argv):
    failures = replay(argv)
    for f, what in failures:
        print(f"{f}: {what}")
    print(f"{len(failures)} finding(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
