# SPDX-License-Identifier: LGPL-2.1-or-later
"""make_planarized(): create a Planarized document object (scripting API, runs headless)."""

from facetwb.objects.planarized import METHODS, Planarized
from facetwb.viewproviders import attach


def make_planarized(source, method="auto", tolerance=1e-6, tolerance_abs=0.0, max_iterations=0,
                    threads=0, name="Planarized"):
    """Add a Planarized object that planarizes ``source`` on recompute.

    Parameters
    ----------
    source : App.DocumentObject
        A PolyMesh, Planarized, FreeCAD Mesh or Part object. Never modified; in the GUI it is
        hidden (the result takes its place in the view).
    method : {"auto", "lg", "ll"}
        Local/global or local/local iterations, or auto: local/global up to 40,000 face
        corners, local/local above (see facet.planarize).
    tolerance : float
        Target planarity relative to each face's mean edge length.
    tolerance_abs : float
        Target planarity in mm (0: only ``tolerance``).
    max_iterations, threads : int
        0 lets the solver choose.

    Returns
    -------
    App.DocumentObject
        The new object; recompute the document to solve.
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, not {method!r}")
    doc = source.Document
    obj = doc.addObject("App::FeaturePython", name)
    Planarized(obj)
    obj.Label = f"{source.Label} planarized"
    obj.Source = source
    obj.Method = method
    obj.Tolerance = tolerance
    obj.ToleranceAbs = tolerance_abs
    obj.MaxIterations = max_iterations
    obj.Threads = threads
    attach.give(obj)
    return obj
