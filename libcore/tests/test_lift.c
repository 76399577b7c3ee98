/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Optimal liftings: dimensions with known answers, optimality, planarity,
 * errors. */
#include "check.h"
#include "facet.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    int32_t nv, nf;
    double *xyz;
    int32_t *start, *faces;
} plan_t;

static void plan_free(plan_t *p)
{
    free(p->xyz), free(p->start), free(p->faces);
}

static facet_mesh plan_mesh(const plan_t *p)
{
    facet_mesh m = {p->nv, p->nf, p->xyz, p->start, p->faces};
    return m;
}

/* nx x ny vertex grid of quads (or triangles when tri), spacing 1, with an
 * optional wobble of the interior vertices (breaks straight grid lines). */
static plan_t grid(int nx, int ny, int tri, double wobble, double offset)
{
    plan_t p;
    p.nv = nx * ny;
    p.nf = (nx - 1) * (ny - 1) * (tri ? 2 : 1);
    p.xyz = calloc(3 * (size_t)p.nv, sizeof(double));
    p.start = malloc(sizeof(int32_t) * (size_t)(p.nf + 1));
    p.faces = malloc(sizeof(int32_t) * 4 * (size_t)p.nf);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            int v = j * nx + i;
            int interior = i > 0 && j > 0 && i < nx - 1 && j < ny - 1;
            p.xyz[3 * v] = offset + i + (interior ? wobble * sin(7.1 * v) : 0.0);
            p.xyz[3 * v + 1] = offset + j + (interior ? wobble * cos(3.3 * v) : 0.0);
            p.xyz[3 * v + 2] = 99.0; /* ignored */
        }
    int f = 0, c = 0;
    p.start[0] = 0;
    for (int j = 0; j + 1 < ny; ++j)
        for (int i = 0; i + 1 < nx; ++i) {
            int a = j * nx + i, b = a + 1, d = a + nx, e = d + 1;
            if (tri) {
                p.faces[c++] = a, p.faces[c++] = b, p.faces[c++] = e;
                p.start[++f] = c;
                p.faces[c++] = a, p.faces[c++] = e, p.faces[c++] = d;
                p.start[++f] = c;
            } else {
                p.faces[c++] = a, p.faces[c++] = b, p.faces[c++] = e, p.faces[c++] = d;
                p.start[++f] = c;
            }
        }
    return p;
}

/* Triangle in triangle joined by three quads; the inner triangle is the
 * outer one scaled by 0.4 about the centroid (the joining lines meet there)
 * and then turned by angle. */
static plan_t nested_triangles(double angle)
{
    plan_t p;
    p.nv = 6, p.nf = 4;
    p.xyz = calloc(18, sizeof(double));
    p.start = malloc(sizeof(int32_t) * 5);
    p.faces = malloc(sizeof(int32_t) * 15);
    double outer[3][2] = {{0, 0}, {4, 0}, {1, 3}};
    double cx = 5.0 / 3, cy = 1.0;
    for (int i = 0; i < 3; ++i) {
        p.xyz[3 * i] = outer[i][0], p.xyz[3 * i + 1] = outer[i][1];
        double dx = 0.4 * (outer[i][0] - cx), dy = 0.4 * (outer[i][1] - cy);
        p.xyz[3 * (i + 3)] = cx + cos(angle) * dx - sin(angle) * dy;
        p.xyz[3 * (i + 3) + 1] = cy + sin(angle) * dx + cos(angle) * dy;
    }
    int32_t faces[] = {3, 4, 5, 0, 1, 4, 3, 1, 2, 5, 4, 2, 0, 3, 5};
    int32_t start[] = {0, 3, 7, 11, 15};
    memcpy(p.faces, faces, sizeof faces);
    memcpy(p.start, start, sizeof start);
    return p;
}

static double max_abs_diff(int32_t n, const double *a, const double *b)
{
    double m = 0;
    for (int32_t i = 0; i < n; ++i)
        m = fmax(m, fabs(a[i] - b[i]));
    return m;
}

