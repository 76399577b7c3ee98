# SPDX-License-Identifier: LGPL-2.1-or-later
"""Write the seed corpus of the Python parser target (libcore/fuzz/corpus/python).

Each seed is one selector byte (the reader, see harness.KINDS) followed by a
real file: the permissively licensed files of ../shared/data (when present;
CC BY-NC files are never copied) and of tests/data, plus small files
written here (CSV segments and targets, a DXF plan made with ezdxf, OFF and
compas JSON variants). Only files up to MAX_BYTES are used. Attribution:
libcore/fuzz/corpus/python/README.md.

    /usr/bin/python3 tools/fuzz/make_corpus.py [--shared ../shared/data]
"""

import argparse
import io
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path[:0] = [HERE, os.path.join(ROOT, "workbench")]
from harness import KINDS  # noqa: E402

MAX_BYTES = 36_000

#: shared data folder -> licence (only these are copied)
SHARED = {
    "BlockResearchGroup__compas-RV": "MIT",
    "BlockResearchGroup__compas_ags": "MIT",
    "BlockResearchGroup__compas_shapeop": "MIT",
    "BlockResearchGroup__compas_tna": "MIT",
    "BlockResearchGroup__compas_tno": "MIT",
    "WWmore__DOS": "MIT",
    "compas-dev__compas": "MIT",
    "compas-dev__compas_libigl": "MIT",
    "mozman__ezdxf": "MIT",
}


def selectors(suffix):
    """Selector bytes of the readers that take this suffix."""
    return [i for i, (_, s) in enumerate(KINDS) if s == suffix.lower()]


def written():
    """Small inputs written for Facet (LGPL-2.1-or-later)."""
    files = {
        "segments.csv": "x1,y1,x2,y2\n0,0,2,0\n2,0,2,1\n2,1,0,1\n0,1,0,0\n1,0,1,1\n# comment\n",
        "targets.csv": "x,y,z\n0,0,0\n1,0,0.5\n2,0,1\n0,1,0\n1,1,0.25\n2,1.5,2\n",
        "pins.csv": "0,0,1\n2,1.5,3\n",
        "quad.off": "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0.1\n4 0 1 2 3\n",
        "color.off": "COFF\n# c\n3 1 3\n0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n0 1 0 0 0 1 1\n3 0 1 2 255 0 0\n",
        "plan.obj": "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1.5 0\n"
                    "f 1 2 5 4\nf 2 3 6 5\n",
        "groups.obj": "# obj\nmtllib a.mtl\no a\ng b\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                      "vt 0 0\nvn 0 0 1\nusemtl m\ns off\nf 1/1/1 2//1 -2 -1\nl 1 2\n",
        "old.json": '{"vertex": {"0": {"x": 0, "y": 0, "z": 0}, "1": {"x": 1, "y": 0, "z": 0},'
                    ' "2": {"x": 1, "y": 1, "z": 0}, "3": {"x": 0, "y": 1, "z": 0.1}},'
                    ' "face": {"0": [0, 1, 2, 3]}, "facedata": {"0": {"_is_loaded": true}}}',
        "new.json": '{"dtype": "compas.datastructures/Mesh", "data": {"vertex": '
                    '{"0": {"x": 0, "y": 0, "z": 0}, "1": {"x": 1, "y": 0, "z": 0},'
                    ' "2": {"x": 1, "y": 1, "z": 0}}, "face": {"0": [0, 1, 2]}}}',
    }
    out = {k: v.encode() for k, v in files.items()}
    try:
        import ezdxf

        doc = ezdxf.new("R2010")
        msp = doc.modelspace()
        for a, b in [((0, 0), (2, 0)), ((2, 0), (2, 1)), ((2, 1), (0, 1)), ((0, 1), (0, 0)),
                     ((1, 0), (1, 1))]:
            msp.add_line(a, b)
        msp.add_lwpolyline([(3, 0), (4, 0), (4, 1), (3, 1)], close=True)
        stream = io.StringIO()
        doc.write(stream)
        out["plan.dxf"] = stream.getvalue().encode()
        doc = ezdxf.new("R12")
        doc.modelspace().add_polyline2d([(0, 0), (1, 0), (1, 1), (0, 1)], close=True)
        stream = io.StringIO()
        doc.write(stream)
        out["polyline_r12.dxf"] = stream.getvalue().encode()
    except ImportError:
        pass
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shared", default=os.path.join(os.path.dirname(ROOT), "shared", "data"))
    parser.add_argument("--out", default=os.path.join(ROOT, "libcore", "fuzz", "corpus", "python"))
    args = parser.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    sources = []  # (label, name, bytes)
    if os.path.isdir(args.shared):
        for folder in sorted(SHARED):
            d = os.path.join(args.shared, folder)
            for name in sorted(os.listdir(d)) if os.path.isdir(d) else []:
                path = os.path.join(d, name)
                if os.path.getsize(path) <= MAX_BYTES:
                    with open(path, "rb") as h:
                        sources.append((folder, name, h.read()))
    tests = os.path.join(ROOT, "tests", "data")
    for name in sorted(os.listdir(tests)):
        path = os.path.join(tests, name)
        if name != "README.md" and os.path.getsize(path) <= MAX_BYTES:
            with open(path, "rb") as h:
                sources.append(("tests-data", name, h.read()))
    for name, data in sorted(written().items()):
        sources.append(("facet", name, data))
    seen = set()
    count = 0
    for label, name, data in sources:
        for sel in selectors(os.path.splitext(name)[1]):
            seed = bytes([sel]) + data
            if seed in seen:
                continue
            seen.add(seed)
            out = os.path.join(args.out, f"{sel}-{label}-{name}")
            with open(out, "wb") as h:
                h.write(seed)
            count += 1
    print(f"{count} seeds in {args.out}")


if __name__ == "__main__":
    main()
