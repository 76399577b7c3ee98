# SPDX-License-Identifier: LGPL-2.1-or-later
"""make_polymesh(): create a PolyMesh document object (scripting API, runs headless)."""

import FreeCAD as App

from facetwb.objects.polymesh import PolyMesh, set_mesh
from facetwb.viewproviders import attach


def make_polymesh(mesh, name="PolyMesh", label=None, doc=None):
    """Add a PolyMesh holding ``mesh`` (a ``facet.PolyMesh``) to ``doc``.

    Parameters
    ----------
    mesh : facet.PolyMesh
        The polygon mesh; its coordinates are stored bit for bit.
    name, label : str
        Internal name (made unique by FreeCAD) and label shown in the tree.
    doc : App.Document, optional
        Defaults to the active document, or a new one if there is none.

    Returns
    -------
    App.DocumentObject
        The new object; recompute the document to measure its planarity.
    """
    doc = doc or App.ActiveDocument or App.newDocument()
    obj = doc.addObject("App::FeaturePython", name)
    PolyMesh(obj)
    if label:
        obj.Label = label
    set_mesh(obj, mesh)
    attach.give(obj)
    return obj


def make_polymesh_from_object(source, name="PolyMesh", tessellation_tolerance=0.0):
    """Add a PolyMesh built from a FreeCAD Mesh or Part object, kept linked to it.

    The PolyMesh rebuilds itself from ``source`` on recompute: a Part shape of planar
    polygons gives one polygon per face, other shapes and Meshes give triangles.
    """
    doc = source.Document
    obj = doc.addObject("App::FeaturePython", name)
    PolyMesh(obj)
    obj.Label = f"{source.Label} polygons"
    obj.Source = source
    obj.TessellationTolerance = tessellation_tolerance
    attach.give(obj)
    return obj
