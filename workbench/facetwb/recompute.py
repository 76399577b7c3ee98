# SPDX-License-Identifier: LGPL-2.1-or-later
"""One line in the report view when a Facet object cannot recompute.

FreeCAD 0.20 reports an exception raised by a scripted object's ``execute`` with the
whole Python traceback, although a bad input (a NaN in a file, a plan with no bounded
face, a panel thickness of 0) is not a bug and its message already says everything::

    Facet: Plan: roof.csv: the drawing has no bounded face (3 dangling edges)

:func:`guarded` wraps ``execute`` methods: a bad-input error (``facet.FacetError``, which
includes ``InputError`` and ``Cancelled``, a ``ValueError`` naming the object, an
``OSError`` of a file) is raised again as :class:`RecomputeError` with that one line; the
object is left in FreeCAD's error state with its previous shape and results (every
``execute`` computes first and assigns last), and ``obj.getStatusString()`` is the line.
Any other exception is a bug and keeps its traceback.

How the traceback is left out: FreeCAD formats the error with ``str(type(error))`` and then
``PyTraceBack_Print``, which prints nothing while ``sys.tracebacklimit`` is 0. The
metaclass of :class:`RecomputeError` sets it to 0 when FreeCAD asks for the type's name
(only FreeCAD's error report does that), and it is put back as it was when the document
finishes recomputing (a document observer) or when the next Facet object recomputes,
whichever comes first. Nothing else in FreeCAD is changed.
"""

import functools
import sys

from facetwb import progress
from facetwb.translation import translate

__all__ = ["RecomputeError", "Recomputes", "after_recompute", "after_undo", "cancel_live_edit",
           "failure", "guarded", "keep_up_to_date", "observe_documents", "one_line",
           "up_to_date"]

_saved_limit = []
_observer = []
_after = []  # (document name, action) to run once that document has recomputed
_recorders = []  # the open Recomputes
_undo_actions = []  # action(doc) to run after each undo or redo of a document


def _restore_traceback_limit():
    while _saved_limit:
        value = _saved_limit.pop()
        if value is None:
            if hasattr(sys, "tracebacklimit"):
                del sys.tracebacklimit
        else:
            sys.tracebacklimit = value


class _DocumentObserver:
    def slotRecomputedDocument(self, doc):  # noqa: N802 - FreeCAD's name
        _restore_traceback_limit()
        _run_after(doc)

    def slotUndoDocument(self, doc):  # noqa: N802 - FreeCAD's name
        _run_undo_actions(doc)

    def slotRedoDocument(self, doc):  # noqa: N802
        _run_undo_actions(doc)

    def slotChangedObject(self, obj, prop):  # noqa: N802
        if prop == "Mesh":
            _mesh_replaced(obj)

    def slotRecomputedObject(self, obj):  # noqa: N802
        doc = getattr(getattr(obj, "Document", None), "Name", None)
        for recorder in _recorders:
            if recorder.doc_name == doc:
                recorder.names.add(obj.Name)


def _run_after(doc):
    name = getattr(doc, "Name", None)
    due = [action for owner, action in _after if owner == name]
    _after[:] = [(owner, action) for owner, action in _after if owner != name]
    for action in due:
        try:
            action()
        except Exception as error:  # noqa: BLE001 - one failed action must not stop the rest
            import FreeCAD as App

            App.Console.PrintError(f"Facet: after recomputing {name}: {error}\n")


def _mesh_replaced(obj):
    """A FreeCAD Mesh whose mesh was replaced outside a recompute (a script, a Mesh
    workbench repair, an undo): FreeCAD marks neither it (its Mesh is an output property)
    nor what is made from it, and the Facet objects made from it stayed up to date with
    the old mesh's results, a recompute changing nothing. They are marked now."""
    doc = getattr(obj, "Document", None)
    if (doc is None or getattr(doc, "Recomputing", False) or getattr(doc, "Restoring", False)
            or not obj.isDerivedFrom("Mesh::Feature")):
        return
    for user in obj.InList:
        if (str(getattr(getattr(user, "Proxy", None), "Type", "")).startswith("Facet::")
                and "Touched" not in user.State):
            user.touch()


def observe_documents():
    """Start the workbench's document observer (once): Facet objects call it when they
    are made or restored, so that what it follows is followed from then on."""
    _observe()


def after_undo(action):
    """Run ``action(doc)`` after each undo and redo of any document, once the properties
    are put back (FreeCAD's ``signalUndo``, ``signalRedo``); an action given again is
    still run once."""
    if action not in _undo_actions:
        _undo_actions.append(action)
    _observe()


def _run_undo_actions(doc):
    for action in list(_undo_actions):
        try:
            action(doc)
        except Exception as error:  # noqa: BLE001 - one failed action must not stop the rest
            import FreeCAD as App

            App.Console.PrintError(f"Facet: after undo in {getattr(doc, 'Name', doc)}: "
                                   f"{error}\n")


def up_to_date(objects):
    """The names of those of ``objects`` not marked for recompute: what a task panel's
    Cancel, which puts the same result back, leaves up to date (:func:`keep_up_to_date`)."""
    return [o.Name for o in objects if "Touched" not in o.State]


