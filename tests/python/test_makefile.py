# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Makefile's targets install what they use: each may be the first command run on a
fresh Debian machine (README: "Setting up")."""

import os
import re
import shutil
import subprocess

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

#: What a recipe runs that needs the Python packages, FreeCAD or the built core.
#: (``-DPython3_EXECUTABLE=$(PYTHON)`` names the interpreter, it does not run it.)
_USES_PACKAGES = re.compile(r"(?<![=\"])\$\((PYTHON|FC_ENV)\)|pytest|freecad")
_USES_CORE = re.compile(r"\$\(BUILD\)/libcore\b|(?<![=\"])\$\((PYTHON|FC_ENV)\)")


def _rules():
    """{target: (prerequisites, recipe lines)} from make's own reading of the Makefile."""
    if not shutil.which("make"):
        pytest.skip("make is not installed")
    db = subprocess.run(["make", "-pRrq", "-f", "Makefile"], cwd=ROOT, capture_output=True,
                        text=True).stdout
    rules, target = {}, None
    for line in db[db.index("# Files"):].splitlines():
        head = re.match(r"^([.A-Za-z][\w.-]*):(?!=)\s*(.*)$", line)
        if head:
            target = head.group(1)
            rules[target] = (head.group(2).split(), [])
        elif line.startswith("\t") and target:
            rules[target][1].append(line)
        elif not line.strip():
            target = None
    return rules


def _needs(rules, target, seen=None):
    seen = set() if seen is None else seen
    for prerequisite in rules.get(target, ((), ()))[0]:
        if prerequisite not in seen:
            seen.add(prerequisite)
            _needs(rules, prerequisite, seen)
    return seen


def test_targets_that_run_python_or_freecad_install_and_build_first():
    rules = _rules()
    phony = set(rules[".PHONY"][0])
    checked = 0
    for target in sorted(phony):
        recipe = rules[target][1]
        text = "\n".join(recipe)
        needs = _needs(rules, target)
        if _USES_PACKAGES.search(text):
            checked += 1
            assert "deps-test" in needs, f"make {target} runs Python or FreeCAD without deps-test"
        if target != "build" and _USES_CORE.search(text):
            assert "build" in needs, f"make {target} uses the built core without build"
    assert checked >= 6  # bench, demo, examples, the test targets...
