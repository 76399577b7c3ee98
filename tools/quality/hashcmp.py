"""hashcmp.py WORKBENCH OUT [MAX_FACES]: the default solve (method auto, one
thread) of every benchmark family mesh up to MAX_FACES faces (110000) and
every public mesh (tests/data and /work/shared/data), with the facet package
found in WORKBENCH (a worktree's workbench/, to compare branches): per mesh
iterations, stop reason, planarity, smallest corner, quality outcome and a
hash of the result's bits."""
import hashlib, json, os, sys, time
wb, out = sys.argv[1], sys.argv[2]
max_faces = int(sys.argv[3]) if len(sys.argv) > 3 else 110000
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [wb, os.path.join(HERE, '..', 'bench')]
import numpy as np
import facet, families


specs = families.family_specs(max_faces=max_faces) + [{"family": "hypar", "n": n, "name": f"hypar{n}"}
                                                       for n in (32, 40, 48, 56, 60, 63, 65, 72)]
public, _ = families.public_meshes(include_shared=True)
with open(out, 'w') as f:
    for spec in specs + public:
        if 'path' in spec:
            m = facet.read_mesh(spec['path'])
        else:
            b = families.generate(spec)
            m = facet.PolyMesh(b.vertices, b.face_start, b.face_vertices)
        t = time.process_time()
        r = facet.planarize(m, threads=1)
        dt = time.process_time() - t
        V = np.ascontiguousarray(r.mesh.vertices)
        ang = float(np.min(r.quality.min_angle))
        row = dict(it=int(r.iterations), stop=str(r.stop_reason), rel=float(np.max(r.planarity.max_rel)),
                   ang=round(ang, 3), quality=getattr(r, 'quality_check', '-'),
                   sha=hashlib.sha1(V.tobytes()).hexdigest()[:16], cpu=round(dt, 2), faces=m.n_faces)
        print(spec['name'], json.dumps(row), file=f, flush=True)
