# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet's user preferences, under ``User parameter:BaseApp/Preferences/Mod/Facet``.

The preferences page (resources/ui/preferences.ui, Edit > Preferences > Facet) writes them;
the commands and task panels read their defaults here. Every value has a default, so Facet
works with an empty parameter group. Lengths are stored in mm (FreeCAD's internal unit).
"""

import FreeCAD as App

from facet.nest import DEFAULT_MARGIN_MM, DEFAULT_SPACING_MM
from facet.panels import DEFAULT_GAP_MM

PATH = "User parameter:BaseApp/Preferences/Mod/Facet"

#: name -> (kind, default). Kinds: "float", "int", "bool", "string".
DEFAULTS = {
    # planarize
    "PlanarizeMethod": ("string", "auto"),
    "PlanarizeTolerance": ("float", 1e-6),
    "PlanarizeToleranceAbs": ("float", 0.0),
    "PlanarizeMaxIterations": ("int", 0),
    # surfaces to control meshes
    "SurfacePattern": ("string", "quad"),
    "SurfaceCountU": ("int", 10),
    "SurfaceCountV": ("int", 10),
    "SurfacePanelSize": ("float", 0.0),
    # panels
    "PanelThickness": ("float", 40.0),
    "PanelOffset": ("string", "outer"),
    "PanelGap": ("float", DEFAULT_GAP_MM),
    "PanelEdge": ("string", "square"),
    "PanelIdPrefix": ("string", "P-"),
    # cut sheets
    "SheetWidth": ("float", 3000.0),
    "SheetHeight": ("float", 1500.0),
    "SheetMargin": ("float", DEFAULT_MARGIN_MM),
    "SheetSpacing": ("float", DEFAULT_SPACING_MM),
    "SheetRotations": ("string", "90"),
    "SheetOutputDir": ("string", ""),
    "SheetTextOutlines": ("bool", False),
    # display
    "LegendMax": ("float", 0.0),
}

#: Choices of the string preferences that are enumerations (first: default).
CHOICES = {
    "PlanarizeMethod": ["auto", "lg", "ll"],
    "SurfacePattern": ["quad", "hex", "tri-quad"],
    "PanelOffset": ["outer", "inner", "center"],
    "PanelEdge": ["square", "bisector"],
    "SheetRotations": ["90", "none", "free"],
}


def group():
    return App.ParamGet(PATH)


def get(name):
    """The preference ``name`` (its default when unset or unusable)."""
    kind, default = DEFAULTS[name]
    params = group()
    if kind == "float":
        value = params.GetFloat(name, default)
    elif kind == "int":
        value = params.GetInt(name, default)
    elif kind == "bool":
        value = params.GetBool(name, default)
    else:
        value = params.GetString(name, default)
        if name in CHOICES and value not in CHOICES[name]:
            value = default
    if kind == "float" and not (value == value and abs(value) != float("inf")):
        value = default
    return value


def set(name, value):  # noqa: A001 - the counterpart of get
    """Store ``value`` as the preference ``name``."""
    kind, _default = DEFAULTS[name]
    params = group()
    if kind == "float":
        params.SetFloat(name, float(value))
    elif kind == "int":
        params.SetInt(name, int(value))
    elif kind == "bool":
        params.SetBool(name, bool(value))
    else:
        if name in CHOICES and value not in CHOICES[name]:
            raise ValueError(f"preference {name} must be one of {CHOICES[name]}, not {value!r}")
        params.SetString(name, str(value))


def reset():
    """Forget every Facet preference (back to the defaults)."""
    params = group()
    for name, (kind, _default) in DEFAULTS.items():
        remover = {"float": params.RemFloat, "int": params.RemInt, "bool": params.RemBool,
                   "string": params.RemString}[kind]
        remover(name)
