/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Method AUTO's comparison (facet.h, FACET_STAGE_COMPARE; planarize_quality.c,
 * compare_ll): where AUTO picks L/G it also solves by L/L and returns the
 * result closer to the input surface unless L/L's smallest corner is below
 * L/G's and 10 degrees. Each case solves L/G and L/L on handles of their
 * own, measures both results here through the public API, applies the rule
 * and checks that AUTO returned the bits of the one the rule picks; the
 * meshes are chosen so that both outcomes occur; a warm start after it
 * starts from the result returned. Then: the progress of the
 * comparison (one count, its limit in the bound, the stage named),
 * cancelling it (L/G's result, kept as the handle's last result), output in
 * place, thread counts, a second solve on the same handle, and the solves
 * that make no comparison. */
#include "check.h"
#include "facet.h"
#include "test_meshes.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

static size_t v3_of(const test_mesh *g)
{
    return 3 * (size_t)g->mesh.n_vertices;
}

/* The shortest edge of the mesh at xyz relative to its length in the input. */
static double edge_ratio(const test_mesh *g, const double *xyz)
{
    double shortest = 1.0;
    for (int32_t f = 0; f < g->mesh.n_faces; ++f) {
        const int32_t b = g->mesh.face_start[f], e = g->mesh.face_start[f + 1];
        for (int32_t k = b; k < e; ++k) {
            const int32_t i = g->mesh.face_vertices[k], j = g->mesh.face_vertices[k + 1 < e ? k + 1 : b];
            double in2 = 0.0, out2 = 0.0;
            for (int c = 0; c < 3; ++c) {
                const double din = g->xyz[3 * j + c] - g->xyz[3 * i + c], dout = xyz[3 * j + c] - xyz[3 * i + c];
                in2 += din * din, out2 += dout * dout;
            }
            if (in2 > 0.0 && sqrt(out2 / in2) < shortest)
                shortest = sqrt(out2 / in2);
        }
    }
    return shortest;
}

/* RMS distance of the mesh's vertices at xyz from its input surface, their
 * RMS displacement from the input and the smallest corner angle (degrees),
 * as the rule measures them. */
static void measure(const test_mesh *g, const double *xyz, double *rms, double *moved, double *angle)
{
    double sum_moved = 0.0;
    for (size_t k = 0; k < v3_of(g); ++k)
        sum_moved += (xyz[k] - g->xyz[k]) * (xyz[k] - g->xyz[k]);
    *moved = sqrt(sum_moved / (double)g->mesh.n_vertices);
    facet_error err;
    facet_surface *surface = NULL;
    CHECK_STATUS(facet_surface_create_from_mesh(&g->mesh, &surface, &err), FACET_OK);
    const int32_t nv = g->mesh.n_vertices, nf = g->mesh.n_faces;
    double *work = malloc(sizeof(double) * (size_t)(nv > nf ? nv : nf));
    CHECK_STATUS(facet_surface_closest(surface, nv, xyz, 1, NULL, work, NULL, NULL, &err), FACET_OK);
    double sum = 0.0;
    for (int32_t v = 0; v < nv; ++v)
        sum += work[v] * work[v];
    *rms = sqrt(sum / (double)nv);
    facet_mesh at = g->mesh;
    at.xyz = xyz;
    CHECK_STATUS(facet_face_shape(&at, NULL, 1, work, NULL, NULL, &err), FACET_OK);
    double least = 2.0 * PI;
    for (int32_t f = 0; f < nf; ++f)
        least = least < work[f] ? least : work[f];
    *angle = least / (PI / 180.0); /* as the library converts */
    free(work);
    facet_surface_free(&surface);
}

/* L/L as AUTO's comparison runs it: AUTO's options, L/L's floor, one solve. */
static facet_planarize_options ll_as_compared(void)
{
    facet_planarize_options o;
    facet_planarize_options_default(FACET_METHOD_AUTO, &o);
    o.method = FACET_METHOD_LOCAL_LOCAL;
    o.mu_min = o.mu_min > FACET_LL_MU_MIN ? o.mu_min : FACET_LL_MU_MIN;
    o.quality_angle = 0.0; /* no re-solve: the comparison runs L/L once */
    return o;
}

/* L/G as the solve with a finer hold runs it: AUTO's options, L/G, the hold
 * times FACET_FINER_HOLD, one solve. */
