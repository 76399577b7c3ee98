# SPDX-License-Identifier: LGPL-2.1-or-later
"""Where Facet's resources (icons) are, in a checkout and in an installed Mod folder.

Layouts this finds (``facetwb`` is the directory of this package):

- checkout or Addon Manager clone: ``<root>/workbench/facetwb`` and ``<root>/resources``;
- flat install: ``Mod/Facet/facetwb`` and ``Mod/Facet/resources``.

Symlinks are resolved first, so a checkout linked into a user Mod folder works too.
"""

import os

_PACKAGE_DIR = os.path.dirname(os.path.realpath(__file__))
_WORKBENCH_DIR = os.path.dirname(_PACKAGE_DIR)


def resources_dir():
    """The ``resources`` directory, or the first candidate if none exists."""
    candidates = [
        os.path.join(_WORKBENCH_DIR, "resources"),
        os.path.join(os.path.dirname(_WORKBENCH_DIR), "resources"),
    ]
    for candidate in candidates:
        if os.path.isdir(candidate):
            return candidate
    return candidates[0]


def icon_path(name):
    """Absolute path of ``resources/icons/<name>.svg`` (commands share their icon's name)."""
    return os.path.join(resources_dir(), "icons", name + ".svg")
