/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* The planarizer's memory layout (docs/benchmarks.md, "Memory per face"):
 * the last result, kept between solves in the Anderson history's memory,
 * survives the history's reallocation, solves without a history and live
 * updates; the history ring at depths 1 (its f and g in a column beside the
 * ring), 2, 5 and 16 gives the same bits for 1 and 2 threads; L/G's matrix,
 * no longer stored, with held vertices and faces of more than 255 corners.
 * The same for a mesh above FACET_ANDERSON_SKETCH_VERTICES, whose history
 * keeps the residuals' differences for a sample of the entries only. */
#include "check.h"
#include "facet.h"
#include "planarize_internal.h"
#include "test_meshes.h"

#include <stdlib.h>
#include <string.h>

/* Without the quality re-solves on the sketched grid, whose first solve
 * leaves a corner under 5 degrees (re-solved without Anderson, 30 times the
 * solve): these tests are about the history. */
static int no_quality;

static facet_planarize_options options(facet_method method, int anderson, int threads)
{
    facet_planarize_options o;
    facet_planarize_options_default(method, &o);
    o.anderson = anderson;
    o.threads = threads;
    if (no_quality)
        o.quality_angle = 0.0;
    return o;
}

/* A solve that stops at iteration 0 gives back its starting point: with
 * warm, the last result, bit for bit. */
static void check_previous_is(facet_planarizer *s, const test_mesh *t, facet_method method, int anderson,
                              const double *expected)
{
    const size_t n = 3 * (size_t)t->mesh.n_vertices;
    double *out = malloc(sizeof(double) * n);
    facet_planarize_options o = options(method, anderson, 1);
    o.warm = 1;
    o.max_iter = 0;
    facet_planarize_result r;
    facet_error e;
    const facet_status status = facet_planarizer_solve(s, t->xyz, &o, out, &r, &e);
    CHECK(status >= 0);
    CHECK(r.iterations == 0);
    CHECK(memcmp(out, expected, sizeof(double) * n) == 0);
    free(out);
}

/* A grid of nu x nv quads: small, or (SKETCHED) with just over
 * FACET_ANDERSON_SKETCH_VERTICES vertices. */
enum { SMALL = 0, SKETCHED = 1 };

static test_mesh grid(int size, int nu, int nv)
{
    no_quality = size == SKETCHED;
    return size == SKETCHED ? test_grid(185, 180, 0.6, 1.0, 0.0) : test_grid(nu, nv, 0.6, 1.0, 0.0);
}

static void test_previous_kept(facet_method method, int first_depth, int size)
{
    test_mesh t = grid(size, 16, 12);
    const size_t n = 3 * (size_t)t.mesh.n_vertices;
    facet_planarizer *s = NULL;
    facet_error e;
    CHECK_STATUS(facet_planarizer_create(&t.mesh, &s, &e), FACET_OK);
    double *first = malloc(sizeof(double) * n), *out = malloc(sizeof(double) * n);
    facet_planarize_options o = options(method, first_depth, 1);
    facet_planarize_result r;
    CHECK_STATUS(facet_planarizer_solve(s, t.xyz, &o, first, &r, &e), FACET_OK);
    /* a deeper history: reallocated, the last result moved with it */
    check_previous_is(s, &t, method, 8, first);
    /* a solve without a history leaves it alone */
    check_previous_is(s, &t, method, 0, first);
    check_previous_is(s, &t, method, 3, first);
    /* a live update with nothing edited gives the last result back */
    o = options(method, 5, 1);
    CHECK_STATUS(facet_planarizer_update(s, t.xyz, &o, 0, out, &r, &e), FACET_OK);
    CHECK(memcmp(out, first, sizeof(double) * n) == 0);
    /* an edit, then a warm solve from it: the same as on a fresh handle
     * that solved the same first (the history's use leaves no trace) */
    double *edited = malloc(sizeof(double) * n), *again = malloc(sizeof(double) * n);
    memcpy(edited, t.xyz, sizeof(double) * n);
    edited[3 * 40 + 2] += 0.1;
    o = options(method, 5, 1);
    o.warm = 1;
    CHECK(facet_planarizer_solve(s, edited, &o, out, &r, &e) >= 0);
    facet_planarizer *fresh = NULL;
    CHECK_STATUS(facet_planarizer_create(&t.mesh, &fresh, &e), FACET_OK);
    facet_planarize_options o1 = options(method, first_depth, 1);
    CHECK_STATUS(facet_planarizer_solve(fresh, t.xyz, &o1, again, &r, &e), FACET_OK);
    CHECK(facet_planarizer_solve(fresh, edited, &o, again, &r, &e) >= 0);
    CHECK(memcmp(out, again, sizeof(double) * n) == 0);
    facet_planarizer_free(&fresh);
    facet_planarizer_free(&s);
    free(first), free(out), free(edited), free(again);
    test_mesh_free(&t);
}

