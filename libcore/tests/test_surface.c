/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Closest points on a triangle surface against brute force. */
#include "check.h"
#include "facet.h"
#include "test_meshes.h"

#include <string.h>

static uint32_t seed = 2024u;
static double rnd(void)
{
    seed = seed * 1664525u + 1013904223u;
    return (double)(seed >> 8) / 16777216.0;
}

static double dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Distance from p to triangle abc by brute force: the interior projection if
 * inside, else the best of the three segments, sampled densely and refined
 * by the exact segment formula. Independent of the library's code path. */
static double seg_dist(const double *p, const double *a, const double *b)
{
    double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    double l2 = dot(ab, ab), t = l2 > 0 ? dot(ap, ab) / l2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    double d[3] = {a[0] + t * ab[0] - p[0], a[1] + t * ab[1] - p[1], a[2] + t * ab[2] - p[2]};
    return sqrt(dot(d, d));
}

static double tri_dist(const double *p, const double *a, const double *b, const double *c)
{
    double best = fmin(seg_dist(p, a, b), fmin(seg_dist(p, b, c), seg_dist(p, c, a)));
    double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0]};
    double nn = dot(n, n);
    if (nn > 0) {
        /* barycentric coordinates of the projection, by areas */
        double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
        double h = dot(ap, n) / nn;
        double q[3] = {p[0] - h * n[0], p[1] - h * n[1], p[2] - h * n[2]};
        const double *v[3] = {a, b, c};
        int inside = 1;
        for (int k = 0; k < 3; ++k) {
            const double *s = v[k], *t = v[(k + 1) % 3];
            double st[3] = {t[0] - s[0], t[1] - s[1], t[2] - s[2]};
            double sq[3] = {q[0] - s[0], q[1] - s[1], q[2] - s[2]};
            double x[3] = {st[1] * sq[2] - st[2] * sq[1], st[2] * sq[0] - st[0] * sq[2],
                           st[0] * sq[1] - st[1] * sq[0]};
            if (dot(x, n) < 0)
                inside = 0;
        }
        if (inside)
            best = fmin(best, fabs(h) * sqrt(nn));
    }
    return best;
}

static void random_surface_test(int nt, double offset, double size)
{
    const int nv = 3 * nt;
    double *xyz = malloc(sizeof(double) * 3 * nv);
    int32_t *tri = malloc(sizeof(int32_t) * 3 * nt);
    for (int t = 0; t < nt; ++t) {
        double c[3] = {rnd(), rnd(), rnd()};
        for (int k = 0; k < 3; ++k) {
            for (int j = 0; j < 3; ++j)
                xyz[9 * t + 3 * k + j] = offset + size * (c[j] + 0.15 * (rnd() - 0.5));
            tri[3 * t + k] = 3 * t + k;
        }
        if (t % 17 == 0) /* zero-area: two corners equal */
            memcpy(xyz + 9 * t + 3, xyz + 9 * t, 3 * sizeof(double));
        if (t % 23 == 0) /* zero-area: collinear */
            for (int j = 0; j < 3; ++j)
                xyz[9 * t + 6 + j] = 2 * xyz[9 * t + 3 + j] - xyz[9 * t + j];
    }
    facet_surface *s = NULL;
    facet_error e;
    CHECK_STATUS(facet_surface_create(nv, xyz, nt, tri, &s, &e), FACET_OK);
    CHECK(facet_surface_triangle_count(s) == nt);
    const int nq = 400;
    double *q = malloc(sizeof(double) * 3 * nq);
    for (int i = 0; i < 3 * nq; ++i)
        q[i] = offset + size * (1.4 * rnd() - 0.2);
    double *cl = malloc(sizeof(double) * 3 * nq), *d = malloc(sizeof(double) * nq);
    double *nrm = malloc(sizeof(double) * 3 * nq), *d1 = malloc(sizeof(double) * nq);
    int32_t *ti = malloc(sizeof(int32_t) * nq), *t1 = malloc(sizeof(int32_t) * nq);
    CHECK_STATUS(facet_surface_closest(s, nq, q, 2, cl, d, ti, nrm, &e), FACET_OK);
    CHECK_STATUS(facet_surface_closest(s, nq, q, 1, NULL, d1, t1, NULL, &e), FACET_OK);
    int bad = 0, nan = 0, diff_threads = 0;
    for (int i = 0; i < nq; ++i) {
        double brute = INFINITY;
        for (int t = 0; t < nt; ++t)
            brute = fmin(brute, tri_dist(q + 3 * i, xyz + 9 * t, xyz + 9 * t + 3, xyz + 9 * t + 6));
        if (!(fabs(d[i] - brute) <= 1e-9 * size))
            ++bad;
        if (!isfinite(d[i]) || !isfinite(cl[3 * i]) || !isfinite(nrm[3 * i]))
            ++nan;
        if (memcmp(&d[i], &d1[i], sizeof(double)) != 0 || ti[i] != t1[i])
            ++diff_threads;
        /* the closest point is that far and lies on the triangle reported */
        const int t = ti[i];
        double dd[3] = {cl[3 * i] - q[3 * i], cl[3 * i + 1] - q[3 * i + 1], cl[3 * i + 2] - q[3 * i + 2]};
        if (!(fabs(sqrt(dot(dd, dd)) - d[i]) <= 1e-9 * size))
            ++bad;
        if (!(tri_dist(cl + 3 * i, xyz + 9 * t, xyz + 9 * t + 3, xyz + 9 * t + 6) <= 1e-9 * size))
            ++bad;
        const double nl = dot(nrm + 3 * i, nrm + 3 * i);
        if (!(fabs(nl - 1.0) < 1e-12 || nl == 0.0))
            ++bad;
    }
    CHECK(bad == 0);
    CHECK(nan == 0);
    CHECK(diff_threads == 0);
    if (bad)
        fprintf(stderr, "  %d bad of %d queries (nt %d, offset %g)\n", bad, nq, nt, offset);
    facet_surface_free(&s);
    CHECK(s == NULL);
    free(xyz), free(tri), free(q), free(cl), free(d), free(nrm), free(d1), free(ti), free(t1);
}

