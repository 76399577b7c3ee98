# SPDX-License-Identifier: LGPL-2.1-or-later
"""Shared fixtures of the pure-Python tests.

The tests read only ``tests/data`` and write only to pytest's ``tmp_path``.
The ``facet`` package is imported from ``workbench/`` next to ``tests/``,
whatever the current directory.
"""

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
WORKBENCH = ROOT / "workbench"
DATA = ROOT / "tests" / "data"

if str(WORKBENCH) not in sys.path:
    sys.path.insert(0, str(WORKBENCH))


@pytest.fixture
def data_dir():
    """Folder of the real test meshes (tests/data)."""
    return DATA


@pytest.fixture
def write_file(tmp_path):
    """Write a small text file in tmp_path and return its path."""

    def write(name, text):
        path = tmp_path / name
        path.write_text(text, encoding="utf-8")
        return path

    return write


def facet_environment():
    """The environment of a child Python that imports facet from workbench/."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(
        [str(WORKBENCH)] + ([env["PYTHONPATH"]] if env.get("PYTHONPATH") else [])
    )
    return env


def run_facet(*args, cwd=None, timeout=300):
    """Run ``python -m facet`` with this interpreter and the workbench on PYTHONPATH.

    Returns
    -------
    subprocess.CompletedProcess
        With text ``stdout`` and ``stderr``.
    """
    return subprocess.run(
        [sys.executable, "-m", "facet", *map(str, args)],
        cwd=cwd,
        env=facet_environment(),
        capture_output=True,
        text=True,
        timeout=timeout,
    )


@pytest.fixture
def facet_command():
    """The function :func:`run_facet`."""
    return run_facet


def interrupt_facet(*args, after=3.0):
    """Start ``python -m facet ARGS``, check it is still running ``after`` seconds later,
    send it SIGINT (a real Ctrl+C) and wait for it.

    Returns
    -------
    subprocess.CompletedProcess
        With text ``stdout`` and ``stderr``.
    """
    import signal
    import time

    process = subprocess.Popen(
        [sys.executable, "-m", "facet", *map(str, args)],
        env=facet_environment(), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        time.sleep(after)
        assert process.poll() is None, process.communicate()
        process.send_signal(signal.SIGINT)
        out, err = process.communicate(timeout=60)
    finally:
        if process.poll() is None:
            process.kill()
            process.communicate()
    return subprocess.CompletedProcess(process.args, process.returncode, out, err)


@pytest.fixture
def facet_interrupt():
    """The function :func:`interrupt_facet`."""
    return interrupt_facet


@pytest.fixture
def facet_env():
    """Environment for a child process running facet (see :func:`facet_environment`)."""
    return facet_environment()