static void test_triangulated(void)
{
    plan_t p = grid(6, 5, 1, 0.2, 0.0);
    facet_mesh m = plan_mesh(&p);
    facet_lifter *l = NULL;
    facet_error e;
    CHECK_STATUS(facet_lifter_create(&m, NULL, NULL, &l, &e), FACET_OK);
    CHECK(facet_lifter_dimension(l) == p.nv);
    double *t = malloc(sizeof(double) * p.nv), *z = malloc(sizeof(double) * p.nv);
    for (int v = 0; v < p.nv; ++v)
        t[v] = sin(v * 1.7) * 3.0;
    facet_lift_result r;
    CHECK_STATUS(facet_lifter_solve(l, t, z, &r, &e), FACET_OK);
    CHECK(max_abs_diff(p.nv, t, z) < 1e-12);
    CHECK(r.dimension == p.nv && r.trivial_dimension == 3);
    facet_lifter_free(&l);
    CHECK(l == NULL);
    free(t), free(z);
    plan_free(&p);
}

static void test_nested_triangles(void)
{
    plan_t p = nested_triangles(0.0);
    facet_mesh m = plan_mesh(&p);
    facet_lifter *l = NULL;
    facet_error e;
    CHECK_STATUS(facet_lifter_create(&m, NULL, NULL, &l, &e), FACET_OK);
    CHECK(facet_lifter_dimension(l) == 4);
    double t[6] = {0, 0, 0, 1, 1, 1}, z[6];
    facet_lift_result r;
    CHECK_STATUS(facet_lifter_solve(l, t, z, &r, &e), FACET_OK);
    CHECK(r.planarity_max_rel < 1e-12);
    CHECK(r.target_max < 1e-12); /* a frustum: exactly liftable */
    facet_lifter_free(&l);
    plan_free(&p);

    p = nested_triangles(0.3);
    m = plan_mesh(&p);
    CHECK_STATUS(facet_lifter_create(&m, NULL, NULL, &l, &e), FACET_OK);
    CHECK(facet_lifter_dimension(l) == 3);
    CHECK_STATUS(facet_lifter_solve(l, t, z, &r, &e), FACET_WARNING_TRIVIAL_LIFTING);
    CHECK(strstr(e.message, "trivial") != NULL);
    CHECK(r.planarity_max_rel < 1e-12);
    /* The best-fitting plane of these targets (symmetric about the
     * centroid) is flat at their mean. */
    for (int v = 0; v < 6; ++v)
        CHECK_NEAR(z[v], 0.5, 1e-12);
    facet_lifter_free(&l);
    plan_free(&p);
}

/* Nearly liftable: the inner triangle turned by a hair. Turned by 1e-13
 * the constraint is dependent within the rank tolerance (dimension 4, faces
 * planar to rounding); by 1e-6 or 1e-9 it is independent, only the plane
 * remains, and the ill-conditioned projection must still be exact (1e-9 is
 * beyond the semi-normal equations: the orthogonal Q takes over). */
static void test_nearly_liftable(void)
{
    const double angles[] = {1e-13, 1e-9, 1e-6};
    const int32_t dims[] = {4, 3, 3};
    for (int k = 0; k < 3; ++k) {
        plan_t p = nested_triangles(angles[k]);
        facet_mesh m = plan_mesh(&p);
        facet_lifter *l = NULL;
        facet_error e;
        CHECK_STATUS(facet_lifter_create(&m, NULL, NULL, &l, &e), FACET_OK);
        CHECK(facet_lifter_dimension(l) == dims[k]);
        double t[6] = {0, 0, 0, 1, 1, 1}, z[6];
        facet_lift_result r;
        facet_status st = facet_lifter_solve(l, t, z, &r, &e);
        CHECK(st == (dims[k] == 3 ? FACET_WARNING_TRIVIAL_LIFTING : FACET_OK));
        CHECK(r.planarity_max_rel < 1e-9);
        if (dims[k] == 3)
            for (int v = 0; v < 6; ++v)
                CHECK_NEAR(z[v], 0.5, 1e-9);
        else
            CHECK(r.target_max < 1e-9);
        facet_lifter_free(&l);
        plan_free(&p);
    }
}

