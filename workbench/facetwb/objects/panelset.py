# SPDX-License-Identifier: LGPL-2.1-or-later
"""PanelSet and CutSheets: panel solids and nested cut sheets as parametric objects.

PanelSet (``Part::FeaturePython``) links a planar mesh (a PolyMesh or Planarized object) in
``Source`` and, on recompute, runs ``facet.panels`` with its properties; its ``Shape`` is one
compound of OCC solids, one per panel, in the order of ``PartIds`` (solid k is panel
``PartIds[k]``). Each solid is checked with BRepCheck (``isValid``) before it is stored.
A recompute after changes to :data:`NO_GEOMETRY` alone (Density, OnePerPanel, the part IDs)
keeps the solids: only masses, IDs and the per-panel objects change.
With ``OnePerPanel`` it also keeps one plain ``Part::Feature`` per panel (labelled by its part
ID, listed in ``PanelObjects``, shown under it in the tree) and hides its own compound.

CutSheets (``Part::FeaturePython``) links a PanelSet, nests its flat parts on stock sheets
(``facet.nest``) and, when ``OutputDir`` is set, writes the DXF, STEP, schedule and previews
there. Its ``Shape`` is the sheet layout (sheet borders and cut outlines, flat, side by side).
It reuses the panels and solids its PanelSet computed in this session (recomputing them
only when the PanelSet has none, e.g. right after the document was opened). It keeps its
nesting while the parts' outlines and its sheet are the same: when its PanelSet recomputed
for its masses (Density), OnePerPanel or the part IDs (IdPrefix, IdScheme: the same
outlines under other names), or when only its :data:`FILE_INPUTS` changed (OutputDir,
WriteStep, TextOutlines); it then writes only the files that changed (the IDs: all of
them; Density: the schedules; TextOutlines: the DXF; WriteStep on: the STEP file; a new
OutputDir: all of them there) and those no longer there. WriteStep off removes the
panels.step it wrote.

The source is never modified. The numerics are in ``facet``; this module is wiring.
"""

import FreeCAD as App
import numpy as np

import facet.errors
from facet.nest import DEFAULT_MARGIN_MM, DEFAULT_SPACING_MM
from facet.panels import DEFAULT_GAP_MM
from facet.part_types import DEFAULT_TOL_MM
from facetwb import compat, progress
from facetwb.recompute import guarded, observe_documents
from facetwb.translation import QT_TRANSLATE_NOOP, translate
from facetwb.units import length_text

TYPE_PANELSET = "Facet::PanelSet"
TYPE_CUTSHEETS = "Facet::CutSheets"

OFFSETS = ["outer", "inner", "center"]
EDGE_MODES = ["square", "bisector"]
ID_SCHEMES = ["auto", "grid", "index"]
ROTATIONS = ["90", "none", "free"]
#: The PanelSet's inputs that change no solid: a recompute after changes to these alone
#: keeps its Shape (masses, part IDs and the per-panel objects only).
NO_GEOMETRY = frozenset({"Density", "OnePerPanel", "IdScheme", "IdPrefix",
                         "PartTypeTolerance"})
#: Properties that change nothing a recompute makes (hidden or shown in the tree, renamed):
#: not counted as changes at all (after one, a Density change rebuilt every solid).
NOT_INPUTS = frozenset({"Visibility", "Label", "Label2"})
#: The CutSheets' inputs that change which files are written, where and how, not the
#: nesting: a recompute after changes to these alone keeps it.
FILE_INPUTS = frozenset({"OutputDir", "WriteStep", "TextOutlines"})
#: The kinds of files a CutSheets writes (run_pipeline's), in the order of its Files.
FILE_KINDS = ("dxf", "schedule", "svg", "step")


class _Proxy:
    TYPE = ""

    def __init__(self, obj):
        self.Type = self.TYPE
        obj.Proxy = self
        self.init_properties(obj)
        observe_documents()  # (a FreeCAD Mesh in Source replaced: marked for recompute)

    def onDocumentRestored(self, obj):
        self.init_properties(obj)
        observe_documents()
        from facetwb.viewproviders import attach

        attach.schedule(obj)  # a document saved without the GUI has no view provider

    def onChanged(self, obj, prop):  # noqa: N802 - FreeCAD's name
        """Note what changed since the last recompute (``_changed``, emptied by a whole
        one): what it may keep depends on it."""
        if prop in NOT_INPUTS:
            return
        changed = getattr(self, "_changed", None)
        if changed is None:
            changed = self._changed = set()
        changed.add(prop)

    def dumps(self):
        return {"Type": self.Type}

    def loads(self, state):
        self.Type = self.TYPE
        if isinstance(state, dict):
            self.Type = state.get("Type", self.TYPE)

    def __getstate__(self):
        return self.dumps()

    def __setstate__(self, state):
        self.loads(state)


def _enum(obj, name, group, doc, values, default):
    if compat.add_property(obj, "App::PropertyEnumeration", name, group, doc):
        setattr(obj, name, values)
        setattr(obj, name, default)


def _output(obj, type_name, name, doc, group="Result"):
    compat.add_property(obj, type_name, name, group, doc, attr=compat.PROP_OUTPUT,
                        editor_mode=compat.EDITOR_READ_ONLY)


