/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Planarization by the penalty method of Poranne, Ovreiu and Gotsman (2013):
 *
 *   minimize  mu * (data and regularizers) + (1 - mu) * (planarity and constraints)
 *
 * alternating local steps for the per-face variables (planes, shapes,
 * circles) and the boundary targets with either a local step per vertex
 * (local/local) or one sparse SPD solve for all vertices and plane offsets
 * (local/global), while mu falls geometrically to a floor mu_min. The terms
 * are listed in facet.h (facet_planarize_options); the local steps are in
 * planarize_local.c, the global system in planarize_global.c.
 *
 * Anderson acceleration (Peng et al. 2018) extrapolates the vertex iterates
 * from the last m steps; an accelerated iterate is kept only if the energy of
 * the current mu does not rise above that of the iterate it came from
 * (the un-accelerated step never raises it), else the plain step is taken
 * and the history restarts.
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
#include "planarize_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

facet_status facet_pl_fail(facet_planarizer *s, facet_error *error, facet_status status,
                           const char *text)
{
    snprintf(s->message, sizeof s->message, "%s", text);
    return facet_fail(error, status, -1, -1, "%s", text);
}

void facet_planarize_options_default(facet_method method, facet_planarize_options *o)
{
    if (!o)
        return;
    memset(o, 0, sizeof *o);
    o->method = method;
    o->mu0 = 1.0;
    /* The staircase schedule with Anderson acceleration (docs/solver-notes.md):
     * mu falls tenfold once a step moves no vertex by more than 1% of the
     * largest move of the first step at that mu (or after 40 steps), so each
     * mu's fixed point is nearly reached before the next: the result follows
     * the penalty path, which is what keeps vertices from sliding, and
     * Anderson acceleration makes each stay short. L/G to 1e-6, one thread,
     * iterations and RMS (max) vertex move in mean edges, against the
     * geometric schedule (ratio 0.95 every step, no acceleration):
     *   tubemesh   85, 0.140 (0.43)   vs 333, 0.141 (0.39)
     *   hypar     102, 0.280 (0.47)   vs 281, 0.324 (0.51)
     *   quad_dome  24, 0.0104         vs 188, 0.0104
     *   conical1   35, max 3e-4       vs 161, max 3e-4
     * The floor on mu keeps every iterate bounded at any iteration count;
     * L/G's can be tiny because its global solve does not amplify the
     * ill-conditioned plane intersections at vertices of nearly parallel
     * faces the way L/L's local solve does.
     * A hold of 1% lets panels collapse on some meshes: a 64 x 64 hypar grid
     * ends with 9 faces below 5 degrees (the smallest 0.3), Level 5 with
     * plane data 1.7 degrees. The angle floor (opt-in, angle_floor) with a
     * hold of 0.3% keeps every face of the benchmark and public meshes above
     * 5 degrees with point data (64 x 64 hypar: 191 iterations, 11.4
     * degrees), but not with plane or surface data (Level 5: 4.4 and 4.2
     * degrees after the floor lets go), nor with a sliding boundary and held
     * vertices, and it costs 10-60% more iterations and live updates 3-20
     * times more; so neither is the default (docs/solver-notes.md). What is:
     * a result with a new narrow corner is solved again along the penalty
     * path (quality_angle, planarize_quality.c). */
    o->ratio = 0.1;
    o->hold_tol = 0.01;
    o->hold_max = 40;
    o->anderson = 5;
    if (method == FACET_METHOD_LOCAL_LOCAL) {
        o->mu_min = FACET_LL_MU_MIN;
        o->max_iter = 3000;
    } else { /* L/G, and AUTO (which raises the floor to L/L's when it picks L/L) */
        o->mu_min = 1e-12;
        o->max_iter = 1000;
    }
    o->tol_rel = 1e-6;
    o->data_tangent = 1.0;
    o->data_normal = 1.0;
    o->laplacian_weights = FACET_LAPLACIAN_UNIFORM;
    o->shape = FACET_SHAPE_NONE;
    o->shape_weight = 1.0;
    o->boundary = FACET_BOUNDARY_FREE;
    o->angle_floor = 0.0; /* off: see above */
    o->quality_angle = 5.0; /* planarize_quality.c */
}

/* ---- topology --------------------------------------------------------------- */

typedef struct {
    int32_t lo, hi, from, face;
} half_edge;

static int compare_half_edge(const void *x, const void *y)
{
    const half_edge *a = x, *b = y;
    if (a->lo != b->lo)
        return a->lo < b->lo ? -1 : 1;
    if (a->hi != b->hi)
        return a->hi < b->hi ? -1 : 1;
    return a->face < b->face ? -1 : (a->face > b->face ? 1 : 0);
}

static int compare_int32(const void *x, const void *y)
{
    const int32_t a = *(const int32_t *)x, b = *(const int32_t *)y;
    return a < b ? -1 : (a > b ? 1 : 0);
}

/* Sorts and de-duplicates each list of a CSR structure in place. */
static void csr_sort_unique(int32_t n, int32_t *start, int32_t *items)
{
    int32_t out = 0;
    for (int32_t i = 0; i < n; ++i) {
        const int32_t b = start[i], e = start[i + 1];
        qsort(items + b, (size_t)(e - b), sizeof(int32_t), compare_int32);
        start[i] = out;
        for (int32_t k = b; k < e; ++k)
            if (k == b || items[k] != items[k - 1])
                items[out++] = items[k];
    }
    start[n] = out;
}

/* The half-edges, sorted by edge (lo, hi) then face; NULL if out of memory. */
static half_edge *sorted_half_edges(const facet_planarizer *s)
{
    half_edge *h = malloc(sizeof *h * (size_t)(s->nc ? s->nc : 1));
    if (!h)
        return NULL;
    for (int32_t f = 0; f < s->nf; ++f) {
        const int32_t b = s->face_start[f], e = s->face_start[f + 1];
        for (int32_t k = b; k < e; ++k) {
            const int32_t u = s->face_vertices[k], v = s->face_vertices[k + 1 < e ? k + 1 : b];
            h[k].lo = u < v ? u : v, h[k].hi = u < v ? v : u, h[k].from = u, h[k].face = f;
        }
    }
    qsort(h, (size_t)s->nc, sizeof *h, compare_half_edge);
    return h;
}

/* For each pair of distinct faces on one edge of the sorted half-edges h,
 * either both faces' counts go up in count[f + 1] (adj NULL), or each face
 * goes at its neighbour's next slot fill[f] of adj. */
static void walk_face_pairs(const half_edge *h, int32_t nc, int32_t *count, int32_t *fill, int32_t *adj)
{
    for (int32_t k = 0; k < nc;) {
        int32_t e = k + 1;
        while (e < nc && h[e].lo == h[k].lo && h[e].hi == h[k].hi)
            ++e;
        for (int32_t a = k; a < e; ++a)
            for (int32_t b = a + 1; b < e; ++b) {
                const int32_t fa = h[a].face, fb = h[b].face;
                if (fa == fb)
                    continue;
                if (adj)
                    adj[fill[fa]++] = fb, adj[fill[fb]++] = fa;
                else
                    count[fa + 1]++, count[fb + 1]++;
            }
        k = e;
    }
}

/* The faces sharing an edge with each face (face_adj), ascending: only the
 * face-normal Laplacian reads them, so they are built when it is first on. */
static int build_face_adjacency(facet_planarizer *s)
{
    const int32_t nf = s->nf, nc = s->nc;
    half_edge *h = sorted_half_edges(s);
    free(s->face_adj_start), free(s->face_adj); /* (left by a failed call) */
    s->face_adj = NULL;
    s->face_adj_start = calloc((size_t)nf + 1, sizeof(int32_t));
    if (!h || !s->face_adj_start) {
        free(h);
        return 0;
    }
    walk_face_pairs(h, nc, s->face_adj_start, NULL, NULL);
    for (int32_t f = 0; f < nf; ++f)
        s->face_adj_start[f + 1] += s->face_adj_start[f];
    const int32_t n_pairs = s->face_adj_start[nf];
    s->face_adj = malloc(sizeof(int32_t) * (size_t)(n_pairs ? n_pairs : 1));
    int32_t *ffill = malloc(sizeof(int32_t) * (size_t)(nf ? nf : 1));
    if (!s->face_adj || !ffill) {
        free(h), free(ffill);
        return 0;
    }
    memcpy(ffill, s->face_adj_start, sizeof(int32_t) * (size_t)nf);
    walk_face_pairs(h, nc, NULL, ffill, s->face_adj);
    free(h), free(ffill);
    csr_sort_unique(nf, s->face_adj_start, s->face_adj);
    return 1;
}

