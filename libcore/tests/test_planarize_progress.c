/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Progress across the quality re-solves (planarize_quality.c; facet.h,
 * facet_progress_fn and facet_planarizer_stage): every progress call of a
 * solve that re-solves is recorded, and the calls must read as one solve:
 * the iteration counts on (1, 2, 3, ... up to result.iterations), max_iter
 * never grows and never falls below the iteration, it is the documented
 * bound when each stage starts, and facet_planarizer_stage names the
 * re-solve running. Cancelling a re-solve still returns the first result. */
#include "check.h"
#include "facet.h"
#include "test_meshes.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_CALLS = 40000 };

/* Every progress call: its arguments and what facet_planarizer_stage said. */
typedef struct {
    const facet_planarizer *s;
    int32_t n;
    int32_t iteration[MAX_CALLS], max_iter[MAX_CALLS], stage[MAX_CALLS], stages[MAX_CALLS];
    int32_t cancel_stage, cancel_after; /* cancel at this stage's cancel_after-th call (0: never) */
    int32_t in_stage;
} recorder;

static int record(void *user, int32_t iteration, int32_t max_iter, double planarity)
{
    recorder *r = user;
    (void)planarity;
    int32_t stages;
    const int32_t stage = facet_planarizer_stage(r->s, &stages);
    if (r->n < MAX_CALLS) {
        r->iteration[r->n] = iteration, r->max_iter[r->n] = max_iter;
        r->stage[r->n] = stage, r->stages[r->n] = stages;
    }
    ++r->n;
    if (r->cancel_after > 0 && stage == r->cancel_stage && ++r->in_stage >= r->cancel_after)
        return 1;
    return 0;
}

static recorder *recorder_new(const facet_planarizer *s)
{
    recorder *r = calloc(1, sizeof *r);
    r->s = s;
    return r;
}

/* An n x n hypar, its planarizer, an output array and the default options
 * recording every progress call. */
typedef struct {
    test_mesh g;
    facet_planarizer *s;
    double *out;
    facet_planarize_options o;
    recorder *rec;
} fixture;

static fixture fixture_new(int n)
{
    fixture x;
    facet_error err;
    x.g = test_hypar(n);
    x.s = NULL;
    CHECK_STATUS(facet_planarizer_create(&x.g.mesh, &x.s, &err), FACET_OK);
    x.out = malloc(sizeof(double) * 3 * (size_t)x.g.mesh.n_vertices);
    facet_planarize_options_default(FACET_METHOD_LOCAL_GLOBAL, &x.o);
    x.rec = recorder_new(x.s);
    x.o.progress = record, x.o.progress_user = x.rec;
    return x;
}

static void fixture_free(fixture *x)
{
    free(x->rec), free(x->out);
    facet_planarizer_free(&x->s);
    test_mesh_free(&x->g);
}

/* The re-solves' limits from stage k (1-based) on, as facet.h documents
 * them: four stages for point data (max_iter, max_iter, at least 4000,
 * max_iter), five for sliding data (at least 4000, then max_iter: the exact
 * path, the angle floor's recipe, and the last three held more firmly). */
static int32_t stages_of(int sliding)
{
    return sliding ? 5 : 4;
}

static int32_t limits_from(int32_t k, int sliding, int32_t max_iter)
{
    const int32_t exact = max_iter > 4000 ? max_iter : 4000;
    int32_t sum = 0;
    for (int32_t j = k; j <= stages_of(sliding); ++j) /* the exact path: the third, or the first */
        sum += j == (sliding ? 1 : 3) ? exact : max_iter;
    return sum;
}

/* What every recorded solve must show: one count from 1 to result.iterations,
 * a bound that never grows and never falls below it, the documented bound
 * at each stage start, stages in order. */
