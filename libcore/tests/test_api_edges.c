/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Every public function of facet.h called with NULL for each pointer
 * argument, zero and negative sizes, out-of-range indices and enum values,
 * NaN and infinite coordinates and options. Each must answer with its status
 * (never crash, never write through NULL -- the sanitizer build and valgrind
 * see to that), fill the error record's message, leave the outputs untouched
 * on error, and never put a NaN or infinity into an output. The table in
 * docs/CONTRACTS.md ("Bad arguments") lists what each call returns. */
#include "check.h"
#include "facet.h"
#include "test_meshes.h"
#include "test_panel_output.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SENTINEL 12345.0

/* The call failed with the expected status and said why. */
#define CHECK_FAILS(expr, expected)                                                       \
    do {                                                                                  \
        memset(&e, 0, sizeof e);                                                          \
        CHECK_STATUS((expr), (expected));                                                 \
        CHECK(e.status == (expected));                                                    \
        CHECK(e.message[0] != '\0');                                                      \
    } while (0)

static facet_error e;

static void fill(double *x, size_t n)
{
    for (size_t i = 0; i < n; ++i)
        x[i] = SENTINEL;
}

static int untouched(const double *x, size_t n)
{
    for (size_t i = 0; i < n; ++i)
        if (x[i] != SENTINEL)
            return 0;
    return 1;
}

/* A 3 x 2 grid of quads (12 vertices, 6 faces), slightly non-planar. */
static test_mesh grid(void)
{
    return test_grid(3, 2, 0.3, 1.0, 0.0);
}

static void test_status_and_version(void)
{
    /* every listed code has its own text; an unknown code still gets a string */
#define X(name, value, text) CHECK(strcmp(facet_status_string(name), text) == 0);
    FACET_STATUS_LIST(X)
#undef X
    CHECK(facet_status_string((facet_status)-999) != NULL);
    CHECK(facet_status_string((facet_status)999) != NULL);
    CHECK(facet_status_string((facet_status)-999)[0] != '\0');
    CHECK(strcmp(facet_version(), "0.1.0") == 0);
}

