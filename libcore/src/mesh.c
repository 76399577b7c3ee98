/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Polygon mesh validation. */
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

facet_status facet_mesh_check_arrays(const facet_mesh *mesh, facet_error *error)
{
    if (!mesh)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1, "mesh is NULL");
    if (mesh->n_vertices <= 0 || mesh->n_faces <= 0)
        return facet_fail(error, FACET_ERROR_EMPTY_MESH, -1, -1,
                          "empty mesh: %d vertices and %d faces", (int)mesh->n_vertices,
                          (int)mesh->n_faces);
    if (!mesh->face_start || !mesh->face_vertices)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1, "mesh has no face arrays");
    if (mesh->face_start[0] != 0)
        return facet_fail(error, FACET_ERROR_BAD_FACE_START, 0, -1,
                          "face offsets must start at 0, not %d", (int)mesh->face_start[0]);
    for (int32_t f = 0; f < mesh->n_faces; ++f) {
        if (mesh->face_start[f + 1] < mesh->face_start[f])
            return facet_fail(error, FACET_ERROR_BAD_FACE_START, f, -1,
                              "face offsets decrease at face %d (%d then %d)", (int)f,
                              (int)mesh->face_start[f], (int)mesh->face_start[f + 1]);
    }
    return FACET_OK;
}

facet_status facet_mesh_check_indices(const facet_mesh *mesh, facet_error *error)
{
    for (int32_t f = 0; f < mesh->n_faces; ++f)
        for (int32_t k = mesh->face_start[f]; k < mesh->face_start[f + 1]; ++k) {
            const int32_t v = mesh->face_vertices[k];
            if (v < 0 || v >= mesh->n_vertices)
                return facet_fail(error, FACET_ERROR_INDEX_OUT_OF_RANGE, f, -1,
                                  "face %d has vertex index %d out of range (%d vertices)", (int)f,
                                  (int)v, (int)mesh->n_vertices);
        }
    return FACET_OK;
}

static int compare_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

facet_status facet_mesh_check_measurable(const facet_mesh *mesh, facet_error *error)
{
    facet_status status = facet_mesh_check_arrays(mesh, error);
    if (status != FACET_OK)
        return status;
    if (!mesh->xyz)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1, "mesh has no coordinates");
    status = facet_mesh_check_indices(mesh, error);
    if (status != FACET_OK)
        return status;
    return facet_check_finite(mesh->n_vertices, mesh->xyz, "vertex", error);
}

facet_status facet_check_finite(int32_t n, const double *xyz, const char *what, facet_error *error)
{
    for (int32_t v = 0; v < n; ++v) {
        const double *p = xyz + 3 * (size_t)v;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
            return facet_fail(error, FACET_ERROR_NONFINITE, -1, v,
                              "%s %d has a non-finite coordinate (%g, %g, %g)", what, (int)v,
                              p[0], p[1], p[2]);
    }
    return FACET_OK;
}

facet_status facet_mesh_validate(const facet_mesh *mesh, facet_mesh_report *report,
                                 facet_error *error)
{
    facet_error_clear(error);
    facet_status status = facet_mesh_check_arrays(mesh, error);
    if (status != FACET_OK)
        return status;
    if (!mesh->xyz)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1, "mesh has no coordinates");
    return facet_mesh_validate_topology(mesh, 1, report, error);
}

