# SPDX-License-Identifier: LGPL-2.1-or-later
"""View providers of PlanGraph and Lifting objects: the PolyMesh drawing with their icons.

Both name what a click picks, as every Facet mesh does
(:meth:`ViewProviderPolyMesh.getElementPicked`): ``Vertex<n>`` near plan vertex n (counted
from 0), else ``Face<f>`` or ``Edge<e>``; the Pin heights panel takes the vertices selected
so. A Lifting draws its
pinned heights (markers at x, y, height, labelled with the height) while the pins are its
targets; its ``ShowPins`` view property hides them.
"""

from facetwb import compat
from facetwb.viewproviders.view_polymesh import EditsInPanel, ViewProviderPolyMesh

#: Colour of the pin markers and their labels.
PIN_COLOR = (0.85, 0.10, 0.55)


class ViewProviderPlanGraph(ViewProviderPolyMesh):
    """A plan graph: flat faces with their edges."""

    TYPE = "Facet::ViewProviderPlanGraph"
    ICON = "Facet_PlanGraph"
    DEFAULT_DISPLAY_MODE = "Flat Lines"


class ViewProviderLifting(EditsInPanel, ViewProviderPolyMesh):
    """A lifted plan: faces with their edges (Planarity mode shows they are flat), and its
    pinned heights."""

    TYPE = "Facet::ViewProviderLifting"
    ICON = "Facet_Lifting"
    DEFAULT_DISPLAY_MODE = "Flat Lines"
    #: A roof is seen from above, where the headlight lit the slopes of one pitch alike:
    #: a light from above the -x, -y corner (as the sun from the south-west) shades each
    #: slope by the way it faces.
    KEY_LIGHT = ((0.35, 0.6, -0.72), 0.4)

    def init_properties(self, vobj):
        super().init_properties(vobj)
        compat.add_property(vobj, "App::PropertyBool", "ShowPins", "Display",
                            "Show the pinned heights (markers labelled with the height) "
                            "while they are the targets", value=True)

    def attach(self, vobj):
        from facetwb.viewproviders.markers import Markers

        super().attach(vobj)
        self.pins = Markers(PIN_COLOR)
        switch = vobj.SwitchNode
        self.pins.add_to([switch.getChild(k) for k in range(switch.getNumChildren())])
        self.draw_pins(vobj.Object)

    def draw_pins(self, obj):
        """Markers at the pinned points (x, y, height), labelled with the height, while the
        pins are the Lifting's targets and ShowPins is on; none otherwise."""
        from facetwb.objects.lifting import pins_in_use
        from facetwb.viewproviders.markers import length_text

        if not hasattr(self, "pins"):
            return
        shown = bool(getattr(self.ViewObject, "ShowPins", True))
        if not (shown and "PinnedPoints" in obj.PropertiesList and pins_in_use(obj)):
            self.pins.clear()
            return
        points = [(p.x, p.y, p.z) for p in obj.PinnedPoints]
        self.pins.set(points, [length_text(p[2]) for p in points])

    def updateData(self, obj, prop):  # noqa: N802 - FreeCAD's name
        super().updateData(obj, prop)
        if prop in ("PinnedPoints", "Targets", "TargetFile"):
            self.draw_pins(obj)

    def onChanged(self, vobj, prop):  # noqa: N802
        super().onChanged(vobj, prop)
        if prop == "ShowPins" and hasattr(self, "pins"):
            self.draw_pins(vobj.Object)

    def open_panel(self, obj):
        """Double-click: the Pin heights panel of a Lifting lifted to pinned heights (or to
        no targets yet), the Shape lifting panel of one that follows a surface or points
        (Pin heights said there that its pins were not used)."""
        from facetwb.taskpanels import lift_mix, lift_pins

        follows = obj.Targets is not None or bool(obj.TargetFile)
        return (lift_mix if follows else lift_pins).edit(obj)
