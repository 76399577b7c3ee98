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
 *    the thread count. A thread count above max(64, 4 x processors, the
 *    OpenMP default) is clamped to it.
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
    X(FACET_ERROR_NOTHING_LEFT, -40, "cleanup collapsed every face")                  \
    X(FACET_WARNING_COLLAPSE_SKIPPED, 30, "short edges kept: collapsing them would break the mesh") \
    X(FACET_ERROR_PLAN_DEGENERATE_FACE, -20, "face has collinear corners in plan")    \
    X(FACET_ERROR_BAD_WEIGHT, -21, "weight not finite and > 0")                       \
    X(FACET_ERROR_BAD_TARGET, -22, "target height not finite")                        \
    X(FACET_WARNING_TRIVIAL_LIFTING, 10, "plan admits only the trivial liftings")     \
    X(FACET_WARNING_PLANARITY, 11, "lifted faces not planar to 1e-9") \
    X(FACET_WARNING_LIFTING_RANK, 12, "lifting space's dimension not found reliably") \
    X(FACET_ERROR_NOT_PLANAR, -30, "faces not planar within the tolerance")           \
    X(FACET_ERROR_NOT_ORIENTABLE, -31, "faces cannot be oriented consistently")       \
    X(FACET_ERROR_PANEL_GEOMETRY, -32, "panel outline degenerate or consumed")        \
    X(FACET_WARNING_PANEL_NON_MANIFOLD, 20, "non-manifold edges treated as boundary") \
    X(FACET_ERROR_COORDINATE_RANGE, -60, "coordinate beyond 1e30 in magnitude")

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
 * The mesh must be valid (facet_mesh_validate); this call checks sizes,
 * indices and that coordinates are finite (FACET_ERROR_NONFINITE).
 * threads <= 0 means the OpenMP default. Results do not depend on threads. */
facet_status facet_planarity(const facet_mesh *mesh, int threads, double *max_abs,
                             double *rms_abs, double *mean_edge, double *diagonal,
                             facet_error *error);

/* Least-squares plane of n points (xyz[3*n]): unit normal and offset with
 * normal . x + offset = 0 on the plane; returns the smallest eigenvalue of
 * the (unnormalised) scatter matrix, or -1 (normal and offset untouched) when
 * n < 3, xyz or normal is NULL, or a coordinate is NaN or infinite.
 * Thread-safe. */
double facet_fit_plane(int32_t n, const double *xyz, double normal[3], double *offset);

/* ------------------------------------------------------------------------ */
/* Planarization                                                             */
/* ------------------------------------------------------------------------ */

typedef enum facet_method {
    FACET_METHOD_LOCAL_LOCAL = 0,  /* paper's Algorithm Planarize */
    FACET_METHOD_LOCAL_GLOBAL = 1, /* normals local, (q, d) by one sparse solve */
    FACET_METHOD_AUTO = 2          /* L/G up to FACET_AUTO_LG_MAX_CORNERS face corners
                                      (its factorization's memory), L/L above; see
                                      facet_planarize_options_default; where it picks
                                      L/G it also solves by L/L and returns the result
                                      closer to the design (FACET_STAGE_COMPARE) */
} facet_method;

/* The largest mesh (in face corners: 4 per quad) that FACET_METHOD_AUTO
 * solves by L/G: 10,000 quads or 6,666 hexagons. Above it L/L (with its
 * finish and quality re-solves) reaches 1e-6 6-165 times faster than L/G
 * with the comparison, closer to the input surface than L/G and than the
 * exact penalty path, in under 1 KB per face (L/G: 1.3-1.8 KB); on the
 * benchmark meshes just above it auto already returned L/L's result
 * (docs/solver-notes.md, "Method auto: L/L from 10,000 quads"). */
#define FACET_AUTO_LG_MAX_CORNERS 40000

/* The same without the staircase schedule (hold_tol 0), with which L/L
 * cannot finish (facet_planarizer_choose_method): 50,000 quads or 33,000
 * hexagons. Above it L/G's CHOLMOD factor takes 2-4 KB per face and a
 * solve minutes (docs/solver-notes.md, "Large meshes"). */
#define FACET_AUTO_LG_MAX_CORNERS_STAIRCASE 200000

/* The deepest Anderson history (facet_planarize_options.anderson). */
#define FACET_ANDERSON_MAX 16

/* The largest a term's weight may be, as a multiple of data_tangent (every
 * weight of facet_planarize_options but data_tangent and time_budget): beside
 * a larger one the data term is lost to rounding and the vertices drift. */
#define FACET_WEIGHT_SPAN 1e12

/* The largest per-face planarity weight (facet_planarizer_set_face_weights):
 * the planarity term's own weight grows to 1 / mu_min over the schedule. */
#define FACET_FACE_WEIGHT_MAX 1e6

typedef enum facet_stop_reason {
    FACET_STOP_NONE = 0,
    FACET_STOP_TOLERANCE = 1,   /* planarity (and constraints) reached tol_abs or tol_rel */
    FACET_STOP_MAX_ITER = 2,    /* max_iter iterations done, tolerance not met */
    FACET_STOP_ITERATIONS = 3,  /* fixed iteration count done (no early stop) */
    FACET_STOP_STAGNATION = 4,  /* mu at its floor and planarity no longer falls */
    FACET_STOP_CANCELLED = 5,
    FACET_STOP_TIME = 6         /* time_budget seconds used, tolerance not met */
} facet_stop_reason;

/* What happens at the boundary of an open mesh. */
typedef enum facet_boundary_mode {
    FACET_BOUNDARY_FREE = 0,    /* boundary vertices move like the others */
    FACET_BOUNDARY_FIXED = 1,   /* boundary vertices stay where they are (hard) */
    FACET_BOUNDARY_SLIDING = 2  /* boundary vertices stay on the control mesh's boundary
                                   polyline but may slide along it */
} facet_boundary_mode;

