/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Fuzz target: facet_planarizer_create / set_fixed / set_face_weights /
 * set_reference / solve, both methods, a few terms, a few iterations, with
 * options that are sometimes out of range or not finite. Determinism: the
 * solve runs on 1 and on 2 threads and must give the same bits. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

typedef struct cancel_at {
    int32_t iteration;
} cancel_at;

static int progress(void *user, int32_t iteration, int32_t max_iter, double planarity)
{
    (void)max_iter;
    (void)planarity;
    const cancel_at *c = user;
    return c->iteration >= 0 && iteration >= c->iteration;
}

/* Maybe replace an option by a special value. */
static double maybe(fz_bytes *b, double value)
{
    return fz_u8(b) < 8 ? fz_special(b) : value;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_bytes b = {data, size};
    static fz_mesh m;
    fz_mesh_decode(&b, &m);
    facet_planarizer *p = NULL;
    facet_error e;
    fz_error_init(&e);
    facet_status s = facet_planarizer_create(&m.mesh, &p, &e);
    fz_check_status("facet_planarizer_create", s, &e);
    if (s < 0) {
        if (p != NULL) FZ_FAIL("facet_planarizer_create failed but returned a handle");
        return 0;
    }
    if (p == NULL) FZ_FAIL("facet_planarizer_create: ok without a handle");
    int32_t nv = m.mesh.n_vertices, nf = m.mesh.n_faces;

    /* fixed vertices */
    if (fz_u8(&b) < 64) {
        int32_t fixed[8], n = fz_below(&b, 9);
        for (int32_t k = 0; k < n; k++) fixed[k] = fz_u8(&b) < 250 ? fz_below(&b, nv) : nv + fz_below(&b, 3) - 1;
        fz_error_init(&e);
        s = facet_planarizer_set_fixed(p, n, fixed, &e);
        fz_check_status("facet_planarizer_set_fixed", s, &e);
    }
    /* face weights */
    if (fz_u8(&b) < 64) {
        double *w = fz_calloc((size_t)nf, sizeof(double));
        for (int32_t f = 0; f < nf; f++) w[f] = fz_u8(&b) < 40 ? 0.0 : fz_range(&b, 0.0, 4.0, 8);
        fz_error_init(&e);
        s = facet_planarizer_set_face_weights(p, w, &e);
        fz_check_status("facet_planarizer_set_face_weights", s, &e);
        free(w);
    }
    /* reference surface: the mesh itself */
    facet_surface *surface = NULL;
    if (fz_u8(&b) < 64) {
        fz_error_init(&e);
        s = facet_surface_create_from_mesh(&m.mesh, &surface, &e);
        fz_check_status("facet_surface_create_from_mesh", s, &e);
        if (s >= 0) {
            fz_error_init(&e);
            s = facet_planarizer_set_reference(p, surface, &e);
            fz_check_status("facet_planarizer_set_reference", s, &e);
        }
    }

    facet_planarize_options o;
    facet_method method = fz_u8(&b) & 1 ? FACET_METHOD_LOCAL_GLOBAL : FACET_METHOD_LOCAL_LOCAL;
    facet_planarize_options_default(method, &o);
    if (fz_u8(&b) < 16) o.method = (facet_method)(fz_u8(&b) % 4);
    o.mu0 = maybe(&b, o.mu0);
    o.ratio = maybe(&b, o.ratio);
    o.mu_min = maybe(&b, o.mu_min);
    o.tol_rel = maybe(&b, o.tol_rel);
    o.tol_abs = maybe(&b, o.tol_abs);
    o.max_iter = 1 + fz_below(&b, 12);
    o.iterations = fz_u8(&b) < 64 ? fz_below(&b, 8) : 0;
    /* zero or negative limits (refused or not); not huge ones: a solve of a
     * billion iterations is what was asked for, not a finding */
    if (fz_u8(&b) < 4) o.max_iter = -(int32_t)(fz_u32(&b) % 1000u);
    o.warm = 0;
    o.data_tangent = maybe(&b, fz_u8(&b) < 200 ? 1.0 : fz_range(&b, 0.0, 2.0, 0));
    o.data_normal = maybe(&b, fz_u8(&b) < 200 ? 1.0 : fz_range(&b, 0.0, 2.0, 0));
    o.surface_weight = surface && fz_u8(&b) < 128 ? maybe(&b, fz_range(&b, 0.0, 10.0, 0)) : 0.0;
    uint8_t terms = fz_u8(&b);
    if (terms & 1) o.laplacian = maybe(&b, fz_range(&b, 0.0, 1.0, 0));
    if (terms & 2) o.laplacian_weights = (facet_laplacian_weights)(fz_u8(&b) % 3);
    if (terms & 4) o.normal_laplacian = maybe(&b, fz_range(&b, 0.0, 1.0, 0));
    if (terms & 8) o.boundary_fairness = maybe(&b, fz_range(&b, 0.0, 1.0, 0));
    if (terms & 16) {
        o.shape = (facet_shape_mode)(fz_u8(&b) % 4);
        o.shape_weight = maybe(&b, 1.0);
    }
    if (terms & 32) o.boundary = (facet_boundary_mode)(fz_u8(&b) % 4);
    if (terms & 64) o.circular = maybe(&b, fz_range(&b, 0.0, 1.0, 0));
    if (terms & 128) o.parallelogram = maybe(&b, fz_range(&b, 0.0, 1.0, 0));
    uint8_t sched = fz_u8(&b);
    if (sched & 1) o.hold_tol = maybe(&b, fz_range(&b, 0.0, 0.5, 0));
    if (sched & 2) o.hold_max = fz_below(&b, 6) - 1;
    if (sched & 4) o.anderson = fz_below(&b, 20) - 1;
    cancel_at cancel = {-1};
    if (sched & 8) {
        cancel.iteration = fz_below(&b, 4);
        o.progress = progress;
        o.progress_user = &cancel;
    }

    /* control positions: the mesh's, sometimes with a bad value */
    double *in = fz_calloc(3 * (size_t)nv, sizeof(double));
    memcpy(in, m.xyz, 3 * (size_t)nv * sizeof(double));
    if (fz_u8(&b) < 8 && nv > 0) {
        double value = fz_special(&b); /* value first: see fuzz_common.h */
        in[fz_below(&b, 3 * nv)] = value;
    }
    double *out1 = fz_calloc(3 * (size_t)nv, sizeof(double));
    double *out2 = fz_calloc(3 * (size_t)nv, sizeof(double));
    facet_planarize_result r1, r2;
    memset(&r1, 0, sizeof r1);
    memset(&r2, 0, sizeof r2);
    facet_error e2;
    fz_error_init(&e);
    fz_error_init(&e2);
    if (getenv("FACET_FUZZ_VERBOSE"))
        fprintf(stderr, "planarize: nv %d nf %d method %d max_iter %d iterations %d mu0 %g ratio %g mu_min %g "
                "tol %g %g data %g %g surface %g lap %g nlap %g bfair %g shape %d %g boundary %d circ %g "
                "par %g hold %g %d anderson %d cancel %d\n", (int)nv, (int)nf, (int)o.method, (int)o.max_iter,
                (int)o.iterations, o.mu0, o.ratio, o.mu_min, o.tol_abs, o.tol_rel, o.data_tangent, o.data_normal,
                o.surface_weight, o.laplacian, o.normal_laplacian, o.boundary_fairness, (int)o.shape,
                o.shape_weight, (int)o.boundary, o.circular, o.parallelogram, o.hold_tol, (int)o.hold_max,
                (int)o.anderson, (int)cancel.iteration);
    o.threads = 1;
    facet_status s1 = facet_planarizer_solve(p, in, &o, out1, &r1, &e);
    fz_check_status("facet_planarizer_solve", s1, &e);
    o.threads = 2;
    facet_status s2 = facet_planarizer_solve(p, in, &o, out2, &r2, &e2);
    fz_check_status("facet_planarizer_solve", s2, &e2);
    if (s1 != s2) FZ_FAIL("facet_planarizer_solve: status %d on 1 thread, %d on 2", (int)s1, (int)s2);
    if (s1 >= 0 || s1 == FACET_ERROR_CANCELLED) {
        if (s1 >= 0) {
            fz_check_finite("facet_planarizer_solve", "xyz_out", out1, 3 * (int64_t)nv);
            double rv[4] = {r1.mu, r1.planarity_max_abs, r1.planarity_max_rel, r1.constraint_max_rel};
            fz_check_finite("facet_planarizer_solve", "result", rv, 4);
        }
        fz_check_same("facet_planarizer_solve", "xyz_out (1 vs 2 threads)", out1, out2,
                      3 * (size_t)nv * sizeof(double));
        if (r1.iterations != r2.iterations || r1.stop_reason != r2.stop_reason ||
            memcmp(&r1.planarity_max_abs, &r2.planarity_max_abs, sizeof(double)) != 0)
            FZ_FAIL("facet_planarizer_solve: result differs between 1 and 2 threads");
    } else if (strcmp(e2.message, facet_planarizer_message(p)) != 0) {
        FZ_FAIL("facet_planarizer_solve: handle message differs from the error's");
    }
    free(in);
    free(out1);
    free(out2);
    facet_planarizer_free(&p);
    if (p != NULL) FZ_FAIL("facet_planarizer_free did not clear the pointer");
    facet_surface_free(&surface);
    return 0;
}
