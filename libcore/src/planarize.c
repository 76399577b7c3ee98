/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Planarization by the penalty method of Poranne, Ovreiu and Gotsman (2013):
 *
 *   minimize  mu * sum_i |p_i - q_i|^2 + (1 - mu) * sum_corners (n_j . q_i + d_j)^2
 *
 * alternating a local step for the face planes (n_j, d_j) with either a
 * local step per vertex (local/local) or one sparse SPD solve for all q and d
 * (local/global), while mu falls geometrically to a floor mu_min.
 *
 * Every iteration starts with the plane fit of the current iterate, which is
 * also its planarity measurement: the tolerance test costs nothing extra.
 * Coordinates are centred on the bounding box and scaled by the mean edge
 * length inside the solver, so millimetres, metres and georeferenced
 * coordinates behave the same.
 *
 * Determinism: each loop iteration writes only its own face or vertex, sums
 * run in a fixed order, and reductions read per-element arrays serially, so
 * the bits do not depend on the thread count. */
#include "internal.h"

#include <cholmod.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

struct facet_planarizer {
    int32_t nv, nf, nc;
    int32_t *face_start, *face_vertices;
    int32_t *vertex_start, *vertex_faces; /* faces around each vertex, ascending */
    double *p, *q;                        /* control and current, normalised */
    double *normal, *offset;              /* per face */
    double *face_dev, *face_edge;         /* per face: max distance, mean edge length */
    double *previous;                     /* last result, model units (warm start) */
    int has_previous;
    /* local/global */
    int cholmod_started;
    cholmod_common cm;
    cholmod_sparse *matrix;
    cholmod_factor *factor;
    cholmod_dense *rhs;
    int32_t *corner_slot; /* per corner: index in matrix->x of its first coupling entry */
    char message[512];
};

static facet_status handle_fail(facet_planarizer *s, facet_error *error, facet_status status,
                                const char *text)
{
    snprintf(s->message, sizeof s->message, "%s", text);
    return facet_fail(error, status, -1, -1, "%s", text);
}

void facet_planarize_options_default(facet_method method, facet_planarize_options *o)
{
    memset(o, 0, sizeof *o);
    o->method = method;
    o->mu0 = 1.0;
    /* Measured (docs/solver-notes.md): the slower mu falls, the less the
     * vertices slide. L/G to 1e-6 on tubemesh, RMS displacement in mean edge
     * lengths: ratio 0.7 0.36 (54 iterations), 0.9 0.18 (178), 0.95 0.14
     * (333), 0.98 0.125 (762). 0.95 is the default for both schemes. The
     * floor on mu keeps every iterate bounded at any iteration count; L/G's
     * can be tiny because its global solve does not amplify the
     * ill-conditioned plane intersections at vertices of nearly parallel
     * faces the way L/L's local solve does. */
    o->ratio = 0.95;
    if (method == FACET_METHOD_LOCAL_GLOBAL) {
        o->mu_min = 1e-12;
        o->max_iter = 1000;
    } else {
        o->mu_min = 1e-6;
        o->max_iter = 3000;
    }
    o->tol_rel = 1e-6;
    o->tol_abs = 0.0;
    o->iterations = 0;
    o->threads = 0;
}

