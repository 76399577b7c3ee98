# SPDX-License-Identifier: LGPL-2.1-or-later
"""Run by test_documents.py in a FRESH freecadcmd: open a saved document, record its Facet
objects as loaded, recompute everything, record again, write both as JSON.

freecadcmd takes no script arguments: FACET_REOPEN_IN (the .FCStd) and FACET_REOPEN_OUT (the
JSON) come from the environment. freecadcmd exits 0 when a script raises, so errors go into
the JSON ({"error": traceback}).
"""

import json
import os
import sys
import traceback

HERE = os.path.dirname(os.path.abspath(__file__))
# Only this folder: facet and facetwb come from FreeCAD's Mod/Facet, as for a designer.
# FreeCAD 0.20.2 (Debian) refuses, while restoring a document, to import a proxy module
# found outside its Mod folders: a checkout's workbench/ first on sys.path would leave the
# first restored object without its proxy.
sys.path.insert(0, HERE)

out = os.environ["FACET_REOPEN_OUT"]
try:
    import FreeCAD as App

    from document_state import state

    doc = App.openDocument(os.environ["FACET_REOPEN_IN"])
    loaded = state(doc)
    for obj in doc.Objects:
        obj.touch()
    doc.recompute()
    result = {"loaded": loaded, "recomputed": state(doc)}
except BaseException:  # noqa: BLE001 - reported to the parent test
    result = {"error": traceback.format_exc()}
with open(out, "w", encoding="utf-8") as handle:
    json.dump(result, handle)
sys.stdout.flush()
os._exit(0)
