"""sweep.py "dict(anderson=0)" [case names]: iterations, planarity, smallest angle
and new narrow corners of each case with these options."""
import sys, time
from cases import selected, data_options, new_narrow, np, facet
extra = eval(sys.argv[1]) if len(sys.argv) > 1 else {}
names = sys.argv[2:]
for name, data, m in selected(names):
    t = time.process_time()
    r = facet.planarize(m, **data_options(data), **extra)
    dt = time.process_time() - t
    n, amin = new_narrow(m, r.mesh.vertices)
    print(f"{name:8s} {data:8s} it={r.iterations:5d} stop={r.stop_reason} pl={float(np.max(r.planarity.max_rel)):.1e} "
          f"min={amin:6.2f} new<5={n:3d} dist_rms={getattr(r.quality, 'distance_rms', float('nan'))} cpu={dt:.2f}", flush=True)