facet_status facet_mesh_validate_topology(const facet_mesh *mesh, int check_coordinates,
                                          facet_mesh_report *report, facet_error *error)
{
    facet_status status = facet_mesh_check_arrays(mesh, error);
    if (status != FACET_OK)
        return status;
    const int32_t nv = mesh->n_vertices, nf = mesh->n_faces;
    const int32_t *start = mesh->face_start, *fv = mesh->face_vertices;

    for (int32_t v = 0; check_coordinates && v < nv; ++v) {
        const double *p = mesh->xyz + 3 * (size_t)v;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
            return facet_fail(error, FACET_ERROR_NONFINITE, -1, v,
                              "vertex %d has a non-finite coordinate (%g, %g, %g)", (int)v, p[0],
                              p[1], p[2]);
    }

    status = facet_mesh_check_indices(mesh, error);
    if (status != FACET_OK)
        return status;

    /* Repeated vertices and degree, with a stamp per vertex. */
    int32_t *stamp = malloc(sizeof *stamp * (size_t)nv);
    if (!stamp)
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    for (int32_t v = 0; v < nv; ++v)
        stamp[v] = -1;
    int32_t max_degree = 0;
    for (int32_t f = 0; f < nf; ++f) {
        const int32_t degree = start[f + 1] - start[f];
        if (degree > max_degree)
            max_degree = degree;
        int32_t distinct = 0, repeated = -1;
        for (int32_t k = start[f]; k < start[f + 1]; ++k) {
            const int32_t v = fv[k];
            if (stamp[v] == f) {
                if (repeated < 0)
                    repeated = v;
            } else {
                stamp[v] = f;
                ++distinct;
            }
        }
        if (distinct < 3) {
            free(stamp);
            if (degree < 3)
                return facet_fail(error, FACET_ERROR_DEGENERATE_FACE, f, -1,
                                  "face %d has %d vertices (at least 3 needed)", (int)f,
                                  (int)degree);
            return facet_fail(error, FACET_ERROR_DEGENERATE_FACE, f, -1,
                              "face %d has only %d distinct vertices (at least 3 needed)", (int)f,
                              (int)distinct);
        }
        if (repeated >= 0) {
            free(stamp);
            return facet_fail(error, FACET_ERROR_REPEATED_VERTEX, f, repeated,
                              "face %d repeats vertex %d", (int)f, (int)repeated);
        }
    }

    /* Isolated vertices: stamp >= 0 means some face used it. */
    int64_t n_isolated = 0, first_isolated = -1;
    for (int32_t v = 0; v < nv; ++v) {
        if (stamp[v] < 0) {
            if (first_isolated < 0)
                first_isolated = v;
            ++n_isolated;
        }
    }
    free(stamp);

    /* Edges: sort undirected keys and count multiplicities. */
    const size_t nc = (size_t)start[nf];
    uint64_t *keys = malloc(sizeof *keys * (nc ? nc : 1));
    if (!keys)
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    for (int32_t f = 0; f < nf; ++f) {
        const int32_t b = start[f], e = start[f + 1];
        for (int32_t k = b; k < e; ++k) {
            uint32_t u = (uint32_t)fv[k], w = (uint32_t)fv[k + 1 < e ? k + 1 : b];
            if (u > w) {
                uint32_t t = u;
                u = w;
                w = t;
            }
            keys[k] = ((uint64_t)u << 32) | w;
        }
    }
    qsort(keys, nc, sizeof *keys, compare_u64);
    int64_t n_edges = 0, n_boundary = 0, n_non_manifold = 0;
    int64_t first_nm[2] = {-1, -1};
    for (size_t k = 0; k < nc;) {
        size_t m = k + 1;
        while (m < nc && keys[m] == keys[k])
            ++m;
        ++n_edges;
        if (m - k == 1)
            ++n_boundary;
        else if (m - k > 2) {
            if (n_non_manifold == 0) {
                first_nm[0] = (int64_t)(keys[k] >> 32);
                first_nm[1] = (int64_t)(keys[k] & 0xffffffffu);
            }
            ++n_non_manifold;
        }
        k = m;
    }
    free(keys);

    if (report) {
        report->n_edges = n_edges;
        report->n_boundary_edges = n_boundary;
        report->n_non_manifold_edges = n_non_manifold;
        report->n_isolated_vertices = n_isolated;
        report->first_non_manifold_edge[0] = first_nm[0];
        report->first_non_manifold_edge[1] = first_nm[1];
        report->first_isolated_vertex = first_isolated;
        report->max_degree = max_degree;
    }
    if (n_non_manifold > 0 || n_isolated > 0)
        return facet_fail(error, FACET_WARNING_MESH, -1, first_isolated,
                          "%lld non-manifold edges, %lld isolated vertices",
                          (long long)n_non_manifold, (long long)n_isolated);
    return FACET_OK;
}
