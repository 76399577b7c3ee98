"""table.py [case names]: docs/solver-notes.md's table for "Quality by default
(branch quality5)": per case, the first solve alone (quality_angle=0), the
default (with the re-solve) and the exact penalty path (no Anderson,
hold_tol 1e-9, hold_max 200): iterations, smallest angle, new narrow corners,
RMS distance from the input surface in mean edges; one thread."""
import sys, time
from cases import CASES, data_options, new_narrow, np, facet
names = sys.argv[1:]
cache = {}
VARIANTS = [('before', dict(quality_angle=0)), ('after', {}),
            ('exact', dict(quality_angle=0, anderson=0, hold_tol=1e-9, hold_max=200, max_iter=4000))]
for name, data, mk in CASES:
    if names and name not in names and f'{name}:{data}' not in names:
        continue
    m = cache.setdefault(name, mk())
    edges = m.edges()
    V = m.vertices
    mean_edge = float(np.mean(np.linalg.norm(V[edges[:, 0]] - V[edges[:, 1]], axis=1)))
    cells = []
    for label, extra in VARIANTS:
        t = time.process_time()
        r = facet.planarize(m, **data_options(data), threads=1, **extra)
        dt = time.process_time() - t
        n, amin = new_narrow(m, r.mesh.vertices)
        d = r.quality.as_dict()['distance_rms'] / mean_edge
        cells.append(f"{label}: it={r.iterations}({r.first_iterations}) {r.quality_check} "
                     f"pl={float(np.max(r.planarity.max_rel)):.1e} min={amin:.2f} new={n} dist={d:.4f} cpu={dt:.1f}")
    print(f"{name} {data} | " + " | ".join(cells), flush=True)
