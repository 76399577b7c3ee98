/* SPDX-License-Identifier: LGPL-2.1-or-later */
/*
 * facet.h -- the public interface of libfacet, Facet's solver library.
 *
 * Contract (after CHOLMOD's):
 *  - Every public symbol starts with facet_ / FACET_.
 *  - Parameter order: handle first, then inputs, then outputs, then the error
 *    record (facet_error *, which may always be NULL).
 *  - Calls that can fail return a facet_status: 0 is OK, negative is an error,
 *    positive is a warning (the call did its work; something is worth saying).
 *    On error the error record holds a message that names the input and what
 *    is wrong with it ("face 17 repeats vertex 4"), and outputs are untouched
 *    unless stated otherwise.
 *  - The library never prints, never aborts, never exits, and keeps no global
 *    state: it is reentrant, and separate handles may be used from separate
 *    threads at once. One handle must not be used by two threads at once.
 *  - Memory is caller-owned wherever it can be: outputs are arrays the caller
 *    allocates with the sizes stated. Handles are created through an
 *    out-parameter and freed by facet_*_free(T **), which sets the pointer to
 *    NULL and accepts NULL.
 *  - Deterministic: the same inputs and options give the same bits whatever
 *    the thread count.
 *
 * Data model: a polygon mesh is n_vertices points xyz[3*n_vertices] and
 * n_faces faces in CSR form: face f has the vertices
 * face_vertices[face_start[f] .. face_start[f+1]-1], in order around the face.
 * Faces of any degree >= 3 live side by side. face_start[0] must be 0.
 */
#ifndef FACET_H
#define FACET_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define FACET_VERSION_MAJOR 0
#define FACET_VERSION_MINOR 1
#define FACET_VERSION_PATCH 0

/* X-macro: name, value, description. Errors < 0 < warnings. */
#define FACET_STATUS_LIST(X)                                                          \
    X(FACET_OK, 0, "ok")                                                              \
    X(FACET_WARNING_MESH, 1, "mesh has non-manifold edges or isolated vertices")     \
    X(FACET_WARNING_NOT_CONVERGED, 2, "iteration limit reached before tolerance")    \
    X(FACET_ERROR_INVALID_ARGUMENT, -1, "invalid argument")                           \
    X(FACET_ERROR_EMPTY_MESH, -2, "empty mesh")                                       \
    X(FACET_ERROR_BAD_FACE_START, -3, "face offsets are not increasing from 0")       \
    X(FACET_ERROR_INDEX_OUT_OF_RANGE, -4, "vertex index out of range")                \
    X(FACET_ERROR_DEGENERATE_FACE, -5, "face with fewer than 3 distinct vertices")    \
    X(FACET_ERROR_REPEATED_VERTEX, -6, "vertex repeated in a face")                   \
    X(FACET_ERROR_NONFINITE, -7, "NaN or infinite coordinate")                        \
    X(FACET_ERROR_OUT_OF_MEMORY, -8, "out of memory")                                 \
    X(FACET_ERROR_NUMERICAL, -9, "numerical failure")                                 \
    X(FACET_ERROR_CANCELLED, -10, "cancelled")                                        \
    X(FACET_ERROR_TOO_LARGE, -11, "mesh too large")                                  \
    X(FACET_ERROR_NOT_PLANAR, -30, "faces not planar within the tolerance")           \
    X(FACET_ERROR_NOT_ORIENTABLE, -31, "faces cannot be oriented consistently")       \
    X(FACET_ERROR_PANEL_GEOMETRY, -32, "panel outline degenerate or consumed")        \
    X(FACET_WARNING_PANEL_NON_MANIFOLD, 20, "non-manifold edges treated as boundary")

typedef enum facet_status {
#define FACET_STATUS_ENUM(name, value, text) name = value,
    FACET_STATUS_LIST(FACET_STATUS_ENUM)
#undef FACET_STATUS_ENUM
} facet_status;

/* A static string for a status code ("vertex index out of range").
 * Never NULL; thread-safe. */
const char *facet_status_string(facet_status status);

/* "0.1.0". Thread-safe. */
const char *facet_version(void);

/* The error record filled by a failing call. face and vertex are the offending
 * indices, or -1 when the error is not about one face or vertex. */
typedef struct facet_error {
    facet_status status;
    int64_t face;
    int64_t vertex;
    char message[512];
} facet_error;

/* A polygon mesh, borrowed: the library never keeps these pointers past the
 * call they are passed to, except where a handle says it copies them. */