facet_status facet_planarizer_create(const facet_mesh *mesh, facet_planarizer **out,
                                     facet_error *error)
{
    facet_error_clear(error);
    if (!out)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1, "out is NULL");
    *out = NULL;
    facet_mesh_report report;
    facet_status status = facet_mesh_validate_topology(mesh, 0, &report, error);
    if (status < 0)
        return status;
    facet_error_clear(error);
    const int32_t nv = mesh->n_vertices, nf = mesh->n_faces, nc = mesh->face_start[nf];
    if ((int64_t)3 * nv + nf > INT32_MAX / 2 || (int64_t)nc * 3 > INT32_MAX / 2)
        return facet_fail(error, FACET_ERROR_TOO_LARGE, -1, -1,
                          "mesh too large: %d vertices, %d corners", (int)nv, (int)nc);
    facet_planarizer *s = calloc(1, sizeof *s);
    if (!s)
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    s->nv = nv, s->nf = nf, s->nc = nc;
    s->face_start = malloc(sizeof(int32_t) * (size_t)(nf + 1));
    s->face_vertices = malloc(sizeof(int32_t) * (size_t)nc);
    s->vertex_start = calloc((size_t)nv + 1, sizeof(int32_t));
    s->vertex_faces = malloc(sizeof(int32_t) * (size_t)nc);
    s->p = malloc(sizeof(double) * 3 * (size_t)nv);
    s->q = malloc(sizeof(double) * 3 * (size_t)nv);
    s->previous = malloc(sizeof(double) * 3 * (size_t)nv);
    s->normal = malloc(sizeof(double) * 3 * (size_t)nf);
    s->offset = malloc(sizeof(double) * (size_t)nf);
    s->face_dev = malloc(sizeof(double) * (size_t)nf);
    s->face_edge = malloc(sizeof(double) * (size_t)nf);
    if (!s->face_start || !s->face_vertices || !s->vertex_start || !s->vertex_faces || !s->p ||
        !s->q || !s->previous || !s->normal || !s->offset || !s->face_dev || !s->face_edge) {
        facet_planarizer_free(&s);
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    }
    memcpy(s->face_start, mesh->face_start, sizeof(int32_t) * (size_t)(nf + 1));
    memcpy(s->face_vertices, mesh->face_vertices, sizeof(int32_t) * (size_t)nc);
    /* vertex -> faces, faces ascending (a counting sort keeps the order). */
    for (int32_t k = 0; k < nc; ++k)
        s->vertex_start[s->face_vertices[k] + 1]++;
    for (int32_t v = 0; v < nv; ++v)
        s->vertex_start[v + 1] += s->vertex_start[v];
    int32_t *fill = malloc(sizeof(int32_t) * (size_t)nv);
    if (!fill) {
        facet_planarizer_free(&s);
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    }
    memcpy(fill, s->vertex_start, sizeof(int32_t) * (size_t)nv);
    for (int32_t f = 0; f < nf; ++f)
        for (int32_t k = s->face_start[f]; k < s->face_start[f + 1]; ++k)
            s->vertex_faces[fill[s->face_vertices[k]]++] = f;
    free(fill);
    *out = s;
    return FACET_OK;
}

void facet_planarizer_free(facet_planarizer **handle)
{
    if (!handle || !*handle)
        return;
    facet_planarizer *s = *handle;
    if (s->cholmod_started) {
        cholmod_free_sparse(&s->matrix, &s->cm);
        cholmod_free_factor(&s->factor, &s->cm);
        cholmod_free_dense(&s->rhs, &s->cm);
        cholmod_finish(&s->cm);
    }
    free(s->corner_slot);
    free(s->face_start);
    free(s->face_vertices);
    free(s->vertex_start);
    free(s->vertex_faces);
    free(s->p);
    free(s->q);
    free(s->previous);
    free(s->normal);
    free(s->offset);
    free(s->face_dev);
    free(s->face_edge);
    free(s);
    *handle = NULL;
}

const char *facet_planarizer_message(const facet_planarizer *s)
{
    return s ? s->message : "";
}

/* ---- local steps ------------------------------------------------------- */

/* Plane of every face of q, with its largest vertex distance and mean edge. */
static void fit_faces(facet_planarizer *s, int nthreads)
{
    const int32_t nf = s->nf;
    const int32_t *start = s->face_start, *fv = s->face_vertices;
    const double *q = s->q;
#pragma omp parallel for schedule(static) num_threads(nthreads)
    for (int32_t f = 0; f < nf; ++f) {
        const int32_t n = start[f + 1] - start[f];
        const int32_t *idx = fv + start[f];
        s->face_edge[f] = facet_face_measure(n, q, idx, s->normal + 3 * (size_t)f,
                                             &s->offset[f], &s->face_dev[f], NULL);
    }
}

/* Per vertex: (mu I + (1-mu) sum n n^T) q = mu p - (1-mu) sum d n.
 * Returns 0 if some result was not finite. */
