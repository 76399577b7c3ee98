# SPDX-License-Identifier: LGPL-2.1-or-later
"""What a Facet document holds, as plain JSON-able data, for exact comparisons.

Used by test_documents.py in the test process and in the fresh ``freecadcmd`` it starts:
every Facet object's validity, its mesh points (float64 bit patterns as hex) or its shape's
vertices (bits too), and a few result properties.
"""

import numpy as np

RESULTS = ("VertexCount", "FaceCount", "Iterations", "StopReason", "Converged", "Dimension",
           "PanelCount", "PartIds", "SheetCount", "Unplaced", "DanglingEdges")


def _hex(values):
    array = np.ascontiguousarray(np.asarray(values, dtype=np.float64).reshape(-1))
    return array.view(np.uint64).astype(">u8").tobytes().hex()


def unhex(text):
    """The float64 array of a :func:`_hex` string."""
    return np.frombuffer(bytes.fromhex(text), dtype=">u8").astype(np.uint64).view(np.float64)


def facet_type(obj):
    return getattr(getattr(obj, "Proxy", None), "Type", "") or ""


def object_state(obj):
    entry = {"type": facet_type(obj), "valid": bool(obj.isValid()),
             "status": obj.getStatusString(), "label": obj.Label}
    if hasattr(obj, "Points"):
        entry["points"] = _hex([(p.x, p.y, p.z) for p in obj.Points])
        entry["faces"] = [list(obj.FaceStart), list(obj.FaceVertices)]
    if hasattr(obj, "Shape") and not hasattr(obj, "Points"):
        entry["shape"] = _hex([(v.Point.x, v.Point.y, v.Point.z) for v in obj.Shape.Vertexes])
    for name in RESULTS:
        if hasattr(obj, name):
            value = getattr(obj, name)
            entry[name] = list(value) if isinstance(value, (list, tuple)) else value
    return entry


def state(doc):
    """{object name: object_state} for the Facet objects of ``doc``."""
    return {o.Name: object_state(o) for o in doc.Objects if facet_type(o).startswith("Facet::")}


def reopen_in_fresh_process(path, folder):
    """Open ``path`` in a new ``freecadcmd`` (tests/freecad/reopen_child.py), as a designer
    would, recompute it, and return (its JSON result: {"loaded": state, "recomputed": state}
    or {"error": ...}, or None when the child wrote nothing; the child's output)."""
    import json
    import os
    import subprocess

    out = os.path.join(folder, os.path.basename(path) + ".reopened.json")
    env = dict(os.environ, FACET_REOPEN_IN=path, FACET_REOPEN_OUT=out)
    child = os.path.join(os.path.dirname(os.path.abspath(__file__)), "reopen_child.py")
    done = subprocess.run(["freecadcmd", child], env=env, capture_output=True, text=True,
                          timeout=600)
    output = done.stdout + done.stderr
    if not os.path.exists(out):
        return None, output
    with open(out, encoding="utf-8") as handle:
        return json.load(handle), output


#: Objects whose points come through BLAS: a Lifting's heights are SuiteSparseQR's and
#: LAPACK's, whose last bits depend on the machine's BLAS (Debian's reference BLAS or
#: OpenBLAS, and OpenBLAS's kernel for the CPU). Every other object's points are Facet's own
#: arithmetic (CHOLMOD's simplicial factorization calls no BLAS): the same bits anywhere.
BLAS_TYPES = ("Facet::Lifting",)


def assert_entry_equal(test, got, want, context, shape_bits=True, blas_bits=True):
    """Every key of the object state ``want`` equal in ``got``. A shape read back from BREP
    text (``shape_bits`` False) keeps 17 digits, not always the last bit; the points of a
    BLAS_TYPES object computed on another machine (``blas_bits`` False) may differ in their
    last bits: both equal to 1e-15 of the largest coordinate."""
    for key, value in want.items():
        if (key == "shape" and not shape_bits) or (
                key == "points" and not blas_bits and want.get("type") in BLAS_TYPES):
            expected = unhex(value)
            np.testing.assert_allclose(unhex(got[key]), expected, rtol=0,
                                       atol=1e-15 * np.abs(expected).max(), err_msg=context)
        else:
            test.assertEqual(got[key], value, f"{context} {key}")