/* Keep each face a rigid or similar copy of its control face (paper 6.2:
 * per-face orthogonal Procrustes in the local step). */
typedef enum facet_shape_mode {
    FACET_SHAPE_NONE = 0,
    FACET_SHAPE_ASAP = 1,       /* as similar as possible: rotation and scale */
    FACET_SHAPE_ARAP = 2        /* as rigid as possible: rotation only */
} facet_shape_mode;

typedef enum facet_laplacian_weights {
    FACET_LAPLACIAN_UNIFORM = 0,      /* every neighbour weighs 1 */
    FACET_LAPLACIAN_INVERSE_EDGE = 1  /* 1 / control edge length */
} facet_laplacian_weights;

/* Progress callback: called once per iteration from the calling thread, with
 * the iteration just finished, the iteration limit and the largest relative
 * planarity. Return nonzero to cancel (the solve returns
 * FACET_ERROR_CANCELLED with the last iterate in the output).
 * facet_planarizer_solve reports its quality re-solves (facet_quality_outcome)
 * as part of one solve: `iteration` counts every iteration, re-solves
 * included (the last call's is result.iterations), and `max_iter` bounds the
 * whole solve: options.max_iter (options.iterations for a fixed count) plus,
 * when the solve may re-solve, the limits of the re-solves that may follow;
 * when a re-solve starts it is recomputed as the iterations done, that
 * re-solve's limit and the later ones'. It never grows during a solve and is
 * never below `iteration`, so iteration / max_iter never falls: a progress
 * bar does not run backwards (it may jump forward when a solve ends early).
 * Method AUTO's comparison solve (FACET_STAGE_COMPARE) counts on in the
 * same way, its limit included in the bound from the start.
 * facet_planarizer_stage says which re-solve is running. */
typedef int (*facet_progress_fn)(void *user, int32_t iteration, int32_t max_iter,
                                 double planarity_max_rel);

/* Progress of a step counted in parts (the panels: faces done of total; a lifter's
 * create step: stages done of total); return nonzero to cancel (FACET_ERROR_CANCELLED,
 * outputs unspecified). Called from the calling thread. */
typedef int (*facet_count_progress_fn)(void *user, int64_t done, int64_t total);

/* The energy, in coordinates centred and scaled to a mean edge of 1:
 *
 *   mu * [ data + laplacian * E_lap + boundary_fairness * E_fair
 *          + shape_weight * E_shape + surface_weight * E_surface ]
 * + (1 - mu) * [ sum_faces w_f * sum_corners (n_f . q_i + d_f)^2
 *          + circular * E_circle + parallelogram * E_par + E_slide ]
 *
 * data = sum_i data_tangent |T_i (q_i - p_i)|^2 + data_normal (nu_i . (q_i - p_i))^2
 * with nu_i the control mesh's area-weighted vertex normal and T_i the
 * projection onto its tangent plane: 1 and 1 is point-to-point distance to
 * the control points, a small data_tangent lets vertices slide along the
 * design (the paper's point-to-plane split). E_surface = sum_i (nu_s . (q_i -
 * s_i))^2 with s_i the closest point of the reference surface
 * (facet_planarizer_set_reference) and nu_s its normal there. The terms after
 * (1 - mu) become hard as mu falls; those after mu are soft. Fixed vertices
 * (facet_planarizer_set_fixed and FACET_BOUNDARY_FIXED) are hard throughout.
 * A face of weight 0 (facet_planarizer_set_face_weights) is exempt from
 * planarity (an opening); its planarity is not counted by the tolerance. */
typedef struct facet_planarize_options {
    facet_method method;
    double mu0;          /* first penalty weight in (0, 1]; 1 = start at the input */
    double ratio;        /* mu <- max(ratio * mu, mu_min) each iteration, in (0, 1] */
    double mu_min;       /* floor on mu, > 0: without it L/L diverges */
    double tol_abs;      /* stop when every face's max_abs <= tol_abs (0: off) */
    double tol_rel;      /* stop when every face's max_abs/mean_edge <= tol_rel (0: off) */
    int32_t max_iter;    /* iteration limit */
    int32_t iterations;  /* > 0: run exactly this many, no early stop */
    int32_t threads;     /* <= 0: by mesh size: one thread per FACET_CORNERS_PER_THREAD
                            face corners, at most OpenMP's default */
    int32_t warm;        /* nonzero: start from the previous result of this handle */
    facet_progress_fn progress; /* may be NULL */
    void *progress_user;
    /* --- data terms (soft, >= 0; data_tangent + data_normal + surface_weight > 0) */
    double data_tangent;      /* weight of displacement in the control tangent plane (1) */
    double data_normal;       /* weight of displacement along the control normal (1) */
    double surface_weight;    /* closeness to the reference surface (0; needs one set) */
    /* --- regularizers (soft, >= 0) */
    double laplacian;         /* vertex Laplacian (paper eq. 7), fairing (0) */
    facet_laplacian_weights laplacian_weights;
    double normal_laplacian;  /* face-normal Laplacian in the plane fit (0) */
    double boundary_fairness; /* second differences along boundary polylines (0) */
    facet_shape_mode shape;   /* ASAP / ARAP (NONE) */
    double shape_weight;      /* weight of the shape term (1 when shape is set) */
    /* --- constraints (become hard as mu falls) */
    facet_boundary_mode boundary; /* (FREE) */
    double circular;          /* vertices of each face on a circle: weight (0 = off) */
    double parallelogram;     /* quads as parallelograms: weight (0 = off) */
    double angle_floor;       /* degrees: a corner angle that falls below this (or below
                                 its control angle, if smaller) is opened back to it with
                                 the planarity's weight; inactive while every corner is
                                 wider; let go when it stalls the solve (the quality report
                                 then names the narrow faces). Opt-in: it helps with point
                                 data and hold_tol 0.003, not with plane/surface data or a
                                 sliding boundary (0 = off, the default; < 60) */
    /* --- schedule, acceleration and budget */
    double hold_tol;          /* > 0: staircase schedule: mu falls (by ratio) only once the
                                 largest vertex move of a step is <= hold_tol times that of
                                 the first step at this mu, or after hold_max steps, and
                                 only while the tolerance is not met (0: fall every step) */
    int32_t hold_max;         /* longest stay at one mu in the staircase schedule */
    int32_t anderson;         /* Anderson acceleration history depth (0 = off, at most
                                 FACET_ANDERSON_MAX); on a mesh of 32,768 vertices or
                                 more its least-squares problem is formed over a fixed
                                 eighth of the entries
                                 (docs/solver-notes.md, "Anderson's least squares on a
                                 sample") */
    double time_budget;       /* stop after this many seconds (0 = no budget) */
    /* --- quality by default (facet_planarizer_solve; docs/solver-notes.md, "Quality by
     * default (branch quality5)") */
    double quality_angle;     /* degrees: a cold solve that reaches the tolerance and leaves a
                                 corner below this angle that the input did not have (a
                                 new narrow corner: below it while the input corner was not,
                                 or below half the input corner; or a face folded over
                                 itself, a bowtie, that was not) is solved again along the
                                 penalty path, without Anderson acceleration, until no such
                                 corner is left (5, the default; 0 = off; < 60) */
} facet_planarize_options;

