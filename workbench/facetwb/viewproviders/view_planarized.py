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
  (a ratio; 0 = same proportions as the source);
- Straightest corner: how far a face's straightest corner turns its outline
  (degrees; red = nearly straight: a quad that is a triangle with a kink).

In every display mode the vertices held in place (``FixedVertices``) are drawn as magenta
squares (11 pixels) and, while the Planarize edit panel is open, the vertices selected in
the 3D view framed in black (17 pixels), over the panels (``markers.VertexMarkers``).
"""

import numpy as np

from facetwb import compat
from facetwb.objects.polymesh import MESH_PROPERTIES
from facetwb.viewproviders.view_polymesh import EditsInPanel, ViewProviderPolyMesh

#: Held vertices: colour and marker (a filled square, screen pixels); magenta is not in the
#: colour map.
HELD_COLOR = (1.0, 0.0, 1.0)
HELD_STYLE = ("square", 11)
#: Vertices selected while the Planarize edit panel is open: a black frame around the
#: vertex, held or not.
SELECTED_COLOR = (0.0, 0.0, 0.0)
SELECTED_STYLE = ("frame", 17)

#: ColorBy choices: (facet.QualityReport.per_face name, legend title, kind, reversed).
COLOR_BY = {
    "Planarity": ("planarity", "Planarity", "length", False),
    "Displacement": ("displacement", "Displacement", "length", False),
    "Distance to input": ("distance", "Distance to input", "length", False),
    "Distance to reference": ("distance", "Distance to reference", "length", False),
    "Smallest angle": ("min_angle", "Smallest angle", "angle", True),
    "Edge ratio change": ("ratio_change", "Edge ratio change", "ratio", False),
    "Straightest corner": ("straight_corner", "Straightest corner", "angle", True),
}


class ViewProviderPlanarized(EditsInPanel, ViewProviderPolyMesh):
    """View provider of Planarized objects: PolyMesh drawing, Planarity mode first."""

    TYPE = "Facet::ViewProviderPlanarized"
    ICON = "Facet_Planarized"
    DEFAULT_DISPLAY_MODE = "Planarity"

    def init_properties(self, vobj):
        super().init_properties(vobj)
        if compat.add_property(vobj, "App::PropertyEnumeration", "ColorBy", "Planarity",
                               "What the colours of Planarity mode show: planarity, vertex "
                               "displacement, distance from the source's surface or from "
                               "the Reference (mm), smallest angle (degrees), change of edge "
                               "ratios or how far the straightest corner turns (degrees)"):
            vobj.ColorBy = list(COLOR_BY)
            vobj.ColorBy = "Planarity"
        elif list(vobj.getEnumerationsOfProperty("ColorBy")) != list(COLOR_BY):
            # a document from before a choice was added: the same choice, the new list
            choice = vobj.ColorBy
            vobj.ColorBy = list(COLOR_BY)
            vobj.ColorBy = choice

    def overlay_nodes(self):
        from facetwb.viewproviders.markers import VertexMarkers

        self.held = VertexMarkers(HELD_COLOR, HELD_STYLE)
        self.selected = VertexMarkers(SELECTED_COLOR, SELECTED_STYLE)
        return (self.selected.root, self.held.root)

    def redraw_mesh(self, obj):
        super().redraw_mesh(obj)
        self.redraw_markers(obj)

    def redraw_markers(self, obj, selected=None):
        """The held vertices' markers from ``obj.FixedVertices``; the selected ones' from
        ``selected`` (indices; None: the same vertices as before)."""
        if not hasattr(self, "held"):
            return
        self.held.show(getattr(obj, "FixedVertices", ()), self.coords.point)
        self.selected.show(self.selected.vertices if selected is None else selected,
                           self.coords.point)

    def updateData(self, obj, prop):
        super().updateData(obj, prop)
        if prop == "FixedVertices" and prop not in MESH_PROPERTIES:
            self.redraw_markers(obj)
        from facetwb import live_parameters

        live_parameters.parameter_changed(obj, prop)

    def open_panel(self, obj):
        """Double-click: the Planarize panel of this object, its parameters applied live."""
        from facetwb.taskpanels import edit_panels

        return edit_panels.edit(obj)

    def onChanged(self, vobj, prop):
        super().onChanged(vobj, prop)
        if prop == "ColorBy" and hasattr(self, "coords"):
            self.recolor(vobj.Object)

    def colour_values(self, obj):
        choice = getattr(self.ViewObject, "ColorBy", "Planarity")
        if choice not in COLOR_BY or choice == "Planarity":
            return super().colour_values(obj)
        name, title, kind, reverse = COLOR_BY[choice]
        import facet
        from facetwb import conversion
        from facetwb.objects.polymesh import get_mesh

        mesh = get_mesh(obj)
        if choice == "Distance to reference":
            # the design surface the panels were held to (Data surface), when one is given
            reference = getattr(obj, "Reference", None)
            if mesh is None or reference is None:
                return None, title, kind, reverse
            values = facet.quality(mesh, reference=conversion.mesh_from_object(
                reference)).per_face(name)
            return np.asarray(values, dtype=np.float64), title, kind, reverse
        source = getattr(obj, "Source", None)
        if mesh is None or source is None:
            return None, title, kind, reverse
        before = conversion.mesh_from_object(source)
        if not mesh.same_topology(before):
            return None, title, kind, reverse
        values = facet.quality(mesh, input=before).per_face(name)
        if values is None:
            return None, title, kind, reverse
        return np.asarray(values, dtype=np.float64), title, kind, reverse
