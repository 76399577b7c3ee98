/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Numerical robustness (issue 7 item 5): no solver puts a NaN or an infinity
 * into an output for any finite input. Every solver is run on extreme but
 * finite inputs -- coordinates from 1e-6 to 1e7 in scale with offsets of
 * 1e7 (millimetres to georeferenced metres), nearly degenerate and collinear
 * faces, zero-length edges, faces collapsed to a point, weights from 1e-12
 * to 1e12 -- and must either succeed (possibly with a warning) with finite
 * outputs, or fail with a status and a message, outputs untouched. A solver
 * that cannot meet its tolerance must say so (FACET_WARNING_NOT_CONVERGED)
 * and return its best finite result. */
#include "check.h"
#include "facet.h"
#include "test_meshes.h"
#include "test_panel_output.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* small meshes and few iterations: the point is the arithmetic's range, not
 * convergence, and the term matrix makes some 1500 solves */
enum { GRID_U = 4, GRID_V = 3, MAX_ITER = 60 };

#ifdef FACET_SANITIZED
static const double SCALES[] = {1e-6, 1.0, 1e7};
#else
static const double SCALES[] = {1e-6, 1e-3, 1.0, 1e3, 1e7};
#endif
static const double OFFSETS[] = {0.0, 1e7};
enum { NSCALES = sizeof SCALES / sizeof SCALES[0], NOFFSETS = sizeof OFFSETS / sizeof OFFSETS[0] };

/* Mesh variants with trouble built in. */
enum {
    PLAIN,          /* the smooth grid */
    NEAR_DEGENERATE, /* one quad squashed to a sliver 1e-9 of an edge wide */
    COLLINEAR,       /* one quad with its corners on one line */
    ZERO_EDGE,       /* two vertices of a face at the same point */
    POINT_FACE,      /* a whole face collapsed to one point */
    NVARIANTS
};
static const char *VARIANT_NAMES[] = {"plain", "near-degenerate", "collinear", "zero-edge",
                                      "point-face"};

/* Vertex (i, j) of the grid. */
static double *vertex(test_mesh *t, int i, int j)
{
    return t->xyz + 3 * (size_t)(j * (GRID_U + 1) + i);
}

static test_mesh make_mesh(int variant, double scale, double offset)
{
    test_mesh t = test_grid(GRID_U, GRID_V, 0.4, scale, offset);
    double *a = vertex(&t, 1, 1), *b = vertex(&t, 2, 1), *c = vertex(&t, 2, 2), *d = vertex(&t, 1, 2);
    switch (variant) {
    case NEAR_DEGENERATE: /* face (1,1): c and d pulled to within 1e-9 of a-b */
        for (int k = 0; k < 3; ++k) {
            c[k] = b[k] + 1e-9 * (c[k] - b[k]);
            d[k] = a[k] + 1e-9 * (d[k] - a[k]);
        }
        break;
    case COLLINEAR: /* face (1,1): every corner on the line through a and b */
        for (int k = 0; k < 3; ++k) {
            c[k] = a[k] + 2.0 * (b[k] - a[k]);
            d[k] = a[k] + 3.0 * (b[k] - a[k]);
        }
        break;
    case ZERO_EDGE:
        memcpy(b, a, 3 * sizeof(double));
        break;
    case POINT_FACE:
        memcpy(b, a, 3 * sizeof(double));
        memcpy(c, a, 3 * sizeof(double));
        memcpy(d, a, 3 * sizeof(double));
        break;
    default:
        break;
    }
    return t;
}

static int n_solves = 0, n_warnings = 0, n_errors = 0;

/* A solve that succeeded must have finite outputs; one that failed must
 * have said why and left them alone. */
