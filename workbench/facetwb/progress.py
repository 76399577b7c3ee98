# SPDX-License-Identifier: LGPL-2.1-or-later
"""Progress and Cancel for recomputes that can take a while.

Document objects run their solver inside ``execute``, where no dialog can be passed in. A
command (or task panel) that starts a long recompute opens a :func:`reporting` context; the
objects' ``execute`` passes :func:`hook` to the ``facet`` functions as their ``progress``
callable. Headless, or with no context open, :func:`hook` is None and nothing is reported.

``facet`` progress callables get ``(done, total, ...)`` or ``(iteration, max_iterations,
planarity)``; both start with a count and its total, which is all this module reads. A
callable returning True cancels: the ``facet`` function raises ``facet.Cancelled``.

What the operation is doing now (a planarization re-solving for panel quality) goes in the
dialog's text through :func:`say_hook`; the bar keeps counting (the planarizer's count and
bound run on through its re-solves, so the bar never runs backwards).

Once the operation holds a result worth keeping (a planarization that reached its
tolerance and re-solves for panel quality) it calls the reporter's ``offer_keep()``
(:func:`hook`): the button then reads "Stop and keep". Pressed, the ``facet`` function
still raises ``facet.Cancelled``, with the result on it; the object keeps that result and
calls ``reporter.withdraw_keep(finished=True)``, so that the rest of the recompute runs
as if nothing had been pressed (``reporter.cancelled`` is False again).
"""

import contextlib

from facetwb.translation import translate

#: The active reporters (innermost last).
_stack = []


def hook():
    """The progress callable for ``facet`` functions, or None when nobody is listening: the
    innermost reporter (also its ``keeps``, ``offer_keep()`` and ``withdraw_keep()``)."""
    if not _stack:
        return None
    reporter = _stack[-1]
    return reporter


def say_hook():
    """``say(text)`` showing what the operation is doing now under the title (None: the
    title alone again), or None when nobody is listening."""
    return _stack[-1].say if _stack else None


@contextlib.contextmanager
def reporting(title, minimum_seconds=0.5):
    """Show ``title`` with a progress bar and a Cancel button (GUI) while the block runs.

    Yields the reporter; ``reporter.cancelled`` tells afterwards whether Cancel was pressed.
    Without the GUI the reporter only records the calls (scripts, tests).
    """
    reporter = _Reporter(title, minimum_seconds)
    _stack.append(reporter)
    try:
        yield reporter
    finally:
        _stack.remove(reporter)
        reporter.close()


@contextlib.contextmanager
def unless_reporting(title):
    """:func:`reporting` for a recompute that no command opened a reporter for (the property
    editor, Recompute, Ctrl+R, a live re-solve, an edit panel's OK): progress and Cancel
    there too. Inside a reporter already, or without the GUI, nothing is added.

    Yields the reporter, or None when none was opened.
    """
    import FreeCAD as App

    if _stack or not App.GuiUp:
        yield None
        return
    with reporting(title) as reporter:
        yield reporter


