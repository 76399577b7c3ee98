# SPDX-License-Identifier: LGPL-2.1-or-later
"""The progress line of ``facet planarize`` on a terminal.

One line on stderr, rewritten in place (carriage return), at most every ``interval``
seconds::

    facet planarize: iteration 120 of at most 8000, planarity 3.2e-05
    facet planarize: re-solving for panel quality (stage 1 of 4): iteration 300 of at most 7154, ...

and erased before the summary is printed. The planarizer's count and bound run on through
its quality re-solves, so the numbers never run backwards. Not a terminal (a pipe, a file,
a test): nothing is written.
"""

import sys
import time


class ProgressLine:
    """``progress`` and ``stage`` callables for :func:`facet.planarize` that keep one
    status line up to date on ``out``.

    Parameters
    ----------
    out : file, optional
        Default ``sys.stderr``.
    prefix : str
        What the line starts with.
    interval : float
        Least time between two updates, seconds (a stage change is shown at once).
    force : bool
        Write even when ``out`` is not a terminal (tests).
    """

    def __init__(self, out=None, prefix="facet planarize", interval=0.1, force=False):
        self.out = out or sys.stderr
        isatty = getattr(self.out, "isatty", None)
        self.enabled = bool(force or (isatty is not None and isatty()))
        self.prefix = prefix
        self.interval = float(interval)
        self.stage_text = ""
        self._last = None
        self._width = 0

    def progress(self, iteration, max_iter, planarity):
        """facet's ``progress(iteration, max_iter, planarity_max_rel)``; never cancels."""
        if self._due():
            self._show(f"iteration {iteration} of at most {max_iter}, planarity {planarity:.2g}")
        return False

    def steps(self, done, total, what):
        """A count of steps: ``what done of total``; never cancels (the last one is shown
        at once)."""
        if self._due(at_once=done >= total):
            self._show(f"{what} {done} of {total}")
        return False

    def _due(self, at_once=False):
        """Whether to rewrite the line now: on a terminal, at most every ``interval``
        seconds (or at once)."""
        if not self.enabled:
            return False
        now = time.monotonic()
        if not at_once and self._last is not None and now - self._last < self.interval:
            return False
        self._last = now
        return True

    def stage(self, stage, stages):
        """facet's ``stage(stage, stages)``: a quality re-solve starts, or one of method
        auto's comparison solves (``stage`` is facet.planarize.STAGE_COMPARE or
        STAGE_FINER) or its fallback (STAGE_FALLBACK)."""
        from facet.planarize import STAGE_COMPARE, STAGE_FALLBACK, STAGE_FINER

        if stage == STAGE_COMPARE:
            self.stage_text = "solving by local/local too, for a result closer to the design"
        elif stage == STAGE_FINER:
            self.stage_text = "solving by local/global again with a finer hold, closer to the design"
        elif stage == STAGE_FALLBACK:
            self.stage_text = "local/local closed a panel: solving by local/global"
        else:
            self.stage_text = f"re-solving for panel quality (stage {stage} of {stages})"
        self._last = None  # the next iteration is shown at once

    def close(self):
        """Erase the line (before the summary)."""
        if self.enabled and self._width:
            self.out.write("\r" + " " * self._width + "\r")
            self.out.flush()
            self._width = 0

    def _show(self, counts):
        text = f"{self.prefix}: {self.stage_text + ': ' if self.stage_text else ''}{counts}"
        pad = max(self._width - len(text), 0)
        self.out.write("\r" + text + " " * pad)
        self.out.flush()
        self._width = len(text)