static facet_planarize_options finer_as_run(void)
{
    facet_planarize_options o;
    facet_planarize_options_default(FACET_METHOD_AUTO, &o);
    o.method = FACET_METHOD_LOCAL_GLOBAL;
    o.hold_tol *= FACET_FINER_HOLD;
    o.quality_angle = 0.0; /* no re-solve: it runs once */
    return o;
}

/* What the rule returned on a mesh: which result, and whether the finer L/G
 * solve ran. */
typedef struct {
    int ll, guarded, finer;
    int short_edge; /* closer, as wide corners, but a shorter edge than L/G's and a quarter */
} outcome;

/* Returns what AUTO returned: L/L's result, L/G's, or (guarded: L/L's was
 * closer and as wide but moved the vertices too far) the finer L/G's. */
static outcome check_rule(const char *name, test_mesh *g)
{
    const size_t v3 = v3_of(g);
    double *lg = malloc(sizeof(double) * v3), *ll = malloc(sizeof(double) * v3);
    double *fine = malloc(sizeof(double) * v3), *out = malloc(sizeof(double) * v3);
    facet_planarizer *h_lg = NULL, *h_ll = NULL, *h_fine = NULL, *h_auto = NULL;
    facet_error err;
    CHECK_STATUS(facet_planarizer_create(&g->mesh, &h_lg, &err), FACET_OK);
    CHECK_STATUS(facet_planarizer_create(&g->mesh, &h_ll, &err), FACET_OK);
    CHECK_STATUS(facet_planarizer_create(&g->mesh, &h_fine, &err), FACET_OK);
    CHECK_STATUS(facet_planarizer_create(&g->mesh, &h_auto, &err), FACET_OK);
    facet_planarize_options o;
    facet_planarize_result r_lg, r_ll, r_fine, r;
    facet_planarize_options_default(FACET_METHOD_LOCAL_GLOBAL, &o);
    CHECK_STATUS(facet_planarizer_solve(h_lg, g->xyz, &o, lg, &r_lg, &err), FACET_OK);
    CHECK(r_lg.compare_iterations == 0 && r_lg.finer_iterations == 0); /* L/G named: none */
    o = ll_as_compared();
    CHECK_STATUS(facet_planarizer_solve(h_ll, g->xyz, &o, ll, &r_ll, &err), FACET_OK);
    CHECK(r_lg.stop_reason == FACET_STOP_TOLERANCE && r_ll.stop_reason == FACET_STOP_TOLERANCE);
    facet_planarize_options_default(FACET_METHOD_AUTO, &o);
    CHECK_STATUS(facet_planarizer_solve(h_auto, g->xyz, &o, out, &r, &err), FACET_OK);

    double d_lg, m_lg, a_lg, d_ll, m_ll, a_ll, d_f = 0, m_f = 0, a_f = 0, e_f = 0;
    measure(g, lg, &d_lg, &m_lg, &a_lg);
    measure(g, ll, &d_ll, &m_ll, &a_ll);
    const double e_lg = edge_ratio(g, lg), e_ll = edge_ratio(g, ll);
    const int closer = d_ll < d_lg;
    const int edge_kept = e_ll >= (e_lg < 0.25 ? e_lg : 0.25);
    const int wide = a_ll >= (a_lg < 10.0 ? a_lg : 10.0) && edge_kept;
    const int still = m_ll <= 1.05 * m_lg; /* point data: vertices held at their points */
    outcome result = {closer && wide && still, closer && wide && !still, 0,
                      closer && a_ll >= (a_lg < 10.0 ? a_lg : 10.0) && !edge_kept};
    /* then, L/L's markedly closer, L/G with a finer hold, by the same rule against L/G's */
    const int finer_runs = result.guarded && d_ll <= FACET_FINER_WHEN * d_lg;
    if (finer_runs) {
        o = finer_as_run();
        CHECK_STATUS(facet_planarizer_solve(h_fine, g->xyz, &o, fine, &r_fine, &err), FACET_OK);
        measure(g, fine, &d_f, &m_f, &a_f);
        e_f = edge_ratio(g, fine);
        result.finer = r_fine.stop_reason == FACET_STOP_TOLERANCE && d_f < d_lg &&
                       a_f >= (a_lg < 10.0 ? a_lg : 10.0) && e_f >= (e_lg < 0.25 ? e_lg : 0.25) &&
                       m_f <= 1.05 * m_lg;
        printf("%s: L/G with a finer hold %.6g (moved %.4g, %.3g deg, %d it): %s\n", name, d_f, m_f,
               a_f, (int)r_fine.iterations, result.finer ? "taken" : "not taken");
        CHECK(r.finer_iterations == r_fine.iterations && r.finer_kept == result.finer);
    } else {
        CHECK(r.finer_iterations == 0 && r.finer_kept == 0);
    }
    printf("%s: L/G %.6g (moved %.4g, %.3g deg, edge %.3g, %d it), L/L %.6g (moved %.4g, %.3g deg, "
           "edge %.3g, %d it): %s\n",
           name, d_lg, m_lg, a_lg, e_lg, (int)r_lg.iterations, d_ll, m_ll, a_ll, e_ll, (int)r_ll.iterations,
           result.ll ? "L/L" : result.finer ? "L/G, finer" : "L/G");
    const double *expected = result.ll ? ll : result.finer ? fine : lg;
    const facet_planarize_result *expected_r = result.ll ? &r_ll : result.finer ? &r_fine : &r_lg;
    CHECK(r.narrow_corners == 0 && r_lg.narrow_corners == 0);
    CHECK(r.method == (result.ll ? FACET_METHOD_LOCAL_LOCAL : FACET_METHOD_LOCAL_GLOBAL));
    CHECK(memcmp(out, expected, sizeof(double) * v3) == 0);
    CHECK(r.stop_reason == FACET_STOP_TOLERANCE);
    CHECK(r.planarity_max_rel == expected_r->planarity_max_rel);
    CHECK(r.iterations == r_lg.iterations + r_ll.iterations + (finer_runs ? r_fine.iterations : 0));
    CHECK(r.compare_iterations == r_ll.iterations);
    CHECK(r.first_iterations == r_lg.first_iterations);
    CHECK(r.quality_resolves == r_lg.quality_resolves);
    /* L/G's figures are those of the L/G result returned */
    CHECK(r.compare_distance_rms[FACET_METHOD_LOCAL_GLOBAL] == (result.finer ? d_f : d_lg));
    CHECK(r.compare_distance_rms[FACET_METHOD_LOCAL_LOCAL] == d_ll);
    CHECK(r.compare_min_angle[FACET_METHOD_LOCAL_GLOBAL] == (result.finer ? a_f : a_lg));
    CHECK(r.compare_min_angle[FACET_METHOD_LOCAL_LOCAL] == a_ll);
    CHECK(r.compare_displacement_rms[FACET_METHOD_LOCAL_GLOBAL] == (result.finer ? m_f : m_lg));
    CHECK(r.compare_displacement_rms[FACET_METHOD_LOCAL_LOCAL] == m_ll);
    CHECK(r.compare_edge_ratio[FACET_METHOD_LOCAL_GLOBAL] == (result.finer ? e_f : e_lg));
    CHECK(r.compare_edge_ratio[FACET_METHOD_LOCAL_LOCAL] == e_ll);
    /* the handle's last result is the one returned: a warm start from it as
     * from the handle that solved it alone */
    double *warm = malloc(sizeof(double) * v3);
    facet_planarize_result rw, rw_ref;
    facet_planarize_options_default(FACET_METHOD_LOCAL_GLOBAL, &o);
    o.warm = 1;
    CHECK_STATUS(facet_planarizer_solve(h_auto, g->xyz, &o, out, &rw, &err), FACET_OK);
    facet_planarizer *h_ref = result.ll ? h_ll : result.finer ? h_fine : h_lg;
    CHECK_STATUS(facet_planarizer_solve(h_ref, g->xyz, &o, warm, &rw_ref, &err), FACET_OK);
    CHECK(rw.iterations == rw_ref.iterations && memcmp(out, warm, sizeof(double) * v3) == 0);
    free(warm);
    facet_planarizer_free(&h_lg), facet_planarizer_free(&h_ll), facet_planarizer_free(&h_fine);
    facet_planarizer_free(&h_auto);
    free(lg), free(ll), free(fine), free(out);
    return result;
}