static void judge(facet_status s, const facet_error *e, const double *out, size_t n,
                  const double *before, const char *what, int variant, double scale,
                  double offset)
{
    ++n_solves;
    if (s > 0)
        ++n_warnings;
    if (s >= 0) {
        CHECK(all_finite(out, n));
        if (!all_finite(out, n))
            fprintf(stderr, "  %s: non-finite output (%s mesh, scale %g, offset %g)\n", what,
                    VARIANT_NAMES[variant], scale, offset);
    } else {
        ++n_errors;
        CHECK(e->message[0] != '\0');
        /* a finite input is never a numerical failure: at worst the best
         * finite iterate with a warning */
        CHECK(s != FACET_ERROR_INVALID_ARGUMENT && s != FACET_ERROR_OUT_OF_MEMORY &&
              s != FACET_ERROR_NUMERICAL);
        if (before)
            CHECK(memcmp(out, before, n * sizeof(double)) == 0);
        if (s == FACET_ERROR_INVALID_ARGUMENT || s == FACET_ERROR_NUMERICAL)
            fprintf(stderr, "  %s: status %d (%s) on the %s mesh, scale %g, offset %g\n", what,
                    (int)s, e->message, VARIANT_NAMES[variant], scale, offset);
    }
}

/* Term configurations of the planarizer: each with huge and tiny weights. */
typedef struct {
    const char *name;
    void (*set)(facet_planarize_options *o, double w);
} term;

static void t_data(facet_planarize_options *o, double w) { o->data_tangent = w, o->data_normal = w; }
static void t_point_plane(facet_planarize_options *o, double w) { o->data_tangent = 1e-12 * w, o->data_normal = w; }
static void t_lap(facet_planarize_options *o, double w) { o->laplacian = w, o->laplacian_weights = FACET_LAPLACIAN_INVERSE_EDGE; }
static void t_nlap(facet_planarize_options *o, double w) { o->normal_laplacian = w; }
static void t_fair(facet_planarize_options *o, double w) { o->boundary_fairness = w; }
static void t_asap(facet_planarize_options *o, double w) { o->shape = FACET_SHAPE_ASAP, o->shape_weight = w; }
static void t_arap(facet_planarize_options *o, double w) { o->shape = FACET_SHAPE_ARAP, o->shape_weight = w; }
static void t_circ(facet_planarize_options *o, double w) { o->circular = w; }
static void t_par(facet_planarize_options *o, double w) { o->parallelogram = w; }
static void t_fixed(facet_planarize_options *o, double w) { o->boundary = FACET_BOUNDARY_FIXED, o->laplacian = w; }
static void t_slide(facet_planarize_options *o, double w) { o->boundary = FACET_BOUNDARY_SLIDING, o->data_normal = w; }
static void t_surface(facet_planarize_options *o, double w) { o->surface_weight = w; }
static void t_paper(facet_planarize_options *o, double w)
{
    (void)w;
    o->hold_tol = 0.0, o->anderson = 0, o->ratio = o->method == FACET_METHOD_LOCAL_LOCAL ? 0.9 : 0.7;
}

static const term TERMS[] = {{"data", t_data},           {"point-to-plane", t_point_plane},
                             {"laplacian", t_lap},       {"normal laplacian", t_nlap},
                             {"boundary fairness", t_fair}, {"asap", t_asap},
                             {"arap", t_arap},           {"circular", t_circ},
                             {"parallelogram", t_par},   {"fixed boundary", t_fixed},
                             {"sliding boundary", t_slide}, {"surface", t_surface},
                             {"paper schedule", t_paper}};
enum { NTERMS = sizeof TERMS / sizeof TERMS[0] };

