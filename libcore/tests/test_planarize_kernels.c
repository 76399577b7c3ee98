/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* The planarizer's fast kernels against the plain ones they replace, bit for
 * bit: the paired eigenvector solver against two single calls, and the
 * one-pass plane fit (faces in pairs, quads unrolled, the angle floor's test
 * on the edge vectors) against facet_face_measure and the exact corner
 * cosine, on a mesh with triangles, quads, hexagons and a 10-gon, with the
 * angle floor on and off (off, runs of four faces of one size take SIMD
 * lanes); and four faces of 3 to 8 corners at once (facet_face_measure4),
 * two such fours (facet_face_measure8) and sixteen faces of one size
 * (facet_face_measure16), against facet_face_measure on random, planar, collinear, coincident,
 * zero, huge and tiny faces. */
#include "check.h"
#include "planarize_internal.h"
#include "simd.h"
#include "test_meshes.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static uint32_t rng_state = 2463534242u;

static double uniform(void) /* in [-1, 1) */
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return (double)rng_state / 2147483648.0 - 1.0;
}

static int same_bits(const double *a, const double *b, int n)
{
    return memcmp(a, b, sizeof(double) * (size_t)n) == 0;
}

/* The scatter matrix of n points with coordinates scaled by s per axis. */
static void scatter(int n, const double s[3], double a[6])
{
    double p[16][3], c[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < 3; ++j) {
            p[k][j] = s[j] * uniform();
            c[j] += p[k][j] / n;
        }
    memset(a, 0, sizeof(double) * 6);
    for (int k = 0; k < n; ++k) {
        const double x = p[k][0] - c[0], y = p[k][1] - c[1], z = p[k][2] - c[2];
        a[0] += x * x, a[1] += x * y, a[2] += x * z, a[3] += y * y, a[4] += y * z, a[5] += z * z;
    }
}

static void test_eigenvector_pairs(void)
{
    /* nearly planar, planar, collinear, coincident, indefinite, zero, huge, tiny */
    const double shapes[][3] = {{1, 1, 1e-3}, {1, 1, 1e-9}, {1, 1, 0}, {1, 0, 0},
                                {0, 0, 0},    {1, 1, 1},    {1e150, 1e150, 1e140}, {1e-150, 1e-150, 1e-155}};
    const int n_shapes = (int)(sizeof shapes / sizeof shapes[0]);
    int compared = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        double a[6], b[6];
        scatter(3 + trial % 6, shapes[trial % n_shapes], a);
        scatter(3 + (trial / 7) % 6, shapes[(trial / 3) % n_shapes], b);
        if (trial % 11 == 0) /* indefinite, as the face-normal Laplacian makes */
            for (int k = 0; k < 6; ++k)
                b[k] = uniform();
        if (trial % 13 == 0)
            memset(a, 0, sizeof a);
        double va[3], vb[3], wa[3], wb[3];
        facet_sym3_smallest_eigenvector(a, va);
        facet_sym3_smallest_eigenvector(b, vb);
        facet_sym3_smallest_eigenvector2(a, b, wa, wb);
        CHECK(same_bits(va, wa, 3));
        CHECK(same_bits(vb, wb, 3));
        ++compared;
    }
    CHECK(compared == 4000);
    /* and a known answer through the pair: the z axis for points in z = 0 */
    const double flat[6] = {2.0, 0.5, 0.0, 1.0, 0.0, 0.0};
    const double tilted[6] = {1.0, 0.0, 0.0, 1.0, 0.0, 1e-3};
    double v1[3], v2[3];
    facet_sym3_smallest_eigenvector2(flat, tilted, v1, v2);
    CHECK_NEAR(fabs(v1[2]), 1.0, 1e-15);
    CHECK_NEAR(fabs(v2[2]), 1.0, 1e-15);
}

/* A 9 x 5 grid whose cells are merged or split into faces of 3 to 10
 * corners; 39 faces (an odd count, so one face has no partner). */
typedef struct {
    double xyz[3 * 60];
    int32_t start[64], idx[256];
    int32_t nf, nv;
} mixed_mesh;

static void add_face(mixed_mesh *m, int n, const int32_t *v)
{
    for (int k = 0; k < n; ++k)
        m->idx[m->start[m->nf] + k] = v[k];
    m->start[m->nf + 1] = m->start[m->nf] + n;
    m->nf++;
}

