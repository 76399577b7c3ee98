# SPDX-License-Identifier: LGPL-2.1-or-later
"""The facet package: its public names, and working without the compiled core."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import facet

PUBLIC = [
    "PolyMesh", "FacetError", "MeshError", "Cancelled", "read_mesh", "write_mesh", "planarize",
    "Planarizer", "PlanarizeResult", "planarity", "PlanarityReport", "__version__",
]


def test_public_names():
    for name in PUBLIC:
        assert hasattr(facet, name), name
        assert name in facet.__all__
    assert facet.__version__ == "0.1.0"
    assert callable(facet.planarize) and callable(facet.planarity)
    assert isinstance(facet.Planarizer, type)


def test_submodule_import_does_not_hide_the_functions():
    import facet.planarity  # noqa: F401
    import facet.planarize  # noqa: F401

    assert callable(facet.planarize)
    assert callable(facet.planarity)


def test_no_freecad_import():
    """No module of facet imports FreeCAD (facet.step does, when it writes). In a process
    of its own: other tests (STEP read back) import FreeCAD in this one."""
    package = Path(facet.__file__).parent
    names = sorted(p.stem for p in package.glob("*.py") if p.stem != "__main__")
    script = ("import importlib, sys\n"
              f"for name in {names!r}:\n"
              "    importlib.import_module('facet' if name == '__init__' else 'facet.' + name)\n"
              "print(sorted(m for m in ('FreeCAD', 'Part', 'FreeCADGui') if m in sys.modules))\n")
    env = dict(os.environ, PYTHONPATH=str(package.parent))
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[]"


def test_works_without_the_compiled_core(tmp_path, data_dir):
    """Reading and writing still work; the solver says how to build the core."""
    package = Path(facet.__file__).parent
    copy = tmp_path / "facet"
    shutil.copytree(package, copy, ignore=shutil.ignore_patterns("_core*", "__pycache__"))
    script = (
        "import facet, sys\n"
        f"mesh = facet.read_mesh({str(data_dir / 'hypar.obj')!r}, validate=False)\n"
        "print(mesh.n_faces)\n"
        "try:\n"
        "    facet.planarize(mesh)\n"
        "except ImportError as error:\n"
        "    print('ImportError', error)\n"
    )
    env = dict(os.environ, PYTHONPATH=str(tmp_path))
    done = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True,
                          text=True, cwd=tmp_path, timeout=120)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0] == "64"
    assert lines[1].startswith("ImportError facet.planarize is not available")
    assert "make" in lines[1]
