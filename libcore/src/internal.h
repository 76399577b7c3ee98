/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Internal helpers shared by libfacet's modules. Not installed. */
#ifndef FACET_INTERNAL_H
#define FACET_INTERNAL_H

#include "facet.h"

#include <math.h>
#include <stdarg.h>

#if defined(__GNUC__)
#define FACET_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define FACET_PRINTF(a, b)
#endif

/* Fills *error (if not NULL) and returns status. */
facet_status facet_fail(facet_error *error, facet_status status, int64_t face, int64_t vertex,
                        const char *format, ...) FACET_PRINTF(5, 6);

/* Clears *error (if not NULL) to FACET_OK. */
void facet_error_clear(facet_error *error);

/* Checks array sizes and pointers of a mesh, not its contents. */
facet_status facet_mesh_check_arrays(const facet_mesh *mesh, facet_error *error);

/* Checks that every face index is in range (O(corners), no allocation). */
facet_status facet_mesh_check_indices(const facet_mesh *mesh, facet_error *error);

/* What a measurement over the faces needs: arrays (facet_mesh_check_arrays),
 * coordinates, every index in range, and finite coordinates
 * (FACET_ERROR_NONFINITE naming the first bad vertex). */
facet_status facet_mesh_check_measurable(const facet_mesh *mesh, facet_error *error);

/* FACET_ERROR_NONFINITE naming the first of n points xyz[3n] with a NaN or
 * infinite coordinate ("<what> 7 has a non-finite coordinate ..."). */
facet_status facet_check_finite(int32_t n, const double *xyz, const char *what, facet_error *error);

/* facet_mesh_validate without the coordinates when check_coordinates is 0. */
facet_status facet_mesh_validate_topology(const facet_mesh *mesh, int check_coordinates,
                                          facet_mesh_report *report, facet_error *error);

/* Smallest-eigenvalue eigenvector of a symmetric positive semi-definite 3x3
 * matrix given by its upper triangle a = {a00, a01, a02, a11, a12, a22}.
 * Writes a unit vector to v and returns the eigenvalue. */
double facet_sym3_smallest_eigenvector(const double a[6], double v[3]);

/* quality.c: a face's Newell normal (its vector area, twice: not unit),
 * about its first vertex; whether a face folds over itself: two of its
 * edges cross when seen along nrm (any length), as a bowtie's do; never for
 * a triangle or a zero nrm (a face without area). */
void facet_newell(int32_t n, const double *xyz, const int32_t *idx, double out[3]);
int facet_face_folds(int32_t n, const double *xyz, const int32_t *idx, const double nrm[3]);

/* The same for two matrices at once (the same bits as two calls; faster:
 * their Newton steps overlap). */
void facet_sym3_smallest_eigenvector2(const double a[6], const double b[6], double va[3], double vb[3]);

/* One face (the points xyz[idx[k]], k < n, in order around it): its
 * least-squares plane (unit normal, and offset with normal . x + offset = 0;
 * offset may be NULL), the largest and RMS distance of its vertices from
 * that plane (either may be NULL); returns its mean edge length. */
double facet_face_measure(int32_t n, const double *xyz, const int32_t *idx, double normal[3],
                          double *offset, double *max_distance, double *rms_distance);

/* Four faces of n corners each at once (3 <= n <= FACET_LANE_CORNERS_MAX;
 * face l is the points xyz[idx[n l + k]], k < n): for each, what
 * facet_face_measure gives, bit for bit (the same arithmetic in the same
 * order, in SIMD lanes: 4 faces per AVX2 or AVX-512 instruction where the
 * processor has it, 2 per SSE2 instruction otherwise), with the sum of
 * squared distances
 * (rms^2 n) in square_sum. Outputs are arrays of four (normal: twelve).
 * With floor not NULL (the cosines of the faces' corners' floors, corner k
 * of face l at n l + k), also the angle floor's corner test: the corners'
 * cosines where they may be below their floors (-1 elsewhere, 1 at an edge
 * without length) in corner_cos (written only when a corner of the four is
 * below its floor: the floor's targets read them only for such faces), and
 * per face whether a corner is below its floor in guard; returns whether
 * any is. */
enum { FACET_LANE_CORNERS_MAX = 8 };
int facet_face_measure4(int32_t n, const double *xyz, const int32_t *idx, double normal[12],
                        double offset[4], double max_distance[4], double square_sum[4],
                        double edge_mean[4], const double *floor, double *corner_cos, uint8_t *guard);

/* Eight faces at once: four of na corners (the points xyz[idx_a[na l + k]])
 * and four of nb (idx_b), their eigenvector solves side by side (in one
 * vector of eight lanes in the AVX-512 copy when na == nb and idx_b follows
 * idx_a); outputs as facet_face_measure4's, arrays of eight (normal: 24),
 * the first four for idx_a; floor, corner_cos: the first four faces'
 * corners, then the second four's. */
int facet_face_measure8(int32_t na, int32_t nb, const double *xyz, const int32_t *idx_a,
                        const int32_t *idx_b, double normal[24], double offset[8], double max_distance[8],
                        double square_sum[8], double edge_mean[8], const double *floor, double *corner_cos,
                        uint8_t *guard);

/* Sixteen faces of n corners, one after another in idx (the points
 * xyz[idx[n l + k]]), in two vectors of eight side by side in the AVX-512
 * copy, else as two facet_face_measure8; outputs as facet_face_measure4's,
 * arrays of sixteen (normal: 48); floor, corner_cos: the faces' corners in
 * order. */
int facet_face_measure16(int32_t n, const double *xyz, const int32_t *idx, double normal[48],
                         double offset[16], double max_distance[16], double square_sum[16],
                         double edge_mean[16], const double *floor, double *corner_cos, uint8_t *guard);

/* Sets the number of OpenMP threads for a parallel region: n <= 0 gives the
 * OpenMP default; n is clamped to max(64, 4 x processors, the default). */
int facet_thread_count(int requested);

/* max and min without fmax's call and NaN rules (callers pass no NaN). */
/* A point the library accepts: every coordinate finite and within
 * FACET_COORDINATE_MAX (NaN fails the comparison). Check isfinite first to
 * tell FACET_ERROR_NONFINITE from FACET_ERROR_COORDINATE_RANGE. */
static inline int facet_point_in_range(const double *p, int dims)
{
    for (int k = 0; k < dims; ++k)
        if (!(fabs(p[k]) <= FACET_COORDINATE_MAX))
            return 0;
    return 1;
}

static inline double facet_max(double a, double b)
{
    return a > b ? a : b;
}

static inline double facet_min(double a, double b)
{
    return a < b ? a : b;
}

/* Monotonic wall clock in seconds. */
double facet_now(void);

#endif