static int local_vertex_step(facet_planarizer *s, double mu, int nthreads)
{
    const int32_t nv = s->nv;
    const double w = 1.0 - mu;
    int finite = 1;
#pragma omp parallel for schedule(static) num_threads(nthreads) reduction(&& : finite)
    for (int32_t v = 0; v < nv; ++v) {
        double a00 = mu, a01 = 0.0, a02 = 0.0, a11 = mu, a12 = 0.0, a22 = mu;
        const double *pv = s->p + 3 * (size_t)v;
        double b0 = mu * pv[0], b1 = mu * pv[1], b2 = mu * pv[2];
        for (int32_t k = s->vertex_start[v]; k < s->vertex_start[v + 1]; ++k) {
            const int32_t f = s->vertex_faces[k];
            const double *n = s->normal + 3 * (size_t)f;
            const double d = s->offset[f];
            a00 += w * n[0] * n[0], a01 += w * n[0] * n[1], a02 += w * n[0] * n[2];
            a11 += w * n[1] * n[1], a12 += w * n[1] * n[2], a22 += w * n[2] * n[2];
            b0 -= w * d * n[0], b1 -= w * d * n[1], b2 -= w * d * n[2];
        }
        /* 3x3 Cholesky (SPD since mu > 0). */
        const double l00 = sqrt(a00);
        const double l10 = a01 / l00, l20 = a02 / l00;
        const double l11 = sqrt(a11 - l10 * l10);
        const double l21 = (a12 - l20 * l10) / l11;
        const double l22 = sqrt(a22 - l20 * l20 - l21 * l21);
        const double y0 = b0 / l00;
        const double y1 = (b1 - l10 * y0) / l11;
        const double y2 = (b2 - l20 * y0 - l21 * y1) / l22;
        const double x2 = y2 / l22;
        const double x1 = (y1 - l21 * x2) / l11;
        const double x0 = (y0 - l10 * x1 - l20 * x2) / l00;
        double *qv = s->q + 3 * (size_t)v;
        if (isfinite(x0) && isfinite(x1) && isfinite(x2)) {
            qv[0] = x0, qv[1] = x1, qv[2] = x2;
        } else {
            finite = 0;
        }
    }
    return finite;
}

/* ---- local/global ------------------------------------------------------ */

/* Unknowns: q (3 nv) then d (nf). Upper triangle, CSC:
 *   column 3v+a: rows 3v..3v+a (the vertex's own 3x3 block);
 *   column 3nv+f: rows 3v+0..2 for each vertex v of f (ascending v), then
 *   the diagonal 3nv+f. */
static facet_status global_setup(facet_planarizer *s, facet_error *error)
{
    if (s->factor)
        return FACET_OK;
    const int32_t nv = s->nv, nf = s->nf, nc = s->nc;
    if (!s->cholmod_started) {
        cholmod_start(&s->cm);
        s->cm.print = 0;
        s->cm.error_handler = NULL;
        s->cholmod_started = 1;
    }
    const size_t n = 3 * (size_t)nv + (size_t)nf;
    const size_t nnz = 6 * (size_t)nv + 3 * (size_t)nc + (size_t)nf;
    s->matrix = cholmod_allocate_sparse(n, n, nnz, 1, 1, 1, CHOLMOD_REAL, &s->cm);
    s->rhs = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &s->cm);
    s->corner_slot = malloc(sizeof(int32_t) * (size_t)nc);
    if (!s->matrix || !s->rhs || !s->corner_slot)
        return handle_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory for the sparse system");
    int *cp = s->matrix->p, *ri = s->matrix->i;
    size_t at = 0;
    for (int32_t v = 0; v < nv; ++v)
        for (int a = 0; a < 3; ++a) {
            cp[3 * v + a] = (int)at;
            for (int b = 0; b <= a; ++b)
                ri[at++] = 3 * v + b;
        }
    int32_t order[64];
    for (int32_t f = 0; f < nf; ++f) {
        cp[3 * nv + f] = (int)at;
        const int32_t b = s->face_start[f], n_f = s->face_start[f + 1] - b;
        int32_t *ord = n_f <= 64 ? order : malloc(sizeof(int32_t) * (size_t)n_f);
        if (!ord)
            return handle_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory");
        for (int32_t k = 0; k < n_f; ++k) { /* insertion sort of corners by vertex */
            int32_t m = k;
            while (m > 0 && s->face_vertices[b + ord[m - 1]] > s->face_vertices[b + k]) {
                ord[m] = ord[m - 1];
                --m;
            }
            ord[m] = k;
        }
        for (int32_t k = 0; k < n_f; ++k) {
            const int32_t v = s->face_vertices[b + ord[k]];
            s->corner_slot[b + ord[k]] = (int32_t)at;
            for (int a = 0; a < 3; ++a)
                ri[at++] = 3 * v + a;
        }
        ri[at++] = 3 * nv + f;
        if (ord != order)
            free(ord);
    }
    cp[n] = (int)at;
    /* Structure only: analyse with unit values. */
    double *x = s->matrix->x;
    for (size_t k = 0; k < at; ++k)
        x[k] = 1.0;
    s->factor = cholmod_analyze(s->matrix, &s->cm);
    if (!s->factor || s->cm.status < CHOLMOD_OK)
        return handle_fail(s, error, FACET_ERROR_NUMERICAL, "sparse analysis failed");
    return FACET_OK;
}