static void test_planarize_extremes(void)
{
    const double weights[] = {1e-12, 1.0, 1e12};
    for (int variant = 0; variant < NVARIANTS; ++variant)
        for (int si = 0; si < NSCALES; ++si)
            for (int oi = 0; oi < NOFFSETS; ++oi) {
                const double scale = SCALES[si], offset = OFFSETS[oi];
                test_mesh t = make_mesh(variant, scale, offset);
                const size_t n = 3 * (size_t)t.mesh.n_vertices;
                facet_error e;
                facet_planarizer *p = NULL;
                CHECK_STATUS(facet_planarizer_create(&t.mesh, &p, &e), FACET_OK);
                facet_surface *ref = NULL;
                CHECK_STATUS(facet_surface_create_from_mesh(&t.mesh, &ref, &e), FACET_OK);
                CHECK_STATUS(facet_planarizer_set_reference(p, ref, &e), FACET_OK);
                double *out = malloc(sizeof(double) * n), *before = malloc(sizeof(double) * n);
                /* the full term matrix on the plain mesh at three scales; the
                 * troubled meshes with every term at weight 1 and extremes of
                 * the data and shape terms */
                const int full = variant == PLAIN;
                for (int method = 0; method < 2; ++method)
                    for (int k = 0; k < NTERMS; ++k)
                        for (int wi = 0; wi < 3; ++wi) {
                            if (!full && wi != 1)
                                continue;
                            facet_planarize_options o;
                            facet_planarize_options_default((facet_method)method, &o);
                            o.max_iter = MAX_ITER;
                            /* one thread: on meshes this small each parallel region
                             * costs more than its work, and on a loaded machine a
                             * spinning team made this loop 30x slower; threads are
                             * exercised by the other solves here and by the other
                             * tests (results do not depend on them) */
                            o.threads = 1;
                            TERMS[k].set(&o, weights[wi]);
                            for (size_t i = 0; i < n; ++i)
                                out[i] = before[i] = -1.0;
                            facet_planarize_result r;
                            memset(&r, 0, sizeof r);
                            facet_status s = facet_planarizer_solve(p, t.xyz, &o, out, &r, &e);
                            char what[128];
                            snprintf(what, sizeof what, "planarize %s %s weight %g",
                                     method ? "L/G" : "L/L", TERMS[k].name, weights[wi]);
                            judge(s, &e, out, n, before, what, variant, scale, offset);
                            if (s >= 0) {
                                /* a face collapsed to a point has no deviation
                                 * either: its relative planarity is 0, not 0/0 */
                                CHECK(isfinite(r.planarity_max_abs) && isfinite(r.mu) &&
                                      isfinite(r.constraint_max_rel) &&
                                      isfinite(r.planarity_max_rel));
                                CHECK(s == FACET_OK || s == FACET_WARNING_NOT_CONVERGED);
                                CHECK((s == FACET_OK) == (r.stop_reason == FACET_STOP_TOLERANCE));
                            }
                        }
                /* face weights: the largest allowed, tiny and zero side by side (above
                 * FACET_FACE_WEIGHT_MAX refused, naming the face: 1e10 beside 1 moved a
                 * unit grid's vertices by 6,600) */
                double fw[GRID_U * GRID_V];
                for (int f = 0; f < GRID_U * GRID_V; ++f)
                    fw[f] = f % 3 == 0 ? 1e12 : (f % 3 == 1 ? 1e-12 : 0.0);
                CHECK_STATUS(facet_planarizer_set_face_weights(p, fw, &e), FACET_ERROR_INVALID_ARGUMENT);
                CHECK(e.face == 0 && strstr(e.message, "face 0 has planarity weight 1e+12") != NULL);
                for (int f = 0; f < GRID_U * GRID_V; f += 3)
                    fw[f] = FACET_FACE_WEIGHT_MAX;
                CHECK_STATUS(facet_planarizer_set_face_weights(p, fw, &e), FACET_OK);
                for (int method = 0; method < 2; ++method) {
                    facet_planarize_options o;
                    facet_planarize_options_default((facet_method)method, &o);
                    o.max_iter = MAX_ITER;
                    o.threads = 1;
                    facet_status s = facet_planarizer_solve(p, t.xyz, &o, out, NULL, &e);
                    judge(s, &e, out, n, NULL, "planarize face weights", variant, scale, offset);
                }
                facet_planarizer_free(&p);
                facet_surface_free(&ref);
                free(out), free(before);
                test_mesh_free(&t);
            }
}

/* An unreachable tolerance: the solver says so and returns a finite result
 * no less planar than its input. */
