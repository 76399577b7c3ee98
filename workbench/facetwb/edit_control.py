# SPDX-License-Identifier: LGPL-2.1-or-later
"""Edit and observe: drag the control vertices of a Planarized object in the 3D view.

An :class:`EditSession` shows the control mesh of a Planarized object (its ``Source``, a
PolyMesh) as a wireframe with a marker on every vertex, over the planar result. Press the
left mouse button on a marker and drag: the vertex moves in the plane through it facing
the view, its neighbours within the soft-selection radius follow by the falloff weight,
and the planar result follows in the same view (a :class:`facet.live.LiveSolver` keeps the
solver alive; a frame is a live update: the region around the moved vertices re-solved to
the object's tolerance, on a worker thread; moves that arrive while a frame is solving are
merged into the next frame). Releasing the button re-solves the whole mesh only if the last
frame fell short of the tolerance. The result is coloured by planarity or by the distance
of each panel from the control mesh.

Nothing in the document changes while editing: the moved positions live in the session.
**Done** (the task panel's OK, or Esc in the 3D view) writes them to the control PolyMesh in
one undoable transaction and recomputes; **Cancel** leaves the control mesh as it was. A
control mesh rebuilt from another object on recompute (a SurfaceMesh of the tutorial's
surface) is left as it is: Done puts the moved vertices in a new PolyMesh, which the
Planarized object then follows, in the same transaction.

Numerics (soft selection, solves, colours) come from ``facet``; this module is wiring:
Coin nodes, mouse events, a Qt timer and the task panel.
"""

import threading
import time

import numpy as np
from pivy import coin

import FreeCAD as App
import FreeCADGui as Gui

from facet.errors import Cancelled
from facet.live import FALLOFFS, LiveSolver, panel_triangles
from facetwb.objects.planarized import is_planarized, term_options
from facetwb.objects.polymesh import get_mesh, is_polymesh
from facetwb.viewproviders import colormap
from facetwb.viewproviders.legend import tick_labels

#: What the result's colours show while editing.
COLOR_BY = ("Planarity", "Distance to control")

#: Depth (edges) of the result's region drawn by the live part of a drag: twice the live
#: update's default region (4 rings), so a region that grows once still stays inside it
#: (a vertex moved outside it is drawn correctly too, at the cost of that frame's caches).
REGION_RINGS = 8

#: A drag's frames solve in the mouse handler while they take at most this long (median
#: of the last five, solve and scene update; live updates take 3-10 ms on a 10k-face
#: facade, several times that on a loaded machine); after slower ones (a region that
#: grew to the whole mesh), on the worker thread for the rest of the drag, so the view
#: stays responsive.
INLINE_SECONDS = 0.1

#: Pick radius around a marker, pixels.
PICK_PIXELS = 12

#: Marker colours: still vertices, vertices moved by the soft selection (scaled by weight).
MARKER_COLOR = (0.10, 0.10, 0.12)
SELECTED_COLOR = (1.00, 0.45, 0.00)
WIRE_COLOR = (0.95, 0.55, 0.10)

#: The running session (one at a time).
_active = None


class EditError(ValueError):
    """The selection cannot be edited (one line naming the object and why)."""


def active_session():
    """The running EditSession, or None."""
    return _active


def control_of(obj):
    """``(planarized, control)`` for a Planarized object or the PolyMesh it planarizes.

    Raises EditError when the object has no editable control mesh."""
    if is_planarized(obj):
        planarized = obj
    elif is_polymesh(obj):
        users = [o for o in obj.InList if is_planarized(o) and o.Source is obj]
        if not users:
            raise EditError(f"{obj.Label}: no Planarized object uses it; planarize it first")
        if len(users) > 1:
            raise EditError(f"{obj.Label}: {len(users)} Planarized objects use it; select the "
                            "one to edit")
        planarized = users[0]
    else:
        raise EditError(f"{obj.Label} is not a Planarized object or its control PolyMesh")
    control = planarized.Source
    if control is None:
        raise EditError(f"{planarized.Label}: Source is empty, there is no control mesh")
    if not is_polymesh(control) or is_planarized(control):
        raise EditError(f"{planarized.Label}: its Source {control.Label} is not a PolyMesh; "
                        "convert it with 'To PolyMesh' to edit its vertices")
    return planarized, control


def is_linked(control):
    """Whether ``control`` is rebuilt from another object on recompute (a SurfaceMesh from
    its surface, a PolyMesh from a Mesh or Part object): moved vertices written to it would
    be lost at the next recompute, so Done puts them in a new PolyMesh instead."""
    return getattr(control, "Source", None) is not None


def linked_note(control):
    """What Done does with the moved vertices of a linked control mesh (one line)."""
    from facetwb.translation import translate

    return translate("Facet", "{0} is rebuilt from {1} on recompute: OK puts the moved "
                              "vertices in a new polygon mesh, '{0} edited', which the planar "
                              "result then follows; both are kept as they are").format(
        control.Label, control.Source.Label)


