/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* The planarizer's state, shared by its three parts:
 *   planarize.c         the handle, the options, the solve loop, Anderson acceleration;
 *   planarize_local.c   the local steps (planes, shapes, circles, boundary, energies)
 *                       and the local/local vertex step;
 *   planarize_global.c  the local/global system: pattern, assembly, CHOLMOD.
 * All coordinates here are normalised: centred on the control mesh's bounding
 * box and divided by its mean edge length. */
#ifndef FACET_PLANARIZE_INTERNAL_H
#define FACET_PLANARIZE_INTERNAL_H

#include "internal.h"

#include <cholmod.h>
#include <stdint.h>

/* Anderson's sketched least squares (planarize.c, anderson_step;
 * docs/solver-notes.md, "Anderson's least squares on a sample"): on a mesh of
 * at least FACET_ANDERSON_SKETCH_VERTICES vertices the history's
 * least-squares problem is formed over one piece of 512 vertices in every
 * FACET_ANDERSON_SKETCH_STRIDE of each block, and the residuals' differences
 * (dF) are stored for those entries only. The extrapolation still combines
 * the full plain iterates' differences (dG). */
enum { FACET_ANDERSON_SKETCH_VERTICES = 32768, FACET_ANDERSON_SKETCH_STRIDE = 8 };

/* Which coupled (vertex-vertex) terms are in the global matrix. */
enum {
    COUPLE_LAPLACIAN = 1,
    COUPLE_FAIRNESS = 2,
    COUPLE_SHAPE = 4,
    COUPLE_PARALLELOGRAM = 8
};

/* Sums over faces and over vertices go in at most this many blocks of
 * consecutive elements (at least 512 each), summed in order within a block
 * and across blocks: the same bits for any thread count, without a serial
 * pass over every element. */
enum { FACET_ENERGY_BLOCKS = 256, FACET_ENERGY_BLOCK_MIN = 512 };

struct facet_planarizer {
    int32_t nv, nf, nc;
    int32_t *face_start, *face_vertices;
    int32_t *vertex_start, *vertex_faces; /* faces around each vertex, ascending */
    int32_t *vertex_adj_start, *vertex_adj; /* edge neighbours of each vertex, ascending */
    int32_t *face_adj_start, *face_adj;   /* faces sharing an edge with each face, ascending */
    int32_t *boundary_prev, *boundary_next; /* along the boundary loop; -1 if none */
    uint8_t *on_boundary;                 /* has a boundary edge */
    int32_t n_boundary;

    /* settings kept between solves */
    int32_t *user_fixed;
    int32_t n_user_fixed;
    double *face_weight;                  /* NULL: all 1 */
    const facet_surface *reference;       /* borrowed; NULL: none */

    /* the solve in progress */
    facet_planarize_options o;
    uint8_t *fixed;                       /* per vertex, hard */
    double *p, *q;                        /* control and current */
    double *vertex_normal;                /* control normals, unit */
    double *normal, *offset;              /* per face plane of the step */
    double *face_dev, *face_edge;         /* per face: max distance, mean edge length */
    double *face_sq;                      /* per face: sum of squared distances */
    /* the largest face_dev and face_dev / face_edge over the faces with a
     * weight (exempt faces do not count), found by the plane fit */
    double fit_max_abs, fit_max_rel;
    /* the energy's parts (mu's and the constraints'), summed per block of
     * faces and of vertices (facet_pl_energy adds the blocks in order) */
    double energy_block[2][2][FACET_ENERGY_BLOCKS];
    int32_t energy_blocks[2];
    /* the vertices' blocks hold the energy of the iterate already: Anderson's
     * extrapolation summed it as it wrote the iterate (the next local step
     * then skips its pass; facet_pl_vertex_energy_plain) */
    int vertex_energy_done;
    double *face_residual;                /* per face: constraint residual (circle, parallelogram) */
    double *vertex_residual;              /* per vertex: sliding residual */
    double *normal_fit;                   /* per face: best-fit normal (normal-Laplacian input) */
    double *control_centroid;             /* per face, of p (the shape term only: NULL until asked) */
    double *shape;                        /* per face: s R, 9 values (shape term) */
    double *circle_target;                /* per corner, 3 values (circular term) */
    /* angle floor: per corner the cosine of its floor and of its angle now; per
     * face whether a corner is below its floor; per vertex the count and sum
     * of its targets */
    double *corner_floor, *corner_cos;
    uint8_t *face_guard;
    double *guard_count, *guard_sum;
    int guard_on;                         /* some corner is below its floor now */
    int finishing; /* L/L's finish (planarize.c): the vertex step's p is the iterate itself,
                      and so are the shape, Laplacian, boundary fairness and
                      reference surface targets */
    int scalar_kernels; /* tests: the plain per-face and per-vertex code, not the SIMD lanes */
    double *slide_target, *slide_tangent; /* per vertex (sliding boundary) */
    double *laplace_weight;               /* per vertex_adj entry: normalised weight */
    double *surface_point, *surface_normal; /* per vertex: closest reference point, its normal */
    double *surface_query;                /* per vertex: q in model units (the query) */
    double scale, centre[3];              /* model = normalised * scale + centre */
    double *q_next;                       /* local/local: the new iterate (Jacobi) */
    double *face_plane_terms;             /* local/local, per face: w_f n n^T (6) and w_f d n (3) */
    double *previous;                     /* last result, model units (warm start) */
    double *previous_control;             /* the control positions it was solved from */
    int has_previous;
    int previous_in_history;              /* both in aa_df's first two columns
                                             (planarize.c, previous_storage) */