static facet_status global_step(facet_planarizer *s, double mu, int nthreads, facet_error *error)
{
    const int32_t nv = s->nv, nf = s->nf;
    const double w = 1.0 - mu;
    double *x = s->matrix->x;
    const int *cp = s->matrix->p;
    double *b = s->rhs->x;
    /* vertex blocks */
#pragma omp parallel for schedule(static) num_threads(nthreads)
    for (int32_t v = 0; v < nv; ++v) {
        double a00 = mu, a01 = 0.0, a02 = 0.0, a11 = mu, a12 = 0.0, a22 = mu;
        for (int32_t k = s->vertex_start[v]; k < s->vertex_start[v + 1]; ++k) {
            const double *n = s->normal + 3 * (size_t)s->vertex_faces[k];
            a00 += w * n[0] * n[0], a01 += w * n[0] * n[1], a02 += w * n[0] * n[2];
            a11 += w * n[1] * n[1], a12 += w * n[1] * n[2], a22 += w * n[2] * n[2];
        }
        x[cp[3 * v]] = a00;
        x[cp[3 * v + 1]] = a01, x[cp[3 * v + 1] + 1] = a11;
        x[cp[3 * v + 2]] = a02, x[cp[3 * v + 2] + 1] = a12, x[cp[3 * v + 2] + 2] = a22;
        const double *pv = s->p + 3 * (size_t)v;
        b[3 * v] = mu * pv[0], b[3 * v + 1] = mu * pv[1], b[3 * v + 2] = mu * pv[2];
    }
#pragma omp parallel for schedule(static) num_threads(nthreads)
    for (int32_t f = 0; f < nf; ++f) {
        const double *n = s->normal + 3 * (size_t)f;
        const int32_t b0 = s->face_start[f], b1 = s->face_start[f + 1];
        for (int32_t k = b0; k < b1; ++k) {
            const int32_t at = s->corner_slot[k];
            x[at] = w * n[0], x[at + 1] = w * n[1], x[at + 2] = w * n[2];
        }
        x[cp[3 * nv + f + 1] - 1] = w * (double)(b1 - b0);
        b[3 * nv + f] = 0.0;
    }
    if (!cholmod_factorize(s->matrix, s->factor, &s->cm) || s->cm.status != CHOLMOD_OK)
        return handle_fail(s, error, FACET_ERROR_NUMERICAL,
                           "the sparse factorization failed (matrix not positive definite)");
    cholmod_dense *sol = cholmod_solve(CHOLMOD_A, s->factor, s->rhs, &s->cm);
    if (!sol)
        return handle_fail(s, error, FACET_ERROR_NUMERICAL, "the sparse solve failed");
    const double *y = sol->x;
    int finite = 1;
    for (size_t k = 0; k < 3 * (size_t)nv; ++k)
        if (!isfinite(y[k]))
            finite = 0;
    if (finite)
        memcpy(s->q, y, sizeof(double) * 3 * (size_t)nv);
    cholmod_free_dense(&sol, &s->cm);
    if (!finite)
        return handle_fail(s, error, FACET_ERROR_NUMERICAL, "the sparse solve gave a non-finite result");
    return FACET_OK;
}

/* ---- the solve --------------------------------------------------------- */

