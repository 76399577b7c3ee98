#!/bin/sh
# SPDX-License-Identifier: LGPL-2.1-or-later
# make demo: the facade workflow on the bundled example, headless: planarize
# (OBJ and JSON report), turn the flat faces into mitred 8 mm panels nested
# on 3210 x 2250 sheets (DXF cut sheets, STEP solids, CSV/JSON schedule with
# each panel's mass as 2,500 kg/m³ glass, SVG previews), and a FreeCAD
# document (source, result, planarity colour map) with PNG renders.
#   tools/demo.sh [OUT_DIR]
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-out/demo}
mkdir -p "$out"
out=$(cd "$out" && pwd)
mesh="$root/examples/wave_facade.obj"
python=${PYTHON:-/usr/bin/python3}

echo "== planarize (command line)"
PYTHONPATH="$root/workbench" "$python" -m facet planarize "$mesh" \
    -o "$out/wave_facade_planar.obj" --report "$out/wave_facade_report.json"
echo
echo "== panels and cut sheets (command line; STEP through FreeCAD's OCC)"
PYTHONPATH="$root/workbench" "$python" -m facet panels \
    "$out/wave_facade_planar.obj" --thickness 8 --gap 6 --edge bisector \
    --sheet 3210x2250 --margin 20 --spacing 10 --rotations 90 --density 2500 \
    --dxf "$out/wave_facade_cutsheets.dxf" --step "$out/wave_facade_panels.step" \
    --schedule "$out/wave_facade_schedule.csv" --svg "$out/sheets" \
    --report "$out/wave_facade_panels.json"
echo
echo "== FreeCAD document and render (FreeCAD under Xvfb)"
sh "$root/tests/fc_env.sh" demo "$mesh" "$out"
echo
echo "Facet demo files:"
for f in "$out"/*; do echo "  $f"; done
