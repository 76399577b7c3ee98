/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* The default thread count of a solve (facet.h, FACET_CORNERS_PER_THREAD):
 * one thread per 100,000 face corners, at least one and at most OpenMP's
 * default; a count asked for is used as given; a live update runs on its
 * region's count; the bits do not depend on it. */
#include "check.h"
#include "facet.h"
#include "test_meshes.h"

#include <omp.h>
#include <stdlib.h>
#include <string.h>

static int solve_threads(test_mesh *g, int32_t threads, int32_t iterations, double *out)
{
    facet_planarizer *s = NULL;
    facet_error err;
    CHECK_STATUS(facet_planarizer_create(&g->mesh, &s, &err), FACET_OK);
    facet_planarize_options o;
    facet_planarize_options_default(FACET_METHOD_AUTO, &o);
    o.threads = threads;
    o.iterations = iterations;
    facet_planarize_result r;
    memset(&r, 0, sizeof r);
    const facet_status status = facet_planarizer_solve(s, g->xyz, &o, out, &r, &err);
    CHECK(status == FACET_OK || status == FACET_WARNING_NOT_CONVERGED);
    facet_planarizer_free(&s);
    return r.threads;
}

int main(void)
{
    const int most = omp_get_max_threads();
    /* a small mesh: one thread by default, the count asked for otherwise */
    test_mesh small = test_grid(10, 10, 0.5, 1.0, 0.0);
    const size_t v3 = 3 * (size_t)small.mesh.n_vertices;
    double *a = malloc(sizeof(double) * v3), *b = malloc(sizeof(double) * v3);
    double *c = malloc(sizeof(double) * v3);
    CHECK(solve_threads(&small, 0, 0, a) == 1);
    CHECK(solve_threads(&small, 2, 0, b) == 2);
    CHECK(solve_threads(&small, 1, 0, c) == 1);
    CHECK(memcmp(a, b, sizeof(double) * v3) == 0 && memcmp(a, c, sizeof(double) * v3) == 0);
    free(a), free(b), free(c);
    test_mesh_free(&small);

    /* 250 x 250 quads, 250,000 corners: two threads where OpenMP offers two */
    test_mesh big = test_grid(250, 250, 0.5, 1.0, 0.0);
    const size_t n3 = 3 * (size_t)big.mesh.n_vertices;
    double *out = malloc(sizeof(double) * n3);
    CHECK(solve_threads(&big, 0, 2, out) == (most < 2 ? most : 2));
    CHECK(solve_threads(&big, 1, 2, out) == 1);

    /* a live update of one vertex runs on its region's count: one */
    facet_planarizer *s = NULL;
    facet_error err;
    CHECK_STATUS(facet_planarizer_create(&big.mesh, &s, &err), FACET_OK);
    facet_planarize_options o;
    facet_planarize_options_default(FACET_METHOD_LOCAL_LOCAL, &o);
    o.iterations = 2;
    facet_planarize_result r;
    CHECK(facet_planarizer_solve(s, big.xyz, &o, out, &r, &err) >= 0);
    double *control = malloc(sizeof(double) * n3);
    memcpy(control, big.xyz, sizeof(double) * n3);
    control[3 * 1000 + 2] += 0.01;
    o.iterations = 0;
    o.max_iter = 200;
    memset(&r, 0, sizeof r);
    CHECK(facet_planarizer_update(s, control, &o, 0, out, &r, &err) >= 0);
    CHECK(r.iterations > 0 && r.threads == 1);
    free(control), free(out);
    facet_planarizer_free(&s);
    test_mesh_free(&big);
    return check_report("test_planarize_threads");
}