/* Vertex adjacency through edges, and the boundary loops. */
static int build_topology(facet_planarizer *s)
{
    const int32_t nv = s->nv, nc = s->nc;
    half_edge *h = sorted_half_edges(s);
    s->vertex_adj_start = calloc((size_t)nv + 1, sizeof(int32_t));
    s->vertex_adj = malloc(sizeof(int32_t) * 2 * (size_t)nc);
    s->boundary_prev = malloc(sizeof(int32_t) * (size_t)nv);
    s->boundary_next = malloc(sizeof(int32_t) * (size_t)nv);
    s->on_boundary = calloc((size_t)nv, 1);
    if (!h || !s->vertex_adj_start || !s->vertex_adj || !s->boundary_prev ||
        !s->boundary_next || !s->on_boundary) {
        free(h);
        return 0;
    }
    for (int32_t v = 0; v < nv; ++v)
        s->boundary_prev[v] = s->boundary_next[v] = -1;
    uint8_t *pinch = calloc((size_t)nv, 1);
    if (!pinch) {
        free(h);
        return 0;
    }
    /* counts */
    for (int32_t k = 0; k < nc;) {
        int32_t e = k + 1;
        while (e < nc && h[e].lo == h[k].lo && h[e].hi == h[k].hi)
            ++e;
        s->vertex_adj_start[h[k].lo + 1]++;
        s->vertex_adj_start[h[k].hi + 1]++;
        const int32_t m = e - k;
        if (m == 1) {
            const int32_t from = h[k].from, to = from == h[k].lo ? h[k].hi : h[k].lo;
            s->on_boundary[from] = s->on_boundary[to] = 1;
            if (s->boundary_next[from] >= 0)
                pinch[from] = 1;
            if (s->boundary_prev[to] >= 0)
                pinch[to] = 1;
            s->boundary_next[from] = to;
            s->boundary_prev[to] = from;
        }
        k = e;
    }
    for (int32_t v = 0; v < nv; ++v) {
        s->vertex_adj_start[v + 1] += s->vertex_adj_start[v];
        if (s->on_boundary[v] && (pinch[v] || s->boundary_prev[v] < 0 || s->boundary_next[v] < 0))
            s->boundary_prev[v] = s->boundary_next[v] = -1;
        s->n_boundary += s->on_boundary[v];
    }
    /* a neighbour of a pinch loses its link to it */
    for (int32_t v = 0; v < nv; ++v) {
        if (s->boundary_prev[v] >= 0 && s->boundary_prev[s->boundary_prev[v]] < 0)
            s->boundary_prev[v] = s->boundary_next[v] = -1;
        else if (s->boundary_next[v] >= 0 && s->boundary_next[s->boundary_next[v]] < 0)
            s->boundary_prev[v] = s->boundary_next[v] = -1;
    }
    free(pinch);
    int32_t *vfill = malloc(sizeof(int32_t) * (size_t)(nv ? nv : 1));
    if (!vfill) {
        free(h);
        return 0;
    }
    memcpy(vfill, s->vertex_adj_start, sizeof(int32_t) * (size_t)nv);
    for (int32_t k = 0; k < nc;) {
        int32_t e = k + 1;
        while (e < nc && h[e].lo == h[k].lo && h[e].hi == h[k].hi)
            ++e;
        s->vertex_adj[vfill[h[k].lo]++] = h[k].hi;
        s->vertex_adj[vfill[h[k].hi]++] = h[k].lo;
        k = e;
    }
    free(h), free(vfill);
    csr_sort_unique(nv, s->vertex_adj_start, s->vertex_adj);
    /* room for every corner twice, used about once (each edge twice): give
     * the rest back (a shrinking realloc keeps the contents) */
    int32_t *adj = realloc(s->vertex_adj, sizeof(int32_t) * (size_t)(s->vertex_adj_start[nv] ? s->vertex_adj_start[nv] : 1));
    if (adj)
        s->vertex_adj = adj;
    return 1;
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
    s->couple_key = -1;
    const size_t v3 = 3 * (size_t)nv * sizeof(double), fd = (size_t)nf * sizeof(double);
    s->face_start = malloc(sizeof(int32_t) * (size_t)(nf + 1));
    s->face_vertices = malloc(sizeof(int32_t) * (size_t)nc);
    s->vertex_start = calloc((size_t)nv + 1, sizeof(int32_t));
    s->vertex_faces = malloc(sizeof(int32_t) * (size_t)nc);
    s->fixed = malloc((size_t)nv);
    s->p = malloc(v3), s->q = malloc(v3); /* previous, previous_control: previous_storage */
    s->vertex_normal = malloc(v3);
    s->vertex_residual = malloc((size_t)nv * sizeof(double));
    s->normal = malloc(3 * fd), s->offset = malloc(fd);
    s->face_dev = malloc(fd), s->face_edge = malloc(fd), s->face_sq = malloc(fd);
    s->face_residual = malloc(fd);
    if (!s->face_start || !s->face_vertices || !s->vertex_start || !s->vertex_faces || !s->fixed ||
        !s->p || !s->q || !s->vertex_normal || !s->vertex_residual || !s->normal || !s->offset ||
        !s->face_dev || !s->face_edge || !s->face_sq || !s->face_residual) {
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
    if (!fill || !build_topology(s)) {
        free(fill);
        facet_planarizer_free(&s);
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    }
    memcpy(fill, s->vertex_start, sizeof(int32_t) * (size_t)nv);
    for (int32_t f = 0; f < nf; ++f)
        for (int32_t k = s->face_start[f]; k < s->face_start[f + 1]; ++k)
            s->vertex_faces[fill[s->face_vertices[k]]++] = f;
    free(fill);
    s->laplace_weight = malloc(sizeof(double) * (size_t)(s->vertex_adj_start[nv] ? s->vertex_adj_start[nv] : 1));
    if (!s->laplace_weight) {
        facet_planarizer_free(&s);
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    }
    *out = s;
    return FACET_OK;
}

void facet_planarizer_free(facet_planarizer **handle)
{
    if (!handle || !*handle)
        return;
    facet_planarizer *s = *handle;
    if (s->previous_in_history) /* freed with aa_df */
        s->previous = s->previous_control = NULL;
    facet_pl_global_free(s);
    facet_planarizer_free(&s->live);
    if (s->cholmod_started)
        cholmod_finish(&s->cm);
    void *arrays[] = {s->face_start, s->face_vertices, s->vertex_start, s->vertex_faces,
                      s->vertex_adj_start, s->vertex_adj, s->face_adj_start, s->face_adj,
                      s->boundary_prev, s->boundary_next, s->on_boundary, s->user_fixed,
                      s->face_weight, s->fixed, s->p, s->q, s->vertex_normal, s->normal,
                      s->offset, s->face_dev, s->face_edge, s->face_sq, s->face_residual, s->vertex_residual, s->normal_fit,
                      s->control_centroid, s->shape, s->circle_target, s->slide_target,
                      s->slide_tangent, s->laplace_weight, s->previous, s->aa_df, s->aa_dg,
                      s->q_next, s->surface_point,
                      s->surface_normal, s->surface_query, s->previous_control,
                      s->live_vertex, s->live_changed, s->live_mark, s->live_xyz, s->live_face_dev,
                      s->guard_count, s->guard_sum, s->corner_floor, s->corner_cos, s->face_guard,
                      s->face_plane_terms};
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; ++k)
        free(arrays[k]);
    free(s);
    *handle = NULL;
}

const char *facet_planarizer_message(const facet_planarizer *s)
{
    return s ? s->message : "";
}

