/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Fuzz target: facet_cleanup (collapse short edges) on any mesh, thresholds
 * sometimes zero, negative or not finite; the output mesh must be valid when
 * the call succeeds; run twice, same bits. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_bytes b = {data, size};
    static fz_mesh m;
    fz_mesh_decode(&b, &m);
    int32_t nv = m.mesh.n_vertices, nf = m.mesh.n_faces;
    if (nv < 0 || nf < 0) return 0;
    int32_t nc = nf > 0 && m.face_start[nf] > 0 && m.face_start[nf] <= FZ_MAX_CORNERS ? m.face_start[nf] : FZ_MAX_CORNERS;
    facet_cleanup_options opt;
    opt.relative = fz_u8(&b) & 1;
    opt.min_edge = fz_u8(&b) < 16 ? fz_special(&b) : fz_range(&b, 0.0, opt.relative ? 1.0 : 2.0, 0);
    uint8_t mask = fz_u8(&b);
    double *xyz[2];
    int32_t *fs[2], *fv[2], *map[2], *col[2], *rem[2];
    facet_cleanup_result r[2];
    facet_status s[2];
    for (int k = 0; k < 2; k++) {
        xyz[k] = fz_calloc(3 * (size_t)nv, sizeof(double));
        fs[k] = fz_calloc((size_t)nf + 1, sizeof(int32_t));
        fv[k] = fz_calloc((size_t)nc, sizeof(int32_t));
        map[k] = mask & 1 ? fz_calloc((size_t)nv, sizeof(int32_t)) : NULL;
        col[k] = mask & 2 ? fz_calloc(2 * (size_t)nv, sizeof(int32_t)) : NULL;
        rem[k] = mask & 4 ? fz_calloc((size_t)nf, sizeof(int32_t)) : NULL;
        memset(&r[k], 0, sizeof r[k]);
        facet_error e;
        fz_error_init(&e);
        s[k] = facet_cleanup(&m.mesh, &opt, xyz[k], fs[k], fv[k], map[k], col[k], rem[k], &r[k], &e);
        fz_check_status("facet_cleanup", s[k], &e);
    }
    if (s[0] != s[1]) FZ_FAIL("facet_cleanup: status %d then %d", (int)s[0], (int)s[1]);
    if (s[0] >= 0) {
        facet_cleanup_result *q = &r[0];
        if (q->n_vertices < 0 || q->n_vertices > nv || q->n_faces < 0 || q->n_faces > nf ||
            q->n_corners < 0 || q->n_corners > nc || q->n_collapsed < 0 || q->n_collapsed > nv ||
            q->n_removed_faces < 0 || q->n_removed_faces > nf)
            FZ_FAIL("facet_cleanup: result counts out of range");
        fz_check_finite("facet_cleanup", "xyz_out", xyz[0], 3 * (int64_t)q->n_vertices);
        if (!isfinite(q->threshold)) FZ_FAIL("facet_cleanup: threshold %g", q->threshold);
        if (fs[0][q->n_faces] != q->n_corners) FZ_FAIL("facet_cleanup: face_start_out[n_faces] != n_corners");
        facet_mesh out = {q->n_vertices, q->n_faces, xyz[0], fs[0], fv[0]};
        facet_error e;
        fz_error_init(&e);
        facet_status v = facet_mesh_validate(&out, NULL, &e);
        if (v < 0) FZ_FAIL("facet_cleanup: output mesh invalid: %s", e.message);
        if (map[0])
            for (int32_t i = 0; i < nv; i++)
                if (map[0][i] < -1 || map[0][i] >= q->n_vertices) /* -1: left without a face */ FZ_FAIL("facet_cleanup: vertex_map[%d] = %d", (int)i, (int)map[0][i]);
        fz_check_same("facet_cleanup", "xyz_out", xyz[0], xyz[1], 3 * (size_t)q->n_vertices * sizeof(double));
        fz_check_same("facet_cleanup", "face_vertices_out", fv[0], fv[1], (size_t)q->n_corners * sizeof(int32_t));
    }
    for (int k = 0; k < 2; k++) {
        free(xyz[k]); free(fs[k]); free(fv[k]); free(map[k]); free(col[k]); free(rem[k]);
    }
    return 0;
}
