# SPDX-License-Identifier: LGPL-2.1-or-later
"""Reading and filling the widgets of Facet's .ui forms (resources/ui), by name.

A form's input widgets are named after what they set (an object property or a preference);
their kind follows from the widget class: Gui::QuantitySpinBox (a length in mm, shown in the
user's units), QSpinBox (int), QDoubleSpinBox (float), QLineEdit (text, or a number when the
default is a float), QComboBox (one of a list of choices, by index), QCheckBox (bool).
"""

import os

from facetwb import paths


def ui_path(name):
    """Absolute path of ``resources/ui/<name>.ui``."""
    return os.path.join(paths.resources_dir(), "ui", name + ".ui")


def load(name):
    """The QWidget of ``resources/ui/<name>.ui`` (FreeCAD's loader knows the Gui:: widgets)."""
    import FreeCADGui as Gui

    return Gui.PySideUic.loadUi(ui_path(name))


def widget(form, name):
    from facetwb.compat import qt_gui

    found = form.findChild(qt_gui().QWidget, name)
    if found is None:
        raise KeyError(f"form {form.objectName()} has no field {name}")
    return found


def _class(w):
    return w.metaObject().className()


def set_value(form, name, value, choices=None):
    """Show ``value`` in the field ``name`` (``choices``: the values of a combo box's items)."""
    w = widget(form, name)
    kind = _class(w)
    if kind == "Gui::QuantitySpinBox":
        w.setProperty("rawValue", float(value))
    elif kind == "QComboBox":
        w.setCurrentIndex(choices.index(value) if choices else int(value))
    elif kind == "QCheckBox":
        w.setChecked(bool(value))
    elif kind == "QLineEdit":
        w.setText(repr(value) if isinstance(value, float) else str(value))
    else:
        w.setValue(value)


def get_value(form, name, choices=None, number=False):
    """The value of the field ``name``; a ValueError names the field when it is unusable."""
    import math

    w = widget(form, name)
    kind = _class(w)
    if kind == "Gui::QuantitySpinBox":
        value = float(w.property("rawValue"))
    elif kind == "QComboBox":
        index = w.currentIndex()
        value = choices[index] if choices else index
    elif kind == "QCheckBox":
        value = w.isChecked()
    elif kind == "QLineEdit":
        value = w.text().strip()
        if number:
            try:
                value = float(value)
            except ValueError:
                raise ValueError(f"{label(form, name)}: {w.text()!r} is not a number") from None
    else:
        value = w.value()
    if isinstance(value, float) and not math.isfinite(value):
        raise ValueError(f"{label(form, name)} is not a finite number")
    return value


def label(form, name):
    """The text of the field's label (for messages), or its name."""
    from facetwb.compat import qt_gui

    found = form.findChild(qt_gui().QLabel, "label_" + name)
    return found.text() if found is not None else name


def elided(label, text, width=180):
    """``text`` shortened in the middle (with an ellipsis) to ``width`` pixels of ``label``'s
    font: a word that long cannot wrap, and would widen the task panel past its pane."""
    from PySide import QtCore

    return label.fontMetrics().elidedText(text, QtCore.Qt.ElideMiddle, width)


def on_change(form, name, callback):
    """Call ``callback`` when the user changes the field ``name`` (a line edit: when its
    editing finishes, not at every key)."""
    w = widget(form, name)
    kind = _class(w)
    if kind == "QComboBox":
        w.currentIndexChanged.connect(callback)
    elif kind == "QCheckBox":
        w.toggled.connect(callback)
    elif kind == "QLineEdit":
        w.editingFinished.connect(callback)
    else:  # QSpinBox, QDoubleSpinBox, Gui::QuantitySpinBox
        w.valueChanged.connect(callback)


def ok_cancel_buttons():
    """``getStandardButtons`` of a task panel with OK and Cancel."""
    from facetwb.compat import qt_gui

    buttons = qt_gui().QDialogButtonBox
    return int(buttons.Ok | buttons.Cancel)


def report_summary(obj, summary):
    """``summary`` (an object's summary text, e.g. ``planarize_summary(obj)``) in the report
    view when a task panel's OK makes or changes ``obj``: a message, an error when the
    object failed."""
    import FreeCAD as App

    printer = App.Console.PrintMessage if obj.isValid() else App.Console.PrintError
    printer(summary + "\n")