    /* quality re-solves (planarize_quality.c): facet_planarizer_stage's
     * answer, 0 and 0 outside a solve */
    int32_t quality_stage, quality_stages;

    /* live updates (planarize_live.c): the region around the edited vertices */
    struct facet_planarizer *live;        /* handle of the region's submesh; NULL: none */
    int32_t *live_vertex;                 /* submesh vertex -> vertex */
    int32_t live_nv, live_rings;          /* submesh vertices; rings of the region */
    int live_complete;                    /* the region holds every vertex the edit reaches */
    int32_t *live_changed;                /* the edited vertices the region was built for */
    int32_t live_n_changed;
    uint8_t *live_mark;                   /* per vertex: 1 in the region, 2 its fixed rim */
    double *live_xyz;                     /* submesh control and result, 6 * live_nv */
    double *live_face_dev;                /* per face: planarity, absolute then relative */
    int live_face_valid;                  /* live_face_dev is that of `previous` */
    int live_stale;                       /* fixed vertices, weights or reference changed
                                             since the last solve: update solves in full */

    /* local/global */
    int cholmod_started;
    cholmod_common cm;
    cholmod_sparse *matrix;
    cholmod_factor *factor;
    cholmod_dense *rhs;
    /* The matrix as CHOLMOD factorizes it, permuted once at the analysis:
     * triu(P A P^T), whose entry j is matrix->x[pmap[j]]; factor is its
     * factorization in the natural order, so no factorization transposes
     * the matrix (planarize_global.c). perm: the fill-reducing order.
     * Without vertex couplings the unknowns are numbered in a fill-reducing
     * order from the start (face_col) and pmatrix, pmap and perm are NULL. */
    int32_t *face_col; /* per face: the column of its offset (3 nv + its rank) */
    /* Without vertex couplings the (3 nv + nf) matrix is never stored: the
     * vertices are eliminated by hand and each step solves the offsets'
     * system (Schur complement, nf x nf) for the offsets' increment, by
     * conjugate gradients preconditioned with CHOLMOD's factorization of an
     * earlier step's offsets' system, or directly after refactorizing it
     * (planarize_global.c, schur_step). schur: that system's upper triangle
     * (faces in face_col's order), factor its factorization; block: per vertex,
     * the LDL' of this step's 3x3 block (l10 l20 l21 1/d0 1/d1 1/d2);
     * schur_u: per vertex, B^-1 of its residual, then its increment;
     * schur_vec: two vectors of nf (search direction, solution), schur_b
     * and schur_x two more (right-hand side, then residual; preconditioned
     * residual and product) for cholmod_solve2. NULL with couplings. */
    cholmod_sparse *schur;
    double *block, *schur_u, *schur_vec;
    cholmod_dense *schur_b, *schur_x;
    cholmod_sparse *pmatrix;
    int32_t *pmap, *perm;
    cholmod_dense *perm_b, *perm_x;
    /* the factorization as a preconditioner (planarize_global.c, pcg_solve
     * and schur_pcg) */
    int factor_ready, factor_age;
    /* the stored system's factorization costs more than FACTOR_COSTLY
     * conjugate gradient steps (flops from the analysis): its factor serves
     * for as long as the steps stay few, whatever its age */
    int factor_costly;
    int factorizations; /* numeric factorizations of the handle's life (tests) */
    double factor_mu;
    /* With couplings (matrix, rhs and pcg_p .. pcg_x of 3 nv + nf; NULL
     * without): pcg_p also holds [q; d] of the iterate (the step solves for
     * the increment), pcg_x the increment. pcg_y, pcg_e: cholmod_solve2's
     * workspace, either way */
    cholmod_dense *pcg_p, *pcg_ap, *pcg_r, *pcg_x, *pcg_y, *pcg_e;
    int32_t *corner_slot;   /* per corner: index in matrix->x of its first coupling entry */
    int32_t couple_key;     /* COUPLE_* flags the matrix pattern was built for; -1 none */
    /* the scalar coupling matrix K (vertex x vertex, symmetric): per vertex v,
     * entries u < v at couple_start[v] .. couple_start[v+1]-1 */
    int32_t *couple_start, *couple_vertex;
    double *couple_mu, *couple_con;       /* off-diagonal values */
    double *couple_diag_mu, *couple_diag_con; /* NULL without coupled terms */

