# SPDX-License-Identifier: LGPL-2.1-or-later
"""ViewProviderPolyMesh: draws a Facet polygon mesh with Coin3D.

Scene graph (nodes are shared between the display modes)::

    SoCoordinate3               all vertices
    SoShapeHints                UNKNOWN_FACE_TYPE: faces may be non-convex polygons, which
                                Coin triangulates; two-sided lighting; flat shading
    SoSeparator                 (Flat Lines and Shaded)
      SoDirectionalLight        the key light (KEY_LIGHT; off when None)
      SoMaterial                ShapeColor
      SoIndexedFaceSet          one polygon per face
    SoIndexedLineSet            each edge once

Display modes:

- "Flat Lines": faces in ShapeColor with their edges;
- "Shaded": faces only;
- "Wireframe": edges only;
- "Planarity": each face coloured by its planarity (FacePlanarity: largest distance of its
  vertices from its best-fit plane) with a legend in model units (see legend.py).
"""

import numpy as np
from pivy import coin

import facet
from facetwb import compat, paths
from facetwb.objects.polymesh import MESH_PROPERTIES, mesh_arrays, mesh_update_pending
from facetwb.picked import EDGE, FACE, VERTEX, element_name, parse_element
from facetwb.viewproviders import colormap
from facetwb.viewproviders.legend import PlanarityLegend

DISPLAY_MODES = ["Flat Lines", "Shaded", "Wireframe", "Planarity"]

#: PlanarityEdges "Auto" draws edges up to this many faces.
AUTO_EDGES_MAX_FACES = 20000

#: A pick on a panel or an edge selects its corner ("VertexN") when the corner is drawn
#: within this many pixels of the pick.
VERTEX_PICK_PIXELS = 10

#: The vertex a click would pick (preselected: the cursor near it) is ringed in this colour
#: (FreeCAD's default preselection yellow is in the planarity colours) with a ring as wide
#: as the pick's reach, in a halo of the other colour: white alone was faint on FreeCAD's
#: light grey faces.
PRESELECTED_COLOR = (1.0, 1.0, 1.0)
PRESELECTED_HALO = (0.1, 0.1, 0.1)
PRESELECTED_STYLE = ("ring", 2 * VERTEX_PICK_PIXELS + 1)


def _fit_view(obj, pose):
    """Fit the 3D view of ``obj``'s document to what it shows if it still looks from
    ``pose`` (``attach.fit_view_unmoved``); nothing when ``obj`` was deleted (its document
    closed) before the timer that calls this fired."""
    from facetwb.viewproviders import attach

    try:
        doc = obj.Document
    except ReferenceError:  # ("Cannot access attribute 'Document' of deleted object")
        return
    if doc is not None:
        attach.fit_view_unmoved(doc.Name, pose)