class PanelSet(_Proxy):
    """Proxy of a set of panel solids made from a planar mesh."""

    TYPE = TYPE_PANELSET

    def onDocumentRestored(self, obj):
        """A PanelSet saved by a Facet without part types (before PartTypes): it must
        recompute (:meth:`mustExecute`), which finds them, and the report view says so.
        It read 0 part types of its panels, up to date, and a Recompute did nothing."""
        older = "PartTypes" not in obj.PropertiesList
        super().onDocumentRestored(obj)
        self._no_part_types = older and obj.PanelCount > 0
        if self._no_part_types:
            App.Console.PrintWarning(translate(
                "Facet", "{0}: saved by an earlier Facet, without the part types of its "
                         "{1} panels: the next recompute finds them").format(
                obj.Label, obj.PanelCount) + "\n")

    def mustExecute(self, obj):  # noqa: N802 - FreeCAD's name
        """Whether the PanelSet must recompute although none of its inputs changed: saved
        without part types (:meth:`onDocumentRestored`)."""
        return bool(getattr(self, "_no_part_types", False))

    def init_properties(self, obj):
        add = compat.add_property
        add(obj, "App::PropertyLink", "Source", "Base",
            "The planar mesh (PolyMesh or Planarized object); never modified")
        add(obj, "App::PropertyLength", "Thickness", "Panels", "Panel thickness", value=40.0)
        _enum(obj, "Offset", "Panels", "Panel on the outer (+normal) side of the surface, "
              "the inner side, or centred on it", OFFSETS, "outer")
        # (a document keeps the Gap it was saved with: add_property adds what it lacks)
        add(obj, "App::PropertyLength", "Gap", "Panels",
            "Joint width between neighbouring panels (0: the panels' edges on the mesh's; "
            "square cuts then overlap on every valley)", value=DEFAULT_GAP_MM)
        _enum(obj, "EdgeMode", "Panels", "Edge cuts square to the panel, or mitred on the "
              "bisector of the two panels' planes", EDGE_MODES, "square")
        add(obj, "App::PropertyBool", "Flip", "Panels", "Swap the outer and inner sides")
        add(obj, "App::PropertyFloat", "Tolerance", "Panels",
            "Planarity accepted, relative to each face's mean edge length", value=1e-6)
        add(obj, "App::PropertyLength", "ToleranceAbs", "Panels",
            "Planarity accepted, in model units (the larger tolerance applies)")
        add(obj, "App::PropertyFloat", "MinEdge", "Panels",
            "An edge shorter than this fraction of a face's mean edge vanishes: its ends "
            "become one corner, so a quad whose edge vanished is a triangle panel (0: keep "
            "every edge)", value=0.01)
        add(obj, "App::PropertyLength", "MinEdgeAbs", "Panels",
            "The same in model units (the larger one applies)")
        _enum(obj, "IdScheme", "Part IDs", "auto: grid row and column when the mesh is a "
              "regular quad grid, else the face index", ID_SCHEMES, "auto")
        add(obj, "App::PropertyString", "IdPrefix", "Part IDs", "Prefix of every part ID",
            value="P-")
        add(obj, "App::PropertyBool", "OnePerPanel", "Part IDs",
            "Also one Part object per panel, labelled by its part ID (else one compound)")
        add(obj, "App::PropertyLength", "PartTypeTolerance", "Part IDs",
            "Panels whose corners all lie within this of another's, turned and moved, are "
            "one part type (PartTypes)", value=DEFAULT_TOL_MM)
        add(obj, "App::PropertyFloat", "Density", "Panels",
            "The panels' material in kg/m³ (glass 2500, aluminium 2700, steel 7850): each "
            "panel's mass in Masses and the cut sheets' schedule (0: none)")
        _output(obj, "App::PropertyLinkList", "PanelObjects",
                "The per-panel objects (with OnePerPanel), in the order of PartIds")
        _output(obj, "App::PropertyStringList", "PartIds", "Part ID of each solid, in order")
        _output(obj, "App::PropertyStringList", "PartTypes",
                "Part type of each panel, in the order of PartIds: T1 the type with the most "
                "panels, then T2, ... (the cut sheets' schedule has them too)")
        _output(obj, "App::PropertyInteger", "PartTypeCount",
                "Number of different parts: panels within PartTypeTolerance of each other "
                "are one")
        _output(obj, "App::PropertyInteger", "PanelCount", "Number of panels")
        _output(obj, "App::PropertyFloatList", "Volumes", "Volume of each solid")
        _output(obj, "App::PropertyFloatList", "Areas", "Bottom face area of each panel")
        _output(obj, "App::PropertyFloatList", "Masses",
                "Mass of each panel in kg, from Volumes and Density (empty without one)")
        _output(obj, "App::PropertyFloat", "TotalMass",
                "Mass of all the panels in kg (0 without a Density)")
        _output(obj, "App::PropertyAngle", "MaxNodeDeviation",
                "Largest angle by which a node's edge planes miss a common axis")
        _output(obj, "App::PropertyIntegerList", "Corners",
                "Corners of each panel, in the order of PartIds (a quad whose edge vanished "
                "has 3)")
        _output(obj, "App::PropertyStringList", "VanishedEdgePanels",
                "Part IDs of the panels built with fewer corners than their faces, because an "
                "edge shorter than MinEdge vanished")
        _output(obj, "App::PropertyDistance", "NarrowestJoint",
                "The narrowest joint between two neighbouring panels, across its section "
                "(negative: how deep they overlap)")
        _output(obj, "App::PropertyStringList", "NarrowestJointPanels",
                "The part IDs of the two panels at the narrowest joint")
        _output(obj, "App::PropertyInteger", "OverlappingJoints",
                "Joints whose panels overlap: cut square on the inner side of a fold with too "
                "small a Gap (mitred joints never do)")
        _output(obj, "App::PropertyLength", "ClearingGap",
                "The least Gap at which no panel would overlap another, across a joint or at "
                "a node (0 when none does)")
        _output(obj, "App::PropertyInteger", "NodeClashes",
                "Pairs of panels that meet at a node but not across a joint and overlap there")
        _output(obj, "App::PropertyLength", "DeepestNodeClash",
                "How deep the deepest of them overlap (0 when none do)")
        _output(obj, "App::PropertyStringList", "NodeClashPanels",
                "The part IDs of the deepest pair")
        _output(obj, "App::PropertyStringList", "ClashingPanels",
                "Part IDs of the panels that overlap another, across a joint or at a node "
                "(shown in red while the view's ShowClashes is on)")
        _output(obj, "App::PropertyStringList", "Warnings", "What was found worth telling")

    def panel_set(self, obj, mesh=None):
        """The facet.panels.PanelSet for the current properties (computed afresh), of
        ``mesh`` (the Source's, read here when not given)."""
        from facet.panels import panels

        if mesh is None:
            mesh = self._source_mesh(obj)
        try:
            return panels(mesh, obj.Thickness.Value, offset=obj.Offset, gap=obj.Gap.Value,
                          edge=obj.EdgeMode, flip=bool(obj.Flip), ids=obj.IdScheme,
                          prefix=obj.IdPrefix, tol=obj.Tolerance,
                          tol_abs=obj.ToleranceAbs.Value, min_edge=obj.MinEdge,
                          min_edge_abs=obj.MinEdgeAbs.Value, progress=progress.hook(),
                          units="mm", option_names=option_names())
        except facet.errors.InputError as error:
            size = _size_warning(mesh.mean_edge_length()) if "gap" in str(error) else None
            if size:
                # a mesh in metres read as millimetres: the Gap (6 mm by default) consumes
                # its 1.5 mm panels, and the error named a face and a gap, not the units
                raise ValueError(f"{error}; {size}") from None
            # "planarize first" of a source that was planarized, but stopped short
            src = obj.Source
            from facetwb.objects.planarized import STOP_REASONS, is_planarized

            if ("not planar" in str(error) and is_planarized(src)
                    and not getattr(src, "Converged", True)):
                raise ValueError(translate(
                    "Facet", "{0}; {1} stopped before its tolerance ({2}): raise its Max. "
                             "iterations, or set it to 0 for the solver to decide").format(
                    error, src.Label, STOP_REASONS.get(src.StopReason, src.StopReason))) from None
            raise

    @staticmethod
    def _source_mesh(obj):
        from facetwb import conversion

        if obj.Source is None:
            raise ValueError(f"{obj.Label}: Source is empty, no mesh to make panels of")
        return conversion.mesh_from_object(obj.Source)

    def _geometry_key(self, obj):
        """What the panels' solids depend on, besides the Source's mesh: not the part IDs
        (IdScheme, IdPrefix), Density, OnePerPanel or the view."""
        src = obj.Source
        return (src.Name if src is not None else None, obj.Thickness.Value, obj.Offset,
                obj.Gap.Value, obj.EdgeMode, bool(obj.Flip), obj.Tolerance,
                obj.ToleranceAbs.Value, obj.MinEdge, obj.MinEdgeAbs.Value)

    def _key(self, obj):
        """What the computed panels depend on, besides the Source's geometry."""
        return self._geometry_key(obj) + (obj.IdScheme, obj.IdPrefix)

    def _same_solids(self, obj, cache, mesh):
        """Whether the Shape's solids, built at the last recompute (``cache``), are still
        those of the current properties and ``mesh``: only properties that make no
        geometry (:data:`NO_GEOMETRY`) changed since, and at least one (a recompute marked
        by hand builds them again)."""
        changed = getattr(self, "_changed", None) or set()
        if (cache is None or not changed or not changed <= NO_GEOMETRY
                or cache[0][:-2] != self._geometry_key(obj)):
            return False
        ps, built = cache[1], cache[2]
        return (len(obj.Shape.Solids) == len(ps.panels)
                and np.array_equal(built.vertices, mesh.vertices)
                and np.array_equal(built.face_start, mesh.face_start)
                and np.array_equal(built.face_vertices, mesh.face_vertices))

    def record(self):
        """What the last recompute left (a new object at each; None before the first):
        the CutSheets tell from it that their PanelSet recomputed since they nested."""
        return getattr(self, "_cache", None)

    def computed(self, obj):
        """(facet PanelSet, [(id, Part.Solid)] or None) as of the last recompute, when
        still current; else the panels computed afresh (and no solids)."""
        cache = getattr(self, "_cache", None)
        stale = ("Touched" in obj.State or obj.Source is None
                 or "Touched" in obj.Source.State)
        if cache is not None and not stale and cache[0] == self._key(obj):
            ps = cache[1]
            solids = None
            shape_solids = obj.Shape.Solids
            if obj.Placement.isIdentity() and len(shape_solids) == len(ps.panels):
                solids = [(p.id, s) for p, s in zip(ps.panels, shape_solids)]
            return ps, solids
        return self.panel_set(obj), None

    @guarded
    def execute(self, obj):
        import Part

        from facet.report import first_names
        from facet.step import SolidError, panel_solids

        density = _density(obj)  # (before anything changes)
        cache, self._cache = getattr(self, "_cache", None), None
        mesh = self._source_mesh(obj)
        if self._same_solids(obj, cache, mesh):
            # a Density, OnePerPanel or part ID change: the solids (most of the time: 280
            # panels 0.28 s, their panels 0.02 s) were all built again for masses or names
            solids = obj.Shape.Solids  # (placed as the object, as the panels' objects are)
            if cache[0] == self._key(obj):
                obj.Masses, obj.TotalMass = _masses(obj.Volumes, density)
                if ("PartTypeTolerance" in self._changed
                        or len(obj.PartTypes) != len(cache[1].panels)):
                    _set_part_types(obj, cache[1])  # (the panels' types: their tolerance's)
                self._update_panel_objects(obj, cache[1], solids)
                self._cache = (self._key(obj), cache[1], mesh)
                self._changed = set()
                self._no_part_types = False
                return
            ps = self.panel_set(obj, mesh)  # (new part IDs)
        else:
            ps = self.panel_set(obj, mesh)
            try:
                # every solid checked by BRepCheck (brepcheck=True); most of the time of a
                # large set (3,200 panels: 0.4 s the panels, 2.6-10 s their solids), which
                # showed no progress and could not be cancelled
                stage = _stage_progress(progress.hook(), progress.say_hook())
                solids = [s for _, s in panel_solids(
                    ps, brepcheck=True,
                    progress=None if stage is None else lambda done, total: stage(
                        "solids", done, total))]
            except SolidError as exc:
                raise ValueError(f"{obj.Label}: {exc}") from None
            obj.Shape = Part.makeCompound(solids)
            obj.Volumes = [s.Volume for s in solids]
        obj.PartIds = [p.id for p in ps.panels]
        obj.PanelCount = len(ps.panels)
        _set_part_types(obj, ps)
        obj.Masses, obj.TotalMass = _masses(obj.Volumes, density)
        obj.Areas = [p.area for p in ps.panels]
        obj.MaxNodeDeviation = ps.max_node_deviation_deg
        obj.Corners = [p.corners for p in ps.panels]
        vanished = [p.id for p in ps.vanished_panels]
        obj.VanishedEdgePanels = vanished
        obj.NarrowestJoint = ps.narrowest_joint or 0.0
        obj.NarrowestJointPanels = list(ps.narrowest_joint_panels or ())
        obj.OverlappingJoints = ps.overlapping_joints
        obj.ClearingGap = ps.clearing_gap or 0.0
        obj.NodeClashes = ps.node_clash_pairs
        obj.DeepestNodeClash = ps.node_clashes[0]["depth"] if ps.node_clashes else 0.0
        obj.NodeClashPanels = list(ps.deepest_node_clash_panels or ())
        obj.ClashingPanels = [p.id for p in ps.clashing_panels]
        size = _size_warning(ps.mean_edge_length()) if ps.panels else None
        obj.Warnings = list(ps.warnings) + ([size] if size else [])
        if size:
            App.Console.PrintWarning(f"{obj.Label}: {size}\n")
        # (lengths in the unit FreeCAD shows them in: these said mm to a designer in inches)
        if ps.overlapping_joints:
            a, b = ps.narrowest_joint_panels
            clears = (translate("Facet", "a Gap of {0} or EdgeMode bisector clears "
                                "them").format(length_text(ps.clearing_gap, 4))
                      if ps.clearing_gap is not None else  # (no gap clears the node clashes)
                      translate("Facet", "no Gap found clears every overlap: EdgeMode "
                                "bisector or thinner panels"))
            App.Console.PrintWarning(translate(
                "Facet", "{0}: joints that overlap (cut square on the inner side of a fold): "
                "{1}; the deepest {2} and {3} by {4}; {5}").format(
                    obj.Label, ps.overlapping_joints, a, b,
                    length_text(-ps.narrowest_joint, 4), clears) + "\n")
        if ps.node_clashes:
            App.Console.PrintWarning(translate(
                "Facet", "{0}: pairs of panels that overlap at nodes they share without a "
                "joint: {1}; the deepest {2} and {3} by {4}; a Gap of {5} clears "
                "every overlap (see its Warnings)").format(
                    obj.Label, ps.node_clash_pairs, *ps.deepest_node_clash_panels,
                    length_text(ps.node_clashes[0]["depth"], 4),
                    length_text(ps.clearing_gap or 0.0, 4)) + "\n")
        if vanished:
            App.Console.PrintMessage(translate(
                "Facet", "{0}: panels built with fewer corners than their faces, because "
                "edges shorter than MinEdge vanished (panels: {1}, edges: {2}): {3}").format(
                    obj.Label, len(vanished), len(ps.vanished_edges),
                    first_names(vanished, 8)) + "\n")
        if ps.short_edges_kept:
            App.Console.PrintWarning(translate(
                "Facet", "{0}: edges shorter than MinEdge kept as they are: {1} (see its "
                "Warnings)").format(
                    obj.Label, len(ps.short_edges_kept)) + "\n")
        self._update_panel_objects(obj, ps, solids)
        self._cache = (self._key(obj), ps, mesh)
        self._changed = set()
        self._no_part_types = False

    def _update_panel_objects(self, obj, ps, solids):
        """Keep one plain Part::Feature per panel (OnePerPanel), reusing the existing ones
        in order and removing the rest (after the recompute: recompute.after_recompute).
        Only the PanelSet's own are used: a copy of a PanelSet links its original's until
        it makes its own, and leaves those alone."""
        from facetwb.recompute import after_recompute

        doc = obj.Document
        have = [o for o in obj.PanelObjects if o is not None and _owns(obj, o)]
        want = len(ps.panels) if obj.OnePerPanel else 0
        keep = have[:want]
        extras = [o.Name for o in have[want:]]

        def remove():
            for name in extras:
                if doc.getObject(name) is not None:
                    doc.removeObject(name)

        if extras:
            after_recompute(doc, remove)
        for k in range(len(keep), want):
            # a name of its own: FreeCAD finds a free "Panel..." by scanning every object
            keep.append(doc.addObject("Part::Feature", f"{obj.Name}_Panel{k:05d}"))
        for child, p, solid in zip(keep, ps.panels, solids):
            child.Label = p.id
            child.Shape = solid
            child.Placement = obj.Placement
            child.purgeTouched()
        obj.PanelObjects = keep
        if App.GuiUp:
            if keep or have:
                # the compound shown instead of the panels' objects, or they instead of
                # it; else as the designer left it (every recompute showed a PanelSet
                # hidden to look at its mesh)
                obj.ViewObject.Visibility = not keep
            if hasattr(obj.ViewObject.Proxy, "show_clashes"):
                obj.ViewObject.Proxy.show_clashes(obj)  # the new objects' colours


