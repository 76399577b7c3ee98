# SPDX-License-Identifier: LGPL-2.1-or-later
"""FreeCAD's triangulation of a shape (``MeshPart.meshFromShape``, Mefisto) with progress and
Cancel.

Mefisto is one call that reports nothing and cannot be stopped, and its time grows faster
than its triangles: a 12 x 12 m BSpline face cut into edges of 1/100 of its diagonal took
1 s (8,000 triangles), of 1/200 13 s (32,000), of 1/300 over three minutes (130,000). A
large one is therefore made in a worker process (``facet.parallel.run_chunks``, as the STEP
file is) while the recompute's progress shows a busy bar; Cancel stops the worker. The
triangles are the same as those made here: the worker reads the shape from its BREP and
makes the same call.
"""

import math

#: Triangles (estimated from the shape's area and the edge length) from which the
#: triangulation runs in a worker process when someone listens for progress (below it, the
#: worker's start, about a second, would cost more than it saves).
WORKER_TRIANGLES = 10000


def estimated_triangles(shape, max_length):
    """How many equilateral triangles with edges ``max_length`` cover ``shape``'s area."""
    return 4.0 * float(shape.Area) / (math.sqrt(3.0) * float(max_length) ** 2)


def triangles_from_shape(shape, max_length, label, progress=None):
    """The triangles of ``MeshPart.meshFromShape(Shape=shape, MaxLength=max_length)`` as a
    ``facet.PolyMesh`` (``facetwb.conversion.mesh_from_mesh``; `label` names the source).

    With ``progress`` (a ``facetwb.progress`` reporter, or any ``progress(done, total)``)
    and at least :data:`WORKER_TRIANGLES` estimated triangles, made in a worker process:
    ``progress(0, 0)`` (a busy bar) every 0.2 s meanwhile, True from it stops the worker and
    raises ``facet.Cancelled`` ("triangulating LABEL cancelled"). Where no worker can run
    (no Python interpreter, or FreeCAD not found by it), made here as without ``progress``;
    where the mesher fails or crashes in the worker, a ``conversion.SourceError`` names the
    source (made here again, it would have taken as long with no Cancel, and a crash would
    have taken FreeCAD down).
    """
    import MeshPart

    from facet.errors import Cancelled
    from facet.parallel import WorkerError, python_executable, run_chunks
    from facetwb.conversion import SourceError, mesh_from_mesh, mesh_from_topology

    if (progress is not None and estimated_triangles(shape, max_length) >= WORKER_TRIANGLES
            and python_executable() is not None):
        try:
            (topology,) = run_chunks("facetwb.tessellation:_triangulate",
                                     [(shape.exportBrepToString(), float(max_length))], None,
                                     1, progress=lambda done, total: progress(0, 0))
        except Cancelled:
            raise Cancelled(f"triangulating {label} cancelled") from None
        except WorkerError as error:
            raise SourceError(f"{label}: FreeCAD's mesher failed in a worker process "
                              f"({error})") from None
        if topology is not None:
            return mesh_from_topology(*topology, label)
        # (None: the worker found no FreeCAD: made here, as before)
    return mesh_from_mesh(MeshPart.meshFromShape(Shape=shape, MaxLength=max_length), label)


def _triangulate(chunk, settings):
    """In a worker process: the BREP's triangulation's ``Topology``, points as (x, y, z);
    None where FreeCAD or its mesher cannot be imported here."""
    from facet.step import FreeCADMissing, import_freecad

    try:
        import_freecad()
        import MeshPart
        import Part
    except (FreeCADMissing, ImportError):
        return None

    brep, max_length = chunk
    shape = Part.Shape()
    shape.importBrepFromString(brep)
    points, facets = MeshPart.meshFromShape(Shape=shape, MaxLength=max_length).Topology
    return [(p.x, p.y, p.z) for p in points], [tuple(f) for f in facets]
