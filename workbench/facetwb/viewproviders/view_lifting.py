# SPDX-License-Identifier: LGPL-2.1-or-later
"""View providers of PlanGraph and Lifting objects: the PolyMesh drawing with their icons."""

from facetwb.viewproviders.view_polymesh import ViewProviderPolyMesh


class ViewProviderPlanGraph(ViewProviderPolyMesh):
    """A plan graph: flat faces with their edges."""

    TYPE = "Facet::ViewProviderPlanGraph"
    ICON = "Facet_PlanGraph"
    DEFAULT_DISPLAY_MODE = "Flat Lines"


class ViewProviderLifting(ViewProviderPolyMesh):
    """A lifted plan: faces with their edges (Planarity mode shows they are flat)."""

    TYPE = "Facet::ViewProviderLifting"
    ICON = "Facet_Lifting"
    DEFAULT_DISPLAY_MODE = "Flat Lines"
