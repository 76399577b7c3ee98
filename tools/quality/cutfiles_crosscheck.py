# SPDX-License-Identifier: LGPL-2.1-or-later
"""Cross-check facet panels' cut files against each other, as a shop would before cutting.

usage: /usr/bin/python3 tools/quality/cutfiles_crosscheck.py MESH OUTDIR [panels options]

Runs ``facet panels MESH --dxf --step --schedule --report`` (into OUTDIR) with the options
given (``--thickness`` and ``--sheet`` at least; ``--units``, ``--gap``, ``--edge``...),
then reads the files back on their own: the DXF with ezdxf, the STEP with FreeCAD
(``Import.insert``, solids by label), the schedule CSV and the JSON report; the mesh for
each face's plane. It prints the largest discrepancy of each comparison (model units,
degrees) and the panel where it is, and "!!" lines for what does not match at all:

- IDs: the same set in the STEP labels, the DXF's LABEL texts (each inside one CUT
  outline), the schedule and the report; $INSUNITS against --units, the STEP in mm.
- The CUT outline against the STEP solid's cut face (of the two faces parallel to the
  mesh face, the one it fits by a proper rigid motion, seen from the other: not mirrored):
  corner residual, area, perimeter, edge lengths in order, corner angles; the TOP outline
  against the other face under the same motion; the schedule's thickness, area, area_top,
  perimeter, edge lengths, width and height against the solid's.
- Bevels: the angle between each side face and the cut face, less 90 (positive where the
  top is the larger face), against the schedule and the DXF's BEVEL text nearest that edge.
- The schedule's sheet, x, y and rotation placing the cut face (in the frame of the face's
  first corner and edge, its top normal +z) onto the DXF's outline, corner by corner (not
  where an edge vanished: that frame starts at the first corner left).
- Neighbours (panels sharing a mesh vertex): OCC's common volume where the schedule says
  no clash, and every panel with a clash overlapping some neighbour; mitred joints: the
  distance of the two parallel side planes against --gap; other panels whose bounding boxes
  meet: their common volume.
- With --grain: each part's grain arrow (its GRAIN shaft, head last) against the grain
  direction projected into the panel, through the same motion.
- The sheets: each part's footprint (CUT and TOP outlines) inside its sheet less --margin
  and at least --spacing from the others.

A symmetric part (both faces fit, or several turns of its outline do) is matched by the
TOP outline, then by the schedule's placement. It needs --dxf as one file (no --per-sheet).
Written for the cross-check that found square joints across valleys folded 90 degrees or
more reported as touching (their solids overlapped by the panels' thickness) and parts
left 4 um off the sheet at spacing 0; on the meshes it was run on, the rest agreed to
rounding (1e-9 of the part's size; 1e-5 mm where the mesh is planar to 1e-6 only), bevel
texts to their 0.05 degree rounding.
"""

import csv
import json
import math
import os
import subprocess
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MM = {"mm": 1.0, "cm": 10.0, "m": 1000.0, "in": 25.4, "ft": 304.8}
INSUNITS = {"mm": 4, "cm": 5, "m": 6, "in": 1, "ft": 2}


def run(mesh, out, opts):
    out = os.path.abspath(out); os.makedirs(out, exist_ok=True)
    cmd = ["/usr/bin/python3", "-m", "facet", "panels", mesh,
           "--dxf", f"{out}/s.dxf", "--step", f"{out}/p.step",
           "--schedule", f"{out}/s.csv", "--report", f"{out}/r.json"] + opts
    env = dict(os.environ, PYTHONPATH=f"{ROOT}/workbench", OPENBLAS_NUM_THREADS="1")
    p = subprocess.run(cmd, env=env, capture_output=True, text=True, cwd=ROOT)
    if p.returncode != 0:
        print(p.stdout, p.stderr)
        raise SystemExit(f"facet panels failed: {p.returncode}")
    return p.stdout + p.stderr


def opt(opts, name, default):
    return opts[opts.index(name) + 1] if name in opts else default