static void test_not_converged(void)
{
    test_mesh t = test_grid(GRID_U, GRID_V, 0.5, 1e-3, 1e7);
    const size_t n = 3 * (size_t)t.mesh.n_vertices;
    facet_planarizer *p = NULL;
    facet_error e;
    CHECK_STATUS(facet_planarizer_create(&t.mesh, &p, &e), FACET_OK);
    double *out = malloc(sizeof(double) * n);
    double *in_dev = malloc(sizeof(double) * GRID_U * GRID_V);
    double *out_dev = malloc(sizeof(double) * GRID_U * GRID_V);
    CHECK_STATUS(facet_planarity(&t.mesh, 1, in_dev, NULL, NULL, NULL, &e), FACET_OK);
    double in_max = 0.0;
    for (int f = 0; f < GRID_U * GRID_V; ++f)
        in_max = fmax(in_max, in_dev[f]);
    for (int method = 0; method < 2; ++method)
        for (int budget = 0; budget < 2; ++budget) {
            facet_planarize_options o;
            facet_planarize_options_default((facet_method)method, &o);
            o.tol_rel = 1e-300; /* below rounding at 1e7: unreachable */
            o.max_iter = 12;
            o.mu_min = 1e-3;
            if (budget)
                o.max_iter = 100000, o.time_budget = 1e-9;
            facet_planarize_result r;
            facet_status s = facet_planarizer_solve(p, t.xyz, &o, out, &r, &e);
            CHECK_STATUS(s, FACET_WARNING_NOT_CONVERGED);
            CHECK(e.status == FACET_WARNING_NOT_CONVERGED && strstr(e.message, "not reached"));
            CHECK(budget ? r.stop_reason == FACET_STOP_TIME
                         : (r.stop_reason == FACET_STOP_MAX_ITER ||
                            r.stop_reason == FACET_STOP_STAGNATION));
            CHECK(all_finite(out, n));
            CHECK(isfinite(r.planarity_max_abs) && isfinite(r.planarity_max_rel));
            facet_mesh m = t.mesh;
            m.xyz = out;
            CHECK_STATUS(facet_planarity(&m, 1, out_dev, NULL, NULL, NULL, &e), FACET_OK);
            double out_max = 0.0;
            for (int f = 0; f < GRID_U * GRID_V; ++f)
                out_max = fmax(out_max, out_dev[f]);
            if (!budget || r.iterations > 0)
                CHECK(out_max <= in_max);
            if (!budget) /* the solve's own measure agrees with a fresh one */
                CHECK(fabs(out_max - r.planarity_max_abs) <= 1e-6 * in_max + 1e-9);
        }
    /* a problem whose steps overflow (tangent pull 1e-24 of the planarity
     * weight): the last finite iterate, with the warning, not an error */
    for (int method = 0; method < 2; ++method) {
        facet_planarize_options o;
        facet_planarize_options_default((facet_method)method, &o);
        o.data_tangent = 1e-24, o.data_normal = 1e-12;
        o.max_iter = MAX_ITER;
        facet_planarize_result r;
        facet_status s = facet_planarizer_solve(p, t.xyz, &o, out, &r, &e);
        CHECK(s == FACET_WARNING_NOT_CONVERGED || s == FACET_OK);
        CHECK(all_finite(out, n));
        if (s == FACET_WARNING_NOT_CONVERGED && r.stop_reason == FACET_STOP_STAGNATION)
            CHECK(strstr(e.message, "last finite iterate") != NULL);
    }
    facet_planarizer_free(&p);
    free(out), free(in_dev), free(out_dev);
    test_mesh_free(&t);
}