class Recomputes:
    """The names of the objects of ``doc`` recomputed from now on (``names``), until
    :meth:`stop`: a task panel's, whose Cancel recomputes again what a Recompute pressed
    while it was open built from the values it takes back (:func:`keep_up_to_date`)."""

    def __init__(self, doc):
        self.doc_name = doc.Name
        self.names = set()
        _observe()
        _recorders.append(self)

    def take(self):
        """The names recorded so far; the record starts again empty."""
        names, self.names = self.names, set()
        return names

    def stop(self):
        if self in _recorders:
            _recorders.remove(self)


def keep_up_to_date(doc, names, recomputed=()):
    """After a task panel's Cancel: unmark the objects ``names`` (:func:`up_to_date`'s) that
    the panel's live re-solves marked: they stayed marked for a Recompute that would have
    rebuilt the panels and rewritten the cut files for nothing. Those of them in
    ``recomputed`` (a Recompute pressed while the panel was open rebuilt them, and wrote
    their files, from the values Cancel took back) are recomputed again; the others of
    ``recomputed`` (marked when the panel opened) are marked again."""
    again = []
    for name in sorted(set(names) | set(recomputed)):
        obj = doc.getObject(name)
        if obj is None:
            continue
        if name in recomputed:
            obj.touch()
            if name in names:
                again.append(obj)
        elif "Touched" in obj.State:
            obj.purgeTouched()
    if again:
        doc.recompute(again)


def cancel_live_edit(doc, obj, fresh, recomputes, restore=None, solve_again=True):
    """A task panel's Cancel, whose changes to ``obj`` were re-solved live (``obj`` alone)
    in a transaction open on ``doc``: abort it (the previous values and result),
    ``restore()`` (if given: what the transaction did not put back; True when it set
    anything), re-solve ``obj`` alone when that set values, when ``obj`` is left in error
    or, with ``solve_again``, when it is marked (an object whose proxy keeps what a
    transaction does not put back); then :func:`keep_up_to_date` with ``fresh`` (the
    names that were up to date when the panel opened) and what a Recompute pressed
    meanwhile rebuilt from ``obj`` (``recomputes``, a :class:`Recomputes` started with the
    panel). What is made from ``obj`` is not recomputed otherwise: a document recompute
    here rebuilt the panels, and rewrote cut sheets' files, made from the result Cancel
    puts back. Without ``solve_again`` the result the transaction put back is kept as it
    is: solved again, it came out different in its last digits."""
    rebuilt = recomputes.take() & {o.Name for o in obj.InListRecursive}
    doc.abortTransaction()
    changed = bool(restore()) if restore is not None else False
    if changed or not obj.isValid() or (solve_again and "Touched" in obj.State):
        doc.recompute([obj])
    keep_up_to_date(doc, fresh, rebuilt - recomputes.take())


def after_recompute(doc, action):
    """Run ``action()`` once ``doc`` has finished recomputing, or now when it is not
    recomputing (an ``execute`` called by ``obj.recompute()``).

    For removing objects from an ``execute``: FreeCAD 0.20 defers a ``removeObject`` made
    while the document recomputes and keeps the name on its list afterwards, so that an
    object made later under the same name is removed at the end of every recompute that
    follows (fixed in FreeCAD 0.21). Removed after the recompute, the name stays free."""
    if not getattr(doc, "Recomputing", False):
        action()
        return
    _observe()
    _after.append((doc.Name, action))


def _observe():
    if _observer:
        return
    try:
        import FreeCAD as App

        observer = _DocumentObserver()
        App.addDocumentObserver(observer)
        _observer.append(observer)
    except Exception:  # noqa: BLE001 - without the observer the next execute restores
        pass


class _OneLineType(type):
    def __str__(cls):
        if not _saved_limit:
            _saved_limit.append(getattr(sys, "tracebacklimit", None))
        sys.tracebacklimit = 0
        return "Facet"


class RecomputeError(Exception, metaclass=_OneLineType):
    """A Facet object could not recompute because of its input; ``str()`` is one line."""


#: What counts as bad input (one line, no traceback); anything else is a bug.
def _expected():
    import facet.errors

    return (facet.errors.FacetError, ValueError, OSError)


def one_line(obj, error):
    """The report-view line for ``error`` raised while recomputing ``obj``."""
    if isinstance(error, OSError) and error.strerror:
        text = f"{error.filename}: {error.strerror}" if error.filename else error.strerror
    else:
        text = str(error) or type(error).__name__
    return _named(obj, text)


def _named(obj, text):
    """`text` on one line, starting with the object's label (once)."""
    text = " ".join(text.split())
    label = getattr(obj, "Label", "")
    if label and not text.startswith(label + ":"):
        text = f"{label}: {text}"
    return text


def failure(obj):
    """The one line of an object in FreeCAD's error state: its status string, which names
    the object (:func:`one_line`), or the label then FreeCAD's own status."""
    return _named(obj, obj.getStatusString())


def guarded(execute):
    """Decorate a proxy's ``execute(self, obj)`` (see the module's docstring)."""

    @functools.wraps(execute)
    def wrapper(self, obj):
        _restore_traceback_limit()
        _observe()
        try:
            # a long recompute that no command reports on gets a dialog with Cancel too
            with progress.unless_reporting(translate("Facet", "Recomputing {0} ...").format(
                    obj.Label)):
                return execute(self, obj)
        except _expected() as error:
            if isinstance(error, RecomputeError):
                raise
            raise RecomputeError(one_line(obj, error)) from None

    return wrapper