class _Reporter:
    """A progress callable backed by a QProgressDialog when the GUI is up."""

    def __init__(self, title, minimum_seconds):
        import FreeCAD as App

        self.title = title
        self.cancelled = False
        self.calls = 0
        self.dialog = None
        #: The dialog's text now, and every text shown (for scripts and tests).
        self.text = title
        self.texts = [title]
        #: The last call's count and total.
        self.done = self.total = 0
        #: For tests: cancel at this call number (0: never).
        self.cancel_at = _cancel_at
        #: True while the button reads "Stop and keep" (offer_keep).
        self.keeps = False
        if App.GuiUp:
            from facetwb.compat import qt_gui
            import FreeCADGui as Gui

            QtGui = qt_gui()
            self.dialog = QtGui.QProgressDialog(title, translate("Facet", "Cancel"), 0, 1000,
                                                Gui.getMainWindow())
            self.dialog.setWindowTitle("Facet")
            self.dialog.setMinimumDuration(int(1000 * minimum_seconds))
            # nothing else in the window while it runs: an edit made during a recompute
            # would be lost (the object's Touched mark is cleared when it ends)
            from PySide import QtCore

            self.dialog.setWindowModality(QtCore.Qt.WindowModal)
            self.dialog.setAutoClose(False)
            self.dialog.setAutoReset(False)
            self.dialog.setValue(0)

    def __call__(self, done=0, total=0, *rest):
        self.calls += 1
        self.done, self.total = done, total
        if self.cancel_at and self.calls >= self.cancel_at:
            self.cancelled = True
        if self.dialog is not None:
            try:
                fraction = float(done) / float(total) if total else None
            except (TypeError, ValueError, ZeroDivisionError):
                fraction = None
            if fraction is None:
                # no total: a busy bar (it moves while the operation calls), not 0%
                if self.dialog.maximum() != 0:
                    self.dialog.setRange(0, 0)
                self.dialog.setValue(0)
            else:
                if self.dialog.maximum() == 0:
                    self.dialog.setRange(0, 1000)
                self.dialog.setValue(int(1000 * min(max(fraction, 0.0), 1.0)))
        return self._pressed()

    def say(self, text=None):
        """Show ``text`` (what the operation does now) below the title; None: the title alone."""
        self.text = self.title if not text else f"{self.title}\n{text}"
        self.texts.append(self.text)
        if self.dialog is not None:
            self.dialog.setLabelText(self.text)
            self._events()

    def offer_keep(self):
        """The operation holds a result it would keep if stopped now: the button says so.
        A press of Cancel not yet seen is a Cancel (it is seen first)."""
        if self._pressed():
            return
        self.keeps = True
        self._button(translate("Facet", "Stop and keep"),
                     translate("Facet", "Stop here and keep the result that reached the tolerance"))

    def withdraw_keep(self, finished):
        """The operation that offered to keep is over: the button is Cancel again. When it
        `finished` with a result (the one kept after a press of Stop and keep, or its
        complete one, the press not yet seen), the press is spent: the rest of the recompute
        is not cancelled (the dialog shows again, with Cancel, if the rest takes long)."""
        if self.keeps:
            if self._pressed() and finished:
                self.cancelled = False
                self.cancel_at = 0
                if self.dialog is not None:
                    self.dialog.reset()
            self._button(translate("Facet", "Cancel"), "")
        self.keeps = False

    def _pressed(self):
        """Whether the operation is cancelled: the button pressed (events handled first) or
        ``cancel_at`` reached; sets ``cancelled``."""
        if self.dialog is not None:
            self._events()
            if self.dialog.wasCanceled():
                self.cancelled = True
        return self.cancelled

    def _events(self):
        """Let Qt draw and time: the dialog, once shown (modal), takes the clicks and keys;
        before it shows (``minimum_seconds``) no click or key is handled, so none reaches
        the document while it recomputes."""
        from PySide import QtCore

        from facetwb.compat import qt_gui

        if self.dialog.isVisible():
            qt_gui().QApplication.processEvents()
        else:
            qt_gui().QApplication.processEvents(QtCore.QEventLoop.ExcludeUserInputEvents)

    def _button(self, text, tip):
        if self.dialog is not None:
            from facetwb.compat import qt_gui

            self.dialog.setCancelButtonText(text)
            button = self.dialog.findChild(qt_gui().QPushButton)
            if button is not None:
                button.setToolTip(tip)

    def close(self):
        if self.dialog is not None:
            self.dialog.close()
            self.dialog.deleteLater()
            self.dialog = None


#: Tests set this to make the next reporters cancel at the given call (0: never).
_cancel_at = 0


def cancel_after(calls):
    """Make every reporter opened from now on cancel at its ``calls``-th progress call
    (0 turns it off). For tests of Cancel without a person pressing it."""
    global _cancel_at
    _cancel_at = int(calls)