static facet_status check_options(const facet_planarize_options *o, char *text, size_t size)
{
    if (o->method != FACET_METHOD_LOCAL_LOCAL && o->method != FACET_METHOD_LOCAL_GLOBAL)
        return snprintf(text, size, "unknown method %d", (int)o->method), FACET_ERROR_INVALID_ARGUMENT;
    if (!(o->mu0 > 0.0 && o->mu0 <= 1.0))
        return snprintf(text, size, "mu0 must be in (0, 1], not %g", o->mu0), FACET_ERROR_INVALID_ARGUMENT;
    if (!(o->ratio > 0.0 && o->ratio <= 1.0))
        return snprintf(text, size, "ratio must be in (0, 1], not %g", o->ratio), FACET_ERROR_INVALID_ARGUMENT;
    if (!(o->mu_min > 0.0 && o->mu_min <= 1.0))
        return snprintf(text, size, "mu_min must be in (0, 1], not %g", o->mu_min), FACET_ERROR_INVALID_ARGUMENT;
    if (!(o->tol_abs >= 0.0) || !(o->tol_rel >= 0.0) || !isfinite(o->tol_abs) || !isfinite(o->tol_rel))
        return snprintf(text, size, "tolerances must be finite and >= 0"), FACET_ERROR_INVALID_ARGUMENT;
    if (o->max_iter < 0 || o->iterations < 0)
        return snprintf(text, size, "iteration counts must be >= 0"), FACET_ERROR_INVALID_ARGUMENT;
    return FACET_OK;
}