facet_status facet_planarizer_set_fixed(facet_planarizer *s, int32_t n, const int32_t *vertices,
                                        facet_error *error)
{
    facet_error_clear(error);
    if (!s || n < 0 || (n > 0 && !vertices))
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1,
                          "planarizer must not be NULL, n must be >= 0 and vertices given when n > 0");
    for (int32_t k = 0; k < n; ++k)
        if (vertices[k] < 0 || vertices[k] >= s->nv)
            return facet_fail(error, FACET_ERROR_INDEX_OUT_OF_RANGE, -1, vertices[k],
                              "fixed vertex %d (entry %d) is out of range (%d vertices)",
                              (int)vertices[k], (int)k, (int)s->nv);
    if (n == s->n_user_fixed && (n == 0 || memcmp(vertices, s->user_fixed, sizeof(int32_t) * (size_t)n) == 0))
        return FACET_OK; /* unchanged: a live region stays valid */
    int32_t *copy = NULL;
    if (n > 0) {
        copy = malloc(sizeof(int32_t) * (size_t)n);
        if (!copy)
            return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
        memcpy(copy, vertices, sizeof(int32_t) * (size_t)n);
    }
    free(s->user_fixed);
    s->user_fixed = copy;
    s->n_user_fixed = n;
    s->live_stale = 1; /* the next live update solves in full */
    return FACET_OK;
}

facet_status facet_planarizer_set_reference(facet_planarizer *s, const facet_surface *surface,
                                            facet_error *error)
{
    facet_error_clear(error);
    if (!s)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1, "planarizer is NULL");
    if (s->reference != surface)
        s->live_stale = 1;
    s->reference = surface;
    return FACET_OK;
}

facet_status facet_planarizer_set_face_weights(facet_planarizer *s, const double *weights,
                                               facet_error *error)
{
    facet_error_clear(error);
    if (!s)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1, "planarizer is NULL");
    if (!weights && !s->face_weight)
        return FACET_OK;
    if (weights && s->face_weight && memcmp(weights, s->face_weight, sizeof(double) * (size_t)s->nf) == 0)
        return FACET_OK; /* unchanged: a live region stays valid */
    s->live_stale = 1;
    if (!weights) {
        free(s->face_weight);
        s->face_weight = NULL;
        return FACET_OK;
    }
    for (int32_t f = 0; f < s->nf; ++f)
        if (!(weights[f] >= 0.0) || !(weights[f] <= FACET_FACE_WEIGHT_MAX))
            return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, f, -1,
                              "face %d has planarity weight %g; weights must be in [0, 1e6]",
                              (int)f, weights[f]);
    if (!s->face_weight) {
        s->face_weight = malloc(sizeof(double) * (size_t)s->nf);
        if (!s->face_weight)
            return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    }
    memcpy(s->face_weight, weights, sizeof(double) * (size_t)s->nf);
    return FACET_OK;
}

/* ---- options ------------------------------------------------------------ */

/* L/L reaches the tolerance only with the staircase (its finish); the
 * paper's schedule (hold_tol 0) stalls at its floor. */
static int ll_finishes(const facet_planarize_options *o)
{
    return o->hold_tol > 0.0;
}

facet_method facet_planarizer_choose_method(const facet_planarizer *s,
                                            const facet_planarize_options *options)
{
    facet_planarize_options defaults;
    if (!options) {
        facet_planarize_options_default(FACET_METHOD_AUTO, &defaults);
        options = &defaults;
    }
    const int32_t most = ll_finishes(options) ? FACET_AUTO_LG_MAX_CORNERS
                                              : FACET_AUTO_LG_MAX_CORNERS_STAIRCASE;
    return s && s->nc > most ? FACET_METHOD_LOCAL_LOCAL : FACET_METHOD_LOCAL_GLOBAL;
}

static facet_status check_options(const facet_planarize_options *o, int has_reference, char *text,
                                  size_t size)
{
#define BAD(...) return snprintf(text, size, __VA_ARGS__), FACET_ERROR_INVALID_ARGUMENT
    if (o->method != FACET_METHOD_LOCAL_LOCAL && o->method != FACET_METHOD_LOCAL_GLOBAL &&
        o->method != FACET_METHOD_AUTO)
        BAD("unknown method %d", (int)o->method);
    if (!(o->mu0 > 0.0 && o->mu0 <= 1.0))
        BAD("mu0 must be in (0, 1], not %g", o->mu0);
    if (!(o->ratio > 0.0 && o->ratio <= 1.0))
        BAD("ratio must be in (0, 1], not %g", o->ratio);
    if (!(o->mu_min > 0.0 && o->mu_min <= 1.0))
        BAD("mu_min must be in (0, 1], not %g", o->mu_min);
    if (!(o->tol_abs >= 0.0) || !(o->tol_rel >= 0.0) || !isfinite(o->tol_abs) || !isfinite(o->tol_rel))
        BAD("tolerances must be finite and >= 0");
    if (o->max_iter < 0 || o->iterations < 0)
        BAD("iteration counts must be >= 0");
    const struct {
        const char *name;
        double value;
    } weights[] = {{"data_tangent", o->data_tangent}, {"data_normal", o->data_normal},
                   {"surface_weight", o->surface_weight}, {"laplacian", o->laplacian},
                   {"normal_laplacian", o->normal_laplacian},
                   {"boundary_fairness", o->boundary_fairness}, {"shape_weight", o->shape_weight},
                   {"circular", o->circular}, {"parallelogram", o->parallelogram},
                   {"time_budget", o->time_budget}};
    for (size_t k = 0; k < sizeof weights / sizeof weights[0]; ++k)
        if (!(weights[k].value >= 0.0) || !isfinite(weights[k].value))
            BAD("%s must be finite and >= 0, not %g", weights[k].name, weights[k].value);
    if (!(o->data_tangent > 0.0))
        BAD("data_tangent must be > 0: a vertex with no pull along the surface could drift "
            "without bound");
    /* beside a weight FACET_WEIGHT_SPAN times data_tangent's the data term is lost to
     * rounding and the vertices drift (fuzzing: parallelogram 1e16 moved a unit grid's
     * vertices by 900, and boundary_fairness 1e16 by 1,300, with FACET_OK); a shape weight
     * with no shape term is not read */
    for (size_t k = 1; k + 1 < sizeof weights / sizeof weights[0]; ++k)
        if (weights[k].value > FACET_WEIGHT_SPAN * o->data_tangent &&
            !(o->shape == FACET_SHAPE_NONE && strcmp(weights[k].name, "shape_weight") == 0))
            BAD("%s %g is more than %g times data_tangent (%g): beside it the data term is "
                "lost to rounding", weights[k].name, weights[k].value, FACET_WEIGHT_SPAN,
                o->data_tangent);
    if (o->laplacian_weights != FACET_LAPLACIAN_UNIFORM &&
        o->laplacian_weights != FACET_LAPLACIAN_INVERSE_EDGE)
        BAD("unknown laplacian_weights %d", (int)o->laplacian_weights);
    if (o->shape != FACET_SHAPE_NONE && o->shape != FACET_SHAPE_ASAP && o->shape != FACET_SHAPE_ARAP)
        BAD("unknown shape mode %d", (int)o->shape);
    if (o->boundary != FACET_BOUNDARY_FREE && o->boundary != FACET_BOUNDARY_FIXED &&
        o->boundary != FACET_BOUNDARY_SLIDING)
        BAD("unknown boundary mode %d", (int)o->boundary);
    if (!(o->angle_floor >= 0.0 && o->angle_floor < 60.0))
        BAD("angle_floor must be in [0, 60) degrees, not %g", o->angle_floor);
    if (!(o->quality_angle >= 0.0 && o->quality_angle < 60.0))
        BAD("quality_angle must be in [0, 60) degrees, not %g", o->quality_angle);
    if (!(o->hold_tol >= 0.0) || !isfinite(o->hold_tol))
        BAD("hold_tol must be finite and >= 0, not %g", o->hold_tol);
    if (o->hold_max < 1)
        BAD("hold_max must be >= 1, not %d", (int)o->hold_max);
    if (o->anderson < 0 || o->anderson > FACET_ANDERSON_MAX)
        BAD("anderson must be in 0..%d, not %d", FACET_ANDERSON_MAX, (int)o->anderson);
    if (o->surface_weight > 0.0 && !has_reference)
        BAD("surface_weight needs a reference surface (facet_planarizer_set_reference), and "
            "none is set");
#undef BAD
    return FACET_OK;
}

facet_status facet_pl_check_options(facet_planarizer *s, const facet_planarize_options *options,
                                   facet_error *error)
{
    char text[256];
    const facet_status status = check_options(options, s->reference != NULL, text, sizeof text);
    return status == FACET_OK ? FACET_OK : facet_pl_fail(s, error, status, text);
}

/* Dot products are summed in blocks of ANDERSON_BLOCK entries, each block in
 * index order, then the blocks' sums in block order: the bits do not depend
 * on the thread count, and a mesh of up to ANDERSON_BLOCK / 3 vertices (one
 * block) sums exactly as a plain serial loop. */