/* Defaults for a method: mu0 1; the staircase schedule (ratio 0.1, hold_tol
 * 0.01, hold_max 40) with Anderson acceleration of depth 5; mu_min 1e-6
 * (L/L) or 1e-12 (L/G and AUTO); tol_rel 1e-6, tol_abs off; max_iter 3000
 * (L/L) or 1000 (L/G and AUTO); data 1 and 1 (point-to-point); no angle
 * floor, no regularizer, other constraint or time budget; quality_angle 5
 * (a result with a new corner under 5 degrees is solved again: see
 * facet_quality_outcome). The paper's
 * schedule is hold_tol 0, anderson 0, ratio 0.7 (L/G) or 0.9 (L/L).
 * AUTO solves by facet_planarizer_choose_method's choice with these
 * options, except that when it picks L/L its floor is at least
 * FACET_LL_MU_MIN; where it picks L/G it also solves by L/L and may return
 * that result (FACET_STAGE_COMPARE). With the staircase (hold_tol > 0),
 * L/L finishes: once mu is at its floor and the step has settled above the
 * tolerance, the data, shape, Laplacian and boundary fairness terms pull
 * towards the iterate itself instead of their own targets, so the planarity
 * no longer stalls near 10 mu_min
 * (docs/solver-notes.md, "Large meshes"). */
void facet_planarize_options_default(facet_method method, facet_planarize_options *options);

/* With options.threads <= 0 a solve runs on one thread per this many face
 * corners (at least one, at most OpenMP's default): 100,000 corners, 25,000
 * quads. Below it a second thread gained nothing on this project's 2-core
 * machine (0.92-1.10 times, 256 to 30,000 quads, to 1e-6) and, while another
 * process held a core, made solves 2 to several hundred times slower (every barrier
 * waits for a descheduled thread); above it L/L gains (1.6 times at 50,000
 * quads). Results do not depend on the thread count. */
#define FACET_CORNERS_PER_THREAD 100000

/* L/L's default floor on mu, also the least FACET_METHOD_AUTO uses when it
 * chooses L/L (below it L/L's vertex step amplifies rounding, and its
 * finish reaches the tolerance instead). */
#define FACET_LL_MU_MIN 1e-6

