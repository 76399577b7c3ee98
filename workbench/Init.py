# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet start-up (also headless): registers the polygon mesh import types.

FreeCAD's Mesh module registers .obj too; both appear in File > Import, and Facet's entry keeps
quads and other polygons instead of splitting them into triangles.
"""

import FreeCAD

FreeCAD.addImportType("Polygon mesh for Facet (*.obj *.off)", "facetwb.importer")
