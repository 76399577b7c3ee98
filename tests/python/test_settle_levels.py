# SPDX-License-Identifier: LGPL-2.1-or-later
"""tools/bench/settle_levels.py in a tiny run: it drives bench_large and reads its line."""

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DRIVER = ROOT / "tools" / "bench" / "settle_levels.py"
BENCH = ROOT / "build" / "libcore" / "bench" / "bench_large"


@pytest.mark.skipif(not BENCH.exists(), reason="bench_large not built (make build)")
def test_rows_for_the_default_and_a_variant():
    p = subprocess.run(
        [sys.executable, str(DRIVER), "--threads", "1", "--meshes", "grid:12x10",
         "--variant", "short=hold_max:2"],
        capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    rows = [line.split() for line in p.stdout.splitlines()[1:]]
    assert [r[:2] for r in rows] == [["grid:12x10", "default"], ["grid:12x10", "short"]]
    default, short = (int(r[2]) for r in rows)
    assert default > 0 and short > 0
    # a hold of at most 2 steps per level changes the schedule: another iteration count
    assert short != default
    for r in rows:
        assert 0.0 < float(r[5]) < 180.0  # the smallest angle was read, not '?'


def test_bad_variant_is_refused():
    p = subprocess.run([sys.executable, str(DRIVER), "--variant", "x=hold_max:two"],
                       capture_output=True, text=True, timeout=60)
    assert p.returncode != 0
    assert "bad setting 'hold_max=two'" in p.stderr
