# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet: planar panels for freeform facades.

The pure-Python API of the Facet workbench; it never imports FreeCAD.

>>> import facet
>>> mesh = facet.read_mesh("tubemesh.off")                # doctest: +SKIP
>>> result = facet.planarize(mesh, tol=1e-6)               # doctest: +SKIP
>>> facet.write_mesh(result.mesh, "tubemesh_planar.obj")   # doctest: +SKIP

The solver and the planarity measures live in the compiled core
(``facet._core``). When it is not built, reading, writing and the mesh class
still work, and using :func:`planarize` or :func:`planarity` raises an
ImportError saying so.
"""

from facet.errors import Cancelled, FacetError, InputError, MeshError
from facet.io import read_mesh, write_mesh
from facet.mesh import PolyMesh
from facet.plan import PlanError, PlanGraph, read_plan

__version__ = "0.1.0"

__all__ = [
    "PolyMesh",
    "FacetError",
    "InputError",
    "MeshError",
    "Cancelled",
    "read_mesh",
    "write_mesh",
    "planarize",
    "Planarizer",
    "PlanarizeResult",
    "planarity",
    "PlanarityReport",
    "Surface",
    "quality",
    "QualityReport",
    "cleanup",
    "CleanupResult",
    "PlanError",
    "PlanGraph",
    "read_plan",
    "lift",
    "Lifter",
    "LiftResult",
    "LiftingSpace",
    "lifting_space",
    "panels",
    "PanelSet",
    "PanelError",
    "LiveSolver",
    "soft_weights",
    "__version__",
]

_SOLVER_NAMES = ("planarize", "Planarizer", "PlanarizeResult", "planarity", "PlanarityReport",
                 "Surface", "quality", "QualityReport", "cleanup", "CleanupResult",
                 "lift", "Lifter", "LiftResult", "LiftingSpace", "lifting_space",
                 "panels", "PanelSet", "PanelError", "LiveSolver", "soft_weights")
_SOLVER_MODULES = ("facet.planarity", "facet.planarize", "facet._core", "facet.surface",
                   "facet.quality", "facet.cleanup", "facet.lift", "facet.panels",
                   "facet.live")
_solver_import_error = None

try:
    from facet.planarity import PlanarityReport, planarity
    from facet.planarize import Planarizer, PlanarizeResult, planarize
    from facet.surface import Surface
    from facet.quality import QualityReport, quality
    from facet.cleanup import CleanupResult, cleanup
    from facet.lift import Lifter, LiftingSpace, LiftResult, lift, lifting_space
    from facet.panels import PanelError, PanelSet, panels
    from facet.live import LiveSolver, soft_weights
except ImportError as exc:  # the compiled core is not built (yet)
    core_missing = exc.name == "facet" and "_core" in str(exc)
    if exc.name not in _SOLVER_MODULES and not core_missing:
        raise
    _solver_import_error = exc
    del core_missing
    for _name in _SOLVER_NAMES:
        globals().pop(_name, None)
    del _name


def __getattr__(name):
    if name in _SOLVER_NAMES and _solver_import_error is not None:
        raise ImportError(
            f"facet.{name} is not available ({_solver_import_error}); build the compiled "
            "core with 'make' in the Facet source tree",
            name=_solver_import_error.name,
        ) from _solver_import_error
    raise AttributeError(f"module 'facet' has no attribute {name!r}")