class ViewProviderPolyMesh:
    """View provider of PolyMesh objects (Gui::ViewProviderPythonFeature)."""

    TYPE = "Facet::ViewProviderPolyMesh"
    ICON = "Facet_PolyMesh"
    DEFAULT_DISPLAY_MODE = "Flat Lines"
    #: A light fixed in the model that shades the faces in Flat Lines and Shaded besides
    #: FreeCAD's headlight: (direction it travels in the model, share of the light), or
    #: None. The headlight shines along the line of sight: in an isometric view, faces as
    #: steep as each other facing -y and +x (a roof of one pitch) were lit alike, one flat
    #: grey, and the form did not read. The faces take ``1 - share`` of the headlight
    #: (ShapeColor scaled) and ``share`` of the key light: lit head-on by both, they show
    #: ShapeColor, never brighter (washed out to white).
    KEY_LIGHT = None

    def __init__(self, vobj):
        self.Type = self.TYPE
        self.init_properties(vobj)
        # FreeCAD attaches the proxy (attach draws the mesh), then calls updateData with
        # every property of the object: the mesh was drawn three more times, the same
        # (an imported 1M-face mesh: 4 x 2.6 s, with no progress call in between)
        self.attaching = True
        try:
            vobj.Proxy = self
        finally:
            del self.attaching

    def init_properties(self, vobj):
        """Add the view properties ``vobj`` lacks (idempotent; also run by attach)."""
        add = compat.add_property
        add(vobj, "App::PropertyColor", "ShapeColor", "Display", "Colour of the faces",
            value=(0.80, 0.80, 0.82))
        add(vobj, "App::PropertyColor", "LineColor", "Display", "Colour of the edges",
            value=(0.10, 0.10, 0.12))
        add(vobj, "App::PropertyFloat", "LineWidth", "Display", "Width of the edges, pixels",
            value=1.0)
        add(vobj, "App::PropertyLength", "LegendMax", "Planarity",
            "Planarity shown in the top colour (red) in Planarity mode; larger values are "
            "red too (0: the largest face value)")
        add(vobj, "App::PropertyBool", "ShowLegend", "Planarity",
            "Show the colour legend in Planarity mode", value=True)
        if add(vobj, "App::PropertyEnumeration", "PlanarityEdges", "Planarity",
               "Edges in Planarity mode (Auto: only while the mesh has at most "
               f"{AUTO_EDGES_MAX_FACES} faces, so dense meshes show their colours)"):
            vobj.PlanarityEdges = ["Auto", "Show", "Hide"]
            vobj.PlanarityEdges = "Auto"

    # --- scene graph ------------------------------------------------------------------------

    def attach(self, vobj):
        self.init_properties(vobj)
        self.ViewObject = vobj
        self.Object = vobj.Object
        self.face_count = 0

        self.coords = coin.SoCoordinate3()
        self.faces = coin.SoIndexedFaceSet()
        self.edges = coin.SoIndexedLineSet()
        hints = coin.SoShapeHints()
        hints.vertexOrdering = coin.SoShapeHints.COUNTERCLOCKWISE
        hints.shapeType = coin.SoShapeHints.UNKNOWN_SHAPE_TYPE
        hints.faceType = coin.SoShapeHints.UNKNOWN_FACE_TYPE
        hints.creaseAngle = 0.0
        offset = coin.SoPolygonOffset()  # faces slightly back, so their edges show

        self.face_material = coin.SoMaterial()
        # the key light in a separator with the faces: it lights them alone, not the edges,
        # markers or other objects drawn after them
        self.key_light = coin.SoDirectionalLight()
        if self.KEY_LIGHT is None:
            self.key_light.on = False
        else:
            direction, share = self.KEY_LIGHT
            self.key_light.direction.setValue(*direction)
            self.key_light.intensity = share / (1.0 - share)
        lit_faces = coin.SoSeparator()
        for node in (self.key_light, self.face_material, self.faces):
            lit_faces.addChild(node)
        self.planarity_material = coin.SoMaterial()
        per_face = coin.SoMaterialBinding()
        per_face.value = coin.SoMaterialBinding.PER_FACE
        self.line_material = coin.SoMaterial()
        self.line_style = coin.SoDrawStyle()
        edge_group = coin.SoSeparator()
        overall = coin.SoMaterialBinding()
        overall.value = coin.SoMaterialBinding.OVERALL
        unlit = coin.SoLightModel()
        unlit.model = coin.SoLightModel.BASE_COLOR
        for node in (overall, unlit, self.line_material, self.line_style, self.edges):
            edge_group.addChild(node)
        self.legend = PlanarityLegend()
        self.planarity_edges = coin.SoSwitch()
        self.planarity_edges.addChild(edge_group)

        layouts = {
            "Flat Lines": (self.coords, hints, offset, lit_faces, edge_group),
            "Shaded": (self.coords, hints, lit_faces),
            "Wireframe": (self.coords, edge_group),
            "Planarity": (self.coords, hints, offset, per_face, self.planarity_material,
                          self.faces, self.planarity_edges, self.legend.root),
        }
        from facetwb.viewproviders import preselection
        from facetwb.viewproviders.markers import VertexMarkers

        self.preselected = VertexMarkers(PRESELECTED_COLOR, PRESELECTED_STYLE,
                                         halo=PRESELECTED_HALO)
        overlays = (self.preselected.root,) + tuple(self.overlay_nodes())
        preselection.watch()
        for mode in DISPLAY_MODES:
            group = coin.SoSeparator()
            for node in layouts[mode] + tuple(overlays):
                group.addChild(node)
            vobj.addDisplayMode(group, mode)

        for prop in ("ShapeColor", "LineColor", "LineWidth"):
            self.onChanged(vobj, prop)
        self.redraw_mesh(vobj.Object)

    def overlay_nodes(self):
        """Nodes drawn over the mesh in every display mode (a subclass's markers)."""
        return ()

    def getDisplayModes(self, vobj):
        return DISPLAY_MODES

    def getDefaultDisplayMode(self):
        return self.DEFAULT_DISPLAY_MODE

    def setDisplayMode(self, mode):
        return mode

    def updateData(self, obj, prop):
        if not hasattr(self, "coords"):
            return
        if prop in MESH_PROPERTIES:
            # (drawn by attach; set_mesh stores three properties: drawn at the last)
            if not getattr(self, "attaching", False) and not mesh_update_pending(obj, prop):
                self.redraw_mesh(obj)
        elif prop == "FacePlanarity":
            self.recolor(obj)

    def onChanged(self, vobj, prop):
        if not hasattr(self, "coords"):
            return
        if prop == "ShapeColor":
            share = self.KEY_LIGHT[1] if self.KEY_LIGHT is not None else 0.0
            self.face_material.diffuseColor.setValue(
                *[c * (1.0 - share) for c in vobj.ShapeColor[:3]])
        elif prop == "LineColor":
            self.line_material.diffuseColor.setValue(*vobj.LineColor[:3])
        elif prop == "LineWidth":
            self.line_style.lineWidth = max(vobj.LineWidth, 0.1)
        elif prop in ("LegendMax", "ShowLegend", "PlanarityEdges"):
            self.recolor(vobj.Object)

    def redraw_mesh(self, obj):
        """Rebuild coordinates, faces and edges from the object's mesh properties."""
        arrays = mesh_arrays(obj)
        if arrays is None:  # empty, or mid-update: draw nothing until the three agree
            _set_mfield(self.coords.point, [])
            _set_mfield(self.faces.coordIndex, [])
            _set_mfield(self.edges.coordIndex, [])
            self.preselected.show([], self.coords.point)
            self.face_count = 0
            self.drawn_topology = None
            self.recolor(obj)
            return
        xyz, face_start, face_vertices = arrays
        _set_mfield(self.coords.point, xyz)
        self.preselected.show(self.preselected.vertices, self.coords.point)  # a re-solve
        drawn = getattr(self, "drawn_topology", None)
        if not (drawn is not None and np.array_equal(drawn[0], face_start)
                and np.array_equal(drawn[1], face_vertices)):
            self.draw_topology(xyz, face_start, face_vertices)
        self.recolor(obj)
        pose = getattr(self, "fit_when_drawn", None)
        if pose and self.face_count:
            # (the view's pose, set by a command whose first result was empty: a drawing
            # that failed to read into an empty view; fitted then, the view showed nothing
            # of it. A designer who has moved the view since keeps it.)
            self.fit_when_drawn = None
            from PySide import QtCore

            QtCore.QTimer.singleShot(0, lambda: _fit_view(obj, pose))

    def draw_topology(self, xyz, face_start, face_vertices):
        """Face and edge indices; skipped when only the coordinates change (a re-solve)."""
        degrees = np.diff(face_start)
        n_faces = degrees.size
        # Face indices with -1 after each face: face j's corners go to start_j + j ...
        face_index = np.full(face_vertices.size + n_faces, -1, dtype=np.int32)
        face_index[np.arange(face_vertices.size) + np.repeat(np.arange(n_faces), degrees)] = \
            face_vertices
        mesh = facet.PolyMesh(xyz, face_start, face_vertices)
        edges = np.asarray(mesh.edges(), dtype=np.int32).reshape(-1, 2)
        edge_index = np.hstack([edges, np.full((edges.shape[0], 1), -1, dtype=np.int32)])
        _set_mfield(self.faces.coordIndex, face_index)
        _set_mfield(self.edges.coordIndex, edge_index.ravel())
        self.face_count = n_faces
        self.drawn_topology = (face_start.copy(), face_vertices.copy())

    def colour_values(self, obj):
        """What the colour map shows: (per-face values or None, legend title, kind,
        reversed). kind is "length" (mm), "angle" (degrees) or "ratio"; reversed puts the
        top colour (red) at the small end. PolyMesh: FacePlanarity in mm."""
        values = np.asarray(getattr(obj, "FacePlanarity", []), dtype=np.float64)
        return values, "Planarity", "length", False

    def recolor(self, obj):
        """Colour the faces by ``colour_values`` and label the legend."""
        vobj = self.ViewObject
        try:
            values, title, kind, reverse = (self.colour_values(obj) if self.face_count else
                                            (None, "Planarity", "length", False))
        except Exception as exc:  # a bad source must not break drawing; say why
            import FreeCAD as App

            App.Console.PrintWarning(f"{obj.Label}: colour map not computed: {exc}\n")
            values, title, kind, reverse = None, "Planarity", "length", False
        if values is None or self.face_count == 0 or values.size != self.face_count:
            count = max(self.face_count, 1)
            _set_mfield(self.planarity_material.diffuseColor,
                        np.tile(np.asarray(colormap.NO_VALUE, dtype=np.float32), (count, 1)))
            self.legend.update(0.0, title=title, kind=kind,
                               note="not computed")
        else:
            actual_max = float(values.max()) if values.size else 0.0
            legend_max = vobj.LegendMax.Value if kind == "length" else 0.0
            scale_max = legend_max if legend_max > 0.0 else actual_max
            rgb = colormap.colors(values, scale_max, reverse=reverse)
            _set_mfield(self.planarity_material.diffuseColor, rgb.astype(np.float32))
            if reverse:  # small is bad: say the smallest
                self.legend.update(scale_max, actual_max=float(values.min()), title=title,
                                   kind=kind, reverse=True, extreme_name="min")
            else:
                self.legend.update(scale_max, actual_max=actual_max, title=title, kind=kind)
        self.legend.set_visible(bool(vobj.ShowLegend))
        edges = getattr(vobj, "PlanarityEdges", "Auto")
        show_edges = edges == "Show" or (
            edges == "Auto" and self.face_count <= AUTO_EDGES_MAX_FACES)
        self.planarity_edges.whichChild = coin.SO_SWITCH_ALL if show_edges else \
            coin.SO_SWITCH_NONE

    # --- selection in the 3D view -----------------------------------------------------------

    def getElementPicked(self, pp):  # noqa: N802 - FreeCAD's name
        """The sub-element under a pick in the 3D view (the status bar and
        ``Gui.Selection.getSelectionEx`` show it): "VertexN" when a corner of the picked
        panel or edge is drawn within VERTEX_PICK_PIXELS of the pick (N: the vertex's index
        in the mesh, from 0, as FixedVertices counts), else "FaceN" (the panel, from 0),
        "EdgeN" (the edge, from 0, in the order of facet.PolyMesh.edges) or ""."""
        element, corners = picked_element(pp.getDetail())
        kind, index = parse_element(element)
        if kind == FACE:
            element, corners = self.picked_face(index, corners)
        vertex = self.nearest_corner(corners, pp.getPoint().getValue())
        return element_name(VERTEX, vertex) if vertex is not None else element

    def preselect(self, vertex):
        """Ring ``vertex`` (an index; None: none), where it is drawn: FreeCAD preselects it
        while the cursor is near it (``preselection``). True when it is ringed."""
        if not hasattr(self, "coords"):
            return False
        self.preselected.show([] if vertex is None else [vertex], self.coords.point)
        return bool(self.preselected.vertices)

    def picked_face(self, index, corners):
        """("FaceN", all its corners) of the picked polygon ``index``: Coin's detail has
        the corners of the triangle of it that was hit. While an Edit control mesh session
        draws the panels as triangles, ("", the triangle's corners)."""
        from facetwb import edit_control

        session = edit_control.active_session()
        drawn = getattr(self, "drawn_topology", None)
        if (session is not None and session.vobj is self.ViewObject) or drawn is None \
                or not 0 <= index < drawn[0].size - 1:
            return "", corners
        face_start, face_vertices = drawn
        return (element_name(FACE, index),
                face_vertices[face_start[index]:face_start[index + 1]].tolist())

    def nearest_corner(self, corners, point):
        """The one of ``corners`` (vertex indices) drawn nearest ``point`` (a picked point)
        on the screen, if within VERTEX_PICK_PIXELS; or None."""
        import FreeCAD as App

        view = _view_of(self.Object)
        if view is None or not corners or not hasattr(self, "coords"):
            return None
        drawn = self.coords.point
        at = view.getPointOnScreen(App.Vector(*point))
        best, best_pixels = None, VERTEX_PICK_PIXELS
        for vertex in corners:
            if not 0 <= vertex < drawn.getNum():
                continue
            x, y = view.getPointOnScreen(App.Vector(*drawn[vertex].getValue()))
            pixels = float(np.hypot(x - at[0], y - at[1]))
            if pixels <= best_pixels:
                best, best_pixels = vertex, pixels
        return best

    # --- tree -----------------------------------------------------------------------------

    def getIcon(self):
        return paths.icon_path(self.ICON)

    def claimChildren(self):
        source = getattr(self.Object, "Source", None) if hasattr(self, "Object") else None
        return [source] if source is not None else []

    def onDelete(self, vobj, subelements):
        """Show the source again when its derived object is deleted."""
        source = getattr(vobj.Object, "Source", None)
        if source is not None and source.ViewObject is not None:
            source.ViewObject.Visibility = True
        return True

    # --- saving: nothing to save, everything is rebuilt by attach() -----------------------

    def dumps(self):
        return None

    def loads(self, state):
        self.Type = self.TYPE

    def __getstate__(self):
        return self.dumps()

    def __setstate__(self, state):
        self.loads(state)