typedef struct facet_planarize_result {
    int32_t iterations;
    facet_stop_reason stop_reason;
    double mu;                 /* penalty weight of the last iteration */
    double planarity_max_abs;  /* model units, over faces of nonzero weight */
    double planarity_max_rel;  /* relative to each face's mean edge length */
    double constraint_max_rel; /* largest residual of circular, parallelogram and sliding
                                  constraints relative to the mean edge (0 when none) */
    double seconds;            /* wall time of the solve */
    int32_t anderson_accepted; /* accelerated steps kept */
    int32_t anderson_rejected; /* accelerated steps refused by the energy safeguard */
    facet_method method;       /* the method that ran (what FACET_METHOD_AUTO chose) */
    /* quality by default (options.quality_angle; facet_quality_outcome) */
    int32_t quality;           /* FACET_QUALITY_*: checked? recovered? */
    int32_t narrow_corners;    /* new narrow corners in xyz_out (0 unless quality is
                                  FACET_QUALITY_NARROW or NOT_CHECKED; with the check
                                  on, a result short of the tolerance has them counted,
                                  not re-solved) */
    int32_t quality_resolves;  /* re-solves run (0: the first solve's result) */
    int32_t quality_timed_out; /* 1: options.time_budget ended the re-solves before one
                                  kept every corner open (quality FACET_QUALITY_NARROW) */
    int32_t first_iterations;  /* iterations of the first solve; `iterations` counts every
                                  solve's, `seconds` their time */
    /* method AUTO's comparison of L/G's result with L/L's (facet_planarizer_solve;
     * FACET_STAGE_COMPARE) */
    int32_t compare_iterations;      /* iterations of the L/L solve it ran (counted in
                                        `iterations`; 0: no comparison ran) */
    double compare_distance_rms[2];  /* RMS distance of L/L's [0] and L/G's [1] result
                                        (indexed by facet_method) from the input surface,
                                        model units; 0 0 when none was compared */
    double compare_min_angle[2];     /* their smallest corner angles, degrees (facet_face_shape) */
    double compare_displacement_rms[2]; /* their RMS vertex displacement from the input */
    double compare_edge_ratio[2];    /* their shortest edge relative to its input length */
    int32_t finer_iterations;        /* iterations of the L/G solve with a finer hold that
                                        follows when L/L's result was closer but moved the
                                        vertices too far (FACET_STAGE_FINER; counted in
                                        `iterations`; 0: none ran) */
    int32_t finer_kept;              /* 1 when that solve's result was returned: then
                                        compare_*[FACET_METHOD_LOCAL_GLOBAL] are its figures */
    int32_t threads;                 /* threads the (last) solve ran on (options.threads) */
    double data_tangent;             /* the data_tangent xyz_out was solved with:
                                        options.data_tangent, unless a quality re-solve
                                        held sliding vertices more firmly along the design
                                        (3 or 10 times; facet_quality_outcome); a live
                                        update: options.data_tangent, its region's */
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

/* The method FACET_METHOD_AUTO chooses for this planarizer's mesh and these
 * options (NULL: the defaults): FACET_METHOD_LOCAL_GLOBAL up to
 * FACET_AUTO_LG_MAX_CORNERS face corners, FACET_METHOD_LOCAL_LOCAL above;
 * without the staircase (hold_tol 0), with which L/L cannot finish, L/G up
 * to FACET_AUTO_LG_MAX_CORNERS_STAIRCASE. NULL planarizer: L/G. */
facet_method facet_planarizer_choose_method(const facet_planarizer *planarizer,
                                            const facet_planarize_options *options);

/* Planarizes the control positions xyz_in[3*n_vertices] (same topology as at
 * create) into xyz_out[3*n_vertices] (may equal xyz_in). Coordinates are
 * centred and scaled inside. On error the message is also kept in the handle
 * (facet_planarizer_message). xyz_out never receives a NaN: a non-finite
 * iterate stops the solve with FACET_ERROR_NUMERICAL and xyz_out is left
 * untouched. Returns FACET_WARNING_NOT_CONVERGED when max_iter ran out, and
 * also (stop reason FACET_STOP_STAGNATION, said in the message) when after
 * at least one iteration the next step was not finite -- an ill-conditioned
 * problem, such as weights many orders of magnitude apart: xyz_out is then
 * the last finite iterate. */
facet_status facet_planarizer_solve(facet_planarizer *planarizer, const double *xyz_in,
                                    const facet_planarize_options *options,
                                    double *xyz_out, facet_planarize_result *result,
                                    facet_error *error);

/* A live update after the designer moved some control vertices (xyz_in: all
 * control positions, same topology): cheaper than a warm re-solve, for
 * following a drag. The vertices whose control position differs from the
 * last solve's or update's, and those within `rings` edges of them (0: 4),
 * are re-solved with `options` (warm ignored); the other vertices of the
 * faces they touch are held, and every other vertex keeps its previous
 * result bit for bit. The region's control positions are the previous
 * result moved by the edit, so it follows the edit instead of being pulled
 * back to the original control mesh. If the held rim keeps the region from
 * the tolerance, the region grows (rings doubled) up to the whole mesh, or
 * all of it the edit reaches (a mesh in pieces). A moved vertex of no face
 * moves by its edit. The region's topology (and symbolic factorization) is
 * kept while the same vertices are edited. result->planarity_* are over all
 * faces. A full solve (facet_planarizer_solve) afterwards gives the globally
 * optimal result. After the fixed vertices, face weights or reference
 * changed, the next update is a full warm solve. options are checked as a
 * solve checks them, also when no vertex moved. xyz_out may be xyz_in.
 * Needs a previous solve on this handle (else FACET_ERROR_INVALID_ARGUMENT). */
facet_status facet_planarizer_update(facet_planarizer *planarizer, const double *xyz_in,
                                     const facet_planarize_options *options, int32_t rings,
                                     double *xyz_out, facet_planarize_result *result,
                                     facet_error *error);

/* The last error's message of a handle ("" when none). Valid until the next
 * call on the handle. */
const char *facet_planarizer_message(const facet_planarizer *planarizer);

/* Hard-fixes vertices at their control positions (xyz_in of each solve), in
 * addition to FACET_BOUNDARY_FIXED. n == 0 clears the set. Errors:
 * FACET_ERROR_INDEX_OUT_OF_RANGE naming the first bad entry. */
facet_status facet_planarizer_set_fixed(facet_planarizer *planarizer, int32_t n,
                                        const int32_t *vertices, facet_error *error);

/* Per-face planarity weights, n_faces values in [0, FACET_FACE_WEIGHT_MAX] (0: the face is exempt, an
 * opening or a door); NULL restores 1 for every face. */
facet_status facet_planarizer_set_face_weights(facet_planarizer *planarizer,
                                               const double *weights, facet_error *error);

typedef struct facet_surface facet_surface; /* below: closest points on a triangle surface */

/* The reference surface of the surface_weight term (vertices may slide along
 * it but not leave it): borrowed, it must outlive the solves that use it, in
 * the model coordinates of the solves' xyz_in. NULL clears it. */
facet_status facet_planarizer_set_reference(facet_planarizer *planarizer,
                                            const facet_surface *surface, facet_error *error);
/* ------------------------------------------------------------------------ */
/* Closest points on a triangle surface                                      */
/* ------------------------------------------------------------------------ */

/* A triangle surface prepared for closest-point queries: a bounding volume
 * hierarchy (binary AABB tree, median split of triangle centroids along the
 * widest axis, up to 4 triangles per leaf). Coordinates are centred on the
 * bounding box and scaled by its largest side inside, so georeferenced input
 * keeps its precision; results are given in the caller's coordinates. */
typedef struct facet_surface facet_surface;

/* Triangles of n_vertices points xyz[3*n_vertices]; tri[3*n_triangles]. Copies
 * what it needs. Errors: FACET_ERROR_EMPTY_MESH, FACET_ERROR_NONFINITE (a
 * vertex used by a triangle), FACET_ERROR_INDEX_OUT_OF_RANGE,
 * FACET_ERROR_TOO_LARGE (a bounding box wider than a double holds). Zero-area
 * triangles are allowed (their closest point is found on their edges; their
 * normal is 0 0 0). */
facet_status facet_surface_create(int32_t n_vertices, const double *xyz, int32_t n_triangles,
                                  const int32_t *tri, facet_surface **out, facet_error *error);

/* The surface of a polygon mesh: triangles kept, quads split along the
 * shorter diagonal, larger faces as a fan from their vertex centroid (the
 * same for any starting vertex; exact for faces star-shaped from the
 * centroid, which covers convex and near-convex panels). Triangle t of the
 * surface belongs to face facet_surface_face(surface, t). */
facet_status facet_surface_create_from_mesh(const facet_mesh *mesh, facet_surface **out,
                                            facet_error *error);

void facet_surface_free(facet_surface **surface);

/* Number of triangles; the face of the mesh triangle t came from (-1 when
 * the surface was made from triangles). */
int32_t facet_surface_triangle_count(const facet_surface *surface);
int32_t facet_surface_face(const facet_surface *surface, int32_t triangle);

/* For n query points query[3n]: closest point on the surface (closest[3n]),
 * its distance (distance[n]), the triangle (triangle[n]) and that
 * triangle's unit normal (normal[3n], 0 0 0 for a zero-area triangle); any
 * output may be NULL. Triangles within 1e-12 of the nearest distance (a
 * query on a corner or an edge they share) are a tie: one with area wins,
 * then the lowest triangle index, the same in any units or place.
 * A non-finite query point is FACET_ERROR_NONFINITE (vertex = its index),
 * outputs untouched. OpenMP over queries; results do not depend on
 * threads. */
facet_status facet_surface_closest(const facet_surface *surface, int64_t n, const double *query,
                                   int32_t threads, double *closest, double *distance,
                                   int32_t *triangle, double *normal, facet_error *error);

/* ------------------------------------------------------------------------ */
/* Face shape (quality report)                                               */
/* ------------------------------------------------------------------------ */

/* Per-face shape of a mesh, each output n_faces doubles (any may be NULL):
 *  min_angle   smallest interior angle in radians, in [0, 2 pi): measured at
 *              each corner between the two edges, turning about the face's
 *              Newell normal, so a reflex corner of a concave panel counts
 *              as more than pi; 0 at a corner with a zero-length edge,
 *              and 0 for a face that folds over itself (two of its edges
 *              cross, seen along its normal: a bowtie has no interior);
 *  area        length of the face's vector area (Newell), model units^2;
 *  ratio_change  with xyz_input (the same topology before an operation; may
 *              be NULL, then 0): with r_e = l_e / mean_l the length of edge
 *              e over the face's mean edge length,
 *              max over the face's edges of |r_e(xyz) / r_e(xyz_input) - 1|,
 *              edges of zero input length left out.
 * The mesh must be valid; this call checks sizes, indices and that the
 * coordinates (and xyz_input's) are finite (FACET_ERROR_NONFINITE). */
facet_status facet_face_shape(const facet_mesh *mesh, const double *xyz_input, int32_t threads,
                              double *min_angle, double *area, double *ratio_change,
                              facet_error *error);

/* ------------------------------------------------------------------------ */
/* Cleanup: collapse short edges                                             */
/* ------------------------------------------------------------------------ */

typedef struct facet_cleanup_options {
    double min_edge;   /* collapse edges shorter than this (> 0) */
    int32_t relative;  /* nonzero: min_edge is a fraction of the mean edge length */
} facet_cleanup_options;

typedef struct facet_cleanup_result {
    int32_t n_vertices;      /* of the new mesh */
    int32_t n_faces;
    int32_t n_corners;       /* face_start_out[n_faces] */
    int32_t n_collapsed;     /* edges collapsed (pairs in collapsed_edges) */
    int32_t n_removed_faces; /* input faces that fell below 3 vertices */
    int32_t n_skipped;       /* short edges kept because collapsing them would make
                              * a non-manifold edge or vertex, or turn a face over */
    double threshold;        /* the absolute length used */
} facet_cleanup_result;

/* Collapses edges shorter than the threshold, shortest first, each to its
 * midpoint (to the boundary vertex when one end is on the boundary and the
 * other not). Faces lose the merged corners and drop to lower degree; faces
 * left with fewer than 3 vertices are removed. A collapse is skipped when it
 * would put an edge in more than two faces, pinch a vertex (more than one
 * fan of faces around it) or repeat a vertex in a face, where the input was
 * manifold. Passes repeat until no edge is short or none can go.
 * Outputs, caller-allocated at input size: xyz_out[3*n_vertices],
 * face_start_out[n_faces+1], face_vertices_out[corners], vertex_map[n_vertices]
 * (input vertex -> output vertex, -1 when its faces were all removed;
 * isolated vertices are kept),
 * collapsed_edges[2*n_vertices] (input vertex
 * pairs, in collapse order), removed_faces[n_faces] (input face indices).
 * Any of vertex_map, collapsed_edges, removed_faces may be NULL.
 * Returns FACET_WARNING_COLLAPSE_SKIPPED when short edges remain,
 * FACET_ERROR_NOTHING_LEFT when every face would go (outputs untouched). */
facet_status facet_cleanup(const facet_mesh *mesh, const facet_cleanup_options *options,
                           double *xyz_out, int32_t *face_start_out, int32_t *face_vertices_out,
                           int32_t *vertex_map, int32_t *collapsed_edges,
                           int32_t *removed_faces, facet_cleanup_result *result,
                           facet_error *error); \
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
    /* may be NULL: called by facet_lifter_create with (done, 3) as its stages end (the
     * sparse QR; the search for the directions its rank lost, and between that search's
     * blocks with done 1; the check), the factorization's QR itself not interruptible;
     * nonzero cancels (FACET_ERROR_CANCELLED, no lifter) */
    facet_count_progress_fn progress;
    void *progress_user;
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

/* Dimension of the lifting space (>= 3, but see FACET_WARNING_LIFTING_RANK), and the
 * factorization's time. */
int32_t facet_lifter_dimension(const facet_lifter *lifter);
double facet_lifter_factor_seconds(const facet_lifter *lifter);

/* The optimal lifting of targets[n_vertices] into heights[n_vertices] (may
 * be the same array). result may be NULL. Returns FACET_WARNING_TRIVIAL_LIFTING
 * when the plan admits only the affine liftings (heights are then the
 * weighted best-fitting plane), FACET_WARNING_PLANARITY when a face is planar
 * only to more than 1e-9 relative (then said in the message),
 * FACET_WARNING_LIFTING_RANK when the affine liftings do not survive the
 * projection: the sparse QR kept dependent constraints that the create step
 * did not recover, so the dimension is too small and the heights may be
 * farther from the targets than the closest lifting (a guard: at rank tolerances
 * up to 1e-6, where the search for the dependencies SPQR's rank lost runs, no plan
 * measured since it goes on past its largest block sets it off; a looser one, whose
 * rank stands, can). Where both warnings hold, FACET_WARNING_LIFTING_RANK is
 * returned, its message ending with the planarity finding. A non-finite
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
 * Consumed edges: the penalty method shrinks some edges to a few percent of
 * their length, and leaves some corners nearly straight (a vertex slid onto
 * the line of its neighbours). A gap, or a bevel, then turns such an edge of
 * an offset outline around: a short edge's outline vanishes, and two mitres
 * of different angles meet far beyond a nearly straight corner. Such an
 * edge is repaired (repair_consumed, the default):
 *  - where it and the kept edges on either side of it are square, the
 *    outlines there are the face's outline offset in its plane, and it is
 *    dropped as a CAD offset drops it: its two corners become the point
 *    where its neighbours' edge lines meet, the same point in both outlines
 *    (dropped[k] = 1; a quad becomes a triangle panel). The worst first,
 *    until every kept edge keeps its direction;
 *  - where one of the three is mitred, those joints become butt joints:
 *    cut square on this panel (squared[k] = 1, bevel 0) and on the
 *    neighbour's side with the whole fold, on this panel's square plane
 *    (squared = 2), so the joint stays a slot of constant width; the mitres
 *    beside the edge first, then its own. The faces they touch are outlined
 *    again. If the neighbour needs that joint square too, it is square on
 *    both sides, which closes the joint on the fold's inner side: if the two
 *    panels would then overlap, that is an error naming both faces and the
 *    overlap (a larger gap or thinner panels).
 * A face left with fewer than three edges is an error. With repair_consumed
 * 0 a consumed edge is an error naming the face, the vertex and the edge's
 * length.
 *
 * Straight corners (a vertex on a straight edge, as where two panels meet
 * along one side of a third): the corner is the point of the edge's offset
 * line nearest the vertex, in both outlines, where the two edges are cut
 * alike (square, or mitred at one angle, as a planar mesh makes them). A
 * mitre beside a cut of another angle there (a free edge, a butt joint)
 * becomes a butt joint as above (beside a butt joint whose plane its
 * neighbour's square plane continues, the neighbour is cut square and this
 * panel takes the whole fold); with repair_consumed 0 that is an error. So
 * does a mitre beside a free edge at a nearly straight corner (a turn under
 * 10 degrees, bevels a degree apart or more) whose outline corner would lie
 * more than 4 thicknesses from the vertex (the two cuts' lines meet far along
 * the edge: 28 thicknesses at a turn of 0.57 degrees).
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


typedef struct facet_panel_options {
    double thickness;          /* > 0, model units */
    facet_panel_offset offset;
    double gap;                /* >= 0, joint width, model units */
    facet_panel_edge edge;
    int32_t flip;              /* nonzero: reverse every face's orientation */
    double planarity_tol_abs;  /* a face is planar when its vertices are within */
    double planarity_tol_rel;  /* max(tol_abs, tol_rel * mean edge) of its plane */
    int32_t repair_consumed;   /* an edge the gap or bevel turns around is dropped,
                                  its mitres cut square first (default 1); 0: an error */
    facet_count_progress_fn progress; /* may be NULL */
    void *progress_user;
    const char *length_unit;   /* the model's unit ("mm"), written after every
                                  length in error messages; NULL or "" writes
                                  them bare (model units) */
} facet_panel_options;

