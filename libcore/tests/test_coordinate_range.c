/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Coordinates beyond FACET_COORDINATE_MAX are refused, naming the vertex,
 * by every entry point that takes coordinates (fuzzing found squared
 * distances overflowing to infinity at 1e300); 1e30 itself and
 * georeferenced coordinates are accepted. */
#include "check.h"
#include "test_meshes.h"

#include <string.h>

int main(void)
{
    test_mesh t = test_grid(3, 3, 0.1, 1.0, 0.0);
    facet_error e;
    CHECK_STATUS(facet_mesh_validate(&t.mesh, NULL, &e), FACET_OK);

    t.xyz[3 * 5 + 1] = 1e300;
    CHECK_STATUS(facet_mesh_validate(&t.mesh, NULL, &e), FACET_ERROR_COORDINATE_RANGE);
    CHECK(e.vertex == 5);
    CHECK(strstr(e.message, "vertex 5") != NULL);
    CHECK(strcmp(facet_status_string(FACET_ERROR_COORDINATE_RANGE), "coordinate beyond 1e30 in magnitude") == 0);

    facet_surface *s = NULL;
    CHECK_STATUS(facet_surface_create_from_mesh(&t.mesh, &s, &e), FACET_ERROR_COORDINATE_RANGE);
    CHECK(s == NULL);
    int32_t tri[3] = {0, 5, 1};
    CHECK_STATUS(facet_surface_create(t.mesh.n_vertices, t.xyz, 1, tri, &s, &e), FACET_ERROR_COORDINATE_RANGE);

    facet_panel_options po;
    facet_panel_options_default(&po);
    CHECK_STATUS(facet_panels(&t.mesh, &po, &(facet_panel_output){0}, NULL, &e), FACET_ERROR_COORDINATE_RANGE);

    facet_lifter *l = NULL;
    CHECK_STATUS(facet_lifter_create(&t.mesh, NULL, NULL, &l, &e), FACET_ERROR_COORDINATE_RANGE);
    CHECK(l == NULL && e.vertex == 5);

    /* exactly the limit, and negative: accepted; just beyond: refused */
    t.xyz[3 * 5 + 1] = -FACET_COORDINATE_MAX;
    CHECK(facet_mesh_validate(&t.mesh, NULL, &e) >= 0);
    t.xyz[3 * 5 + 1] = -1.0000001e30;
    CHECK_STATUS(facet_mesh_validate(&t.mesh, NULL, &e), FACET_ERROR_COORDINATE_RANGE);
    test_mesh_free(&t);

    /* georeferenced: fine everywhere; the planarizer's control positions and
     * the surface's queries and the lift's targets are checked too */
    t = test_grid(3, 3, 0.1, 1000.0, 6.5e6);
    CHECK(facet_mesh_validate(&t.mesh, NULL, &e) >= 0);
    CHECK_STATUS(facet_surface_create_from_mesh(&t.mesh, &s, &e), FACET_OK);
    double q[3] = {6.5e6, 6.5e6, 1e31}, c[3];
    CHECK_STATUS(facet_surface_closest(s, 1, q, 1, c, NULL, NULL, NULL, &e), FACET_ERROR_COORDINATE_RANGE);
    q[2] = 1e3;
    CHECK_STATUS(facet_surface_closest(s, 1, q, 1, c, NULL, NULL, NULL, &e), FACET_OK);
    facet_surface_free(&s);

    facet_planarizer *p = NULL;
    CHECK_STATUS(facet_planarizer_create(&t.mesh, &p, &e), FACET_OK);
    const int32_t nv = t.mesh.n_vertices;
    double *in = malloc(sizeof(double) * 3 * (size_t)nv), *out = malloc(sizeof(double) * 3 * (size_t)nv);
    memcpy(in, t.xyz, sizeof(double) * 3 * (size_t)nv);
    memcpy(out, t.xyz, sizeof(double) * 3 * (size_t)nv);
    in[3 * 7] = 2e30;
    facet_planarize_options o;
    facet_planarize_options_default(FACET_METHOD_LOCAL_GLOBAL, &o);
    o.max_iter = 2;
    CHECK_STATUS(facet_planarizer_solve(p, in, &o, out, NULL, &e), FACET_ERROR_COORDINATE_RANGE);
    CHECK(e.vertex == 7);
    CHECK(memcmp(out, t.xyz, sizeof(double) * 3 * (size_t)nv) == 0); /* untouched */
    facet_planarizer_free(&p);

    /* a flat plan: lifting towards a target beyond the limit */
    test_mesh plan = test_grid(2, 2, 0.0, 1.0, 0.0);
    CHECK_STATUS(facet_lifter_create(&plan.mesh, NULL, NULL, &l, &e), FACET_OK);
    double z[9] = {0, 0, 0, 0, 1e300, 0, 0, 0, 0}, h[9];
    CHECK_STATUS(facet_lifter_solve(l, z, h, NULL, &e), FACET_ERROR_BAD_TARGET);
    CHECK(e.vertex == 4);
    z[4] = 1.0;
    CHECK(facet_lifter_solve(l, z, h, NULL, &e) >= 0);
    facet_lifter_free(&l);
    /* a denormal weight among ordinary ones: refused by name (it used to
     * normalise to 0 and make the fundamental lifting NaN) */
    double w[9] = {1, 1, 1, 1, 4.9406564584124654e-324, 1, 1, 1, 1};
    CHECK_STATUS(facet_lifter_create(&plan.mesh, w, NULL, &l, &e), FACET_ERROR_BAD_WEIGHT);
    CHECK(l == NULL && e.vertex == 4);
    w[4] = 1e-90;
    CHECK_STATUS(facet_lifter_create(&plan.mesh, w, NULL, &l, &e), FACET_OK);
    CHECK_STATUS(facet_lifter_fundamental(l, 4, h, &e), FACET_OK);
    for (int v = 0; v < 9; ++v)
        CHECK(isfinite(h[v]));
    facet_lifter_free(&l);
    for (int v = 0; v < 9; ++v)
        w[v] = 1.7e308; /* the sum would overflow */
    CHECK_STATUS(facet_lifter_create(&plan.mesh, w, NULL, &l, &e), FACET_OK);
    CHECK(facet_lifter_solve(l, z, h, NULL, &e) >= 0);
    for (int v = 0; v < 9; ++v)
        CHECK(isfinite(h[v]));
    facet_lifter_free(&l);
    test_mesh_free(&plan);
    free(in);
    free(out);
    test_mesh_free(&t);
    return check_report("test_coordinate_range");
}