def solver_settings(planarized, mesh):
    """LiveSolver keyword arguments from a Planarized object's properties."""
    return dict(method=planarized.Method, tol=planarized.Tolerance,
                tol_abs=planarized.ToleranceAbs.Value or None,
                max_iter=planarized.MaxIterations or None,
                threads=planarized.Threads or None, **term_options(planarized, mesh))


class EditSession:
    """Interactive editing of one Planarized object's control mesh (see the module doc).

    Parameters
    ----------
    obj : App.DocumentObject
        A Planarized object or its control PolyMesh.
    view : Gui 3D view, optional
        Default: the active view.
    threaded : bool
        Solve on a worker thread (the 3D view stays responsive); False solves in the
        event handlers (tests, benchmarks that time each part).
    """

    def __init__(self, obj, view=None, threaded=True):
        self.planarized, self.control_obj = control_of(obj)
        self.view = view or Gui.ActiveDocument.ActiveView
        self.vobj = self.planarized.ViewObject
        self.threaded = threaded
        mesh = get_mesh(self.control_obj)
        self.mesh = mesh
        try:
            shown = get_mesh(self.planarized)
            start = shown if shown.same_topology(mesh) else None
        except ValueError:
            start = None
        self.live = LiveSolver(mesh, result=start, **solver_settings(self.planarized, mesh))
        self.edge_length = mesh.mean_edge_length()
        self.radius = 2.0 * self.edge_length
        self.panel = None  # the task panel, when start() shows one
        self.falloff = "smooth"
        self.color_by = COLOR_BY[0]
        self.plane = None  # (point, normal) of the current drag
        self.pending = False  # a move arrived while a frame was solving
        self.worker = None
        self.worker_result = None
        self.worker_error = None
        self.closed = False
        self.closing = False  # Done or Cancel: a running settle stops at its next iteration
        self.stats = {"frames": 0, "solve": [], "scene": [], "moves": 0, "planarity": []}
        self.shown_control = None  # the control positions of the result drawn
        self.listeners = []  # callables(session) told after each shown frame
        self._shown = {}  # what each Coin field holds: only changed ranges are set again
        self._legend_key = None
        self._navicube = None  # the navigation cube's state while it is hidden for a drag
        self._rgb = None  # the colour of each panel drawn
        self._highlight = None  # the selection root's highlightMode while a drag turns it off
        self.show_still_control = False  # the whole control mesh during a drag
        self.inline_frames = True  # live updates solved in the event handler (see below)
        self.inline_times = []
        self.reconfigure_pending = False  # parameters changed during a drag
        self._build_scene()
        self._draw_triangles()
        self._previous_mode = self.vobj.DisplayMode
        if "Planarity" in self.vobj.getEnumerationsOfProperty("DisplayMode"):
            self.vobj.DisplayMode = "Planarity"
        self.vobj.Visibility = True
        self._callbacks = [
            (coin.SoMouseButtonEvent.getClassTypeId(), self._on_button),
            (coin.SoLocation2Event.getClassTypeId(), self._on_move),
            (coin.SoKeyboardEvent.getClassTypeId(), self._on_key),
        ]
        for kind, callback in self._callbacks:
            self.view.addEventCallbackPivy(kind, callback)
        self.timer = None
        if threaded:
            from PySide import QtCore

            self.timer = QtCore.QTimer()
            self.timer.setInterval(4)
            self.timer.timeout.connect(self.poll)
            self.timer.start()
        self.show_result(self.live.result)

    # --- scene ----------------------------------------------------------------------------

    def _build_scene(self):
        """The session's nodes, split in what a drag changes and what it does not.

        Coin caches a separator whose contents did not change (an OpenGL display list),
        and redraws it far faster than it traverses and sends it again; a change of a
        coordinate invalidates every cache that uses the coordinate node. So a drag draws
        from two copies of the coordinates: the *still* parts (control edges and points
        away from the moved vertices; the result's panels and edges away from the live
        region, drawn by the Planarized object's own nodes) use coordinates that do not
        change during the drag, and only the *live* parts (around the drag, below
        separators that do not cache) use the coordinates that change every frame."""
        self.root = coin.SoSeparator()
        self.root.renderCaching = coin.SoSeparator.OFF
        unlit = coin.SoLightModel()
        unlit.model = coin.SoLightModel.BASE_COLOR
        wire_material = coin.SoMaterial()
        wire_material.diffuseColor.setValue(*WIRE_COLOR)
        style = coin.SoDrawStyle()
        style.lineWidth = 1.5
        # Points, not an SoMarkerSet: one draw call for all of them (markers are drawn one
        # bitmap at a time: seconds per frame at 10k vertices with software OpenGL).
        point_style = coin.SoDrawStyle()
        point_style.pointSize = 5.0
        edges = np.asarray(self.mesh.edges(), dtype=np.int64).reshape(-1, 2)
        self.edge_list = edges
        # Control mesh, still part: cached.
        still = coin.SoSeparator()
        still.renderCaching = coin.SoSeparator.ON
        self.coords = coin.SoCoordinate3()
        self.wire = coin.SoIndexedLineSet()
        self.markers = coin.SoIndexedPointSet()
        still_marker_material = coin.SoMaterial()
        still_marker_material.diffuseColor.setValue(*MARKER_COLOR)
        for node in (self.coords, unlit, wire_material, style, self.wire,
                     still_marker_material, point_style, self.markers):
            still.addChild(node)
        # Control mesh, live part: the moved vertices, their edges.
        moving = coin.SoSeparator()
        moving.renderCaching = coin.SoSeparator.OFF
        self.live_coords = coin.SoCoordinate3()
        self.live_wire = coin.SoIndexedLineSet()
        binding = coin.SoMaterialBinding()
        binding.value = coin.SoMaterialBinding.PER_VERTEX_INDEXED
        self.marker_material = coin.SoMaterial()
        self.live_markers = coin.SoIndexedPointSet()
        for node in (self.live_coords, unlit, wire_material, style, self.live_wire,
                     binding, self.marker_material, point_style, self.live_markers):
            moving.addChild(node)
        # Result, live part: the panels and edges of the live region (the Planarized
        # object's nodes draw the rest).
        region = coin.SoSeparator()
        region.renderCaching = coin.SoSeparator.OFF
        self.region_coords = coin.SoCoordinate3()
        hints = coin.SoShapeHints()
        hints.vertexOrdering = coin.SoShapeHints.COUNTERCLOCKWISE
        hints.shapeType = coin.SoShapeHints.UNKNOWN_SHAPE_TYPE
        hints.faceType = coin.SoShapeHints.CONVEX  # triangles
        hints.creaseAngle = 0.0
        per_face = coin.SoMaterialBinding()
        per_face.value = coin.SoMaterialBinding.PER_FACE
        self.region_material = coin.SoMaterial()
        self.region_faces = coin.SoIndexedFaceSet()
        region_edges = coin.SoSeparator()
        overall = coin.SoMaterialBinding()
        overall.value = coin.SoMaterialBinding.OVERALL
        self.region_line_material = coin.SoMaterial()
        self.region_line_style = coin.SoDrawStyle()
        self.region_edges = coin.SoIndexedLineSet()
        self.region_edge_switch = coin.SoSwitch()
        for node in (overall, unlit, self.region_line_material, self.region_line_style,
                     self.region_edges):
            region_edges.addChild(node)
        self.region_edge_switch.addChild(region_edges)
        for node in (self.region_coords, hints, coin.SoPolygonOffset(), per_face,
                     self.region_material, self.region_faces, self.region_edge_switch):
            region.addChild(node)
        # During a drag only the control near it is drawn (the live part): the still
        # control wire and points are a third of the redraw with software OpenGL, and
        # away from the drag the result's own edges show the panels.
        self.still_switch = coin.SoSwitch()
        self.still_switch.addChild(still)
        self.still_switch.whichChild = coin.SO_SWITCH_ALL
        for node in (self.still_switch, moving, region):
            self.root.addChild(node)
        self.moving_vertices = None  # the control vertices the current drag moves
        self.region_vertices = None  # the result's vertices drawn by the live part
        self._set_still_control(None)
        self.view.getSceneGraph().addChild(self.root)

    def _set_still_control(self, moving):
        """Control edges and points: all of them in the still part, or (during a drag)
        those away from the ``moving`` vertices (bool mask), the others in the live part
        (with the soft-selection colours)."""
        edges = self.edge_list
        vertices = np.arange(self.mesh.n_vertices)
        self.still_switch.whichChild = coin.SO_SWITCH_ALL if moving is None or \
            self.show_still_control else coin.SO_SWITCH_NONE
        if moving is None:
            still_edges, live_edges = edges, edges[:0]
            still_points, live_points = vertices, vertices[:0]
        else:
            touch = moving[edges[:, 0]] | moving[edges[:, 1]]
            still_edges, live_edges = edges[~touch], edges[touch]
            still_points, live_points = vertices[~moving], vertices[moving]
        _set_field(self.wire.coordIndex, _line_index(still_edges))
        _set_field(self.markers.coordIndex, still_points.tolist())
        _set_field(self.live_wire.coordIndex, _line_index(live_edges))
        _set_field(self.live_markers.coordIndex, live_points.tolist())
        self._shown.pop("control", None)
        self._shown.pop("control_live", None)
        self._set_changed(self.coords.point, self.live.control, "control")
        if moving is not None:
            self._set_changed(self.live_coords.point, self.live.control, "control_live")

    def _set_control_coords(self):
        if self.moving_vertices is not None:
            self._set_changed(self.live_coords.point, self.live.control, "control_live")
        else:
            self._set_changed(self.coords.point, self.live.control, "control")

    def _set_changed(self, field, values, key):
        """Set the rows of ``values`` (n, k) that differ from what ``field`` holds (one
        ``setValues`` of the range from the first to the last changed row; the whole
        field when its size changed or someone else set it). Returns the changed rows
        (None: all)."""
        values = np.asarray(values, dtype=np.float64)
        previous = self._shown.get(key)
        rows = None
        if previous is None or previous.shape != values.shape or \
                field.getNum() != values.shape[0]:
            _set_field(field, values)
        else:
            rows = np.flatnonzero(np.any(values != previous, axis=1))
            if rows.size == 0:
                return rows
            lo, hi = int(rows[0]), int(rows[-1]) + 1
            field.setValues(lo, hi - lo, values[lo:hi].tolist())
        self._shown[key] = values.copy()
        return rows

    def _draw_triangles(self):
        """Draw the result's panels as triangles while editing (facet.live.panel_triangles,
        computed once here): Coin would otherwise re-tessellate every polygon whenever the
        coordinates change (UNKNOWN_FACE_TYPE goes through GLU tessellation)."""
        proxy = self.vobj.Proxy
        faces = getattr(proxy, "faces", None)
        self.tri_face = None
        if faces is None or getattr(proxy, "face_count", 0) != self.mesh.n_faces:
            return
        self.triangles, self.tri_face = panel_triangles(self.mesh,
                                                        self.live.result.mesh.vertices)
        self.proxy_edge_index = list(proxy.edges.coordIndex.getValues()) \
            if hasattr(proxy, "edges") else None
        self._set_region(None)

    def _set_region(self, region):
        """Result panels: all in the Planarized object's nodes, or (during a drag) those
        with a vertex in ``region`` (bool mask over the vertices) in the live part."""
        if self.tri_face is None:
            return
        proxy = self.vobj.Proxy
        tri, tri_face = self.triangles, self.tri_face
        if region is None:
            still = np.ones(tri.shape[0], dtype=bool)
            live_edges = self.edge_list[:0]
        else:
            still = ~np.any(region[tri], axis=1)
            edges = self.edge_list
            live_edges = edges[region[edges[:, 0]] | region[edges[:, 1]]]
        self.still_tri_face, self.live_tri_face = tri_face[still], tri_face[~still]
        _set_field(proxy.faces.coordIndex, _face_index(tri[still]))
        _set_field(self.region_faces.coordIndex, _face_index(tri[~still]))
        if self.proxy_edge_index is not None:
            if region is None:
                _set_field(proxy.edges.coordIndex, self.proxy_edge_index)
            else:
                edges = self.edge_list
                still_edges = edges[~(region[edges[:, 0]] | region[edges[:, 1]])]
                _set_field(proxy.edges.coordIndex, _line_index(still_edges))
        _set_field(self.region_edges.coordIndex, _line_index(live_edges))
        self.region_line_material.diffuseColor.setValue(*self.vobj.LineColor[:3])
        self.region_line_style.lineWidth = max(self.vobj.LineWidth, 0.1)
        self.region_edge_switch.whichChild = proxy.planarity_edges.whichChild.getValue()
        drawn = self._shown.get("result_live")
        for key in ("colors", "colors_live", "result_live"):
            self._shown.pop(key, None)
        if self.region_vertices is not None and drawn is not None:
            # the drag ends: the Planarized object's nodes draw the latest result again
            self._set_changed(proxy.coords.point, drawn, "result")
        self.region_vertices = region
        if region is not None:
            xyz = self._shown.get("result", self.live.result.mesh.vertices)
            self._set_changed(self.region_coords.point, xyz, "result_live")
        if self._rgb is not None:
            self._set_changed(proxy.planarity_material.diffuseColor,
                              self._rgb[self.still_tri_face], "colors")
            self._set_changed(self.region_material.diffuseColor,
                              self._rgb[self.live_tri_face], "colors_live")

    def _color_markers(self, weights):
        n = self.mesh.n_vertices
        if weights is None:
            rgb = np.tile(MARKER_COLOR, (n, 1))
        else:
            w = np.asarray(weights)[:, None]
            rgb = (1.0 - w) * np.asarray(MARKER_COLOR) + w * np.asarray(SELECTED_COLOR)
        _set_field(self.marker_material.diffuseColor, rgb)

    def face_values(self, result):
        """Per-face values of the colour map and the legend title."""
        if self.color_by == "Distance to control":
            distance = np.linalg.norm(result.mesh.vertices - self.live.control, axis=1)
            per_corner = distance[self.mesh.face_vertices]
            return np.maximum.reduceat(per_corner, self.mesh.face_start[:-1]), \
                "Distance to control"
        return np.asarray(result.planarity.max_abs, dtype=np.float64), "Planarity"

    def show_result(self, result):
        """Draw ``result`` in the Planarized object's nodes (coordinates and colours in
        bulk; the document is not touched)."""
        t0 = time.perf_counter()
        proxy = self.vobj.Proxy
        # Only what changed: a live update moves the region around the drag. During a
        # drag the live part draws the region from its own coordinates; the Planarized
        # object's (cached) nodes change only if a vertex outside the region moved.
        xyz = result.mesh.vertices
        region = self.region_vertices
        if region is not None:
            rows = self._set_changed(self.region_coords.point, xyz, "result_live")
            if rows is None or np.any(~region[rows]):
                self._set_changed(proxy.coords.point, xyz, "result")
        else:
            self._set_changed(proxy.coords.point, xyz, "result")
        values, title = self.face_values(result)
        if getattr(proxy, "face_count", 0) == values.size:
            legend_max = self.vobj.LegendMax.Value if hasattr(self.vobj, "LegendMax") else 0.0
            top = float(values.max()) if values.size else 0.0
            # A round top of the scale (1, 2 or 5 times a power of ten): the worst value
            # changes every frame, and a scale that followed it would recolour every
            # panel every frame.
            scale = legend_max if legend_max > 0.0 else _round_up(top)
            rgb = colormap.colors(values, scale)
            self._rgb = rgb
            if self.tri_face is None:
                self._set_changed(proxy.planarity_material.diffuseColor, rgb, "colors")
            else:  # per triangle (PER_FACE binding)
                self._set_changed(proxy.planarity_material.diffuseColor,
                                  rgb[self.still_tri_face], "colors")
                self._set_changed(self.region_material.diffuseColor,
                                  rgb[self.live_tri_face], "colors_live")
            key = (tuple(tick_labels(scale)), tick_labels(top, 2)[-1], title)
            if key != self._legend_key:  # the legend's text nodes are rebuilt: only if new
                proxy.legend.update(scale, actual_max=top, title=title, kind="length")
                self._legend_key = key
        if result is self.live.result:
            self.shown_control = self.live.result_control
        self.stats["scene"].append(time.perf_counter() - t0)
        self.stats["frames"] += 1
        self.stats["planarity"].append(float(result.planarity.max_rel_all))
        for listener in list(self.listeners):
            listener(self)

    # --- picking and dragging -------------------------------------------------------------

    def screen_position(self, vertex):
        """Pixel position (Coin convention, origin bottom left) of a control vertex."""
        x, y = self.view.getPointOnScreen(App.Vector(*self.live.control[vertex]))
        return int(x), int(y)

    def pick(self, position):
        """The control vertex drawn nearest ``position`` (pixels) within PICK_PIXELS, the
        one nearer the viewer when two are as near; or None."""
        size = self.view.getSize()
        x, y = position
        direction = np.array(tuple(self.view.getViewDirection()))
        best, best_key = None, None
        for vertex, point in enumerate(self.live.control):
            sx, sy = self.view.getPointOnScreen(App.Vector(*point))
            if abs(sx - x) > PICK_PIXELS or abs(sy - y) > PICK_PIXELS:
                continue
            if not (0 <= sx < size[0] and 0 <= sy < size[1]):
                continue
            key = (round(float(np.hypot(sx - x, sy - y))), float(np.dot(point, direction)))
            if key[0] <= PICK_PIXELS and (best is None or key < best_key):
                best, best_key = vertex, key
        return best

    def _ray(self, position):
        """A point and a direction of the line of sight through ``position`` (pixels)."""
        point = np.array(tuple(self.view.getPoint(int(position[0]), int(position[1]))))
        camera = self.view.getCameraNode()
        if camera.getTypeId() == coin.SoPerspectiveCamera.getClassTypeId():
            eye = np.array(camera.position.getValue().getValue())
            direction = point - eye
        else:
            direction = np.array(tuple(self.view.getViewDirection()))
        return point, direction / np.linalg.norm(direction)

    def begin_drag(self, vertex):
        """Start dragging ``vertex`` (index) in the view plane through it."""
        weights = self.live.begin_drag(vertex, self.radius, self.falloff)
        normal = np.array(tuple(self.view.getViewDirection()))
        self.plane = (self.live.control[vertex].copy(), normal / np.linalg.norm(normal))
        self._color_markers(weights)
        self.inline_frames, self.inline_times = True, []
        moving = weights > 0.0
        self.moving_vertices = moving
        self._set_still_control(moving)
        self._set_region(_rings(moving, self.edge_list, REGION_RINGS))
        self._hide_navicube(True)

    def _hide_navicube(self, hide):
        """Hide the navigation cube and turn preselection off while the button is held
        (neither can be used during a drag; the cube is a sixth of a redraw with software
        OpenGL, preselection a pick of the whole scene per move); restore them as they
        were."""
        try:
            viewer = self.view.getViewer()
            if hide and self._navicube is None:
                self._navicube = bool(viewer.isEnabledNaviCube())
                if self._navicube:
                    viewer.setEnabledNaviCube(False)
            elif not hide and self._navicube is not None:
                if self._navicube:
                    viewer.setEnabledNaviCube(True)
                self._navicube = None
        except Exception:  # noqa: BLE001 - a view without a cube (or closed)
            self._navicube = None
        # Preselection: FreeCAD's selection root ray-picks the whole scene on every mouse
        # move to highlight what is under the cursor (measured: about 10 ms per move over
        # the 10k-panel facade); nothing can be preselected during a drag.
        try:
            field = self.view.getSceneGraph().getField("highlightMode")
            if field is None:
                return
            if hide and self._highlight is None:
                value = field.get()  # an SbString
                self._highlight = value.getString() if hasattr(value, "getString") \
                    else str(value)
                field.set("OFF")
            elif not hide and self._highlight is not None:
                field.set(self._highlight)
                self._highlight = None
        except Exception:  # noqa: BLE001 - not FreeCAD's selection root (or closed)
            self._highlight = None

    def drag_to_screen(self, position):
        """Move the dragged vertex under ``position`` (pixels), in its view plane."""
        if self.plane is None:
            return
        origin, normal = self.plane
        point, direction = self._ray(position)
        denominator = float(np.dot(direction, normal))
        if abs(denominator) < 1e-12:
            return
        target = point + direction * float(np.dot(origin - point, normal)) / denominator
        self.move_to(target)

    def move_to(self, target):
        """Move the dragged vertex to ``target`` (model coordinates) and ask for a frame."""
        self.live.drag_to(target)
        self.stats["moves"] += 1
        self._set_control_coords()
        self.request_frame()

    def end_drag(self):
        """Release: end the drag. The frames are planar to the tolerance already (live
        updates); only when the last one fell short is the whole mesh re-solved."""
        if self.plane is None:
            return
        self.plane = None
        self.live.end_drag()
        self._color_markers(None)
        self.moving_vertices = None
        self._set_still_control(None)
        self._set_region(None)
        self._hide_navicube(False)
        if self.reconfigure_pending:
            self.reconfigure()  # parameters changed during the drag
        elif not self.live.settled:
            self.request_settle()

    @property
    def current(self):
        """True when the result drawn is the solution of the control positions drawn."""
        return self.shown_control is not None and \
            np.array_equal(self.shown_control, self.live.control)

    # --- solving ----------------------------------------------------------------------------

    @property
    def busy(self):
        """True while a solve runs on the worker thread."""
        return self.worker is not None

    def request_frame(self):
        if self.busy:
            self.pending = True  # merged: the next frame takes the latest positions
            return
        if self.threaded and self.inline_frames and self.live.live_updates:
            # A live update takes a few milliseconds: solved here, drawn in the same
            # redraw as the control that moved (every frame shows the result of the
            # control drawn); a worker thread would compete with the software
            # rasterizer for the same cores and draw results a move late.
            t0 = time.perf_counter()
            try:
                self._start(self.live.frame, inline=True)
            except Exception as exc:  # noqa: BLE001 - one line, as from the worker
                App.Console.PrintError(f"Facet: edit of {self.planarized.Label}: {exc}\n")
                return
            self.inline_times.append(time.perf_counter() - t0)
            recent = self.inline_times[-5:]
            if len(recent) == 5 and sorted(recent)[2] > INLINE_SECONDS:
                self.inline_frames = False  # slow frames: the worker, for this drag
            return
        self._start(self.live.frame)

    def request_settle(self):
        if self.busy:
            self.pending = True
            return
        self._start(lambda: self.live.settle(progress=lambda *_args: self.closing))

    def _start(self, solve, inline=False):
        self.pending = False
        if not self.threaded or inline:
            t0 = time.perf_counter()
            result = solve()
            self.stats["solve"].append(time.perf_counter() - t0)
            self.show_result(result)
            return

        def run():
            t0 = time.perf_counter()
            try:
                self.worker_result = solve()
            except Exception as exc:  # noqa: BLE001 - reported in the main thread
                self.worker_error = exc
            self.stats["solve"].append(time.perf_counter() - t0)

        self.worker = threading.Thread(target=run, name="facet-live", daemon=True)
        self.worker.start()

    def poll(self):
        """Show a finished solve and start the next one (the Qt timer calls this)."""
        if self.worker is None or self.worker.is_alive():
            return
        self.worker.join()
        self.worker = None
        result, error = self.worker_result, self.worker_error
        self.worker_result = self.worker_error = None
        if isinstance(error, Cancelled):
            error = None
        if error is not None:
            App.Console.PrintError(f"Facet: edit of {self.planarized.Label}: {error}\n")
        elif result is not None and not (self.closed or self.closing):
            # a closing session draws nothing more and tells its panel nothing: Done
            # writes the control mesh, and the panel's widgets may be deleted already
            self.show_result(result)
        if self.closed or self.closing:
            self.pending = False
            return
        if self.pending or (self.live.dragging and not self.live.converged):
            self.request_frame()  # the hand moved on, or the frame is short of the tolerance
        elif not self.live.dragging and not self.live.settled:
            self.request_settle()

    def wait(self, timeout=60.0):
        """Process solves until none runs and none is pending (tests, benchmarks)."""
        end = time.monotonic() + timeout
        while (self.busy or self.pending) and time.monotonic() < end:
            if self.worker is not None:
                self.worker.join(0.002)
            self.poll()
        return not (self.busy or self.pending)

    # --- events -----------------------------------------------------------------------------

    def _on_button(self, node):
        event = node.getEvent()
        if event.getButton() != coin.SoMouseButtonEvent.BUTTON1:
            return
        position = tuple(event.getPosition().getValue())
        if event.getState() == coin.SoButtonEvent.DOWN:
            vertex = self.pick(position)
            if vertex is not None:
                self.begin_drag(vertex)
                node.setHandled()
        elif event.getState() == coin.SoButtonEvent.UP and self.plane is not None:
            self.drag_to_screen(position)
            self.end_drag()
            node.setHandled()

    def _on_move(self, node):
        if self.plane is None:
            return
        self.drag_to_screen(tuple(node.getEvent().getPosition().getValue()))
        node.setHandled()

    def _on_key(self, node):
        event = node.getEvent()
        if event.getKey() == coin.SoKeyboardEvent.ESCAPE and \
                event.getState() == coin.SoButtonEvent.DOWN:
            node.setHandled()
            # Leave the event handler before the view's callbacks are removed.
            from PySide import QtCore

            QtCore.QTimer.singleShot(0, finish)

    def reconfigure(self):
        """Re-read the Planarized object's parameters and re-solve the edited control mesh
        with them (live parameters during an edit). During a drag it waits for the
        release (the drag's solver keeps the picked vertex and its weights)."""
        if self.plane is not None:
            self.reconfigure_pending = True
            return
        self.reconfigure_pending = False
        self.wait()
        original = self.live.original
        control = self.live.control.copy()
        self.live = LiveSolver(self.mesh.with_vertices(control), result=self.live.result,
                               **solver_settings(self.planarized, self.mesh))
        self.live.original = original
        self.live.settled = False
        self.request_settle()

    # --- ending -----------------------------------------------------------------------------

    def done(self):
        """Write the moved control vertices to the control PolyMesh (one undoable
        transaction) and recompute. Returns True if something was written."""
        self.closing = True  # the recompute solves the written mesh anyway
        self.wait()
        moved = self.live.moved
        self.close()
        if not moved:
            self._parameters_back()
            return False
        doc = self.control_obj.Document
        doc.openTransaction("Edit control mesh")
        try:
            if is_linked(self.control_obj):
                # a control mesh rebuilt from a surface, Mesh or Part would drop the moved
                # vertices at the next recompute: they go into a PolyMesh of their own,
                # which the planar result follows from now on
                from facetwb.make.make_polymesh import make_polymesh

                edited = make_polymesh(self.mesh.with_vertices(self.live.control),
                                       label=f"{self.control_obj.Label} edited", doc=doc)
                self.planarized.Source = edited
                edited.ViewObject.Visibility = False
            else:
                from facetwb.objects.polymesh import set_points

                set_points(self.control_obj, self.live.control)
            doc.recompute()
        except Exception:
            doc.abortTransaction()
            raise
        doc.commitTransaction()
        return True

    def cancel(self):
        """Leave the control mesh as it was and show the stored result again."""
        self.closing = True
        self.wait()
        self.close()
        self._parameters_back()

    def _parameters_back(self):
        """A parameter changed during the session (the session solved it live): the
        stored result has to be solved with it too (it kept the old one, Touched)."""
        from facetwb import live_parameters

        live_parameters.resolve_if_touched(self.planarized)

    def _restore_view(self):
        """Draw the stored result again, as polygons (the session drew triangles)."""
        proxy = self.vobj.Proxy
        if hasattr(proxy, "redraw_mesh"):
            proxy.drawn_topology = None
            proxy.redraw_mesh(self.planarized)

    def close(self):
        """Remove the session's nodes, callbacks and timer (idempotent)."""
        global _active
        if self.closed:
            return
        self.closed = True
        if self.timer is not None:
            self.timer.stop()
        self._hide_navicube(False)
        try:
            self._restore_view()
        except Exception as exc:  # noqa: BLE001 - the object may be deleted already
            App.Console.PrintWarning(f"Facet: edit: redrawing the result failed: {exc}\n")
        for kind, callback in self._callbacks:
            try:
                self.view.removeEventCallbackPivy(kind, callback)
            except Exception:  # noqa: BLE001 - the view may be closed already
                pass
        try:
            self.view.getSceneGraph().removeChild(self.root)
        except Exception:  # noqa: BLE001
            pass
        try:
            self.vobj.DisplayMode = self._previous_mode
        except Exception:  # noqa: BLE001
            pass
        if _active is self:
            _active = None


