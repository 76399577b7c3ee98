# SPDX-License-Identifier: LGPL-2.1-or-later
"""Replay of the parser fuzzing's inputs (libcore/fuzz, tools/fuzz/harness.py).

Every finding of ``make fuzz`` on the Python readers is kept as an input in
libcore/fuzz/regressions/python/ and replayed here through the same harness
the fuzzer runs (selector byte + file; InputError is the only accepted
failure of a reader, any other exception or a non-finite result is a
finding). The seed corpus (real files from tests/data and ../shared/data,
copied under their licences) is replayed too: every seed must read or be
refused cleanly.
"""

import importlib.util
import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
FUZZ = ROOT / "libcore" / "fuzz"


def _harness():
    spec = importlib.util.spec_from_file_location("facet_fuzz_harness", ROOT / "tools" / "fuzz" / "harness.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _inputs(folder):
    d = FUZZ / folder / "python"
    return sorted(p for p in d.iterdir() if p.is_file() and p.name != "README.md") if d.is_dir() else []


@pytest.fixture(scope="module")
def harness():
    pytest.importorskip("facet._core")
    return _harness()


@pytest.mark.parametrize("path", _inputs("regressions"), ids=lambda p: p.name)
def test_regression(harness, path):
    harness.one_input(path.read_bytes())


@pytest.mark.parametrize("path", _inputs("corpus"), ids=lambda p: p.name)
def test_seed(harness, path):
    harness.one_input(path.read_bytes())


def test_regressions_exist():
    # the directory is where make fuzz's findings are kept; it must not vanish
    assert _inputs("regressions"), "libcore/fuzz/regressions/python is empty"


def test_harness_flags_a_finding(harness, monkeypatch):
    # the oracle can fail: a reader raising anything but InputError is a finding
    import facet.io

    def broken(path, **options):
        raise IndexError("list index out of range")

    monkeypatch.setitem(facet.io.READERS, ".obj", broken)
    with pytest.raises(IndexError):
        harness.one_input(b"\x00v 0 0 0\n")
    monkeypatch.undo()
    # and an InputError is not
    harness.one_input(b"\x00this is not an obj file\n")
    assert os.path.isdir(harness._DIR)