    /* Anderson acceleration */
    double *aa_df, *aa_dg;                /* m columns (2 if m = 1) of 3 nv (aa_dg) and of
                                             facet_pl_anderson_len (aa_df, at least 2 x 3 nv
                                             in all: the last result); the ring's next slot
                                             holds the last f = g - x and g */
    int32_t aa_capacity;                  /* columns aa_df and aa_dg hold */

    char message[512];
};

/* planarize_local.c */
void facet_pl_prepare_solve(facet_planarizer *s);
facet_status facet_pl_local_step(facet_planarizer *s, double mu, int nthreads, facet_error *error);
void facet_pl_energy(const facet_planarizer *s, double *energy_mu, double *energy_con);
int32_t facet_pl_energy_block_size(int32_t n);
int facet_pl_vertex_energy_plain(const facet_planarizer *s);
double facet_pl_vertex_data_energy(const facet_planarizer *s, const double *q, int32_t v0, int32_t v1);
int facet_pl_vertex_step(facet_planarizer *s, double mu, int nthreads);
void facet_pl_procrustes(const double c[9], int similar, double sr[9]);
int facet_pl_circle_targets(int32_t n, const double *xyz, const int32_t *idx,
                            const double normal[3], double *targets);
int32_t facet_pl_couple_key(const facet_planarize_options *o);

/* planarize_global.c */
facet_status facet_pl_global_setup(facet_planarizer *s, facet_error *error);
facet_status facet_pl_global_step(facet_planarizer *s, double mu, int nthreads,
                                  facet_error *error);
void facet_pl_global_free(facet_planarizer *s);

/* planarize.c */
facet_status facet_pl_solve_once(facet_planarizer *s, const double *xyz_in,
                                 const facet_planarize_options *options, double *xyz_out,
                                 facet_planarize_result *result, facet_error *error);
facet_status facet_pl_fail(facet_planarizer *s, facet_error *error, facet_status status,
                           const char *text);
/* FACET_OK, or FACET_ERROR_INVALID_ARGUMENT naming the first bad option (as a solve). */
facet_status facet_pl_check_options(facet_planarizer *s, const facet_planarize_options *options,
                                   facet_error *error);
void facet_pl_history_trim(facet_planarizer *s);
/* Entries of one column of the Anderson history's residual differences:
 * 3 nv, or fewer on a mesh whose least squares is sketched. */
size_t facet_pl_anderson_len(int32_t nv);
/* The threads a solve of this planarizer uses for options.threads = requested. */
int facet_pl_threads(const facet_planarizer *s, int requested);

/* planarize_quality.c: corners of the iterate q below angle_deg whose control
 * corner (p) was not, or below half of the control corner, and faces of q
 * that fold over themselves where p's did not (each counted once, as a
 * corner of 0 degrees); the smallest such corner's angle in degrees in
 * *smallest (180 if none) */
int32_t facet_pl_new_narrow(const facet_planarizer *s, double angle_deg, int nthreads,
                            double *smallest);

#endif