/* Two plans side by side as one (disconnected) plan. */
static plan_t combine(const plan_t *a, const plan_t *b, double shift)
{
    plan_t p;
    p.nv = a->nv + b->nv, p.nf = a->nf + b->nf;
    p.xyz = malloc(sizeof(double) * 3 * (size_t)p.nv);
    p.start = malloc(sizeof(int32_t) * (size_t)(p.nf + 1));
    p.faces = malloc(sizeof(int32_t) * (size_t)(a->start[a->nf] + b->start[b->nf]));
    memcpy(p.xyz, a->xyz, sizeof(double) * 3 * (size_t)a->nv);
    for (int v = 0; v < b->nv; ++v) {
        p.xyz[3 * (a->nv + v)] = b->xyz[3 * v] + shift;
        p.xyz[3 * (a->nv + v) + 1] = b->xyz[3 * v + 1];
        p.xyz[3 * (a->nv + v) + 2] = b->xyz[3 * v + 2];
    }
    memcpy(p.start, a->start, sizeof(int32_t) * (size_t)(a->nf + 1));
    memcpy(p.faces, a->faces, sizeof(int32_t) * (size_t)a->start[a->nf]);
    for (int f = 1; f <= b->nf; ++f)
        p.start[a->nf + f] = a->start[a->nf] + b->start[f];
    for (int c = 0; c < b->start[b->nf]; ++c)
        p.faces[a->start[a->nf] + c] = b->faces[c] + a->nv;
    return p;
}

/* A lifting space larger than the affine one in which one constraint is
 * independent only by sigma (the inner triangle turned by about that). The
 * optimum itself then moves by about 1e-16 / sigma under rounding of the
 * plan, so that is the accuracy asked for. At 1e-9 the semi-normal
 * equations cannot resolve it and the projection falls back on Q. Planarity
 * must be exact in both cases. */
static void ill_conditioned_projection(double angle, double accuracy)
{
    plan_t a = nested_triangles(angle), b = grid(4, 4, 0, 0.0, 0.0);
    plan_t p = combine(&a, &b, 10.0);
    facet_mesh m = plan_mesh(&p);
    facet_lifter *l = NULL;
    facet_error e;
    CHECK_STATUS(facet_lifter_create(&m, NULL, NULL, &l, &e), FACET_OK);
    /* Each part lifts on its own: 3 (affine triangles part) + 4 + 4 - 1. */
    CHECK(facet_lifter_dimension(l) == 3 + 7);
    double *t = calloc((size_t)p.nv, sizeof(double)), *z = malloc(sizeof(double) * p.nv);
    for (int v = 3; v < 6; ++v)
        t[v] = 1.0;
    for (int v = 6; v < p.nv; ++v)
        t[v] = sin(1.3 * v);
    facet_lift_result r;
    CHECK_STATUS(facet_lifter_solve(l, t, z, &r, &e), FACET_OK);
    CHECK(r.planarity_max_rel < 1e-9);
    for (int v = 0; v < 6; ++v) /* the triangles' part: its own best plane */
        CHECK_NEAR(z[v], 0.5, accuracy);
    /* The grid part: any height on a straight grid's lines f(x) + g(y) is
     * reachable, and the residual is orthogonal to every lifting. */
    double *basis = malloc(sizeof(double) * (size_t)p.nv * 10);
    CHECK_STATUS(facet_lifter_basis(l, FACET_BASIS_ORTHONORMAL, 10, basis, NULL, &e), FACET_OK);
    for (int k = 0; k < 10; ++k) {
        double dot = 0;
        for (int v = 0; v < p.nv; ++v)
            dot += (t[v] - z[v]) * basis[(size_t)k * p.nv + v];
        CHECK(fabs(dot) < accuracy);
    }
    facet_lifter_free(&l);
    free(t), free(z), free(basis);
    plan_free(&a), plan_free(&b), plan_free(&p);
}

static void test_ill_conditioned_projection(void)
{
    ill_conditioned_projection(1e-6, 1e-9);
    ill_conditioned_projection(1e-9, 1e-6);
}

/* Straight quad grid: liftings are f(x) + g(y), dimension nx + ny - 1 =
 * n_vertices - n_faces; a wobbled interior keeps the quads' constraints
 * independent, so the dimension stays (the liftings are no longer sums). */
