# SPDX-License-Identifier: LGPL-2.1-or-later
"""ViewProviderPlanarized: a planarized mesh, shown in its planarity colours by default."""

from facetwb.viewproviders.view_polymesh import ViewProviderPolyMesh


class ViewProviderPlanarized(ViewProviderPolyMesh):
    """View provider of Planarized objects: PolyMesh drawing, Planarity mode first."""

    TYPE = "Facet::ViewProviderPlanarized"
    ICON = "Facet_Planarized"
    DEFAULT_DISPLAY_MODE = "Planarity"