/* ---- progress and cancelling -------------------------------------------- */

enum { MAX_CALLS = 20000 };

typedef struct {
    const facet_planarizer *s;
    int32_t n;
    int32_t iteration[MAX_CALLS], max_iter[MAX_CALLS], stage[MAX_CALLS];
    int32_t cancel_at_compare; /* cancel at the comparison's k-th call (0: never) */
    int32_t cancel_stage;      /* ...of that stage (FACET_STAGE_COMPARE or FACET_STAGE_FINER) */
    int32_t in_compare;
} recorder;

static int record(void *user, int32_t iteration, int32_t max_iter, double planarity)
{
    recorder *r = user;
    (void)planarity;
    const int32_t stage = facet_planarizer_stage(r->s, NULL);
    if (r->n < MAX_CALLS)
        r->iteration[r->n] = iteration, r->max_iter[r->n] = max_iter, r->stage[r->n] = stage;
    ++r->n;
    return stage == (r->cancel_stage ? r->cancel_stage : FACET_STAGE_COMPARE) &&
           r->cancel_at_compare > 0 && ++r->in_compare >= r->cancel_at_compare;
}

/* Whether the recorded calls count 1, 2, ... under bounds that never grow;
 * *calls and *first: how many were made during `stage` and the index of
 * the first of them (-1: none). */