/* A pyramid's four sloped triangles around its apex, each with corners of its own, in
 * the units `scale` and at `offset`; queries on the apex, on the edge the first two
 * share, and 1e-13 off the apex. Each is a tie that rounding alone decided before (the
 * first strictly closer triangle won): now the lowest triangle index wins, in any units,
 * so the normal (a planarization's tangent plane there) is the same in mm and in m. */
static void tie_test(double scale, double offset)
{
    const double apex[3] = {0, 0, 1};
    const double base[4][3] = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
    double xyz[36];
    int32_t tri[12];
    for (int t = 0; t < 4; ++t) {
        const double *c[3] = {apex, base[t], base[(t + 1) % 4]};
        for (int k = 0; k < 3; ++k) {
            for (int j = 0; j < 3; ++j)
                xyz[9 * t + 3 * k + j] = c[k][j] * scale + offset;
            tri[3 * t + k] = 3 * t + k;
        }
    }
    /* triangle 3 first: the lowest index must win whatever the order seen */
    int32_t order[12];
    for (int k = 0; k < 12; ++k)
        order[k] = tri[(k + 9) % 12];
    for (int pass = 0; pass < 2; ++pass) {
        facet_surface *s = NULL;
        facet_error e;
        CHECK_STATUS(facet_surface_create(12, xyz, 4, pass ? order : tri, &s, &e), FACET_OK);
        const double at[3][3] = {{0, 0, 1}, {0.5, 0, 0.5}, {1e-13, -2e-13, 1}};
        double q[9], n[9];
        int32_t t[3];
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k)
                q[3 * i + k] = at[i][k] * scale + offset;
        CHECK_STATUS(facet_surface_closest(s, 3, q, 1, NULL, NULL, t, n, &e), FACET_OK);
        /* apex: all four tie; edge 0-1 of triangle 0 (apex to base[0]) is shared with
         * triangle 3; the point just off the apex lies within the tie */
        CHECK(t[0] == 0);
        CHECK(t[1] == 0);
        CHECK(t[2] == 0);
        /* triangle 0: the first face, normal (1, 1, 1) / sqrt 3; in pass 1 the fourth,
         * (1, -1, 1) / sqrt 3 */
        const double r3 = 1.0 / sqrt(3.0);
        for (int i = 0; i < 3; ++i) {
            CHECK_NEAR(n[3 * i + 0], r3, 1e-12);
            CHECK_NEAR(n[3 * i + 1], pass ? -r3 : r3, 1e-12);
            CHECK_NEAR(n[3 * i + 2], r3, 1e-12);
        }
        facet_surface_free(&s);
    }
}

