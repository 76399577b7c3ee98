# SPDX-License-Identifier: LGPL-2.1-or-later
"""View provider of SurfaceMesh objects: a PolyMesh drawing with the surface-mesh icon."""

from facetwb.viewproviders.view_polymesh import ViewProviderPolyMesh


class ViewProviderSurfaceMesh(ViewProviderPolyMesh):
    """Draws a SurfaceMesh like any Facet polygon mesh (Flat Lines, Planarity, ...)."""

    TYPE = "Facet::ViewProviderSurfaceMesh"
    ICON = "Facet_SurfaceMesh"