def area2(p):
    return 0.5 * (np.dot(p[:, 0], np.roll(p[:, 1], -1)) - np.dot(p[:, 1], np.roll(p[:, 0], -1)))


def dedupe(p, tol):
    keep = [q for i, q in enumerate(p) if np.linalg.norm(q - p[i - 1]) > tol]
    return np.array(keep)


def lengths(p):
    return np.linalg.norm(np.roll(p, -1, axis=0) - p, axis=1)


def angles(p):
    d0 = p - np.roll(p, 1, axis=0)
    d1 = np.roll(p, -1, axis=0) - p
    return np.degrees(np.arctan2(np.cross(d0, d1), np.einsum("ij,ij->i", d0, d1)))


def rigid_fit(a, b):
    """best proper rigid motion a->b (2D, same order); return max residual."""
    ca, cb = a.mean(0), b.mean(0)
    h = (a - ca).T @ (b - cb)
    u, s, vt = np.linalg.svd(h)
    d = np.sign(np.linalg.det(vt.T @ u.T))
    r = vt.T @ np.diag([1, d]) @ u.T
    if np.linalg.det(r) < 0:
        return np.inf, None
    res = np.linalg.norm((a - ca) @ r.T + cb - b, axis=1).max()
    return res, (r, ca, cb)


def fits(a, b, a_top=None, b_top=None):
    """Every cyclic shift of a (k,2) CCW polygon onto b by a proper rigid motion:
    [(residual, top residual, shift, (r, ca, cb))]; the top residual carries a_top onto
    b_top (the DXF's TOP outline) by the same motion (0 without them)."""
    if len(a) != len(b):
        return []
    out = []
    for s in range(len(a)):
        res, t = rigid_fit(np.roll(a, -s, axis=0), b)
        top = 0.0
        if t is not None and a_top is not None and b_top is not None:
            r, ca, cb = t
            q = (a_top - ca) @ r.T + cb
            d = np.linalg.norm(q[:, None, :] - b_top[None, :, :], axis=2)
            top = max(d.min(0).max(), d.min(1).max())
        out.append((res, top, s, t))
    return out


def face_ring(face):
    """ordered 3D corners of a planar face's outer wire"""
    return np.array([[v.X, v.Y, v.Z] for v in face.OuterWire.OrderedVertexes])


def frame2d(n):
    n = n / np.linalg.norm(n)
    a = np.array([1.0, 0, 0]) if abs(n[0]) < 0.9 else np.array([0, 1.0, 0])
    u = np.cross(n, a)
    u /= np.linalg.norm(u)
    v = np.cross(n, u)
    return u, v  # u x v = n