static void build_mixed(mixed_mesh *m)
{
    const int nu = 9, nv = 5;
    m->nv = (nu + 1) * (nv + 1);
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
            double *x = m->xyz + 3 * (j * (nu + 1) + i);
            x[0] = i + 0.1 * uniform(), x[1] = j + 0.1 * uniform();
            x[2] = 0.3 * sin(0.7 * i) * cos(0.5 * j) + 0.05 * uniform();
        }
#define V(i, j) ((j) * (nu + 1) + (i))
    m->nf = 0;
    m->start[0] = 0;
    /* row 0: a 10-gon over cells 0-3, then quads */
    add_face(m, 10, (int32_t[]){V(0, 0), V(1, 0), V(2, 0), V(3, 0), V(4, 0), V(4, 1), V(3, 1), V(2, 1),
                                V(1, 1), V(0, 1)});
    for (int i = 4; i < nu; ++i)
        add_face(m, 4, (int32_t[]){V(i, 0), V(i + 1, 0), V(i + 1, 1), V(i, 1)});
    /* row 1: hexagons over cell pairs, a last quad */
    for (int i = 0; i + 1 < nu; i += 2)
        add_face(m, 6, (int32_t[]){V(i, 1), V(i + 1, 1), V(i + 2, 1), V(i + 2, 2), V(i + 1, 2), V(i, 2)});
    add_face(m, 4, (int32_t[]){V(nu - 1, 1), V(nu, 1), V(nu, 2), V(nu - 1, 2)});
    /* row 2: triangles (cells split), then quads */
    for (int i = 0; i < 3; ++i) {
        add_face(m, 3, (int32_t[]){V(i, 2), V(i + 1, 2), V(i + 1, 3)});
        add_face(m, 3, (int32_t[]){V(i, 2), V(i + 1, 3), V(i, 3)});
    }
    for (int i = 3; i < nu; ++i)
        add_face(m, 4, (int32_t[]){V(i, 2), V(i + 1, 2), V(i + 1, 3), V(i, 3)});
    /* rows 3 and 4: quads, all but the last cell (an odd face count) */
    for (int j = 3; j < nv; ++j)
        for (int i = 0; i < nu; ++i)
            if (!(j == 4 && i >= nu - 2))
                add_face(m, 4, (int32_t[]){V(i, j), V(i + 1, j), V(i + 1, j + 1), V(i, j + 1)});
#undef V
}

