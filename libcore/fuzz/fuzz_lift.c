/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Fuzz target: facet_lifter_create / solve / fundamental / basis on plans
 * decoded from the bytes (x, y of the mesh; grids make liftable plans),
 * weights and targets sometimes zero, negative or not finite. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* One full run; heights/basis/values are the outputs compared between runs. */
static facet_status run(const facet_mesh *plan, const double *weights, const facet_lift_options *opt,
                        const double *targets, int32_t vertex, facet_basis_kind kind, int32_t count,
                        double *heights, double *fundamental, double *basis, double *values,
                        int32_t *dimension)
{
    facet_lifter *l = NULL;
    facet_error e;
    fz_error_init(&e);
    int32_t nv = plan->n_vertices;
    facet_status s = facet_lifter_create(plan, weights, opt, &l, &e);
    fz_check_status("facet_lifter_create", s, &e);
    *dimension = -1;
    if (s < 0) {
        if (l != NULL) FZ_FAIL("facet_lifter_create failed but returned a handle");
        return s;
    }
    *dimension = facet_lifter_dimension(l);
    if (*dimension < 3) FZ_FAIL("facet_lifter_dimension %d < 3", (int)*dimension);
    facet_lift_result r;
    fz_error_init(&e);
    s = facet_lifter_solve(l, targets, heights, &r, &e);
    fz_check_status("facet_lifter_solve", s, &e);
    if (s >= 0) {
        fz_check_finite("facet_lifter_solve", "heights", heights, nv);
        double rv[4] = {r.planarity_max_abs, r.planarity_max_rel, r.target_rms, r.target_max};
        fz_check_finite("facet_lifter_solve", "result", rv, 4);
    } else if (strcmp(e.message, facet_lifter_message(l)) != 0) {
        FZ_FAIL("facet_lifter_solve: handle message differs from the error's");
    }
    fz_error_init(&e);
    s = facet_lifter_fundamental(l, vertex, fundamental, &e);
    fz_check_status("facet_lifter_fundamental", s, &e);
    if (s >= 0) fz_check_finite("facet_lifter_fundamental", "heights", fundamental, nv);
    fz_error_init(&e);
    s = facet_lifter_basis(l, kind, count, basis, values, &e);
    fz_check_status("facet_lifter_basis", s, &e);
    if (s >= 0 && count > 0 && count <= *dimension) {
        fz_check_finite("facet_lifter_basis", "basis", basis, (int64_t)count * nv);
        fz_check_finite("facet_lifter_basis", "values", values, count);
    }
    facet_lifter_free(&l);
    if (l != NULL) FZ_FAIL("facet_lifter_free did not clear the pointer");
    return s;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_bytes b = {data, size};
    static fz_mesh m;
    fz_mesh_decode(&b, &m);
    int32_t nv = m.mesh.n_vertices;
    if (nv < 0 || nv > FZ_MAX_VERTICES) return 0;
    double *weights = NULL;
    if (fz_u8(&b) < 64) {
        weights = fz_calloc((size_t)nv, sizeof(double));
        for (int32_t v = 0; v < nv; v++) weights[v] = fz_range(&b, 1e-6, 10.0, 10);
    }
    facet_lift_options opt = {0.0, NULL, NULL};
    if (fz_u8(&b) < 32) opt.rank_tol = fz_special(&b);
    double *targets = fz_calloc((size_t)nv, sizeof(double));
    for (int32_t v = 0; v < nv; v++) targets[v] = fz_range(&b, -10.0, 10.0, 4);
    int32_t vertex = fz_u8(&b) < 250 ? fz_below(&b, nv) : nv + fz_below(&b, 3) - 1;
    facet_basis_kind kind = fz_u8(&b) & 1 ? FACET_BASIS_EIGEN : FACET_BASIS_ORTHONORMAL;
    if (fz_u8(&b) < 8) kind = (facet_basis_kind)(fz_u8(&b) % 4);
    int32_t count = fz_below(&b, 12) - 1;
    size_t basis_n = count > 0 ? (size_t)count * (size_t)nv : 0;
    if (getenv("FACET_FUZZ_VERBOSE")) {
        fprintf(stderr, "lift: nv %d nf %d rank_tol %g vertex %d kind %d count %d\n", (int)nv,
                (int)m.mesh.n_faces, opt.rank_tol, (int)vertex, (int)kind, (int)count);
        for (int32_t v = 0; v < nv; v++)
            fprintf(stderr, "  v%d %.17g %.17g w %.17g t %.17g\n", (int)v, m.xyz[3 * v], m.xyz[3 * v + 1],
                    weights ? weights[v] : 1.0, targets[v]);
        for (int32_t f = 0; f < m.mesh.n_faces && f < 50; f++) {
            fprintf(stderr, "  f%d:", (int)f);
            for (int32_t k = m.face_start[f]; k < m.face_start[f + 1] && k < FZ_MAX_CORNERS; k++)
                fprintf(stderr, " %d", (int)m.face_vertices[k]);
            fprintf(stderr, "\n");
        }
    }
    double *out[2][4];
    int32_t dim[2];
    facet_status s[2];
    for (int k = 0; k < 2; k++) {
        out[k][0] = fz_calloc((size_t)nv, sizeof(double));
        out[k][1] = fz_calloc((size_t)nv, sizeof(double));
        out[k][2] = fz_calloc(basis_n, sizeof(double));
        out[k][3] = fz_calloc(count > 0 ? (size_t)count : 0, sizeof(double));
        s[k] = run(&m.mesh, weights, fz_u8(&b) < 128 ? &opt : NULL, targets, vertex, kind, count,
                   out[k][0], out[k][1], out[k][2], out[k][3], &dim[k]);
        if (opt.rank_tol != 0.0) break; /* NULL options differ from a set rank_tol */
    }
    if (opt.rank_tol == 0.0) {
        if (s[0] != s[1] || dim[0] != dim[1]) FZ_FAIL("lifter: two runs disagree (status %d %d, dimension %d %d)",
                                                      (int)s[0], (int)s[1], (int)dim[0], (int)dim[1]);
        fz_check_same("facet_lifter_solve", "heights", out[0][0], out[1][0], (size_t)nv * sizeof(double));
        fz_check_same("facet_lifter_fundamental", "heights", out[0][1], out[1][1], (size_t)nv * sizeof(double));
        fz_check_same("facet_lifter_basis", "basis", out[0][2], out[1][2], basis_n * sizeof(double));
    }
    for (int k = 0; k < 2; k++)
        for (int j = 0; j < 4; j++)
            if (k == 0 || opt.rank_tol == 0.0) free(out[k][j]);
    free(weights);
    free(targets);
    return 0;
}