def _set_part_types(obj, ps):
    """The PanelSet's PartTypes and PartTypeCount, of the facet PanelSet ``ps``."""
    from facet.part_types import part_types

    stage = _stage_progress(progress.hook(), progress.say_hook())
    types = part_types(ps.panels, obj.PartTypeTolerance.Value, progress=None if stage is None
                       else lambda done, total: stage("types", done, total))
    obj.PartTypes = types
    obj.PartTypeCount = len(set(types))


def _density(obj):
    """The PanelSet's Density (kg/m³), None when 0 (not given); a ValueError naming the
    object when it is not a finite number > 0."""
    from facet.panels import check_density

    if obj.Density == 0.0:
        return None
    try:
        return check_density(obj.Density)
    except ValueError as exc:
        raise ValueError(f"{obj.Label}: {exc}") from None


def _masses(volumes, density):
    """(each panel's mass in kg, their sum) from `volumes` (mm³) and `density` (kg/m³);
    ([], 0.0) without a density."""
    from facet.panels import mass_kg

    if density is None:
        return [], 0.0
    masses = [float(m) for m in mass_kg(volumes, density)]
    return masses, float(sum(masses))


def _owns(obj, child):
    """Whether a per-panel object is the PanelSet's own: no other PanelSet links it (a
    copy made with its dependencies, a document of an older version whose objects are
    named ``Panel001``), or several do and it is named after this one (``NAME_Panel00012``,
    or FreeCAD's variant of that name with more digits): a copy made without its
    dependencies links its original's objects until it makes its own."""
    others = [o for o in getattr(child, "InList", ()) if o is not obj and is_panelset(o)
              and child in (getattr(o, "PanelObjects", None) or [])]
    if not others:
        return True
    prefix = obj.Name + "_Panel"
    return child.Name.startswith(prefix) and child.Name[len(prefix):].isdigit()


