/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Plane fit, eigenvectors and the per-face measures against known answers. */
#include "check.h"
#include "facet.h"

#include <string.h>

int main(void)
{
    /* points on the plane x + 2y + 2z = 3 (unit normal (1,2,2)/3, offset -1) */
    const double pts[] = {3, 0, 0, 1, 1, 0, 1, 0, 1, -1, 1, 1, 5, -1, 0};
    double n[3], d;
    double lambda = facet_fit_plane(5, pts, n, &d);
    const double sign = n[0] > 0 ? 1.0 : -1.0;
    CHECK_NEAR(n[0] * sign, 1.0 / 3.0, 1e-15);
    CHECK_NEAR(n[1] * sign, 2.0 / 3.0, 1e-15);
    CHECK_NEAR(n[2] * sign, 2.0 / 3.0, 1e-15);
    CHECK_NEAR(d * sign, -1.0, 1e-14);
    CHECK(fabs(lambda) < 1e-13);
    CHECK(facet_fit_plane(2, pts, n, &d) == -1.0);

    /* collinear points: a unit normal perpendicular to the line */
    const double line[] = {0, 0, 0, 1, 1, 1, 2, 2, 2};
    facet_fit_plane(3, line, n, &d);
    CHECK_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-15);
    CHECK_NEAR(n[0] + n[1] + n[2], 0.0, 1e-15);

    /* a twisted unit square: corners at heights +h, -h, +h, -h. The best-fit
     * plane is z = 0, every corner is h from it, and the diagonals are 2h apart. */
    const double h = 0.05;
    const double quad_xyz[] = {0, 0, h, 1, 0, -h, 1, 1, h, 0, 1, -h};
    const int32_t start[] = {0, 4};
    const int32_t quad[] = {0, 1, 2, 3};
    facet_mesh m = {4, 1, quad_xyz, start, quad};
    double max_abs, rms_abs, mean_edge, diagonal;
    facet_error e;
    CHECK_STATUS(facet_planarity(&m, 1, &max_abs, &rms_abs, &mean_edge, &diagonal, &e), FACET_OK);
    CHECK_NEAR(max_abs, h, 1e-15);
    CHECK_NEAR(rms_abs, h, 1e-15);
    CHECK_NEAR(mean_edge, sqrt(1.0 + 4 * h * h), 1e-15);
    const double diag_len = sqrt(2.0);
    CHECK_NEAR(diagonal, 2 * h / diag_len, 1e-15);

    /* a planar pentagon in a tilted plane at georeferenced offset */
    const double off = 2.5e6;
    double pent[15];
    for (int k = 0; k < 5; ++k) {
        const double a = 2 * M_PI * k / 5.0, u = cos(a), v = sin(a);
        pent[3 * k] = off + u;
        pent[3 * k + 1] = off + 0.6 * v;
        pent[3 * k + 2] = 100.0 + 0.8 * v;
    }
    const int32_t pstart[] = {0, 5};
    const int32_t pface[] = {0, 1, 2, 3, 4};
    facet_mesh mp = {5, 1, pent, pstart, pface};
    CHECK_STATUS(facet_planarity(&mp, 2, &max_abs, &rms_abs, &mean_edge, &diagonal, &e), FACET_OK);
    CHECK(max_abs < 1e-9);
    CHECK(diagonal == -1.0);

    /* out-of-range index is caught, not read */
    const int32_t bad[] = {0, 1, 2, 9};
    facet_mesh mb = {4, 1, quad_xyz, start, bad};
    CHECK_STATUS(facet_planarity(&mb, 1, &max_abs, NULL, NULL, NULL, &e),
                 FACET_ERROR_INDEX_OUT_OF_RANGE);
    return check_report("test_planarity");
}
