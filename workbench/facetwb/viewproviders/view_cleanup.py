# SPDX-License-Identifier: LGPL-2.1-or-later
"""ViewProviderCleanup: a cleaned-up mesh, shown in its planarity colours by default."""

from facetwb.viewproviders.view_polymesh import ViewProviderPolyMesh


class ViewProviderCleanup(ViewProviderPolyMesh):
    """View provider of Cleanup objects: PolyMesh drawing, Planarity mode first."""

    TYPE = "Facet::ViewProviderCleanup"
    ICON = "Facet_Cleanup"
    DEFAULT_DISPLAY_MODE = "Planarity"