static int scan_calls(const recorder *rec, int32_t stage, int *calls, int *first)
{
    int ordered = 1;
    *calls = 0, *first = -1;
    for (int32_t k = 0; k < rec->n && k < MAX_CALLS; ++k) {
        ordered &= rec->iteration[k] == k + 1 && rec->max_iter[k] >= rec->iteration[k];
        ordered &= k == 0 || rec->max_iter[k] <= rec->max_iter[k - 1];
        if (rec->stage[k] == stage) {
            *first = *first < 0 ? k : *first;
            ++*calls;
        }
    }
    return ordered;
}

static void test_progress_and_cancel(void)
{
    test_mesh g = test_hypar(12);
    const size_t v3 = v3_of(&g);
    facet_planarizer *s = NULL;
    facet_error err;
    CHECK_STATUS(facet_planarizer_create(&g.mesh, &s, &err), FACET_OK);
    double *out = malloc(sizeof(double) * v3), *lg = malloc(sizeof(double) * v3);
    recorder *rec = calloc(1, sizeof *rec);
    rec->s = s;
    facet_planarize_options o;
    facet_planarize_options_default(FACET_METHOD_AUTO, &o);
    o.progress = record, o.progress_user = rec;
    facet_planarize_result r, r_lg;
    CHECK_STATUS(facet_planarizer_solve(s, g.xyz, &o, out, &r, &err), FACET_OK);
    CHECK(r.compare_iterations > 0 && rec->n == r.iterations && rec->n <= MAX_CALLS);
    /* the first solve's bound: its 1000, the four re-solves' 1000, 1000,
     * 4000, 1000, the comparison's 1000 and the finer L/G solve's 1000 */
    CHECK(rec->max_iter[0] == 10000);
    CHECK(r.finer_iterations == 0); /* (L/L's result was refused for its shortest edge) */
    int compare_calls, compare_first;
    CHECK(scan_calls(rec, FACET_STAGE_COMPARE, &compare_calls, &compare_first));
    /* the comparison's calls come last, after every L/G call, and its
     * bound is the iterations done and its own limit */
    CHECK(compare_calls == r.compare_iterations);
    CHECK(compare_first == r.iterations - r.compare_iterations);
    CHECK(compare_first > 0 && rec->max_iter[compare_first] == compare_first + 1000 + 1000);
    CHECK(facet_planarizer_stage(s, NULL) == 0); /* outside a solve */

    /* cancelled in the comparison: L/G's result, which the handle keeps; a
     * warm start from it as on a handle whose last solve was L/G's */
    facet_planarizer *h = NULL;
    CHECK_STATUS(facet_planarizer_create(&g.mesh, &h, &err), FACET_OK);
    double *warm_lg = malloc(sizeof(double) * v3);
    facet_planarize_options_default(FACET_METHOD_LOCAL_GLOBAL, &o);
    CHECK_STATUS(facet_planarizer_solve(h, g.xyz, &o, lg, &r_lg, &err), FACET_OK);
    o.warm = 1;
    facet_planarize_result r_warm;
    CHECK_STATUS(facet_planarizer_solve(h, g.xyz, &o, warm_lg, &r_warm, &err), FACET_OK);
    facet_planarizer_free(&h);
    memset(rec, 0, sizeof *rec);
    rec->s = s, rec->cancel_at_compare = 5;
    facet_planarize_options_default(FACET_METHOD_AUTO, &o);
    o.progress = record, o.progress_user = rec;
    memset(out, 0, sizeof(double) * v3);
    CHECK_STATUS(facet_planarizer_solve(s, g.xyz, &o, out, &r, &err), FACET_ERROR_CANCELLED);
    CHECK(rec->in_compare == 5);
    CHECK(memcmp(out, lg, sizeof(double) * v3) == 0);
    CHECK(r.method == FACET_METHOD_LOCAL_GLOBAL && r.compare_iterations == 5);
    facet_planarize_options_default(FACET_METHOD_LOCAL_GLOBAL, &o);
    o.warm = 1;
    CHECK_STATUS(facet_planarizer_solve(s, g.xyz, &o, out, &r, &err), FACET_OK);
    CHECK(r.iterations == r_warm.iterations && memcmp(out, warm_lg, sizeof(double) * v3) == 0);
    free(warm_lg);
    free(rec), free(out), free(lg);
    facet_planarizer_free(&s);
    test_mesh_free(&g);
}

