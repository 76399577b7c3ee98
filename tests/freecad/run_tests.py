# SPDX-License-Identifier: LGPL-2.1-or-later
"""Run Facet's headless FreeCAD tests and exit with their status.

    tests/fc_env.sh freecadcmd tests/freecad/run_tests.py     # as the Makefile does
    freecadcmd tests/freecad/run_tests.py                      # works too; skips Init.py checks

freecadcmd (0.20) accepts no arguments for the script, so options come from the environment:
FACET_TESTS=test_planarized to run one module (or a comma-separated list). The checkout's
workbench/ directory goes first on sys.path, so its facet and facetwb are the ones tested.

freecadcmd exits 0 when a script raises, so everything here is caught and turned into an exit
status: 0 all passed, 1 a test failed, 2 the run itself broke.
"""

import os
import sys
import traceback
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def main():
    sys.path.insert(0, os.path.join(ROOT, "workbench"))
    sys.path.insert(0, HERE)
    loader = unittest.defaultTestLoader
    names = [name.strip() for name in os.environ.get("FACET_TESTS", "").split(",")
             if name.strip()]
    if names:
        suite = loader.loadTestsFromNames(names)
    else:
        suite = loader.discover(HERE, pattern="test_*.py", top_level_dir=HERE)
    result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(suite)
    sys.stdout.flush()
    return 0 if result.wasSuccessful() and result.testsRun > 0 else 1


try:
    status = main()
except BaseException:  # noqa: BLE001 - freecadcmd would turn an exception into status 0
    traceback.print_exc()
    status = 2
sys.stdout.flush()
sys.stderr.flush()
os._exit(status)
