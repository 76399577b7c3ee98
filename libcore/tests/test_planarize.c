/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Solver invariants: planar input unchanged, tolerance reached, the same bits
 * for 1 and 2 threads, scale invariance, bad options, cancel, warm restart,
 * and no divergence on long runs. */
#include "check.h"
#include "facet.h"
#include "test_meshes.h"

#include <stdlib.h>
#include <string.h>

static double max_rel_planarity(const facet_mesh *m, const double *xyz)
{
    facet_mesh mm = *m;
    mm.xyz = xyz;
    double *a = malloc(sizeof(double) * (size_t)m->n_faces);
    double *e = malloc(sizeof(double) * (size_t)m->n_faces);
    facet_planarity(&mm, 1, a, NULL, e, NULL, NULL);
    double worst = 0.0;
    for (int32_t f = 0; f < m->n_faces; ++f)
        worst = fmax(worst, a[f] / e[f]);
    free(a);
    free(e);
    return worst;
}

static double max_move(const double *a, const double *b, int32_t nv)
{
    double worst = 0.0;
    for (int32_t v = 0; v < nv; ++v) {
        const double dx = a[3 * v] - b[3 * v], dy = a[3 * v + 1] - b[3 * v + 1],
                     dz = a[3 * v + 2] - b[3 * v + 2];
        worst = fmax(worst, sqrt(dx * dx + dy * dy + dz * dz));
    }
    return worst;
}

static int stop_after;
static int cancel_at(void *user, int32_t it, int32_t max_it, double rel)
{
    (void)user, (void)max_it, (void)rel;
    return it >= stop_after;
}

static void test_planar_input_unchanged(facet_method method)
{
    /* a cylinder strip: every quad is a planar rectangle */
    const int nu = 12, nv = 5;
    test_mesh t = test_grid(nu, nv, 0.0, 1.0, 0.0);
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
            const int v = j * (nu + 1) + i;
            const double a = 0.2 * i;
            t.xyz[3 * v] = 654321.0 + 8.0 * cos(a);
            t.xyz[3 * v + 1] = 1234567.0 + 8.0 * sin(a);
            t.xyz[3 * v + 2] = 1.3 * j;
        }
    facet_planarizer *s = NULL;
    facet_error e;
    CHECK_STATUS(facet_planarizer_create(&t.mesh, &s, &e), FACET_OK);
    facet_planarize_options o;
    facet_planarize_options_default(method, &o);
    double *out = malloc(sizeof(double) * 3 * (size_t)t.mesh.n_vertices);
    facet_planarize_result r;
    CHECK_STATUS(facet_planarizer_solve(s, t.xyz, &o, out, &r, &e), FACET_OK);
    CHECK(r.stop_reason == FACET_STOP_TOLERANCE);
    CHECK(max_move(out, t.xyz, t.mesh.n_vertices) == 0.0); /* stopped before any update */
    /* also when forced to iterate: within 1e-12 of the edge length (1.3) */
    o.iterations = 50;
    CHECK_STATUS(facet_planarizer_solve(s, t.xyz, &o, out, &r, &e), FACET_OK);
    CHECK(r.iterations == 50 && r.stop_reason == FACET_STOP_ITERATIONS);
    CHECK(max_move(out, t.xyz, t.mesh.n_vertices) <= 1e-12 * 1.3);
    free(out);
    facet_planarizer_free(&s);
    CHECK(s == NULL);
    test_mesh_free(&t);
}

