#!/bin/sh
# SPDX-License-Identifier: LGPL-2.1-or-later
# Installs the Facet workbench into FreeCAD's user Mod folders (0.20:
# ~/.FreeCAD/Mod, 1.x: ~/.local/share/FreeCAD/Mod) in the repository's own
# layout, as the Addon Manager would: Mod/Facet/{package.xml, LICENSE,
# workbench/, resources/} (FreeCAD reads package.xml and loads workbench/),
# and a `facet` command in PREFIX/bin that runs `python3 -m facet` with
# FreeCAD's Python.
#
#   tools/install.sh PREFIX PYTHON        install (after `make`)
#   tools/install.sh --uninstall PREFIX   remove what install put there
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
mods="$HOME/.FreeCAD/Mod ${XDG_DATA_HOME:-$HOME/.local/share}/FreeCAD/Mod"

if [ "${1:-}" = "--uninstall" ]; then
    prefix=$2
    for mod in $mods; do rm -rf "$mod/Facet"; done
    rm -f "$prefix/bin/facet"
    echo "facet: removed Mod/Facet and $prefix/bin/facet"
    exit 0
fi

prefix=$1
python=$2
if ! ls "$root"/workbench/facet/_core*.so >/dev/null 2>&1; then
    echo "facet: the compiled core is not built; run 'make' first" >&2
    exit 1
fi
for mod in $mods; do
    target="$mod/Facet"
    rm -rf "$target.new"
    mkdir -p "$target.new"
    cp -R "$root/workbench" "$target.new/workbench"
    cp -R "$root/resources" "$target.new/resources"
    cp "$root/package.xml" "$root/LICENSE" "$root/README.md" "$target.new/"
    find "$target.new" -name __pycache__ -type d -prune -exec rm -rf {} +
    rm -rf "$target"
    mv "$target.new" "$target"
    echo "facet: workbench installed in $target"
done
first_mod=$(echo "$mods" | awk '{print $1}')
mkdir -p "$prefix/bin"
cat > "$prefix/bin/facet" <<EOS
#!/bin/sh
# Facet's command line (installed by make install)
PYTHONPATH="$first_mod/Facet/workbench\${PYTHONPATH:+:\$PYTHONPATH}" exec "$python" -m facet "\$@"
EOS
chmod +x "$prefix/bin/facet"
echo "facet: command installed as $prefix/bin/facet"
case ":$PATH:" in *":$prefix/bin:"*) ;; *) echo "facet: add $prefix/bin to PATH to run 'facet'" ;; esac
