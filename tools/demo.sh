#!/bin/sh
# SPDX-License-Identifier: LGPL-2.1-or-later
# make demo: planarize the bundled facade headless and write the planarized
# OBJ, the JSON report, a FreeCAD document (source, result, planarity colour
# map) and PNG renders of it.   tools/demo.sh [OUT_DIR]
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
echo "== FreeCAD document and render (FreeCAD under Xvfb)"
sh "$root/tests/fc_env.sh" demo "$mesh" "$out"
echo
echo "Facet demo files:"
for f in "$out"/*; do echo "  $f"; done