class EditPanel:
    """Task panel of an edit: soft-selection radius and falloff, colours, status."""

    def __init__(self, session):
        from PySide import QtGui

        self.session = session
        self.form = QtGui.QWidget()
        from facetwb.translation import translate

        self.form.setWindowTitle(translate("Facet", "Edit control mesh"))
        layout = QtGui.QFormLayout(self.form)
        help_text = QtGui.QLabel(translate(
            "Facet", "Drag a control vertex (dot) with the left mouse button; the planar "
            "result follows. OK (or Esc) keeps the edit, Cancel drops it."))
        help_text.setWordWrap(True)
        layout.addRow(help_text)
        if is_linked(session.control_obj):
            self.linked = QtGui.QLabel(linked_note(session.control_obj))
            self.linked.setWordWrap(True)
            layout.addRow(self.linked)
        # a length in the user's units, as in the other panels (it always said "mm")
        self.radius = Gui.UiLoader().createWidget("Gui::QuantitySpinBox")
        self.radius.setProperty("unit", "mm")
        self.radius.setProperty("minimum", 0.0)
        # as the .ui forms' length boxes: without a maximum the box asked for room for
        # DBL_MAX (177 px) and pushed the panel past the task pane, the text cut off
        self.radius.setProperty("maximum", 1e9)
        self.radius.setProperty("rawValue", float(session.radius))
        self.radius.setToolTip(translate(
            "Facet", "Vertices closer than this to the dragged one move with it (0: the "
            "dragged vertex alone)"))
        self.radius.valueChanged.connect(self._radius)
        layout.addRow(translate("Facet", "Radius"), self.radius)
        self.falloff = QtGui.QComboBox()
        self.falloff.addItems(list(FALLOFFS))
        self.falloff.setToolTip(translate(
            "Facet", "How much the neighbours move: smooth, linear with the distance, or all "
            "of them as much as the dragged vertex"))
        self.falloff.currentIndexChanged.connect(self._falloff)
        layout.addRow(translate("Facet", "Falloff"), self.falloff)
        self.color_by = QtGui.QComboBox()
        self.color_by.addItems(list(COLOR_BY))
        self.color_by.setToolTip(translate(
            "Facet", "Colour the result by the planarity of each panel or by how far its "
            "corners are from the control mesh"))
        self.color_by.currentIndexChanged.connect(self._color_by)
        layout.addRow(translate("Facet", "Colour by"), self.color_by)
        self.status = QtGui.QLabel("")
        self.status.setWordWrap(True)
        layout.addRow(self.status)
        session.listeners.append(self._update_status)
        self._update_status(session)

    def _radius(self, _value=None):
        self.session.radius = float(self.radius.property("rawValue"))

    def _falloff(self, index):
        self.session.falloff = FALLOFFS[index]

    def _color_by(self, index):
        self.session.color_by = COLOR_BY[index]
        self.session.show_result(self.session.live.result)

    def _update_status(self, session):
        result = session.live.result
        state = "solved" if result.converged else "solving..."
        self.status.setText(f"{state} planarity {result.planarity.max_rel_all:.2g} of the "
                            f"edge length, {result.iterations} iterations")

    def getStandardButtons(self):
        from facetwb.taskpanels import forms

        return forms.ok_cancel_buttons()

    def accept(self):
        finish(True)
        return True

    def reject(self):
        finish(False)
        return True