static void test_quad_grid(void)
{
    for (int georef = 0; georef < 2; ++georef) {
        plan_t p = grid(7, 5, 0, 0.0, georef ? 5e6 : 0.0);
        facet_mesh m = plan_mesh(&p);
        facet_lifter *l = NULL;
        facet_error e;
        CHECK_STATUS(facet_lifter_create(&m, NULL, NULL, &l, &e), FACET_OK);
        CHECK(facet_lifter_dimension(l) == 7 + 5 - 1);
        facet_lifter_free(&l);
        plan_free(&p);
    }
    plan_t p = grid(7, 5, 0, 0.15, 0.0);
    facet_mesh m = plan_mesh(&p);
    facet_lifter *l = NULL;
    facet_error e;
    CHECK_STATUS(facet_lifter_create(&m, NULL, NULL, &l, &e), FACET_OK);
    CHECK(facet_lifter_dimension(l) == 7 + 5 - 1);
    facet_lifter_free(&l);
    plan_free(&p);
}

/* Optimality: the residual t - z is W-orthogonal to every lifting. */
static void test_optimal(void)
{
    plan_t p = grid(8, 6, 0, 0.0, 1000.0);
    facet_mesh m = plan_mesh(&p);
    const int32_t n = p.nv;
    double *w = malloc(sizeof(double) * n), *t = malloc(sizeof(double) * n);
    double *z = malloc(sizeof(double) * n), *z2 = malloc(sizeof(double) * n);
    for (int v = 0; v < n; ++v) {
        w[v] = 0.5 + (v % 5);
        t[v] = 300.0 + sin(0.9 * v) + 0.1 * v;
    }
    facet_lifter *l = NULL;
    facet_error e;
    CHECK_STATUS(facet_lifter_create(&m, w, NULL, &l, &e), FACET_OK);
    const int32_t d = facet_lifter_dimension(l);
    CHECK(d == 8 + 6 - 1);
    facet_lift_result r;
    CHECK_STATUS(facet_lifter_solve(l, t, z, &r, &e), FACET_OK);
    CHECK(r.planarity_max_rel < 1e-9);
    CHECK(r.target_rms > 0.1);
    double *basis = malloc(sizeof(double) * (size_t)n * d), *values = malloc(sizeof(double) * d);
    CHECK_STATUS(facet_lifter_basis(l, FACET_BASIS_ORTHONORMAL, d, basis, values, &e), FACET_OK);
    double wsum = 0;
    for (int v = 0; v < n; ++v)
        wsum += w[v];
    for (int k = 0; k < d; ++k) {
        double dot = 0, self = 0;
        for (int v = 0; v < n; ++v) {
            dot += w[v] * (t[v] - z[v]) * basis[(size_t)k * n + v];
            self += w[v] * basis[(size_t)k * n + v] * basis[(size_t)k * n + v];
        }
        CHECK(fabs(dot) < 1e-9 * wsum);
        CHECK_NEAR(self * n / wsum, 1.0, 1e-9); /* W-orthonormal for mean-1 weights */
    }
    /* Each basis function is a lifting: solving for it returns it. */
    CHECK_STATUS(facet_lifter_solve(l, basis + (size_t)5 * n, z2, &r, &e), FACET_OK);
    CHECK(max_abs_diff(n, z2, basis + (size_t)5 * n) < 1e-12);
    /* The fundamental lifting of a vertex is the solve for its unit target. */
    double *unit = calloc(n, sizeof(double));
    unit[9] = 1.0;
    CHECK_STATUS(facet_lifter_solve(l, unit, z, &r, &e), FACET_OK);
    CHECK_STATUS(facet_lifter_fundamental(l, 9, z2, &e), FACET_OK);
    CHECK(max_abs_diff(n, z, z2) < 1e-14);
    CHECK_STATUS(facet_lifter_fundamental(l, n, z2, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    /* Eigen basis: energies ascending, functions W-orthonormal. */
    CHECK_STATUS(facet_lifter_basis(l, FACET_BASIS_EIGEN, d, basis, values, &e), FACET_OK);
    for (int k = 4; k < d; ++k)
        CHECK(values[k] >= values[k - 1] - 1e-12);
    for (int a = 3; a < d; ++a)
        for (int b = 0; b <= a; ++b) {
            double dot = 0;
            for (int v = 0; v < n; ++v)
                dot += w[v] * basis[(size_t)a * n + v] * basis[(size_t)b * n + v];
            CHECK_NEAR(dot * n / wsum, a == b ? 1.0 : 0.0, 1e-9);
        }
    facet_lifter_free(&l);
    free(w), free(t), free(z), free(z2), free(basis), free(values), free(unit);
    plan_free(&p);
}

static void test_errors(void)
{
    plan_t p = grid(3, 3, 0, 0.0, 0.0);
    facet_mesh m = plan_mesh(&p);
    facet_lifter *l = NULL;
    facet_error e;
    double w[9] = {1, 1, 1, 1, 0, 1, 1, 1, 1};
    CHECK_STATUS(facet_lifter_create(&m, w, NULL, &l, &e), FACET_ERROR_BAD_WEIGHT);
    CHECK(e.vertex == 4 && strstr(e.message, "vertex 4") != NULL);
    CHECK(l == NULL);
    /* Collinear face: squash the top row onto the middle one. */
    for (int i = 6; i < 9; ++i)
        p.xyz[3 * i + 1] = 1.0;
    p.xyz[3 * 4 + 1] = 1.0;
    p.xyz[3 * 3 + 1] = 1.0;
    p.xyz[3 * 5 + 1] = 1.0;
    CHECK_STATUS(facet_lifter_create(&m, NULL, NULL, &l, &e), FACET_ERROR_PLAN_DEGENERATE_FACE);
    CHECK(strstr(e.message, "collinear") != NULL);
    plan_free(&p);
    p = grid(3, 3, 0, 0.0, 0.0);
    m = plan_mesh(&p);
    CHECK_STATUS(facet_lifter_create(&m, NULL, NULL, &l, &e), FACET_OK);
    double t[9] = {0, 0, 0, 0, NAN, 0, 0, 0, 0}, z[9];
    for (int v = 0; v < 9; ++v)
        z[v] = -7.0;
    CHECK_STATUS(facet_lifter_solve(l, t, z, NULL, &e), FACET_ERROR_BAD_TARGET);
    CHECK(e.vertex == 4);
    CHECK(z[0] == -7.0); /* untouched */
    CHECK_STATUS(facet_lifter_basis(l, FACET_BASIS_EIGEN, 99, z, NULL, &e),
                 FACET_ERROR_INVALID_ARGUMENT);
    facet_lifter_free(&l);
    plan_free(&p);
}

typedef struct {
    int calls, cancel_at;
    int64_t done[8], total[8];
} stages_t;

static int stages(void *user, int64_t done, int64_t total)
{
    stages_t *st = user;
    if (st->calls < 8)
        st->done[st->calls] = done, st->total[st->calls] = total;
    return ++st->calls == st->cancel_at;
}

/* The create step's progress: (done, 3) as its stages end; a nonzero return cancels
 * (FACET_ERROR_CANCELLED, no lifter; the sanitizer build finds what it would leak). */
static void test_create_progress_and_cancel(void)
{
    plan_t p = grid(12, 9, 0, 0.2, 0.0);
    facet_mesh m = plan_mesh(&p);
    facet_lifter *l = NULL;
    facet_error e;
    stages_t st = {0, 0, {0}, {0}};
    facet_lift_options o = {0.0, stages, &st};
    CHECK_STATUS(facet_lifter_create(&m, NULL, &o, &l, &e), FACET_OK);
    CHECK(st.calls == 3);
    for (int k = 0; k < 3 && k < st.calls; ++k)
        CHECK(st.done[k] == k + 1 && st.total[k] == 3);
    facet_lifter_free(&l);
    for (int at = 1; at <= 3; ++at) {
        stages_t stop = {0, at, {0}, {0}};
        facet_lift_options so = {0.0, stages, &stop};
        CHECK_STATUS(facet_lifter_create(&m, NULL, &so, &l, &e), FACET_ERROR_CANCELLED);
        CHECK(l == NULL && stop.calls == at);
    }
    plan_free(&p);
}

int main(void)
{
    test_create_progress_and_cancel();
    test_triangulated();
    test_nested_triangles();
    test_quad_grid();
    test_nearly_liftable();
    test_ill_conditioned_projection();
    test_optimal();
    test_errors();
    return check_report("test_lift");
}
