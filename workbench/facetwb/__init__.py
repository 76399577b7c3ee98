# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet's FreeCAD layer: document objects, view providers, commands and the importer.

The numerics live in the pure-Python ``facet`` package beside this one; this package only
turns ``facet`` objects into FreeCAD document objects and draws them.

Scripting API (runs headless in ``freecadcmd``)::

    import FreeCAD as App
    import facet, facetwb

    source = facetwb.make_polymesh(facet.read_mesh("facade.obj"), label="facade")
    result = facetwb.make_planarized(source, tolerance=1e-6)
    App.ActiveDocument.recompute()
    print(facetwb.planarize_summary(result))

The names below are resolved on first use, so importing ``facetwb`` (as ``InitGui.py`` does at
start-up) does not load numpy or the compiled solver.
"""

import importlib

_API = {
    "make_polymesh": "facetwb.make.make_polymesh",
    "make_polymesh_from_object": "facetwb.make.make_polymesh",
    "make_planarized": "facetwb.make.make_planarized",
    "get_mesh": "facetwb.objects.polymesh",
    "is_polymesh": "facetwb.objects.polymesh",
    "is_planarized": "facetwb.objects.planarized",
    "planarize_summary": "facetwb.objects.planarized",
    "make_cleanup": "facetwb.make.make_cleanup",
    "is_cleanup": "facetwb.objects.cleanup",
    "cleanup_summary": "facetwb.objects.cleanup",
    "make_plan_graph": "facetwb.make.make_lifting",
    "make_lifting": "facetwb.make.make_lifting",
    "is_plan_graph": "facetwb.objects.plangraph",
    "is_lifting": "facetwb.objects.lifting",
    "lifting_summary": "facetwb.objects.lifting",
    "make_panelset": "facetwb.objects.panelset",
    "make_cutsheets": "facetwb.objects.panelset",
    "is_panelset": "facetwb.objects.panelset",
    "is_cutsheets": "facetwb.objects.panelset",
    "cutsheets_summary": "facetwb.objects.panelset",
    "make_surface_mesh": "facetwb.objects.surfacemesh",
    "is_surface_mesh": "facetwb.objects.surfacemesh",
}

__all__ = sorted(_API)


def __getattr__(name):
    module = _API.get(name)
    if module is None:
        raise AttributeError(f"module 'facetwb' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_API))