class CutSheets(_Proxy):
    """Proxy of the nested cut sheets of a PanelSet (and the files written from them)."""

    TYPE = TYPE_CUTSHEETS

    def init_properties(self, obj):
        add = compat.add_property
        add(obj, "App::PropertyLink", "Panels", "Base", "The PanelSet to cut")
        add(obj, "App::PropertyLength", "SheetWidth", "Sheet", "Stock sheet width",
            value=3000.0)
        add(obj, "App::PropertyLength", "SheetHeight", "Sheet", "Stock sheet height",
            value=1500.0)
        add(obj, "App::PropertyLength", "Margin", "Sheet", "Clear border along sheet edges",
            value=10.0)
        add(obj, "App::PropertyLength", "Spacing", "Sheet", "Least distance between parts",
            value=6.0)
        _enum(obj, "Rotations", "Sheet", "Rotations allowed when nesting (none when a grain "
              "is set)", ROTATIONS, "90")
        add(obj, "App::PropertyVector", "Grain", "Sheet",
            "Grain direction in model space (zero: no grain)")
        add(obj, "App::PropertyBool", "TightNesting", "Sheet",
            "Slower nesting, often on fewer sheets: the parts of the least-filled sheets "
            "are nested again together", value=False)
        add(obj, "App::PropertyPath", "OutputDir", "Files",
            "Folder for sheets.dxf, panels.step, schedule.csv/.json and previews "
            "(empty: write nothing)")
        add(obj, "App::PropertyBool", "WriteStep", "Files", "Also write panels.step",
            value=True)
        add(obj, "App::PropertyBool", "TextOutlines", "Files",
            "IDs and bevel angles in sheets.dxf as the outlines of their letters (closed "
            "polylines), for CAM programs that import no TEXT", value=False)
        _output(obj, "App::PropertyInteger", "SheetCount", "Number of sheets")
        _output(obj, "App::PropertyFloat", "Utilisation", "Part area over sheet area, all sheets")
        _output(obj, "App::PropertyFloatList", "SheetUtilisation", "Per sheet")
        _output(obj, "App::PropertyStringList", "Unplaced", "Parts that fit on no sheet")
        _output(obj, "App::PropertyStringList", "Files", "Files written")
        _output(obj, "App::PropertyStringList", "Warnings",
                "What was found worth telling about the sheets (texts too small to engrave)")
        from facetwb.recompute import after_undo

        after_undo(mark_stale_after_undo)

    def onDocumentRestored(self, obj):
        """A document whose files are no longer where its CutSheets wrote them (the
        OutputDir deleted or moved, the document opened on another machine): the CutSheets
        must recompute (:meth:`mustExecute`), which writes them again, and the report view
        says so. They were shown up to date, their Files naming files that were not there,
        and a Recompute did nothing. (FreeCAD 0.20 clears a mark made while a document
        loads.)"""
        super().onDocumentRestored(obj)
        import os

        missing = [f for f in obj.Files if not os.path.isfile(f)] if obj.OutputDir else []
        self._missing = bool(missing)
        if missing:
            App.Console.PrintWarning(translate(
                "Facet", "{0}: {1} of the {2} files it wrote are no longer there ({3}): "
                         "the next recompute writes them again in {4}").format(
                obj.Label, len(missing), len(obj.Files), missing[0], obj.OutputDir) + "\n")

    def mustExecute(self, obj):  # noqa: N802 - FreeCAD's name
        """Whether the CutSheets must recompute although nothing of theirs changed: their
        files went missing while the document was closed."""
        return bool(getattr(self, "_missing", False))

    @guarded
    def execute(self, obj):
        import os

        from facet.cli_panels import run_pipeline, write_schedule
        from facetwb import conversion

        ps_obj = obj.Panels
        if ps_obj is None or getattr(getattr(ps_obj, "Proxy", None), "Type", "") != TYPE_PANELSET:
            raise ValueError(f"{obj.Label}: Panels must be a PanelSet")
        g = obj.Grain
        grain = None if g.Length == 0 else (g.x, g.y, g.z)
        out = obj.OutputDir
        if out:
            sharing = _sharing_output(obj)
            if sharing:
                # (a copy of a CutSheets keeps its OutputDir: a recompute of the copy
                # replaced the original's files, which still showed up to date)
                other = sharing[0]
                name = (other.Label if other.Document == obj.Document else translate(
                    "Facet", "{0} of the document {1}").format(other.Label,
                                                              other.Document.Label))
                raise ValueError(translate(
                    "Facet", "{0}: its OutputDir {1} is also that of {2}, whose files it "
                             "would replace: choose another folder").format(
                    obj.Label, out, name))
            os.makedirs(out, exist_ok=True)
        panel_set, solids = ps_obj.Proxy.computed(ps_obj)
        # the PanelSet's part types when they are those of these panels (its last
        # recompute's, still current), else run_pipeline finds them
        record = ps_obj.Proxy.record()
        types = (list(ps_obj.PartTypes) if record is not None and record[1] is panel_set
                 and len(ps_obj.PartTypes) == len(panel_set.panels) else None)
        density = _density(ps_obj)
        kept, self._kept = getattr(self, "_kept", None), None
        if not self._nesting_kept(obj, ps_obj, kept):
            kept = None
        write = self._to_write(obj, panel_set, density, kept,
                               type_tol=ps_obj.PartTypeTolerance.Value)

        def path(kind, name):
            return os.path.join(out, name) if kind in write else None

        mesh = conversion.mesh_from_object(ps_obj.Source)
        from facet.io.files import staged, when_staged

        with staged():  # the files of a run together, or none of them
            report, ps, drawings, result = run_pipeline(
                mesh, ps_obj.Thickness.Value, panel_set=panel_set, solids=solids,
                offset=ps_obj.Offset, gap=ps_obj.Gap.Value, edge=ps_obj.EdgeMode,
                flip=bool(ps_obj.Flip), ids=ps_obj.IdScheme, prefix=ps_obj.IdPrefix,
                tol=ps_obj.Tolerance, tol_abs=ps_obj.ToleranceAbs.Value,
                min_edge=ps_obj.MinEdge, min_edge_abs=ps_obj.MinEdgeAbs.Value,
                option_names=option_names(),
                sheet=(obj.SheetWidth.Value, obj.SheetHeight.Value), margin=obj.Margin.Value,
                spacing=obj.Spacing.Value, rotations=obj.Rotations, grain=grain,
                tight=bool(obj.TightNesting), dxf=path("dxf", "sheets.dxf"),
                schedule=path("schedule", "schedule.csv"), svg=path("svg", "svg"),
                step=path("step", "panels.step"),
                text_outlines=bool(obj.TextOutlines), density=density,
                type_tol=ps_obj.PartTypeTolerance.Value, types=types,
                progress=_stage_progress(progress.hook(), progress.say_hook()),
                nested=None if kept is None else (kept["panels"], kept["drawings"],
                                                  kept["result"]))
            files = dict(kept["files"]) if kept is not None and kept["out"] == out else {}
            files.update(report["files"])
            if "schedule" in write:
                json_path = _schedule_paths(out)[1]
                write_schedule(json_path, ps, report["panels"],  # (the schedule's rows)
                               density=density, units="mm")
                files["schedule"] = files["schedule"] + [json_path]
            step = os.path.join(out, "panels.step") if out else None
            if not obj.WriteStep:
                files.pop("step", None)
                if step in obj.Files and os.path.isfile(step):
                    # the STEP file of an earlier recompute (WriteStep turned off): left
                    # there, it would no longer be the panels of the sheets beside it
                    when_staged(lambda: _remove(step))
        if report["nested"] or kept is None:
            obj.Shape = _layout(result, drawings)
            obj.SheetCount = len(result.sheets)
            obj.Utilisation = float(result.utilisation)
            obj.SheetUtilisation = [float(s.utilisation) for s in result.sheets]
        # (else the same parts in the same places: the same layout)
        obj.Unplaced = list(result.unplaced)
        obj.Files = [f for kind in FILE_KINDS for f in files.get(kind, [])]
        if not out or report["files"].get("dxf") or report["files"].get("svg"):
            # (else the texts of the files kept are those warned about at the time)
            obj.Warnings = _text_warnings(report["text_warnings"], drawings)
            for warning in obj.Warnings:
                App.Console.PrintWarning(f"{obj.Label}: {warning}\n")
        self._kept = dict(layout=self._layout_key(obj, ps_obj), panels=panel_set,
                          record=ps_obj.Proxy.record(), drawings=drawings, result=result,
                          density=density, out=out, text_outlines=bool(obj.TextOutlines),
                          type_tol=ps_obj.PartTypeTolerance.Value, files=files)
        self._changed = set()
        self._missing = False

    @staticmethod
    def _layout_key(obj, ps_obj):
        """What the nesting depends on besides the parts: the PanelSet, sheet and nesting
        inputs."""
        g = obj.Grain
        return (ps_obj.Name, obj.SheetWidth.Value, obj.SheetHeight.Value, obj.Margin.Value,
                obj.Spacing.Value, obj.Rotations, (g.x, g.y, g.z), bool(obj.TightNesting))

    def _nesting_kept(self, obj, ps_obj, kept):
        """Whether the nesting of the last recompute (``kept``) may be kept: the sheet and
        nesting inputs are the same, and since then the PanelSet recomputed or only
        :data:`FILE_INPUTS` of the CutSheets' own changed. run_pipeline keeps it when the
        parts' outlines are the same (other part IDs, masses), else it nests again. A
        recompute of the CutSheets marked by hand nests again."""
        changed = getattr(self, "_changed", None) or set()
        return (kept is not None and kept["layout"] == self._layout_key(obj, ps_obj)
                and (kept["record"] is not ps_obj.Proxy.record()
                     or bool(changed) and changed <= FILE_INPUTS))

    @staticmethod
    def _to_write(obj, panel_set, density, kept, type_tol):
        """The kinds of files (:data:`FILE_KINDS`) the recompute writes: all of them without
        a nesting ``kept``, for new panels (other part IDs: in every file) or in another
        OutputDir; else those whose inputs changed (the schedules: Density, the PanelSet's
        PartTypeTolerance; the DXF: TextOutlines; STEP: WriteStep turned on) and those no
        longer there."""
        import os

        if not obj.OutputDir:
            return set()
        every = {"dxf", "schedule", "svg"} | ({"step"} if obj.WriteStep else set())
        if kept is None or kept["panels"] is not panel_set or kept["out"] != obj.OutputDir:
            return every
        write = {kind for kind in every
                 if not kept["files"].get(kind)
                 or not all(os.path.exists(p) for p in kept["files"][kind])}
        if density != kept["density"] or type_tol != kept["type_tol"]:
            write.add("schedule")
        if bool(obj.TextOutlines) != kept["text_outlines"]:
            write.add("dxf")
        return write