enum {
    ANDERSON_BLOCK = 32768,
    ANDERSON_PIECE = 3 * 512, /* entries: whole vertices, 12 KB of each column */
    ANDERSON_PARTIAL = 2 * FACET_ANDERSON_MAX + 2 /* per block: the sums, largest |f|, move */
};

static size_t anderson_blocks(size_t n)
{
    return (n + ANDERSON_BLOCK - 1) / ANDERSON_BLOCK;
}

/* Anderson's sketch (planarize_internal.h, FACET_ANDERSON_SKETCH_VERTICES):
 * a block's pieces of ANDERSON_PIECE entries run from its first whole vertex,
 * at most ANDERSON_BLOCK_PIECES of them, and with the sketch the residual
 * differences are kept for every stride-th piece (0, 8, 16) only, packed
 * block by block in anderson_block_room entries each. At a million faces the
 * history is the iteration's largest stream through memory; the least
 * squares over a sample saves 7 of a step's 19 streams of 24 MB, and its
 * (at most 5) unknowns are as well determined by 400,000 entries as by 3
 * million. */
enum { ANDERSON_BLOCK_PIECES = (ANDERSON_BLOCK + ANDERSON_PIECE - 1) / ANDERSON_PIECE };

static int anderson_stride(int32_t nv)
{
    return nv >= FACET_ANDERSON_SKETCH_VERTICES ? FACET_ANDERSON_SKETCH_STRIDE : 1;
}

static size_t anderson_block_room(int stride)
{
    return (size_t)((ANDERSON_BLOCK_PIECES + stride - 1) / stride) * ANDERSON_PIECE;
}

/* The entries of one column of the residuals' differences (aa_df). */
size_t facet_pl_anderson_len(int32_t nv)
{
    const size_t n = 3 * (size_t)nv;
    const int stride = anderson_stride(nv);
    return stride == 1 ? n : anderson_blocks(n) * anderson_block_room(stride);
}

/* Allocates what the options need beyond the base workspace. */
static int ensure_workspace(facet_planarizer *s)
{
    const facet_planarize_options *o = &s->o;
    /* the shape term's rotations and the control faces' centroids it is
     * anchored at: only the shape term reads them (24 bytes per face that
     * every solve wrote before) */
    if (o->shape != FACET_SHAPE_NONE && !s->shape &&
        !(s->shape = malloc(sizeof(double) * 9 * (size_t)s->nf)))
        return 0;
    if (o->shape != FACET_SHAPE_NONE && !s->control_centroid &&
        !(s->control_centroid = malloc(sizeof(double) * 3 * (size_t)s->nf)))
        return 0;
    if (o->surface_weight > 0.0 && !s->surface_point) {
        s->surface_point = malloc(sizeof(double) * 3 * (size_t)s->nv);
        s->surface_normal = malloc(sizeof(double) * 3 * (size_t)s->nv);
        s->surface_query = malloc(sizeof(double) * 3 * (size_t)s->nv);
        if (!s->surface_point || !s->surface_normal || !s->surface_query)
            return 0;
    }
    if (o->circular > 0.0 && !s->circle_target &&
        !(s->circle_target = malloc(sizeof(double) * 3 * (size_t)s->nc)))
        return 0;
    if (o->angle_floor > 0.0 && !s->guard_count) {
        s->guard_count = calloc((size_t)s->nv, sizeof(double)); /* zero while no corner is held */
        s->guard_sum = malloc(sizeof(double) * 3 * (size_t)s->nv);
        s->corner_floor = malloc(sizeof(double) * (size_t)s->nc);
        s->corner_cos = malloc(sizeof(double) * (size_t)s->nc);
        s->face_guard = malloc((size_t)s->nf);
        if (!s->guard_count || !s->guard_sum || !s->corner_floor || !s->corner_cos || !s->face_guard)
            return 0;
    }
    if (o->method == FACET_METHOD_LOCAL_LOCAL && !s->face_plane_terms &&
        !(s->face_plane_terms = malloc(sizeof(double) * 9 * (size_t)s->nf)))
        return 0;
    /* what only some terms or one method read: allocated when first asked
     * for (issue 3's memory target), kept for later solves */
    if (o->method == FACET_METHOD_LOCAL_LOCAL && !s->q_next &&
        !(s->q_next = malloc(sizeof(double) * 3 * (size_t)s->nv)))
        return 0;
    if (o->boundary == FACET_BOUNDARY_SLIDING && !s->slide_target) {
        s->slide_target = calloc(3 * (size_t)s->nv, sizeof(double));
        s->slide_tangent = calloc(3 * (size_t)s->nv, sizeof(double));
        if (!s->slide_target || !s->slide_tangent)
            return 0;
    }
    if (o->normal_laplacian > 0.0 && !s->normal_fit &&
        !(s->normal_fit = malloc(sizeof(double) * 3 * (size_t)s->nf)))
        return 0;
    if (o->normal_laplacian > 0.0 && !s->face_adj && !build_face_adjacency(s))
        return 0;
    if (o->anderson > s->aa_capacity) {
        /* the depth asked for, not FACET_ANDERSON_MAX: at depth 5 the history
         * is 240 bytes per vertex, at 16 it would be 768 (issue 3's memory
         * target is 1 KB per face); the last step's f and g live in the
         * ring's next slot (anderson_prev_col), a column beside it at depth 1 */
        const size_t v3 = 3 * (size_t)s->nv, columns = o->anderson == 1 ? 2 : (size_t)o->anderson;
        const size_t df = columns * facet_pl_anderson_len(s->nv);
        double *old = s->aa_df;
        free(s->aa_dg);
        s->aa_df = malloc(sizeof(double) * (df > 2 * v3 ? df : 2 * v3));
        s->aa_dg = malloc(sizeof(double) * v3 * columns);
        if (s->previous_in_history) { /* the last result moves with the history's memory */
            if (s->aa_df)
                memcpy(s->aa_df, old, sizeof(double) * 2 * v3);
            s->previous = s->aa_df, s->previous_control = s->aa_df ? s->aa_df + v3 : NULL;
            if (!s->aa_df)
                s->has_previous = 0, s->previous_in_history = 0;
        }
        free(old);
        s->aa_capacity = s->aa_df && s->aa_dg ? o->anderson : 0;
        if (!s->aa_df || !s->aa_dg)
            return 0;
    }
    return 1;
}

/* Between solves the Anderson history holds only the last result and its
 * control positions (previous_storage): gives back the rest, for work done
 * after a solve (method AUTO's comparison measures); the next solve
 * allocates it again (ensure_workspace). */
void facet_pl_history_trim(facet_planarizer *s)
{
    if (!s->aa_df)
        return;
    free(s->aa_dg);
    s->aa_dg = NULL;
    s->aa_capacity = 0;
    if (!s->previous_in_history) {
        free(s->aa_df);
        s->aa_df = NULL;
        return;
    }
    const size_t v3 = 3 * (size_t)s->nv;
    double *kept = realloc(s->aa_df, sizeof(double) * 2 * v3);
    if (kept)
        s->aa_df = kept, s->previous = kept, s->previous_control = kept + v3;
}

/* Where the last result and its control positions are kept between solves:
 * the first two columns of the Anderson history (at least two when it is
 * allocated), which a solve needs only from its first step to its end,
 * while the last result is read only before (the warm start) and both are
 * written only after: so they add nothing to a solve's peak memory (issue 3:
 * 48 bytes per vertex). Without a history, arrays of their own. Returns 0 if
 * out of memory. */
static int previous_storage(facet_planarizer *s)
{
    if (s->previous)
        return 1;
    const size_t v3 = 3 * (size_t)s->nv;
    if (s->aa_df) {
        s->previous = s->aa_df, s->previous_control = s->aa_df + v3;
        s->previous_in_history = 1;
        return 1;
    }
    s->previous = malloc(sizeof(double) * v3);
    s->previous_control = malloc(sizeof(double) * v3);
    if (s->previous && s->previous_control)
        return 1;
    free(s->previous), free(s->previous_control);
    s->previous = s->previous_control = NULL;
    return 0;
}

/* ---- Anderson acceleration ------------------------------------------------ */

typedef struct {
    int m, count, head;       /* depth, columns held, next slot */
    int have_previous;        /* the previous step's f and g are held (anderson_prev_col) */
    int plain_col;            /* the column where the last step left its g (kept by a restart) */
    int nthreads;
    double gram[FACET_ANDERSON_MAX][FACET_ANDERSON_MAX]; /* dF^T dF by slot (sampled) */
    double *partial;          /* per block: 2 m dot-product parts and the largest |f| */
} anderson_state;

