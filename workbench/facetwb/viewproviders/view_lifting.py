# SPDX-License-Identifier: LGPL-2.1-or-later
"""View providers of PlanGraph and Lifting objects: the PolyMesh drawing with their icons.

Both name what a click picks (:meth:`PickedVertices.getElementPicked`): ``Vertex<n>`` when
the click is within :data:`PICK_PIXELS` of plan vertex n (counted from 0), else ``Face<f>``
or ``Edge<e>``; the Pin heights panel takes the vertices selected so. A Lifting draws its
pinned heights (markers at x, y, height, labelled with the height) while the pins are its
targets; its ``ShowPins`` view property hides them.
"""

from facetwb import compat
from facetwb.viewproviders.view_polymesh import ViewProviderPolyMesh

#: A click this close to a vertex on the screen picks the vertex, pixels.
PICK_PIXELS = 10

#: Colour of the pin markers and their labels.
PIN_COLOR = (0.85, 0.10, 0.55)


def _screen_distance(view, a, b):
    """Distance in pixels of the points ``a`` and ``b`` ((x, y, z) mm) in ``view``."""
    import FreeCAD as App

    pa = view.getPointOnScreen(App.Vector(*a))
    pb = view.getPointOnScreen(App.Vector(*b))
    return ((pa[0] - pb[0]) ** 2 + (pa[1] - pb[1]) ** 2) ** 0.5


def _distance(a, b):
    return sum((p - q) ** 2 for p, q in zip(a, b)) ** 0.5


class PickedVertices:
    """Mixin for a PolyMesh view provider: sub-element names of picks (Vertex, Edge,
    Face), so a vertex can be selected in the 3D view."""

    def getElementPicked(self, picked):  # noqa: N802 - FreeCAD's name
        from pivy import coin

        from facetwb.pins import EDGE, FACE, VERTEX, element_name

        detail = picked.getDetail()
        topology = getattr(self, "drawn_topology", None)
        if detail is None or topology is None:
            return ""
        face_start, face_vertices = topology
        point = tuple(picked.getPoint().getValue())
        if detail.isOfType(coin.SoFaceDetail.getClassTypeId()):
            face = coin.cast(detail, "SoFaceDetail").getFaceIndex()
            if not 0 <= face < len(face_start) - 1:
                return ""
            corners = [int(v) for v in face_vertices[face_start[face]:face_start[face + 1]]]
            fallback = element_name(FACE, face)
        elif detail.isOfType(coin.SoLineDetail.getClassTypeId()):
            line = coin.cast(detail, "SoLineDetail")
            corners = [line.getPoint0().getCoordinateIndex(),
                       line.getPoint1().getCoordinateIndex()]
            fallback = element_name(EDGE, line.getLineIndex())
        else:
            return ""
        # (the corners alone read: preselection asks at every move of the mouse)
        xyz = {v: tuple(self.coords.point[v].getValue()) for v in corners}
        vertex = min(corners, key=lambda v: _distance(xyz[v], point))
        if self._near(point, vertex, xyz):
            return element_name(VERTEX, vertex)
        return fallback

    def _near(self, point, vertex, xyz):
        """True when ``point`` is close enough to corner ``vertex`` to pick it: within
        PICK_PIXELS on the screen, or (no 3D view) within a fifth of the nearest other
        corner."""
        try:
            import FreeCADGui as Gui

            view = Gui.ActiveDocument.ActiveView
            return _screen_distance(view, point, xyz[vertex]) <= PICK_PIXELS
        except Exception:  # noqa: BLE001 - no 3D view: by the face's own size
            others = [_distance(xyz[v], xyz[vertex]) for v in xyz if v != vertex]
            return bool(others) and _distance(point, xyz[vertex]) <= 0.2 * min(others)


class ViewProviderPlanGraph(PickedVertices, ViewProviderPolyMesh):
    """A plan graph: flat faces with their edges."""

    TYPE = "Facet::ViewProviderPlanGraph"
    ICON = "Facet_PlanGraph"
    DEFAULT_DISPLAY_MODE = "Flat Lines"


class ViewProviderLifting(PickedVertices, ViewProviderPolyMesh):
    """A lifted plan: faces with their edges (Planarity mode shows they are flat), and its
    pinned heights."""

    TYPE = "Facet::ViewProviderLifting"
    ICON = "Facet_Lifting"
    DEFAULT_DISPLAY_MODE = "Flat Lines"

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

    def setEdit(self, vobj, mode=0):  # noqa: N802 - FreeCAD's name
        """Double-click: the Pin heights panel of this Lifting."""
        if mode != 0:
            return None
        from facetwb.taskpanels import lift_pins

        return lift_pins.edit(vobj.Object)

    def unsetEdit(self, vobj, mode=0):  # noqa: N802
        if mode != 0:
            return None
        return True

    def doubleClicked(self, vobj):  # noqa: N802
        import FreeCADGui as Gui

        Gui.ActiveDocument.setEdit(vobj.Object.Name, 0)
        return True
