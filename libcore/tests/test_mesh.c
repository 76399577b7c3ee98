/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Validation: every bad input gives its status and a message naming it. */
#include "check.h"
#include "facet.h"
#include "test_meshes.h"

#include <string.h>

static facet_mesh make(int32_t nv, const double *xyz, int32_t nf, const int32_t *start,
                       const int32_t *fv)
{
    facet_mesh m = {nv, nf, xyz, start, fv};
    return m;
}

int main(void)
{
    const double xyz[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0};
    const int32_t start[] = {0, 4};
    const int32_t quad[] = {0, 1, 2, 3};
    facet_error e;
    facet_mesh_report r;

    facet_mesh m = make(4, xyz, 1, start, quad);
    CHECK_STATUS(facet_mesh_validate(&m, &r, &e), FACET_OK);
    CHECK(r.n_edges == 4 && r.n_boundary_edges == 4 && r.max_degree == 4);

    m = make(0, xyz, 0, start, quad);
    CHECK_STATUS(facet_mesh_validate(&m, &r, &e), FACET_ERROR_EMPTY_MESH);
    CHECK(strstr(e.message, "empty") != NULL);

    const int32_t bad_index[] = {0, 1, 2, 7};
    m = make(4, xyz, 1, start, bad_index);
    CHECK_STATUS(facet_mesh_validate(&m, &r, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);
    CHECK(e.face == 0 && e.vertex == -1); /* 7 is not a vertex */
    CHECK(strcmp(e.message, "face 0 has vertex index 7 out of range (4 vertices)") == 0);

    const int32_t negative[] = {0, 1, -2, 3};
    m = make(4, xyz, 1, start, negative);
    CHECK_STATUS(facet_mesh_validate(&m, &r, &e), FACET_ERROR_INDEX_OUT_OF_RANGE);

    const int32_t repeated[] = {0, 1, 2, 1};
    m = make(4, xyz, 1, start, repeated);
    CHECK_STATUS(facet_mesh_validate(&m, &r, &e), FACET_ERROR_REPEATED_VERTEX);
    CHECK(strcmp(e.message, "face 0 repeats vertex 1") == 0);

    const int32_t two_distinct[] = {0, 1, 0, 1};
    m = make(4, xyz, 1, start, two_distinct);
    CHECK_STATUS(facet_mesh_validate(&m, &r, &e), FACET_ERROR_DEGENERATE_FACE);

    const int32_t start2[] = {0, 2};
    m = make(4, xyz, 1, start2, quad);
    CHECK_STATUS(facet_mesh_validate(&m, &r, &e), FACET_ERROR_DEGENERATE_FACE);
    CHECK(strstr(e.message, "face 0 has 2 vertices") != NULL);

    const int32_t bad_start[] = {1, 4};
    m = make(4, xyz, 1, bad_start, quad);
    CHECK_STATUS(facet_mesh_validate(&m, &r, &e), FACET_ERROR_BAD_FACE_START);

    double nan_xyz[15];
    memcpy(nan_xyz, xyz, sizeof nan_xyz);
    nan_xyz[7] = NAN;
    m = make(4, nan_xyz, 1, start, quad);
    CHECK_STATUS(facet_mesh_validate(&m, &r, &e), FACET_ERROR_NONFINITE);
    CHECK(e.vertex == 2 && strstr(e.message, "vertex 2") != NULL);
    nan_xyz[7] = INFINITY;
    CHECK_STATUS(facet_mesh_validate(&m, &r, &e), FACET_ERROR_NONFINITE);

    /* isolated vertex 4: a warning, not an error */
    m = make(5, xyz, 1, start, quad);
    CHECK_STATUS(facet_mesh_validate(&m, &r, &e), FACET_WARNING_MESH);
    CHECK(r.n_isolated_vertices == 1 && r.first_isolated_vertex == 4);

    /* three triangles on one edge: non-manifold */
    const double fan_xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1};
    const int32_t fan_start[] = {0, 3, 6, 9};
    const int32_t fan[] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    m = make(5, fan_xyz, 3, fan_start, fan);
    CHECK_STATUS(facet_mesh_validate(&m, &r, &e), FACET_WARNING_MESH);
    CHECK(r.n_non_manifold_edges == 1 && r.first_non_manifold_edge[0] == 0 &&
          r.first_non_manifold_edge[1] == 1);

    CHECK_STATUS(facet_mesh_validate(NULL, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK(strcmp(facet_status_string(FACET_ERROR_REPEATED_VERTEX), "vertex repeated in a face") == 0);

    /* a grid: interior edges are manifold */
    test_mesh g = test_grid(5, 4, 0.5, 1.0, 0.0);
    CHECK_STATUS(facet_mesh_validate(&g.mesh, &r, &e), FACET_OK);
    CHECK(r.n_edges == 5 * 5 + 6 * 4 && r.n_boundary_edges == 2 * (5 + 4));
    test_mesh_free(&g);
    return check_report("test_mesh");
}