def main():
    mesh, out, opts = sys.argv[1], sys.argv[2], sys.argv[3:]
    mesh, out = os.path.abspath(mesh), os.path.abspath(out)
    log = run(mesh, out, opts)
    units = opt(opts, "--units", "mm")
    k_mm = MM[units]
    t_opt = float(opt(opts, "--thickness", "nan"))
    gap = float(opt(opts, "--gap", "0"))
    edge_mode = opt(opts, "--edge", "square")
    sys.path.insert(0, f"{ROOT}/workbench")
    import ezdxf
    from shapely.geometry import Point, Polygon

    import facet
    from facet.step import import_freecad

    FreeCAD, Part = import_freecad()
    import Import

    findings = {}

    def worst(name, value, where=""):
        cur = findings.get(name)
        if cur is None or value > cur[0]:
            findings[name] = (float(value), where)

    # ---- schedule / report
    from facet.cutsheets import column_units

    # (the headers give the columns' units, "area_mm2": read by the rows' keys, "area")
    keys = {f"{key}_{unit}": key for key, unit in column_units(units).items()}
    rows = [{keys.get(h, h): v for h, v in r.items()}
            for r in csv.DictReader(open(f"{out}/s.csv"))]
    sched = {r["id"]: r for r in rows}
    rep = json.load(open(f"{out}/r.json"))
    rep_ids = [p["id"] for p in rep["panels"]]

    # ---- DXF
    doc = ezdxf.readfile(f"{out}/s.dxf")
    ins = doc.header.get("$INSUNITS")
    print(f"$INSUNITS={ins} (expected {INSUNITS[units]}), $MEASUREMENT={doc.header.get('$MEASUREMENT')}")
    if ins != INSUNITS[units]:
        print("  !! INSUNITS mismatch")
    msp = doc.modelspace()
    cuts, tops = [], []
    for e in msp.query("LWPOLYLINE"):
        pts = np.array(e.get_points("xyb"))
        if np.any(np.abs(pts[:, 2]) > 0):
            print("  !! bulge in", e.dxf.layer)
        if not e.closed:
            print("  !! open polyline on", e.dxf.layer)
        (cuts if e.dxf.layer == "CUT" else tops if e.dxf.layer == "TOP" else []).append(
            pts[:, :2])
    # the sheets in the order of their names ("SHEET n", under each sheet: they lie in
    # rows), each by its lower-left corner
    rects = [np.array(e.get_points("xy")) for e in msp.query("LWPOLYLINE[layer=='SHEET']")]
    names = {}
    for t in msp.query("TEXT[layer=='SHEET']"):
        x, y = t.dxf.align_point.x, t.dxf.align_point.y
        under = [q for q, r in enumerate(rects)
                 if r[:, 0].min() <= x <= r[:, 0].max() and y < r[:, 1].min()]
        names[int(t.dxf.text.split()[-1])] = max(under, key=lambda q: -rects[q][:, 1].min())
    if sorted(names) != list(range(1, len(rects) + 1)) or len(set(names.values())) != len(rects):
        print("  !! the sheets' names are not 1 to", len(rects), "each under its own sheet")
    sheet_rects = [rects[names[n]] for n in sorted(names)]
    sheets_xy0 = [r.min(axis=0) for r in sheet_rects]
    labels = [(t.dxf.text, np.array(tuple(t.get_placement()[1])[:2])) for t in msp.query("TEXT[layer=='LABEL']")]
    bevels = [(t.dxf.text, np.array(tuple(t.get_placement()[1])[:2]), t.dxf.rotation)
              for t in msp.query("TEXT[layer=='BEVEL']")]
    polys = [Polygon(c) for c in cuts]
    dxf_part = {}
    for text, p in labels:
        hit = [i for i, pg in enumerate(polys) if pg.contains(Point(p))]
        if len(hit) != 1:
            print("  !! label", text, "in", len(hit), "CUT outlines")
            continue
        if text in dxf_part:
            print("  !! label twice", text)
        dxf_part[text] = hit[0]
    part_bevels = {i: [] for i in range(len(cuts))}
    for text, p, rot in bevels:
        hit = [i for i, pg in enumerate(polys) if pg.contains(Point(p))]
        if len(hit) != 1:
            print("  !! bevel text", text, "in", len(hit), "outlines")
            continue
        part_bevels[hit[0]].append((text, p, rot))
    # the grain arrows: each part's longest GRAIN line (the shaft; its head is two short ones)
    part_grain = {}
    for ln in msp.query("LINE[layer=='GRAIN']"):
        a_, b_ = np.array(ln.dxf.start)[:2], np.array(ln.dxf.end)[:2]
        hit = [i for i, pg in enumerate(polys) if pg.contains(Point(0.5 * (a_ + b_)))]
        if len(hit) == 1 and np.linalg.norm(b_ - a_) > np.linalg.norm(
                np.subtract(*part_grain.get(hit[0], (a_, a_)))[::-1]):
            part_grain[hit[0]] = (a_, b_)
    part_top = {}
    for tp in tops:
        pg = Polygon(tp)
        best = max(range(len(polys)), key=lambda i: polys[i].intersection(pg).area if pg.is_valid else 0)
        part_top.setdefault(best, []).append(tp)

    # ---- STEP
    text = open(f"{out}/p.step").read()
    si = "SI_UNIT(.MILLI.,.METRE.)" in text.replace(" ", "")
    print(f"STEP length unit mm: {si}")
    sdoc = FreeCAD.newDocument("xcheck")
    Import.insert(f"{out}/p.step", sdoc.Name, useLinkGroup=False)
    solids = {}
    for o in sdoc.Objects:
        if hasattr(o, "Shape") and o.Shape.Solids and o.TypeId == "Part::Feature":
            if len(o.Shape.Solids) == 1:
                if o.Label in solids:
                    print("  !! STEP label twice", o.Label)
                solids[o.Label] = o.Shape.Solids[0]
    ids_s, ids_d, ids_c, ids_r = set(solids), set(dxf_part), set(sched), set(rep_ids)
    print(f"IDs: STEP {len(ids_s)} DXF {len(ids_d)} schedule {len(ids_c)} report {len(ids_r)} "
          f"CUT outlines {len(cuts)}; all equal: {ids_s == ids_d == ids_c == ids_r}")
    if not (ids_s == ids_d == ids_c == ids_r):
        print("   STEP-DXF", sorted(ids_s - ids_d)[:5], "DXF-STEP", sorted(ids_d - ids_s)[:5],
              "sched-STEP", sorted(ids_c - ids_s)[:5])
    if rep_ids != [r["id"] for r in rows]:
        print("  !! report and schedule order differ")

    m = facet.read_mesh(mesh)
    V = np.asarray(m.vertices, float) if hasattr(m, "vertices") else None
    faces = m.faces() if callable(getattr(m, "faces", None)) else list(m.faces)

    bottom_side = []
    n_ambiguous = []
    for pid in sorted(ids_s & ids_d & ids_c):
        sol = solids[pid]
        row = sched[pid]
        if not (sol.isValid() and sol.isClosed()):
            print("  !! invalid/open solid", pid)
        fidx = int(row["face"])
        fv = V[faces[fidx]]
        n_mesh = np.zeros(3)
        for i in range(len(fv)):
            n_mesh += np.cross(fv[i] - fv.mean(0), fv[(i + 1) % len(fv)] - fv.mean(0))
        n_mesh /= np.linalg.norm(n_mesh)
        # STEP in mm -> model units
        cand = []
        for f in sol.Faces:
            ring = face_ring(f) / k_mm
            nn = np.zeros(3)
            c = ring.mean(0)
            for i in range(len(ring)):
                nn += np.cross(ring[i] - c, ring[(i + 1) % len(ring)] - c)
            nn /= np.linalg.norm(nn)
            if abs(abs(nn @ n_mesh) - 1) < 1e-6:
                cand.append((f, ring, c))
        if len(cand) != 2:
            print("  !!", pid, len(cand), "faces parallel to the mesh face")
            continue
        (fa, ra, ca), (fb, rb, cb) = cand
        thick = abs((cb - ca) @ n_mesh)
        worst("thickness |STEP - schedule|", abs(thick - float(row["thickness"])), pid)
        worst("thickness |STEP - option|", abs(thick - t_opt), pid)
        cut = dedupe(cuts[dxf_part[pid]], 1e-12)
        if area2(cut) < 0:
            cut = cut[::-1]
        size0 = np.ptp(cut, axis=0).max()
        tol = 1e-6 * max(size0, 1)
        if row["sheet"]:
            th = math.radians(float(row["rotation_deg"]))
            R = np.array([[math.cos(th), -math.sin(th)], [math.sin(th), math.cos(th)]])
            t_sheet = np.array([float(row["x"]), float(row["y"])]) + sheets_xy0[
                int(row["sheet"]) - 1]
        candidates = []
        for m_, ((f, ring, c), (_, other_ring, c_other)) in enumerate(
                (((fa, ra, ca), (fb, rb, cb)), ((fb, rb, cb), (fa, ra, ca)))):
            inward = (c_other - c) @ n_mesh * n_mesh
            u, v = frame2d(inward)
            ring3 = dedupe(ring, 1e-9 * max(size0, 1))
            flat = np.stack([(ring3 - c) @ u, (ring3 - c) @ v], axis=1)
            if area2(flat) < 0:
                flat, ring3 = flat[::-1], ring3[::-1]
            ring_o = dedupe(other_ring, 1e-9)
            flat_o = np.stack([(ring_o - c) @ u, (ring_o - c) @ v], axis=1)
            tops_p = part_top.get(dxf_part[pid], [])
            mirror = flat[::-1] * [-1, 1]
            resm = min([f_[0] for f_ in fits(mirror, cut)] or [np.inf])
            # the schedule's placement of this face (its frame: the face's first corner
            # and edge, the top normal +z), corner by corner
            placed = None
            if row["sheet"] and row["corners"] == row["input_corners"]:
                # (where an edge vanished the frame starts at the first corner that is left)
                nz = inward / np.linalg.norm(inward)
                fx = fv[1] - fv[0]
                fx = fx - (fx @ nz) * nz
                fx /= np.linalg.norm(fx)
                fy = np.cross(nz, fx)
                placed = np.stack([(ring3 - fv[0]) @ fx, (ring3 - fv[0]) @ fy],
                                  axis=1) @ R.T + t_sheet
            for res, top, s_, tr_ in fits(flat, cut, flat_o, tops_p[0] if tops_p else None):
                pres = 0.0
                if placed is not None:
                    pres = np.linalg.norm(np.roll(placed, -s_, axis=0) - cut, axis=1).max()
                candidates.append((res, top, pres, resm, s_, tr_, flat, f, ring3, c, c_other,
                                   inward, m_))
        if not candidates:
            print(f"  !! {pid}: the DXF outline has another number of corners than its faces")
            continue
        best_res = min(x[0] for x in candidates)
        good = [x for x in candidates if x[0] <= best_res + tol]
        best_top = min(x[1] for x in good)
        good = [x for x in good if x[1] <= best_top + tol]
        # a symmetric part (both faces, or several turns, fit): the schedule says which
        chosen = min(good, key=lambda x: x[2])
        if len({(x[12], x[4]) for x in good}) > 1:
            n_ambiguous.append(pid)
        res, _, pres, resm, s, tr, flat, f_cut, ring, c, c_other, inward, m_ = chosen
        if not res < tol:
            print(f"  !! {pid}: DXF CUT matches no STEP face by a proper motion: residual "
                  f"{res:.3g}, mirrored {resm:.3g}")
            continue
        if row["sheet"] and row["corners"] == row["input_corners"]:
            worst("schedule placement vs DXF CUT, corner by corner", pres, pid)
        u, v = frame2d(inward)  # the frame the chosen match was made in
        o_ring = dedupe(rb if m_ == 0 else ra, 1e-9 * max(size0, 1))
        o_face = fb if m_ == 0 else fa
        size = size0
        worst("CUT vs STEP cut face: vertex residual", res, pid)
        # which face: cut face side relative to mesh face plane
        d_cut = (c - fv.mean(0)) @ n_mesh
        d_oth = (c_other - fv.mean(0)) @ n_mesh
        bottom_side.append((pid, round(d_cut, 6), round(d_oth, 6)))
        a_flat = np.roll(flat, -s, axis=0)
        worst("area |DXF - STEP face|", abs(area2(cut) - area2(a_flat)), pid)
        worst("area |schedule - STEP face|", abs(float(row["area"]) - f_cut.Area / k_mm ** 2), pid)
        worst("perimeter |DXF - STEP|", abs(lengths(cut).sum() - f_cut.OuterWire.Length / k_mm), pid)
        worst("perimeter |schedule - STEP|", abs(float(row["perimeter"]) - f_cut.OuterWire.Length / k_mm), pid)
        worst("edge length |DXF - STEP| in order", np.abs(lengths(cut) - lengths(a_flat)).max(), pid)
        da = np.abs((angles(cut) - angles(a_flat) + 180) % 360 - 180).max()
        worst("corner turn |DXF - STEP| deg", da, pid)
        el = np.array([float(x) for x in row["edge_lengths"].split(";")])
        # schedule edge order vs DXF order: find shift
        Ls = lengths(cut)
        if len(el) != len(Ls):
            print(f"  !! {pid}: schedule has {len(el)} edges, DXF {len(Ls)}")
        else:
            shifts = [np.abs(np.roll(Ls, -q) - el).max() for q in range(len(el))]
            worst("edge lengths |schedule - DXF| (best shift)", min(shifts), pid)
            q_ok = [q for q in range(len(el)) if shifts[q] <= min(shifts) + 1e-7 * size0]
            # each edge's bevel on the STEP solid, in the DXF's order
            ring2 = dedupe(ring, 1e-9)
            c2 = ring2.mean(0)
            u, v = frame2d(inward)
            fl2 = np.stack([(ring2 - c2) @ u, (ring2 - c2) @ v], axis=1)
            if area2(fl2) < 0:
                ring2 = ring2[::-1]
            ring2 = np.roll(ring2, -s, axis=0)  # now aligned with DXF cut order
            nin = inward / np.linalg.norm(inward)
            sb = []
            for i in range(len(ring2)):
                a, b = ring2[i], ring2[(i + 1) % len(ring2)]
                e = (b - a) / np.linalg.norm(b - a)
                mdir = np.cross(nin, e)  # into the polygon (CCW about nin)
                # side face through this edge
                side = None
                for f in sol.Faces:
                    if f.isSame(f_cut):
                        continue
                    rr = face_ring(f) / k_mm
                    if (np.min(np.linalg.norm(rr - a, axis=1)) < 1e-6 * max(size, 1)
                            and np.min(np.linalg.norm(rr - b, axis=1)) < 1e-6 * max(size, 1)):
                        side = rr
                if side is None:
                    print("  !! no side face for edge", i, pid)
                    sb.append(np.nan)
                    continue
                far = side[np.argmax(np.abs((side - a) @ nin))]
                w = far - a
                w = w - (w @ e) * e
                w /= np.linalg.norm(w)
                theta = math.degrees(math.acos(np.clip(w @ mdir, -1, 1)))
                sb.append(theta - 90.0)
            sb = np.array(sb)
            bs = np.array([float(x) for x in row["bevel_deg"].split(";")])
            worst("bevel |schedule - STEP| deg", min(np.abs(np.roll(sb, -q) - bs).max() for q in q_ok), pid)
            # DXF bevel texts: nearest edge
            got = {}
            for text_, p, rot in part_bevels[dxf_part[pid]]:
                dist = []
                for i in range(len(cut)):
                    a, b = cut[i], cut[(i + 1) % len(cut)]
                    t = np.clip((p - a) @ (b - a) / ((b - a) @ (b - a)), 0, 1)
                    dist.append(np.linalg.norm(a + t * (b - a) - p))
                i = int(np.argmin(dist))
                val = float(text_.replace("\u00b0", ""))
                if i in got:
                    print(f"  !! {pid}: two bevel texts nearest edge {i}")
                got[i] = val
                worst("bevel |DXF text - STEP| deg", abs(val - sb[i]), pid)
            for i in range(len(cut)):
                if abs(sb[i]) >= 0.05 and i not in got:
                    print(f"  !! {pid}: edge {i} has STEP bevel {sb[i]:.3f} but no DXF text")
        grain = opt(opts, "--grain", None)
        if grain is not None:
            g = np.array([float(x) for x in grain.split(",")])
            nin = inward / np.linalg.norm(inward)
            g = g - (g @ nin) * nin
            if dxf_part[pid] not in part_grain:
                print(f"  !! {pid}: no grain arrow")
            else:
                a_, b_ = part_grain[dxf_part[pid]]
                r_ = tr[0]
                d2 = r_.T @ (b_ - a_)  # the arrow in the cut face's frame (u, v)
                d3 = d2[0] * u + d2[1] * v
                cosang = d3 @ g / (np.linalg.norm(d3) * np.linalg.norm(g))
                worst("grain arrow's angle from the grain in the panel, deg",
                      math.degrees(math.acos(np.clip(cosang, -1, 1))), pid)
        # top outline (dashed) vs STEP top face under the same motion
        ftop = o_ring
        tf = np.stack([(ftop - c) @ u, (ftop - c) @ v], axis=1)
        r, ca_, cb_ = tr
        tf_sheet = (tf - ca_) @ r.T + cb_
        tops_here = part_top.get(dxf_part[pid], [])
        if not tops_here:
            dd = np.linalg.norm(tf_sheet[:, None, :] - cut[None, :, :], axis=2)
            worst("no TOP outline: STEP top face vs the CUT outline",
                  max(dd.min(1).max(), dd.min(0).max()), pid)
        else:
            tp = tops_here[0]
            dd = np.linalg.norm(tf_sheet[:, None, :] - tp[None, :, :], axis=2)
            worst("TOP outline vs STEP top face (max nearest-vertex)", max(dd.min(1).max(), dd.min(0).max()), pid)
        # the sheet the DXF has the part on, against the schedule's
        if row["sheet"]:
            # which sheet the DXF part is on
            cx, cy = cut.mean(axis=0)
            on = [q for q, r in enumerate(sheet_rects)
                  if (r.min(axis=0) <= (cx, cy)).all() and ((cx, cy) <= r.max(axis=0)).all()]
            if on != [int(row["sheet"]) - 1]:
                print(f"  !! {pid}: schedule sheet {row['sheet']} but DXF sheet {on}")
        # dimensions: width along the mesh face's first edge
        allv = np.array([[p.X, p.Y, p.Z] for p in sol.Vertexes]) / k_mm
        e0 = fv[1] - fv[0]
        e0 = e0 - (e0 @ n_mesh) * n_mesh
        e0 /= np.linalg.norm(e0)
        e1 = np.cross(n_mesh, e0)
        wd, ht = np.ptp(allv @ e0), np.ptp(allv @ e1)
        worst("width |schedule - STEP|", abs(float(row["width"]) - wd), pid)
        worst("height |schedule - STEP|", abs(float(row["height"]) - ht), pid)
        worst("area_top |schedule - STEP|", abs(float(row["area_top"]) - o_face.Area / k_mm ** 2), pid)

    sides = {(round(a, 4), round(b, 4)) for _, a, b in bottom_side}
    print("parts that fit their CUT outline more than one way (symmetric; the schedule's "
          "placement chose):", len(n_ambiguous))
    print("cut face offset from mesh plane (cut, other), distinct:", sorted(sides)[:6])
    # ---- neighbours: overlap and gaps
    ids = sorted(ids_s & ids_c)
    face_of = {pid: int(sched[pid]["face"]) for pid in ids}
    vsets = {pid: set(faces[face_of[pid]]) for pid in ids}
    n_pairs, unfaced = 0, []
    overl = {}

    def edges(f):
        return {frozenset((v, faces[f][(i + 1) % len(faces[f])])) for i, v in enumerate(faces[f])}

    for i, a in enumerate(ids):
        for b in ids[i + 1:]:
            shared = vsets[a] & vsets[b]
            if not shared:
                if solids[a].BoundBox.intersect(solids[b].BoundBox):
                    cv = solids[a].common(solids[b]).Volume / k_mm ** 3
                    worst("common volume of other panels whose boxes meet", cv, f"{a}/{b}")
                continue
            n_pairs += 1
            sa, sb_ = solids[a], solids[b]
            common = sa.common(sb_).Volume / k_mm ** 3
            clash = max(float(sched[a]["clash"] or 0), float(sched[b]["clash"] or 0))
            if clash == 0:
                worst("common volume of neighbours the schedule gives no clash", common,
                      f"{a}/{b}")
            else:
                for pid in (a, b):
                    overl[pid] = max(overl.get(pid, 0.0), common)
            if edge_mode == "bisector" and edges(face_of[a]) & edges(face_of[b]):
                # a mitred joint: its two side faces lie on parallel planes --gap apart
                best = None
                for fa_ in sa.Faces:
                    for fb_ in sb_.Faces:
                        pa_, pb_ = fa_.Surface.Axis, fb_.Surface.Axis
                        if abs(abs(pa_.dot(pb_)) - 1) < 1e-6:
                            pd = abs((fb_.Vertexes[0].Point - fa_.Vertexes[0].Point)
                                     .dot(pa_)) / k_mm
                            if (fa_.distToShape(fb_)[0] / k_mm < 2 * gap + 1e-9
                                    and (best is None or abs(pd - gap) < best)):
                                best = abs(pd - gap)
                if best is None:  # (an edge vanished there, or a butt joint)
                    unfaced.append(f"{a}/{b}")
                else:
                    worst("mitred joint: side planes' distance - gap", best, f"{a}/{b}")
    if unfaced:
        print(f"mitred joints without two parallel side faces (vanished edges, butt joints): "
              f"{len(unfaced)}, first {unfaced[0]}")
    print(f"neighbour pairs checked: {n_pairs}")
    for pid in ids:
        cl = float(sched[pid]["clash"] or 0)
        if cl > 0 and overl.get(pid, 0) <= 0:
            worst("schedule clash > 0 but no neighbour's solid overlaps it (clash)", cl, pid)
    print("panels with a clash in the schedule:",
          sum(float(sched[p]["clash"] or 0) > 0 for p in ids),
          "with a common volume in the STEP:", sum(v > 0 for v in overl.values()))
    # ---- the sheets: footprints inside the sheet less the margin, the spacing apart
    from shapely.ops import unary_union

    # the run's own (facet panels nests 10 mm from the edges and 6 mm apart unless told
    # otherwise, in --units: without --margin and --spacing this checked 0 and 0)
    margin = float(rep["options"]["margin"])
    spacing = float(rep["options"]["spacing"])
    feet = [unary_union([Polygon(c).buffer(0)] + [Polygon(t).buffer(0)
                                                  for t in part_top.get(i, [])])
            for i, c in enumerate(cuts)]
    name = {i: pid for pid, i in dxf_part.items()}
    for i, f in enumerate(feet):
        x0, y0, x1, y1 = f.bounds
        cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
        on = [r for r in sheet_rects if r[:, 0].min() <= cx <= r[:, 0].max()
              and r[:, 1].min() <= cy <= r[:, 1].max()]
        if len(on) != 1:
            print("  !! a part on", len(on), "sheets")
            continue
        sx0, sy0 = on[0].min(axis=0)
        sx1, sy1 = on[0].max(axis=0)
        worst("part past its sheet less the margin", max(sx0 + margin - x0, sy0 + margin - y0,
                                                         x1 - (sx1 - margin), y1 - (sy1 - margin)),
              name.get(i, "?"))
    bounds = np.array([f.bounds for f in feet])
    reach = 2 * spacing + 1e-9
    for i, f in enumerate(feet):
        near = np.flatnonzero((bounds[:, 0] <= bounds[i, 2] + reach)
                              & (bounds[:, 2] >= bounds[i, 0] - reach)
                              & (bounds[:, 1] <= bounds[i, 3] + reach)
                              & (bounds[:, 3] >= bounds[i, 1] - reach))
        for j in near[near > i]:
            worst("spacing - distance between two parts' footprints",
                  spacing - f.distance(feet[j]), f"{name.get(i, '?')}/{name.get(j, '?')}")
            worst("area shared by two parts' footprints", f.intersection(feet[j]).area,
                  f"{name.get(i, '?')}/{name.get(j, '?')}")
    print(f"sheets: DXF {len(sheet_rects)}, report {len(rep['sheets'])}")
    for k, (v, where) in findings.items():
        print(f"  {k:62s} {v:10.3g}  {where}")
    for line in log.splitlines():
        if any(w in line for w in ("joints", "nodes", "warning", "vanished")):
            print("  log:", line.strip()[:200])


if __name__ == "__main__":
    main()