typedef struct facet_mesh {
    int32_t n_vertices;
    int32_t n_faces;
    const double *xyz;            /* 3*n_vertices */
    const int32_t *face_start;    /* n_faces+1, face_start[0] == 0 */
    const int32_t *face_vertices; /* face_start[n_faces] */
} facet_mesh;

/* ------------------------------------------------------------------------ */
/* Validation                                                                */
/* ------------------------------------------------------------------------ */

/* What validation found that is not an error. */
typedef struct facet_mesh_report {
    int64_t n_edges;               /* distinct undirected edges */
    int64_t n_boundary_edges;      /* edges with one face */
    int64_t n_non_manifold_edges;  /* edges with more than two faces */
    int64_t n_isolated_vertices;   /* vertices no face uses */
    int64_t first_non_manifold_edge[2]; /* its vertices, or -1 -1 */
    int64_t first_isolated_vertex;      /* or -1 */
    int32_t max_degree;            /* largest face degree */
} facet_mesh_report;

/* Checks a mesh. Errors, in the order checked: FACET_ERROR_EMPTY_MESH (no
 * vertex or no face), FACET_ERROR_BAD_FACE_START, FACET_ERROR_NONFINITE (first
 * vertex with a NaN or infinite coordinate), FACET_ERROR_INDEX_OUT_OF_RANGE,
 * FACET_ERROR_REPEATED_VERTEX (a vertex twice in a face with at least 3
 * distinct vertices), FACET_ERROR_DEGENERATE_FACE (fewer than 3 distinct).
 * Returns FACET_WARNING_MESH when non-manifold edges or isolated vertices were
 * found (counted in *report). report may be NULL. Allocates a temporary edge
 * table of 16 bytes per corner. Thread-safe. */
facet_status facet_mesh_validate(const facet_mesh *mesh, facet_mesh_report *report,
                                 facet_error *error);

/* ------------------------------------------------------------------------ */
/* Planarity                                                                 */
/* ------------------------------------------------------------------------ */

/* Per-face planarity, each output an array of n_faces doubles (any may be
 * NULL):
 *  max_abs    largest distance of the face's vertices from their
 *             least-squares plane, model units;
 *  rms_abs    RMS of those distances;
 *  mean_edge  mean edge length of the face (relative figures are
 *             max_abs / mean_edge);
 *  diagonal   for quads, libigl's measure: distance between the two diagonal
 *             lines divided by the mean diagonal length; -1 for other faces.
 * The mesh must be valid (facet_mesh_validate); this call checks only sizes.
 * threads <= 0 means the OpenMP default. Results do not depend on threads. */
facet_status facet_planarity(const facet_mesh *mesh, int threads, double *max_abs,
                             double *rms_abs, double *mean_edge, double *diagonal,
                             facet_error *error);

/* Least-squares plane of n points (xyz[3*n]): unit normal and offset with
 * normal . x + offset = 0 on the plane; returns the smallest eigenvalue of
 * the (unnormalised) scatter matrix, or -1 when n < 3. Thread-safe. */
double facet_fit_plane(int32_t n, const double *xyz, double normal[3], double *offset);

/* ------------------------------------------------------------------------ */
/* Planarization                                                             */
/* ------------------------------------------------------------------------ */

typedef enum facet_method {
    FACET_METHOD_LOCAL_LOCAL = 0,  /* paper's Algorithm Planarize */
    FACET_METHOD_LOCAL_GLOBAL = 1  /* normals local, (q, d) by one sparse solve */
} facet_method;

typedef enum facet_stop_reason {
    FACET_STOP_NONE = 0,
    FACET_STOP_TOLERANCE = 1,   /* planarity reached tol_abs or tol_rel */
    FACET_STOP_MAX_ITER = 2,    /* max_iter iterations done, tolerance not met */
    FACET_STOP_ITERATIONS = 3,  /* fixed iteration count done (no early stop) */
    FACET_STOP_STAGNATION = 4,  /* mu at its floor and planarity no longer falls */
    FACET_STOP_CANCELLED = 5
} facet_stop_reason;

/* Progress callback: called once per iteration from the calling thread, with
 * the iteration just finished, the iteration limit and the largest relative
 * planarity. Return nonzero to cancel (the solve returns
 * FACET_ERROR_CANCELLED with the last iterate in the output). */
typedef int (*facet_progress_fn)(void *user, int32_t iteration, int32_t max_iter,
                                 double planarity_max_rel);

