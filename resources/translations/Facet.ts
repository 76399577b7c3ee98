<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1">
<context>
    <name>Cutsheets</name>
    <message>
        <location filename="../ui/cutsheets.ui" line="6"/>
        <source>Cut sheets</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/cutsheets.ui" line="10"/>
        <source>Lays the panels flat, nests them on stock sheets and writes the cut files.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/cutsheets.ui" line="16"/>
        <source>Sheet width</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/cutsheets.ui" line="22"/>
        <source>Width of the stock sheets</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/cutsheets.ui" line="30"/>
        <source>Sheet height</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/cutsheets.ui" line="36"/>
        <source>Height of the stock sheets</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/cutsheets.ui" line="44"/>
        <source>Sheet margin</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/cutsheets.ui" line="50"/>
        <source>Border left free around each sheet</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/cutsheets.ui" line="58"/>
        <source>Part spacing</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/cutsheets.ui" line="64"/>
        <source>Free space between neighbouring parts (the cutter&apos;s kerf and more)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/cutsheets.ui" line="72"/>
        <source>Rotations</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/cutsheets.ui" line="78"/>
        <source>Rotations the nester may use: 90 degree steps, none (keeps the grain), or any angle</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/cutsheets.ui" line="79"/>
        <source>90 degree steps</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/cutsheets.ui" line="80"/>
        <source>None</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/cutsheets.ui" line="81"/>
        <source>Free</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/cutsheets.ui" line="86"/>
        <source>Output folder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/cutsheets.ui" line="92"/>
        <source>Folder for the DXF, STEP, schedule and previews (empty: nothing is written, the layout is only shown)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/cutsheets.ui" line="97"/>
        <source>Texts as outlines in the DXF</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/cutsheets.ui" line="98"/>
        <source>IDs and bevel angles written as the outlines of their letters (closed polylines), for CAM programs that import no DXF text</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Facet</name>
    <message>
        <location filename="../../workbench/facetwb/progress.py" line="167"/>
        <source>Cancel</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/derive_panels.py" line="200"/>
        <source>Surface to control mesh</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/edit_panels.py" line="28"/>
        <source>Planarize</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/derive_panels.py" line="275"/>
        <source>Panels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/derive_panels.py" line="320"/>
        <source>Cut sheets</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/derive_panels.py" line="374"/>
        <source>Lift plan</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="6"/>
        <source>Facet</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="10"/>
        <source>Defaults of the Facet commands. Lengths are shown in the unit system chosen under General &gt; Units.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="16"/>
        <source>Planarize method</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="24"/>
        <source>Local/global</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="25"/>
        <source>Local/local</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="30"/>
        <source>Planarity tolerance (relative)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="36"/>
        <source>Stop when every vertex is within this fraction of its face&apos;s mean edge length from the face&apos;s plane (1e-6: 2 micrometres on a 2 m panel)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="41"/>
        <source>Planarity tolerance (absolute)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="47"/>
        <source>Stop when every vertex is within this distance of its face&apos;s plane (0: only the relative tolerance)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="55"/>
        <source>Max. iterations</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="61"/>
        <source>Give up after this many iterations (0: the solver&apos;s default)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="68"/>
        <source>Surface mesh pattern</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="74"/>
        <source>Default pattern of Surface to control mesh</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="75"/>
        <source>Quad grid</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="76"/>
        <source>Hex grid</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="77"/>
        <source>Paired triangles</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="82"/>
        <source>Panels along u</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="88"/>
        <source>Default panel count along u</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="95"/>
        <source>Panels along v</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="101"/>
        <source>Default panel count along v</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="108"/>
        <source>Panel size</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="114"/>
        <source>Default target panel size (0: use the counts)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="122"/>
        <source>Panel thickness</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="128"/>
        <source>Default panel thickness</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="136"/>
        <source>Panel offset</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="142"/>
        <source>Default side of the surface the panels lie on</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="143"/>
        <source>Outer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="144"/>
        <source>Inner</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="145"/>
        <source>Centre</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="150"/>
        <source>Joint gap</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="156"/>
        <source>Default joint gap between panels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="164"/>
        <source>Edge cut</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="170"/>
        <source>Default edge cut</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="171"/>
        <source>Square</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="172"/>
        <source>Bisector</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="177"/>
        <source>Part ID prefix</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="183"/>
        <source>Default part ID prefix</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="188"/>
        <source>Sheet width</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="194"/>
        <source>Default stock sheet width</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="202"/>
        <source>Sheet height</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="208"/>
        <source>Default stock sheet height</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="216"/>
        <source>Sheet margin</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="222"/>
        <source>Default sheet margin</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="230"/>
        <source>Part spacing</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="236"/>
        <source>Default space between parts</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="244"/>
        <source>Rotations</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="250"/>
        <source>Default rotations of the nester</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="251"/>
        <source>90 degree steps</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="252"/>
        <source>None</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="253"/>
        <source>Free</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="258"/>
        <source>Output folder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="264"/>
        <source>Default folder for cut files (empty: none written)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="275"/>
        <source>Colour map top</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="281"/>
        <source>Planarity shown in the top colour (red) of new meshes&apos; colour maps (0: the largest face value)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/derive_panels.py" line="331"/>
        <source>Choose the output folder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/derive_panels.py" line="339"/>
        <source>Folder for the cut files</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="23"/>
        <source>Automatic</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/planarized.py" line="259"/>
        <source>Planarize {0}: solving by local/local too, for a result closer to the design</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/planarized.py" line="262"/>
        <source>Planarize {0}: solving by local/global again with a finer hold, closer to the design</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/planarized.py" line="267"/>
        <source>Planarize {0}: re-solving for panel quality (stage {1} of {2})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/planarized.py" line="245"/>
        <source>planarity {0:.2g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/planarized.py" line="245"/>
        <source>planarity {0:.2g} (tolerance {1:.2g})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="387"/>
        <source>{0}: panels built with fewer corners than their faces, because edges shorter than MinEdge vanished (panels: {1}, edges: {2}): {3}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="393"/>
        <source>{0}: edges shorter than MinEdge kept as they are: {1} (see its Warnings)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/planarized.py" line="265"/>
        <source>Planarize {0}: local/local closed a panel, solving by local/global</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/progress.py" line="153"/>
        <source>Stop and keep</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/progress.py" line="153"/>
        <source>Stop here and keep the result that reached the tolerance</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/recompute.py" line="278"/>
        <source>Recomputing {0} ...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="22"/>
        <source>Automatic (the default): local/global and local/local up to 10,000 quads, keeping the result closer to the design; local/local alone above. Local/global: one sparse solve per iteration, few iterations. Local/local: many cheap per-face steps, little memory.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/edit_control.py" line="827"/>
        <source>Edit control mesh</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/edit_control.py" line="829"/>
        <source>Drag a control vertex (dot) with the left mouse button; the planar result follows. OK (or Esc) keeps the edit, Cancel drops it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/edit_control.py" line="846"/>
        <source>Vertices closer than this to the dragged one move with it (0: the dragged vertex alone)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/edit_control.py" line="850"/>
        <source>Radius</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/edit_control.py" line="853"/>
        <source>How much the neighbours move: smooth, linear with the distance, or all of them as much as the dragged vertex</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/edit_control.py" line="857"/>
        <source>Falloff</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/edit_control.py" line="860"/>
        <source>Colour the result by the planarity of each panel or by how far its corners are from the control mesh</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/edit_control.py" line="864"/>
        <source>Colour by</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_mix.py" line="100"/>
        <source>Lifting {0}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_mix.py" line="107"/>
        <source>Height of this lifting at its peak; the faces stay planar</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_mix.py" line="118"/>
        <source>Raise vertex</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_mix.py" line="120"/>
        <source>The plan vertex to raise or lower</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_mix.py" line="134"/>
        <source>How far the vertex moves; the rest of the roof follows, every face planar</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="368"/>
        <source>no Gap found clears every overlap: EdgeMode bisector or thinner panels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="269"/>
        <source>Texts as outlines in the DXF</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/preferences.ui" line="270"/>
        <source>Default: IDs and bevel angles written as the outlines of their letters, for CAM programs that import no DXF text</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="940"/>
        <source>Building the panels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="944"/>
        <source>Nesting the parts on the sheets</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="945"/>
        <source>Making the solids for STEP</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="946"/>
        <source>Drawing the parts in the DXF</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="947"/>
        <source>Writing the SVG sheets</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="948"/>
        <source>Writing the PNG sheets</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/edit_panels.py" line="53"/>
        <source>{0}: every change re-solves it at once. OK keeps the changes in one undo step; Cancel puts the previous values and result back.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/commands/import_mesh.py" line="118"/>
        <source>Import polygon mesh</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="941"/>
        <source>Making the panel solids</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/edit_control.py" line="114"/>
        <source>{0} is rebuilt from {1} on recompute: OK puts the moved vertices in a new polygon mesh, &apos;{0} edited&apos;, which the planar result then follows; both are kept as they are</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="932"/>
        <source>the panels&apos; edges are {0:.3g} mm long on average, which no facade&apos;s are: a mesh drawn in metres and read as millimetres is a thousand times too small; import it again with Facet &gt; Import polygon mesh, which asks for its units</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="893"/>
        <source>; no files written: choose an Output folder (the object&apos;s OutputDir) and recompute</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="899"/>
        <source>; written to {0}: {1}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="245"/>
        <source>{0}; {1} stopped before its tolerance ({2}): raise its Max. iterations, or set it to 0 for the solver to decide</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_mix.py" line="266"/>
        <source>Shape lifting</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_mix.py" line="67"/>
        <source>{0}: this plan admits only planes: there is nothing to mix. Change the drawing (or lift it with moved vertices) to get more shapes.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/derive_panels.py" line="396"/>
        <source>Points file (x, y, z)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/derive_panels.py" line="410"/>
        <source>Choose the points file</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/derive_panels.py" line="437"/>
        <source>Target heights</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_mix.py" line="63"/>
        <source>{0}: there is no lifting to shape: {1}. Fix it and recompute first.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/derive_panels.py" line="399"/>
        <source>Pinned heights (pick vertices)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="26"/>
        <source>Pin heights</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="51"/>
        <source>Vertex</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="68"/>
        <source>Height</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="69"/>
        <source>The height the selected vertices are pinned at</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="78"/>
        <source>Pin selected vertices</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="79"/>
        <source>Pin the vertices selected in the 3D view (click near a corner of the plan or of the roof; Ctrl+click for more) at the height</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="90"/>
        <source>Pins (lengths in mm):</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="94"/>
        <source>The pins: the plan vertex, its x and y, and the height (double-click a height to edit it)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="105"/>
        <source>Remove pin</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="106"/>
        <source>Remove the pins selected in the table</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="143"/>
        <source>none</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="190"/>
        <source>Pinned {0} {1} at {2}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="190"/>
        <source>vertex</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="190"/>
        <source>vertices</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="198"/>
        <source>Select the pins to remove in the table first</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="202"/>
        <source>Removed {0} pin(s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="209"/>
        <source>Height of pin {0}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="247"/>
        <source>{0}: click vertices of the roof or of its plan in the 3D view (Ctrl+click for more), type a height and press Pin selected vertices. The roof follows at once; the other vertices are free. OK keeps the pins in one undo step; Cancel puts the previous ones back.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_pins.py" line="255"/>
        <source>Pins are used only without other targets: the targets are now {0} (empty Targets and TargetFile to use the pins).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_mix.py" line="191"/>
        <source>vertex {0}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/fixed_vertices.py" line="28"/>
        <source>{0}: Source is empty, it has no vertices</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/fixed_vertices.py" line="32"/>
        <source>{0} shows {1} vertices, its Source {2} has {3}: recompute it, then select its vertices</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/fixed_vertices.py" line="80"/>
        <source>No vertex held</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/fixed_vertices.py" line="82"/>
        <source>1 vertex held</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/fixed_vertices.py" line="83"/>
        <source>{0} vertices held</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/picked.py" line="106"/>
        <source>Nothing is selected: click vertices of {0} in the 3D view (Ctrl+click for more)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/picked.py" line="111"/>
        <source>{0} is selected: click vertices of {1}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/picked.py" line="115"/>
        <source>{0} is selected as a whole (in the tree?): click its vertices in the 3D view</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/picked.py" line="120"/>
        <source>an edge</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/picked.py" line="121"/>
        <source>a face</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/picked.py" line="122"/>
        <source>{0} of {1} is {2}, not a vertex: click closer to a corner (within a few pixels)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/picked.py" line="122"/>
        <source>something else</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/picked.py" line="126"/>
        <source>{0} of {1}: {2} has {3} vertices (0 to {4})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/edit_panels.py" line="89"/>
        <source>Held vertices</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/edit_panels.py" line="93"/>
        <source>Click corners of the mesh in the 3D view (Ctrl+click for more) to hold them in place while it is planarized (FixedVertices). Held: magenta squares; selected: framed in black.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/edit_panels.py" line="100"/>
        <source>Hold selected</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/edit_panels.py" line="100"/>
        <source>Hold the vertices selected in the 3D view in place</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/edit_panels.py" line="100"/>
        <source>Free selected</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/edit_panels.py" line="100"/>
        <source>Let the selected held vertices move again</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/edit_panels.py" line="100"/>
        <source>Free all</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/edit_panels.py" line="100"/>
        <source>Let every held vertex move again</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/edit_panels.py" line="149"/>
        <source>{0} of the {1} selected held now</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/edit_panels.py" line="158"/>
        <source>None of the selected vertices was held</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/edit_panels.py" line="178"/>
        <source>No vertex selected</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/edit_panels.py" line="178"/>
        <source>1 vertex selected</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/edit_panels.py" line="178"/>
        <source>{0} vertices selected</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/pins.py" line="53"/>
        <source>{0}: {1} is not a number of mm</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/pins.py" line="56"/>
        <source>{0}: {1} mm is not a finite height up to {2} mm</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/pins.py" line="73"/>
        <source>{0}: {1} is not a length (a number of mm, or with a length unit: 2.4 m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/commands/import_mesh.py" line="111"/>
        <source>{0}: its edges are {1:.3g} of its units long on average; as millimetres, no facade&apos;s panel is that small or large. Which units are its numbers in?</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="943"/>
        <source>Unfolding the parts</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="918"/>
        <source>the PanelSet&apos;s MinEdge</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="919"/>
        <source>the PanelSet&apos;s MinEdgeAbs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/commands/lift.py" line="128"/>
        <source>{0} holds no plan to lift ({1}): correct the drawing or the plan&apos;s properties and recompute it first</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_mix.py" line="73"/>
        <source>{0}: besides tilting it as one plane, the plan admits one other shape of the roof with planar faces. The slider adds it; every face stays exactly planar.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_mix.py" line="78"/>
        <source>{0}: besides tilting it as one plane, the plan admits {1} other shapes of the roof with planar faces. Each slider adds one (smoothest first); every face stays exactly planar.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/derive_panels.py" line="96"/>
        <source>In error: {0}. Correct it and recompute it first.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_mix.py" line="326"/>
        <source>The roof is in error: no distance from its targets.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_mix.py" line="328"/>
        <source>Roof to its pins (the markers): {0} at most (vertex {1}), {2} RMS.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_mix.py" line="331"/>
        <source>Roof to its targets: {0} at most (vertex {1}), {2} RMS.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/taskpanels/lift_mix.py" line="332"/>
        <source>With every slider at 0 and no vertex raised the roof is closest to them.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/lifting.py" line="232"/>
        <source>the Lifting&apos;s Snap</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/plangraph.py" line="124"/>
        <source>the PlanGraph&apos;s Snap</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/plangraph.py" line="125"/>
        <source>the PlanGraph&apos;s ArcTolerance</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="942"/>
        <source>Comparing the parts</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="920"/>
        <source>the PanelSet&apos;s IdScheme</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/importer.py" line="91"/>
        <source>Checking the mesh</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/importer.py" line="183"/>
        <source>Adding it to the document</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/importer.py" line="228"/>
        <source>Importing {0} ...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="545"/>
        <source>{0}: {1} of the {2} files it wrote are no longer there ({3}): the next recompute writes them again in {4}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="577"/>
        <source>{0}: its OutputDir {1} is also that of {2}, whose files it would replace: choose another folder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/commands/import_mesh.py" line="111"/>
        <source>{0}: its edges are {1:.3g} of its units long on average. FreeCAD shows lengths in inches or feet here (its unit schema) and the file does not say its units: which units are its numbers in?</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="368"/>
        <source>a Gap of {0} or EdgeMode bisector clears them</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="373"/>
        <source>{0}: joints that overlap (cut square on the inner side of a fold): {1}; the deepest {2} and {3} by {4}; {5}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="379"/>
        <source>{0}: pairs of panels that overlap at nodes they share without a joint: {1}; the deepest {2} and {3} by {4}; a Gap of {5} clears every overlap (see its Warnings)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="127"/>
        <source>{0}: saved by an earlier Facet, without the part types of its {1} panels: the next recompute finds them</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/objects/panelset.py" line="574"/>
        <source>{0} of the document {1}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/importer.py" line="247"/>
        <source>import cancelled; nothing changed</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Facet_Cleanup</name>
    <message>
        <location filename="../../workbench/facetwb/commands/cleanup.py" line="23"/>
        <source>Collapse short edges</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/commands/cleanup.py" line="24"/>
        <source>Join the selected polygon mesh&apos;s unwelded seams (vertices at one point), collapse its edges shorter than a tenth of its mean edge (change MinEdge in the new object), then planarize again. The result is a new mesh with fewer panels; the source is kept.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Facet_CutSheets</name>
    <message>
        <location filename="../../workbench/facetwb/commands/panels.py" line="56"/>
        <source>Cut sheets</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/commands/panels.py" line="57"/>
        <source>Lay the selected panels flat with their IDs and bevel angles, nest them on stock sheets, and write DXF, STEP, schedule and previews to the folder set in OutputDir</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Facet_EditControlMesh</name>
    <message>
        <location filename="../../workbench/facetwb/commands/edit_control.py" line="24"/>
        <source>Edit control mesh</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/commands/edit_control.py" line="25"/>
        <source>Drag the control vertices of the selected Planarized object (or its control PolyMesh) in the 3D view; the planar result follows live. OK writes the moved vertices in one undoable step, Cancel drops them.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Facet_ImportMesh</name>
    <message>
        <location filename="../../workbench/facetwb/commands/import_mesh.py" line="23"/>
        <source>Import polygon mesh...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/commands/import_mesh.py" line="24"/>
        <source>Import an OBJ or OFF file as a Facet polygon mesh (quads, hexagons and other polygons are kept, not split into triangles)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Facet_Lift</name>
    <message>
        <location filename="../../workbench/facetwb/commands/lift.py" line="94"/>
        <source>Lift plan</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/commands/lift.py" line="95"/>
        <source>Select a plan (PlanGraph or Facet mesh), then a target surface (mesh or shape), or the plan alone to lift it to the heights of a points file: every plan vertex gets a height so that every face is exactly planar, as close as possible to the surface straight above it or to the points.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Facet_LiftMix</name>
    <message>
        <location filename="../../workbench/facetwb/commands/lift.py" line="153"/>
        <source>Shape lifting</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/commands/lift.py" line="154"/>
        <source>Sliders for the selected Lifting: add the smoothest other planar-faced shapes over the same plan; the result follows live and every face stays exactly planar.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Facet_LiftPins</name>
    <message>
        <location filename="../../workbench/facetwb/commands/lift.py" line="175"/>
        <source>Pin heights</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/commands/lift.py" line="176"/>
        <source>Pin heights of the selected Lifting: click vertices of the roof or of its plan in the 3D view, type a height and pin them; the roof follows, every face planar, the other vertices free. Also by double-clicking a Lifting that has no other targets.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Facet_PanelSet</name>
    <message>
        <location filename="../../workbench/facetwb/commands/panels.py" line="30"/>
        <source>Panels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/commands/panels.py" line="31"/>
        <source>Turn every planar face of the selected mesh into a panel solid with its thickness and edge cuts, named by part ID (edit Thickness, Offset, Gap, EdgeMode in the property view)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Facet_PlanGraph</name>
    <message>
        <location filename="../../workbench/facetwb/commands/lift.py" line="37"/>
        <source>Plan graph</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/commands/lift.py" line="38"/>
        <source>Make a plan graph (faces seen from above) from the selected Sketches, Draft wires or Part edges, or, with nothing selected, from a drawing file (.dxf, .csv, plan mesh). Crossings are split, dangling edges dropped. It follows changes of the drawing.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Facet_Planarize</name>
    <message>
        <location filename="../../workbench/facetwb/commands/planarize.py" line="24"/>
        <source>Planarize</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/commands/planarize.py" line="25"/>
        <source>Move the vertices of the selected polygon mesh as little as possible so that every face is planar (a flat panel). The source is kept; the result is coloured by planarity.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Facet_SurfaceMesh</name>
    <message>
        <location filename="../../workbench/facetwb/commands/surface_mesh.py" line="25"/>
        <source>Surface to control mesh</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/commands/surface_mesh.py" line="27"/>
        <source>Panelize the selected surfaces (Part, Surface or Curves faces, shells, solids) into a quad grid, a hexagonal grid or triangles paired into quads, or pair the triangles of a selected Mesh. The control mesh follows changes of the surface; the surface is not modified.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Facet_ToPolyMesh</name>
    <message>
        <location filename="../../workbench/facetwb/commands/to_polymesh.py" line="19"/>
        <source>To polygon mesh</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../../workbench/facetwb/commands/to_polymesh.py" line="20"/>
        <source>Make a Facet polygon mesh from the selected Mesh or Part objects: a shape of planar polygons gives one panel per face, other shapes and meshes give triangles. It follows changes of its source.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Liftplan</name>
    <message>
        <location filename="../ui/lifting.ui" line="6"/>
        <source>Lift plan</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/lifting.ui" line="38"/>
        <source>Snap distance</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/lifting.ui" line="10"/>
        <source>Gives every vertex of the plan a height so that every face is exactly planar, as close as possible to the target surface or to the heights of a points file.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/lifting.ui" line="16"/>
        <source>Target</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/lifting.ui" line="22"/>
        <source>The surface the roof should follow (every plan vertex gets the height that keeps every face planar and the roof closest to this surface), or the points of a file</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/lifting.ui" line="27"/>
        <source>Points file</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/lifting.ui" line="33"/>
        <source>Target heights as x,y,z points (.csv, one point at a plan vertex each; the other vertices are free) or a mesh file, when the target is a points file</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/lifting.ui" line="44"/>
        <source>Largest plan distance from a point of the points file to its vertex (0: 1e-6 of the plan&apos;s size)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Panels</name>
    <message>
        <location filename="../ui/panels.ui" line="6"/>
        <source>Panels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.ui" line="10"/>
        <source>Turns every planar face of the selected mesh into a panel solid with a part ID.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.ui" line="16"/>
        <source>Thickness</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.ui" line="22"/>
        <source>Panel thickness</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.ui" line="30"/>
        <source>Offset</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.ui" line="36"/>
        <source>Outer: the panel lies on the outer (+normal) side of the surface; inner: the inner side; centre: centred on it</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.ui" line="37"/>
        <source>Outer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.ui" line="38"/>
        <source>Inner</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.ui" line="39"/>
        <source>Centre</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.ui" line="44"/>
        <source>Joint gap</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.ui" line="50"/>
        <source>Width of the open joint between neighbouring panels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.ui" line="58"/>
        <source>Edge cut</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.ui" line="64"/>
        <source>Square: edges cut square to the panel. Bisector: edges mitred on the plane halfway between neighbouring panels, so the joint closes</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.ui" line="65"/>
        <source>Square</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.ui" line="66"/>
        <source>Bisector</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.ui" line="71"/>
        <source>Part ID prefix</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.ui" line="77"/>
        <source>Text before every part number on the panels, schedule and cut sheets</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Planarize</name>
    <message>
        <location filename="../ui/planarize.ui" line="6"/>
        <source>Planarize</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/planarize.ui" line="10"/>
        <source>Moves the vertices of the selected mesh as little as possible so that every face is planar. The source mesh is kept.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/planarize.ui" line="16"/>
        <source>Method</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/planarize.ui" line="24"/>
        <source>Local/global</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/planarize.ui" line="25"/>
        <source>Local/local</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/planarize.ui" line="36"/>
        <source>Stop when every vertex is within this fraction of its face&apos;s mean edge length from the face&apos;s plane (1e-6: 2 micrometres on a 2 m panel)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/planarize.ui" line="47"/>
        <source>Stop when every vertex is within this distance of its face&apos;s plane (0: only the relative tolerance)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/planarize.ui" line="55"/>
        <source>Max. iterations</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/planarize.ui" line="61"/>
        <source>Give up after this many iterations (0: the solver&apos;s default)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/planarize.ui" line="30"/>
        <source>Rel. tolerance</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/planarize.ui" line="41"/>
        <source>Abs. tolerance</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/planarize.ui" line="23"/>
        <source>Automatic</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/planarize.ui" line="22"/>
        <source>Automatic (the default): local/global and local/local up to 10,000 quads, keeping the result closer to the design; local/local alone above. Local/global: one sparse solve per iteration, few iterations. Local/local: many cheap per-face steps, little memory.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Surfacetocontrolmesh</name>
    <message>
        <location filename="../ui/surface_mesh.ui" line="6"/>
        <source>Surface to control mesh</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/surface_mesh.ui" line="10"/>
        <source>Samples the selected surface into a control mesh that follows the surface when it changes. The surface is not modified.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/surface_mesh.ui" line="16"/>
        <source>Pattern</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/surface_mesh.ui" line="22"/>
        <source>Quad grid: quads along the surface&apos;s u and v lines. Hex grid: a honeycomb. Paired triangles: a triangulation whose best neighbouring triangles are joined into quads.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/surface_mesh.ui" line="23"/>
        <source>Quad grid</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/surface_mesh.ui" line="24"/>
        <source>Hex grid</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/surface_mesh.ui" line="25"/>
        <source>Paired triangles</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/surface_mesh.ui" line="30"/>
        <source>Panels along u</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/surface_mesh.ui" line="36"/>
        <source>Number of panels along the surface&apos;s u direction, per face (used when the panel size is 0)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/surface_mesh.ui" line="43"/>
        <source>Panels along v</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/surface_mesh.ui" line="49"/>
        <source>Number of panels (hex grid: rows) along the surface&apos;s v direction, per face (used when the panel size is 0)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/surface_mesh.ui" line="56"/>
        <source>Panel size</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/surface_mesh.ui" line="62"/>
        <source>Target panel width: quad edge, hexagon across flats, triangle edge. 0 uses the counts above.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
</TS>
