/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Face shape measures against known answers. */
#include "check.h"
#include "facet.h"

#include <string.h>

int main(void)
{
    /* a 2 x 1 rectangle, a right triangle (30-60-90), an L-shaped hexagon
     * (one reflex corner of 270 degrees) */
    const double s3 = sqrt(3.0);
    const double xyz[] = {0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0,               /* 0-3 */
                          10, 0, 0, 10 + s3, 0, 0, 10, 1, 0,                 /* 4-6 */
                          20, 0, 0, 22, 0, 0, 22, 1, 0, 21, 1, 0, 21, 2, 0, 20, 2, 0}; /* 7-12 */
    const int32_t start[] = {0, 4, 7, 13};
    const int32_t fv[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    facet_mesh m = {13, 3, xyz, start, fv};
    double angle[3], area[3], change[3];
    facet_error e;
    CHECK_STATUS(facet_face_shape(&m, NULL, 1, angle, area, change, &e), FACET_OK);
    CHECK_NEAR(angle[0], M_PI / 2, 1e-15);
    CHECK_NEAR(angle[1], M_PI / 6, 1e-15);
    CHECK_NEAR(angle[2], M_PI / 2, 1e-15); /* the reflex corner is 3 pi / 2, not pi / 2 */
    CHECK_NEAR(area[0], 2.0, 1e-15);
    CHECK_NEAR(area[1], s3 / 2, 1e-15);
    CHECK_NEAR(area[2], 3.0, 1e-14);
    CHECK(change[0] == 0.0 && change[1] == 0.0 && change[2] == 0.0);

    /* the same faces turned over (clockwise): the same angles */
    const int32_t fv_rev[] = {3, 2, 1, 0, 6, 5, 4, 12, 11, 10, 9, 8, 7};
    facet_mesh mr = {13, 3, xyz, start, fv_rev};
    CHECK_STATUS(facet_face_shape(&mr, NULL, 2, angle, NULL, NULL, &e), FACET_OK);
    CHECK_NEAR(angle[0], M_PI / 2, 1e-15);
    CHECK_NEAR(angle[1], M_PI / 6, 1e-15);
    CHECK_NEAR(angle[2], M_PI / 2, 1e-15);

    /* ratio change: the rectangle stretched to 4 x 1: mean edge 2.5 (was 1.5);
     * long edges 4/2.5 = 1.6 vs 2/1.5: 1.2 - 1 = 0.2; short edges 0.4 vs
     * 0.6667: |0.6 - 1| = 0.4. Scaling the whole face changes nothing. */
    double moved[39];
    memcpy(moved, xyz, sizeof moved);
    moved[3] = 4, moved[6] = 4;
    for (int k = 12; k < 39; ++k)
        moved[k] = 3.0 * xyz[k];
    facet_mesh mm = {13, 3, moved, start, fv};
    CHECK_STATUS(facet_face_shape(&mm, xyz, 0, NULL, NULL, change, &e), FACET_OK);
    CHECK_NEAR(change[0], 0.4, 1e-15);
    CHECK_NEAR(change[1], 0.0, 1e-15);
    CHECK_NEAR(change[2], 0.0, 1e-15);

    /* a face collapsed to a point: angle 0, area 0, no NaN */
    const double point[] = {1, 1, 1, 1, 1, 1, 1, 1, 1};
    const int32_t tstart[] = {0, 3};
    const int32_t tri[] = {0, 1, 2};
    facet_mesh mp = {3, 1, point, tstart, tri};
    const double before[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    CHECK_STATUS(facet_face_shape(&mp, before, 0, angle, area, change, &e), FACET_OK);
    CHECK(angle[0] == 0.0 && area[0] == 0.0 && change[0] == 1.0);

    const int32_t bad[] = {0, 1, 5};
    facet_mesh mb = {3, 1, point, tstart, bad};
    CHECK_STATUS(facet_face_shape(&mb, NULL, 0, angle, NULL, NULL, &e),
                 FACET_ERROR_INDEX_OUT_OF_RANGE);
    return check_report("test_quality");
}