typedef struct facet_planarize_options {
    facet_method method;
    double mu0;          /* first penalty weight in (0, 1]; 1 = start at the input */
    double ratio;        /* mu <- max(ratio * mu, mu_min) each iteration, in (0, 1] */
    double mu_min;       /* floor on mu, > 0: without it L/L diverges */
    double tol_abs;      /* stop when every face's max_abs <= tol_abs (0: off) */
    double tol_rel;      /* stop when every face's max_abs/mean_edge <= tol_rel (0: off) */
    int32_t max_iter;    /* iteration limit */
    int32_t iterations;  /* > 0: run exactly this many, no early stop */
    int32_t threads;     /* <= 0: OpenMP default */
    int32_t warm;        /* nonzero: start from the previous result of this handle */
    facet_progress_fn progress; /* may be NULL */
    void *progress_user;
} facet_planarize_options;

/* Defaults for a method: mu0 1, ratio 0.95; mu_min 1e-6 (L/L) or 1e-12 (L/G);
 * tol_rel 1e-6, tol_abs off; max_iter 3000 (L/L) or 1000 (L/G). */
void facet_planarize_options_default(facet_method method, facet_planarize_options *options);

typedef struct facet_planarize_result {
    int32_t iterations;
    facet_stop_reason stop_reason;
    double mu;                 /* penalty weight of the last iteration */
    double planarity_max_abs;  /* model units */
    double planarity_max_rel;  /* relative to each face's mean edge length */
    double seconds;            /* wall time of the solve */
} facet_planarize_result;

/* A planarization solver for one mesh topology. It copies the topology and
 * keeps its workspace (normals, offsets, the symbolic factorization), so a
 * re-solve after the designer moved vertices is cheap and may start warm. */
typedef struct facet_planarizer facet_planarizer;

/* Validates the mesh (as facet_mesh_validate; warnings are not errors) and
 * copies its topology. The coordinates in mesh->xyz are ignored here. */
facet_status facet_planarizer_create(const facet_mesh *mesh, facet_planarizer **out,
                                     facet_error *error);

void facet_planarizer_free(facet_planarizer **planarizer);

/* Planarizes the control positions xyz_in[3*n_vertices] (same topology as at
 * create) into xyz_out[3*n_vertices] (may equal xyz_in). Coordinates are
 * centred and scaled inside. On error the message is also kept in the handle
 * (facet_planarizer_message). xyz_out never receives a NaN: a non-finite
 * iterate stops the solve with FACET_ERROR_NUMERICAL and xyz_out is left
 * untouched. Returns FACET_WARNING_NOT_CONVERGED when max_iter ran out. */
facet_status facet_planarizer_solve(facet_planarizer *planarizer, const double *xyz_in,
                                    const facet_planarize_options *options,
                                    double *xyz_out, facet_planarize_result *result,
                                    facet_error *error);

/* The last error's message of a handle ("" when none). Valid until the next
 * call on the handle. */
const char *facet_planarizer_message(const facet_planarizer *planarizer);

/* ------------------------------------------------------------------------ */
/* Panels                                                                    */
/* ------------------------------------------------------------------------ */

/* Panel geometry for a planar polygon mesh: each face becomes a solid slab
 * of the given thickness whose top and bottom outlines are the intersections
 * of its two offset planes with its edge planes, so every side face is
 * planar and the solid is a true polyhedron.
 *
 * Orientation: faces are oriented consistently by propagation across
 * manifold edges (two faces per edge); each connected part keeps the winding
 * of its lowest-numbered face, all reversed when flip is set. A face's
 * oriented normal n follows its consistent winding (counter-clockwise seen
 * from +n). "Top" is the +n side.
 *
 * Offset side: OUTER puts the panel on the +n side of the mesh surface (the
 * bottom face lies on the mesh), INNER on the -n side (the top face lies on
 * it), CENTER half on each side.
 *
 * Edge planes: SQUARE is perpendicular to the panel and contains the edge;
 * BISECTOR (mitred) is the plane through the edge that halves the angle
 * between the two panels' planes, so neighbours meet without overlap.
 * Boundary and non-manifold edges are always square. A joint gap g moves
 * every edge plane by g/2 along its inward normal: between two mitred
 * neighbours the joint is a slot of constant width g; with square edges each
 * edge line moves g/2 into its panel, measured in the panel's plane.
 *
 * Angles (radians), per face corner k, for the edge from corner k to k+1:
 *  dihedral  angle between the two panels on their bottom (-n) side: pi
 *            when flat, below pi where the top side is convex (a ridge);
 *            0 on boundary edges (neighbor -1);
 *  bevel     angle of the side face from square to the panel: 0 for square
 *            edges, positive when the top face is the larger (the side
 *            leans outwards going up); half the fold for mitred edges.
 *
 * Node deviation: at each vertex the bisector planes of its edges (square on
 * the boundary) all pass through it; they share a line (a torsion-free node,
 * which can be built with a straight node axis) when their normals are
 * coplanar. The deviation is the largest angle between an edge plane's
 * normal and the plane best fitting those normals (radians; 0 for vertices
 * with fewer than 3 edges).
 *
 * Unfold frame: per face a rigid transform, 12 doubles R (row-major 3x3) and
 * t, with flat = R x + t: corner 0 of the face (projected onto its plane)
 * goes to the origin, the edge from corner 0 to corner 1 along +x, the
 * oriented normal to +z. A face whose winding was reversed (reversed[f] = 1)
 * then runs clockwise in the xy plane.
 *
 * Coordinates are centred and scaled inside. */

