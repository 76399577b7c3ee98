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