/* thickness 1, outer, gap 0, square, no flip, tol_abs 0, tol_rel 1e-6,
 * repair_consumed 1, length_unit NULL. */
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
    int32_t *dropped;       /* nc: 1 when the outlines drop edge k (corners k and
                               k+1 then coincide in both), else 0 */
    int32_t *squared;       /* nc: 1 when edge k is cut square because a mitre
                               could not be cut, 2 when it is the other half of
                               such a butt joint (cut with the whole fold), else
                               0 (see Consumed edges) */
    double *joint;          /* nc: the narrowest width of the joint at edge k
                               across its section, model units (the same along
                               the edge): the gap where it is mitred or a butt
                               joint; cut square across a fold, less on the
                               fold's inner side, and negative where the gap is
                               too small and the panels overlap (minus how deep:
                               the least overlap of the two panels' sections
                               along the normals of their planes and side
                               planes, as panels at a node are measured); 0 on
                               the boundary (neighbor -1) and where either panel
                               dropped the edge (no joint there) */
    double *node_clash;     /* n_vertices: how deep two panels that meet at the
                               vertex but not across a joint there (or across one
                               at a reflex corner of either) overlap, the
                               deepest pair's, model units (the least distance
                               along a direction that would part them: separating
                               axes of the two solids, a concave one taken as
                               triangle pieces); 0 when none do */
    double *clash;          /* n_faces: how deep the panel overlaps another, across
                               a joint or at a node (model units, the deepest); 0
                               when it overlaps none */
} facet_panel_output;