static void test_measures_extremes(void)
{
    for (int variant = 0; variant < NVARIANTS; ++variant)
        for (int si = 0; si < NSCALES; ++si)
            for (int oi = 0; oi < NOFFSETS; ++oi) {
                test_mesh t = make_mesh(variant, SCALES[si], OFFSETS[oi]);
                const int nf = t.mesh.n_faces, nv = t.mesh.n_vertices;
                facet_error e;
                double a[GRID_U * GRID_V], b[GRID_U * GRID_V], c[GRID_U * GRID_V],
                    d[GRID_U * GRID_V];
                CHECK_STATUS(facet_planarity(&t.mesh, 1, a, b, c, d, &e), FACET_OK);
                CHECK(all_finite(a, nf) && all_finite(b, nf) && all_finite(c, nf) &&
                      all_finite(d, nf));
                double *input = malloc(sizeof(double) * 3 * nv);
                test_mesh plain = make_mesh(PLAIN, SCALES[si], OFFSETS[oi]);
                memcpy(input, plain.xyz, sizeof(double) * 3 * nv);
                CHECK_STATUS(facet_face_shape(&t.mesh, input, 1, a, b, c, &e), FACET_OK);
                CHECK(all_finite(a, nf) && all_finite(b, nf) && all_finite(c, nf));
                /* and the other way round: degenerate input, plain output */
                facet_mesh pm = plain.mesh;
                CHECK_STATUS(facet_face_shape(&pm, t.xyz, 1, a, b, c, &e), FACET_OK);
                CHECK(all_finite(a, nf) && all_finite(b, nf) && all_finite(c, nf));
                free(input);
                test_mesh_free(&plain);

                /* closest points from vertices pushed off the surface */
                facet_surface *s = NULL;
                CHECK_STATUS(facet_surface_create_from_mesh(&t.mesh, &s, &e), FACET_OK);
                double *q = malloc(sizeof(double) * 3 * nv), *cl = malloc(sizeof(double) * 3 * nv);
                double *dist = malloc(sizeof(double) * nv), *nrm = malloc(sizeof(double) * 3 * nv);
                int32_t *tri = malloc(sizeof(int32_t) * nv);
                for (int i = 0; i < 3 * nv; ++i)
                    q[i] = t.xyz[i] + SCALES[si] * 0.3 * sin(i);
                CHECK_STATUS(facet_surface_closest(s, nv, q, 1, cl, dist, tri, nrm, &e), FACET_OK);
                CHECK(all_finite(cl, 3 * nv) && all_finite(dist, nv) && all_finite(nrm, 3 * nv));
                int found = 1;
                for (int v = 0; v < nv; ++v)
                    found &= tri[v] >= 0;
                CHECK(found);
                facet_surface_free(&s);
                free(q), free(cl), free(dist), free(nrm), free(tri);
                test_mesh_free(&t);
            }
}

static void test_cleanup_extremes(void)
{
    for (int variant = 0; variant < NVARIANTS; ++variant)
        for (int si = 0; si < NSCALES; ++si)
            for (int oi = 0; oi < NOFFSETS; ++oi) {
                test_mesh t = make_mesh(variant, SCALES[si], OFFSETS[oi]);
                const int nv = t.mesh.n_vertices, nf = t.mesh.n_faces;
                const double thresholds[] = {1e-12, 0.1, 0.6};
                for (int k = 0; k < 3; ++k) {
                    facet_cleanup_options o = {thresholds[k], 1};
                    double *xyz = malloc(sizeof(double) * 3 * nv), *before = malloc(sizeof(double) * 3 * nv);
                    int32_t *start = malloc(sizeof(int32_t) * (nf + 1)), *fv = malloc(sizeof(int32_t) * 4 * nf);
                    for (int i = 0; i < 3 * nv; ++i)
                        xyz[i] = before[i] = -2.0;
                    facet_cleanup_result r;
                    facet_error e;
                    facet_status s = facet_cleanup(&t.mesh, &o, xyz, start, fv, NULL, NULL, NULL, &r, &e);
                    judge(s, &e, xyz, s >= 0 ? 3 * (size_t)r.n_vertices : 3 * (size_t)nv, before,
                          "cleanup", variant, SCALES[si], OFFSETS[oi]);
                    if (s >= 0)
                        CHECK(isfinite(r.threshold) && r.threshold > 0.0);
                    free(xyz), free(before), free(start), free(fv);
                }
                test_mesh_free(&t);
            }
}

