# SPDX-License-Identifier: LGPL-2.1-or-later
"""Shared helpers of the headless FreeCAD tests."""

import os
import tempfile
import unittest

import FreeCAD as App
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, "tests", "data")


def data_path(name):
    return os.path.join(DATA, name)


def bits(array):
    """The float64 bit patterns of ``array`` (for exact comparisons, NaN included)."""
    return np.ascontiguousarray(array, dtype=np.float64).view(np.uint64)


def points_array(obj):
    return np.array([(p.x, p.y, p.z) for p in obj.Points], dtype=np.float64).reshape(-1, 3)


class DocumentTestCase(unittest.TestCase):
    """A test class with its own fresh document (``cls.doc``) and a temp folder."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="facet-test-")
        cls.documents_before = set(App.listDocuments())
        cls.doc = App.newDocument(cls.__name__)

    @classmethod
    def tearDownClass(cls):
        for name in set(App.listDocuments()) - cls.documents_before:
            App.closeDocument(name)
        cls.tmp.cleanup()

    def recompute_cancelled(self, after):
        """Recompute ``self.doc`` with a progress reporter whose Cancel is pressed at its
        ``after``-th call (facetwb.progress.cancel_after); returns the reporter."""
        from facetwb import progress

        progress.cancel_after(after)
        try:
            with progress.reporting("test") as reporter:
                self.doc.recompute()
        finally:
            progress.cancel_after(0)
        return reporter

    def save_and_reopen(self, filename):
        """Save ``self.doc``, close it, reopen it; ``self.doc`` is the reopened one."""
        path = os.path.join(self.tmp.name, filename)
        type(self).doc.saveAs(path)
        name = type(self).doc.Name
        App.closeDocument(name)
        type(self).doc = App.openDocument(path)
        return type(self).doc


def outward_faces(obj, centre=None):
    """True for each face of ``obj``'s mesh whose polygon normal (Newell) points away from
    ``centre`` (default: the mean of the mesh's vertices)."""
    import facetwb

    mesh = facetwb.get_mesh(obj)
    if centre is None:
        centre = mesh.vertices.mean(axis=0)
    result = []
    for face in mesh.faces():
        corners = mesh.vertices[face]
        normal = np.cross(corners, np.roll(corners, -1, axis=0)).sum(axis=0)
        result.append(float(np.dot(normal, corners.mean(axis=0) - centre)) > 0.0)
    return result