/* The L/G solve with a finer hold (grid 16x8: L/L's result moved too far,
 * the finer L/G's taken): its calls come last, named FACET_STAGE_FINER,
 * bounded by the iterations done and its limit; cancelled in it, the first
 * L/G result, which the handle keeps. With plane data (vertices sliding) no
 * finer solve can follow: its limit is not in the bound. */
static void test_finer_progress_and_cancel(void)
{
    test_mesh g = test_grid(16, 8, 0.3, 1.0, 0.0);
    const size_t v3 = v3_of(&g);
    facet_planarizer *s = NULL, *h = NULL;
    facet_error err;
    CHECK_STATUS(facet_planarizer_create(&g.mesh, &s, &err), FACET_OK);
    CHECK_STATUS(facet_planarizer_create(&g.mesh, &h, &err), FACET_OK);
    double *out = malloc(sizeof(double) * v3), *lg = malloc(sizeof(double) * v3);
    double *warm_lg = malloc(sizeof(double) * v3);
    recorder *rec = calloc(1, sizeof *rec);
    rec->s = s;
    facet_planarize_options o;
    facet_planarize_options_default(FACET_METHOD_AUTO, &o);
    o.progress = record, o.progress_user = rec;
    facet_planarize_result r, r_lg, r_warm;
    CHECK_STATUS(facet_planarizer_solve(s, g.xyz, &o, out, &r, &err), FACET_OK);
    CHECK(r.finer_iterations > 0 && r.finer_kept == 1 && r.method == FACET_METHOD_LOCAL_GLOBAL);
    CHECK(rec->n == r.iterations && rec->n <= MAX_CALLS && rec->max_iter[0] == 10000);
    int finer_calls, finer_first;
    CHECK(scan_calls(rec, FACET_STAGE_FINER, &finer_calls, &finer_first));
    CHECK(finer_calls == r.finer_iterations && finer_first == r.iterations - r.finer_iterations);
    CHECK(finer_first > 0 && rec->max_iter[finer_first] == finer_first + 1000);
    CHECK(rec->stage[finer_first - 1] == FACET_STAGE_COMPARE);

    /* cancelled in the finer solve: the first L/G result, kept by the handle */
    facet_planarize_options_default(FACET_METHOD_LOCAL_GLOBAL, &o);
    CHECK_STATUS(facet_planarizer_solve(h, g.xyz, &o, lg, &r_lg, &err), FACET_OK);
    o.warm = 1;
    CHECK_STATUS(facet_planarizer_solve(h, g.xyz, &o, warm_lg, &r_warm, &err), FACET_OK);
    memset(rec, 0, sizeof *rec);
    rec->s = s, rec->cancel_at_compare = 5, rec->cancel_stage = FACET_STAGE_FINER;
    facet_planarize_options_default(FACET_METHOD_AUTO, &o);
    o.progress = record, o.progress_user = rec;
    memset(out, 0, sizeof(double) * v3);
    CHECK_STATUS(facet_planarizer_solve(s, g.xyz, &o, out, &r, &err), FACET_ERROR_CANCELLED);
    CHECK(rec->in_compare == 5 && r.finer_iterations == 5 && r.finer_kept == 0);
    CHECK(memcmp(out, lg, sizeof(double) * v3) == 0 && r.method == FACET_METHOD_LOCAL_GLOBAL);
    facet_planarize_options_default(FACET_METHOD_LOCAL_GLOBAL, &o);
    o.warm = 1;
    CHECK_STATUS(facet_planarizer_solve(s, g.xyz, &o, out, &r, &err), FACET_OK);
    CHECK(r.iterations == r_warm.iterations && memcmp(out, warm_lg, sizeof(double) * v3) == 0);

    /* plane data: five re-solve stages (4000 + 1000, then held more firmly 1000 + 1000
     * + 1000) and the comparison, no finer solve */
    memset(rec, 0, sizeof *rec);
    rec->s = s;
    facet_planarize_options_default(FACET_METHOD_AUTO, &o);
    o.data_tangent = 0.01;
    o.progress = record, o.progress_user = rec;
    CHECK_STATUS(facet_planarizer_solve(s, g.xyz, &o, out, &r, &err), FACET_OK);
    CHECK(rec->max_iter[0] == 1000 + 4000 + 1000 + 1000 + 1000 + 1000 + 1000 && r.finer_iterations == 0);
    free(rec), free(out), free(lg), free(warm_lg);
    facet_planarizer_free(&s), facet_planarizer_free(&h);
    test_mesh_free(&g);
}

