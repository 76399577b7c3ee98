/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Tests' facet_panels outputs: every array allocated for a mesh of nv
 * vertices, nf faces and nc corners, the check that the double ones are all
 * finite (check.h's all_finite), and their release. */
#ifndef FACET_TEST_PANEL_OUTPUT_H
#define FACET_TEST_PANEL_OUTPUT_H

#include "check.h"
#include "facet.h"

#include <math.h>
#include <stdlib.h>

static inline facet_panel_output test_panel_output(int nv, int nf, int nc)
{
    facet_panel_output o;
    o.plane = malloc(sizeof(double) * 4 * (size_t)nf);
    o.top = malloc(sizeof(double) * 3 * (size_t)nc);
    o.bottom = malloc(sizeof(double) * 3 * (size_t)nc);
    o.frame = malloc(sizeof(double) * 12 * (size_t)nf);
    o.reversed = malloc(sizeof(int32_t) * (size_t)nf);
    o.neighbor = malloc(sizeof(int32_t) * (size_t)nc);
    o.dihedral = malloc(sizeof(double) * (size_t)nc);
    o.bevel = malloc(sizeof(double) * (size_t)nc);
    o.node_deviation = malloc(sizeof(double) * (size_t)nv);
    o.planarity = malloc(sizeof(double) * (size_t)nf);
    o.nonplanar = malloc(sizeof(int32_t) * (size_t)nf);
    return o;
}

static inline int test_panel_output_finite(const facet_panel_output *o, int nv, int nf, int nc)
{
    return all_finite(o->plane, 4 * (size_t)nf) && all_finite(o->top, 3 * (size_t)nc) &&
           all_finite(o->bottom, 3 * (size_t)nc) && all_finite(o->frame, 12 * (size_t)nf) &&
           all_finite(o->dihedral, (size_t)nc) && all_finite(o->bevel, (size_t)nc) &&
           all_finite(o->node_deviation, (size_t)nv) && all_finite(o->planarity, (size_t)nf);
}

static inline void test_panel_output_free(facet_panel_output *o)
{
    free(o->plane), free(o->top), free(o->bottom), free(o->frame), free(o->reversed);
    free(o->neighbor), free(o->dihedral), free(o->bevel), free(o->node_deviation);
    free(o->planarity), free(o->nonplanar);
}

#endif
