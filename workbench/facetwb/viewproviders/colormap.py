# SPDX-License-Identifier: LGPL-2.1-or-later
"""The planarity colour map: face planarity (a length) to RGB, blue (flat) to red (worst).

The same stops colour the faces and the legend's bar, so they always agree.
"""

import numpy as np

#: (position in [0, 1], RGB) stops, interpolated linearly: FreeCAD's colour bar order
#: (blue, cyan, green, yellow, red), slightly softened so dark edges stay visible on it.
STOPS = (
    (0.00, (0.15, 0.30, 0.85)),
    (0.25, (0.15, 0.75, 0.90)),
    (0.50, (0.30, 0.80, 0.30)),
    (0.75, (0.95, 0.85, 0.20)),
    (1.00, (0.85, 0.15, 0.10)),
)

#: Faces without a value (the mesh and its planarity disagree while they are being updated).
NO_VALUE = (0.6, 0.6, 0.6)


def colors(values, vmax, reverse=False):
    """RGB rows (n, 3) for ``values`` on the scale 0 .. ``vmax`` (values beyond clip).

    ``reverse``: small values get the top colour (red), for measures where small is bad
    (smallest angle)."""
    values = np.asarray(values, dtype=np.float64)
    scale = vmax if vmax > 0.0 else 1.0
    t = np.clip(np.nan_to_num(values, nan=0.0) / scale, 0.0, 1.0)
    if reverse:
        t = 1.0 - t
    positions = np.array([stop[0] for stop in STOPS])
    rgb = np.array([stop[1] for stop in STOPS])
    return np.stack([np.interp(t, positions, rgb[:, k]) for k in range(3)], axis=1)


def stop_colors():
    """The ``(position, RGB)`` stops, for drawing the legend's bar."""
    return STOPS