/* ---- the same bits in place, on 1 and 2 threads, and again on a handle --- */

static void test_same_bits(test_mesh *g)
{
    const size_t v3 = v3_of(g);
    double *one = malloc(sizeof(double) * v3), *two = malloc(sizeof(double) * v3);
    double *again = malloc(sizeof(double) * v3), *inplace = malloc(sizeof(double) * v3);
    facet_planarizer *s = NULL;
    facet_error err;
    CHECK_STATUS(facet_planarizer_create(&g->mesh, &s, &err), FACET_OK);
    facet_planarize_options o;
    facet_planarize_options_default(FACET_METHOD_AUTO, &o);
    facet_planarize_result r1, r2, r3, r4;
    o.threads = 1;
    CHECK_STATUS(facet_planarizer_solve(s, g->xyz, &o, one, &r1, &err), FACET_OK);
    /* a second solve on the handle sets L/G's system up again */
    CHECK_STATUS(facet_planarizer_solve(s, g->xyz, &o, again, &r3, &err), FACET_OK);
    o.threads = 2;
    CHECK_STATUS(facet_planarizer_solve(s, g->xyz, &o, two, &r2, &err), FACET_OK);
    memcpy(inplace, g->xyz, sizeof(double) * v3);
    CHECK_STATUS(facet_planarizer_solve(s, inplace, &o, inplace, &r4, &err), FACET_OK);
    CHECK(r1.compare_iterations > 0);
    CHECK(memcmp(one, two, sizeof(double) * v3) == 0 && r1.iterations == r2.iterations);
    CHECK(memcmp(one, again, sizeof(double) * v3) == 0 && r1.iterations == r3.iterations);
    CHECK(memcmp(one, inplace, sizeof(double) * v3) == 0 && r1.method == r4.method);
    free(one), free(two), free(again), free(inplace);
    facet_planarizer_free(&s);
}

/* ---- solves that make no comparison ---------------------------------------- */

