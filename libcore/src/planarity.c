/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Least-squares planes and per-face planarity measures. */
#include "internal.h"

#include <math.h>
#include <stdlib.h>

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
 * product of two rows of (A - lambda I). */
double facet_sym3_smallest_eigenvector(const double a[6], double v[3])
{
    double scale = 0.0;
    for (int k = 0; k < 6; ++k)
        scale = fmax(scale, fabs(a[k]));
    if (!(scale > 0.0)) {
        v[0] = 0.0, v[1] = 0.0, v[2] = 1.0;
        return 0.0;
    }
    const double inv = 1.0 / scale;
    const double b00 = a[0] * inv, b01 = a[1] * inv, b02 = a[2] * inv;
    const double b11 = a[3] * inv, b12 = a[4] * inv, b22 = a[5] * inv;
    const double c2 = b00 + b11 + b22;
    const double c1 = b00 * b11 - b01 * b01 + b00 * b22 - b02 * b02 + b11 * b22 - b12 * b12;
    const double c0 = b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) +
                      b02 * (b01 * b12 - b11 * b02);
    /* f(x) = x^3 - c2 x^2 + c1 x - c0 */
    double x = 0.0;
    for (int it = 0; it < 64; ++it) {
        const double f = ((x - c2) * x + c1) * x - c0;
        const double df = (3.0 * x - 2.0 * c2) * x + c1;
        if (!(f < 0.0) || !(df > 0.0))
            break;
        const double step = f / df;
        const double next = x - step;
        if (!(next > x))
            break;
        x = next;
        if (step > -1e-17 * (1.0 + x))
            break;
    }
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
    return x * scale;
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
        dmax = fmax(dmax, d);
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
