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
    X(FACET_ERROR_TOO_LARGE, -11, "mesh too large")                                   \
    X(FACET_ERROR_PLAN_DEGENERATE_FACE, -20, "face has collinear corners in plan")    \
    X(FACET_ERROR_BAD_WEIGHT, -21, "weight not finite and > 0")                       \
    X(FACET_ERROR_BAD_TARGET, -22, "target height not finite")                        \
    X(FACET_WARNING_TRIVIAL_LIFTING, 10, "plan admits only the trivial liftings")     \
    X(FACET_WARNING_PLANARITY, 11, "lifted faces not planar to 1e-9")

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
/* Lifting plan drawings                                                      */
/* ------------------------------------------------------------------------ */

/* A lifting of a plan (a facet_mesh whose x, y are the plan and whose z is
 * ignored) gives every vertex a height z so that every face is planar: the
 * corners of face f satisfy z = a_f x + b_f y + c_f. The liftings form a
 * linear space (the lifting space) that contains the three affine (trivial)
 * liftings 1, x, y. A lifter computes, from one rank-revealing sparse QR
 * (SuiteSparseQR) of the planarity constraints, the lifting closest to any
 * targets in the weighted least-squares sense
 *
 *     minimize sum_v w_v (z_v - t_v)^2  subject to every face planar,
 *
 * the dimension of the lifting space and bases of it.
 *
 * Constraints: a face with k corners gives k-3 rows, an orthonormal basis of
 * the complement of span(1, x, y) over its corners (computed on the face's
 * own centred and scaled corners, so plan units and placement do not
 * matter). Redundant and nearly redundant rows are normal in real plans: the
 * rank is decided by SPQR's column-norm test with tolerance rank_tol (on
 * unit-norm rows scaled by 1/sqrt of the weights normalised to mean 1;
 * <= 0 means 1e-10). A constraint dependent on the others to within
 * rank_tol is treated as dependent (the lifting then violates it by about
 * that much, inside the 1e-9 planarity promise); the others are enforced
 * exactly, so a drawing that is liftable only up to coarser rounding lifts
 * only trivially. */

typedef struct facet_lifter facet_lifter;

typedef struct facet_lift_options {
    double rank_tol; /* <= 0: 1e-10 */
} facet_lift_options;

typedef struct facet_lift_result {
    int32_t dimension;          /* of the lifting space */
    int32_t trivial_dimension;  /* 3 */
    double planarity_max_abs;   /* largest vertical distance of a corner from its face's
                                   least-squares plane (>= the true distance; 0 for
                                   triangles) */
    double planarity_max_rel;   /* the same relative to each face's mean 3D edge length */
    double target_rms;          /* RMS of z - t over all vertices */
    double target_max;          /* largest |z - t| */
    int32_t target_max_vertex;  /* where */
    double seconds;             /* wall time of the solve */
} facet_lift_result;

/* Validates the plan (as facet_mesh_validate, checking x and y; warnings
 * are not errors), refuses faces whose corners are collinear in plan
 * (FACET_ERROR_PLAN_DEGENERATE_FACE) and weights that are not finite and > 0
 * (FACET_ERROR_BAD_WEIGHT; weights may be NULL: all 1), copies what it needs
 * and factorizes. options may be NULL. Deterministic: when the BLAS is
 * OpenBLAS, the lifter's calls run it single-threaded (its process-wide
 * setting, restored afterwards), since its threaded kernels round
 * differently for different thread counts. */
facet_status facet_lifter_create(const facet_mesh *plan, const double *weights,
                                 const facet_lift_options *options, facet_lifter **out,
                                 facet_error *error);

void facet_lifter_free(facet_lifter **lifter);

/* Dimension of the lifting space (>= 3), and the factorization's time. */
int32_t facet_lifter_dimension(const facet_lifter *lifter);
double facet_lifter_factor_seconds(const facet_lifter *lifter);

/* The optimal lifting of targets[n_vertices] into heights[n_vertices] (may
 * be the same array). result may be NULL. Returns FACET_WARNING_TRIVIAL_LIFTING
 * when the plan admits only the affine liftings (heights are then the
 * weighted best-fitting plane), FACET_WARNING_PLANARITY when a face is planar
 * only to more than 1e-9 relative (then said in the message). A non-finite
 * target gives FACET_ERROR_BAD_TARGET naming the vertex. */
facet_status facet_lifter_solve(facet_lifter *lifter, const double *targets, double *heights,
                                facet_lift_result *result, facet_error *error);

/* The fundamental lifting of a vertex: the lifting closest (weighted) to the
 * unit target at that vertex and 0 elsewhere, into heights[n_vertices]. Costs
 * two applications of the stored Q, no new factorization. */
facet_status facet_lifter_fundamental(facet_lifter *lifter, int32_t vertex, double *heights,
                                      facet_error *error);

typedef enum facet_basis_kind {
    FACET_BASIS_ORTHONORMAL = 0, /* any W-orthonormal basis (fast: no eigen-solve) */
    FACET_BASIS_EIGEN = 1        /* eigen-liftings, smoothest first */
} facet_basis_kind;

/* The first count functions of a basis of the lifting space, basis k in
 * basis[k*n_vertices ...]; values[count] (may be NULL) gets each function's
 * Dirichlet energy z' L z (L the combinatorial Laplacian of the plan's
 * edges). Functions 0..2 are always the trivial liftings 1, x, y made
 * orthonormal in the weighted inner product sum_v w_v a_v b_v; the rest are
 * orthogonal to them and to each other in that inner product. For
 * FACET_BASIS_EIGEN the rest minimise z' L z / z' W z in turn (the
 * eigenvectors of P L P for uniform weights), smoothest first. The eigen
 * basis is dense: it is refused (FACET_ERROR_TOO_LARGE) when the dimension
 * exceeds 2000 or n_vertices * dimension exceeds 2e7. Signs are fixed so the
 * largest-magnitude entry of each function is positive. */
facet_status facet_lifter_basis(facet_lifter *lifter, facet_basis_kind kind, int32_t count,
                                double *basis, double *values, facet_error *error);

/* The last error's message of a handle ("" when none). */
const char *facet_lifter_message(const facet_lifter *lifter);

#ifdef __cplusplus
}
#endif
#endif /* FACET_H */