static void test_no_comparison(void)
{
    test_mesh g = test_hypar(8);
    const size_t v3 = v3_of(&g);
    double *out = malloc(sizeof(double) * v3);
    facet_planarizer *s = NULL;
    facet_error err;
    CHECK_STATUS(facet_planarizer_create(&g.mesh, &s, &err), FACET_OK);
    const struct {
        const char *name;
        facet_method method;
        int32_t iterations, warm;
        double laplacian, normal_laplacian, fairness;
        facet_shape_mode shape;
        double hold_tol;
    } cases[] = {
        {"L/G named", FACET_METHOD_LOCAL_GLOBAL, 0, 0, 0, 0, 0, FACET_SHAPE_NONE, 0.01},
        {"L/L named", FACET_METHOD_LOCAL_LOCAL, 0, 0, 0, 0, 0, FACET_SHAPE_NONE, 0.01},
        {"fixed count", FACET_METHOD_AUTO, 30, 0, 0, 0, 0, FACET_SHAPE_NONE, 0.01},
        {"warm", FACET_METHOD_AUTO, 0, 1, 0, 0, 0, FACET_SHAPE_NONE, 0.01},
        {"laplacian", FACET_METHOD_AUTO, 0, 0, 0.1, 0, 0, FACET_SHAPE_NONE, 0.01},
        {"normal laplacian", FACET_METHOD_AUTO, 0, 0, 0, 0.1, 0, FACET_SHAPE_NONE, 0.01},
        {"boundary fairness", FACET_METHOD_AUTO, 0, 0, 0, 0, 0.1, FACET_SHAPE_NONE, 0.01},
        {"ASAP", FACET_METHOD_AUTO, 0, 0, 0, 0, 0, FACET_SHAPE_ASAP, 0.01},
        {"paper's schedule", FACET_METHOD_AUTO, 0, 0, 0, 0, 0, FACET_SHAPE_NONE, 0.0},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        facet_planarize_options o;
        facet_planarize_options_default(cases[c].method, &o);
        o.iterations = cases[c].iterations;
        o.warm = cases[c].warm;
        o.laplacian = cases[c].laplacian;
        o.normal_laplacian = cases[c].normal_laplacian;
        o.boundary_fairness = cases[c].fairness;
        o.shape = cases[c].shape;
        o.hold_tol = cases[c].hold_tol;
        facet_planarize_result r;
        memset(&r, 0xff, sizeof r);
        const facet_status status = facet_planarizer_solve(s, g.xyz, &o, out, &r, &err);
        CHECK(status == FACET_OK || status == FACET_WARNING_NOT_CONVERGED);
        if (r.compare_iterations != 0 || r.compare_distance_rms[0] != 0.0 ||
            r.compare_min_angle[1] != 0.0)
            printf("%s: compared (%d iterations)\n", cases[c].name, (int)r.compare_iterations);
        CHECK(r.finer_iterations == 0 && r.finer_kept == 0);
        CHECK(r.compare_iterations == 0 && r.compare_distance_rms[0] == 0.0 &&
              r.compare_distance_rms[1] == 0.0 && r.compare_min_angle[0] == 0.0 &&
              r.compare_min_angle[1] == 0.0);
    }
    free(out);
    facet_planarizer_free(&s);
    test_mesh_free(&g);
}

int main(void)
{
    int took_ll = 0, kept_lg = 0, guarded = 0, finer = 0, short_edge = 0;
    const struct {
        const char *name;
        int hypar; /* n for test_hypar, else a test_grid of nu x nv */
        int nu, nv;
        double amplitude;
    } meshes[] = {
        {"hypar 8", 8, 0, 0, 0},       {"hypar 12", 12, 0, 0, 0},      {"hypar 6", 6, 0, 0, 0},
        {"grid 12x9", 0, 12, 9, 0.5},  {"grid 24x18", 0, 24, 18, 0.3}, {"grid 20x20", 0, 20, 20, 1.0},
        {"grid 16x8", 0, 16, 8, 0.3},  {"grid 12x12", 0, 12, 12, 0.4},
    };
    for (size_t m = 0; m < sizeof meshes / sizeof meshes[0]; ++m) {
        test_mesh g = meshes[m].hypar ? test_hypar(meshes[m].hypar)
                                      : test_grid(meshes[m].nu, meshes[m].nv, meshes[m].amplitude, 1.0, 0.0);
        const outcome o = check_rule(meshes[m].name, &g);
        took_ll += o.ll, kept_lg += !o.ll, guarded += o.guarded, finer += o.finer;
        short_edge += o.short_edge;
        if (m == 0)
            test_same_bits(&g);
        test_mesh_free(&g);
    }
    /* the meshes cover every outcome (else a branch of the rule is untested):
     * L/L's result (hypar 6, grid 12x12), L/G's, L/L's refused for moving
     * further and then the finer L/G's taken (grid 16x8) or not (grid
     * 24x18), L/L's refused for its shortest edge (hypar 12) */
    CHECK(took_ll > 0 && kept_lg > 0 && guarded > finer && finer > 0 && short_edge > 0);
    printf("L/L taken on %d, L/G's kept on %d, L/L's moved too far on %d, the finer L/G's taken on %d\n",
           took_ll, kept_lg, guarded, finer);
    test_progress_and_cancel();
    test_finer_progress_and_cancel();
    test_no_comparison();
    return check_report("test_planarize_compare");
}