class EditsInPanel:
    """Mixin for a view provider whose double-click opens the object's task panel:
    :meth:`open_panel` (``panel(obj)``, True when it opened); FreeCAD's own edit modes
    (transform, ...) are left to FreeCAD."""

    def open_panel(self, obj):
        raise NotImplementedError

    def setEdit(self, vobj, mode=0):  # noqa: N802 - FreeCAD's name
        if mode != 0:
            return None
        return self.open_panel(vobj.Object)

    def unsetEdit(self, vobj, mode=0):  # noqa: N802
        if mode != 0:
            return None
        return True

    def doubleClicked(self, vobj):  # noqa: N802
        import FreeCADGui as Gui

        Gui.ActiveDocument.setEdit(vobj.Object.Name, 0)
        return True


def picked_element(detail):
    """``(element, corners)`` of a Coin pick's detail on a mesh drawn by this module:
    "FaceN" and the coordinate indices of the picked polygon's corners, "EdgeN" and its two
    ends, "VertexN" and that vertex; ("", ()) for anything else."""
    if detail is None:
        return "", ()
    if detail.isOfType(coin.SoFaceDetail.getClassTypeId()):
        face = coin.cast(detail, "SoFaceDetail")
        corners = [face.getPoint(i).getCoordinateIndex() for i in range(face.getNumPoints())]
        return element_name(FACE, face.getFaceIndex()), corners
    if detail.isOfType(coin.SoLineDetail.getClassTypeId()):
        line = coin.cast(detail, "SoLineDetail")
        return element_name(EDGE, line.getLineIndex()), [
            line.getPoint0().getCoordinateIndex(), line.getPoint1().getCoordinateIndex()]
    if detail.isOfType(coin.SoPointDetail.getClassTypeId()):
        index = coin.cast(detail, "SoPointDetail").getCoordinateIndex()
        return element_name(VERTEX, index), [index]
    return "", ()


def _view_of(obj):
    """The 3D view showing ``obj``'s document (the active one of it), or None."""
    try:
        import FreeCADGui as Gui

        view = Gui.getDocument(obj.Document.Name).ActiveView
    except Exception:  # noqa: BLE001 - no GUI document (closing)
        return None
    return view if hasattr(view, "getPointOnScreen") else None


def _set_mfield(field, values):
    """Replace all values of a Coin multiple-value field (setValues alone never shrinks it).

    ``values``: a list, or a numpy array (rows of 3 for vector fields), which pivy reads
    without a Python object per value (1M vertices: 0.1 s, as a list of lists 0.8 s)."""
    count = len(values)
    field.setNum(count)
    if count:
        field.setValues(0, count, values)
