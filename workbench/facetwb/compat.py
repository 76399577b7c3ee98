# SPDX-License-Identifier: LGPL-2.1-or-later
"""Differences between the FreeCAD versions Facet supports (0.20 and 1.x), in one place.

Everything else in ``facetwb`` imports version-dependent things from here.
"""

import FreeCAD as App

#: (major, minor) of the running FreeCAD, e.g. (0, 20) or (1, 0).
FREECAD_VERSION = tuple(int(part) for part in App.Version()[:2])

# Proxies: FreeCAD 0.21.2 and later serialise Python proxies through ``dumps``/``loads``,
# older versions through ``__getstate__``/``__setstate__``. Facet's proxies define both, so no
# flag is needed for it.

#: Attribute bits of ``addProperty`` (App::PropertyType in FreeCAD's Property.h).
PROP_READ_ONLY = 1
PROP_TRANSIENT = 2
PROP_HIDDEN = 4
PROP_OUTPUT = 8
PROP_NO_RECOMPUTE = 16

#: Editor modes of ``setEditorMode``.
EDITOR_NORMAL = 0
EDITOR_READ_ONLY = 1
EDITOR_HIDDEN = 2


def add_property(obj, type_name, name, group, doc, *, attr=0, editor_mode=EDITOR_NORMAL,
                 value=None):
    """Add a property to ``obj`` (a document or view object) unless it exists already.

    Idempotent, so ``init_properties()`` can run again on a restored document and only add
    what an older document lacks. Returns True when the property was added.
    """
    if name in obj.PropertiesList:
        return False
    # Positional arguments: the keyword names of addProperty changed between versions.
    obj.addProperty(type_name, name, group, doc, attr)
    if editor_mode != EDITOR_NORMAL:
        obj.setEditorMode(name, editor_mode)
    if value is not None:
        setattr(obj, name, value)
    return True


def qt_gui():
    """FreeCAD's Qt widgets module (PySide2 in 0.20, PySide6 in 1.x) through FreeCAD's shim.

    The shim's ``QtGui`` also carries the QtWidgets classes (QMessageBox, QFileDialog).
    """
    from PySide import QtGui  # FreeCAD's PySide shim, present in 0.20 and 1.x

    return QtGui
