/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Least-squares planes and per-face planarity measures. */
#include "internal.h"
#include "simd.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Trig-free: the smallest root of the characteristic polynomial by Newton's
 * method from 0 (for a PSD matrix every root is >= 0, so Newton from 0 rises
 * monotonically to the smallest), then the eigenvector as the largest cross
 * product of two rows of (A - lambda I). In three parts, so that two
 * matrices can go through Newton's steps side by side (below). */
typedef struct {
    double scale, b00, b01, b02, b11, b12, b22, c0, c1, c2;
} sym3_problem;

/* Returns 0 for the zero matrix (any unit vector is an eigenvector). */
static inline int sym3_prepare(const double a[6], sym3_problem *p)
{
    double scale = 0.0;
    for (int k = 0; k < 6; ++k) /* fmax without the libm call (a NaN is skipped, as by fmax) */
        if (fabs(a[k]) > scale)
            scale = fabs(a[k]);
    if (!(scale > 0.0))
        return 0;
    const double inv = 1.0 / scale;
    const double b00 = a[0] * inv, b01 = a[1] * inv, b02 = a[2] * inv;
    const double b11 = a[3] * inv, b12 = a[4] * inv, b22 = a[5] * inv;
    p->scale = scale;
    p->b00 = b00, p->b01 = b01, p->b02 = b02, p->b11 = b11, p->b12 = b12, p->b22 = b22;
    p->c2 = b00 + b11 + b22;
    p->c1 = b00 * b11 - b01 * b01 + b00 * b22 - b02 * b02 + b11 * b22 - b12 * b12;
    p->c0 = b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) +
            b02 * (b01 * b12 - b11 * b02);
    return 1;
}

/* One Newton step on f(x) = x^3 - c2 x^2 + c1 x - c0 from *x (updated);
 * returns 0 when Newton is done: after a step below 1e-9 (of the scaled
 * matrix's largest entry), since Newton converges quadratically, the error
 * left is of the order of that step's square, below the rounding. */
static inline int sym3_newton_step(const sym3_problem *p, double *x_io)
{
    const double x = *x_io, c0 = p->c0, c1 = p->c1, c2 = p->c2;
    const double f = ((x - c2) * x + c1) * x - c0;
    const double df = (3.0 * x - 2.0 * c2) * x + c1;
    if (!(f < 0.0) || !(df > 0.0))
        return 0;
    const double step = f / df;
    const double next = x - step;
    if (!(next > x))
        return 0;
    *x_io = next;
    return !(step > -1e-9 * (1.0 + next));
}

/* The eigenvector for the eigenvalue x (scaled); returns the eigenvalue. */
static inline double sym3_finish(const sym3_problem *p, double x, double v[3])
{
    const double b00 = p->b00, b01 = p->b01, b02 = p->b02, b11 = p->b11, b12 = p->b12, b22 = p->b22;
    const double r0[3] = {b00 - x, b01, b02};
    const double r1[3] = {b01, b11 - x, b12};
    const double r2[3] = {b02, b12, b22 - x};
    double c01[3], c02[3], c12[3];
    cross3(r0, r1, c01);
    cross3(r0, r2, c02);
    cross3(r1, r2, c12);
    const double n01 = dot3(c01, c01), n02 = dot3(c02, c02), n12 = dot3(c12, c12);
    const double *best = c01;
    double nbest = n01;
    if (n02 > nbest)
        best = c02, nbest = n02;
    if (n12 > nbest)
        best = c12, nbest = n12;
    if (nbest > 1e-28) {
        const double s = 1.0 / sqrt(nbest);
        v[0] = best[0] * s, v[1] = best[1] * s, v[2] = best[2] * s;
    } else {
        /* Two or three equal smallest eigenvalues (collinear or coincident
         * points): any unit vector orthogonal to the largest row. */
        const double *rows[3] = {r0, r1, r2};
        int big = 0;
        double nr = dot3(r0, r0);
        for (int k = 1; k < 3; ++k)
            if (dot3(rows[k], rows[k]) > nr)
                big = k, nr = dot3(rows[k], rows[k]);
        if (nr < 1e-28) {
            v[0] = 0.0, v[1] = 0.0, v[2] = 1.0;
        } else {
            const double *r = rows[big];
            double t[3] = {0.0, 0.0, 0.0};
            int axis = fabs(r[0]) <= fabs(r[1]) ? (fabs(r[0]) <= fabs(r[2]) ? 0 : 2)
                                                 : (fabs(r[1]) <= fabs(r[2]) ? 1 : 2);
            t[axis] = 1.0;
            double c[3];
            cross3(r, t, c);
            const double s = 1.0 / sqrt(dot3(c, c));
            v[0] = c[0] * s, v[1] = c[1] * s, v[2] = c[2] * s;
        }
    }
    return x * p->scale;
}