typedef struct facet_panel_result {
    int64_t n_nonplanar;          /* faces above the planarity tolerance */
    int64_t n_non_manifold_edges; /* edges with more than two faces */
    int64_t n_reversed;           /* faces whose winding was reversed */
    int32_t n_components;         /* edge-connected parts */
    int64_t worst_node;           /* vertex of max_node_deviation, or -1 */
    double max_node_deviation;    /* radians */
    double max_planarity;         /* model units */
    int64_t n_dropped_edges;      /* face edges the gap consumed, dropped */
    int64_t n_squared_edges;      /* face edges cut square where a mitre could not be */
    int64_t n_butt_edges;         /* their neighbours' edges, cut with the whole fold */
    double narrowest_repaired_joint; /* the narrowest of those joints across its section
                                        at its edge's midpoint, model units: the gap at a
                                        butt joint, less at one square on both panels
                                        across a fold; -1 when none */
    double narrowest_joint;       /* the least of out->joint over the interior
                                     edges (negative: the deepest overlap); 0
                                     when there is none */
    int64_t narrowest_joint_vertex; /* its edge's first vertex, or -1 */
    int32_t narrowest_joint_faces[2]; /* the two faces it parts, or -1 -1 */
    int64_t n_overlapping_joints; /* joints whose panels overlap: cut square on
                                     the inner side of a fold with too small a
                                     gap (a mitre never overlaps) */
    double clearing_gap;          /* the least gap at which none of them would
                                     overlap across its section, model units (0
                                     when none does) */
    int64_t n_node_clashes;       /* pairs of panels that meet at a vertex, not
                                     across a joint there (or across one at a
                                     reflex corner of either), and overlap (see
                                     out->node_clash; a pair meeting at two
                                     vertices counts at each) */
    double deepest_node_clash;    /* model units, 0 when none */
    int64_t node_clash_vertex;    /* its vertex, or -1 */
    int32_t node_clash_faces[2];  /* its two faces, or -1 -1 */
    double seconds;
    int32_t failed_joint_faces[2]; /* on the FACET_ERROR_PANEL_GEOMETRY of a joint
                                      that had to be cut square on both panels
                                      and whose panels overlap: its two faces (the
                                      first is error->face, whose edge from
                                      error->vertex it is); else -1 -1 */
    double failed_joint_overlap;  /* how deep they overlap there, model units */
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
 * treated as boundary. result may be NULL; on the error of a joint square on
 * both panels that overlaps (failed_joint_faces) *result is written too. Unlike the general contract, a
 * failing call may have written part of the outputs (except on
 * FACET_ERROR_INVALID_ARGUMENT): discard them. Serial and O(corners log
 * corners); deterministic. */
facet_status facet_panels(const facet_mesh *mesh, const facet_panel_options *options,
                          facet_panel_output *out, facet_panel_result *result,
                          facet_error *error);

/* ------------------------------------------------------------------------ */
/* Input range (hardening)                                                   */
/* ------------------------------------------------------------------------ */

/* The largest coordinate magnitude the library accepts (mesh vertices, plan
 * x and y, lift targets, surface points and queries, planarizer control
 * positions). Beyond about 1e100 products of coordinates that are not
 * centred first (scatter matrices, squared distances) overflow to infinity
 * (fuzzing found them at 1e300); 1e30 leaves room for their cubes and is
 * far beyond any model in mm, m or georeferenced coordinates. A finite
 * coordinate beyond it is FACET_ERROR_COORDINATE_RANGE (lift targets:
 * FACET_ERROR_BAD_TARGET), naming the vertex. */
#define FACET_COORDINATE_MAX 1e30

/* ------------------------------------------------------------------------ */
/* Planarization quality by default (branch quality5)                       */
/* ------------------------------------------------------------------------ */

/* facet_planarize_result.quality. A solve (not a fixed iteration count, no
 * angle floor, quality_angle > 0) that stops at the tolerance is checked, in
 * one pass over the faces, for new narrow corners:
 * a corner below quality_angle whose input corner was not, or below half of
 * its input corner. If there is one, a cold solve is run again from the input
 * (a warm one only reports them: FACET_QUALITY_NARROW, no re-solve),
 * without Anderson acceleration: with the default hold (hold_tol 0.01,
 * hold_max 40), then hold_tol 0.003 (these two only when data_tangent >=
 * data_normal and surface_weight is 0: vertices held at their control
 * points), then along the exact penalty path (hold_tol 1e-9, hold_max 200,
 * max_iter at least 4000), then with Anderson, hold_tol 0.003 and the angle
 * floor at 1.2 quality_angle; and when vertices slide along the design
 * (data_tangent < data_normal, or surface_weight > 0), held more firmly
 * along it: with Anderson and the default hold at three times data_tangent,
 * then the angle floor's recipe at three and at ten times (each at most
 * data_normal or surface_weight, whichever is larger, and skipped when it
 * would repeat an earlier stage; result.data_tangent says which returned),
 * stopping at the first result that reaches the tolerance with no new
 * narrow corner, which is returned. If none does, the first solve's result
 * is returned (FACET_QUALITY_NARROW, narrow_corners > 0; the message says
 * so). Deterministic for any thread count (each solve is). The progress
 * callback counts on through the re-solves (facet_progress_fn,
 * facet_planarizer_stage), and cancelling one
 * returns FACET_ERROR_CANCELLED with xyz_out holding the first solve's
 * result. The live update (facet_planarizer_update) does not check. */
typedef enum facet_quality_outcome {
    FACET_QUALITY_NOT_CHECKED = 0, /* off, fixed count, angle floor, live, or not converged */
    FACET_QUALITY_OK = 1,          /* checked: no new narrow corner */
    FACET_QUALITY_RECOVERED = 2,   /* the first result had one; a re-solve has none */
    FACET_QUALITY_NARROW = 3       /* every re-solve left one (or warm): the first result */
} facet_quality_outcome;

/* ------------------------------------------------------------------------ */
/* Progress across the quality re-solves (branch progress6)                 */
/* ------------------------------------------------------------------------ */

/* Which solve of facet_planarizer_solve is running, for the progress text
 * ("re-solving for panel quality, stage 2 of 4"). Call it from the solve's
 * progress callback (the calling thread, while the solve runs). Returns 0
 * during the first solve and k (1 <= k <= *stages) during the k-th quality
 * re-solve (facet_quality_outcome), FACET_STAGE_COMPARE during method AUTO's
 * comparison solve and FACET_STAGE_FINER during its L/G solve with a finer
 * hold (below); *stages (may be NULL) receives how many
 * re-solves this solve may run: 0 when it cannot re-solve (quality_angle 0,
 * a fixed iteration count, an angle floor, a warm start), else 4 (vertices
 * held at their control points) or 2 to 5 (vertices sliding along the
 * design: data_tangent < data_normal or surface_weight > 0; 5 unless a
 * firmer hold would not raise data_tangent or would repeat a stage: the
 * presets have 5). Re-solves end at the
 * first that recovers, so k = *stages is not always reached. Outside a
 * solve, in a live update (facet_planarizer_update) and for NULL: 0 and 0. */
int32_t facet_planarizer_stage(const facet_planarizer *planarizer, int32_t *stages);

/* ------------------------------------------------------------------------ */
/* Method auto: the result closer to the design (branch ref7)               */
/* ------------------------------------------------------------------------ */

/* Where FACET_METHOD_AUTO picks L/G (facet_planarizer_choose_method), a cold
 * solve that reaches the tolerance, after its quality re-solves, is solved
 * again from the input by L/L (the same options, mu_min at least
 * FACET_LL_MU_MIN; a tenth of an L/G solve's time or less), and L/L's
 * result is returned instead of L/G's when it reaches the tolerance, lies
 * closer to the input surface (RMS distance of the vertices; the reference
 * surface instead when surface_weight > 0), has a smallest corner angle of
 * at least the smaller of L/G's and 10 degrees, a shortest edge (relative
 * to its input length) of at least the smaller of L/G's and a quarter (a
 * skew quad may shrink an edge to nothing, becoming a triangle, with no
 * narrow corner), has no more new narrow
 * corners (facet_quality_outcome) than L/G's and, unless the data term lets
 * vertices slide (data_tangent < data_normal or surface_weight > 0), moves
 * the vertices no more than 5% further (RMS) than L/G's: L/L is often
 * closer because its vertices slide further along the surface, which
 * changes the panels' sizes. Neither method is closer on every mesh: L/G
 * ends up to 24% further from the design than the exact penalty path on
 * some meshes, L/L up to 12% on others (docs/solver-notes.md, "Method auto:
 * the closer result").
 * result.method says whose result was returned, compare_* what was
 * compared. No comparison is made for a fixed iteration count, a warm start,
 * the paper's schedule (hold_tol 0: L/L does not reach the tolerance with
 * it), or a solve whose energy asks for more than closeness (a shape term,
 * laplacian, normal_laplacian or boundary_fairness > 0). If the comparison
 * solve fails or stops short of the tolerance, L/G's result stands;
 * cancelling it returns FACET_ERROR_CANCELLED with L/G's result in xyz_out.
 * During the comparison facet_planarizer_stage returns FACET_STAGE_COMPARE.
 *
 * When L/L's result is refused only for moving the vertices further (its
 * corners and edges as good) and lies markedly closer to the input surface (at most
 * FACET_FINER_WHEN times L/G's distance), L/G's result has strayed from the
 * penalty path, which L/L's shows to lie nearer the design: L/G solves once
 * more from the input with a finer hold (hold_tol times FACET_FINER_HOLD,
 * Anderson kept, no quality re-solve; facet_planarizer_stage returns
 * FACET_STAGE_FINER), and its result is returned instead of the first when
 * it reaches the tolerance, lies closer to the input surface, has a
 * smallest corner of at least the smaller of the first's and 10 degrees, a
 * shortest edge of at least the smaller of the first's and a quarter, no
 * more new narrow corners, and moves the vertices no more than 5% further
 * (RMS). result.finer_iterations and finer_kept say what it did. The bound
 * the progress callback sees from the first call includes this solve's
 * limit (max_iter) where it may run (vertices held at their control
 * points). Cancelling it returns FACET_ERROR_CANCELLED with the first L/G
 * result in xyz_out. */
#define FACET_STAGE_COMPARE (-1)
#define FACET_STAGE_FINER (-2)
#define FACET_FINER_HOLD 0.3
#define FACET_FINER_WHEN 0.8

/* ------------------------------------------------------------------------ */
/* Method auto: L/G when L/L leaves a panel closed                          */
/* ------------------------------------------------------------------------ */

/* Where FACET_METHOD_AUTO picks L/L on a mesh of at most
 * FACET_AUTO_FALLBACK_MAX_CORNERS face corners, a cold solve whose
 * energy asks for closeness alone (as for the comparison above) and whose
 * result, after its quality re-solves, still has a new narrow corner
 * (FACET_QUALITY_NARROW) or that stopped on stagnation above the tolerance
 * is solved once more from the input by L/G (the same options, no quality
 * re-solve; facet_planarizer_stage returns FACET_STAGE_FALLBACK), and L/G's
 * result is returned instead when it reaches the tolerance with fewer new
 * narrow corners (or, L/L's having stalled, no more). L/L's local steps
 * let vertices of nearly coplanar faces drift along them, where mu is
 * small: a flat facade with a local saddle closes panels by L/L (0 degrees,
 * or a stall at 1e-5) and none by L/G (docs/solver-notes.md, "Method auto:
 * L/G when L/L closes a panel"). result.method says whose result was
 * returned; the progress bound from the first call includes this solve's
 * max_iter where it may run. Cancelling it returns FACET_ERROR_CANCELLED
 * with L/L's result in xyz_out. */
#define FACET_STAGE_FALLBACK (-3)
/* 160,000 quads: the largest mesh measured, where L/G's one solve took 86 s
 * on two threads and about 1.5 KB per face, against L/L's 4 s to a result
 * that stalled at 3.5e-6 with a corner of 2.3 degrees. */
#define FACET_AUTO_FALLBACK_MAX_CORNERS 640000

#ifdef __cplusplus
}
#endif
#endif /* FACET_H */
