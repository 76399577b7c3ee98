# SPDX-License-Identifier: LGPL-2.1-or-later
"""PlanGraph: a plan drawing as a planar graph with faces (the panels seen from above).

Parametric on its drawing: ``Sources`` (Sketches, Draft wires and lines, Part edges) or, when
that is empty, ``File`` (.dxf, .csv of segments, or a plan mesh .obj .off .json). Recompute
reads the drawing again and builds the graph with ``facet.plan``: endpoints snapped, crossings
split, duplicate edges merged, dangling edges dropped (counted in ``DanglingEdges``), faces
found by polygonize, faces containing an ``Openings`` point left out; a DXF's layers that are off
or frozen are not read (listed in ``Warnings``), and a DXF drawn in another unit ($INSUNITS:
metres, inches...) is scaled to millimetres (said in ``Warnings``), unless ``FileUnits``
names the file's unit (any file: a DXF whose $INSUNITS is wrong, a table or mesh in
metres). A document saved before ``FileUnits`` keeps its plan as it was read then:
``FileUnits`` "mm". The graph is stored as a flat polygon mesh (z = 0), like a PolyMesh, so
a Lifting (or anything taking a Facet mesh) can use it.
"""

import FreeCAD as App

import facet
from facet.cutsheets import LENGTH_UNITS
from facetwb import compat, progress
from facetwb.recompute import guarded
from facetwb.translation import translate
from facetwb.objects.polymesh import PolyMesh, set_mesh, set_planarity

TYPE_PLANGRAPH = "Facet::PlanGraph"

#: FileUnits' choices: the file's own ($INSUNITS of a DXF; tables and meshes are in mm),
#: or a length unit.
FROM_FILE = "From file"
FILE_UNITS = [FROM_FILE] + list(LENGTH_UNITS)


class PlanGraph(PolyMesh):
    """Proxy of a plan graph (App::FeaturePython)."""

    TYPE = TYPE_PLANGRAPH

    def init_source_properties(self, obj):
        compat.add_property(
            obj, "App::PropertyLinkList", "Sources", "Plan",
            "The drawing: Sketches, Draft wires and lines, Part objects with straight edges in "
            "a horizontal plane (never modified)")
        compat.add_property(
            obj, "App::PropertyFile", "File", "Plan",
            "A drawing file used when Sources is empty: .dxf (LINE, LWPOLYLINE, POLYLINE), "
            ".csv (x1,y1,x2,y2 per line) or a plan mesh (.obj, .off, .json)")
        if compat.add_property(
                obj, "App::PropertyEnumeration", "FileUnits", "Plan",
                "The unit File is drawn in: From file (a DXF's $INSUNITS; a table or mesh in "
                "mm), or a unit to read it in whatever the file says"):
            obj.FileUnits = FILE_UNITS
            obj.FileUnits = FROM_FILE
        compat.add_property(
            obj, "App::PropertyLength", "Snap", "Plan",
            "Endpoints closer than this are merged (0: 1e-6 of the drawing's size)")
        compat.add_property(
            obj, "App::PropertyLength", "ArcTolerance", "Plan",
            "Curves are split into straight segments this close to them (0: curves are "
            "refused)")
        compat.add_property(
            obj, "App::PropertyVectorList", "Openings", "Plan",
            "Points inside faces that are openings (no panel); only x and y count")
        read_only = compat.EDITOR_READ_ONLY
        output = compat.PROP_OUTPUT
        compat.add_property(obj, "App::PropertyInteger", "DanglingEdges", "Result",
                            "Edges dropped because they bound no face", attr=output,
                            editor_mode=read_only)
        compat.add_property(obj, "App::PropertyInteger", "OpeningCount", "Result",
                            "Faces left out as openings", attr=output, editor_mode=read_only)
        compat.add_property(obj, "App::PropertyInteger", "SnappedEndpoints", "Result",
                            "Endpoints moved by snapping", attr=output, editor_mode=read_only)
        compat.add_property(obj, "App::PropertyStringList", "Warnings", "Result",
                            "What reading the drawing left out (layers that are off or "
                            "frozen) or found worth telling", attr=output,
                            editor_mode=read_only)

    def onDocumentRestored(self, obj):
        legacy = "FileUnits" not in obj.PropertiesList
        super().onDocumentRestored(obj)
        if legacy:  # (read as drawn then: the design built on it keeps its size)
            obj.FileUnits = "mm"

    @guarded
    def execute(self, obj):
        from facet.plan import plan_from_segments, read_plan

        openings = [(p.x, p.y) for p in obj.Openings]
        snap = obj.Snap.Value or None
        arc = obj.ArcTolerance.Value or None
        if obj.Sources:
            from facetwb.plan_source import segments_from_objects

            segments = segments_from_objects(obj.Sources, arc or 0.0)
            plan = plan_from_segments(segments, snap=snap, openings=openings, source=obj.Label,
                                      progress=progress.hook(), units="mm",
                                      option_names=option_names())
        elif obj.File:
            # (a DXF drawn in metres or inches: in millimetres, as the document is)
            units = None if obj.FileUnits == FROM_FILE else LENGTH_UNITS[obj.FileUnits][0]
            # (progress and Cancel: a 40,000-face plan takes seconds)
            plan = read_plan(obj.File, snap=snap, arc_tolerance=arc, openings=openings,
                             to_mm=True, units_mm=units, progress=progress.hook(), units="mm",
                             option_names=option_names())
        else:
            raise ValueError(f"{obj.Label}: no drawing: set Sources or File")
        warnings = list(plan.warnings)
        if not obj.Sources:
            warnings += _size_warnings(plan.mesh)
        set_mesh(obj, plan.mesh)
        set_planarity(obj, facet.planarity(plan.mesh))
        obj.DanglingEdges = len(plan.dangling)
        obj.OpeningCount = int(plan.openings)
        obj.SnappedEndpoints = int(plan.snapped)
        if list(obj.Warnings) != warnings:
            obj.Warnings = warnings
        for text in warnings:
            App.Console.PrintWarning(f"{obj.Label}: {text}\n")


def option_names():
    """How the plan's messages name the options they advise (facet.plan.OPTION_NAMES): the
    PlanGraph's properties."""
    return {"snap": translate("Facet", "the PlanGraph's Snap"),
            "arc_tolerance": translate("Facet", "the PlanGraph's ArcTolerance")}


def _size_warnings(mesh):
    """[the warning] when a plan read from a file has edges no roof has (a table in metres
    read as millimetres: a 9 x 6 m canopy 9 x 6 mm), saying to set File Units; []
    otherwise."""
    from facet.cutsheets import implausible_edge_mm

    edge = implausible_edge_mm(mesh.mean_edge_length())
    if edge is None:
        return []
    return [f"its edges are {edge:.3g} mm long on average, which no roof's are: set File "
            "Units to the unit the file is drawn in (m, cm, in or ft)"]


def is_plan_graph(obj):
    """True if ``obj`` is a Facet PlanGraph."""
    return getattr(getattr(obj, "Proxy", None), "Type", None) == TYPE_PLANGRAPH