/* Three parallel triangles under a query, nearest Z, then Y (tied with Z: 0.6e-12 of
 * the squared distance) and X (1.2e-12: not tied with Z, but with Y): in every order
 * of their indices the tied one of lower index wins. One pass kept a single candidate
 * and dropped Y once Z arrived after it (review). */
static void tie_order_test(void)
{
    const double depth[3] = {0.6e-12, 0.3e-12, 0.0}; /* X, Y, Z */
    const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    const double corners[3][2] = {{-0.5, -0.5}, {0.5, -0.5}, {0.0, 0.5}};
    for (int k = 0; k < 6; ++k) {
        double xyz[27];
        int32_t tri[9];
        for (int i = 0; i < 3; ++i)
            for (int c = 0; c < 3; ++c) {
                xyz[9 * i + 3 * c] = corners[c][0];
                xyz[9 * i + 3 * c + 1] = corners[c][1];
                xyz[9 * i + 3 * c + 2] = -depth[perms[k][i]];
                tri[3 * i + c] = 3 * i + c;
            }
        facet_surface *s = NULL;
        facet_error e;
        CHECK_STATUS(facet_surface_create(9, xyz, 3, tri, &s, &e), FACET_OK);
        const double q[3] = {0.0, 0.0, 1.0};
        int32_t t = -1;
        CHECK_STATUS(facet_surface_closest(s, 1, q, 1, NULL, NULL, &t, NULL, &e), FACET_OK);
        int expected = -1; /* the lowest index among Y (1) and Z (2) */
        for (int i = 0; i < 3 && expected < 0; ++i)
            if (perms[k][i] != 0)
                expected = i;
        CHECK(t == expected);
        facet_surface_free(&s);
    }
}

/* A fan of 40 triangles around one corner, listed from the 17th on: a query on the
 * corner ties all 40, more than the search keeps as candidates (32): the second search
 * ranks them, and triangle 0 wins. */
static void tie_fan_test(void)
{
    enum { N = 40 };
    double xyz[9 * N];
    int32_t tri[3 * N];
    for (int k = 0; k < N; ++k) {
        const int j = (k + 17) % N; /* listed from the 17th */
        const double a0 = 2 * M_PI * j / N, a1 = 2 * M_PI * (j + 1) / N;
        const double c[3][3] = {{0, 0, 0.1 * sin(3 * a0)}, {cos(a0), sin(a0), 0},
                                {cos(a1), sin(a1), 0}};
        for (int v = 0; v < 3; ++v) {
            for (int d = 0; d < 3; ++d)
                xyz[9 * k + 3 * v + d] = c[v][d];
            tri[3 * k + v] = 3 * k + v;
        }
        xyz[9 * k + 2] = 0.0; /* the shared corner: one point */
    }
    facet_surface *s = NULL;
    facet_error e;
    CHECK_STATUS(facet_surface_create(3 * N, xyz, N, tri, &s, &e), FACET_OK);
    const double q[3] = {0, 0, 0};
    int32_t t = -1;
    double d = -1;
    CHECK_STATUS(facet_surface_closest(s, 1, q, 1, NULL, &d, &t, NULL, &e), FACET_OK);
    CHECK(t == 0);
    CHECK(d == 0.0);
    facet_surface_free(&s);
}

