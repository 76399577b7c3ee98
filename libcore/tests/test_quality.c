/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Face shape measures against known answers. */
#include "check.h"
#include "facet.h"

#include <math.h>
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

    /* a bowtie: edges 0-1 and 2-3 cross at (2/3, 2/3). Its lobes have
     * different areas, so the Newell normal is the larger's, and the
     * smaller lobe's narrow corner (at 3, about 63 degrees) turns the other
     * way and counts as reflex; the face folds over itself, so 0. The same
     * points as 0-2-1-3 (no fold) and a dart (a non-convex quad whose
     * reflex corner does not fold) keep their angles. Tilted out of the
     * axes' planes and moved to large coordinates. */
    {
        const double c = cos(0.3), sn = sin(0.3);
        const double flat[] = {0, 0, 0, 2, 2, 0, 2, 0, 0, 0, 1, 0,  /* bowtie 0-1-2-3 */
                               0, 0, 0, 4, 0, 0, 1, 1, 0, 0, 4, 0}; /* dart 4-7 */
        double tilted[24];
        for (int k = 0; k < 8; ++k) { /* about the x axis, then lifted */
            const double *p = flat + 3 * k;
            tilted[3 * k] = p[0] + 1e6;
            tilted[3 * k + 1] = c * p[1] - sn * p[2];
            tilted[3 * k + 2] = sn * p[1] + c * p[2] + 2e5;
        }
        const int32_t qstart[] = {0, 4, 8, 12};
        const int32_t qfv[] = {0, 1, 2, 3, 0, 2, 1, 3, 4, 5, 6, 7};
        facet_mesh mq = {8, 3, tilted, qstart, qfv};
        CHECK_STATUS(facet_face_shape(&mq, NULL, 1, angle, area, NULL, &e), FACET_OK);
        CHECK(angle[0] == 0.0);
        CHECK_NEAR(area[0], 1.0, 1e-9); /* the lobes: 4/3 and 1/3, turning opposite ways */
        CHECK(angle[1] > 0.3); /* 0-2-1-3: a quad with corners of 45 degrees and more */
        /* the dart: corners 90 at 4, 45-ish at 5 and 7, reflex at 6 */
        const double dart = atan2(1.0, 3.0); /* at 5: between (-4, 0) and (-3, 1) */
        CHECK_NEAR(angle[2], dart, 1e-9);
    }

    const int32_t bad[] = {0, 1, 5};
    facet_mesh mb = {3, 1, point, tstart, bad};
    CHECK_STATUS(facet_face_shape(&mb, NULL, 0, angle, NULL, NULL, &e),
                 FACET_ERROR_INDEX_OUT_OF_RANGE);
    return check_report("test_quality");
}