/* Forgets the history: the map changed (a new mu, the floor let go, the
 * finish) or an accelerated step was refused. */
static void anderson_restart(anderson_state *a)
{
    a->count = a->head = 0;
    a->have_previous = 0;
}

/* The column of aa_df and aa_dg that holds the last step's f = g - x and g
 * (its plain iterate): the ring's next slot, whose difference the next step
 * writes there in place, reading them; once the ring is full that is its
 * oldest column, which the step that stores them still reads first. At
 * depth 1 the ring's one column is the next slot too: a column beside it. */
static int anderson_prev_col(const anderson_state *a)
{
    return a->m == 1 ? 1 : a->head;
}

/* The last step's plain iterate g (valid after an anderson_step, until the
 * next one; a restart in between, as when mu changes, does not move it). */
static const double *anderson_plain(const facet_planarizer *s, const anderson_state *a)
{
    return s->aa_dg + (size_t)a->plain_col * 3 * (size_t)s->nv;
}

/* The squared distance between a vertex's two positions. */
static inline double vertex_move2(const double *g, const double *x)
{
    return (x[0] - g[0]) * (x[0] - g[0]) + (x[1] - g[1]) * (x[1] - g[1]) + (x[2] - g[2]) * (x[2] - g[2]);
}

/* What a pass of anderson_step reads and writes (see there). */
typedef struct {
    const double *g, *x;
    double *df_new, *dg_new;
    const double *f_prev, *g_prev;
    double *f_to;
    const double *df_all;
    size_t n, len;            /* entries of a column of g, of dF (facet_pl_anderson_len) */
    int m, have;
} anderson_pass;

/* anderson_piece's `at` for a piece outside the sketch's sample */
#define ANDERSON_UNSAMPLED SIZE_MAX

/* The first pass of anderson_step over entries [c0, c1): the new
 * differences, largest |f|, the new Gram row's and the right-hand side's
 * sums (in index order), f into its column and, given `moved` (c0 and c1
 * then at whole vertices), the largest squared move g - x of a vertex. The
 * residual's entries are at `at` .. in dF's columns (c0 .. without the
 * sketch); a piece the sketch leaves out (ANDERSON_UNSAMPLED) gives only
 * dG's difference, largest |f| and the move. */
static inline void anderson_piece(const anderson_pass *c, size_t c0, size_t c1, size_t at, double *largest,
                                  double *gsum, double *rsum, double *moved)
{
    const double *g = c->g, *x = c->x, *f_prev = c->f_prev, *g_prev = c->g_prev, *df_all = c->df_all;
    double *df_new = c->df_new, *dg_new = c->dg_new, *f_to = c->f_to;
    const size_t len = c->len;
    const int m = c->m;
    double big = *largest; /* (locals: the stores below might alias the pointers) */
    if (!c->have) {
        for (size_t k = c0; k < c1; ++k)
            big = facet_max(big, fabs(g[k] - x[k]));
    } else if (at == ANDERSON_UNSAMPLED) {
        for (size_t k = c0; k < c1; ++k) {
            dg_new[k] = g[k] - g_prev[k];
            big = facet_max(big, fabs(g[k] - x[k]));
        }
    } else { /* in place: each entry is read, then written */
        for (size_t k = c0, i = at; k < c1; ++k, ++i) {
            const double f = g[k] - x[k];
            df_new[i] = f - f_prev[i];
            dg_new[k] = g[k] - g_prev[k];
            big = facet_max(big, fabs(f));
        }
    }
    *largest = big;
    if (m > 0 && at != ANDERSON_UNSAMPLED) {
        double gs[FACET_ANDERSON_MAX], rs[FACET_ANDERSON_MAX];
        for (int j = 0; j < m; ++j)
            gs[j] = gsum[j], rs[j] = rsum[j];
        for (size_t k = c0, i = at; k < c1; ++k, ++i) {
            const double d = df_new[i], f = g[k] - x[k];
            for (int j = 0; j < m; ++j) {
                const double dfjk = df_all[(size_t)j * len + i];
                gs[j] += d * dfjk;
                rs[j] += dfjk * f;
            }
        }
        for (int j = 0; j < m; ++j)
            gsum[j] = gs[j], rsum[j] = rs[j];
    }
    if (moved) {
        double most = *moved;
        for (size_t k = c0; k < c1; k += 3)
            most = facet_max(most, vertex_move2(g + k, x + k));
        *moved = most;
    }
    /* then f into its column, which (the ring full) the sums have read */
    if (at != ANDERSON_UNSAMPLED)
        for (size_t k = c0, i = at; k < c1; ++k, ++i)
            f_to[i] = g[k] - x[k];
}

/* The extrapolation over entries [k0, k1): g - dG theta into g, the plain g
 * kept in its column g_to (which the sum reads first). Whether all finite. */
static inline int anderson_extrapolate(double *g, double *g_to, const double *dg_all, const double *theta,
                                       int m, size_t n, size_t k0, size_t k1)
{
    int finite = 1;
    for (size_t k = k0; k < k1; ++k) {
        double value = g[k];
        for (int j = 0; j < m; ++j)
            value -= theta[j] * dg_all[(size_t)j * n + k];
        g_to[k] = g[k]; /* the plain iterate, after the sum read its column */
        g[k] = value;
        finite = finite && isfinite(value);
    }
    return finite;
}

/* Keeps the plain iterate g as the last step's (anderson_prev_col) when no
 * extrapolation reads the history. Returns 0 (not accelerated). */
static int anderson_keep_plain(double *g_to, const double *g, size_t n, int nthreads)
{
#pragma omp parallel for schedule(static) num_threads(nthreads)
    for (size_t blk = 0; blk < anderson_blocks(n); ++blk) {
        const size_t k0 = blk * ANDERSON_BLOCK, k1 = k0 + ANDERSON_BLOCK < n ? k0 + ANDERSON_BLOCK : n;
        memcpy(g_to + k0, g + k0, sizeof(double) * (k1 - k0));
    }
    return 0;
}

/* Given the step x -> g (x in `x`, g in s->q), records the differences and
 * writes the accelerated iterate into s->q. Returns 1 if it accelerated.
 * One pass over the history for the new Gram row and the right-hand side,
 * one for the extrapolation, both in parallel over blocks: at a million
 * faces the serial passes cost as much as the local steps. */