def _layout(result, drawings):
    """The sheets in rows as the DXF lays them (``facet.cutsheets.sheet_origins``), flat in
    the xy plane: their borders and the parts' cut outlines where ``result`` placed them."""
    import Part

    from facet.cutsheets import sheet_origins

    origins = sheet_origins(result)
    w, h = result.sheet_size
    V = App.Vector
    wires = []
    for x0, y0 in origins:
        wires.append(Part.makePolygon([V(x0, y0, 0), V(x0 + w, y0, 0), V(x0 + w, y0 + h, 0),
                                       V(x0, y0 + h, 0), V(x0, y0, 0)]))
    by_id = {d.id: d for d in drawings}
    for pid, pl in result.placements.items():
        pts = pl.transform(by_id[pid].cut)
        x0, y0 = origins[pl.sheet]
        ring = [V(float(x) + x0, float(y) + y0, 0) for x, y in pts]
        wires.append(Part.makePolygon(ring + [ring[0]]))
    return Part.makeCompound(wires)


def _sharing_output(obj):
    """The other CutSheets, in any open document, whose OutputDir is the folder of
    ``obj``'s."""
    import os

    def folder(path):
        return os.path.normcase(os.path.realpath(path))

    mine = folder(obj.OutputDir)
    return [o for doc in App.listDocuments().values() for o in doc.Objects
            if o is not obj and is_cutsheets(o) and getattr(o, "OutputDir", "")
            and folder(o.OutputDir) == mine]