def start(obj, view=None, threaded=True, panel=True):
    """Start editing ``obj`` (a Planarized object or its control PolyMesh). Returns the
    session; raises EditError (one line) when it cannot be edited."""
    global _active
    if _active is not None:
        finish(False)
    session = EditSession(obj, view=view, threaded=threaded)
    _active = session
    if panel and App.GuiUp:
        if Gui.Control.activeDialog():
            Gui.Control.closeDialog()
        session.panel = EditPanel(session)
        Gui.Control.showDialog(session.panel)
    return session


def finish(keep=True):
    """End the running edit: keep (Done) writes the control mesh, else Cancel."""
    global _active
    session = _active
    if session is None:
        return False
    _active = None  # closing the task dialog may call back into finish()
    if Gui.Control.activeDialog():
        Gui.Control.closeDialog()
    try:
        return session.done() if keep else (session.cancel() or False)
    except Exception as exc:  # noqa: BLE001 - one line in the report view
        App.Console.PrintError(f"Facet: edit of {session.planarized.Label} failed: {exc}\n")
        return False


def _round_up(value):
    """The smallest of 1, 2, 5 times a power of ten that is >= ``value`` (0 for 0)."""
    if not value > 0.0 or not np.isfinite(value):
        return 0.0
    power = 10.0 ** np.floor(np.log10(value))
    for step in (1.0, 2.0, 5.0, 10.0):
        if step * power >= value:
            return float(step * power)
    return float(10.0 * power)


def _rings(mask, edges, rings):
    """``mask`` (bool over the vertices) grown by ``rings`` edges."""
    grown = mask.copy()
    for _ in range(rings):
        touch = grown[edges[:, 0]] | grown[edges[:, 1]]
        grown[edges[touch, 0]] = True
        grown[edges[touch, 1]] = True
    return grown


def _line_index(edges):
    """coordIndex of an SoIndexedLineSet of (k, 2) edges."""
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    return np.hstack([edges, np.full((edges.shape[0], 1), -1, dtype=np.int64)]).ravel().tolist()


def _face_index(triangles):
    """coordIndex of an SoIndexedFaceSet of (k, 3) triangles."""
    tri = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    return np.hstack([tri, np.full((tri.shape[0], 1), -1, dtype=np.int64)]).ravel().tolist()


def _set_field(field, values):
    """Set a Coin multiple-value field from an (n, k) array or a list, in bulk."""
    if isinstance(values, np.ndarray):
        values = values.tolist()
    field.setNum(len(values))
    if values:
        field.setValues(0, len(values), values)


__all__ = ["COLOR_BY", "EditError", "EditPanel", "EditSession", "active_session", "control_of",
           "finish", "start"]