static int anderson_step(facet_planarizer *s, anderson_state *a, const double *x, double *move)
{
    const size_t n = 3 * (size_t)s->nv;
    double *g = s->q;
    const int have = a->have_previous;
    const int slot = a->head;
    const int from = anderson_prev_col(a); /* the previous f and g (if have): slot itself unless m = 1 */
    if (have) {
        a->head = (a->head + 1) % a->m;
        if (a->count < a->m)
            a->count++;
    }
    const int to = anderson_prev_col(a); /* this step's f and g: never slot */
    a->plain_col = to;
    const int m = have ? a->count : 0;
    const size_t blocks = anderson_blocks(n), width = ANDERSON_PARTIAL, len = facet_pl_anderson_len(s->nv);
    double *df_new = s->aa_df + (size_t)slot * len, *dg_new = s->aa_dg + (size_t)slot * n;
    const double *f_prev = s->aa_df + (size_t)from * len, *g_prev = s->aa_dg + (size_t)from * n;
    double *f_to = s->aa_df + (size_t)to * len, *g_to = s->aa_dg + (size_t)to * n;
    const double *df_all = s->aa_df;
    const anderson_pass ctx = {g, x, df_new, dg_new, f_prev, g_prev, f_to, df_all, n, len, m, have};
    const int stride = anderson_stride(s->nv);
    const size_t room = anderson_block_room(stride);
#pragma omp parallel for schedule(static) num_threads(a->nthreads)
    for (size_t blk = 0; blk < blocks; ++blk) {
        const size_t k0 = blk * ANDERSON_BLOCK, k1 = k0 + ANDERSON_BLOCK < n ? k0 + ANDERSON_BLOCK : n;
        double *part = a->partial + blk * width;
        double largest = 0.0;
        /* the 2m sums side by side (each still in index order): one chain of
         * dependent additions per sum, 2m chains in flight instead of 2 */
        double gsum[FACET_ANDERSON_MAX] = {0.0}, rsum[FACET_ANDERSON_MAX] = {0.0};
        double moved = 0.0;
        /* A piece at a time, so that the sums and f's column read g, x and
         * the new difference from L1, not memory; each sum still runs in
         * index order (the same bits). The pieces between the block's first
         * and last whole vertex also give the vertices' moves. */
        const size_t a0 = (k0 + 2) / 3 * 3, a1 = k1 / 3 * 3 > a0 ? k1 / 3 * 3 : a0;
        /* with the sketch: only every stride-th piece from a0 is sampled,
         * the pieces' ends across vertices never */
        anderson_piece(&ctx, k0, a0, stride == 1 ? k0 : ANDERSON_UNSAMPLED, &largest, gsum, rsum, NULL);
        for (size_t c0 = a0, piece = 0; c0 < a1; c0 += ANDERSON_PIECE, ++piece) {
            const size_t at = stride == 1                 ? c0
                              : piece % (size_t)stride == 0 ? blk * room + piece / (size_t)stride * ANDERSON_PIECE
                                                            : ANDERSON_UNSAMPLED;
            anderson_piece(&ctx, c0, c0 + ANDERSON_PIECE < a1 ? c0 + ANDERSON_PIECE : a1, at, &largest, gsum,
                           rsum, move ? &moved : NULL);
        }
        anderson_piece(&ctx, a1, k1, stride == 1 ? a1 : ANDERSON_UNSAMPLED, &largest, gsum, rsum, NULL);
        for (int j = 0; j < m; ++j)
            part[2 * j] = gsum[j], part[2 * j + 1] = rsum[j];
        part[width - 2] = largest;
        part[width - 1] = moved;
    }
    double rhs[FACET_ANDERSON_MAX], largest = 0.0;
    for (int j = 0; j < m; ++j) {
        double gsum = 0.0, rsum = 0.0;
        for (size_t blk = 0; blk < blocks; ++blk)
            gsum += a->partial[blk * width + 2 * (size_t)j], rsum += a->partial[blk * width + 2 * (size_t)j + 1];
        a->gram[slot][j] = a->gram[j][slot] = gsum;
        rhs[j] = rsum;
    }
    for (size_t blk = 0; blk < blocks; ++blk)
        largest = facet_max(largest, a->partial[blk * width + width - 2]);
    if (move) {
        double moved = 0.0;
        for (size_t blk = 0; blk < blocks; ++blk)
            moved = facet_max(moved, a->partial[blk * width + width - 1]);
        /* the vertices across the blocks' boundaries */
        for (size_t blk = 1; blk < blocks; ++blk)
            if (blk * ANDERSON_BLOCK % 3 != 0) {
                const size_t k = blk * ANDERSON_BLOCK / 3 * 3;
                moved = facet_max(moved, vertex_move2(g + k, x + k));
            }
        *move = moved;
    }
    a->have_previous = 1;
    /* at a fixed point to rounding there is nothing to extrapolate, and
     * differences of rounding errors would only add noise */
    if (m == 0 || largest <= 1e-13)
        return anderson_keep_plain(g_to, g, n, a->nthreads);
    /* theta = argmin |f - dF theta|: normal equations, Cholesky with a small
     * Tikhonov term; a failed factorisation means no acceleration this time */
    double l[FACET_ANDERSON_MAX][FACET_ANDERSON_MAX], theta[FACET_ANDERSON_MAX];
    double trace = 0.0;
    for (int j = 0; j < m; ++j)
        trace += a->gram[j][j];
    if (!(trace > 0.0) || !isfinite(trace))
        return anderson_keep_plain(g_to, g, n, a->nthreads);
    for (int i = 0; i < m; ++i)
        for (int j = 0; j <= i; ++j) {
            double sum = a->gram[i][j] + (i == j ? 1e-10 * trace : 0.0);
            for (int k = 0; k < j; ++k)
                sum -= l[i][k] * l[j][k];
            if (i == j) {
                if (!(sum > 0.0))
                    return anderson_keep_plain(g_to, g, n, a->nthreads);
                l[i][i] = sqrt(sum);
            } else {
                l[i][j] = sum / l[j][j];
            }
        }
    for (int i = 0; i < m; ++i) {
        double sum = rhs[i];
        for (int k = 0; k < i; ++k)
            sum -= l[i][k] * theta[k];
        theta[i] = sum / l[i][i];
    }
    for (int i = m - 1; i >= 0; --i) {
        double sum = theta[i];
        for (int k = i + 1; k < m; ++k)
            sum -= l[k][i] * theta[k];
        theta[i] = sum / l[i][i];
    }
    for (int j = 0; j < m; ++j)
        if (!isfinite(theta[j]))
            return anderson_keep_plain(g_to, g, n, a->nthreads);
    const double *dg_all = s->aa_dg;
    int finite = 1;
    /* in the energy's blocks of vertices when it is plain: the vertices'
     * part of the safeguard's energy summed from the iterate in cache */
    const int energy = facet_pl_vertex_energy_plain(s);
    const int32_t nv = s->nv, esize = facet_pl_energy_block_size(nv);
    const size_t pieces = energy ? (size_t)(nv / esize + (nv % esize != 0)) : blocks;
#pragma omp parallel for schedule(static) num_threads(a->nthreads) reduction(&& : finite)
    for (size_t blk = 0; blk < pieces; ++blk) {
        if (energy) {
            const int32_t v0 = (int32_t)blk * esize, v1 = nv - v0 < esize ? nv : v0 + esize;
            finite = anderson_extrapolate(g, g_to, dg_all, theta, m, n, 3 * (size_t)v0, 3 * (size_t)v1) && finite;
            s->energy_block[1][0][blk] = facet_pl_vertex_data_energy(s, g, v0, v1);
            s->energy_block[1][1][blk] = 0.0;
        } else {
            const size_t k0 = blk * ANDERSON_BLOCK, k1 = k0 + ANDERSON_BLOCK < n ? k0 + ANDERSON_BLOCK : n;
            finite = anderson_extrapolate(g, g_to, dg_all, theta, m, n, k0, k1) && finite;
        }
    }
    if (energy)
        s->energy_blocks[1] = (int32_t)pieces;
    if (!finite) { /* back to the plain step's iterate */
        memcpy(g, g_to, sizeof(double) * n);
        return 0;
    }
    s->vertex_energy_done = energy;
    return 1;
}

/* ---- the solve --------------------------------------------------------- */

/* Threads of a solve (facet.h, facet_planarize_options.threads): the count
 * asked for, or by default one per FACET_CORNERS_PER_THREAD face corners, at
 * least one and at most OpenMP's default. An iteration is a handful of
 * parallel passes, each ended by a barrier; on a small mesh a pass takes
 * microseconds, so a second thread gains little, and when another process
 * holds a core every barrier waits for a descheduled thread (measured on
 * this project's 2-core machine, docs/solver-notes.md, "Threads by mesh
 * size"). */
int facet_pl_threads(const facet_planarizer *s, int requested)
{
    if (requested > 0)
        return facet_thread_count(requested);
    const int most = facet_thread_count(0);
    const int64_t by_size = (int64_t)s->face_start[s->nf] / FACET_CORNERS_PER_THREAD;
    return by_size < 1 ? 1 : by_size > most ? most : (int)by_size;
}

/* One solve with these options; facet_planarizer_solve (planarize_quality.c)
 * calls it and, when the result has a new narrow corner, re-solves. */
