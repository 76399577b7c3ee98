/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Face shape for the quality report: smallest interior angle, vector area,
 * change of the relative edge lengths against the input. */
#include "internal.h"

#include <math.h>

#define TWO_PI 6.283185307179586476925286766559

void facet_newell(int32_t n, const double *xyz, const int32_t *idx, double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    /* about the first vertex, so large coordinates do not swamp the sum */
    const double *o = xyz + 3 * (size_t)idx[0];
    for (int32_t k = 0; k < n; ++k) {
        const double *p = xyz + 3 * (size_t)idx[k];
        const double *q = xyz + 3 * (size_t)idx[k + 1 < n ? k + 1 : 0];
        const double a[3] = {p[0] - o[0], p[1] - o[1], p[2] - o[2]};
        const double b[3] = {q[0] - o[0], q[1] - o[1], q[2] - o[2]};
        out[0] += a[1] * b[2] - a[2] * b[1];
        out[1] += a[2] * b[0] - a[0] * b[2];
        out[2] += a[0] * b[1] - a[1] * b[0];
    }
}

static double edge_length(const double *xyz, int32_t u, int32_t v)
{
    const double *p = xyz + 3 * (size_t)u, *q = xyz + 3 * (size_t)v;
    const double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* Smallest interior angle of a face, turning about its Newell normal nrm
 * (unit, or 0 for a face without area: then the unsigned angles). */
static double smallest_angle(int32_t n, const double *xyz, const int32_t *idx, const double nrm[3])
{
    double smallest = TWO_PI;
    for (int32_t k = 0; k < n; ++k) {
        const double *p = xyz + 3 * (size_t)idx[k];
        const double *next = xyz + 3 * (size_t)idx[k + 1 < n ? k + 1 : 0];
        const double *prev = xyz + 3 * (size_t)idx[k > 0 ? k - 1 : n - 1];
        const double a[3] = {next[0] - p[0], next[1] - p[1], next[2] - p[2]};
        const double b[3] = {prev[0] - p[0], prev[1] - p[1], prev[2] - p[2]};
        const double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        const double lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
        if (!(la > 0.0) || !(lb > 0.0)) {
            smallest = 0.0;
            continue;
        }
        const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                             a[0] * b[1] - a[1] * b[0]};
        const double cos_part = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        const double sin_abs = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        double angle = atan2(sin_abs, cos_part); /* in [0, pi] */
        /* counter-clockwise about the normal from next to prev: the interior
         * side; a reflex corner turns the other way */
        const double side = c[0] * nrm[0] + c[1] * nrm[1] + c[2] * nrm[2];
        if (side < 0.0)
            angle = TWO_PI - angle;
        if (angle < smallest)
            smallest = angle;
    }
    return smallest;
}

/* Whether two edges of a face cross (not at a shared corner) when the face
 * is seen along its normal: the face then folds over itself (a bowtie), and
 * its signed corners (smallest_angle) would count the fold's narrow corner
 * as reflex. In the plane of the two axes other than the normal's largest;
 * a strict orientation test, so edges that only touch or lie on one line do
 * not count. */
static double orient2(const double *a, const double *b, const double *c, int u, int v)
{
    return (b[u] - a[u]) * (c[v] - a[v]) - (b[v] - a[v]) * (c[u] - a[u]);
}

int facet_face_folds(int32_t n, const double *xyz, const int32_t *idx, const double nrm[3])
{
    /* a triangle cannot fold; a face without area has no side to see it from */
    if (n < 4 || (nrm[0] == 0.0 && nrm[1] == 0.0 && nrm[2] == 0.0))
        return 0;
    const double ax = fabs(nrm[0]), ay = fabs(nrm[1]), az = fabs(nrm[2]);
    const int drop = ax >= ay && ax >= az ? 0 : (ay >= az ? 1 : 2);
    const int u = drop == 0 ? 1 : 0, v = drop == 2 ? 1 : 2;
    for (int32_t i = 0; i < n; ++i) {
        const double *a = xyz + 3 * (size_t)idx[i], *b = xyz + 3 * (size_t)idx[(i + 1) % n];
        /* the edges j that share no corner with edge i */
        for (int32_t j = i + 2; j < n; ++j) {
            if (i == 0 && j == n - 1)
                continue;
            const double *c = xyz + 3 * (size_t)idx[j], *d = xyz + 3 * (size_t)idx[(j + 1) % n];
            const double o1 = orient2(a, b, c, u, v), o2 = orient2(a, b, d, u, v);
            const double o3 = orient2(c, d, a, u, v), o4 = orient2(c, d, b, u, v);
            if (((o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0)) &&
                ((o3 > 0.0 && o4 < 0.0) || (o3 < 0.0 && o4 > 0.0)))
                return 1;
        }
    }
    return 0;
}

facet_status facet_face_shape(const facet_mesh *mesh, const double *xyz_input, int32_t threads,
                              double *min_angle, double *area, double *ratio_change,
                              facet_error *error)
{
    facet_error_clear(error);
    facet_status status = facet_mesh_check_measurable(mesh, error);
    if (status != FACET_OK)
        return status;
    if (xyz_input) {
        status = facet_check_finite(mesh->n_vertices, xyz_input, "input vertex", error);
        if (status != FACET_OK)
            return status;
    }
    const int32_t nf = mesh->n_faces;
    const int32_t *start = mesh->face_start, *fv = mesh->face_vertices;
    const double *xyz = mesh->xyz;
    const int nthreads = facet_thread_count(threads);
    (void)nthreads;
#pragma omp parallel for schedule(static) num_threads(nthreads)
    for (int32_t f = 0; f < nf; ++f) {
        const int32_t n = start[f + 1] - start[f];
        const int32_t *idx = fv + start[f];
        if (n < 3) {
            if (min_angle)
                min_angle[f] = 0.0;
            if (area)
                area[f] = 0.0;
            if (ratio_change)
                ratio_change[f] = 0.0;
            continue;
        }
        double nrm[3];
        facet_newell(n, xyz, idx, nrm);
        const double len = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        if (area)
            area[f] = 0.5 * len;
        if (min_angle) {
            double unit[3] = {0.0, 0.0, 0.0};
            if (len > 0.0)
                unit[0] = nrm[0] / len, unit[1] = nrm[1] / len, unit[2] = nrm[2] / len;
            /* a face folded over itself has no interior: 0, as for a
             * face without area */
            min_angle[f] = facet_face_folds(n, xyz, idx, unit) ? 0.0 : smallest_angle(n, xyz, idx, unit);
        }
        if (ratio_change) {
            double change = 0.0;
            if (xyz_input) {
                double sum_out = 0.0, sum_in = 0.0;
                for (int32_t k = 0; k < n; ++k) {
                    const int32_t u = idx[k], v = idx[k + 1 < n ? k + 1 : 0];
                    sum_out += edge_length(xyz, u, v);
                    sum_in += edge_length(xyz_input, u, v);
                }
                if (!(sum_out > 0.0) && sum_in > 0.0) {
                    change = 1.0; /* every edge shrank to nothing */
                } else if (sum_out > 0.0 && sum_in > 0.0) {
                    for (int32_t k = 0; k < n; ++k) {
                        const int32_t u = idx[k], v = idx[k + 1 < n ? k + 1 : 0];
                        const double r_in = edge_length(xyz_input, u, v) / sum_in;
                        if (!(r_in > 0.0))
                            continue;
                        const double r_out = edge_length(xyz, u, v) / sum_out;
                        change = fmax(change, fabs(r_out / r_in - 1.0));
                    }
                }
            }
            ratio_change[f] = change;
        }
    }
    return FACET_OK;
}