static void test_depths(facet_method method, int depth, int size)
{
    test_mesh t = grid(size, 14, 10);
    const size_t n = 3 * (size_t)t.mesh.n_vertices;
    facet_planarizer *s = NULL;
    facet_error e;
    CHECK_STATUS(facet_planarizer_create(&t.mesh, &s, &e), FACET_OK);
    double *out1 = malloc(sizeof(double) * n), *out2 = malloc(sizeof(double) * n);
    facet_planarize_result r1, r2;
    facet_planarize_options o = options(method, depth, 1);
    CHECK_STATUS(facet_planarizer_solve(s, t.xyz, &o, out1, &r1, &e), FACET_OK);
    CHECK(r1.planarity_max_rel <= 1e-6);
    CHECK(r1.anderson_accepted > 0);
    /* near the design (unit edges): a refused extrapolation goes back to
     * the plain step's iterate, not to some other column of the history */
    double worst = 0.0;
    for (size_t k = 0; k < n; ++k)
        worst = fmax(worst, fabs(out1[k] - t.xyz[k]));
    CHECK(worst < 1.0); /* 0.51-0.53 here; 7.5 when a refusal took the wrong column */
    if (size == SKETCHED) /* the sketch's extrapolations are as good as the full history's */
        CHECK(r1.anderson_accepted >= r1.iterations * 3 / 4);
    o.threads = 2;
    CHECK_STATUS(facet_planarizer_solve(s, t.xyz, &o, out2, &r2, &e), FACET_OK);
    CHECK(r1.iterations == r2.iterations);
    CHECK(r1.anderson_accepted == r2.anderson_accepted && r1.anderson_rejected == r2.anderson_rejected);
    CHECK(memcmp(out1, out2, sizeof(double) * n) == 0);
    facet_planarizer_free(&s);
    free(out1), free(out2);
    test_mesh_free(&t);
}

/* A ring of n quads around one n-gon, slightly out of plane. */
static test_mesh ring_mesh(int n)
{
    test_mesh t;
    const int nv = 2 * n, nf = n + 1;
    t.xyz = malloc(sizeof(double) * 3 * (size_t)nv);
    t.face_start = malloc(sizeof(int32_t) * (size_t)(nf + 1));
    t.face_vertices = malloc(sizeof(int32_t) * (size_t)(n + 4 * n));
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * M_PI * i / n, wobble = 0.05 * sin(7.0 * a) * cos(3.0 * a);
        t.xyz[3 * i] = cos(a), t.xyz[3 * i + 1] = sin(a), t.xyz[3 * i + 2] = wobble;
        t.xyz[3 * (n + i)] = 1.1 * cos(a), t.xyz[3 * (n + i) + 1] = 1.1 * sin(a);
        t.xyz[3 * (n + i) + 2] = 0.05 + 0.5 * wobble;
    }
    t.face_start[0] = 0;
    for (int i = 0; i < n; ++i) /* the n-gon, its vertices in an order of their own */
        t.face_vertices[i] = (int32_t)((n - 1 - i + n / 3) % n);
    /* (reversed and rotated: the corners' ascending order is not theirs) */
    t.face_start[1] = n;
    for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n;
        int32_t *q = t.face_vertices + n + 4 * i;
        /* consistent with the n-gon's (reversed) orientation */
        q[0] = i, q[1] = j, q[2] = n + j, q[3] = n + i;
        t.face_start[2 + i] = n + 4 * (i + 1);
    }
    test_mesh_view(&t, nv, nf);
    return t;
}

static void test_big_face(int n, int held)
{
    test_mesh t = ring_mesh(n);
    const size_t size = 3 * (size_t)t.mesh.n_vertices;
    facet_planarizer *s = NULL;
    facet_error e;
    CHECK_STATUS(facet_planarizer_create(&t.mesh, &s, &e), FACET_OK);
    if (held) {
        int32_t fixed[64], count = 0;
        for (int32_t v = 0; v < t.mesh.n_vertices && count < 64; v += 13)
            fixed[count++] = v;
        CHECK_STATUS(facet_planarizer_set_fixed(s, count, fixed, &e), FACET_OK);
    }
    double *out1 = malloc(sizeof(double) * size), *out2 = malloc(sizeof(double) * size);
    facet_planarize_result r1, r2;
    facet_planarize_options o = options(FACET_METHOD_LOCAL_GLOBAL, 5, 1);
    const facet_status s1 = facet_planarizer_solve(s, t.xyz, &o, out1, &r1, &e);
    CHECK(s1 >= 0);
    if (!held) /* held vertices on the n-gon need not let it be planar */
        CHECK(s1 == FACET_OK && r1.planarity_max_rel <= 1e-6);
    CHECK(all_finite(out1, size));
    o.threads = 2;
    const facet_status s2 = facet_planarizer_solve(s, t.xyz, &o, out2, &r2, &e);
    CHECK(s1 == s2 && r1.iterations == r2.iterations);
    CHECK(memcmp(out1, out2, sizeof(double) * size) == 0);
    if (held) /* held vertices stay where they were, bit for bit */
        for (int32_t v = 0; v < t.mesh.n_vertices; v += 13)
            CHECK(memcmp(out1 + 3 * (size_t)v, t.xyz + 3 * (size_t)v, 3 * sizeof(double)) == 0);
    facet_planarizer_free(&s);
    free(out1), free(out2);
    test_mesh_free(&t);
}