static void check_one_solve(const recorder *rec, const facet_planarize_result *r,
                            int32_t max_iter, int sliding)
{
    const int32_t stages = stages_of(sliding);
    CHECK(rec->n == r->iterations && rec->n <= MAX_CALLS);
    int monotone = 1, bounded = 1, counted = 1, ordered = 1, stages_same = 1, starts = 1;
    int32_t top_stage = 0;
    for (int32_t k = 0; k < rec->n && k < MAX_CALLS; ++k) {
        counted &= rec->iteration[k] == k + 1;
        bounded &= rec->max_iter[k] >= rec->iteration[k];
        stages_same &= rec->stages[k] == stages;
        if (k > 0) {
            monotone &= rec->max_iter[k] <= rec->max_iter[k - 1];
            /* the fraction shown by a bar never falls */
            monotone &= (double)rec->iteration[k] / rec->max_iter[k] >=
                        (double)rec->iteration[k - 1] / rec->max_iter[k - 1];
            ordered &= rec->stage[k] == rec->stage[k - 1] || rec->stage[k] == rec->stage[k - 1] + 1;
        }
        if (k == 0 || rec->stage[k] != rec->stage[k - 1]) {
            /* a stage starts: done so far plus the limits from here */
            const int32_t done = rec->iteration[k] - 1;
            const int32_t expect = rec->stage[k] == 0 ? max_iter + limits_from(1, sliding, max_iter)
                                                      : done + limits_from(rec->stage[k], sliding, max_iter);
            if (rec->max_iter[k] != expect) {
                printf("stage %d starts at iteration %d: max_iter %d, expected %d\n",
                       (int)rec->stage[k], (int)rec->iteration[k], (int)rec->max_iter[k], (int)expect);
                starts = 0;
            }
        }
        if (rec->stage[k] > top_stage)
            top_stage = rec->stage[k];
    }
    CHECK(counted);
    CHECK(bounded);
    CHECK(monotone);
    CHECK(ordered);
    CHECK(stages_same);
    CHECK(starts);
    CHECK(rec->n > 0 && rec->iteration[rec->n - 1] == r->iterations);
    CHECK(top_stage == r->quality_resolves);
    /* the first solve is stage 0 for exactly its iterations */
    CHECK(r->first_iterations > 0 && r->first_iterations < rec->n &&
          rec->stage[r->first_iterations - 1] == 0 && rec->stage[r->first_iterations] == 1);
    /* outside a solve: 0 and 0 */
    int32_t after = -1;
    CHECK(facet_planarizer_stage(rec->s, &after) == 0 && after == 0);
}

/* Point data, quality_angle 40 on an 8 x 8 hypar: no re-solve keeps every
 * corner above 40 degrees, so all four run (2,280 iterations when this was
 * written) and the first result stands. */
static void test_all_four_stages(void)
{
    fixture x = fixture_new(8);
    facet_planarizer *s = x.s;
    recorder *rec = x.rec;
    facet_error err;
    const size_t v3 = 3 * (size_t)x.g.mesh.n_vertices;
    double *plain = malloc(sizeof(double) * v3);
    facet_planarize_options o = x.o;
    o.quality_angle = 40.0;
    /* the same solve without a callback: the relay changes no bit */
    facet_planarize_options quiet = o;
    quiet.progress = NULL;
    facet_planarize_result r0, r;
    CHECK_STATUS(facet_planarizer_solve(s, x.g.xyz, &quiet, plain, &r0, &err), FACET_OK);
    CHECK_STATUS(facet_planarizer_solve(s, x.g.xyz, &o, x.out, &r, &err), FACET_OK);
    CHECK(r.quality_resolves == 4 && r.quality == FACET_QUALITY_NARROW);
    CHECK(r.iterations == r0.iterations && memcmp(x.out, plain, sizeof(double) * v3) == 0);
    printf("hypar 8, quality_angle 40: %d calls, first %d, max_iter %d -> %d\n", (int)rec->n,
           (int)r.first_iterations, (int)rec->max_iter[0], (int)rec->max_iter[rec->n - 1]);
    CHECK(rec->max_iter[0] == 8000); /* 1000 + 1000 + 1000 + 4000 + 1000 */
    check_one_solve(rec, &r, o.max_iter, 0);

    /* a smaller limit: the exact penalty path's 4000 stays */
    memset(rec, 0, sizeof *rec), rec->s = s;
    o.max_iter = 600;
    CHECK_STATUS(facet_planarizer_solve(s, x.g.xyz, &o, x.out, &r, &err), FACET_OK);
    CHECK(rec->max_iter[0] == 600 + 600 + 600 + 4000 + 600);
    if (r.quality_resolves > 0)
        check_one_solve(rec, &r, 600, 0);
    o.max_iter = 1000;

    /* cancelled at the third call of the second re-solve: the first
     * solve's result, the iterations counted up to the cancel */
    facet_planarize_options off = o;
    off.quality_angle = 0.0;
    off.progress = NULL;
    CHECK_STATUS(facet_planarizer_solve(s, x.g.xyz, &off, plain, &r0, &err), FACET_OK);
    memset(rec, 0, sizeof *rec), rec->s = s;
    rec->cancel_stage = 2, rec->cancel_after = 3;
    CHECK_STATUS(facet_planarizer_solve(s, x.g.xyz, &o, x.out, &r, &err), FACET_ERROR_CANCELLED);
    CHECK(memcmp(x.out, plain, sizeof(double) * v3) == 0);
    CHECK(r.quality_resolves == 2);
    CHECK(rec->n == r.iterations && rec->iteration[rec->n - 1] == r.iterations);
    CHECK(rec->stage[rec->n - 1] == 2 && rec->stage[rec->n - 4] == 1);
    int32_t stages = -1;
    CHECK(facet_planarizer_stage(s, &stages) == 0 && stages == 0);
    free(plain);
    fixture_free(&x);
}