double facet_sym3_smallest_eigenvector(const double a[6], double v[3])
{
    sym3_problem p;
    if (!sym3_prepare(a, &p)) {
        v[0] = 0.0, v[1] = 0.0, v[2] = 1.0;
        return 0.0;
    }
    double x = 0.0;
    for (int it = 0; it < 64 && sym3_newton_step(&p, &x); ++it) {
    }
    return sym3_finish(&p, x, v);
}

void facet_sym3_smallest_eigenvector2(const double a[6], const double b[6], double va[3], double vb[3])
{
    sym3_problem pa, pb;
    if (!sym3_prepare(a, &pa) || !sym3_prepare(b, &pb)) {
        facet_sym3_smallest_eigenvector(a, va);
        facet_sym3_smallest_eigenvector(b, vb);
        return;
    }
    /* Newton's steps are a chain of dependent divisions: two independent
     * chains in one loop let the processor overlap them. Each matrix takes
     * exactly the steps it takes alone, so the results are the same bits. */
    double x = 0.0, y = 0.0;
    int run_x = 1, run_y = 1;
    for (int it = 0; it < 64 && (run_x || run_y); ++it) {
        if (run_x)
            run_x = sym3_newton_step(&pa, &x);
        if (run_y)
            run_y = sym3_newton_step(&pb, &y);
    }
    sym3_finish(&pa, x, va);
    sym3_finish(&pb, y, vb);
}

/* Plane of the points p[idx[k]] (or p[k] when idx is NULL). Returns the
 * smallest scatter eigenvalue; writes the unit normal and the centroid. */