static void test_lift_extremes(void)
{
    for (int variant = 0; variant < NVARIANTS; ++variant)
        for (int si = 0; si < NSCALES; ++si)
            for (int oi = 0; oi < NOFFSETS; ++oi) {
                const double scale = SCALES[si], offset = OFFSETS[oi];
                test_mesh t = make_mesh(variant, scale, offset);
                const int nv = t.mesh.n_vertices;
                double *w = malloc(sizeof(double) * nv), *tg = malloc(sizeof(double) * nv);
                double *z = malloc(sizeof(double) * nv), *before = malloc(sizeof(double) * nv);
                for (int v = 0; v < nv; ++v) {
                    w[v] = v % 2 ? 1e12 : 1e-12;
                    tg[v] = offset + t.xyz[3 * v + 2];
                    z[v] = before[v] = -3.0;
                }
                for (int weighted = 0; weighted < 2; ++weighted) {
                    facet_lifter *l = NULL;
                    facet_error e;
                    facet_status s = facet_lifter_create(&t.mesh, weighted ? w : NULL, NULL, &l, &e);
                    if (s < 0) {
                        /* collinear and collapsed faces are refused in plan */
                        CHECK(s == FACET_ERROR_PLAN_DEGENERATE_FACE);
                        CHECK(variant != PLAIN);
                        CHECK(e.message[0] != '\0');
                        continue;
                    }
                    facet_lift_result r;
                    s = facet_lifter_solve(l, tg, z, &r, &e);
                    judge(s, &e, z, nv, before, "lift", variant, scale, offset);
                    if (s >= 0)
                        CHECK(isfinite(r.planarity_max_abs) && isfinite(r.planarity_max_rel) &&
                              isfinite(r.target_rms) && isfinite(r.target_max));
                    s = facet_lifter_fundamental(l, nv / 2, z, &e);
                    judge(s, &e, z, nv, NULL, "lift fundamental", variant, scale, offset);
                    const int d = facet_lifter_dimension(l);
                    double *basis = malloc(sizeof(double) * nv * d), *values = malloc(sizeof(double) * d);
                    for (int kind = 0; kind < 2; ++kind) {
                        s = facet_lifter_basis(l, (facet_basis_kind)kind, d, basis, values, &e);
                        judge(s, &e, basis, (size_t)nv * d, NULL, "lift basis", variant, scale, offset);
                        if (s >= 0)
                            CHECK(all_finite(values, d));
                    }
                    free(basis), free(values);
                    facet_lifter_free(&l);
                }
                free(w), free(tg), free(z), free(before);
                test_mesh_free(&t);
            }
}

static void test_panels_extremes(void)
{
    for (int variant = 0; variant < NVARIANTS; ++variant)
        for (int si = 0; si < NSCALES; ++si)
            for (int oi = 0; oi < NOFFSETS; ++oi) {
                const double scale = SCALES[si], offset = OFFSETS[oi];
                /* panels need planar faces: a flat grid, with the variant's trouble */
                test_mesh t = make_mesh(variant, scale, offset);
                const int nv = t.mesh.n_vertices, nf = t.mesh.n_faces, nc = 4 * nf;
                for (int v = 0; v < nv; ++v)
                    t.xyz[3 * v + 2] = 0.25 * t.xyz[3 * v] - 0.5 * t.xyz[3 * v + 1];
                facet_panel_output out = test_panel_output(nv, nf, nc);
                const double thick[] = {1e-9, 0.05, 1e3};
                for (int k = 0; k < 3; ++k)
                    for (int edge = 0; edge < 2; ++edge) {
                        facet_panel_options o;
                        facet_panel_options_default(&o);
                        o.thickness = thick[k] * scale;
                        o.edge = (facet_panel_edge)edge;
                        o.gap = edge ? 1e-3 * scale : 0.0;
                        o.planarity_tol_rel = 1e-6;
                        facet_panel_result r;
                        facet_error e;
                        facet_status s = facet_panels(&t.mesh, &o, &out, &r, &e);
                        if (s >= 0) {
                            CHECK(test_panel_output_finite(&out, nv, nf, nc));
                            CHECK(isfinite(r.max_node_deviation) && isfinite(r.max_planarity));
                            ++n_solves;
                        } else {
                            ++n_solves, ++n_errors;
                            CHECK(e.message[0] != '\0');
                            CHECK(s == FACET_ERROR_NOT_PLANAR || s == FACET_ERROR_PANEL_GEOMETRY ||
                                  s == FACET_ERROR_NOT_ORIENTABLE);
                            if (variant == PLAIN && k < 2 && s != FACET_ERROR_NOT_PLANAR)
                                fprintf(stderr, "  panels: %s (scale %g offset %g thickness %g)\n",
                                        e.message, scale, offset, o.thickness);
                        }
                    }
                test_panel_output_free(&out);
                test_mesh_free(&t);
            }
}

int main(void)
{
    test_not_converged();
    test_measures_extremes();
    test_cleanup_extremes();
    test_lift_extremes();
    test_panels_extremes();
    test_planarize_extremes();
    printf("%d solves: %d warnings, %d refused with a status\n", n_solves, n_warnings, n_errors);
    return check_report("test_numeric_extremes");
}