typedef enum facet_panel_offset {
    FACET_PANEL_OFFSET_OUTER = 0,
    FACET_PANEL_OFFSET_INNER = 1,
    FACET_PANEL_OFFSET_CENTER = 2
} facet_panel_offset;

typedef enum facet_panel_edge {
    FACET_PANEL_EDGE_SQUARE = 0,
    FACET_PANEL_EDGE_BISECTOR = 1
} facet_panel_edge;

/* Progress: faces done of total; return nonzero to cancel
 * (FACET_ERROR_CANCELLED, outputs unspecified). Called from the calling thread. */
typedef int (*facet_count_progress_fn)(void *user, int64_t done, int64_t total);

typedef struct facet_panel_options {
    double thickness;          /* > 0, model units */
    facet_panel_offset offset;
    double gap;                /* >= 0, joint width, model units */
    facet_panel_edge edge;
    int32_t flip;              /* nonzero: reverse every face's orientation */
    double planarity_tol_abs;  /* a face is planar when its vertices are within */
    double planarity_tol_rel;  /* max(tol_abs, tol_rel * mean edge) of its plane */
    facet_count_progress_fn progress; /* may be NULL */
    void *progress_user;
} facet_panel_options;

/* thickness 1, outer, gap 0, square, no flip, tol_abs 0, tol_rel 1e-6. */
void facet_panel_options_default(facet_panel_options *options);

/* Caller-allocated outputs; any pointer may be NULL. nc = face_start[n_faces]
 * (the number of corners). */
typedef struct facet_panel_output {
    double *plane;          /* 4*n_faces: oriented unit normal, d (n.x + d = 0) */
    double *top;            /* 3*nc: top outline corner of each face corner */
    double *bottom;         /* 3*nc: bottom outline corner */
    double *frame;          /* 12*n_faces: unfold frame R, t */
    int32_t *reversed;      /* n_faces: 1 when the face's winding was reversed */
    int32_t *neighbor;      /* nc: face across edge k (corner k to k+1), or -1 */
    double *dihedral;       /* nc, radians */
    double *bevel;          /* nc, radians */
    double *node_deviation; /* n_vertices, radians */
    double *planarity;      /* n_faces: largest vertex distance from its plane */
    int32_t *nonplanar;     /* n_faces: indices of the faces above tolerance */
} facet_panel_output;

typedef struct facet_panel_result {
    int64_t n_nonplanar;          /* faces above the planarity tolerance */
    int64_t n_non_manifold_edges; /* edges with more than two faces */
    int64_t n_reversed;           /* faces whose winding was reversed */
    int32_t n_components;         /* edge-connected parts */
    int64_t worst_node;           /* vertex of max_node_deviation, or -1 */
    double max_node_deviation;    /* radians */
    double max_planarity;         /* model units */
    double seconds;
} facet_panel_result;

/* Computes the panels. The mesh must be valid (facet_mesh_validate); sizes
 * and indices are checked here. Errors: FACET_ERROR_INVALID_ARGUMENT (bad
 * option), FACET_ERROR_NOT_PLANAR (the message names the count and the first
 * faces; planarity, nonplanar and *result are filled),
 * FACET_ERROR_NOT_ORIENTABLE (names the face where orientation conflicts),
 * FACET_ERROR_PANEL_GEOMETRY (consecutive collinear edges, folded-back
 * neighbours, or a gap/bevel that consumes an edge of the outline; names the
 * face and corner), FACET_ERROR_CANCELLED. Returns
 * FACET_WARNING_PANEL_NON_MANIFOLD when edges with more than two faces were
 * treated as boundary. result may be NULL. Unlike the general contract, a
 * failing call may have written part of the outputs (except on
 * FACET_ERROR_INVALID_ARGUMENT): discard them. Serial and O(corners log
 * corners); deterministic. */
facet_status facet_panels(const facet_mesh *mesh, const facet_panel_options *options,
                          facet_panel_output *out, facet_panel_result *result,
                          facet_error *error);

#ifdef __cplusplus
}
#endif
#endif /* FACET_H */
