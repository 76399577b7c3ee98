/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Fuzz target: facet_mesh_validate, then on a valid mesh facet_planarity,
 * facet_face_shape (the quality report) and facet_fit_plane. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void shape_run(const facet_mesh *mesh, const double *xyz_input, int threads, double *out)
{
    facet_error e;
    fz_error_init(&e);
    int32_t nf = mesh->n_faces;
    facet_status s = facet_planarity(mesh, threads, out, out + nf, out + 2 * nf, out + 3 * nf, &e);
    fz_check_status("facet_planarity", s, &e);
    if (s >= 0) fz_check_finite("facet_planarity", "outputs", out, 4 * (int64_t)nf);
    fz_error_init(&e);
    s = facet_face_shape(mesh, xyz_input, threads, out + 4 * nf, out + 5 * nf, out + 6 * nf, &e);
    fz_check_status("facet_face_shape", s, &e);
    if (s >= 0) fz_check_finite("facet_face_shape", "outputs", out + 4 * nf, 3 * (int64_t)nf);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_bytes b = {data, size};
    static fz_mesh m, m2;
    fz_mesh_decode(&b, &m);
    facet_mesh_report r1, r2;
    facet_error e1, e2;
    fz_error_init(&e1);
    fz_error_init(&e2);
    facet_status s1 = facet_mesh_validate(&m.mesh, &r1, &e1);
    fz_check_status("facet_mesh_validate", s1, &e1);
    facet_status s2 = facet_mesh_validate(&m.mesh, fz_u8(&b) & 1 ? &r2 : NULL, &e2);
    if (s1 != s2) FZ_FAIL("facet_mesh_validate: status %d then %d", (int)s1, (int)s2);
    if (s1 < 0) {
        if (strcmp(e1.message, e2.message) != 0) FZ_FAIL("facet_mesh_validate: two messages");
        return 0;
    }
    if (r1.n_boundary_edges > r1.n_edges || r1.n_non_manifold_edges > r1.n_edges ||
        r1.n_isolated_vertices > m.mesh.n_vertices || r1.max_degree < 3)
        FZ_FAIL("facet_mesh_validate: inconsistent report");
    if ((s1 == FACET_WARNING_MESH) != (r1.n_non_manifold_edges > 0 || r1.n_isolated_vertices > 0))
        FZ_FAIL("facet_mesh_validate: warning %d disagrees with the report", (int)s1);

    /* a second geometry of the same topology for ratio_change */
    m2 = m;
    int32_t nv = m.mesh.n_vertices;
    for (int32_t k = 0, n = fz_below(&b, 8); k < n && nv > 0; k++) {
        double delta = fz_range(&b, -1.0, 1.0, 30); /* value first: see fuzz_common.h */
        m2.xyz[fz_below(&b, 3 * nv)] += delta;
    }
    int32_t nf = m.mesh.n_faces;
    double *o1 = fz_calloc(7 * (size_t)nf, sizeof(double));
    double *o2 = fz_calloc(7 * (size_t)nf, sizeof(double));
    const double *input = fz_u8(&b) & 1 ? m2.xyz : NULL;
    shape_run(&m.mesh, input, 1, o1);
    shape_run(&m.mesh, input, 2, o2);
    fz_check_same("facet_planarity/facet_face_shape", "outputs (1 vs 2 threads)", o1, o2,
                  7 * (size_t)nf * sizeof(double));
    free(o1);
    free(o2);

    /* the plane of the first face's corners */
    int32_t f0 = m.face_start[0], n0 = m.face_start[1] - f0;
    double pts[3 * 64], normal[3], offset;
    if (n0 > 64) n0 = 64;
    for (int32_t k = 0; k < n0; k++) memcpy(pts + 3 * k, m.xyz + 3 * m.face_vertices[f0 + k], 3 * sizeof(double));
    double ev = facet_fit_plane(n0, pts, normal, &offset);
    if (n0 >= 3 && !(isfinite(ev) && isfinite(offset) && isfinite(normal[0]) && isfinite(normal[1]) &&
                     isfinite(normal[2])))
        FZ_FAIL("facet_fit_plane: non-finite plane of finite points");
    return 0;
}
