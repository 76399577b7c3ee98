"""check.py [case names]: the default solve (with the quality re-solve) of each
case: iterations (first solve's), quality outcome, smallest angle, new narrow
corners; 1 against 2 threads bit for bit."""
import sys, time
from cases import selected, data_options, new_narrow, np, facet
names = sys.argv[1:]
for name, data, m in selected(names):
    edges = m.edges()
    mean_edge = float(np.mean(np.linalg.norm(m.vertices[edges[:, 0]] - m.vertices[edges[:, 1]], axis=1)))
    t = time.process_time()
    r = facet.planarize(m, **data_options(data), threads=1)
    dt = time.process_time() - t
    n, amin = new_narrow(m, r.mesh.vertices)
    same = ''
    if '--threads' in sys.argv:
        r2 = facet.planarize(m, **data_options(data), threads=2)
        same = f" same_bits_1v2={np.array_equal(r.mesh.vertices, r2.mesh.vertices)}"
    print(f"{name:8s} {data:8s} it={r.iterations:5d} (first {r.first_iterations}) {r.quality_check} "
          f"resolves={r.quality_resolves} stop={r.stop_reason} pl={float(np.max(r.planarity.max_rel)):.1e} "
          f"min={amin:6.2f} new<5={n:3d} lib_narrow={r.narrow_corners} "
          f"dist={r.quality.as_dict()['distance_rms'] / mean_edge:.4f} cpu={dt:.2f}{same}", flush=True)