static void test_converges(facet_method method, double tol)
{
    test_mesh t = test_grid(24, 18, 0.6, 1.0, 0.0);
    CHECK(max_rel_planarity(&t.mesh, t.xyz) > 1e-2);
    facet_planarizer *s = NULL;
    facet_error e;
    CHECK_STATUS(facet_planarizer_create(&t.mesh, &s, &e), FACET_OK);
    facet_planarize_options o;
    facet_planarize_options_default(method, &o);
    o.tol_rel = tol;
    const size_t n = 3 * (size_t)t.mesh.n_vertices;
    double *out1 = malloc(sizeof(double) * n), *out2 = malloc(sizeof(double) * n);
    facet_planarize_result r1, r2;
    o.threads = 1;
    CHECK_STATUS(facet_planarizer_solve(s, t.xyz, &o, out1, &r1, &e), FACET_OK);
    CHECK(r1.stop_reason == FACET_STOP_TOLERANCE);
    CHECK(r1.planarity_max_rel <= tol);
    CHECK(max_rel_planarity(&t.mesh, out1) <= tol * 1.0001);
    /* the result stays near the design: no vertex moves more than an edge */
    CHECK(max_move(out1, t.xyz, t.mesh.n_vertices) < 1.0);
    o.threads = 2;
    CHECK_STATUS(facet_planarizer_solve(s, t.xyz, &o, out2, &r2, &e), FACET_OK);
    CHECK(r1.iterations == r2.iterations);
    CHECK(memcmp(out1, out2, sizeof(double) * n) == 0);

    /* the same mesh in millimetres at georeferenced coordinates: same answer
     * relative to its scale */
    test_mesh big = test_grid(24, 18, 0.6, 1000.0, 2.5e6);
    double *out3 = malloc(sizeof(double) * n);
    facet_planarizer *s2 = NULL;
    CHECK_STATUS(facet_planarizer_create(&big.mesh, &s2, &e), FACET_OK);
    facet_planarize_result r3;
    o.threads = 0;
    CHECK_STATUS(facet_planarizer_solve(s2, big.xyz, &o, out3, &r3, &e), FACET_OK);
    CHECK(abs(r3.iterations - r1.iterations) <= 1);
    CHECK(max_rel_planarity(&big.mesh, out3) <= tol * 1.0001);
    double worst = 0.0;
    for (size_t k = 0; k < n; ++k)
        worst = fmax(worst, fabs((out3[k] - (k % 3 == 2 ? 0.0 : 2.5e6)) / 1000.0 - out1[k]));
    CHECK(worst < 1e-6);

    /* warm restart after an edit: one vertex lifted by a tenth of an edge */
    double *edited = malloc(sizeof(double) * n);
    memcpy(edited, t.xyz, sizeof(double) * n);
    edited[3 * 200 + 2] += 0.1;
    facet_planarize_result cold, warm;
    CHECK_STATUS(facet_planarizer_solve(s, edited, &o, out2, &cold, &e), FACET_OK);
    double *cold_out = malloc(sizeof(double) * n);
    memcpy(cold_out, out2, sizeof(double) * n);
    CHECK_STATUS(facet_planarizer_solve(s, t.xyz, &o, out1, &r1, &e), FACET_OK);
    facet_planarize_options ow = o;
    ow.warm = 1;
    ow.mu0 = 1e-5;
    CHECK_STATUS(facet_planarizer_solve(s, edited, &ow, out2, &warm, &e), FACET_OK);
    CHECK(warm.stop_reason == FACET_STOP_TOLERANCE);
    if (!(warm.iterations >= 1 && warm.iterations < cold.iterations))
        fprintf(stderr, "method %d: warm %d cold %d\n", (int)method, (int)warm.iterations, (int)cold.iterations);
    CHECK(warm.iterations >= 1 && warm.iterations < cold.iterations);
    /* the edit shows in the warm result: the lifted vertex follows it */
    /* the edit was not ignored: the result changed */
    CHECK(max_move(out2, out1, t.mesh.n_vertices) > 1e-3);
    /* and the warm result is continuous: it moves less than the edit did */
    if (!(max_move(out2, out1, t.mesh.n_vertices) < 0.1))
        fprintf(stderr, "method %d: warm result moved %g\n", (int)method, max_move(out2, out1, t.mesh.n_vertices));
    CHECK(max_move(out2, out1, t.mesh.n_vertices) < 0.1);
    CHECK(max_rel_planarity(&t.mesh, out2) <= tol * 1.0001);

    /* cancel from the progress callback */
    stop_after = 3;
    o.progress = cancel_at;
    CHECK_STATUS(facet_planarizer_solve(s, t.xyz, &o, out1, &r1, &e), FACET_ERROR_CANCELLED);
    CHECK(r1.iterations == 3 && r1.stop_reason == FACET_STOP_CANCELLED);
    o.progress = NULL;

    /* bad options and bad input; the output is untouched */
    facet_planarize_options bad = o;
    bad.mu_min = 0.0;
    CHECK_STATUS(facet_planarizer_solve(s, t.xyz, &bad, out1, &r1, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(e.message, "mu_min") != NULL);
    bad = o;
    bad.ratio = 1.5;
    CHECK_STATUS(facet_planarizer_solve(s, t.xyz, &bad, out1, &r1, &e), FACET_ERROR_INVALID_ARGUMENT);
    /* a weight more than FACET_WEIGHT_SPAN times data_tangent: refused by name
     * (parallelogram 1e16 gave FACET_OK with vertices 900 units off a unit grid) */
    bad = o;
    bad.parallelogram = 2e12;
    CHECK_STATUS(facet_planarizer_solve(s, t.xyz, &bad, out1, &r1, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(e.message, "parallelogram 2e+12 is more than 1e+12 times data_tangent (1)") != NULL);
    bad = o;
    bad.data_tangent = 1e-3, bad.boundary_fairness = 1e10;
    CHECK_STATUS(facet_planarizer_solve(s, t.xyz, &bad, out1, &r1, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(e.message, "boundary_fairness") != NULL);
    bad.boundary_fairness = 1e9; /* at the span: taken */
    bad.max_iter = 1;
    CHECK(facet_planarizer_solve(s, t.xyz, &bad, out1, &r1, &e) >= 0);
    bad = o;
    bad.shape_weight = 1e20; /* with no shape term it is not read: taken */
    bad.max_iter = 1;
    CHECK(facet_planarizer_solve(s, t.xyz, &bad, out1, &r1, &e) >= 0);
    bad.shape = FACET_SHAPE_ARAP;
    CHECK_STATUS(facet_planarizer_solve(s, t.xyz, &bad, out1, &r1, &e), FACET_ERROR_INVALID_ARGUMENT);
    memcpy(edited, t.xyz, sizeof(double) * n);
    edited[3 * 17 + 1] = NAN;
    memcpy(out2, out1, sizeof(double) * n);
    CHECK_STATUS(facet_planarizer_solve(s, edited, &o, out1, &r1, &e), FACET_ERROR_NONFINITE);
    CHECK(e.vertex == 17 && strstr(e.message, "vertex 17") != NULL);
    CHECK(memcmp(out1, out2, sizeof(double) * n) == 0);

    free(edited);
    free(cold_out);
    free(out1);
    free(out2);
    free(out3);
    facet_planarizer_free(&s);
    facet_planarizer_free(&s2);
    test_mesh_free(&t);
    test_mesh_free(&big);
}

/* Thousands of iterations: the mu floor keeps every iterate finite and near
 * the design (without it L/L flies off past ~150 iterations). */
static void test_long_run(facet_method method, int iterations)
{
    test_mesh t = test_grid(20, 14, 0.8, 1.0, 0.0);
    facet_planarizer *s = NULL;
    facet_error e;
    CHECK_STATUS(facet_planarizer_create(&t.mesh, &s, &e), FACET_OK);
    facet_planarize_options o;
    facet_planarize_options_default(method, &o);
    o.iterations = iterations;
    double *out = malloc(sizeof(double) * 3 * (size_t)t.mesh.n_vertices);
    facet_planarize_result r;
    CHECK_STATUS(facet_planarizer_solve(s, t.xyz, &o, out, &r, &e), FACET_OK);
    CHECK(r.iterations == iterations);
    int finite = 1;
    for (int32_t k = 0; k < 3 * t.mesh.n_vertices; ++k)
        finite &= isfinite(out[k]) != 0;
    CHECK(finite);
    CHECK(max_move(out, t.xyz, t.mesh.n_vertices) < 1.0);
    CHECK(r.planarity_max_rel < 1e-3);
    free(out);
    facet_planarizer_free(&s);
    test_mesh_free(&t);
}

/* Live updates: after a solve, one vertex is dragged; only its region moves,
 * the whole mesh stays planar, nothing changed means nothing moves, and the
 * result is the same bits for 1 and 2 threads. */
static void test_live_update(facet_method method, double tol)
{
    test_mesh t = test_grid(30, 24, 0.6, 1000.0, 2.5e6); /* mm, georeferenced */
    const int32_t nv = t.mesh.n_vertices;
    const size_t n = 3 * (size_t)nv;
    facet_planarizer *s = NULL, *s2 = NULL;
    facet_error e;
    CHECK_STATUS(facet_planarizer_create(&t.mesh, &s, &e), FACET_OK);
    CHECK_STATUS(facet_planarizer_create(&t.mesh, &s2, &e), FACET_OK);
    facet_planarize_options o;
    facet_planarize_options_default(method, &o);
    o.tol_rel = tol;
    double *control = malloc(sizeof(double) * n), *first = malloc(sizeof(double) * n);
    double *out = malloc(sizeof(double) * n), *out2 = malloc(sizeof(double) * n);
    memcpy(control, t.xyz, sizeof(double) * n);
    facet_planarize_result r;
    /* no previous solve: refused */
    CHECK_STATUS(facet_planarizer_update(s, control, &o, 0, out, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(e.message, "previous solve") != NULL);
    o.threads = 1;
    CHECK_STATUS(facet_planarizer_solve(s, control, &o, first, &r, &e), FACET_OK);
    CHECK_STATUS(facet_planarizer_solve(s2, control, &o, out2, &r, &e), FACET_OK);
    /* nothing edited: the previous result, bit for bit, no iteration */
    CHECK_STATUS(facet_planarizer_update(s, control, &o, 0, out, &r, &e), FACET_OK);
    CHECK(r.iterations == 0 && memcmp(out, first, sizeof(double) * n) == 0);
    CHECK(r.planarity_max_rel <= tol);
    CHECK_STATUS(facet_planarizer_update(s, control, &o, -1, out, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(facet_planarizer_update(s, NULL, &o, 0, out, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    /* drag vertex (12, 15) in three steps of a hundredth of an edge */
    const int32_t dragged = 15 * 31 + 12;
    o.mu0 = 1e-3, o.hold_tol = 0.0;
    for (int step = 1; step <= 3; ++step) {
        control[3 * dragged + 2] += 10.0;
        o.threads = 1;
        CHECK_STATUS(facet_planarizer_update(s, control, &o, 3, out, &r, &e), FACET_OK);
        if (getenv("FACET_TEST_VERBOSE"))
            fprintf(stderr, "live step %d: %d iterations, stop %d\n", step, (int)r.iterations, (int)r.stop_reason);
        CHECK(r.stop_reason == FACET_STOP_TOLERANCE && r.iterations > 0);
        CHECK(r.planarity_max_rel <= tol);
        CHECK(max_rel_planarity(&t.mesh, out) <= tol * 1.0001);
        o.threads = 2;
        CHECK_STATUS(facet_planarizer_update(s2, control, &o, 3, out2, &r, &e), FACET_OK);
        CHECK(memcmp(out, out2, sizeof(double) * n) == 0);
    }
    /* the result followed the drag (up 30 mm in all) */
    CHECK(out[3 * dragged + 2] - first[3 * dragged + 2] > 10.0);
    /* vertices beyond the region (3 rings and the rim) kept their bits */
    int32_t moved_far = 0, moved_near = 0;
    for (int32_t v = 0; v < nv; ++v) {
        const int32_t dx = abs(v % 31 - 12), dy = abs(v / 31 - 15);
        const int same = memcmp(out + 3 * (size_t)v, first + 3 * (size_t)v, 3 * sizeof(double)) == 0;
        if (dx + dy > 4)
            moved_far += !same;
        else
            moved_near += !same;
    }
    CHECK(moved_far == 0);
    CHECK(moved_near > 1);
    /* a large edit (half an edge) in a one-ring region: the held rim keeps it
     * from the tolerance, so the region grows until it is reached */
    control[3 * dragged + 2] += 500.0;
    o.threads = 0;
    CHECK_STATUS(facet_planarizer_update(s, control, &o, 1, out, &r, &e), FACET_OK);
    CHECK(r.stop_reason == FACET_STOP_TOLERANCE);
    CHECK(max_rel_planarity(&t.mesh, out) <= tol * 1.0001);
    CHECK(out[3 * dragged + 2] - first[3 * dragged + 2] > 100.0);
    /* a newly fixed vertex: the next update solves in full and pins it; the
     * one after is live again and keeps it pinned */
    const int32_t pin = dragged + 1;
    CHECK_STATUS(facet_planarizer_set_fixed(s, 1, &pin, &e), FACET_OK);
    o.threads = 0;
    for (int step = 0; step < 2; ++step) {
        control[3 * dragged] += 50.0;
        CHECK_STATUS(facet_planarizer_update(s, control, &o, 3, out, &r, &e), FACET_OK);
        CHECK(memcmp(out + 3 * (size_t)pin, control + 3 * (size_t)pin, 3 * sizeof(double)) == 0);
        CHECK(max_rel_planarity(&t.mesh, out) <= tol * 1.0001);
    }
    facet_planarizer_free(&s);
    facet_planarizer_free(&s2);
    free(control), free(first), free(out), free(out2);
    test_mesh_free(&t);
}

/* Live updates at the edges: a mesh in two pieces with a vertex of no face,
 * bad options with nothing moved, and the result written over the input. */
static void test_live_update_edges(void)
{
    /* two twisted quads apart, and vertex 8 in no face */
    const double xyz[] = {0, 0, 0, 1, 0, 0.1, 1, 1, 0, 0, 1, 0.1, 3, 0, 0, 4, 0, 0.1,
                          4, 1, 0, 3, 1, 0.1, 9, 9, 9};
    const int32_t face_start[] = {0, 4, 8}, face_vertices[] = {0, 1, 2, 3, 4, 5, 6, 7};
    const facet_mesh mesh = {9, 2, xyz, face_start, face_vertices};
    facet_planarizer *s = NULL;
    facet_error e;
    CHECK_STATUS(facet_planarizer_create(&mesh, &s, &e), FACET_OK);
    facet_planarize_options o;
    facet_planarize_options_default(FACET_METHOD_LOCAL_GLOBAL, &o);
    double control[27], first[27], out[27];
    memcpy(control, xyz, sizeof control);
    facet_planarize_result r;
    CHECK_STATUS(facet_planarizer_solve(s, control, &o, first, &r, &e), FACET_OK);
    /* a tolerance no solve reaches: the region, one quad, cannot grow into the other
     * piece; the update never ended (ring counts doubled until they overflowed) */
    facet_planarize_options stuck = o;
    stuck.tol_rel = 0.0, stuck.tol_abs = 1e-300, stuck.max_iter = 50;
    control[2] += 0.05;
    const facet_status status = facet_planarizer_update(s, control, &stuck, 0, out, &r, &e);
    CHECK(status >= 0 && r.stop_reason != FACET_STOP_TOLERANCE);
    CHECK(r.iterations <= 50); /* one solve of the piece: the same region was solved again */
    CHECK(memcmp(out + 12, first + 12, 12 * sizeof(double)) == 0); /* the other piece kept */
    control[2] -= 0.05;
    CHECK_STATUS(facet_planarizer_solve(s, control, &o, first, &r, &e), FACET_OK);
    /* only the vertex of no face moved: it goes there; it failed with "empty mesh" */
    control[24] += 1.0;
    CHECK_STATUS(facet_planarizer_update(s, control, &o, 0, out, &r, &e), FACET_OK);
    CHECK(out[24] == first[24] + 1.0 && out[25] == first[25] && out[26] == first[26]);
    CHECK(memcmp(out, first, 24 * sizeof(double)) == 0 && r.iterations == 0);
    /* bad options are refused whether or not a vertex moved (nothing moved: FACET_OK) */
    facet_planarize_options bad = o;
    bad.mu0 = NAN;
    CHECK_STATUS(facet_planarizer_update(s, control, &bad, 0, out, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(e.message, "mu0") != NULL);
    bad = o, bad.method = (facet_method)7;
    CHECK_STATUS(facet_planarizer_update(s, control, &bad, 0, out, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    facet_planarizer_free(&s);

    /* the result written over the input (as facet_planarizer_solve allows): the stored
     * control positions took the result, so the next drag moved every vertex */
    test_mesh t = test_grid(8, 8, 0.6, 1.0, 0.0);
    const size_t m = 3 * (size_t)t.mesh.n_vertices;
    facet_planarizer *a = NULL, *b = NULL;
    CHECK_STATUS(facet_planarizer_create(&t.mesh, &a, &e), FACET_OK);
    CHECK_STATUS(facet_planarizer_create(&t.mesh, &b, &e), FACET_OK);
    double *in = malloc(sizeof(double) * m), *io = malloc(sizeof(double) * m);
    double *res = malloc(sizeof(double) * m);
    memcpy(in, t.xyz, sizeof(double) * m);
    o.threads = 1;
    CHECK_STATUS(facet_planarizer_solve(a, in, &o, res, &r, &e), FACET_OK);
    CHECK_STATUS(facet_planarizer_solve(b, in, &o, io, &r, &e), FACET_OK);
    for (int step = 0; step < 2; ++step) {
        in[3 * 40 + 2] += 0.02;
        memcpy(io, in, sizeof(double) * m);
        CHECK_STATUS(facet_planarizer_update(a, in, &o, 0, res, &r, &e), FACET_OK);
        CHECK_STATUS(facet_planarizer_update(b, io, &o, 0, io, &r, &e), FACET_OK);
        CHECK(memcmp(res, io, sizeof(double) * m) == 0);
    }
    facet_planarizer_free(&a);
    facet_planarizer_free(&b);
    free(in), free(io), free(res);
    test_mesh_free(&t);
}

int main(void)
{
    test_live_update_edges();
    test_live_update(FACET_METHOD_LOCAL_GLOBAL, 1e-6);
    test_live_update(FACET_METHOD_LOCAL_LOCAL, 1e-3);
    test_planar_input_unchanged(FACET_METHOD_LOCAL_LOCAL);
    test_planar_input_unchanged(FACET_METHOD_LOCAL_GLOBAL);
    test_converges(FACET_METHOD_LOCAL_GLOBAL, 1e-6);
    test_converges(FACET_METHOD_LOCAL_LOCAL, 1e-3);
    test_long_run(FACET_METHOD_LOCAL_LOCAL, 3000);
    test_long_run(FACET_METHOD_LOCAL_GLOBAL, 1000);

    facet_planarizer *s = NULL;
    CHECK_STATUS(facet_planarizer_create(NULL, &s, NULL), FACET_ERROR_INVALID_ARGUMENT);
    facet_planarizer_free(NULL);
    return check_report("test_planarize");
}
