# SPDX-License-Identifier: LGPL-2.1-or-later
"""Facet's strings for translation: QT_TRANSLATE_NOOP marks them (pylupdate5 collects them
into resources/translations/Facet.ts, see ``make translations``), ``translate`` looks them up.
Command names are the contexts of their menu texts and tooltips, as in FreeCAD's workbenches.
"""


def QT_TRANSLATE_NOOP(context, text):  # noqa: N802 - Qt's name, which pylupdate5 looks for
    """Mark ``text`` for translation in ``context``; FreeCAD translates it when shown."""
    return text


def translate(context, text):
    """``text`` translated in ``context`` (itself without the GUI)."""
    try:
        from PySide import QtCore

        return QtCore.QCoreApplication.translate(context, text)
    except Exception:  # noqa: BLE001 - headless or no Qt: the source string
        return text
