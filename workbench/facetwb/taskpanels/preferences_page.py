# SPDX-License-Identifier: LGPL-2.1-or-later
"""Edit > Preferences > Facet: the defaults of the commands (resources/ui/preferences.ui).

InitGui.py registers :class:`PreferencesPage` with ``Gui.addPreferencePage``. The fields are
named after the preferences (facetwb.preferences.DEFAULTS); lengths in the user's units.
"""

from facetwb import preferences
from facetwb.taskpanels import forms


class PreferencesPage:
    """A FreeCAD preference page: ``form``, ``loadSettings``, ``saveSettings``."""

    def __init__(self, parent=None):
        self.form = forms.load("preferences")

    def loadSettings(self):  # noqa: N802 - FreeCAD's name
        for name in preferences.DEFAULTS:
            try:
                forms.widget(self.form, name)
            except KeyError:
                continue
            forms.set_value(self.form, name, preferences.get(name),
                            preferences.CHOICES.get(name))

    def saveSettings(self):  # noqa: N802 - FreeCAD's name
        import FreeCAD as App

        for name, (kind, _default) in preferences.DEFAULTS.items():
            try:
                forms.widget(self.form, name)
            except KeyError:
                continue
            try:
                value = forms.get_value(self.form, name, preferences.CHOICES.get(name),
                                        number=kind == "float")
            except ValueError as error:
                App.Console.PrintError(f"Facet preferences: {error}; kept the old value\n")
                continue
            preferences.set(name, value)