facet_status facet_pl_solve_once(facet_planarizer *s, const double *xyz_in,
                                 const facet_planarize_options *options, double *xyz_out,
                                 facet_planarize_result *result, facet_error *error)
{
    facet_error_clear(error);
    if (!s || !xyz_in || !xyz_out || !options)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1,
                          "planarizer, input, output and options must not be NULL");
    s->message[0] = '\0';
    const double t0 = facet_now();
    facet_status status = facet_pl_check_options(s, options, error);
    if (status != FACET_OK)
        return status;
    facet_planarize_options chosen = *options;
    if (options->method == FACET_METHOD_AUTO) {
        chosen.method = facet_planarizer_choose_method(s, options);
        if (chosen.method == FACET_METHOD_LOCAL_LOCAL)
            chosen.mu_min = facet_max(chosen.mu_min, FACET_LL_MU_MIN);
        options = &chosen;
    }
    s->o = *options;
    s->vertex_energy_done = 0;
    if (!ensure_workspace(s))
        return facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory");
    const int32_t nv = s->nv, nf = s->nf;
    for (int32_t v = 0; v < nv; ++v) {
        const double *p = xyz_in + 3 * (size_t)v;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
            snprintf(s->message, sizeof s->message,
                     "vertex %d has a non-finite coordinate (%g, %g, %g)", (int)v, p[0], p[1], p[2]);
            return facet_fail(error, FACET_ERROR_NONFINITE, -1, v, "%s", s->message);
        }
        if (!facet_point_in_range(p, 3)) {
            snprintf(s->message, sizeof s->message,
                     "vertex %d has a coordinate beyond 1e30 in magnitude (%g, %g, %g)", (int)v,
                     p[0], p[1], p[2]);
            return facet_fail(error, FACET_ERROR_COORDINATE_RANGE, -1, v, "%s", s->message);
        }
    }
    const int nthreads = facet_pl_threads(s, options->threads);
    /* A factorization left by an earlier solve must not precondition this
     * one: the result would depend on what was solved before (the fuzz
     * replay's 1-then-2-thread oracle caught it). */
    s->factor_ready = 0;

    /* Normalisation: centre of the bounding box, mean edge length. */
    double lo[3] = {xyz_in[0], xyz_in[1], xyz_in[2]}, hi[3] = {lo[0], lo[1], lo[2]};
    for (int32_t v = 1; v < nv; ++v)
        for (int a = 0; a < 3; ++a) {
            lo[a] = facet_min(lo[a], xyz_in[3 * (size_t)v + a]);
            hi[a] = facet_max(hi[a], xyz_in[3 * (size_t)v + a]);
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
    if (!isfinite(scale)) /* was reported as "every edge has zero length" */
        return facet_pl_fail(s, error, FACET_ERROR_TOO_LARGE,
                             "coordinates too large: the edge lengths overflow a double");
    if (!(scale > 0.0))
        return facet_pl_fail(s, error, FACET_ERROR_DEGENERATE_FACE,
                             "every edge of the mesh has zero length");
    const double inv = 1.0 / scale;
    s->scale = scale;
    memcpy(s->centre, centre, sizeof centre);
    const int warm = options->warm && s->has_previous;
    const double *start_xyz = warm ? s->previous : xyz_in;
    for (int32_t v = 0; v < nv; ++v)
        for (int a = 0; a < 3; ++a) {
            s->p[3 * (size_t)v + a] = (xyz_in[3 * (size_t)v + a] - centre[a]) * inv;
            s->q[3 * (size_t)v + a] = (start_xyz[3 * (size_t)v + a] - centre[a]) * inv;
        }
    /* the history is about to overwrite the last result (previous_storage):
     * a solve that fails keeps none (a warm start then starts cold, a live
     * update asks for a solve); one that stops at iteration 0 has not
     * touched it (start_xyz, below) */
    if (s->previous_in_history && options->anderson > 0)
        s->has_previous = 0;
    facet_pl_prepare_solve(s);
    for (int32_t v = 0; v < nv; ++v) /* a fixed vertex starts (and stays) at its control point */
        if (s->fixed[v])
            memcpy(s->q + 3 * (size_t)v, s->p + 3 * (size_t)v, 3 * sizeof(double));

    if (options->method == FACET_METHOD_LOCAL_GLOBAL) {
        status = facet_pl_global_setup(s, error);
        if (status != FACET_OK)
            return status;
    }

    const int fixed_count = options->iterations > 0;
    const int32_t limit = fixed_count ? options->iterations : options->max_iter;
    const double tol_abs = options->tol_abs * inv; /* normalised units */
    const double tol_rel = options->tol_rel;
    const int use_tol = !fixed_count && (tol_abs > 0.0 || tol_rel > 0.0);
    double mu = options->mu0;
    int32_t it = 0;
    facet_stop_reason reason = FACET_STOP_NONE;
    double max_abs = 0.0, max_rel = 0.0, constraint = 0.0;
    enum { WINDOW = 25 };
    double history[WINDOW];
    anderson_state aa;
    memset(&aa, 0, sizeof aa);
    aa.m = options->anderson;
    aa.nthreads = nthreads;
    int accelerated = 0;
    int32_t accepted = 0, rejected = 0;
    double energy_mu = 0.0, energy_con = 0.0, last_mu = 0.0, last_con = 0.0;
    const int staircase = options->hold_tol > 0.0;
    int numerical_stop = 0;
    /* L/L's finish (docs/solver-notes.md, "Large meshes"): once the staircase
     * has settled at the floor above the tolerance, the vertex step's data
     * terms are anchored at the iterate itself instead of the control mesh
     * (a proximal step of weight mu_min), so they no longer hold the
     * planarity at about 10 mu_min, and the safeguard watches the planarity
     * and constraint energy alone. The iterate then moves by about its
     * planarity residual: 1e-5 edge lengths from where the staircase left
     * it. */
    /* The shape term and the regularizers (Laplacian, boundary fairness) are
     * anchored at the iterate too (s->finishing: planarize_local.c): with
     * their own targets, at weight mu_min, they held the planarity at 1e-6 to
     * 1e-4 (a 110 x 110 grid: ASAP 1.4e-4, plane data 7.3e-6, the Laplacian
     * 9.6e-6), and the shape term's targets combine the control positions
     * with the control centroids, which p = q would mismatch. So is the
     * reference surface's pull (surface data), whose point on the surface
     * held the planarity at 1e-7 to 5e-6 (docs/solver-notes.md, "L/L's
     * finish with surface data"). */
    const int can_finish = options->method == FACET_METHOD_LOCAL_LOCAL && staircase;
    int finish = 0;
    int32_t level_steps = 0;
    int32_t since = 0;       /* the stagnation window starts here */
    int32_t guard_last = -1; /* last iteration with a corner below its angle floor */
    double level_first_move = 0.0; /* squared */
    /* the iterate a step starts from, for the staircase's move and Anderson:
     * L/L keeps it in q_next (below), L/G in a copy */
    const int need_before = aa.m > 0 || staircase;
    double *x_before = NULL;
    if (need_before && options->method != FACET_METHOD_LOCAL_LOCAL &&
        !(x_before = malloc(sizeof(double) * 3 * (size_t)nv)))
        return facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory");
    if (aa.m > 0 &&
        !(aa.partial = malloc(sizeof(double) * ANDERSON_PARTIAL *
                              anderson_blocks(3 * (size_t)nv)))) {
        free(x_before);
        return facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory");
    }
    status = FACET_OK;
    for (;;) {
        status = facet_pl_local_step(s, mu, nthreads, error);
        if (status < 0) {
            snprintf(s->message, sizeof s->message, "%s", error ? error->message : "local step failed");
            break;
        }
        if (aa.m > 0) {
            facet_pl_energy(s, &energy_mu, &energy_con);
            if (accelerated) {
                /* safeguard: the accelerated iterate must not have a higher
                 * energy than the iterate its step started from */
                const double e_new = finish ? energy_con : mu * energy_mu + (1.0 - mu) * energy_con;
                const double e_old = finish ? last_con : mu * last_mu + (1.0 - mu) * last_con;
                if (e_new <= e_old && isfinite(e_new)) {
                    ++accepted;
                } else {
                    ++rejected;
                    /* the plain step's iterate, kept by anderson_step */
                    memcpy(s->q, anderson_plain(s, &aa), sizeof(double) * 3 * (size_t)nv);
                    anderson_restart(&aa);
                    status = facet_pl_local_step(s, mu, nthreads, error);
                    if (status < 0)
                        break;
                    facet_pl_energy(s, &energy_mu, &energy_con);
                }
            }
            last_mu = energy_mu, last_con = energy_con;
        }
        if (s->guard_on)
            guard_last = it;
        max_abs = s->fit_max_abs, max_rel = s->fit_max_rel, constraint = 0.0;
        /* the residuals are zero unless these terms are on (planarize_local.c) */
        if (options->circular > 0.0 || options->parallelogram > 0.0)
            for (int32_t f = 0; f < nf; ++f)
                constraint = facet_max(constraint, s->face_residual[f]);
        if (options->boundary == FACET_BOUNDARY_SLIDING)
            for (int32_t v = 0; v < nv; ++v)
                constraint = facet_max(constraint, s->vertex_residual[v]);
        /* A warm start begins at the previous (planar) result: it must take the
         * edited control positions into account before it may stop. */
        if (use_tol && (it > 0 || !warm) && (tol_abs <= 0.0 || max_abs <= tol_abs) &&
            (tol_rel <= 0.0 || max_rel <= tol_rel) &&
            constraint <= (tol_rel > 0.0 ? tol_rel : tol_abs)) {
            reason = FACET_STOP_TOLERANCE;
            break;
        }
        if (it >= limit) {
            reason = fixed_count ? FACET_STOP_ITERATIONS : FACET_STOP_MAX_ITER;
            break;
        }
        if (!fixed_count && options->time_budget > 0.0 && facet_now() - t0 >= options->time_budget) {
            reason = FACET_STOP_TIME;
            break;
        }
        /* Stagnation: mu at its floor and no 2% gain over the last WINDOW
         * iterations; while the angle floor holds a corner, less than a
         * halving is a crawl that the floor causes (Level 5 with plane data
         * lost 4% per WINDOW for 700 iterations) and lets the floor go. */
        const double measure = facet_max(max_rel, constraint);
        const int guarding = s->o.angle_floor > 0.0 && guard_last >= since &&
                             it - guard_last < WINDOW;
        if (!fixed_count && it >= since + WINDOW && mu <= options->mu_min &&
            measure > (guarding ? 0.5 : 0.98) * history[it % WINDOW]) {
            if (guarding) {
                /* The angle floor holds a corner that every nearby planar
                 * mesh closes: a planar mesh with a narrow panel (which the
                 * quality report names) serves better than no planar mesh,
                 * so the floor lets go and the solve goes on. */
                s->o.angle_floor = 0.0;
                memset(s->guard_count, 0, sizeof(double) * (size_t)nv);
                anderson_restart(&aa);
                since = it;
                /* and the penalty path resumes from 1e-6 (L/L's floor;
                 * of 1e-2, 1e-4 and 1e-6 the quickest to the tolerance) */
                mu = facet_max(1e-6, options->mu_min);
                level_steps = 0;
            } else if (can_finish && !finish && measure > tol_rel) {
                /* stalled at the floor before the level settled (hypar.obj:
                 * 2.7e-6 for 36 steps): the finish, not a stop */
                finish = 1;
                anderson_restart(&aa);
                since = it;
                level_steps = 0;
            } else {
                reason = FACET_STOP_STAGNATION;
                break;
            }
        }
        history[it % WINDOW] = measure;
        /* the iterate this step starts from: an L/L step writes the new one
         * beside it and swaps (q_next is then the old one), other steps
         * overwrite it, so it is copied: L/L's other steps (mu = 1) into
         * q_next, which its next step overwrites, L/G's into x_before */
        const int ll_step = mu < 1.0 && options->method == FACET_METHOD_LOCAL_LOCAL;
        double *copy = options->method == FACET_METHOD_LOCAL_LOCAL ? s->q_next : x_before;
        const double *before = copy;
        if (need_before && !ll_step) {
            const double *q = s->q;
#pragma omp parallel for schedule(static) num_threads(nthreads)
            for (int32_t v = 0; v < nv; ++v)
                memcpy(copy + 3 * (size_t)v, q + 3 * (size_t)v, 3 * sizeof(double));
        }
        if (mu >= 1.0) {
            /* at mu = 1 the solution is the control mesh itself */
            memcpy(s->q, s->p, sizeof(double) * 3 * (size_t)nv);
        } else if (options->method == FACET_METHOD_LOCAL_LOCAL) {
            double *control = s->p;
            if (finish) /* anchored at the iterate (the step only reads it) */
                s->p = s->q;
            s->finishing = finish;
            const int finite = facet_pl_vertex_step(s, mu, nthreads);
            s->finishing = 0;
            s->p = control;
            before = s->q_next; /* swapped: the iterate the step started from */
            if (!finite) {
                status = facet_pl_fail(s, error, FACET_ERROR_NUMERICAL,
                                       "a vertex update was not finite");
            }
        } else {
            status = facet_pl_global_step(s, mu, nthreads, error);
        }
        if (status == FACET_ERROR_NUMERICAL && it > 0) {
            /* An ill-conditioned problem (weights many orders of magnitude
             * apart) whose next step is not finite: the steps leave s->q at
             * the last (finite) iterate, which is the best result there is. */
            status = FACET_OK;
            reason = FACET_STOP_STAGNATION;
            numerical_stop = 1;
            facet_error_clear(error);
            break;
        }
        if (status != FACET_OK)
            break;
        double move = 0.0; /* largest vertex move of the plain step, squared */
        const int accelerate = aa.m > 0 && mu < 1.0;
        if (staircase && !accelerate) { /* (else anderson_step's first pass finds it) */
            const double *q = s->q;
#pragma omp parallel for schedule(static) num_threads(nthreads) reduction(max : move)
            for (int32_t v = 0; v < nv; ++v)
                move = facet_max(move, vertex_move2(q + 3 * (size_t)v, before + 3 * (size_t)v));
        }
        accelerated = accelerate ? anderson_step(s, &aa, before, staircase ? &move : NULL) : 0;
        ++it;
        ++level_steps;
        /* The staircase lowers mu only while the planarity is above the
         * tolerance: a stronger penalty than the tolerance needs would only
         * worsen the conditioning (a vertex may slide along its planes at a
         * cost of mu) and let rounding errors move it. */
        const int above = tol_rel > 0.0 ? measure > tol_rel : (tol_abs > 0.0 ? max_abs > tol_abs : 1);
        if (level_steps == 1)
            level_first_move = move;
        if (!staircase || mu >= 1.0 ||
            (above && (move <= options->hold_tol * options->hold_tol * level_first_move ||
                       level_steps >= options->hold_max))) {
            const double next = facet_max(mu * options->ratio, options->mu_min);
            /* at the floor: mu reached it as 1e-5 * 0.1, which may round
             * a last bit above it (a level of up to hold_max steps lost) */
            const int start_finish = can_finish && !finish && above &&
                                     mu <= options->mu_min * (1.0 + 1e-9);
            if (staircase && (next != mu || start_finish)) { /* a new fixed-point map: restart the history */
                anderson_restart(&aa);
            }
            if (start_finish) {
                finish = 1;
                since = it; /* the stagnation window starts with the finish */
            }
            mu = next;
            level_steps = 0;
        }
        if (options->progress &&
            options->progress(options->progress_user, it, limit, max_rel) != 0) {
            reason = FACET_STOP_CANCELLED;
            status = facet_pl_fail(s, error, FACET_ERROR_CANCELLED, "cancelled");
            break;
        }
    }
    free(x_before);
    free(aa.partial);
    if (status < 0 && status != FACET_ERROR_CANCELLED)
        return status;
    if (!previous_storage(s))
        return facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory");
    if (s->previous_control != xyz_in) /* before xyz_out, which may be xyz_in */
        memmove(s->previous_control, xyz_in, sizeof(double) * 3 * (size_t)nv);

    for (size_t k = 0; it > 0 && k < 3 * (size_t)nv; ++k)
        if (!isfinite(s->q[k])) /* never a NaN in xyz_out, whatever went wrong */
            return facet_pl_fail(s, error, FACET_ERROR_NUMERICAL, "the solution is not finite");
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
    s->live_face_valid = 0;
    s->live_stale = 0;
    s->live_rings = 0; /* the live region's held settings may have changed */
    if (result) {
        result->iterations = it;
        result->stop_reason = reason;
        result->mu = mu;
        result->planarity_max_abs = max_abs * scale;
        result->planarity_max_rel = max_rel;
        result->constraint_max_rel = constraint;
        result->seconds = facet_now() - t0;
        result->anderson_accepted = accepted;
        result->anderson_rejected = rejected;
        result->method = options->method;
        result->threads = nthreads;
        result->data_tangent = options->data_tangent;
    }
    if (status == FACET_ERROR_CANCELLED)
        return status;
    if (reason == FACET_STOP_MAX_ITER || reason == FACET_STOP_STAGNATION || reason == FACET_STOP_TIME) {
        snprintf(s->message, sizeof s->message,
                 "planarity %.3g (relative) after %d iterations: tolerance not reached%s", max_rel,
                 (int)it,
                 reason == FACET_STOP_TIME ? " within the time budget"
                 : numerical_stop ? "; stopped at the last finite iterate, the next step was not "
                                    "finite (weights too many orders of magnitude apart?)"
                                  : "");
        return facet_fail(error, FACET_WARNING_NOT_CONVERGED, -1, -1, "%s", s->message);
    }
    return FACET_OK;
}