facet_status facet_planarizer_solve(facet_planarizer *s, const double *xyz_in,
                                    const facet_planarize_options *options, double *xyz_out,
                                    facet_planarize_result *result, facet_error *error)
{
    facet_error_clear(error);
    if (!s || !xyz_in || !xyz_out || !options)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1,
                          "planarizer, input, output and options must not be NULL");
    s->message[0] = '\0';
    const double t0 = facet_now();
    char text[256];
    facet_status status = check_options(options, text, sizeof text);
    if (status != FACET_OK)
        return handle_fail(s, error, status, text);
    const int32_t nv = s->nv, nf = s->nf;
    for (int32_t v = 0; v < nv; ++v) {
        const double *p = xyz_in + 3 * (size_t)v;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
            snprintf(s->message, sizeof s->message,
                     "vertex %d has a non-finite coordinate (%g, %g, %g)", (int)v, p[0], p[1], p[2]);
            return facet_fail(error, FACET_ERROR_NONFINITE, -1, v, "%s", s->message);
        }
    }
    const int nthreads = facet_thread_count(options->threads);

    /* Normalisation: centre of the bounding box, mean edge length. */
    double lo[3] = {xyz_in[0], xyz_in[1], xyz_in[2]}, hi[3] = {lo[0], lo[1], lo[2]};
    for (int32_t v = 1; v < nv; ++v)
        for (int a = 0; a < 3; ++a) {
            lo[a] = fmin(lo[a], xyz_in[3 * (size_t)v + a]);
            hi[a] = fmax(hi[a], xyz_in[3 * (size_t)v + a]);
        }
    const double centre[3] = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
    double edge_sum = 0.0;
    for (int32_t f = 0; f < nf; ++f) {
        const int32_t b = s->face_start[f], e = s->face_start[f + 1];
        for (int32_t k = b; k < e; ++k) {
            const double *a = xyz_in + 3 * (size_t)s->face_vertices[k];
            const double *c = xyz_in + 3 * (size_t)s->face_vertices[k + 1 < e ? k + 1 : b];
            edge_sum += sqrt((c[0] - a[0]) * (c[0] - a[0]) + (c[1] - a[1]) * (c[1] - a[1]) +
                             (c[2] - a[2]) * (c[2] - a[2]));
        }
    }
    double scale = edge_sum / (double)s->nc;
    if (!(scale > 0.0) || !isfinite(scale))
        return handle_fail(s, error, FACET_ERROR_DEGENERATE_FACE,
                           "every edge of the mesh has zero length");
    const double inv = 1.0 / scale;
    const int warm = options->warm && s->has_previous;
    const double *start_xyz = warm ? s->previous : xyz_in;
    for (int32_t v = 0; v < nv; ++v)
        for (int a = 0; a < 3; ++a) {
            s->p[3 * (size_t)v + a] = (xyz_in[3 * (size_t)v + a] - centre[a]) * inv;
            s->q[3 * (size_t)v + a] = (start_xyz[3 * (size_t)v + a] - centre[a]) * inv;
        }

    if (options->method == FACET_METHOD_LOCAL_GLOBAL) {
        status = global_setup(s, error);
        if (status != FACET_OK)
            return status;
    }

    const int fixed = options->iterations > 0;
    const int32_t limit = fixed ? options->iterations : options->max_iter;
    const double tol_abs = options->tol_abs * inv; /* normalised units */
    const double tol_rel = options->tol_rel;
    const int use_tol = !fixed && (tol_abs > 0.0 || tol_rel > 0.0);
    double mu = options->mu0;
    int32_t it = 0;
    facet_stop_reason reason = FACET_STOP_NONE;
    double max_abs = 0.0, max_rel = 0.0;
    enum { WINDOW = 25 };
    double history[WINDOW];
    status = FACET_OK;
    for (;;) {
        fit_faces(s, nthreads);
        max_abs = 0.0, max_rel = 0.0;
        for (int32_t f = 0; f < nf; ++f) {
            max_abs = fmax(max_abs, s->face_dev[f]);
            const double e = s->face_edge[f];
            max_rel = fmax(max_rel, e > 0.0 ? s->face_dev[f] / e : (s->face_dev[f] > 0.0 ? INFINITY : 0.0));
        }
        /* A warm start begins at the previous (planar) result: it must take the
         * edited control positions into account before it may stop. */
        if (use_tol && (it > 0 || !warm) && (tol_abs <= 0.0 || max_abs <= tol_abs) &&
            (tol_rel <= 0.0 || max_rel <= tol_rel)) {
            reason = FACET_STOP_TOLERANCE;
            break;
        }
        if (it >= limit) {
            reason = fixed ? FACET_STOP_ITERATIONS : FACET_STOP_MAX_ITER;
            break;
        }
        /* Stagnation: mu at its floor and no 2% gain over the last WINDOW iterations. */
        if (!fixed && it >= WINDOW && mu <= options->mu_min &&
            max_rel > 0.98 * history[it % WINDOW]) {
            reason = FACET_STOP_STAGNATION;
            break;
        }
        history[it % WINDOW] = max_rel;
        if (mu >= 1.0) {
            /* at mu = 1 the solution is the control mesh itself */
            memcpy(s->q, s->p, sizeof(double) * 3 * (size_t)nv);
        } else if (options->method == FACET_METHOD_LOCAL_LOCAL) {
            if (!local_vertex_step(s, mu, nthreads)) {
                status = handle_fail(s, error, FACET_ERROR_NUMERICAL,
                                     "a vertex update was not finite");
                break;
            }
        } else {
            status = global_step(s, mu, nthreads, error);
            if (status != FACET_OK)
                break;
        }
        ++it;
        mu = fmax(mu * options->ratio, options->mu_min);
        if (options->progress &&
            options->progress(options->progress_user, it, limit, max_rel) != 0) {
            reason = FACET_STOP_CANCELLED;
            status = handle_fail(s, error, FACET_ERROR_CANCELLED, "cancelled");
            break;
        }
    }
    if (status < 0 && status != FACET_ERROR_CANCELLED)
        return status;

    if (it == 0) {
        /* Nothing was solved: give back the starting point bit for bit. */
        if (xyz_out != start_xyz)
            memmove(xyz_out, start_xyz, sizeof(double) * 3 * (size_t)nv);
    } else {
        /* input plus displacement: a vertex that did not move keeps its bits,
         * even at georeferenced coordinates */
        for (size_t k = 0; k < 3 * (size_t)nv; ++k)
            xyz_out[k] = xyz_in[k] + (s->q[k] - s->p[k]) * scale;
    }
    if (s->previous != xyz_out)
        memmove(s->previous, xyz_out, sizeof(double) * 3 * (size_t)nv);
    s->has_previous = 1;
    if (result) {
        result->iterations = it;
        result->stop_reason = reason;
        result->mu = mu;
        result->planarity_max_abs = max_abs * scale;
        result->planarity_max_rel = max_rel;
        result->seconds = facet_now() - t0;
    }
    if (status == FACET_ERROR_CANCELLED)
        return status;
    if (reason == FACET_STOP_MAX_ITER || reason == FACET_STOP_STAGNATION) {
        snprintf(s->message, sizeof s->message,
                 "planarity %.3g (relative) after %d iterations: tolerance not reached", max_rel,
                 (int)it);
        return facet_fail(error, FACET_WARNING_NOT_CONVERGED, -1, -1, "%s", s->message);
    }
    return FACET_OK;
}
