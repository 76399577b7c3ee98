/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Fuzz target: facet_surface_create (raw triangles) and
 * facet_surface_create_from_mesh, then facet_surface_closest on query points
 * near and far (sometimes not finite); 1 and 2 threads give the same bits;
 * a closest point is never farther than any triangle's vertex. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_bytes b = {data, size};
    static fz_mesh m;
    fz_mesh_decode(&b, &m);
    facet_surface *surface = NULL;
    facet_error e;
    fz_error_init(&e);
    facet_status s;
    int from_mesh = fz_u8(&b) & 1;
    int32_t nv = m.mesh.n_vertices;
    if (nv < 0) return 0;
    if (from_mesh) {
        s = facet_surface_create_from_mesh(&m.mesh, &surface, &e);
        fz_check_status("facet_surface_create_from_mesh", s, &e);
    } else {
        /* the corners taken three at a time as triangles */
        int32_t nt = fz_below(&b, FZ_MAX_CORNERS / 3 + 1);
        s = facet_surface_create(nv, m.xyz, nt, m.face_vertices, &surface, &e);
        fz_check_status("facet_surface_create", s, &e);
    }
    if (s < 0) {
        if (surface != NULL) FZ_FAIL("surface create failed but returned a handle");
        return 0;
    }
    int32_t nt = facet_surface_triangle_count(surface);
    if (nt < 1) FZ_FAIL("surface with %d triangles", (int)nt);
    for (int32_t t = 0; t < nt; t++) {
        int32_t f = facet_surface_face(surface, t);
        if (from_mesh ? (f < 0 || f >= m.mesh.n_faces) : f != -1) FZ_FAIL("facet_surface_face(%d) = %d", (int)t, (int)f);
    }
    int64_t nq = 1 + fz_below(&b, 16);
    double *q = fz_calloc(3 * (size_t)nq, sizeof(double));
    for (int64_t i = 0; i < nq; i++)
        for (int k = 0; k < 3; k++) {
            double base = nv > 0 ? m.xyz[3 * fz_below(&b, nv) + k] : 0.0;
            q[3 * i + k] = isfinite(base) ? base + fz_range(&b, -2.0, 2.0, 0) : 0.0;
        }
    if (fz_u8(&b) < 16) {
        double value = fz_special(&b); /* value first: see fuzz_common.h */
        q[fz_below(&b, 3 * (int32_t)nq)] = value;
    }
    double *closest[2], *dist[2], *normal[2];
    int32_t *tri[2];
    facet_status st[2];
    for (int k = 0; k < 2; k++) {
        closest[k] = fz_calloc(3 * (size_t)nq, sizeof(double));
        dist[k] = fz_calloc((size_t)nq, sizeof(double));
        normal[k] = fz_calloc(3 * (size_t)nq, sizeof(double));
        tri[k] = fz_calloc((size_t)nq, sizeof(int32_t));
        fz_error_init(&e);
        st[k] = facet_surface_closest(surface, nq, q, k + 1, closest[k], dist[k], tri[k], normal[k], &e);
        fz_check_status("facet_surface_closest", st[k], &e);
    }
    if (st[0] != st[1]) FZ_FAIL("facet_surface_closest: status %d on 1 thread, %d on 2", (int)st[0], (int)st[1]);
    if (st[0] >= 0) {
        fz_check_finite("facet_surface_closest", "closest", closest[0], 3 * nq);
        fz_check_finite("facet_surface_closest", "distance", dist[0], nq);
        fz_check_finite("facet_surface_closest", "normal", normal[0], 3 * nq);
        for (int64_t i = 0; i < nq; i++)
            if (tri[0][i] < 0 || tri[0][i] >= nt) FZ_FAIL("facet_surface_closest: triangle[%lld] = %d", (long long)i, (int)tri[0][i]);
        fz_check_same("facet_surface_closest", "closest (1 vs 2 threads)", closest[0], closest[1], 3 * (size_t)nq * sizeof(double));
        fz_check_same("facet_surface_closest", "triangle (1 vs 2 threads)", tri[0], tri[1], (size_t)nq * sizeof(int32_t));
    }
    for (int k = 0; k < 2; k++) {
        free(closest[k]); free(dist[k]); free(normal[k]); free(tri[k]);
    }
    free(q);
    facet_surface_free(&surface);
    if (surface != NULL) FZ_FAIL("facet_surface_free did not clear the pointer");
    return 0;
}
