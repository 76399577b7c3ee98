# SPDX-License-Identifier: LGPL-2.1-or-later
"""Live parameters: a Planarized object re-solves shortly after one of its solver
parameters changes (property editor, task panel or Python), without pressing Recompute.

The view provider calls :func:`parameter_changed` from ``updateData``; changes within
:data:`DELAY_MS` of each other are merged into one recompute of that object (debounced, so
typing a number or spinning a box solves once). While an edit session (edit_control) runs
on the object, the session re-solves its edited control mesh with the new parameters
instead, and the document is left alone until Done. GUI only: without a GUI nothing is
scheduled and recompute works as usual.
"""

import FreeCAD as App

from facetwb.objects.planarized import TERM_WEIGHTS

#: Properties of a Planarized object whose change re-solves it.
PARAMETERS = frozenset(
    ["Method", "Tolerance", "ToleranceAbs", "MaxIterations", "Threads", "Data", "Reference",
     "Boundary", "FixedVertices", "FaceWeights", "Shape", "ShapeWeight", "Anderson",
     "TimeBudget"] + [name for name, _option, _tip in TERM_WEIGHTS])

#: Quiet time after the last change before the solve starts, milliseconds.
DELAY_MS = 400

#: Switch for scripts that set many properties and recompute themselves.
ENABLED = True

_timers = {}  # (document name, object name) -> QTimer
_late = set()  # keys whose change came while their document recomputed


def parameter_changed(obj, prop):
    """Schedule a live re-solve of ``obj`` if ``prop`` is one of its solver parameters."""
    if not ENABLED or prop not in PARAMETERS or not App.GuiUp:
        return
    doc = getattr(obj, "Document", None)
    if doc is None or getattr(doc, "Restoring", False):
        return
    key = (doc.Name, obj.Name)
    if getattr(doc, "Recomputing", False) and not _bound(obj, prop):
        # a change made while the document recomputes: solved after it, even though the
        # recompute clears the object's Touched mark when it ends. (Not an expression's
        # value: the object's recompute sets it just before it solves, and a Tolerance
        # bound to a spreadsheet cell was solved a second time after each change.)
        _late.add(key)
    _schedule(key)


def _bound(obj, prop):
    """Whether ``obj``'s property ``prop`` is set by an expression."""
    return any(path.lstrip(".").split(".")[0] == prop
               for path, _expression in getattr(obj, "ExpressionEngine", None) or ())


def resolve_if_touched(obj):
    """Schedule the live re-solve of ``obj`` if a parameter changed and it was not solved
    since: an "Edit control mesh" session takes the changes made while it runs and solves
    them itself, and left them unsolved when it ended without a moved vertex."""
    doc = getattr(obj, "Document", None)
    if ENABLED and App.GuiUp and doc is not None and "Touched" in obj.State:
        _schedule((doc.Name, obj.Name))


def _schedule(key):
    from PySide import QtCore

    timer = _timers.get(key)
    if timer is None:
        timer = QtCore.QTimer()
        timer.setSingleShot(True)
        timer.timeout.connect(lambda key=key: _fire(key))
        _timers[key] = timer
    timer.start(DELAY_MS)


def forget(obj):
    """Drop the scheduled re-solve of ``obj``: a task panel's Cancel put its values back
    and solved them itself (a re-solve starting while a later recompute showed its
    progress dialog would solve them again and mark what is made from it)."""
    doc = getattr(obj, "Document", None)
    if doc is None:
        return
    key = (doc.Name, obj.Name)
    timer = _timers.pop(key, None)
    if timer is not None:
        timer.stop()
    _late.discard(key)


def pending():
    """Number of scheduled re-solves (tests)."""
    return sum(1 for timer in _timers.values() if timer.isActive())


def _fire(key):
    _timers.pop(key, None)
    doc = App.listDocuments().get(key[0])
    obj = doc.getObject(key[1]) if doc is not None else None
    if obj is None or getattr(doc, "Restoring", False):
        return
    if getattr(doc, "Recomputing", False):
        # (after it: a change made before it is solved by it, one made during it is late)
        _schedule(key)
        return
    if key in _late:
        _late.discard(key)
        obj.touch()
    from facetwb import edit_control

    session = edit_control.active_session()
    if session is not None and session.planarized is obj:
        session.reconfigure()
        return
    if "Touched" not in obj.State:  # recomputed meanwhile
        return
    try:
        doc.recompute([obj])  # this object (and what it needs); clears its Touched mark
    except Exception as exc:  # noqa: BLE001 - one line in the report view
        App.Console.PrintError(f"Facet: {obj.Label}: live update failed: {exc}\n")