/* The sketch's column: every entry below the threshold; from it, three
 * pieces of 512 vertices per block of 32,768 entries (a seventh), at least
 * every stride-th piece of each block. */
static void test_sketch_length(void)
{
    const int32_t below = FACET_ANDERSON_SKETCH_VERTICES - 1, at = FACET_ANDERSON_SKETCH_VERTICES;
    CHECK(facet_pl_anderson_len(below) == 3 * (size_t)below);
    const size_t len = facet_pl_anderson_len(at), n = 3 * (size_t)at;
    CHECK(len * 7 <= n && len * FACET_ANDERSON_SKETCH_STRIDE >= n);
    CHECK(facet_pl_anderson_len(1000000) * 7 <= 3000000);
}

/* The control faces' centroids are the shape term's alone: a solve without
 * it leaves them unallocated, and a handle that first solved without it
 * then with it gives the bits of a fresh handle solved with it (they are
 * computed when first asked for). */
static void test_shape_arrays_on_demand(void)
{
    test_mesh t = test_grid(12, 9, 0.6, 1.0, 0.0);
    const size_t n = 3 * (size_t)t.mesh.n_vertices;
    double *reused = malloc(sizeof(double) * n), *fresh = malloc(sizeof(double) * n);
    facet_planarize_options plain = options(FACET_METHOD_LOCAL_GLOBAL, 5, 1), shaped = plain;
    shaped.shape = FACET_SHAPE_ASAP;
    shaped.shape_weight = 0.1;
    facet_planarize_result r;
    facet_error e;
    facet_planarizer *s = NULL, *other = NULL;
    CHECK(facet_planarizer_create(&t.mesh, &s, &e) == FACET_OK);
    CHECK(facet_planarizer_solve(s, t.xyz, &plain, reused, &r, &e) >= 0);
    CHECK(s->control_centroid == NULL);
    CHECK(facet_planarizer_solve(s, t.xyz, &shaped, reused, &r, &e) >= 0);
    CHECK(s->control_centroid != NULL);
    CHECK(facet_planarizer_create(&t.mesh, &other, &e) == FACET_OK);
    CHECK(facet_planarizer_solve(other, t.xyz, &shaped, fresh, &r, &e) >= 0);
    CHECK(r.iterations > 0);
    CHECK(memcmp(reused, fresh, sizeof(double) * n) == 0);
    facet_planarizer_free(&s);
    facet_planarizer_free(&other);
    free(reused), free(fresh);
    test_mesh_free(&t);
}

int main(void)
{
    test_sketch_length();
    test_shape_arrays_on_demand();
    test_previous_kept(FACET_METHOD_LOCAL_LOCAL, 5, SMALL);
    test_previous_kept(FACET_METHOD_LOCAL_GLOBAL, 5, SMALL);
    test_previous_kept(FACET_METHOD_LOCAL_GLOBAL, 1, SMALL);
    test_previous_kept(FACET_METHOD_LOCAL_LOCAL, 0, SMALL);
    test_previous_kept(FACET_METHOD_LOCAL_LOCAL, 5, SKETCHED);
    test_previous_kept(FACET_METHOD_LOCAL_LOCAL, 1, SKETCHED);
    const int depths[] = {1, 2, 5, 16};
    for (int k = 0; k < 4; ++k) {
        test_depths(FACET_METHOD_LOCAL_LOCAL, depths[k], SMALL);
        test_depths(FACET_METHOD_LOCAL_GLOBAL, depths[k], SMALL);
        test_depths(FACET_METHOD_LOCAL_LOCAL, depths[k], SKETCHED);
    }
    test_big_face(100, 0);
    test_big_face(300, 0);
    test_big_face(300, 1);
    return check_report("test_planarize_memory");
}