static void test_one_pass_fit(int threads, double angle_floor)
{
    mixed_mesh m;
    build_mixed(&m);
    CHECK(m.nf % 2 == 1);
    facet_mesh mesh = {m.nv, m.nf, m.xyz, m.start, m.idx};
    facet_planarizer *s = NULL;
    facet_error e;
    CHECK_STATUS(facet_planarizer_create(&mesh, &s, &e), FACET_OK);
    double *out = malloc(sizeof(double) * 3 * (size_t)m.nv);
    for (int method = 0; method < 2; ++method) {
        facet_planarize_options o;
        facet_planarize_options_default((facet_method)method, &o);
        o.iterations = 3;
        o.anderson = 0;
        o.mu0 = 0.5;
        o.angle_floor = angle_floor; /* 50: some corners are below it */
        o.threads = threads;
        facet_planarize_result r;
        facet_planarizer_solve(s, m.xyz, &o, out, &r, &e);
        CHECK(r.iterations == 3);
        /* the last local step measured s->q: redo it face by face */
        int below_any = 0, checked = 0;
        for (int32_t f = 0; f < m.nf; ++f) {
            const int32_t b = m.start[f], n = m.start[f + 1] - b;
            double normal[3], offset, dev, rms;
            const double edge = facet_face_measure(n, s->q, m.idx + b, normal, &offset, &dev, &rms);
            CHECK(same_bits(normal, s->normal + 3 * f, 3));
            CHECK(same_bits(&offset, &s->offset[f], 1));
            CHECK(same_bits(&dev, &s->face_dev[f], 1));
            CHECK(same_bits(&edge, &s->face_edge[f], 1));
            const double sq = rms * rms * (double)n;
            CHECK(same_bits(&sq, &s->face_sq[f], 1));
            int below = 0;
            for (int32_t k = 0; angle_floor > 0.0 && k < n; ++k) {
                const double *pa = s->q + 3 * m.idx[b + (k + n - 1) % n], *pc = s->q + 3 * m.idx[b + k];
                const double *pb = s->q + 3 * m.idx[b + (k + 1) % n];
                const double u[3] = {pa[0] - pc[0], pa[1] - pc[1], pa[2] - pc[2]};
                const double v[3] = {pb[0] - pc[0], pb[1] - pc[1], pb[2] - pc[2]};
                const double cosine = (u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) /
                                      sqrt((u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) *
                                           (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
                const double floor = s->corner_floor[b + k];
                if (s->face_guard[f]) { /* corner_cos is read (and kept) only for such faces */
                    CHECK((cosine > floor) == (s->corner_cos[b + k] > floor));
                    if (cosine > floor)
                        CHECK(same_bits(&cosine, &s->corner_cos[b + k], 1));
                }
                below |= cosine > floor;
            }
            if (angle_floor > 0.0)
                CHECK(s->face_guard[f] == below);
            below_any |= below;
            ++checked;
        }
        CHECK(checked == m.nf);
        CHECK(below_any == (angle_floor > 0.0)); /* the test reached the floor's branch */
    }
    free(out);
    facet_planarizer_free(&s);
}

static void test_face_measure4(void)
{
    /* per-axis scales of a face's points, as in test_eigenvector_pairs, and
     * faces with repeated or coincident corners */
    const double shapes[][3] = {{1, 1, 1e-3}, {1, 1, 1e-9}, {1, 1, 0}, {1, 0, 0},
                                {0, 0, 0},    {1, 1, 1},    {1e150, 1e150, 1e140}, {1e-150, 1e-150, 1e-155}};
    const int n_shapes = (int)(sizeof shapes / sizeof shapes[0]);
    enum { MAX = FACET_LANE_CORNERS_MAX };
    double xyz[3 * 4 * MAX];
    int32_t idx[4 * MAX];
    int compared = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        const int n = 3 + trial % (MAX - 2);
        for (int l = 0; l < 4; ++l) {
            const double *sc = shapes[(trial * 4 + l * 3 + trial / 5) % n_shapes];
            for (int k = 0; k < n; ++k)
                for (int j = 0; j < 3; ++j)
                    xyz[3 * (n * l + k) + j] = 100.0 + sc[j] * uniform();
            if ((trial + l) % 9 == 0) /* a repeated corner */
                memcpy(xyz + 3 * (n * l + 2), xyz + 3 * (n * l + 1), sizeof(double) * 3);
            if ((trial + l) % 17 == 0) /* all at one point */
                for (int k = 1; k < n; ++k)
                    memcpy(xyz + 3 * (n * l + k), xyz + 3 * (n * l), sizeof(double) * 3);
        }
        for (int k = 0; k < 4 * n; ++k) /* lanes take their corners from anywhere */
            idx[k] = (int32_t)((k * 7 + trial) % (4 * n));
        /* and a second four of another size, from the same points */
        const int nb = 3 + (trial / 3) % (MAX - 2);
        int32_t idx_b[4 * MAX];
        for (int k = 0; k < 4 * nb; ++k)
            idx_b[k] = (int32_t)((k * 5 + trial / 2) % (4 * n));
        /* and eight of one size one after another (one vector of eight
         * lanes in the AVX-512 copy) */
        int32_t idx8[8 * MAX];
        memcpy(idx8, idx, sizeof(int32_t) * 4 * (size_t)n);
        for (int k = 0; k < 4 * n; ++k)
            idx8[4 * n + k] = (int32_t)((k * 5 + trial / 2) % (4 * n));
        /* and sixteen of one size (two vectors of eight side by side) */
        int32_t idx16[16 * MAX];
        memcpy(idx16, idx8, sizeof(int32_t) * 8 * (size_t)n);
        for (int k = 0; k < 8 * n; ++k)
            idx16[8 * n + k] = (int32_t)((k * 3 + trial / 7) % (4 * n));
        double normal[48], offset[16], dev[16], sq[16], edge[16];
        for (int mode = 0; mode < 4; ++mode) {
            const int32_t *first = mode >= 2 ? idx8 : idx, *second = mode >= 2 ? idx8 + 4 * n : idx_b;
            const int size_b = mode >= 2 ? n : nb;
            if (mode == 3)
                facet_face_measure16(n, xyz, idx16, normal, offset, dev, sq, edge, NULL, NULL, NULL);
            else if (mode)
                facet_face_measure8(n, size_b, xyz, first, second, normal, offset, dev, sq, edge, NULL, NULL,
                                    NULL);
            else
                facet_face_measure4(n, xyz, idx, normal, offset, dev, sq, edge, NULL, NULL, NULL);
            for (int l = 0; l < (mode == 3 ? 16 : mode ? 8 : 4); ++l) {
                const int size = l < 4 ? n : size_b;
                const int32_t *corners = mode == 3 ? idx16 + n * l
                                         : l < 4   ? first + n * l
                                                   : second + size_b * (l - 4);
                double n1[3], o1, d1, rms;
                const double e1 = facet_face_measure(size, xyz, corners, n1, &o1, &d1, &rms);
                const double sq1 = rms * rms * (double)size;
                CHECK(same_bits(n1, normal + 3 * l, 3));
                CHECK(same_bits(&o1, offset + l, 1));
                CHECK(same_bits(&d1, dev + l, 1));
                CHECK(same_bits(&sq1, sq + l, 1));
                CHECK(same_bits(&e1, edge + l, 1));
                ++compared;
            }
        }
    }
    CHECK(compared == 108000);
}

/* Whole solves with the SIMD lanes (four faces of one size, four vertices
 * of the plain vertex step) against the same solves on the scalar code,
 * bit for bit: L/L and L/G, with and without fixed vertices, face weights
 * (one face exempt) and point-to-plane data, and with an angle floor that
 * some corners are below. */
static void lanes_against_scalar(const facet_mesh *mesh, int threads)
{
    const int32_t nv = mesh->n_vertices, nf = mesh->n_faces;
    double *weights = malloc(sizeof(double) * (size_t)nf);
    const int32_t fixed[3] = {0, 7, nv - 1};
    for (int32_t f = 0; f < nf; ++f)
        weights[f] = f == 5 ? 0.0 : 0.5 + 0.25 * (f % 3);
    double *a = malloc(sizeof(double) * 3 * (size_t)nv), *b = malloc(sizeof(double) * 3 * (size_t)nv);
    for (int method = 0; method < 2; ++method)
        for (int variant = 0; variant < 3; ++variant) {
            double *out[2] = {a, b};
            for (int scalar = 0; scalar < 2; ++scalar) {
                facet_planarizer *s = NULL;
                facet_error e;
                CHECK_STATUS(facet_planarizer_create(mesh, &s, &e), FACET_OK);
                s->scalar_kernels = scalar;
                if (variant == 1) {
                    CHECK_STATUS(facet_planarizer_set_face_weights(s, weights, &e), FACET_OK);
                    CHECK_STATUS(facet_planarizer_set_fixed(s, 3, fixed, &e), FACET_OK);
                }
                facet_planarize_options o;
                facet_planarize_options_default((facet_method)method, &o);
                o.iterations = 40;
                o.threads = threads;
                if (variant == 1)
                    o.data_tangent = 0.3; /* point-to-plane data */
                o.angle_floor = variant == 2 ? 50.0 : 0.0; /* 50: some corners below it */
                facet_planarize_result r;
                CHECK_STATUS(facet_planarizer_solve(s, mesh->xyz, &o, out[scalar], &r, &e), FACET_OK);
                CHECK(r.iterations == 40);
                facet_planarizer_free(&s);
            }
            CHECK(same_bits(a, b, 3 * nv));
        }
    free(a);
    free(b);
    free(weights);
}

static void test_lanes_against_scalar(int threads)
{
    mixed_mesh m; /* faces of 3 to 10 corners */
    build_mixed(&m);
    facet_mesh mixed = {m.nv, m.nf, m.xyz, m.start, m.idx};
    lanes_against_scalar(&mixed, threads);
    test_mesh grid = test_grid(8, 5, 1.0, 1.0, 0.0);
    CHECK(grid.mesh.n_vertices % 4 != 0); /* a last group of vertices with idle lanes */
    lanes_against_scalar(&grid.mesh, threads);
    test_mesh_free(&grid);
}

int main(void)
{
    test_eigenvector_pairs();
    /* the AVX-512 and AVX2 copies of the lanes (where the processor has
     * them), then the baseline ones */
    for (int level = 2; level >= 0; --level) {
#if FACET_HAVE_AVX2_CLONE
        facet_simd_max_level = level;
#else
        if (level > 0)
            continue;
#endif
        test_face_measure4();
        test_one_pass_fit(1, 50.0);
        test_one_pass_fit(2, 50.0);
        test_one_pass_fit(1, 0.0);
        test_one_pass_fit(2, 0.0);
        test_lanes_against_scalar(1);
        test_lanes_against_scalar(2);
    }
    return check_report("test_planarize_kernels");
}
