# SPDX-License-Identifier: LGPL-2.1-or-later
"""Point markers with text labels in the 3D view (Coin nodes, no FreeCAD document data).

A :class:`Markers` is one separator: a marker (a bitmap, the same few pixels wide whatever
the zoom) at each point, and a label beside each. It is drawn over the surfaces
(the depth test off: a pin on the roof is not hidden by the roof's faces) and cannot be
picked (a click goes through it to the object below). Put its ``root`` in a view provider's
display modes (:meth:`Markers.add_to`), or in a 3D view's scene graph for as long as a task
panel is open (:meth:`Markers.show_in` and :meth:`Markers.remove`).

Used by the Lifting's pinned heights (``view_lifting``), the Pin heights panel and the Shape
lifting panel's Raise vertex row; :class:`VertexMarkers`, on vertices of a drawn mesh, by the
Planarized object's held vertices and those selected in its edit panel, and by every Facet
mesh's ring on the vertex under the cursor (``preselection``).
"""

from pivy import coin

#: Marker shapes and their size in pixels: drawn by Facet (FreeCAD 0.20's own bitmaps stop at
#: 9 px, a dot easily lost on a roof's edges).
PIN_STYLE = ("circle", 13)
RAISE_STYLE = ("diamond", 19)

#: Marker indices registered in this process, by style.
_registered = {}


#: How much wider a halo's bitmap is than the marker it surrounds, in pixels.
HALO_GROWTH = 4


def _bitmap(shape, size):
    """Rows of "x" (set) and " " for a ``shape`` of ``size`` pixels: "circle", "diamond",
    "square" (filled), "ring", "frame" (a square's outline, 2 pixels wide) or "halo" (a
    pixel or so either side of the "ring" :data:`HALO_GROWTH` pixels smaller, whose
    colour it sets off on any background)."""
    c = (size - 1) / 2.0
    if shape == "halo":
        ring = c - HALO_GROWTH / 2.0  # the ring's centre radius, as "ring" draws it
        return ["".join("x" if (ring - 3.4 <= r < ring - 2.2 or ring + 0.3 < r <= ring + 1.6)
                        else " " for r in (((i - c) ** 2 + (j - c) ** 2) ** 0.5
                                           for i in range(size)))
                for j in range(size)]
    rows = []
    for j in range(size):
        row = ""
        for i in range(size):
            dx, dy = i - c, j - c
            if shape == "diamond":
                inside = abs(dx) + abs(dy) <= c + 0.25
            elif shape == "square":
                inside = True
            elif shape == "frame":
                inside = max(abs(dx), abs(dy)) >= c - 1.5
            elif shape == "ring":
                inside = c - 2.2 <= (dx * dx + dy * dy) ** 0.5 <= c + 0.3
            else:
                inside = dx * dx + dy * dy <= (c + 0.3) ** 2
            row += "x" if inside else " "
        rows.append(row)
    return rows


def marker_index(style):
    """The SoMarkerSet index of ``(shape, size)``, registered with Coin on first use."""
    if style not in _registered:
        shape, size = style
        index = coin.SoMarkerSet.getNumDefinedMarkers()
        coin.SoMarkerSet.addMarker(index, coin.SbVec2s([size, size]),
                                   "".join(_bitmap(shape, size)), False, True)
        _registered[style] = index
    return _registered[style]


class Markers:
    """Markers of one colour with labels."""

    def __init__(self, color, style=PIN_STYLE, label_color=None, halo=None):
        """``halo``: a colour drawn around each "ring" marker (see :func:`_bitmap`)."""
        self.root = coin.SoSeparator()
        pick = coin.SoPickStyle()
        pick.style = coin.SoPickStyle.UNPICKABLE
        unlit = coin.SoLightModel()
        unlit.model = coin.SoLightModel.BASE_COLOR
        overall = coin.SoMaterialBinding()  # not a Planarity mode's per-face colours
        overall.value = coin.SoMaterialBinding.OVERALL
        depth = coin.SoDepthBuffer()
        depth.test = False  # over the faces
        material = coin.SoMaterial()
        material.diffuseColor.setValue(*color)
        self.coords = coin.SoCoordinate3()
        self.marker = coin.SoMarkerSet()
        self.marker.markerIndex = marker_index(style)
        self.labels = coin.SoSeparator()
        label_material = coin.SoMaterial()
        label_material.diffuseColor.setValue(*(label_color or color))
        font = coin.SoFont()
        font.size = 14
        self.label_root = coin.SoSeparator()
        for node in (label_material, font, self.labels):
            self.label_root.addChild(node)
        behind = ()
        if halo is not None:
            halo_material = coin.SoMaterial()
            halo_material.diffuseColor.setValue(*halo)
            self.halo = coin.SoMarkerSet()
            self.halo.markerIndex = marker_index(("halo", style[1] + HALO_GROWTH))
            behind = (halo_material, self.halo)
        for node in (pick, unlit, overall, depth, self.coords) + behind + (
                material, self.marker, self.label_root):
            self.root.addChild(node)
        self.points = []
        self.texts = []
        self._views = []

    def set(self, points, labels=()):
        """Show a marker at each of ``points`` ((x, y, z) in mm) and ``labels[k]`` beside
        point k (fewer labels: the rest unlabelled)."""
        points = [tuple(float(c) for c in p) for p in points]
        self.coords.point.setNum(len(points))
        if points:
            self.coords.point.setValues(0, len(points), points)
        self.marker.numPoints = len(points)
        if hasattr(self, "halo"):
            self.halo.numPoints = len(points)
        self.labels.removeAllChildren()
        for point, text in zip(points, labels):
            one = coin.SoSeparator()
            move = coin.SoTranslation()
            move.translation.setValue(*point)
            label = coin.SoText2()
            # a space before it: the text starts beside the marker, not on it
            label.string.setValue("   " + str(text))
            one.addChild(move)
            one.addChild(label)
            self.labels.addChild(one)
        self.points = points
        self.texts = [str(t) for t in labels][:len(points)]

    def clear(self):
        self.set([])

    def add_to(self, groups):
        """Draw the markers in each of ``groups`` (a view provider's display modes)."""
        for group in groups:
            if group.findChild(self.root) < 0:
                group.addChild(self.root)

    def show_in(self, view):
        """Draw the markers in ``view`` (a 3D view) until :meth:`remove`."""
        graph = view.getSceneGraph()
        if graph.findChild(self.root) < 0:
            graph.addChild(self.root)
            self._views.append(graph)

    def remove(self):
        """Take the markers out of the views :meth:`show_in` put them in."""
        for graph in self._views:
            index = graph.findChild(self.root)
            if index >= 0:
                graph.removeChild(index)
        self._views = []


class VertexMarkers(Markers):
    """Markers (no labels) on some vertices of a drawn mesh: ``vertices``, their indices."""

    def __init__(self, color, style, halo=None):
        super().__init__(color, style, halo=halo)
        self.vertices = []

    def show(self, vertices, drawn):
        """Markers on ``vertices`` (indices) at their positions in ``drawn`` (the mesh's
        SoCoordinate3 field); indices it does not have are left out."""
        n = drawn.getNum()
        self.vertices = sorted({int(v) for v in vertices if 0 <= int(v) < n})
        self.set([drawn[v].getValue() for v in self.vertices])


def length_text(value):
    """A length in mm in the user's units ("3.00 m", "3000.00 mm")."""
    import FreeCAD as App

    return App.Units.Quantity(float(value), App.Units.Length).UserString
