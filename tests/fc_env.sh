#!/bin/sh
# SPDX-License-Identifier: LGPL-2.1-or-later
#
# Run FreeCAD with this checkout loaded as the Facet workbench, without installing it: a
# throw-away FreeCAD user home (FREECAD_USER_HOME, honoured by FreeCAD 0.20 and 1.x) whose
# Mod/Facet is a symlink to the checkout. FreeCAD reads package.xml there, puts workbench/ on
# sys.path and runs workbench/Init.py and InitGui.py, exactly as for an Addon Manager install.
# The user's own FreeCAD settings are neither read nor changed. Exits with FreeCAD's status.
#
#   tests/fc_env.sh headless                  headless tests (freecadcmd)
#   tests/fc_env.sh gui [OUT_DIR]             GUI test under Xvfb; screenshots in OUT_DIR
#                                             (default build/gui)
#   tests/fc_env.sh demo MESH [OUT_DIR]       demo.FCStd and planarity.png of MESH under Xvfb
#                                             (default OUT_DIR build/demo)
#   tests/fc_env.sh COMMAND [ARG...]          any command, e.g. freecad to try it by hand
#
# Environment: FACET_TESTS=test_planarized (headless: only these modules), XVFB_SCREEN.
set -u
ROOT=$(cd "$(dirname "$0")/.." && pwd)
SCREEN=${XVFB_SCREEN:-1600x1000x24}

FC_HOME=$(mktemp -d "${TMPDIR:-/tmp}/facet-fchome.XXXXXX") || exit 1
trap 'rm -rf "$FC_HOME"' EXIT
trap 'exit 130' INT TERM
mkdir -p "$FC_HOME/Mod"
ln -s "$ROOT" "$FC_HOME/Mod/Facet"
# Start without the Start page (it needs QtWebEngine) in the throw-away home.
cat > "$FC_HOME/user.cfg" <<'CFG'
<?xml version="1.0" encoding="UTF-8" standalone="no" ?>
<FCParameters>
  <FCParamGroup Name="Root">
    <FCParamGroup Name="BaseApp">
      <FCParamGroup Name="Preferences">
        <FCParamGroup Name="General">
          <FCText Name="AutoloadModule">NoneWorkbench</FCText>
        </FCParamGroup>
      </FCParamGroup>
    </FCParamGroup>
  </FCParamGroup>
</FCParameters>
CFG
export FREECAD_USER_HOME="$FC_HOME"
# FreeCAD's Qt WebEngine refuses to start as root without this.
export QTWEBENGINE_CHROMIUM_FLAGS="${QTWEBENGINE_CHROMIUM_FLAGS:---no-sandbox}"

abspath() { case "$1" in /*) echo "$1" ;; *) echo "$(pwd)/$1" ;; esac; }

case "${1:-}" in
headless)
    cd "$ROOT" && freecadcmd tests/freecad/run_tests.py
    ;;
gui)
    FACET_GUI_OUT=$(abspath "${2:-$ROOT/build/gui}")
    export FACET_GUI_OUT
    mkdir -p "$FACET_GUI_OUT"
    cd "$ROOT" && xvfb-run -a -s "-screen 0 $SCREEN" freecad tests/gui/gui_test.py
    ;;
demo)
    if [ $# -lt 2 ]; then echo "usage: $0 demo MESH [OUT_DIR]" >&2; exit 2; fi
    FACET_DEMO_MESH=$(abspath "$2")
    FACET_DEMO_OUT=$(abspath "${3:-$ROOT/build/demo}")
    export FACET_DEMO_MESH FACET_DEMO_OUT
    mkdir -p "$FACET_DEMO_OUT"
    cd "$ROOT" && xvfb-run -a -s "-screen 0 $SCREEN" freecad tools/demo_freecad.py
    ;;
"")
    sed -n '4,18p' "$0" >&2
    exit 2
    ;;
*)
    "$@"
    ;;
esac