def mark_stale_after_undo(doc):
    """After an undo or redo in ``doc``: mark for recompute each CutSheets when anything it
    is made from (its PanelSet, the PanelSet's mesh and what that is made from) is marked.
    FreeCAD marks the objects whose properties the undo put back, not what is made from
    them: undoing a PanelSet's Gap left its CutSheets shown up to date, their Files (and,
    without an OutputDir, their layout Shape and sheet counts) those of the Gap undone,
    until the next recompute."""
    for obj in doc.Objects:
        if (is_cutsheets(obj) and "Touched" not in obj.State
                and any("Touched" in o.State for o in obj.OutListRecursive)):
            obj.touch()


def _remove(path):
    """Remove the file ``path`` if it is still there."""
    import contextlib
    import os

    with contextlib.suppress(FileNotFoundError):
        os.remove(path)


def _schedule_paths(out):
    """The CutSheets' schedules in the folder ``out``: CSV and JSON."""
    import os

    return [os.path.join(out, "schedule.csv"), os.path.join(out, "schedule.json")]


def is_panelset(obj):
    return getattr(getattr(obj, "Proxy", None), "Type", None) == TYPE_PANELSET


def is_cutsheets(obj):
    return getattr(getattr(obj, "Proxy", None), "Type", None) == TYPE_CUTSHEETS


