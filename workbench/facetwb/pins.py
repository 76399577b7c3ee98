# SPDX-License-Identifier: LGPL-2.1-or-later
"""Pinned heights picked in the 3D view: selected plan vertices to a Lifting's
``PinnedPoints`` (x, y of the vertex, z its height). Runs headless: the selection comes in
as ``[(object, [sub-element names]), ...]`` (what ``Gui.Selection.getSelectionEx`` gives).

A vertex is picked on the PlanGraph (or any Facet plan mesh) or on a Lifting of it; the
view providers of both name the element near the click ``Vertex<n>`` (n counted from 0, as
the Shape lifting panel and the Lifting's ``TargetMaxVertex`` count). Anything else (a face,
an edge, another object, an object picked in the tree) is refused with a message saying
what to click (``facetwb.picked``). Wiring only: finding a pin's vertex is
``facet.plan.pin_vertices``.
"""

import math

from facet.plan import COORDINATE_MAX, match_tolerance, pin_vertices
from facetwb.picked import PickError, mesh_vertex_count, picked_vertices
from facetwb.translation import translate


class PinError(PickError):
    """The selection or a height cannot be pinned (one line saying what to do)."""


def plan_of(obj):
    """The plan a Lifting lifts, or ``obj`` itself (a PlanGraph or Facet mesh)."""
    from facetwb.objects.lifting import is_lifting

    return obj.Plan if is_lifting(obj) else obj


def _shows_plan(obj, plan):
    """True when the vertices of ``obj`` are the vertices of ``plan``: the plan itself or a
    Lifting of it."""
    return obj is plan or plan_of(obj) is plan


def selected_vertices(entries, plan):
    """The plan vertices selected in ``entries`` (``[(object, [sub-element names])]``), in
    the order picked, each once: vertices of ``plan`` (the plan the pins are for) or of a
    Lifting of it. A PinError says what is wrong with the first entry that is not."""
    return picked_vertices(entries, plan, mesh_vertex_count(plan),
                           lambda obj: _shows_plan(obj, plan), PinError)


def check_height(height, what=None):
    """``height`` as a float (mm); a PinError when it is not a usable number. ``what``
    names it in the message (default "Height")."""
    what = translate("Facet", "Height") if what is None else what
    try:
        value = float(height)
    except (TypeError, ValueError):
        raise PinError(translate("Facet", "{0}: {1} is not a number of mm").format(
            what, repr(height))) from None
    if not (math.isfinite(value) and abs(value) <= COORDINATE_MAX):
        raise PinError(translate("Facet", "{0}: {1} mm is not a finite height up to {2} mm")
                       .format(what, repr(value), f"{COORDINATE_MAX:g}"))
    return value


def height_from_text(text, what=None):
    """The height in mm of ``text`` typed in the table of pins: a length ("2.4 m", "2400
    mm") or a bare number of mm. A PinError for anything else: not a number, or a quantity
    of another kind ("2.4 kg", "3 m^2" were taken as 2.4 and 3,000,000 mm)."""
    import FreeCAD as App

    try:
        quantity = App.Units.Quantity(str(text))
    except (ValueError, RuntimeError, TypeError):
        return check_height(str(text), what)
    if quantity.Unit not in (App.Units.Length, App.Units.Unit()):
        what = translate("Facet", "Height") if what is None else what
        raise PinError(translate("Facet", "{0}: {1} is not a length (a number of mm, or "
                                          "with a length unit: 2.4 m)").format(what,
                                                                              repr(str(text))))
    return check_height(quantity.Value, what)


def pins_vertices(plan_mesh, pins, snap=0.0):
    """The plan vertex of each pin (x, y, z): a list of ints, -1 for a pin at no vertex."""
    tolerance = match_tolerance(plan_mesh, snap)
    return [int(v) for v in pin_vertices(plan_mesh, [p[:2] for p in pins],
                                         tolerance=tolerance)]


def pin(plan_mesh, pins, vertices, height, snap=0.0):
    """``pins`` (list of (x, y, z)) with ``vertices`` pinned at ``height`` mm: a pin already
    at one of them takes the new height (in its place), the others are appended in order.
    Returns the new list; ``pins`` is not changed."""
    height = check_height(height)
    pins = [tuple(float(c) for c in p) for p in pins]
    at = pins_vertices(plan_mesh, pins, snap)
    xy = plan_mesh.vertices[:, :2]
    for v in vertices:
        if v in at:
            k = at.index(v)
            pins[k] = (pins[k][0], pins[k][1], height)
        else:
            pins.append((float(xy[v, 0]), float(xy[v, 1]), height))
            at.append(v)
    return pins