static void test_validate(void)
{
    test_mesh t = grid();
    facet_mesh m = t.mesh;
    facet_mesh_report r;
    CHECK_STATUS(facet_mesh_validate(&m, NULL, NULL), FACET_OK); /* report and error may be NULL */
    CHECK_FAILS(facet_mesh_validate(NULL, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(facet_mesh_validate(NULL, NULL, NULL), FACET_ERROR_INVALID_ARGUMENT);
    facet_mesh b = m;
    b.xyz = NULL;
    CHECK_FAILS(facet_mesh_validate(&b, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    b = m, b.face_start = NULL;
    CHECK_FAILS(facet_mesh_validate(&b, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    b = m, b.face_vertices = NULL;
    CHECK_FAILS(facet_mesh_validate(&b, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    b = m, b.n_vertices = 0;
    CHECK_FAILS(facet_mesh_validate(&b, &r, &e), FACET_ERROR_EMPTY_MESH);
    b = m, b.n_faces = 0;
    CHECK_FAILS(facet_mesh_validate(&b, &r, &e), FACET_ERROR_EMPTY_MESH);
    b = m, b.n_vertices = -5;
    CHECK_FAILS(facet_mesh_validate(&b, &r, &e), FACET_ERROR_EMPTY_MESH);
    b = m, b.n_faces = INT32_MIN;
    CHECK_FAILS(facet_mesh_validate(&b, &r, &e), FACET_ERROR_EMPTY_MESH);
    /* too few vertices for the indices */
    b = m, b.n_vertices = 5;
    CHECK_FAILS(facet_mesh_validate(&b, &r, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    CHECK(e.face >= 0);
    t.face_vertices[6] = -1;
    CHECK_FAILS(facet_mesh_validate(&m, &r, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    CHECK(e.face == 1);
    t.face_vertices[6] = INT32_MAX;
    CHECK_FAILS(facet_mesh_validate(&m, &r, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    t.face_vertices[6] = t.face_vertices[5];
    CHECK_FAILS(facet_mesh_validate(&m, &r, &e), FACET_ERROR_REPEATED_VERTEX);
    t.face_vertices[6] = t.face_vertices[7];
    CHECK_FAILS(facet_mesh_validate(&m, &r, &e), FACET_ERROR_REPEATED_VERTEX);
    test_mesh_free(&t);

    t = grid();
    m = t.mesh;
    t.face_start[0] = 1;
    CHECK_FAILS(facet_mesh_validate(&m, &r, &e), FACET_ERROR_BAD_FACE_START);
    t.face_start[0] = 0;
    t.face_start[2] = 3; /* decreasing */
    CHECK_FAILS(facet_mesh_validate(&m, &r, &e), FACET_ERROR_BAD_FACE_START);
    t.face_start[2] = 4; /* face 1 now empty */
    t.face_start[1] = 4;
    CHECK_FAILS(facet_mesh_validate(&m, &r, &e), FACET_ERROR_DEGENERATE_FACE);
    t.face_start[1] = 4, t.face_start[2] = 8;
    CHECK_STATUS(facet_mesh_validate(&m, &r, &e), FACET_OK);
    const double bad[] = {NAN, INFINITY, -INFINITY};
    for (int k = 0; k < 3; ++k) {
        t.xyz[3 * 7 + 1] = bad[k];
        CHECK_FAILS(facet_mesh_validate(&m, &r, &e), FACET_ERROR_NONFINITE);
        CHECK(e.vertex == 7);
        t.xyz[3 * 7 + 1] = 1.0;
    }
    test_mesh_free(&t);
}

static void test_planarity_api(void)
{
    test_mesh t = grid();
    facet_mesh m = t.mesh;
    const int nf = m.n_faces;
    double a[6], b[6], c[6], d[6];
    CHECK_STATUS(facet_planarity(&m, 0, NULL, NULL, NULL, NULL, NULL), FACET_OK);
    CHECK_FAILS(facet_planarity(NULL, 0, a, b, c, d, &e), FACET_ERROR_INVALID_ARGUMENT);
    facet_mesh bm = m;
    bm.xyz = NULL;
    CHECK_FAILS(facet_planarity(&bm, 0, a, b, c, d, &e), FACET_ERROR_INVALID_ARGUMENT);
    bm = m, bm.n_faces = 0;
    CHECK_FAILS(facet_planarity(&bm, 0, a, b, c, d, &e), FACET_ERROR_EMPTY_MESH);
    bm = m, bm.n_vertices = 3;
    fill(a, 6);
    CHECK_FAILS(facet_planarity(&bm, 0, a, b, c, d, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    CHECK(untouched(a, 6));
    t.xyz[5] = NAN;
    CHECK_FAILS(facet_planarity(&m, 0, a, b, c, d, &e), FACET_ERROR_NONFINITE);
    CHECK(untouched(a, 6));
    t.xyz[5] = INFINITY;
    CHECK_FAILS(facet_planarity(&m, 0, a, b, c, d, &e), FACET_ERROR_NONFINITE);
    t.xyz[5] = 0.0;
    for (int threads = -3; threads <= 3; threads += 3) {
        CHECK_STATUS(facet_planarity(&m, threads, a, b, c, d, &e), FACET_OK);
        CHECK(all_finite(a, nf) && all_finite(b, nf) && all_finite(c, nf) && all_finite(d, nf));
    }
    test_mesh_free(&t);

    /* facet_fit_plane: n < 3 and NULL give -1 and write nothing */
    const double p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    double n[3] = {SENTINEL, SENTINEL, SENTINEL}, off = SENTINEL;
    CHECK(facet_fit_plane(2, p, n, &off) == -1.0);
    CHECK(facet_fit_plane(0, p, n, &off) == -1.0);
    CHECK(facet_fit_plane(-7, p, n, &off) == -1.0);
    CHECK(facet_fit_plane(3, NULL, n, &off) == -1.0);
    CHECK(untouched(n, 3) && off == SENTINEL);
    CHECK(facet_fit_plane(3, p, NULL, &off) == -1.0);
    CHECK(facet_fit_plane(3, p, n, NULL) >= 0.0); /* offset may be NULL */
    CHECK(fabs(fabs(n[2]) - 1.0) < 1e-15);
    /* all three points the same, and collinear: a finite unit normal */
    const double same[9] = {1e7, 1e7, 5, 1e7, 1e7, 5, 1e7, 1e7, 5};
    const double line[9] = {0, 0, 0, 1, 1, 1, 2, 2, 2};
    CHECK(facet_fit_plane(3, same, n, &off) >= 0.0);
    CHECK(all_finite(n, 3) && isfinite(off) && fabs(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0) < 1e-12);
    CHECK(facet_fit_plane(3, line, n, &off) >= 0.0);
    CHECK(all_finite(n, 3) && isfinite(off) && fabs(n[0] + n[1] + n[2]) < 1e-12);
    /* NaN in: the function has no status; it must not claim a good fit */
    const double nan_pts[9] = {0, 0, 0, 1, 0, NAN, 0, 1, 0};
    const double lambda = facet_fit_plane(3, nan_pts, n, &off);
    CHECK(lambda == -1.0 || isnan(lambda));
}

static void test_planarizer_api(void)
{
    test_mesh t = grid();
    facet_mesh m = t.mesh;
    const int nv = m.n_vertices, nf = m.n_faces;
    facet_planarizer *p = (facet_planarizer *)&e; /* must be overwritten or cleared */
    CHECK_FAILS(facet_planarizer_create(&m, NULL, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_planarizer_create(NULL, &p, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK(p == NULL);
    facet_mesh bm = m;
    bm.n_faces = -1;
    CHECK_FAILS(facet_planarizer_create(&bm, &p, &e), FACET_ERROR_EMPTY_MESH);
    bm = m, bm.n_vertices = 4;
    CHECK_FAILS(facet_planarizer_create(&bm, &p, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    CHECK(p == NULL);
    bm = m, bm.xyz = NULL; /* coordinates are not needed to create */
    CHECK_STATUS(facet_planarizer_create(&bm, &p, NULL), FACET_OK);
    CHECK(p != NULL);

    /* free: NULL and a NULL handle are fine; the pointer is cleared */
    facet_planarizer_free(NULL);
    facet_planarizer *none = NULL;
    facet_planarizer_free(&none);
    CHECK(strcmp(facet_planarizer_message(NULL), "") == 0);
    CHECK(strcmp(facet_planarizer_message(p), "") == 0);

    facet_planarize_options o;
    facet_planarize_options_default(FACET_METHOD_LOCAL_GLOBAL, &o);
    facet_planarize_options_default(FACET_METHOD_LOCAL_LOCAL, NULL); /* no crash */
    double *out = malloc(sizeof(double) * 3 * nv);
    facet_planarize_result res;
    fill(out, 3 * nv);
    facet_planarize_options_default((facet_method)77, &o); /* unknown: refused by the solve */
    CHECK_FAILS(facet_planarizer_solve(p, t.xyz, &o, out, &res, &e), FACET_ERROR_INVALID_ARGUMENT);
    facet_planarize_options_default(FACET_METHOD_LOCAL_GLOBAL, &o);
    o.max_iter = 30;
    CHECK_FAILS(facet_planarizer_solve(NULL, t.xyz, &o, out, &res, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_planarizer_solve(p, NULL, &o, out, &res, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_planarizer_solve(p, t.xyz, NULL, out, &res, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_planarizer_solve(p, t.xyz, &o, NULL, &res, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK(untouched(out, 3 * nv));

    /* every option out of range, NaN and infinite */
    struct {
        const char *name;
        double *field;
        double bad[4];
    } doubles[] = {
        {"mu0", &o.mu0, {0.0, -1.0, 1.5, NAN}},
        {"ratio", &o.ratio, {0.0, -0.5, 2.0, NAN}},
        {"mu_min", &o.mu_min, {0.0, -1e-9, 2.0, NAN}},
        {"tol_abs", &o.tol_abs, {-1.0, INFINITY, NAN, -INFINITY}},
        {"tol_rel", &o.tol_rel, {-1.0, INFINITY, NAN, -INFINITY}},
        {"data_tangent", &o.data_tangent, {0.0, -1.0, INFINITY, NAN}},
        {"data_normal", &o.data_normal, {-1.0, INFINITY, NAN, -INFINITY}},
        {"surface_weight", &o.surface_weight, {-1.0, INFINITY, NAN, 1.0 /* no reference */}},
        {"laplacian", &o.laplacian, {-1.0, INFINITY, NAN, -INFINITY}},
        {"normal_laplacian", &o.normal_laplacian, {-1.0, INFINITY, NAN, -INFINITY}},
        {"boundary_fairness", &o.boundary_fairness, {-1.0, INFINITY, NAN, -INFINITY}},
        {"shape_weight", &o.shape_weight, {-1.0, INFINITY, NAN, -INFINITY}},
        {"circular", &o.circular, {-1.0, INFINITY, NAN, -INFINITY}},
        {"parallelogram", &o.parallelogram, {-1.0, INFINITY, NAN, -INFINITY}},
        {"hold_tol", &o.hold_tol, {-1.0, INFINITY, NAN, -INFINITY}},
        {"time_budget", &o.time_budget, {-1.0, INFINITY, NAN, -INFINITY}},
    };
    for (int method = 0; method < 2; ++method)
        for (size_t i = 0; i < sizeof doubles / sizeof doubles[0]; ++i)
            for (int k = 0; k < 4; ++k) {
                facet_planarize_options_default((facet_method)method, &o);
                /* the field pointers point into o */
                const double saved = *doubles[i].field;
                *doubles[i].field = doubles[i].bad[k];
                CHECK_FAILS(facet_planarizer_solve(p, t.xyz, &o, out, &res, &e),
                            FACET_ERROR_INVALID_ARGUMENT);
                if (e.status != FACET_ERROR_INVALID_ARGUMENT)
                    fprintf(stderr, "  option %s = %g accepted\n", doubles[i].name, doubles[i].bad[k]);
                CHECK(strcmp(facet_planarizer_message(p), "") != 0);
                *doubles[i].field = saved;
            }
    CHECK(untouched(out, 3 * nv));
    struct {
        int32_t *field;
        int32_t bad;
    } ints[] = {{(int32_t *)&o.method, 3},    {(int32_t *)&o.method, -1},
                {&o.max_iter, -1},            {&o.iterations, -1},
                {(int32_t *)&o.laplacian_weights, 9}, {(int32_t *)&o.shape, 3},
                {(int32_t *)&o.shape, -1},     {(int32_t *)&o.boundary, 3},
                {&o.hold_max, 0},             {&o.hold_max, -4},
                {&o.anderson, -1},            {&o.anderson, 17}};
    for (size_t i = 0; i < sizeof ints / sizeof ints[0]; ++i) {
        facet_planarize_options_default(FACET_METHOD_LOCAL_GLOBAL, &o);
        *ints[i].field = ints[i].bad;
        CHECK_FAILS(facet_planarizer_solve(p, t.xyz, &o, out, &res, &e), FACET_ERROR_INVALID_ARGUMENT);
    }
    CHECK(untouched(out, 3 * nv));

    /* non-finite control points: named, output untouched */
    facet_planarize_options_default(FACET_METHOD_LOCAL_GLOBAL, &o);
    o.max_iter = 30;
    const double bad[] = {NAN, INFINITY, -INFINITY};
    for (int k = 0; k < 3; ++k) {
        t.xyz[3 * 9 + 2] = bad[k];
        CHECK_FAILS(facet_planarizer_solve(p, t.xyz, &o, out, &res, &e), FACET_ERROR_NONFINITE);
        CHECK(e.vertex == 9);
    }
    CHECK(untouched(out, 3 * nv));
    t.xyz[3 * 9 + 2] = 0.1;

    /* zero iterations allowed: max_iter 0 gives the input back */
    o.max_iter = 0;
    CHECK(facet_planarizer_solve(p, t.xyz, &o, out, &res, &e) >= 0);
    CHECK(all_finite(out, 3 * nv));
    o.max_iter = 30;
    /* threads: any value */
    o.threads = -100;
    CHECK(facet_planarizer_solve(p, t.xyz, &o, out, NULL, NULL) >= 0); /* result may be NULL */
    CHECK(all_finite(out, 3 * nv));
    o.threads = 1000;
    CHECK(facet_planarizer_solve(p, t.xyz, &o, out, &res, &e) >= 0);
    CHECK(all_finite(out, 3 * nv));

    /* every vertex at one point: refused, output untouched */
    double *same = malloc(sizeof(double) * 3 * nv);
    for (int v = 0; v < 3 * nv; ++v)
        same[v] = 1e7;
    fill(out, 3 * nv);
    CHECK_FAILS(facet_planarizer_solve(p, same, &o, out, &res, &e), FACET_ERROR_DEGENERATE_FACE);
    CHECK(untouched(out, 3 * nv));
    free(same);

    /* finite coordinates beyond FACET_COORDINATE_MAX (their edge lengths
     * would overflow): refused, the vertex named */
    double *huge = malloc(sizeof(double) * 3 * nv);
    memcpy(huge, t.xyz, sizeof(double) * 3 * nv);
    huge[0] = -1.5e308, huge[3] = 1.5e308;
    fill(out, 3 * nv);
    CHECK_FAILS(facet_planarizer_solve(p, huge, &o, out, &res, &e), FACET_ERROR_COORDINATE_RANGE);
    CHECK(e.vertex == 0);
    CHECK(untouched(out, 3 * nv));
    free(huge);

    /* set_fixed */
    int32_t fixed[3] = {0, 5, 11};
    CHECK_FAILS(facet_planarizer_set_fixed(NULL, 3, fixed, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_planarizer_set_fixed(p, 3, NULL, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_planarizer_set_fixed(p, -1, fixed, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(facet_planarizer_set_fixed(p, 0, NULL, &e), FACET_OK);
    fixed[1] = nv;
    CHECK_FAILS(facet_planarizer_set_fixed(p, 3, fixed, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    fixed[1] = -1;
    CHECK_FAILS(facet_planarizer_set_fixed(p, 3, fixed, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    fixed[1] = INT32_MIN;
    CHECK_FAILS(facet_planarizer_set_fixed(p, 3, fixed, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    fixed[1] = 5;
    CHECK_STATUS(facet_planarizer_set_fixed(p, 3, fixed, &e), FACET_OK);
    /* every vertex fixed: nothing can move; finite, and the input back */
    int32_t *allv = malloc(sizeof(int32_t) * nv);
    for (int v = 0; v < nv; ++v)
        allv[v] = v;
    CHECK_STATUS(facet_planarizer_set_fixed(p, nv, allv, &e), FACET_OK);
    for (int method = 0; method < 2; ++method) {
        facet_planarize_options_default((facet_method)method, &o);
        o.max_iter = 20;
        facet_status s = facet_planarizer_solve(p, t.xyz, &o, out, &res, &e);
        CHECK(s == FACET_OK || s == FACET_WARNING_NOT_CONVERGED);
        CHECK(all_finite(out, 3 * nv));
        CHECK(memcmp(out, t.xyz, sizeof(double) * 3 * nv) == 0);
        CHECK(isfinite(res.planarity_max_abs) && isfinite(res.planarity_max_rel));
    }
    free(allv);
    CHECK_STATUS(facet_planarizer_set_fixed(p, 0, NULL, &e), FACET_OK);

    /* face weights */
    double w[6] = {1, 1, 1, 1, 1, 1};
    CHECK_FAILS(facet_planarizer_set_face_weights(NULL, w, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(facet_planarizer_set_face_weights(p, NULL, &e), FACET_OK);
    const double badw[] = {-1.0, NAN, INFINITY, -INFINITY};
    for (int k = 0; k < 4; ++k) {
        w[3] = badw[k];
        CHECK_FAILS(facet_planarizer_set_face_weights(p, w, &e), FACET_ERROR_INVALID_ARGUMENT);
        CHECK(e.face == 3);
    }
    /* every face exempt: planarity counts nothing, output finite */
    for (int f = 0; f < nf; ++f)
        w[f] = 0.0;
    CHECK_STATUS(facet_planarizer_set_face_weights(p, w, &e), FACET_OK);
    for (int method = 0; method < 2; ++method) {
        facet_planarize_options_default((facet_method)method, &o);
        o.max_iter = 20;
        CHECK(facet_planarizer_solve(p, t.xyz, &o, out, &res, &e) >= 0);
        CHECK(all_finite(out, 3 * nv));
    }
    CHECK_STATUS(facet_planarizer_set_face_weights(p, NULL, &e), FACET_OK);

    /* reference */
    CHECK_FAILS(facet_planarizer_set_reference(NULL, NULL, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(facet_planarizer_set_reference(p, NULL, &e), FACET_OK);

    /* NULL error record everywhere */
    CHECK_STATUS(facet_planarizer_solve(NULL, NULL, NULL, NULL, NULL, NULL),
                 FACET_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(facet_planarizer_set_fixed(NULL, 0, NULL, NULL), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(facet_planarizer_set_face_weights(NULL, NULL, NULL), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(facet_planarizer_set_reference(NULL, NULL, NULL), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(facet_planarizer_create(NULL, NULL, NULL), FACET_ERROR_INVALID_ARGUMENT);

    facet_planarizer_free(&p);
    CHECK(p == NULL);
    free(out);
    test_mesh_free(&t);
}

static void test_surface_api(void)
{
    const double xyz[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const int32_t tri[6] = {0, 1, 2, 0, 2, 3};
    facet_surface *s = (facet_surface *)&e;
    CHECK_FAILS(facet_surface_create(4, xyz, 2, tri, NULL, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_surface_create(4, NULL, 2, tri, &s, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK(s == NULL);
    CHECK_FAILS(facet_surface_create(4, xyz, 2, NULL, &s, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_surface_create(0, xyz, 2, tri, &s, &e), FACET_ERROR_EMPTY_MESH);
    CHECK_FAILS(facet_surface_create(4, xyz, 0, tri, &s, &e), FACET_ERROR_EMPTY_MESH);
    CHECK_FAILS(facet_surface_create(-4, xyz, 2, tri, &s, &e), FACET_ERROR_EMPTY_MESH);
    CHECK_FAILS(facet_surface_create(4, xyz, -2, tri, &s, &e), FACET_ERROR_EMPTY_MESH);
    CHECK_FAILS(facet_surface_create(3, xyz, 2, tri, &s, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    const int32_t neg[6] = {0, 1, 2, 0, -2, 3};
    CHECK_FAILS(facet_surface_create(4, xyz, 2, neg, &s, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    CHECK(e.face == 1);
    double nanxyz[12];
    memcpy(nanxyz, xyz, sizeof nanxyz);
    nanxyz[7] = NAN;
    CHECK_FAILS(facet_surface_create(4, nanxyz, 2, tri, &s, &e), FACET_ERROR_NONFINITE);
    CHECK(e.vertex == 2);
    nanxyz[7] = -INFINITY;
    CHECK_FAILS(facet_surface_create(4, nanxyz, 2, tri, &s, &e), FACET_ERROR_NONFINITE);
    /* finite coordinates whose extent overflows: beyond FACET_COORDINATE_MAX, refused */
    double wide[12];
    memcpy(wide, xyz, sizeof wide);
    wide[0] = -1.5e308, wide[3] = 1.5e308;
    CHECK_FAILS(facet_surface_create(4, wide, 2, tri, &s, &e), FACET_ERROR_COORDINATE_RANGE);
    CHECK(s == NULL);
    /* all triangles at one point: allowed, zero area, finite answers */
    const double point[12] = {1e7, 2e7, 3, 1e7, 2e7, 3, 1e7, 2e7, 3, 1e7, 2e7, 3};
    CHECK_STATUS(facet_surface_create(4, point, 2, tri, &s, &e), FACET_OK);
    {
        const double q[6] = {1e7 + 1, 2e7, 3, -5, 0, 0};
        double c[6], d[2], n[6];
        int32_t t[2];
        CHECK_STATUS(facet_surface_closest(s, 2, q, 0, c, d, t, n, &e), FACET_OK);
        CHECK(all_finite(c, 6) && all_finite(d, 2) && all_finite(n, 6));
        CHECK(t[0] >= 0 && t[0] < 2 && t[1] >= 0 && t[1] < 2);
        CHECK_NEAR(d[0], 1.0, 1e-8);
    }
    facet_surface_free(&s);
    CHECK(s == NULL);
    facet_surface_free(&s);
    facet_surface_free(NULL);

    CHECK_STATUS(facet_surface_create(4, xyz, 2, tri, &s, NULL), FACET_OK);
    CHECK(facet_surface_triangle_count(NULL) == 0);
    CHECK(facet_surface_triangle_count(s) == 2);
    CHECK(facet_surface_face(NULL, 0) == -1);
    CHECK(facet_surface_face(s, 0) == -1); /* made from triangles */
    CHECK(facet_surface_face(s, -1) == -1);
    CHECK(facet_surface_face(s, 2) == -1);
    CHECK(facet_surface_face(s, INT32_MAX) == -1);

    double q[6] = {0.2, 0.3, 1, 5, 5, 5}, c[6], d[2], n[6];
    int32_t t[2] = {-7, -7};
    fill(c, 6);
    CHECK_FAILS(facet_surface_closest(NULL, 2, q, 0, c, d, t, n, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_surface_closest(s, -1, q, 0, c, d, t, n, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_surface_closest(s, 2, NULL, 0, c, d, t, n, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(facet_surface_closest(s, 0, NULL, 0, c, d, t, n, &e), FACET_OK);
    q[4] = NAN;
    CHECK_FAILS(facet_surface_closest(s, 2, q, 0, c, d, t, n, &e), FACET_ERROR_NONFINITE);
    CHECK(e.vertex == 1);
    q[4] = INFINITY;
    CHECK_FAILS(facet_surface_closest(s, 2, q, 0, c, d, t, n, &e), FACET_ERROR_NONFINITE);
    CHECK(untouched(c, 6) && t[0] == -7);
    q[4] = 5;
    /* every output may be NULL; any thread count */
    CHECK_STATUS(facet_surface_closest(s, 2, q, -3, NULL, NULL, NULL, NULL, NULL), FACET_OK);
    CHECK_STATUS(facet_surface_closest(s, 2, q, 64, c, d, t, n, &e), FACET_OK);
    CHECK(all_finite(c, 6) && all_finite(d, 2) && all_finite(n, 6));
    CHECK_NEAR(d[0], 1.0, 1e-14);
    /* far away query points up to FACET_COORDINATE_MAX: the closest point is
     * still a point of the surface and the distance finite */
    const double far[] = {1e7, -1e12, 1e20, -1e25, 3e29, -0.999 * FACET_COORDINATE_MAX};
    for (size_t k = 0; k < sizeof far / sizeof far[0]; ++k) {
        const double fq[3] = {0.5, far[k], 0.25 * far[k]};
        double fc[3], fd, fn[3];
        int32_t ft = -1;
        CHECK_STATUS(facet_surface_closest(s, 1, fq, 1, fc, &fd, &ft, fn, &e), FACET_OK);
        CHECK(ft == 0 || ft == 1);
        CHECK(all_finite(fc, 3) && all_finite(fn, 3));
        CHECK(!isnan(fd) && fd > 0.0);
        CHECK(fc[0] >= 0.0 && fc[0] <= 1.0 && fc[1] >= 0.0 && fc[1] <= 1.0 && fc[2] == 0.0);
        const double y = far[k] > 0.0 ? 1.0 : 0.0; /* the nearest edge of the square */
        const double expect = hypot(far[k] - y, 0.25 * far[k]);
        CHECK(fabs(fd - expect) <= 1e-12 * expect);
        /* along the nearest edge every point is as close to rounding: any x */
        CHECK_NEAR(fc[1], y, 1e-12);
        if (ft < 0)
            fprintf(stderr, "  query at %g found no triangle\n", far[k]);
    }
    /* beyond it: refused, the query named, outputs untouched */
    {
        const double fq[6] = {0.5, 0.5, 0.0, 0.5, 1e100, 0.0};
        double fc[6], fd[2], fn[6];
        int32_t ft[2] = {-7, -7};
        fill(fc, 6);
        CHECK_FAILS(facet_surface_closest(s, 2, fq, 1, fc, fd, ft, fn, &e),
                    FACET_ERROR_COORDINATE_RANGE);
        CHECK(e.vertex == 1);
        CHECK(untouched(fc, 6) && ft[0] == -7);
    }
    facet_surface_free(&s);

    /* from a mesh */
    test_mesh g = grid();
    facet_mesh m = g.mesh;
    CHECK_FAILS(facet_surface_create_from_mesh(&m, NULL, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_surface_create_from_mesh(NULL, &s, &e), FACET_ERROR_INVALID_ARGUMENT);
    facet_mesh bm = m;
    bm.xyz = NULL;
    CHECK_FAILS(facet_surface_create_from_mesh(&bm, &s, &e), FACET_ERROR_INVALID_ARGUMENT);
    bm = m, bm.n_vertices = 0;
    CHECK_FAILS(facet_surface_create_from_mesh(&bm, &s, &e), FACET_ERROR_EMPTY_MESH);
    bm = m, bm.n_vertices = 6;
    CHECK_FAILS(facet_surface_create_from_mesh(&bm, &s, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    g.face_start[1] = 2, g.face_start[2] = 2; /* faces with 2 and 0 vertices */
    CHECK_FAILS(facet_surface_create_from_mesh(&m, &s, &e), FACET_ERROR_DEGENERATE_FACE);
    g.face_start[1] = 4, g.face_start[2] = 8;
    g.xyz[0] = NAN;
    CHECK_FAILS(facet_surface_create_from_mesh(&m, &s, &e), FACET_ERROR_NONFINITE);
    CHECK(s == NULL);
    g.xyz[0] = 0.0;
    CHECK_STATUS(facet_surface_create_from_mesh(&m, &s, &e), FACET_OK);
    CHECK(facet_surface_triangle_count(s) == 12);
    CHECK(facet_surface_face(s, 11) == 5);
    CHECK(facet_surface_face(s, 12) == -1);
    facet_surface_free(&s);
    test_mesh_free(&g);
}

static void test_face_shape_api(void)
{
    test_mesh t = grid();
    facet_mesh m = t.mesh;
    double a[6], b[6], c[6];
    CHECK_STATUS(facet_face_shape(&m, NULL, 0, NULL, NULL, NULL, NULL), FACET_OK);
    CHECK_FAILS(facet_face_shape(NULL, NULL, 0, a, b, c, &e), FACET_ERROR_INVALID_ARGUMENT);
    facet_mesh bm = m;
    bm.xyz = NULL;
    CHECK_FAILS(facet_face_shape(&bm, NULL, 0, a, b, c, &e), FACET_ERROR_INVALID_ARGUMENT);
    bm = m, bm.n_faces = 0;
    CHECK_FAILS(facet_face_shape(&bm, NULL, 0, a, b, c, &e), FACET_ERROR_EMPTY_MESH);
    bm = m, bm.n_vertices = 2;
    fill(a, 6);
    CHECK_FAILS(facet_face_shape(&bm, NULL, 0, a, b, c, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    CHECK(untouched(a, 6));
    t.xyz[4] = NAN;
    CHECK_FAILS(facet_face_shape(&m, NULL, 0, a, b, c, &e), FACET_ERROR_NONFINITE);
    CHECK(untouched(a, 6));
    t.xyz[4] = 0.0;
    double *input = malloc(sizeof(double) * 3 * m.n_vertices);
    memcpy(input, t.xyz, sizeof(double) * 3 * m.n_vertices);
    input[10] = -INFINITY;
    CHECK_FAILS(facet_face_shape(&m, input, 0, a, b, c, &e), FACET_ERROR_NONFINITE);
    CHECK(untouched(a, 6));
    /* zero-length edges in the input and the output: finite */
    for (int k = 0; k < 3 * m.n_vertices; ++k)
        input[k] = 7.0;
    CHECK_STATUS(facet_face_shape(&m, input, -1, a, b, c, &e), FACET_OK);
    CHECK(all_finite(a, 6) && all_finite(b, 6) && all_finite(c, 6));
    facet_mesh collapsed = m;
    collapsed.xyz = input;
    CHECK_STATUS(facet_face_shape(&collapsed, t.xyz, 99, a, b, c, &e), FACET_OK);
    CHECK(all_finite(a, 6) && all_finite(b, 6) && all_finite(c, 6));
    free(input);
    test_mesh_free(&t);
}

static void test_cleanup_api(void)
{
    test_mesh t = grid();
    facet_mesh m = t.mesh;
    const int nv = m.n_vertices, nf = m.n_faces, nc = m.face_start[nf];
    facet_cleanup_options o = {0.1, 1};
    double *xyz = malloc(sizeof(double) * 3 * nv);
    int32_t *start = malloc(sizeof(int32_t) * (nf + 1)), *fv = malloc(sizeof(int32_t) * nc);
    int32_t *map = malloc(sizeof(int32_t) * nv), *col = malloc(sizeof(int32_t) * 2 * nv);
    int32_t *rem = malloc(sizeof(int32_t) * nf);
    facet_cleanup_result r;
    fill(xyz, 3 * nv);
    CHECK_FAILS(facet_cleanup(NULL, &o, xyz, start, fv, map, col, rem, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_cleanup(&m, NULL, xyz, start, fv, map, col, rem, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_cleanup(&m, &o, NULL, start, fv, map, col, rem, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_cleanup(&m, &o, xyz, NULL, fv, map, col, rem, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_cleanup(&m, &o, xyz, start, NULL, map, col, rem, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_cleanup(&m, &o, xyz, start, fv, map, col, rem, NULL, &e), FACET_ERROR_INVALID_ARGUMENT);
    const double bad[] = {0.0, -1.0, NAN, INFINITY};
    for (int k = 0; k < 4; ++k) {
        o.min_edge = bad[k];
        CHECK_FAILS(facet_cleanup(&m, &o, xyz, start, fv, map, col, rem, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    }
    o.min_edge = 0.1;
    facet_mesh bm = m;
    bm.n_faces = 0;
    CHECK_FAILS(facet_cleanup(&bm, &o, xyz, start, fv, map, col, rem, &r, &e), FACET_ERROR_EMPTY_MESH);
    bm = m, bm.xyz = NULL;
    CHECK_FAILS(facet_cleanup(&bm, &o, xyz, start, fv, map, col, rem, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    bm = m, bm.n_vertices = 3;
    CHECK_FAILS(facet_cleanup(&bm, &o, xyz, start, fv, map, col, rem, &r, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    t.xyz[8] = NAN;
    CHECK_FAILS(facet_cleanup(&m, &o, xyz, start, fv, map, col, rem, &r, &e), FACET_ERROR_NONFINITE);
    t.xyz[8] = 0.0;
    CHECK(untouched(xyz, 3 * nv));
    /* optional outputs NULL; a threshold that keeps everything */
    CHECK_STATUS(facet_cleanup(&m, &o, xyz, start, fv, NULL, NULL, NULL, &r, NULL), FACET_OK);
    CHECK(r.n_collapsed == 0 && r.n_vertices == nv && r.n_faces == nf);
    CHECK(all_finite(xyz, 3 * (size_t)r.n_vertices));
    /* a threshold larger than the mesh: everything would go, outputs untouched */
    o.min_edge = 1e300;
    o.relative = 0;
    fill(xyz, 3 * nv);
    facet_status s = facet_cleanup(&m, &o, xyz, start, fv, map, col, rem, &r, &e);
    CHECK(s == FACET_ERROR_NOTHING_LEFT || s == FACET_WARNING_COLLAPSE_SKIPPED || s == FACET_OK);
    if (s < 0)
        CHECK(untouched(xyz, 3 * nv));
    else
        CHECK(all_finite(xyz, 3 * (size_t)r.n_vertices));
    o.min_edge = 1e300;
    o.relative = 1; /* 1e300 times the mean edge: overflows to infinity unless guarded */
    s = facet_cleanup(&m, &o, xyz, start, fv, map, col, rem, &r, &e);
    CHECK(s == FACET_ERROR_NOTHING_LEFT || s == FACET_WARNING_COLLAPSE_SKIPPED ||
          s == FACET_ERROR_INVALID_ARGUMENT || s == FACET_OK);
    if (s >= 0)
        CHECK(all_finite(xyz, 3 * (size_t)r.n_vertices) && isfinite(r.threshold));
    free(xyz), free(start), free(fv), free(map), free(col), free(rem);
    test_mesh_free(&t);
}

static void test_lifter_api(void)
{
    test_mesh t = test_grid(3, 3, 0.0, 1.0, 0.0);
    facet_mesh m = t.mesh;
    const int nv = m.n_vertices;
    facet_lifter *l = (facet_lifter *)&e;
    CHECK_FAILS(facet_lifter_create(&m, NULL, NULL, NULL, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_lifter_create(NULL, NULL, NULL, &l, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK(l == NULL);
    facet_mesh bm = m;
    bm.xyz = NULL;
    CHECK_FAILS(facet_lifter_create(&bm, NULL, NULL, &l, &e), FACET_ERROR_INVALID_ARGUMENT);
    bm = m, bm.n_faces = 0;
    CHECK_FAILS(facet_lifter_create(&bm, NULL, NULL, &l, &e), FACET_ERROR_EMPTY_MESH);
    bm = m, bm.n_vertices = 7;
    CHECK_FAILS(facet_lifter_create(&bm, NULL, NULL, &l, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    t.xyz[3 * 4] = NAN;
    CHECK_FAILS(facet_lifter_create(&m, NULL, NULL, &l, &e), FACET_ERROR_NONFINITE);
    CHECK(e.vertex == 4);
    t.xyz[3 * 4] = 1.0;
    t.xyz[3 * 4 + 2] = NAN; /* z is ignored */
    double *w = malloc(sizeof(double) * nv);
    for (int v = 0; v < nv; ++v)
        w[v] = 1.0;
    const double badw[] = {0.0, -1.0, NAN, INFINITY};
    for (int k = 0; k < 4; ++k) {
        w[5] = badw[k];
        CHECK_FAILS(facet_lifter_create(&m, w, NULL, &l, &e), FACET_ERROR_BAD_WEIGHT);
        CHECK(e.vertex == 5);
    }
    w[5] = 1.0;
    /* rank_tol: NaN, negative, infinite, huge: treated as documented, no crash */
    const double tols[] = {NAN, -1.0, INFINITY, 1e300, 0.0};
    for (int k = 0; k < 5; ++k) {
        facet_lift_options lo = {tols[k], NULL, NULL};
        facet_status s = facet_lifter_create(&m, w, &lo, &l, &e);
        CHECK(s >= 0 || s == FACET_ERROR_INVALID_ARGUMENT);
        if (s >= 0) {
            CHECK(facet_lifter_dimension(l) >= 3);
            double *z = malloc(sizeof(double) * nv);
            CHECK(facet_lifter_solve(l, w, z, NULL, NULL) >= 0);
            CHECK(all_finite(z, nv));
            free(z);
        } else {
            CHECK(l == NULL);
        }
        facet_lifter_free(&l);
    }
    CHECK_STATUS(facet_lifter_create(&m, NULL, NULL, &l, NULL), FACET_OK);
    CHECK(facet_lifter_dimension(NULL) == 0);
    CHECK(facet_lifter_dimension(l) == 4 + 2 * 2 + 1 || facet_lifter_dimension(l) >= 3);
    CHECK(facet_lifter_factor_seconds(NULL) == 0.0);
    CHECK(facet_lifter_factor_seconds(l) >= 0.0);
    CHECK(strcmp(facet_lifter_message(NULL), "") == 0);

    double *z = malloc(sizeof(double) * nv), *tg = malloc(sizeof(double) * nv);
    for (int v = 0; v < nv; ++v)
        tg[v] = sin(v);
    fill(z, nv);
    facet_lift_result r;
    CHECK_FAILS(facet_lifter_solve(NULL, tg, z, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_lifter_solve(l, NULL, z, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_lifter_solve(l, tg, NULL, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    const double bad[] = {NAN, INFINITY, -INFINITY};
    for (int k = 0; k < 3; ++k) {
        tg[3] = bad[k];
        CHECK_FAILS(facet_lifter_solve(l, tg, z, &r, &e), FACET_ERROR_BAD_TARGET);
        CHECK(e.vertex == 3);
        CHECK(strcmp(facet_lifter_message(l), "") != 0);
    }
    CHECK(untouched(z, nv));
    tg[3] = 0.5;
    CHECK(facet_lifter_solve(l, tg, z, NULL, NULL) >= 0);
    CHECK(all_finite(z, nv));
    /* in place */
    memcpy(z, tg, sizeof(double) * nv);
    CHECK(facet_lifter_solve(l, z, z, &r, &e) >= 0);
    CHECK(all_finite(z, nv));

    fill(z, nv);
    CHECK_FAILS(facet_lifter_fundamental(NULL, 0, z, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_lifter_fundamental(l, 0, NULL, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_lifter_fundamental(l, -1, z, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    CHECK_FAILS(facet_lifter_fundamental(l, nv, z, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    CHECK_FAILS(facet_lifter_fundamental(l, INT32_MIN, z, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    CHECK(untouched(z, nv));
    CHECK(facet_lifter_fundamental(l, nv - 1, z, NULL) >= 0);
    CHECK(all_finite(z, nv));

    const int d = facet_lifter_dimension(l);
    double *basis = malloc(sizeof(double) * nv * d), values[64];
    fill(basis, (size_t)nv * d);
    CHECK_FAILS(facet_lifter_basis(NULL, FACET_BASIS_ORTHONORMAL, 1, basis, values, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_lifter_basis(l, FACET_BASIS_ORTHONORMAL, 1, NULL, values, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_lifter_basis(l, (facet_basis_kind)2, 1, basis, values, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_lifter_basis(l, (facet_basis_kind)-1, 1, basis, values, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_lifter_basis(l, FACET_BASIS_EIGEN, -1, basis, values, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_lifter_basis(l, FACET_BASIS_EIGEN, d + 1, basis, values, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK(untouched(basis, (size_t)nv * d));
    CHECK_STATUS(facet_lifter_basis(l, FACET_BASIS_EIGEN, 0, NULL, NULL, &e), FACET_OK);
    for (int kind = 0; kind < 2; ++kind) {
        CHECK_STATUS(facet_lifter_basis(l, (facet_basis_kind)kind, d, basis, NULL, NULL), FACET_OK);
        CHECK(all_finite(basis, (size_t)nv * d));
        CHECK_STATUS(facet_lifter_basis(l, (facet_basis_kind)kind, d, basis, values, &e), FACET_OK);
        CHECK(all_finite(values, d));
    }
    facet_lifter_free(&l);
    CHECK(l == NULL);
    facet_lifter_free(&l);
    facet_lifter_free(NULL);
    free(basis), free(z), free(tg), free(w);
    test_mesh_free(&t);
}

static void test_panels_api(void)
{
    /* a planar 3 x 2 grid */
    test_mesh t = test_grid(3, 2, 0.0, 1.0, 0.0);
    facet_mesh m = t.mesh;
    const int nf = m.n_faces, nc = m.face_start[nf], nv = m.n_vertices;
    facet_panel_options o;
    facet_panel_options_default(NULL); /* no crash */
    facet_panel_options_default(&o);
    facet_panel_output out = test_panel_output(nv, nf, nc);
    facet_panel_output none;
    memset(&none, 0, sizeof none);
    facet_panel_result r;
    fill(out.top, 3 * nc);
    CHECK_FAILS(facet_panels(NULL, &o, &out, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_panels(&m, NULL, &out, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK_FAILS(facet_panels(&m, &o, NULL, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    facet_mesh bm = m;
    bm.xyz = NULL;
    CHECK_FAILS(facet_panels(&bm, &o, &out, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    bm = m, bm.face_vertices = NULL;
    CHECK_FAILS(facet_panels(&bm, &o, &out, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    bm = m, bm.n_faces = 0;
    CHECK_FAILS(facet_panels(&bm, &o, &out, &r, &e), FACET_ERROR_EMPTY_MESH);
    bm = m, bm.n_vertices = 4;
    CHECK_FAILS(facet_panels(&bm, &o, &out, &r, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    CHECK(untouched(out.top, 3 * nc));
    struct {
        double *field;
        double bad[4];
    } doubles[] = {{&o.thickness, {0.0, -1.0, NAN, INFINITY}},
                   {&o.gap, {-1.0, NAN, INFINITY, -INFINITY}},
                   {&o.planarity_tol_abs, {-1.0, NAN, INFINITY, -INFINITY}},
                   {&o.planarity_tol_rel, {-1.0, NAN, INFINITY, -INFINITY}}};
    for (size_t i = 0; i < 4; ++i)
        for (int k = 0; k < 4; ++k) {
            facet_panel_options_default(&o);
            *doubles[i].field = doubles[i].bad[k];
            CHECK_FAILS(facet_panels(&m, &o, &out, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
        }
    facet_panel_options_default(&o);
    o.offset = (facet_panel_offset)3;
    CHECK_FAILS(facet_panels(&m, &o, &out, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    o.offset = (facet_panel_offset)-1;
    CHECK_FAILS(facet_panels(&m, &o, &out, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    facet_panel_options_default(&o);
    o.edge = (facet_panel_edge)2;
    CHECK_FAILS(facet_panels(&m, &o, &out, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK(untouched(out.top, 3 * nc));
    facet_panel_options_default(&o);
    /* non-finite coordinates */
    t.xyz[3 * 6 + 2] = NAN;
    CHECK_FAILS(facet_panels(&m, &o, &out, &r, &e), FACET_ERROR_NONFINITE);
    t.xyz[3 * 6 + 2] = 0.0;
    /* faces with fewer than 3 vertices, repeated vertices */
    t.face_start[1] = 2;
    CHECK(facet_panels(&m, &o, &out, &r, &e) < 0);
    CHECK(e.message[0] != '\0');
    t.face_start[1] = 4;
    const int32_t saved = t.face_vertices[5];
    t.face_vertices[5] = t.face_vertices[4];
    CHECK(facet_panels(&m, &o, &out, &r, &e) < 0);
    CHECK(e.message[0] != '\0');
    t.face_vertices[5] = saved;
    /* finite coordinates whose extent overflows: beyond FACET_COORDINATE_MAX, refused */
    const double x0 = t.xyz[0], x3 = t.xyz[3];
    t.xyz[0] = -1.5e308, t.xyz[3] = 1.5e308;
    CHECK_FAILS(facet_panels(&m, &o, &out, &r, &e), FACET_ERROR_COORDINATE_RANGE);
    t.xyz[0] = x0, t.xyz[3] = x3;
    /* every output NULL, result NULL, error NULL */
    CHECK_STATUS(facet_panels(&m, &o, &none, NULL, NULL), FACET_OK);
    /* all outputs, both edge kinds, all offsets */
    for (int edge = 0; edge < 2; ++edge)
        for (int off = 0; off < 3; ++off) {
            o.edge = (facet_panel_edge)edge, o.offset = (facet_panel_offset)off;
            CHECK_STATUS(facet_panels(&m, &o, &out, &r, &e), FACET_OK);
            CHECK(test_panel_output_finite(&out, nv, nf, nc));
        }
    /* a gap wider than the panels: refused with a status, not garbage */
    facet_panel_options_default(&o);
    o.gap = 5.0;
    CHECK(facet_panels(&m, &o, &out, &r, &e) == FACET_ERROR_PANEL_GEOMETRY);
    CHECK(e.message[0] != '\0');
    test_panel_output_free(&out);
    test_mesh_free(&t);
}

int main(void)
{
    test_status_and_version();
    test_validate();
    test_planarity_api();
    test_planarizer_api();
    test_surface_api();
    test_face_shape_api();
    test_cleanup_api();
    test_lifter_api();
    test_panels_api();
    return check_report("test_api_edges");
}
