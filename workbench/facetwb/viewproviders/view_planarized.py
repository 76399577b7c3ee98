# SPDX-License-Identifier: LGPL-2.1-or-later
"""ViewProviderPlanarized: a planarized mesh, shown in its planarity colours by default.

Its ``ColorBy`` property picks what the colour map shows (facet.quality against the
object's Source, the mesh before planarization):

- Planarity: largest distance of a face's vertices from its best-fit plane (mm);
- Displacement: per face, the largest distance one of its vertices moved (mm);
- Distance to input: per face, the largest distance of one of its vertices from the
  source's surface (mm);
- Smallest angle: a face's smallest interior angle (degrees; red = small);
- Edge ratio change: a face's largest change of edge length over mean edge length
  (a ratio; 0 = same proportions as the source).
"""

import numpy as np

from facetwb import compat
from facetwb.viewproviders.view_polymesh import ViewProviderPolyMesh

#: ColorBy choices: (legend title, kind, reversed).
COLOR_BY = {
    "Planarity": ("Planarity", "length", False),
    "Displacement": ("Displacement", "length", False),
    "Distance to input": ("Distance to input", "length", False),
    "Smallest angle": ("Smallest angle", "angle", True),
    "Edge ratio change": ("Edge ratio change", "ratio", False),
}


def face_max(per_vertex, mesh):
    """Per face, the largest of its vertices' values."""
    values = np.asarray(per_vertex, dtype=np.float64)[mesh.face_vertices]
    return np.maximum.reduceat(values, mesh.face_start[:-1])


class ViewProviderPlanarized(ViewProviderPolyMesh):
    """View provider of Planarized objects: PolyMesh drawing, Planarity mode first."""

    TYPE = "Facet::ViewProviderPlanarized"
    ICON = "Facet_Planarized"
    DEFAULT_DISPLAY_MODE = "Planarity"

    def init_properties(self, vobj):
        super().init_properties(vobj)
        if compat.add_property(vobj, "App::PropertyEnumeration", "ColorBy", "Planarity",
                               "What the colours of Planarity mode show: planarity, vertex "
                               "displacement or distance from the source's surface (mm), "
                               "smallest angle (degrees) or change of edge ratios"):
            vobj.ColorBy = list(COLOR_BY)
            vobj.ColorBy = "Planarity"

    def onChanged(self, vobj, prop):
        super().onChanged(vobj, prop)
        if prop == "ColorBy" and hasattr(self, "coords"):
            self.recolor(vobj.Object)

    def colour_values(self, obj):
        choice = getattr(self.ViewObject, "ColorBy", "Planarity")
        if choice not in COLOR_BY or choice == "Planarity":
            return super().colour_values(obj)
        title, kind, reverse = COLOR_BY[choice]
        import facet
        from facetwb import conversion
        from facetwb.objects.polymesh import get_mesh

        mesh = get_mesh(obj)
        source = getattr(obj, "Source", None)
        if mesh is None or source is None:
            return None, title, kind, reverse
        before = conversion.mesh_from_object(source)
        if not mesh.same_topology(before):
            return None, title, kind, reverse
        report = facet.quality(mesh, input=before)
        if choice == "Displacement":
            values = face_max(report.displacement, mesh)
        elif choice == "Distance to input":
            values = face_max(report.distance, mesh)
        elif choice == "Smallest angle":
            values = report.min_angle
        else:
            values = report.ratio_change
        return np.asarray(values, dtype=np.float64), title, kind, reverse
