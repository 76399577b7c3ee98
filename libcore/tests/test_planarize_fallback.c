/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Method AUTO's fallback on L/G (facet.h, FACET_STAGE_FALLBACK;
 * planarize_quality.c, fallback_lg): above 10,000 quads AUTO solves by L/L,
 * whose local steps let the vertices of nearly coplanar faces drift; on a
 * flat grid with a saddle in its middle L/L stalls above the tolerance or
 * leaves a panel closed after its quality re-solves, and AUTO then returns
 * L/G's result, planar with every corner open. On a smooth grid of the same
 * size nothing falls back; cancelling the fallback gives L/L's result. */
#include "check.h"
#include "facet.h"
#include "test_meshes.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    facet_planarizer *s;
    int fallback_calls, other_after; /* calls in the fallback; calls of other stages after it */
    int cancel;                      /* cancel at the fallback's first call */
} recorder;

static int record(void *user, int32_t iteration, int32_t max_iter, double planarity)
{
    (void)iteration, (void)max_iter, (void)planarity;
    recorder *rec = user;
    if (facet_planarizer_stage(rec->s, NULL) == FACET_STAGE_FALLBACK) {
        rec->fallback_calls++;
        return rec->cancel;
    }
    rec->other_after += rec->fallback_calls > 0;
    return 0;
}

/* The smallest corner angle of the mesh at xyz, degrees (facet_face_shape,
 * as the quality check measures it). */
static double smallest_angle(const test_mesh *g, const double *xyz)
{
    facet_mesh at = g->mesh;
    at.xyz = xyz;
    double *angle = malloc(sizeof(double) * (size_t)g->mesh.n_faces);
    facet_error err;
    CHECK_STATUS(facet_face_shape(&at, NULL, 1, angle, NULL, NULL, &err), FACET_OK);
    double least = 2.0 * M_PI;
    for (int32_t f = 0; f < g->mesh.n_faces; ++f)
        least = angle[f] < least ? angle[f] : least;
    free(angle);
    return least * 180.0 / M_PI;
}

/* AUTO on the saddle: L/L's own result (explicit method) is not planar or
 * has a corner under 5 degrees; AUTO's is L/G's, planar, every corner open,
 * and the fallback's calls come last. */
static void test_saddle_falls_back(double radius, double amplitude, int ll_stalls)
{
    test_mesh g = test_saddle(101, radius, amplitude);
    const size_t v3 = 3 * (size_t)g.mesh.n_vertices;
    facet_planarizer *s = NULL;
    facet_error err;
    CHECK_STATUS(facet_planarizer_create(&g.mesh, &s, &err), FACET_OK);
    double *out = malloc(sizeof(double) * v3), *ll = malloc(sizeof(double) * v3);
    facet_planarize_options o;
    facet_planarize_options_default(FACET_METHOD_LOCAL_LOCAL, &o);
    o.threads = 1;
    facet_planarize_result r_ll, r;
    const facet_status ll_status = facet_planarizer_solve(s, g.xyz, &o, ll, &r_ll, &err);
    if (ll_stalls)
        CHECK(ll_status == FACET_WARNING_NOT_CONVERGED && r_ll.stop_reason == FACET_STOP_STAGNATION);
    else
        CHECK(ll_status == FACET_OK && r_ll.quality == FACET_QUALITY_NARROW && smallest_angle(&g, ll) < 5.0);
    CHECK(facet_planarizer_choose_method(s, NULL) == FACET_METHOD_LOCAL_LOCAL);

    recorder rec = {s, 0, 0, 0};
    facet_planarize_options_default(FACET_METHOD_AUTO, &o);
    o.threads = 1;
    o.progress = record, o.progress_user = &rec;
    CHECK_STATUS(facet_planarizer_solve(s, g.xyz, &o, out, &r, &err), FACET_OK);
    CHECK(r.method == FACET_METHOD_LOCAL_GLOBAL);
    CHECK(r.stop_reason == FACET_STOP_TOLERANCE && r.planarity_max_rel <= 1e-6);
    CHECK(r.quality == FACET_QUALITY_RECOVERED && r.narrow_corners == 0);
    CHECK(smallest_angle(&g, out) > 5.0);
    CHECK(rec.fallback_calls > 0 && rec.other_after == 0);
    CHECK(r.iterations > rec.fallback_calls);
    /* the handle's last result is the one returned: a warm start that stops
     * at once gives it back */
    o.warm = 1, o.progress = NULL, o.max_iter = 0;
    facet_planarize_result r_warm;
    CHECK(facet_planarizer_solve(s, g.xyz, &o, ll, &r_warm, &err) >= 0);
    CHECK(r_warm.iterations == 0 && memcmp(ll, out, sizeof(double) * v3) == 0);

    /* cancelled as the fallback starts: L/L's result (the explicit solve's
     * bits: the same options but the method's floor) and the status */
    rec = (recorder){s, 0, 0, 1};
    facet_planarize_options_default(FACET_METHOD_AUTO, &o);
    o.threads = 1;
    o.progress = record, o.progress_user = &rec;
    CHECK_STATUS(facet_planarizer_solve(s, g.xyz, &o, out, &r, &err), FACET_ERROR_CANCELLED);
    CHECK(rec.fallback_calls == 1);
    CHECK(r.method == FACET_METHOD_LOCAL_LOCAL);
    for (size_t k = 0; k < v3; ++k)
        if (!isfinite(out[k])) {
            CHECK(!"a cancelled fallback left a non-finite coordinate");
            break;
        }
    free(out), free(ll);
    facet_planarizer_free(&s);
    test_mesh_free(&g);
}

/* A smooth grid of the same size: L/L's result stands, no fallback. */
static void test_no_fallback(void)
{
    test_mesh g = test_grid(101, 101, 0.3, 1.0, 0.0);
    const size_t v3 = 3 * (size_t)g.mesh.n_vertices;
    facet_planarizer *s = NULL;
    facet_error err;
    CHECK_STATUS(facet_planarizer_create(&g.mesh, &s, &err), FACET_OK);
    double *out = malloc(sizeof(double) * v3);
    recorder rec = {s, 0, 0, 0};
    facet_planarize_options o;
    facet_planarize_options_default(FACET_METHOD_AUTO, &o);
    o.threads = 1;
    o.progress = record, o.progress_user = &rec;
    facet_planarize_result r;
    CHECK_STATUS(facet_planarizer_solve(s, g.xyz, &o, out, &r, &err), FACET_OK);
    CHECK(r.method == FACET_METHOD_LOCAL_LOCAL && r.planarity_max_rel <= 1e-6);
    CHECK(r.quality == FACET_QUALITY_OK || r.quality == FACET_QUALITY_RECOVERED);
    CHECK(rec.fallback_calls == 0);
    free(out);
    facet_planarizer_free(&s);
    test_mesh_free(&g);
}

int main(void)
{
    test_saddle_falls_back(8.0, 0.4, 1);   /* L/L stalls at 2e-5 */
    test_saddle_falls_back(10.0, 0.15, 0); /* L/L's re-solves leave corners closed */
    test_no_fallback();
    return check_report("test_planarize_fallback");
}
