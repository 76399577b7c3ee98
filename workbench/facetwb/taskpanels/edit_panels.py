# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel of an existing Planarized object (double-click it, or Edit in its context menu).

The Planarize form, filled from the object's properties. Every change of a field is set on
the object at once, and :mod:`facetwb.live_parameters` re-solves it shortly after (debounced),
so the planar result follows while the designer types or spins a box. All of it is one
transaction: OK keeps the changes as one undo step, Cancel puts the previous values and the
previous result back. Wiring only.
"""

import FreeCAD as App
import FreeCADGui as Gui

from facetwb.taskpanels import forms
from facetwb.objects.planarized import METHODS
from facetwb.recompute import keep_up_to_date, up_to_date
from facetwb.taskpanels.derive_panels import check_planarize
from facetwb.translation import QT_TRANSLATE_NOOP, translate

#: The open panel, if any (for scripts and the GUI test).
active = None

TITLE = QT_TRANSLATE_NOOP("Facet", "Planarize")

#: (field of planarize.ui = property of the object, choices of a combo box)
FIELDS = (("Method", METHODS), ("Tolerance", None), ("ToleranceAbs", None),
          ("MaxIterations", None))


def _property_value(obj, name):
    value = getattr(obj, name)
    return value.Value if hasattr(value, "Value") else value


class PlanarizeEditPanel:
    """The solver parameters of one Planarized object, applied live."""

    def __init__(self, obj):
        global active
        self.obj = obj
        self.doc = obj.Document
        self.form = forms.load("planarize")
        # the object's name in the note, which wraps: in the title (which does not) a label
        # such as "Control mesh planarized" widened the panel past the task pane, its
        # fields cut off at the right
        self.form.setWindowTitle(translate("Facet", TITLE))
        note = forms.widget(self.form, "note")
        note.setText(translate(
            "Facet", "{0}: every change re-solves it at once. OK keeps the changes in one "
                     "undo step; Cancel puts the previous values and result back.").format(
            forms.elided(note, obj.Label)))
        for name, choices in FIELDS:
            forms.set_value(self.form, name, _property_value(obj, name), choices)
        # what is made from the result (panels, cut sheets) and up to date now: a live
        # re-solve touches it, and Cancel, which puts the same result back, leaves it so
        self.fresh = up_to_date(obj.InListRecursive)
        self.doc.openTransaction(f"Edit {obj.Label}")
        for name, _choices in FIELDS:
            forms.on_change(self.form, name, self.changed)
        active = self

    def read(self):
        """{property: value} from the fields; a ValueError names a field that cannot work."""
        values = {name: forms.get_value(self.form, name, choices, name == "Tolerance")
                  for name, choices in FIELDS}
        check_planarize(values)
        return values

    def changed(self, *_args):
        """Set the fields' values on the object (the object then re-solves by itself)."""
        try:
            values = self.read()
        except ValueError as error:
            self.show_message(str(error))
            return False
        self.show_message("")
        for name, value in values.items():
            if _property_value(self.obj, name) != value:
                setattr(self.obj, name, value)
        return True

    def show_message(self, text):
        forms.widget(self.form, "message").setText(text)

    # --- Gui.Control ---------------------------------------------------------------------

    def accept(self):
        if not self.changed():
            return False
        if "Touched" in self.obj.State:
            self.doc.recompute([self.obj])
        self.doc.commitTransaction()
        self._close()
        return True

    def reject(self):
        self.doc.abortTransaction()  # the previous values, points and planarity
        if "Touched" in self.obj.State:
            self.doc.recompute([self.obj])
        # the result is the one they were made from: they are up to date again
        keep_up_to_date(self.doc, self.fresh)
        self._close()
        return True

    def _close(self):
        global active
        active = None
        if Gui.ActiveDocument is not None:
            Gui.ActiveDocument.resetEdit()
        Gui.Control.closeDialog()

    def getStandardButtons(self):
        return forms.ok_cancel_buttons()


def edit(obj):
    """Open the panel of ``obj`` (a view provider's setEdit). True when it opened."""
    if Gui.Control.activeDialog():
        App.Console.PrintWarning(f"Facet: {obj.Label}: close the open task panel first\n")
        return False
    Gui.Control.showDialog(PlanarizeEditPanel(obj))
    return True
