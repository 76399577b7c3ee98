# SPDX-License-Identifier: LGPL-2.1-or-later
"""Lengths in Facet's messages as the designer's FreeCAD shows them: in the unit its unit
schema (Edit > Preferences > General > Units) picks, not in raw millimetres. A designer in
inches read "narrowest joint 1.178 mm" beside a property editor that said "0.05 in"."""

import FreeCAD as App

#: The units an imperial schema shows lengths in (FreeCAD's symbols: US customary writes
#: inches '"' and feet "'").
IMPERIAL_UNITS = ("in", '"', "ft", "'", "yd", "thou", "mi")

#: The symbols messages write for FreeCAD's ('"' after a number in a sentence reads as a
#: closing quote).
_SYMBOLS = {'"': "in", "'": "ft"}


def user_unit(mm):
    """(mm per unit, unit symbol) of the unit the schema shows a length of ``mm`` in:
    (25.4, "in"), (1000.0, "m")."""
    _, factor, unit = App.Units.Quantity(float(mm), App.Units.Length).getUserPreferred()
    return float(factor), _SYMBOLS.get(unit, unit)


def imperial():
    """True when the schema shows lengths in inches, feet or yards (US customary, Imperial
    decimal, Building US, Imperial for Civil Eng)."""
    return user_unit(1000.0)[1] in IMPERIAL_UNITS


def length_text(mm, digits=3):
    """A length (``mm`` millimetres) in the unit the schema shows it in, to ``digits``
    significant digits: "0.0197 in", "1.18 mm", "12.2 m". Not the schema's own UserString,
    which has a fixed count of decimals (Imperial decimal's "0.02 in" of 0.5 mm) or
    Building US's eighths of an inch (its "0" of 0.5 mm)."""
    mm = float(mm)
    factor, unit = user_unit(abs(mm) if mm else 1.0)
    return f"{mm / factor:.{digits}g} {unit}"