static double fit_plane_indexed(int32_t n, const double *xyz, const int32_t *idx, double normal[3],
                                double centroid[3])
{
    double c[3] = {0.0, 0.0, 0.0};
    for (int32_t k = 0; k < n; ++k) {
        const double *p = xyz + 3 * (size_t)(idx ? idx[k] : k);
        c[0] += p[0], c[1] += p[1], c[2] += p[2];
    }
    const double inv = 1.0 / (double)n;
    c[0] *= inv, c[1] *= inv, c[2] *= inv;
    double a[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    for (int32_t k = 0; k < n; ++k) {
        const double *p = xyz + 3 * (size_t)(idx ? idx[k] : k);
        const double x = p[0] - c[0], y = p[1] - c[1], z = p[2] - c[2];
        a[0] += x * x, a[1] += x * y, a[2] += x * z;
        a[3] += y * y, a[4] += y * z, a[5] += z * z;
    }
    centroid[0] = c[0], centroid[1] = c[1], centroid[2] = c[2];
    return facet_sym3_smallest_eigenvector(a, normal);
}

double facet_fit_plane(int32_t n, const double *xyz, double normal[3], double *offset)
{
    if (n < 3 || !xyz || !normal)
        return -1.0;
    for (int32_t k = 0; k < 3 * n; ++k)
        if (!isfinite(xyz[k]))
            return -1.0;
    double c[3];
    const double lambda = fit_plane_indexed(n, xyz, NULL, normal, c);
    if (offset)
        *offset = -dot3(normal, c);
    return lambda;
}

double facet_face_measure(int32_t n, const double *xyz, const int32_t *idx, double normal[3],
                          double *offset, double *max_distance, double *rms_distance)
{
    double c[3];
    fit_plane_indexed(n, xyz, idx, normal, c);
    double dmax = 0.0, dsum = 0.0, esum = 0.0;
    for (int32_t k = 0; k < n; ++k) {
        const double *p = xyz + 3 * (size_t)idx[k];
        const double *q = xyz + 3 * (size_t)idx[k + 1 < n ? k + 1 : 0];
        const double d = fabs(normal[0] * (p[0] - c[0]) + normal[1] * (p[1] - c[1]) +
                              normal[2] * (p[2] - c[2]));
        if (d > dmax) /* fmax without the libm call */
            dmax = d;
        dsum += d * d;
        const double e[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
        esum += sqrt(dot3(e, e));
    }
    if (offset)
        *offset = -dot3(normal, c);
    if (max_distance)
        *max_distance = dmax;
    if (rms_distance)
        *rms_distance = sqrt(dsum / (double)n);
    return esum / (double)n;
}

/* ---- faces in SIMD lanes ---------------------------------------------------
 * fit_lanes.inc, once on vectors of four doubles (every copy: baseline,
 * AVX2, AVX-512) and once on vectors of eight (the AVX-512 copy). */
#if FACET_HAVE_AVX2_CLONE
int facet_simd_max_level = 2;
#endif

#define VD v4d
#define VI v4i
#define VW 4
#define VLANES(e) {e(0), e(1), e(2), e(3)}
#define VSEL v4_select
#define VABS v4_abs
#define VANY v4_any
#define VSQRT v4_sqrt
#define F(name) name##_w4
#define LANES_T lanes_w4
#define LANES_TARGET
#include "fit_lanes.inc" /* which undefines them */

#if FACET_HAVE_AVX2_CLONE
#define VD v8d
#define VI v8i
#define VW 8
#define VLANES(e) {e(0), e(1), e(2), e(3), e(4), e(5), e(6), e(7)}
#define VSEL v8_select
#define VABS v8_abs
#define VANY v8_any
#define VSQRT v8_sqrt
#define F(name) name##_w8
#define LANES_T lanes_w8
#define LANES_TARGET FACET_TARGET_AVX512 /* lowered for the target before they are inlined */
#include "fit_lanes.inc" /* which undefines them */
#endif

/* Quads get their own copy (n a constant: loops unrolled). */
#define FACE_MEASURE4_ARGS                                                                         \
    const double *xyz, const int32_t *idx, double normal[12], double offset[4],                    \
        double max_distance[4], double square_sum[4], double edge_mean[4], const double *floor,    \
        double *corner_cos, uint8_t *guard
#define FACE_MEASURE4_CALL(n_)                                                                     \
    face_measure_lanes_w4((n_), xyz, idx, normal, offset, max_distance, square_sum, edge_mean, floor, \
                        corner_cos, guard)

#if FACET_HAVE_AVX2_CLONE
FACET_TARGET_AVX2 static int face_measure4_avx2(int n, FACE_MEASURE4_ARGS)
{
    return n == 4 ? FACE_MEASURE4_CALL(4) : FACE_MEASURE4_CALL(n);
}

FACET_TARGET_AVX512 static int face_measure4_avx512(int n, FACE_MEASURE4_ARGS)
{
    return n == 4 ? FACE_MEASURE4_CALL(4) : FACE_MEASURE4_CALL(n);
}
#endif

static int face_measure4_base(int n, FACE_MEASURE4_ARGS)
{
    return n == 4 ? FACE_MEASURE4_CALL(4) : FACE_MEASURE4_CALL(n);
}

int facet_face_measure4(int32_t n, FACE_MEASURE4_ARGS)
{
#if FACET_HAVE_AVX2_CLONE
    const int level = facet_simd_level();
    if (level == 2)
        return face_measure4_avx512((int)n, xyz, idx, normal, offset, max_distance, square_sum, edge_mean,
                                    floor, corner_cos, guard);
    if (level == 1)
        return face_measure4_avx2((int)n, xyz, idx, normal, offset, max_distance, square_sum, edge_mean,
                                  floor, corner_cos, guard);
#endif
    return face_measure4_base((int)n, xyz, idx, normal, offset, max_distance, square_sum, edge_mean, floor,
                              corner_cos, guard);
}

#define FACE_MEASURE8_ARGS                                                                         \
    const double *xyz, const int32_t *idx_a, const int32_t *idx_b, double normal[24], double offset[8], \
        double max_distance[8], double square_sum[8], double edge_mean[8], const double *floor,    \
        double *corner_cos, uint8_t *guard
#define FACE_MEASURE16_ARGS                                                                        \
    const double *xyz, const int32_t *idx, double normal[48], double offset[16], double max_distance[16], \
        double square_sum[16], double edge_mean[16], const double *floor, double *corner_cos,          \
        uint8_t *guard
/* two sets of four side by side (fit_lanes.inc) */
#define FACE_MEASURE8_CALL(na_, nb_)                                                               \
    face_measure_pair_w4((na_), (nb_), xyz, idx_a, idx_b, normal, offset, max_distance, square_sum, \
                         edge_mean, floor, corner_cos, guard)

#if FACET_HAVE_AVX2_CLONE
FACET_TARGET_AVX2 static int face_measure8_avx2(int na, int nb, FACE_MEASURE8_ARGS)
{
    return na == 4 && nb == 4 ? FACE_MEASURE8_CALL(4, 4) : FACE_MEASURE8_CALL(na, nb);
}

/* Eight faces of one size, one after another in idx: in one vector of
 * eight lanes (half the instructions of two fours, and no spills). */
#define FACE_MEASURE_W8_CALL(n_)                                                                   \
    face_measure_lanes_w8((n_), xyz, idx_a, normal, offset, max_distance, square_sum, edge_mean,    \
                          floor, corner_cos, guard)

FACET_TARGET_AVX512 static int face_measure8_avx512(int na, int nb, FACE_MEASURE8_ARGS)
{
    if (na == nb && idx_b == idx_a + 4 * na)
        return na == 4 ? FACE_MEASURE_W8_CALL(4) : FACE_MEASURE_W8_CALL(na);
    return na == 4 && nb == 4 ? FACE_MEASURE8_CALL(4, 4) : FACE_MEASURE8_CALL(na, nb);
}

/* Sixteen faces of n corners, one after another in idx: two vectors of eight
 * side by side. */
FACET_TARGET_AVX512 static int face_measure16_avx512(int n, FACE_MEASURE16_ARGS)
{
#define FACE_MEASURE16_CALL(n_)                                                                    \
    face_measure_pair_w8((n_), (n_), xyz, idx, idx + 8 * (n_), normal, offset, max_distance,        \
                         square_sum, edge_mean, floor, corner_cos, guard)
    return n == 4 ? FACE_MEASURE16_CALL(4) : FACE_MEASURE16_CALL(n);
#undef FACE_MEASURE16_CALL
}
#endif

static int face_measure8_base(int na, int nb, FACE_MEASURE8_ARGS)
{
    return na == 4 && nb == 4 ? FACE_MEASURE8_CALL(4, 4) : FACE_MEASURE8_CALL(na, nb);
}

int facet_face_measure8(int32_t na, int32_t nb, FACE_MEASURE8_ARGS)
{
#if FACET_HAVE_AVX2_CLONE
    const int level = facet_simd_level();
    if (level == 2)
        return face_measure8_avx512((int)na, (int)nb, xyz, idx_a, idx_b, normal, offset, max_distance,
                                    square_sum, edge_mean, floor, corner_cos, guard);
    if (level == 1)
        return face_measure8_avx2((int)na, (int)nb, xyz, idx_a, idx_b, normal, offset, max_distance,
                                  square_sum, edge_mean, floor, corner_cos, guard);
#endif
    return face_measure8_base((int)na, (int)nb, xyz, idx_a, idx_b, normal, offset, max_distance, square_sum,
                              edge_mean, floor, corner_cos, guard);
}

int facet_face_measure16(int32_t n, FACE_MEASURE16_ARGS)
{
#if FACET_HAVE_AVX2_CLONE
    if (facet_simd_level() == 2)
        return face_measure16_avx512((int)n, xyz, idx, normal, offset, max_distance, square_sum, edge_mean,
                                     floor, corner_cos, guard);
#endif
    const int below = facet_face_measure8(n, n, xyz, idx, idx + 4 * n, normal, offset, max_distance,
                                          square_sum, edge_mean, floor, corner_cos, guard);
    return facet_face_measure8(n, n, xyz, idx + 8 * n, idx + 12 * n, normal + 24, offset + 8,
                               max_distance + 8, square_sum + 8, edge_mean + 8, floor ? floor + 8 * n : NULL,
                               floor ? corner_cos + 8 * n : NULL, floor ? guard + 8 : NULL) ||
           below;
}

/* Distance between the diagonal lines of a quad over the mean diagonal length
 * (libigl's quad_planarity, made safe for parallel diagonals). */
static double quad_diagonal_measure(const double *xyz, const int32_t *idx)
{
    const double *v0 = xyz + 3 * (size_t)idx[0], *v1 = xyz + 3 * (size_t)idx[1];
    const double *v2 = xyz + 3 * (size_t)idx[2], *v3 = xyz + 3 * (size_t)idx[3];
    const double d1[3] = {v2[0] - v0[0], v2[1] - v0[1], v2[2] - v0[2]};
    const double d2[3] = {v3[0] - v1[0], v3[1] - v1[1], v3[2] - v1[2]};
    const double w[3] = {v1[0] - v0[0], v1[1] - v0[1], v1[2] - v0[2]};
    const double l1 = sqrt(dot3(d1, d1)), l2 = sqrt(dot3(d2, d2));
    const double mean = 0.5 * (l1 + l2);
    if (!(mean > 0.0))
        return 0.0;
    double c[3];
    cross3(d1, d2, c);
    const double nc = sqrt(dot3(c, c));
    double distance;
    if (nc > 1e-12 * l1 * l2) {
        distance = fabs(dot3(c, w)) / nc;
    } else if (l1 > 0.0) { /* parallel diagonals: distance of v1 from line 1 */
        double t[3];
        cross3(w, d1, t);
        distance = sqrt(dot3(t, t)) / l1;
    } else {
        distance = 0.0;
    }
    return distance / mean;
}

facet_status facet_planarity(const facet_mesh *mesh, int threads, double *max_abs,
                             double *rms_abs, double *mean_edge, double *diagonal,
                             facet_error *error)
{
    facet_error_clear(error);
    facet_status status = facet_mesh_check_measurable(mesh, error);
    if (status != FACET_OK)
        return status;
    const int32_t nf = mesh->n_faces;
    const int32_t *start = mesh->face_start, *fv = mesh->face_vertices;
    const double *xyz = mesh->xyz;
    const int nthreads = facet_thread_count(threads);
    (void)nthreads;
#pragma omp parallel for schedule(static) num_threads(nthreads)
    for (int32_t f = 0; f < nf; ++f) {
        const int32_t n = start[f + 1] - start[f];
        const int32_t *idx = fv + start[f];
        if (n < 1) {
            if (max_abs)
                max_abs[f] = 0.0;
            if (rms_abs)
                rms_abs[f] = 0.0;
            if (mean_edge)
                mean_edge[f] = 0.0;
            if (diagonal)
                diagonal[f] = -1.0;
            continue;
        }
        double normal[3], dmax, drms;
        const double edge = facet_face_measure(n, xyz, idx, normal, NULL, &dmax, &drms);
        if (max_abs)
            max_abs[f] = dmax;
        if (rms_abs)
            rms_abs[f] = drms;
        if (mean_edge)
            mean_edge[f] = edge;
        if (diagonal)
            diagonal[f] = n == 4 ? quad_diagonal_measure(xyz, idx) : -1.0;
    }
    return FACET_OK;
}