#: The colour of panels that overlap another (ShowClashes).
CLASH_COLOR = (0.9, 0.12, 0.1)


def part_type_colour(part_type):
    """The colour of part type ``part_type`` ("T1", "T2", ...) when the PanelSet's view
    shows them (ShowPartTypes): hues a golden angle apart from T1's blue, muted, so that
    the types of neighbouring panels tell apart and none is the clashes' red."""
    import colorsys

    k = int(part_type[1:]) - 1
    hue = (0.58 + 0.6180339887498949 * k) % 1.0
    if hue < 0.04 or hue > 0.94:  # (no red: the clashes')
        hue = (hue + 0.1) % 1.0
    return tuple(round(c, 4) for c in colorsys.hsv_to_rgb(hue, 0.45, 0.85))


class ViewProviderPanels:
    """A Part view provider with Facet's icon (PanelSet and CutSheets). A PanelSet's
    view shows the panels that overlap another in red (ShowClashes)."""

    def __init__(self, vobj, icon):
        self.icon = icon
        vobj.Proxy = self
        self._init_properties(vobj)

    def attach(self, vobj):
        self.Object = vobj.Object
        self.ViewObject = vobj
        self._init_properties(vobj)

    def _init_properties(self, vobj):
        if getattr(self, "icon", "Facet_PanelSet") == "Facet_PanelSet":
            compat.add_property(vobj, "App::PropertyBool", "ShowClashes", "Display",
                                "Show the panels that overlap another (ClashingPanels) in red",
                                value=True)
            compat.add_property(vobj, "App::PropertyBool", "ShowPartTypes", "Display",
                                "Colour each panel by its part type (PartTypes): the panels of "
                                "one type alike", value=False)

    def updateData(self, obj, prop):  # noqa: N802 - FreeCAD's name
        if prop in ("Shape", "ClashingPanels", "PartTypes"):
            self.show_clashes(obj)

    def onChanged(self, vobj, prop):  # noqa: N802
        if prop in ("ShowClashes", "ShowPartTypes", "ShapeColor"):
            self.show_clashes(vobj.Object)

    def show_clashes(self, obj):
        """Per face: red for the solids of ClashingPanels (when ShowClashes), else its part
        type's colour (when ShowPartTypes: :func:`part_type_colour`) or the shape's colour;
        with OnePerPanel the panels' own objects likewise."""
        vobj = getattr(obj, "ViewObject", None)
        if vobj is None or "ShowClashes" not in vobj.PropertiesList:
            return
        clashing = set(getattr(obj, "ClashingPanels", None) or ()) if vobj.ShowClashes else set()
        solids = obj.Shape.Solids if not obj.Shape.isNull() else []
        base = tuple(vobj.ShapeColor[:3])
        types = list(getattr(obj, "PartTypes", None) or [])
        if not (getattr(vobj, "ShowPartTypes", False) and len(types) == len(obj.PartIds)):
            types = [None] * len(obj.PartIds)

        panel_colours = [CLASH_COLOR if part_id in clashing else
                         base if part_type is None else part_type_colour(part_type)
                         for part_id, part_type in zip(obj.PartIds, types)]
        for colour, child in zip(panel_colours, getattr(obj, "PanelObjects", None) or []):
            if child is not None and getattr(child, "ViewObject", None) is not None:
                if tuple(child.ViewObject.ShapeColor[:3]) != colour:
                    child.ViewObject.ShapeColor = colour
        if len(solids) != len(obj.PartIds) or all(c == base for c in panel_colours):
            if len(vobj.DiffuseColor) != 1 or tuple(vobj.DiffuseColor[0][:3]) != base:
                vobj.DiffuseColor = [base]
            return
        colours = []
        for c, solid in zip(panel_colours, solids):
            colours += [c] * len(solid.Faces)
        vobj.DiffuseColor = colours

    def getIcon(self):
        from facetwb import paths

        return paths.icon_path(getattr(self, "icon", "Facet_PanelSet"))

    def claimChildren(self):
        obj = getattr(self, "Object", None)
        return list(getattr(obj, "PanelObjects", None) or [])

    def onDelete(self, vobj, subelements):
        """The per-panel objects belong to the PanelSet: they go with it (its own only, not
        the original's that a copy still links)."""
        obj = vobj.Object
        doc = obj.Document
        for child in list(getattr(obj, "PanelObjects", None) or []):
            if child is not None and _owns(obj, child) and doc.getObject(child.Name) is not None:
                doc.removeObject(child.Name)
        return True

    def dumps(self):
        return {"icon": getattr(self, "icon", "Facet_PanelSet")}

    def loads(self, state):
        self.icon = state.get("icon", "Facet_PanelSet") if isinstance(state, dict) else \
            "Facet_PanelSet"

    def __getstate__(self):
        return self.dumps()

    def __setstate__(self, state):
        self.loads(state)


def cutsheets_summary(obj):
    """The report view's line for a CutSheets object: sheets, use, unplaced parts, and where
    the files went, or that none were written (no OutputDir): the designer who pressed OK
    without choosing a folder was told the sheets and the use, and looked for files."""
    import os

    from facetwb.recompute import failure

    if not obj.isValid():
        return failure(obj)
    text = (f"{obj.Label}: {obj.SheetCount} sheets, utilisation {100 * obj.Utilisation:.1f}%, "
            f"{len(obj.Unplaced)} unplaced")
    if not obj.OutputDir:
        return text + translate("Facet", "; no files written: choose an Output folder (the "
                                         "object's OutputDir) and recompute")
    names = [os.path.relpath(f, obj.OutputDir) for f in obj.Files]
    svg = [n for n in names if n.startswith("svg" + os.sep)]
    shown = [n for n in names if n not in svg] + ([f"svg{os.sep} ({len(svg)} sheets)"]
                                                   if svg else [])
    return text + translate("Facet", "; written to {0}: {1}").format(obj.OutputDir,
                                                                     ", ".join(shown))


