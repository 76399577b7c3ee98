/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Quality by default (issue 3; docs/solver-notes.md, "Quality by default
 * (branch quality5)"): a solve that closes a corner the input did not have
 * is solved again, closer to the penalty path.
 *
 * The default schedule (staircase with a 1% hold and Anderson acceleration)
 * closes corners on some meshes: the narrow faces are darts whose corners
 * close in the jumps (the first step after a tenfold drop of mu, accelerated
 * steps), while the penalty path itself keeps them open. Whether a given
 * mesh collapses is chaotic in the last bits, so nothing here steers the
 * default iteration: its result is checked once, at the end, and only a
 * result with a new narrow corner pays for a re-solve. Every other solve
 * gives the same bits as before, at the cost of one pass over the corners
 * (a cosine test; an angle only for a corner that fails it). */
#include "planarize_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double DEG = 3.14159265358979323846 / 180.0;

static double corner_angle(const double *prev, const double *at, const double *next)
{
    const double u[3] = {prev[0] - at[0], prev[1] - at[1], prev[2] - at[2]};
    const double w[3] = {next[0] - at[0], next[1] - at[1], next[2] - at[2]};
    const double c[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                         u[0] * w[1] - u[1] * w[0]};
    const double cross = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    const double dot = u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
    return atan2(cross, dot) / DEG; /* 0 for an edge of zero length */
}

/* Whether the face folds over itself (quality.c: two edges cross, seen
 * along its Newell normal; a face without area does not count here, its
 * corners do). */
static int folds(int32_t n, const double *xyz, const int32_t *idx)
{
    if (n < 4) /* (no Newell normal for a triangle) */
        return 0;
    double nrm[3];
    facet_newell(n, xyz, idx, nrm);
    return facet_face_folds(n, xyz, idx, nrm);
}

/* Whether a face has an edge of no length (within 1e-12 of its longest): its
 * shape, folded or not, was never defined, and the input's own. */
static int has_empty_edge(int32_t n, const double *xyz, const int32_t *idx)
{
    double longest = 0.0, shortest = INFINITY;
    for (int32_t k = 0; k < n; ++k) {
        const double *a = xyz + 3 * (size_t)idx[k], *b = xyz + 3 * (size_t)idx[(k + 1) % n];
        const double d = (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                         (a[2] - b[2]) * (a[2] - b[2]);
        longest = fmax(longest, d);
        shortest = fmin(shortest, d);
    }
    return shortest <= 1e-24 * longest;
}

int32_t facet_pl_new_narrow(const facet_planarizer *s, double angle_deg, int nthreads,
                            double *smallest)
{
    const double c = cos(angle_deg * DEG), c2 = c * c;
    const double *q = s->q, *p = s->p;
    const int32_t *start = s->face_start, *fv = s->face_vertices;
    int32_t count = 0;
    double least = 180.0;
    /* an integer count and a smallest value: the same for any thread count */
#pragma omp parallel for schedule(static) num_threads(nthreads) reduction(+ : count) \
    reduction(min : least)
    for (int32_t f = 0; f < s->nf; ++f) {
        const int32_t b = start[f], e = start[f + 1];
        if (folds(e - b, q, fv + b) && !folds(e - b, p, fv + b) &&
            !has_empty_edge(e - b, p, fv + b)) {
            /* a new fold: no interior, whatever its corners (a bowtie's may
             * all be wide), counted as a corner of 0 degrees; not where the
             * input face had an edge of no length (a quad that was a
             * triangle, its fourth corner anywhere on an edge) */
            ++count;
            least = 0.0;
            continue;
        }
        for (int32_t k = b; k < e; ++k) {
            const int32_t ip = fv[k > b ? k - 1 : e - 1], ia = fv[k], in = fv[k + 1 < e ? k + 1 : b];
            const double *a = q + 3 * (size_t)ia, *u0 = q + 3 * (size_t)ip, *w0 = q + 3 * (size_t)in;
            const double u[3] = {u0[0] - a[0], u0[1] - a[1], u0[2] - a[2]};
            const double w[3] = {w0[0] - a[0], w0[1] - a[1], w0[2] - a[2]};
            const double dot = u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
            const double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
            const double ww = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
            /* angle < angle_deg (< 90): cos above c; an edge of zero length is
             * a corner of 0 degrees */
            if (!(uu * ww == 0.0 || (dot > 0.0 && dot * dot > c2 * uu * ww)))
                continue;
            const double now = corner_angle(u0, a, w0);
            if (!(now < angle_deg))
                continue; /* the cosine test's last bits */
            const double was = corner_angle(p + 3 * (size_t)ip, p + 3 * (size_t)ia,
                                            p + 3 * (size_t)in);
            if (was >= angle_deg || now < 0.5 * was) {
                ++count;
                least = facet_min(least, now);
            }
        }
    }
    *smallest = least;
    return count;
}

/* The handle's message for a result that keeps `count` new corners under
 * `limit` degrees after `after` (what was tried). */
static void narrow_message(facet_planarizer *s, int32_t count, double limit, const char *after,
                           double smallest)
{
    snprintf(s->message, sizeof s->message,
             "%d corners narrower than %g degrees that the input did not have remain after "
             "%s (the smallest %.3g degrees)",
             (int)count, limit, after, smallest);
}

/* The re-solves, in order, each from the input. The first two follow the
 * default's path without its jumps (no Anderson) and are tried only when
 * the data term holds vertices at their control points: measured, they
 * kept every corner open on 7 point-data meshes (hypar grids, Level 6) at
 * 2-4 times the first solve's iterations, and on none of 5 with vertices
 * sliding along the design (plane or surface data, data_tangent 0.01). The
 * exact penalty path kept them open on three of those (Level 5 with plane,
 * surface and data_tangent 0.01: 8.1, 8.9 and 5.8 degrees, at 1,000-1,200
 * iterations); the other two (the 64 x 64 hypar with plane and surface
 * data: 4.3 and 2.3 degrees) the angle floor does, set a fifth above
 * quality_angle (a corner it holds ends at the floor to the tolerance),
 * with the finer hold it is meant for (docs/solver-notes.md, "Quality by
 * default (branch quality5)"). The last three hold sliding vertices more
 * firmly along the design, where every stage before them closed a panel:
 * on five of 40 meshes with the plane and surface presets (cmc1, pillow_1
 * and the 48 x 48 hypar with surface data, heart and the 40 x 40 hypar with
 * plane data: 0.4-4.0 degrees) they kept every corner open, at 6.0-10.6
 * degrees (docs/solver-notes.md, "Sliding vertices held more firmly when
 * every re-solve closed a panel"). */
static const struct {
    double hold_tol;
    int32_t hold_max, max_iter;
    int anderson; /* keep the options' Anderson depth */
    int floor;    /* the angle floor at 1.2 quality_angle */
    int sliding;  /* also when vertices slide along the design */
    double firmer; /* > 1: only then, with data_tangent times this */
} STAGES[] = {
    {0.01, 40, 0, 0, 0, 0, 1.0},     /* the default's hold without the jumps (Anderson's steps) */
    {0.003, 40, 0, 0, 0, 0, 1.0},    /* a finer hold */
    {1e-9, 200, 4000, 0, 0, 1, 1.0}, /* the exact penalty path: 200 steps at every mu */
    {0.003, 40, 0, 1, 1, 1, 1.0},    /* the opt-in angle floor's recipe */
    /* sliding vertices held more firmly along the design (the presets'
     * data_tangent 0.01 becomes 0.03, then 0.1) */
    {0.01, 40, 0, 1, 0, 1, 3.0},     /* the default's schedule */
    {0.003, 40, 0, 1, 1, 1, 3.0},    /* the angle floor's recipe */
    {0.003, 40, 0, 1, 1, 1, 10.0},   /* the same, ten times */
};

/* ---- progress across the re-solves (facet.h: facet_progress_fn,
 * facet_planarizer_stage) ------------------------------------------------
 *
 * The caller's callback sees one solve: the iteration counts on through the
 * re-solves (the total that result.iterations reports), and max_iter is the
 * whole solve's bound: the iterations done so far, the running solve's limit
 * and the limits of the stages still to come. A solve ends at or before its
 * limit, so the bound only falls when a stage starts and the fraction
 * iteration / max_iter never does (a progress bar never runs backwards).
 * The first solve's bound counts every stage that may follow it: a default
 * L/G solve shows 1,000 + 7,000 (four stages), of which it usually needs a
 * hundred or two before it ends without a re-solve. */

/* The iteration limit of re-solve stage k (its options' max_iter). */
static int32_t stage_limit(const facet_planarize_options *options, size_t k)
{
    return STAGES[k].max_iter > options->max_iter ? STAGES[k].max_iter : options->max_iter;
}

/* Whether a solve with these options checks its result: the check on, not
 * a fixed iteration count, not the angle floor (which holds corners itself);
 * a cold one may then re-solve. */
static int checks_result(const facet_planarize_options *options)
{
    return options->quality_angle > 0.0 && options->iterations <= 0 && !(options->angle_floor > 0.0);
}

/* Whether the data term lets vertices slide along the design (plane or
 * surface data) instead of holding them at their control points. */
static int slides(const facet_planarize_options *options)
{
    return options->data_tangent < options->data_normal || options->surface_weight > 0.0;
}

/* data_tangent held `times` more firmly, at most as firmly as the vertices
 * are held across the design (data_normal, or the design surface's weight):
 * sliding, never more than held at the control point. */
static double firmer_tangent(const facet_planarize_options *options, double times)
{
    const double most = facet_max(options->data_normal, options->surface_weight);
    return facet_max(options->data_tangent, facet_min(times * options->data_tangent, most));
}

/* Whether a stage runs for these options (vertices sliding along the design
 * skip the first two; held at their control points, the last three). */
static int stage_applies(const facet_planarize_options *options, size_t k)
{
    if (!(STAGES[k].firmer > 1.0))
        return !slides(options) || STAGES[k].sliding;
    /* held more firmly: not when data_tangent is already as large as it
     * can be, nor when an earlier stage of the same recipe held as firmly */
    const double tangent = firmer_tangent(options, STAGES[k].firmer);
    if (!slides(options) || !(tangent > options->data_tangent))
        return 0;
    for (size_t j = 0; j < k; ++j)
        if (STAGES[j].firmer > 1.0 && STAGES[j].hold_tol == STAGES[k].hold_tol &&
            STAGES[j].hold_max == STAGES[k].hold_max && STAGES[j].max_iter == STAGES[k].max_iter &&
            STAGES[j].anderson == STAGES[k].anderson && STAGES[j].floor == STAGES[k].floor &&
            firmer_tangent(options, STAGES[j].firmer) == tangent)
            return 0;
    return 1;
}

/* a + b, at most INT32_MAX (the counts are int32; a bound may not wrap) */
static int32_t add_clamped(int64_t a, int64_t b)
{
    const int64_t sum = a + b;
    return sum > INT32_MAX ? INT32_MAX : sum < 0 ? 0 : (int32_t)sum;
}

/* The iterations the stages from k on may take at most. */
static int64_t stages_bound(const facet_planarize_options *options, size_t k)
{
    int64_t sum = 0;
    for (; k < sizeof STAGES / sizeof STAGES[0]; ++k)
        if (stage_applies(options, k))
            sum += stage_limit(options, k) > 0 ? stage_limit(options, k) : 0;
    return sum;
}

typedef struct {
    facet_progress_fn progress; /* the caller's */
    void *user;
    int32_t done;  /* iterations of the solves before the running one */
    int32_t bound; /* the whole solve's bound while this one runs */
} progress_relay;

static int relay_progress(void *user, int32_t iteration, int32_t max_iter, double planarity)
{
    const progress_relay *relay = user;
    (void)max_iter; /* the running solve's own limit: within relay->bound */
    return relay->progress(relay->user, add_clamped(relay->done, iteration), relay->bound,
                           planarity);
}

/* The options with the progress callback relayed (unchanged without one). */
static facet_planarize_options relayed(const facet_planarize_options *options,
                                       progress_relay *relay, int32_t done, int64_t bound)
{
    facet_planarize_options o = *options;
    if (options->progress) {
        relay->progress = options->progress;
        relay->user = options->progress_user;
        relay->done = done;
        relay->bound = add_clamped(bound, 0);
        o.progress = relay_progress;
        o.progress_user = relay;
    }
    return o;
}

int32_t facet_planarizer_stage(const facet_planarizer *s, int32_t *stages)
{
    if (stages)
        *stages = s ? s->quality_stages : 0;
    return s ? s->quality_stage : 0;
}

static facet_status solve_checked(facet_planarizer *s, const double *xyz_in,
                                  const facet_planarize_options *options, int64_t after,
                                  double *xyz_out, facet_planarize_result *result,
                                  facet_error *error);
static int compares(const facet_planarizer *s, const facet_planarize_options *options);
static int32_t compare_limit(const facet_planarize_options *options);
static int32_t finer_bound(const facet_planarize_options *options);
static facet_status compare_ll(facet_planarizer *s, const facet_planarize_options *options,
                               double *xyz_out, facet_planarize_result *result, facet_error *error);
static int falls_back(const facet_planarizer *s, const facet_planarize_options *options);
static facet_status fallback_lg(facet_planarizer *s, const facet_planarize_options *options,
                                facet_status status, double *xyz_out, facet_planarize_result *result,
                                facet_error *error);

facet_status facet_planarizer_solve(facet_planarizer *s, const double *xyz_in,
                                    const facet_planarize_options *options, double *xyz_out,
                                    facet_planarize_result *result, facet_error *error)
{
    if (s) {
        s->quality_stage = 0;
        s->quality_stages = 0;
        if (options && checks_result(options) && !(options->warm && s->has_previous))
            for (size_t k = 0; k < sizeof STAGES / sizeof STAGES[0]; ++k)
                s->quality_stages += stage_applies(options, k);
    }
    /* method AUTO's comparison solves may follow: their limits are in every bound */
    const int compare = compares(s, options), fallback = falls_back(s, options);
    const int64_t after = compare    ? (int64_t)compare_limit(options) + finer_bound(options)
                          : fallback ? (int64_t)options->max_iter
                                     : 0;
    facet_planarize_result r;
    memset(&r, 0, sizeof r);
    facet_status status = solve_checked(s, xyz_in, options, after, xyz_out, &r, error);
    if (compare && status == FACET_OK && r.stop_reason == FACET_STOP_TOLERANCE)
        status = compare_ll(s, options, xyz_out, &r, error);
    else if (fallback)
        status = fallback_lg(s, options, status, xyz_out, &r, error);
    if (result)
        *result = r;
    if (s) /* outside a solve: 0 and 0 */
        s->quality_stage = s->quality_stages = 0;
    return status;
}

/* xyz (solved from `input`, when not NULL) becomes the handle's last result,
 * which warm starts and live updates start from: a later solve of this call
 * overwrote it. */
static void keep_as_last(facet_planarizer *s, const double *xyz, const double *input)
{
    const size_t v3 = 3 * (size_t)s->nv;
    memcpy(s->previous, xyz, sizeof(double) * v3);
    if (input)
        memcpy(s->previous_control, input, sizeof(double) * v3);
    s->has_previous = 1;
}

/* The solve with its quality re-solves; `after` more iterations may follow
 * it (method AUTO's comparison), which every progress bound includes. */
static facet_status solve_checked(facet_planarizer *s, const double *xyz_in,
                                  const facet_planarize_options *options, int64_t after,
                                  double *xyz_out, facet_planarize_result *result,
                                  facet_error *error)
{
    const double t0 = facet_now();
    const int warm = s && options && options->warm && s->has_previous;
    facet_planarize_result first;
    memset(&first, 0, sizeof first);
    /* the first solve's bound: its own limit, and the stages' when it may be
     * followed by any (s->quality_stages, set by the caller) */
    progress_relay relay;
    facet_planarize_options first_o;
    const facet_planarize_options *first_options = options;
    if (s && options && (s->quality_stages > 0 || after > 0)) {
        const int64_t stages = s->quality_stages > 0 ? stages_bound(options, 0) : 0;
        first_o = relayed(options, &relay, 0, (int64_t)options->max_iter + stages + after);
        first_options = &first_o;
    }
    facet_status status = facet_pl_solve_once(s, xyz_in, first_options, xyz_out, &first, error);
    first.quality = FACET_QUALITY_NOT_CHECKED;
    first.first_iterations = first.iterations;
    if (status == FACET_WARNING_NOT_CONVERGED && checks_result(options) && first.iterations > 0) {
        /* short of the tolerance: not re-solved, but a panel it closed is
         * counted (s->q, s->p: the solve's own), so that the result says so */
        double angle;
        first.narrow_corners = facet_pl_new_narrow(s, options->quality_angle,
                                                   facet_pl_threads(s, options->threads), &angle);
    }
    if (status != FACET_OK || first.stop_reason != FACET_STOP_TOLERANCE || !checks_result(options) ||
        first.iterations == 0) {
        if (result)
            *result = first;
        return status;
    }
    const int nthreads = facet_pl_threads(s, options->threads);
    double best_angle;
    int32_t best_count = facet_pl_new_narrow(s, options->quality_angle, nthreads, &best_angle);
    first.quality = best_count ? FACET_QUALITY_NARROW : FACET_QUALITY_OK;
    first.narrow_corners = best_count;
    if (best_count == 0 || warm) { /* a warm solve is checked, not re-solved */
        if (result)
            *result = first;
        return FACET_OK;
    }

    /* Recovery: the input (kept by the solve in previous_control; copied, as
     * a later solve may reuse that storage) and a buffer for each attempt's
     * result. The first re-solve with no new narrow corner replaces the
     * first result in xyz_out; if none has, the first result stands: where
     * every schedule closes a corner (hypar.obj with its boundary and a
     * vertex held, surface data) the re-solves had fewer narrow corners but
     * as narrow (0.001 degrees) and twice the RMS distance from the design
     * (docs/solver-notes.md). */
    const size_t v3 = 3 * (size_t)s->nv;
    double *input = malloc(sizeof(double) * v3), *out = malloc(sizeof(double) * v3);
    if (!input || !out) { /* the first result stands */
        free(input), free(out);
        if (result)
            *result = first;
        return FACET_OK;
    }
    memcpy(input, s->previous_control, sizeof(double) * v3);
    facet_planarize_result best = first;
    int best_is_last = 1;
    int32_t total = first.iterations, resolves = 0;
    int timed_out = 0; /* the time budget ended a re-solve, or left none for the next */
    for (size_t k = 0; k < sizeof STAGES / sizeof STAGES[0] && best_count > 0; ++k) {
        if (!stage_applies(options, k))
            continue;
        /* the bound from here: done, this stage's limit and the later stages' */
        facet_planarize_options o =
            relayed(options, &relay, total, total + stages_bound(options, k) + after);
        if (!STAGES[k].anderson)
            o.anderson = 0;
        if (STAGES[k].floor)
            o.angle_floor = facet_min(1.2 * options->quality_angle, 59.0);
        o.hold_tol = STAGES[k].hold_tol;
        o.hold_max = STAGES[k].hold_max;
        if (STAGES[k].firmer > 1.0)
            o.data_tangent = firmer_tangent(options, STAGES[k].firmer);
        o.max_iter = stage_limit(options, k);
        o.warm = 0;
        if (options->time_budget > 0.0) {
            o.time_budget = options->time_budget - (facet_now() - t0);
            if (!(o.time_budget > 0.0)) {
                timed_out = 1;
                break;
            }
        }
        facet_planarize_result r;
        memset(&r, 0, sizeof r);
        s->quality_stage = resolves + 1; /* facet_planarizer_stage */
        status = facet_pl_solve_once(s, input, &o, out, &r, error);
        ++resolves;
        total += r.iterations;
        best_is_last = 0;
        if (status == FACET_ERROR_CANCELLED)
            break;
        if (status != FACET_OK || r.stop_reason != FACET_STOP_TOLERANCE) {
            timed_out |= status >= 0 && r.stop_reason == FACET_STOP_TIME;
            facet_error_clear(error); /* a failed attempt: the best so far stands */
            status = FACET_OK;
            continue;
        }
        double angle;
        if (facet_pl_new_narrow(s, options->quality_angle, nthreads, &angle) == 0) {
            memcpy(xyz_out, out, sizeof(double) * v3);
            best = r, best_count = 0, best_is_last = 1;
        }
    }
    if (!best_is_last) /* the handle's last result is the one returned */
        keep_as_last(s, xyz_out, input);
    free(input), free(out);
    best.iterations = total;
    best.seconds = facet_now() - t0;
    best.first_iterations = first.iterations;
    best.quality_resolves = resolves;
    best.narrow_corners = best_count;
    best.quality = best_count ? FACET_QUALITY_NARROW : FACET_QUALITY_RECOVERED;
    best.quality_timed_out = best_count > 0 && timed_out;
    if (result)
        *result = best;
    if (status == FACET_ERROR_CANCELLED)
        return facet_pl_fail(s, error, FACET_ERROR_CANCELLED, "cancelled");
    if (best_count > 0) {
        char tried[64];
        snprintf(tried, sizeof tried, best.quality_timed_out ? "%d re-solves (the time budget ended them)"
                                                             : "%d re-solves",
                 (int)resolves);
        narrow_message(s, best_count, options->quality_angle, tried, best_angle);
    }
    return FACET_OK;
}

/* ---- method AUTO: the result closer to the design (facet.h,
 * FACET_STAGE_COMPARE; docs/solver-notes.md, "Method auto: the closer
 * result") ----------------------------------------------------------------
 *
 * Neither L/G nor L/L ends closer to the input surface on every mesh: each
 * follows the penalty path only approximately (the 1% hold, Anderson's
 * jumps), and where it strays it strays differently. L/L costs a tenth of
 * L/G or less, so where AUTO picks L/G it solves by both and returns the
 * closer result, unless that costs panel shape. */

/* The smallest corner a compared result may have: at least L/G's, but a result
 * whose corners are all 10 degrees or wider is as good as any for panels. */
static const double COMPARE_ANGLE_ENOUGH = 10.0;

/* The shortest edge (relative to its input length) a compared result may
 * have: at least L/G's, but a result whose edges all keep a quarter of their
 * length is as good as any. The penalty method may shrink an edge to
 * nothing where the surface asks for it (a skew quad becomes a triangle:
 * hypar grids, Level 5, hex tori), and the corner angles do not show it. */
static const double COMPARE_EDGE_ENOUGH = 0.25;

/* How much further L/L's result may move the vertices (RMS) than L/G's when
 * the data term holds them at their control points: L/L is often closer to
 * the surface because its vertices slide further along it, which changes the
 * panels' sizes (the demo facade: 1.26 times L/G's displacement, edges up to
 * 87% longer against 43%, three panels too large for its sheets). */
static const double COMPARE_DISPLACEMENT_MORE = 1.05;

/* The iteration limit of each solve of the comparison (L/L's, the finer
 * L/G's: their options' max_iter), which the progress bound counts from the
 * first solve on (facet_planarizer_solve). */
static int32_t compare_limit(const facet_planarize_options *options)
{
    return options->max_iter;
}

/* A cold AUTO solve to the tolerance (not a fixed iteration count or a warm
 * start) with the staircase schedule (L/L finishes only with it), whose
 * energy asks for closeness alone (no shape term, Laplacian, normal
 * Laplacian or boundary fairness): the solves AUTO may follow with another
 * (its comparison, its fallback). */
static int auto_closeness(const facet_planarizer *s, const facet_planarize_options *options)
{
    return s && options && options->method == FACET_METHOD_AUTO && options->hold_tol > 0.0 &&
           options->iterations <= 0 && !(options->warm && s->has_previous) &&
           options->shape == FACET_SHAPE_NONE && options->laplacian == 0.0 &&
           options->normal_laplacian == 0.0 && options->boundary_fairness == 0.0;
}

/* Whether AUTO compares: where it picks L/G, for such a solve (without the
 * staircase L/L stalls above the tolerance, and the comparison would run to
 * max_iter for nothing). */
static int compares(const facet_planarizer *s, const facet_planarize_options *options)
{
    return auto_closeness(s, options) && facet_planarizer_choose_method(s, options) == FACET_METHOD_LOCAL_GLOBAL;
}

/* Whether AUTO may fall back on L/G (facet.h, FACET_STAGE_FALLBACK): where
 * it picks L/L on a mesh L/G can still afford (FACET_AUTO_FALLBACK_MAX_CORNERS:
 * up to 160,000 quads), for such a solve that is checked (with a shape term
 * or a regularizer L/G takes minutes there: docs/solver-notes.md, "Method
 * auto: L/L from 10,000 quads"). */
static int falls_back(const facet_planarizer *s, const facet_planarize_options *options)
{
    return auto_closeness(s, options) && facet_planarizer_choose_method(s, options) == FACET_METHOD_LOCAL_LOCAL &&
           s->face_start[s->nf] <= FACET_AUTO_FALLBACK_MAX_CORNERS && checks_result(options);
}

/* What the comparison measures of a result. */
typedef struct {
    double distance; /* RMS distance of the vertices from the input surface */
    double moved;    /* RMS displacement from the input (s->previous_control) */
    double angle;    /* smallest corner angle, degrees */
    double edge;     /* shortest edge relative to its length in the input */
} figures;

/* The figures of the result xyz (0 when a call fails: then the comparison
 * keeps L/G's result). Sums in vertex order: the same for any thread count. */
static int measure(const facet_planarizer *s, const facet_surface *surface, const double *xyz,
                   int nthreads, double *work, figures *fig)
{
    facet_error error;
    const double *input = s->previous_control;
    double sum_moved = 0.0;
    for (size_t k = 0; k < 3 * (size_t)s->nv; ++k) {
        const double d = xyz[k] - input[k];
        sum_moved += d * d;
    }
    fig->moved = sqrt(sum_moved / (double)s->nv);
    if (facet_surface_closest(surface, s->nv, xyz, nthreads, NULL, work, NULL, NULL, &error) !=
        FACET_OK)
        return 0;
    double sum = 0.0;
    for (int32_t v = 0; v < s->nv; ++v)
        sum += work[v] * work[v];
    fig->distance = sqrt(sum / (double)s->nv);
    const facet_mesh mesh = {s->nv, s->nf, xyz, s->face_start, s->face_vertices};
    if (facet_face_shape(&mesh, NULL, nthreads, work, NULL, NULL, &error) != FACET_OK)
        return 0;
    double least = 2.0 * 3.14159265358979323846;
    for (int32_t f = 0; f < s->nf; ++f)
        least = facet_min(least, work[f]);
    fig->angle = least / DEG;
    /* a quad whose edge shrinks to nothing is a triangle, whatever its
     * angles say (the angles at a vanishing edge are those of its ends) */
    double shortest = 1.0;
    for (int32_t f = 0; f < s->nf; ++f) {
        const int32_t b = s->face_start[f], e = s->face_start[f + 1];
        for (int32_t k = b; k < e; ++k) {
            const size_t i = 3 * (size_t)s->face_vertices[k];
            const size_t j = 3 * (size_t)s->face_vertices[k + 1 < e ? k + 1 : b];
            double in2 = 0.0, out2 = 0.0;
            for (int c = 0; c < 3; ++c) {
                in2 += (input[j + c] - input[i + c]) * (input[j + c] - input[i + c]);
                out2 += (xyz[j + c] - xyz[i + c]) * (xyz[j + c] - xyz[i + c]);
            }
            if (in2 > 0.0)
                shortest = facet_min(shortest, sqrt(out2 / in2));
        }
    }
    fig->edge = shortest;
    return isfinite(fig->distance) && isfinite(fig->moved) && isfinite(fig->angle) && isfinite(fig->edge);
}

/* The input surface that results are measured against: the reference
 * surface when the data term uses it, else a tree of the input mesh
 * (s->previous_control) in *own, which the caller frees; NULL when out of
 * memory. */
static const facet_surface *input_surface(const facet_planarizer *s,
                                          const facet_planarize_options *options,
                                          facet_surface **own)
{
    *own = NULL;
    if (options->surface_weight > 0.0)
        return s->reference;
    const facet_mesh mesh = {s->nv, s->nf, s->previous_control, s->face_start, s->face_vertices};
    facet_error ignored;
    return facet_surface_create_from_mesh(&mesh, own, &ignored) == FACET_OK ? *own : NULL;
}

/* What the comparison makes of another result. */
typedef enum {
    KEEP_LG,  /* L/G's result stands */
    TAKE,     /* the other is returned */
    MOVED_FAR /* the other is closer, its corners and edges as good, but its vertices moved too far */
} verdict;

/* L/G's figures as the result holds them (compare_*[FACET_METHOD_LOCAL_GLOBAL]),
 * and a result's figures into them (index: a facet_method). */
static figures held(const facet_planarize_result *result, int index)
{
    const figures f = {result->compare_distance_rms[index], result->compare_displacement_rms[index],
                       result->compare_min_angle[index], result->compare_edge_ratio[index]};
    return f;
}

static void hold(facet_planarize_result *result, int index, const figures *f)
{
    result->compare_distance_rms[index] = f->distance;
    result->compare_displacement_rms[index] = f->moved;
    result->compare_min_angle[index] = f->angle;
    result->compare_edge_ratio[index] = f->edge;
}

/* The rule (facet.h): a result with figures f and `narrow` new narrow
 * corners against L/G's (lg) and its narrow corners. */
static verdict judge(const facet_planarize_options *options, const figures *f, const figures *lg,
                     int32_t narrow, int32_t lg_narrow)
{
    if (!(f->distance < lg->distance) || f->angle < facet_min(lg->angle, COMPARE_ANGLE_ENOUGH) ||
        f->edge < facet_min(lg->edge, COMPARE_EDGE_ENOUGH) || narrow > lg_narrow)
        return KEEP_LG;
    return slides(options) || f->moved <= COMPARE_DISPLACEMENT_MORE * lg->moved ? TAKE : MOVED_FAR;
}

/* Measures L/G's result (xyz_out) into compare_*[FACET_METHOD_LOCAL_GLOBAL]
 * and the handle's last (s->previous, solved from s->previous_control, the
 * input) into compare_*[other], and judges the latter; narrow: its new
 * narrow corners. When other is L/G again (the finer solve), L/G's figures
 * were measured with L/L's, and they become the new result's if it is
 * taken. Memory: what L/G no longer needs is given back first, so that the
 * input surface's tree fits within L/G's own peak. */
static verdict closer(facet_planarizer *s, const facet_planarize_options *options, int other,
                      const double *xyz_out, int32_t narrow, facet_planarize_result *result)
{
    facet_pl_history_trim(s);
    const int nthreads = facet_pl_threads(s, options->threads);
    const size_t nwork = s->nf > s->nv ? (size_t)s->nf : (size_t)s->nv;
    double *work = malloc(sizeof(double) * nwork);
    facet_surface *own = NULL;
    const facet_surface *surface = work ? input_surface(s, options, &own) : NULL;
    const int lg = FACET_METHOD_LOCAL_GLOBAL;
    verdict v = KEEP_LG;
    figures first = held(result, lg), f;
    if (surface && (other == lg || measure(s, surface, xyz_out, nthreads, work, &first)) &&
        measure(s, surface, s->previous, nthreads, work, &f)) {
        v = judge(options, &f, &first, narrow, result->narrow_corners);
        hold(result, lg, &first);
        if (other != lg || v == TAKE)
            hold(result, other, &f);
    } else if (other != lg) { /* out of memory: L/G's result stands */
        const figures none = {0.0, 0.0, 0.0, 0.0};
        hold(result, FACET_METHOD_LOCAL_LOCAL, &none);
        hold(result, lg, &none);
    }
    facet_surface_free(&own);
    free(work);
    return v;
}

/* The iterations the L/G solve with a finer hold may add to the progress
 * bound: it may follow the comparison only with point data, where a result
 * can be refused for moving the vertices further (judge's MOVED_FAR). */
static int32_t finer_bound(const facet_planarize_options *options)
{
    return slides(options) ? 0 : compare_limit(options);
}

/* One more solve, cold, from the input with o_in's options and the time
 * budget left (`remaining`, 0 for none), its progress counted on from
 * result->iterations within `bound` and named `stage`
 * (facet_planarizer_stage); its iterations are added to result's, and L/G's
 * system, if it made one, is freed after (a later L/G solve sets it up
 * again). */
static facet_status solve_more(facet_planarizer *s, const facet_planarize_options *o_in, int32_t stage,
                               int64_t bound, double remaining, const double *input, double *out,
                               facet_planarize_result *result, facet_planarize_result *r, facet_error *error)
{
    progress_relay relay;
    facet_planarize_options o = relayed(o_in, &relay, result->iterations, bound);
    o.warm = 0;
    o.time_budget = remaining;
    memset(r, 0, sizeof *r);
    s->quality_stage = stage;
    const facet_status status = facet_pl_solve_once(s, input, &o, out, r, error);
    facet_pl_global_free(s);
    result->iterations += r->iterations;
    return status;
}

/* A later solve's result (`r`, by `method`, with `narrow` new narrow corners)
 * becomes the one returned: its figures into `result`, which keeps the
 * counts of the whole solve (iterations, time, the comparison's). */
static void adopt(facet_planarize_result *result, const facet_planarize_result *r, facet_method method,
                  int32_t narrow)
{
    result->method = method;
    result->mu = r->mu;
    result->planarity_max_abs = r->planarity_max_abs;
    result->planarity_max_rel = r->planarity_max_rel;
    result->constraint_max_rel = r->constraint_max_rel;
    result->anderson_accepted = r->anderson_accepted;
    result->anderson_rejected = r->anderson_rejected;
    result->data_tangent = r->data_tangent;
    result->narrow_corners = narrow;
}

/* One solve from the input (the handle's: the last solve kept it) with the
 * options o, whose result is judged against L/G's (xyz_out) as `other`
 * (closer). `later`: the limits of the solves that may follow, for the
 * progress bound. On TAKE xyz_out and the result's figures are the new
 * result's and the handle keeps it; else L/G's result stands and the handle
 * keeps that. *v is KEEP_LG also when the solve failed or stopped short of
 * the tolerance. Only cancelling returns an error. */
static facet_status solve_again(facet_planarizer *s, const facet_planarize_options *options,
                                const facet_planarize_options *o_in, int32_t stage, int other,
                                int64_t later, double *xyz_out, facet_planarize_result *result,
                                verdict *v, int32_t *iterations, double t0, facet_error *error)
{
    *v = KEEP_LG;
    const size_t v3 = 3 * (size_t)s->nv;
    double remaining = 0.0;
    if (options->time_budget > 0.0) {
        remaining = options->time_budget - result->seconds - (facet_now() - t0);
        if (!(remaining > 0.0))
            return FACET_OK;
    }
    /* L/G's system goes first, so that the copies below, an L/L solve and
     * the measures (the input surface's tree: about 150 bytes per triangle
     * while it is built) take no more memory than L/G took (the copies
     * beside the system were the peak of method auto's solve at 10,000
     * quads: make bench's quad torus 1,226 -> 1,213 bytes per face). A
     * later L/G solve on this handle sets its system up again (its
     * analysis: about 5% of a cold solve's time). */
    facet_pl_global_free(s);
    /* the input (the last solve kept it; xyz_in may be xyz_out), the result */
    double *input = malloc(sizeof(double) * v3), *out = malloc(sizeof(double) * v3);
    if (!input || !out) { /* L/G's result stands */
        free(input), free(out);
        return FACET_OK;
    }
    memcpy(input, s->previous_control, sizeof(double) * v3);
    facet_planarize_result r;
    facet_status status = solve_more(s, o_in, stage, (int64_t)result->iterations + o_in->max_iter + later,
                                     remaining, input, out, result, &r, error);
    *iterations = r.iterations;
    if (status == FACET_OK && r.stop_reason == FACET_STOP_TOLERANCE) {
        /* the handle keeps the result and the input (s->previous,
         * s->previous_control): the copies go before the measures */
        free(input), free(out);
        input = out = NULL;
        /* the result's new narrow corners (s->q, s->p: the solve's own) */
        double narrowest = 180.0;
        const int32_t narrow = options->quality_angle > 0.0
                                   ? facet_pl_new_narrow(s, options->quality_angle,
                                                         facet_pl_threads(s, options->threads), &narrowest)
                                   : 0;
        *v = closer(s, options, other, xyz_out, narrow, result);
        if (*v == TAKE) {
            memcpy(xyz_out, s->previous, sizeof(double) * v3);
            adopt(result, &r, o_in->method, narrow);
            if (result->quality != FACET_QUALITY_NOT_CHECKED)
                result->quality = narrow ? FACET_QUALITY_NARROW : FACET_QUALITY_OK;
            s->message[0] = '\0'; /* L/G's (its narrow corners) no longer applies */
        }
    } else if (status != FACET_ERROR_CANCELLED) {
        facet_error_clear(error); /* a failed solve: L/G's result stands */
        status = FACET_OK;
    }
    if (*v != TAKE && s->previous) /* the handle's last result is L/G's */
        keep_as_last(s, xyz_out, input);
    free(input), free(out);
    return status;
}

/* Method AUTO's comparison (facet.h): L/L's result, then, when L/L's was
 * refused only for moving the vertices further, L/G's with a finer hold. */
static facet_status compare_ll(facet_planarizer *s, const facet_planarize_options *options,
                               double *xyz_out, facet_planarize_result *result, facet_error *error)
{
    const double t0 = facet_now();
    facet_planarize_options o = *options;
    o.max_iter = compare_limit(options);
    o.method = FACET_METHOD_LOCAL_LOCAL;
    o.mu_min = facet_max(o.mu_min, FACET_LL_MU_MIN);
    verdict v;
    facet_status status = solve_again(s, options, &o, FACET_STAGE_COMPARE, FACET_METHOD_LOCAL_LOCAL,
                                      finer_bound(options), xyz_out, result, &v,
                                      &result->compare_iterations, t0, error);
    const double *d = result->compare_distance_rms;
    if (status == FACET_OK && v == MOVED_FAR &&
        d[FACET_METHOD_LOCAL_LOCAL] <= FACET_FINER_WHEN * d[FACET_METHOD_LOCAL_GLOBAL]) {
        /* L/L's result shows a planar mesh nearer the design than L/G's,
         * which strayed from the penalty path: L/G follows it more closely */
        o = *options;
        o.max_iter = compare_limit(options);
        o.method = FACET_METHOD_LOCAL_GLOBAL;
        o.hold_tol = options->hold_tol * FACET_FINER_HOLD;
        status = solve_again(s, options, &o, FACET_STAGE_FINER, FACET_METHOD_LOCAL_GLOBAL, 0, xyz_out,
                             result, &v, &result->finer_iterations, t0, error);
        result->finer_kept = v == TAKE;
    }
    result->seconds += facet_now() - t0;
    if (status == FACET_ERROR_CANCELLED)
        return facet_pl_fail(s, error, FACET_ERROR_CANCELLED, "cancelled");
    return FACET_OK;
}

/* Method AUTO's fallback (facet.h, FACET_STAGE_FALLBACK): L/L's result (in
 * xyz_out, `result`, `status`) left a new narrow corner or stalled; L/G
 * solves from the input, and its result replaces L/L's when it reaches the
 * tolerance with fewer new narrow corners (no more, when L/L stalled). */
static facet_status fallback_lg(facet_planarizer *s, const facet_planarize_options *options,
                                facet_status status, double *xyz_out, facet_planarize_result *result,
                                facet_error *error)
{
    const int stalled = status == FACET_WARNING_NOT_CONVERGED && result->stop_reason == FACET_STOP_STAGNATION;
    if (!(status == FACET_OK && result->quality == FACET_QUALITY_NARROW) && !stalled)
        return status;
    const double t0 = facet_now();
    double remaining = 0.0;
    if (options->time_budget > 0.0) {
        remaining = options->time_budget - result->seconds;
        if (!(remaining > 0.0))
            return status;
    }
    const int nthreads = facet_pl_threads(s, options->threads);
    double narrowest = 180.0;
    /* (a stalled solve's were counted too, without re-solves: solve_checked) */
    const int32_t ll_narrow = result->narrow_corners;
    const size_t v3 = 3 * (size_t)s->nv;
    /* the input (the last solve kept it), L/L's error and message, a buffer */
    double *input = malloc(sizeof(double) * v3), *out = malloc(sizeof(double) * v3);
    if (!input || !out) { /* L/L's result stands */
        free(input), free(out);
        return status;
    }
    memcpy(input, s->previous_control, sizeof(double) * v3);
    char ll_message[sizeof s->message];
    memcpy(ll_message, s->message, sizeof ll_message);
    facet_error ll_error;
    memset(&ll_error, 0, sizeof ll_error);
    if (error)
        ll_error = *error;
    facet_planarize_options lg = *options;
    lg.method = FACET_METHOD_LOCAL_GLOBAL;
    facet_planarize_result r;
    const facet_status lg_status = solve_more(s, &lg, FACET_STAGE_FALLBACK,
                                              (int64_t)result->iterations + options->max_iter, remaining,
                                              input, out, result, &r, error);
    int take = 0;
    int32_t lg_narrow = 0;
    if (lg_status == FACET_OK && r.stop_reason == FACET_STOP_TOLERANCE) {
        lg_narrow = facet_pl_new_narrow(s, options->quality_angle, nthreads, &narrowest);
        take = stalled ? lg_narrow <= ll_narrow : lg_narrow < ll_narrow;
    }
    if (take) {
        memcpy(xyz_out, out, sizeof(double) * v3);
        adopt(result, &r, FACET_METHOD_LOCAL_GLOBAL, lg_narrow);
        result->stop_reason = FACET_STOP_TOLERANCE;
        result->quality = lg_narrow ? FACET_QUALITY_NARROW : FACET_QUALITY_RECOVERED;
        s->message[0] = '\0';
        if (lg_narrow)
            narrow_message(s, lg_narrow, options->quality_angle, "local/local and local/global",
                           narrowest);
        facet_error_clear(error);
        status = FACET_OK;
    } else {
        /* L/L's result stands: the handle's last result, its message and status */
        keep_as_last(s, xyz_out, input);
        memcpy(s->message, ll_message, sizeof s->message);
        if (error)
            *error = ll_error;
    }
    free(input), free(out);
    result->seconds += facet_now() - t0;
    if (lg_status == FACET_ERROR_CANCELLED)
        return facet_pl_fail(s, error, FACET_ERROR_CANCELLED, "cancelled");
    return status;
}
