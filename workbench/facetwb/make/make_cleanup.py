# SPDX-License-Identifier: LGPL-2.1-or-later
"""make_cleanup(): create a Cleanup document object (scripting API, runs headless)."""

from facetwb.objects.cleanup import Cleanup
from facetwb.viewproviders import attach


def make_cleanup(source, min_edge=0.1, relative=True, planarize=True, tolerance=1e-6,
                 name="Cleanup", weld=True):
    """Add a Cleanup object that collapses the short edges of ``source`` on recompute.

    Parameters
    ----------
    source : App.DocumentObject
        A PolyMesh, Planarized, FreeCAD Mesh or Part object. Never modified; hidden in the GUI.
    min_edge : float
        Edges shorter than this collapse (a fraction of the mean edge when ``relative``,
        else mm).
    relative, planarize : bool
    weld : bool
        First join the vertices at one point that are not one vertex (an unwelded export).
    tolerance : float
        Planarity to reach after the collapse, relative to each face's mean edge.

    Returns
    -------
    App.DocumentObject
        The new object; recompute the document to run it.
    """
    if not min_edge > 0:
        raise ValueError(f"min_edge must be > 0, not {min_edge!r}")
    doc = source.Document
    obj = doc.addObject("App::FeaturePython", name)
    Cleanup(obj)
    obj.Label = f"{source.Label} cleaned"
    obj.Source = source
    obj.MinEdge = float(min_edge)
    obj.Relative = bool(relative)
    obj.Planarize = bool(planarize)
    obj.Weld = bool(weld)
    obj.Tolerance = float(tolerance)
    attach.give(obj)
    return obj