int main(void)
{
    tie_fan_test();
    tie_order_test();
    tie_test(1.0, 0.0);
    tie_test(1000.0, 0.0);
    tie_test(1000.0, 5.7e6); /* millimetres, georeferenced */
    tie_test(1e-3, -2.0);
    random_surface_test(1, 0.0, 1.0);
    random_surface_test(7, 0.0, 1.0);
    random_surface_test(500, 0.0, 1.0);
    random_surface_test(2000, 2.5e6, 50.0); /* georeferenced, metres */
    random_surface_test(300, 0.0, 1e-3);

    /* a fully degenerate surface: every triangle is a point or a segment */
    {
        const double xyz[] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0};
        const int32_t tri[] = {0, 1, 2, 3, 4, 5};
        facet_surface *s = NULL;
        facet_error e;
        CHECK_STATUS(facet_surface_create(6, xyz, 2, tri, &s, &e), FACET_OK);
        const double q[] = {0, 1, 0, 2.5, 0, 1, -1, 0, 0};
        double cl[9], d[3], n[9];
        int32_t t[3];
        CHECK_STATUS(facet_surface_closest(s, 3, q, 0, cl, d, t, n, &e), FACET_OK);
        CHECK_NEAR(d[0], 1.0, 1e-15);
        CHECK(t[0] == 0);
        CHECK_NEAR(d[1], 1.0, 1e-15);
        CHECK_NEAR(cl[3], 2.5, 1e-15);
        CHECK(t[1] == 1);
        CHECK_NEAR(d[2], 1.0, 1e-15);
        for (int k = 0; k < 9; ++k)
            CHECK(n[k] == 0.0);
        facet_surface_free(&s);
    }

    /* from a mesh: a unit quad at z = 0 and a planar hexagon at z = 1 */
    {
        double xyz[3 * 10] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
        for (int k = 0; k < 6; ++k) {
            xyz[12 + 3 * k] = 5 + cos(k * M_PI / 3);
            xyz[12 + 3 * k + 1] = sin(k * M_PI / 3);
            xyz[12 + 3 * k + 2] = 1;
        }
        const int32_t start[] = {0, 4, 10};
        const int32_t fv[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
        facet_mesh m = {10, 2, xyz, start, fv};
        facet_surface *s = NULL;
        facet_error e;
        CHECK_STATUS(facet_surface_create_from_mesh(&m, &s, &e), FACET_OK);
        CHECK(facet_surface_triangle_count(s) == 2 + 6);
        const double q[] = {0.3, 0.6, 2.0, 5.1, 0.2, -3.0, 0.5, -1.0, 0.0};
        double d[3], n[9];
        int32_t t[3];
        CHECK_STATUS(facet_surface_closest(s, 3, q, 0, NULL, d, t, n, &e), FACET_OK);
        CHECK_NEAR(d[0], 2.0, 1e-15);
        CHECK(facet_surface_face(s, t[0]) == 0);
        CHECK_NEAR(fabs(n[2]), 1.0, 1e-15);
        CHECK_NEAR(d[1], 4.0, 1e-14);
        CHECK(facet_surface_face(s, t[1]) == 1);
        CHECK_NEAR(d[2], 1.0, 1e-15);
        CHECK(facet_surface_face(s, 99) == -1);
        /* errors name the input */
        const double bad[] = {0, NAN, 0};
        CHECK_STATUS(facet_surface_closest(s, 1, bad, 0, NULL, d, NULL, NULL, &e),
                     FACET_ERROR_NONFINITE);
        CHECK(strstr(e.message, "query point 0") != NULL);
        facet_surface_free(&s);
        facet_surface_free(&s); /* NULL is fine */
        const int32_t bad_fv[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 10};
        facet_mesh mb = {10, 2, xyz, start, bad_fv};
        CHECK_STATUS(facet_surface_create_from_mesh(&mb, &s, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
        CHECK(s == NULL);
        const int32_t tri[] = {0, 1, 7};
        CHECK_STATUS(facet_surface_create(4, xyz, 1, tri, &s, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
        CHECK(strstr(e.message, "triangle 0") != NULL);
        CHECK_STATUS(facet_surface_create(4, xyz, 0, tri, &s, &e), FACET_ERROR_EMPTY_MESH);
    }

    /* a grid surface at georeferenced offset: points on it are at distance ~0 */
    {
        test_mesh g = test_grid(30, 20, 1.0, 2.0, 3.0e6);
        facet_surface *s = NULL;
        facet_error e;
        CHECK_STATUS(facet_surface_create_from_mesh(&g.mesh, &s, &e), FACET_OK);
        double *d = malloc(sizeof(double) * (size_t)g.mesh.n_vertices);
        CHECK_STATUS(facet_surface_closest(s, g.mesh.n_vertices, g.xyz, 0, NULL, d, NULL, NULL, &e),
                     FACET_OK);
        double worst = 0;
        for (int i = 0; i < g.mesh.n_vertices; ++i)
            worst = fmax(worst, d[i]);
        CHECK(worst < 1e-9);
        free(d);
        facet_surface_free(&s);
        test_mesh_free(&g);
    }
    return check_report("test_surface");
}