def _text_warnings(warnings, drawings):
    """The CutSheets' `warnings` about texts too small to engrave (facet's, in mm), with
    the heights in inches when FreeCAD shows inches or feet (they said "under 3 mm high
    ... the smallest 2.84 mm" beside a property editor in inches)."""
    from facet.unfold import small_text_warnings
    from facetwb.units import imperial

    if warnings and imperial():
        return small_text_warnings(drawings, 1.0, units="in")
    return list(warnings)


def option_names():
    """How the panels' errors name the options they advise (facet.panels.OPTION_NAMES):
    the PanelSet's properties."""
    return {"min_edge": translate("Facet", "the PanelSet's MinEdge"),
            "min_edge_abs": translate("Facet", "the PanelSet's MinEdgeAbs"),
            "ids": translate("Facet", "the PanelSet's IdScheme")}


def _size_warning(mean_edge):
    """A warning when the panels' (or their mesh's) mean edge, in mm, is no facade's
    (facet.cutsheets.implausible_edge_mm): a mesh in metres read as millimetres gave 40 mm
    thick sticks on 0.6 mm faces, and cut sheets of specks, with no word about the units."""
    from facet.cutsheets import implausible_edge_mm

    edges = implausible_edge_mm(mean_edge)
    if edges is None:
        return None
    return translate("Facet", "the panels' edges are {0:.3g} mm long on average, which no "
                              "facade's are: a mesh drawn in metres and read as millimetres "
                              "is a thousand times too small; import it again with Facet > "
                              "Import polygon mesh, which asks for its units").format(edges)


#: What each stage of run_pipeline does, under the progress dialog's title.
_STAGE_TEXTS = {
    "panels": QT_TRANSLATE_NOOP("Facet", "Building the panels"),
    "solids": QT_TRANSLATE_NOOP("Facet", "Making the panel solids"),
    "types": QT_TRANSLATE_NOOP("Facet", "Comparing the parts"),
    "unfold": QT_TRANSLATE_NOOP("Facet", "Unfolding the parts"),
    "nest": QT_TRANSLATE_NOOP("Facet", "Nesting the parts on the sheets"),
    "step": QT_TRANSLATE_NOOP("Facet", "Making the solids for STEP"),
    "dxf": QT_TRANSLATE_NOOP("Facet", "Drawing the parts in the DXF"),
    "svg": QT_TRANSLATE_NOOP("Facet", "Writing the SVG sheets"),
    "png": QT_TRANSLATE_NOOP("Facet", "Writing the PNG sheets"),
}


def _stage_progress(hook, say=None):
    """run_pipeline's ``progress(stage, done, total)`` for a ``(done, total)`` hook; ``say``
    (the dialog's text) names each stage as it starts, as the bar starts again from 0."""
    if hook is None:
        return None
    current = [None]

    def stage_progress(stage, done, total):
        if say is not None and stage != current[0]:
            current[0] = stage
            say(translate("Facet", _STAGE_TEXTS[stage]) if stage in _STAGE_TEXTS else stage)
        # nothing done yet: a busy bar. Nesting 3,200 parts called (0, 3200) every 2 s for
        # the 44 s its first batch took, and the bar sat at 0% as if nothing ran
        return hook(done, total if done else 0)

    return stage_progress


def make_panelset(source, thickness=40.0, offset="outer", gap=DEFAULT_GAP_MM, edge="square",
                  flip=False, ids="auto", prefix="P-", one_per_panel=False, name="PanelSet"):
    """Add a PanelSet on ``source`` (a PolyMesh or Planarized object); recompute to build.
    ``gap`` (mm) defaults to :data:`facet.panels.DEFAULT_GAP_MM`, as ``facet panels``'.

    Returns
    -------
    App.DocumentObject
    """
    if offset not in OFFSETS:
        raise ValueError(f"offset must be one of {OFFSETS}, not {offset!r}")
    if edge not in EDGE_MODES:
        raise ValueError(f"edge must be one of {EDGE_MODES}, not {edge!r}")
    doc = source.Document
    obj = doc.addObject("Part::FeaturePython", name)
    PanelSet(obj)
    obj.Label = f"{source.Label} panels"
    obj.Source = source
    obj.Thickness = thickness
    obj.Offset = offset
    obj.Gap = gap
    obj.EdgeMode = edge
    obj.Flip = bool(flip)
    obj.IdScheme = ids
    obj.IdPrefix = prefix
    obj.OnePerPanel = bool(one_per_panel)
    from facetwb.viewproviders import attach

    attach.give(obj)
    return obj


def make_cutsheets(panelset, sheet=(3000.0, 1500.0), margin=DEFAULT_MARGIN_MM,
                   spacing=DEFAULT_SPACING_MM, rotations="90", grain=None, output_dir="",
                   write_step=True, name="CutSheets", text_outlines=False):
    """Add a CutSheets object nesting ``panelset``'s parts; recompute to nest and write.

    Returns
    -------
    App.DocumentObject
    """
    if rotations not in ROTATIONS:
        raise ValueError(f"rotations must be one of {ROTATIONS}, not {rotations!r}")
    doc = panelset.Document
    obj = doc.addObject("Part::FeaturePython", name)
    CutSheets(obj)
    obj.Label = f"{panelset.Label} cut sheets"
    obj.Panels = panelset
    obj.SheetWidth, obj.SheetHeight = float(sheet[0]), float(sheet[1])
    obj.Margin = margin
    obj.Spacing = spacing
    obj.Rotations = rotations
    if grain is not None:
        obj.Grain = App.Vector(*grain)
    obj.OutputDir = output_dir
    obj.WriteStep = bool(write_step)
    obj.TextOutlines = bool(text_outlines)
    from facetwb.viewproviders import attach

    attach.give(obj)
    return obj