/* Vertices sliding along the design (data_tangent 0.01): five stages (the
 * exact penalty path and the angle floor's recipe, then the default's
 * schedule and the angle floor's recipe with the vertices held three times
 * more firmly, and the latter ten times), numbered 1 to 5 of 5. No re-solve
 * reaches 40 degrees: the first result, with the options' own data_tangent,
 * is returned. */
static void test_sliding_stages(void)
{
    fixture x = fixture_new(8);
    facet_error err;
    x.o.quality_angle = 40.0;
    x.o.data_tangent = 0.01;
    facet_planarize_result r;
    CHECK_STATUS(facet_planarizer_solve(x.s, x.g.xyz, &x.o, x.out, &r, &err), FACET_OK);
    CHECK(r.quality_resolves == 5 && r.quality == FACET_QUALITY_NARROW);
    CHECK(r.data_tangent == 0.01);
    CHECK(x.rec->max_iter[0] == 1000 + 4000 + 1000 + 1000 + 1000 + 1000);
    check_one_solve(x.rec, &r, x.o.max_iter, 1);
    fixture_free(&x);
}

/* The default on the 32 x 32 hypar: the first solve closes corners, a
 * re-solve recovers (the third when this was written), and the stages
 * after it do not run: the bound falls to the total at the end. */
static void test_recovered_default(void)
{
    fixture x = fixture_new(32);
    facet_error err;
    facet_planarize_result r;
    CHECK_STATUS(facet_planarizer_solve(x.s, x.g.xyz, &x.o, x.out, &r, &err), FACET_OK);
    printf("hypar 32, default: %d iterations, %d re-solves, %s\n", (int)r.iterations,
           (int)r.quality_resolves, r.quality == FACET_QUALITY_RECOVERED ? "recovered" : "other");
    if (r.quality_resolves > 0) {
        check_one_solve(x.rec, &r, x.o.max_iter, 0);
    } else { /* the first solve kept its corners open (a change of schedule) */
        CHECK(x.rec->n == r.iterations && x.rec->max_iter[0] == 8000);
    }
    fixture_free(&x);
}

/* Solves that cannot re-solve report as before: their own limit, stage 0 of 0. */
static void test_no_resolve(void)
{
    test_mesh g = test_hypar(8);
    facet_planarizer *s = NULL;
    facet_error err;
    CHECK_STATUS(facet_planarizer_create(&g.mesh, &s, &err), FACET_OK);
    double *out = malloc(sizeof(double) * 3 * (size_t)g.mesh.n_vertices);
    CHECK(facet_planarizer_stage(NULL, NULL) == 0);
    int32_t stages = -1;
    CHECK(facet_planarizer_stage(s, &stages) == 0 && stages == 0);
    const struct {
        const char *what;
        double quality_angle, angle_floor;
        int32_t iterations, warm;
    } cases[] = {
        {"quality off", 0.0, 0.0, 0, 0},
        {"fixed count", 40.0, 0.0, 50, 0},
        {"angle floor", 40.0, 5.0, 0, 0},
        {"warm", 40.0, 0.0, 0, 1},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        facet_planarize_options o;
        facet_planarize_options_default(FACET_METHOD_LOCAL_GLOBAL, &o);
        o.quality_angle = cases[c].quality_angle;
        o.angle_floor = cases[c].angle_floor;
        o.iterations = cases[c].iterations;
        o.warm = cases[c].warm;
        recorder *rec = recorder_new(s);
        o.progress = record, o.progress_user = rec;
        facet_planarize_result r;
        const facet_status st = facet_planarizer_solve(s, g.xyz, &o, out, &r, &err);
        CHECK(st >= 0);
        const int32_t limit = o.iterations > 0 ? o.iterations : o.max_iter;
        int same = rec->n == r.iterations && rec->n > 0;
        for (int32_t k = 0; k < rec->n && k < MAX_CALLS; ++k)
            same &= rec->iteration[k] == k + 1 && rec->max_iter[k] == limit && rec->stage[k] == 0 &&
                    rec->stages[k] == 0;
        if (!same)
            printf("%s: %d calls, %d iterations\n", cases[c].what, (int)rec->n, (int)r.iterations);
        CHECK(same);
        CHECK(r.quality_resolves == 0);
        free(rec);
    }
    free(out);
    facet_planarizer_free(&s);
    test_mesh_free(&g);
}

int main(void)
{
    test_no_resolve();
    test_all_four_stages();
    test_sliding_stages();
    test_recovered_default();
    return check_report("test_planarize_progress");
}
