# SPDX-License-Identifier: LGPL-2.1-or-later
"""The lifting gives the same bits whatever the OpenMP and BLAS thread counts."""

import hashlib
import subprocess
import sys

import pytest

pytest.importorskip("facet._core")

SCRIPT = r"""
import hashlib, numpy as np
from facet.mesh import PolyMesh
from facet.lift import Lifter
rng = np.random.default_rng(1)
n = 30
xs, ys = np.meshgrid(np.arange(n, dtype=float), np.arange(n, dtype=float))
xyz = np.column_stack([xs.ravel(), ys.ravel(), np.zeros(n * n)])
inner = (xyz[:, 0] > 0) & (xyz[:, 0] < n - 1) & (xyz[:, 1] > 0) & (xyz[:, 1] < n - 1)
xyz[inner, :2] += rng.uniform(-0.2, 0.2, size=(int(inner.sum()), 2))
faces = [[j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i]
         for j in range(n - 1) for i in range(n - 1)]
lifter = Lifter(PolyMesh.from_faces(xyz, faces), rng.uniform(0.5, 2, n * n))
z = lifter.solve(rng.normal(size=n * n)).heights
f = lifter.fundamental(17)
basis, energies = lifter.basis("eigen", 12)
print(hashlib.sha256(z.tobytes() + f.tobytes() + basis.tobytes() + energies.tobytes()).hexdigest())
"""


def run(facet_env, threads):
    env = dict(facet_env)
    env.update({"OMP_NUM_THREADS": str(threads), "OPENBLAS_NUM_THREADS": str(threads)})
    done = subprocess.run([sys.executable, "-c", SCRIPT], env=env, capture_output=True,
                          text=True, check=False)
    assert done.returncode == 0, done.stderr
    return done.stdout.strip()


def test_same_bits_for_1_and_2_threads(facet_env):
    assert run(facet_env, 1) == run(facet_env, 2)
