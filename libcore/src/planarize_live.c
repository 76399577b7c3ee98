/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Live updates: the planarizer following a designer's edit.
 *
 * After a solve, the designer moves a few control vertices. A full re-solve
 * costs the whole mesh per iteration; the edit only disturbs the planes near
 * the vertices that moved. An update re-solves a region around them: the
 * vertices within `rings` edges of an edited vertex are free, the other
 * vertices of the faces they touch are held (the region's rim), and every
 * vertex beyond keeps its previous result bit for bit. The region's control
 * positions are the previous result moved by the edit, so the region follows
 * the drag instead of being pulled back to the original control mesh, and
 * the faces outside it, planar before, stay planar. If the region cannot
 * reach the tolerance with its rim held, it grows (rings doubled) up to the
 * whole mesh.
 *
 * The region is a submesh with its own facet_planarizer, kept while the same
 * vertices are edited (a drag), so its topology, and for local/global its
 * symbolic factorization, are built once per drag. */
#include "planarize_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void drop_region(facet_planarizer *s)
{
    facet_planarizer_free(&s->live);
    free(s->live_vertex);
    free(s->live_changed);
    free(s->live_xyz);
    s->live_vertex = s->live_changed = NULL;
    s->live_xyz = NULL;
    s->live_nv = s->live_n_changed = s->live_rings = 0;
}

/* Marks the region (1) within `rings` edges of the changed vertices and its
 * rim (2): the other vertices of the faces the region touches. Returns the
 * number of region vertices, or -1 out of memory. */
static int32_t mark_region(facet_planarizer *s, const int32_t *changed, int32_t n_changed, int32_t rings)
{
    const int32_t nv = s->nv;
    memset(s->live_mark, 0, (size_t)nv);
    int32_t *queue = malloc(sizeof(int32_t) * (size_t)nv);
    if (!queue)
        return -1;
    int32_t head = 0, tail = 0;
    for (int32_t k = 0; k < n_changed; ++k) {
        s->live_mark[changed[k]] = 1;
        queue[tail++] = changed[k];
    }
    for (int32_t ring = 0; ring < rings && head < tail; ++ring) {
        const int32_t end = tail;
        for (; head < end; ++head) {
            const int32_t v = queue[head];
            for (int32_t k = s->vertex_adj_start[v]; k < s->vertex_adj_start[v + 1]; ++k) {
                const int32_t u = s->vertex_adj[k];
                if (!s->live_mark[u]) {
                    s->live_mark[u] = 1;
                    queue[tail++] = u;
                }
            }
        }
    }
    free(queue);
    s->live_complete = head == tail; /* the last ring added no vertex: nothing left to reach */
    const int32_t inside = tail;
    for (int32_t v = 0; v < nv; ++v)
        if (s->live_mark[v] == 1)
            for (int32_t k = s->vertex_start[v]; k < s->vertex_start[v + 1]; ++k) {
                const int32_t f = s->vertex_faces[k];
                for (int32_t c = s->face_start[f]; c < s->face_start[f + 1]; ++c)
                    if (!s->live_mark[s->face_vertices[c]])
                        s->live_mark[s->face_vertices[c]] = 2;
            }
    return inside;
}

/* Whether face f has a vertex in the marked region (and so is re-solved). */
static int in_region(const facet_planarizer *s, int32_t f)
{
    for (int32_t c = s->face_start[f]; c < s->face_start[f + 1]; ++c)
        if (s->live_mark[s->face_vertices[c]] == 1)
            return 1;
    return 0;
}

/* Builds the region's submesh and its planarizer. */
static facet_status build_region(facet_planarizer *s, const int32_t *changed, int32_t n_changed,
                                 int32_t rings, facet_error *error)
{
    drop_region(s);
    const int32_t nv = s->nv, nf = s->nf;
    if (!s->live_mark && !(s->live_mark = malloc((size_t)nv)))
        return facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory for the live region");
    if (mark_region(s, changed, n_changed, rings) < 0)
        return facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory for the live region");
    int32_t *local = malloc(sizeof(int32_t) * (size_t)nv);
    int32_t sub_nv = 0, sub_nf = 0, sub_nc = 0;
    if (!local)
        return facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory for the live region");
    for (int32_t v = 0; v < nv; ++v)
        local[v] = s->live_mark[v] ? sub_nv++ : -1;
    /* faces touching the region, in order */
    for (int32_t f = 0; f < nf; ++f) {
        if (in_region(s, f))
            ++sub_nf, sub_nc += s->face_start[f + 1] - s->face_start[f];
    }
    int32_t *face_start = malloc(sizeof(int32_t) * ((size_t)sub_nf + 1));
    int32_t *face_vertices = malloc(sizeof(int32_t) * (size_t)(sub_nc ? sub_nc : 1));
    double *face_weight = s->face_weight ? malloc(sizeof(double) * (size_t)(sub_nf ? sub_nf : 1)) : NULL;
    int32_t *fixed = malloc(sizeof(int32_t) * (size_t)(sub_nv ? sub_nv : 1));
    s->live_vertex = malloc(sizeof(int32_t) * (size_t)(sub_nv ? sub_nv : 1));
    s->live_changed = malloc(sizeof(int32_t) * (size_t)(n_changed ? n_changed : 1));
    s->live_xyz = malloc(sizeof(double) * 6 * (size_t)(sub_nv ? sub_nv : 1));
    facet_status status = FACET_OK;
    if (!face_start || !face_vertices || (s->face_weight && !face_weight) || !fixed ||
        !s->live_vertex || !s->live_changed || !s->live_xyz) {
        status = facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory for the live region");
        goto done;
    }
    for (int32_t v = 0; v < nv; ++v)
        if (local[v] >= 0)
            s->live_vertex[local[v]] = v;
    int32_t at = 0, g = 0;
    face_start[0] = 0;
    for (int32_t f = 0; f < nf; ++f) {
        if (!in_region(s, f))
            continue;
        for (int32_t c = s->face_start[f]; c < s->face_start[f + 1]; ++c)
            face_vertices[at++] = local[s->face_vertices[c]];
        if (face_weight)
            face_weight[g] = s->face_weight[f];
        face_start[++g] = at;
    }
    /* held: the rim, and the user's fixed vertices inside the region */
    int32_t n_fixed = 0;
    for (int32_t i = 0; i < sub_nv; ++i)
        if (s->live_mark[s->live_vertex[i]] == 2)
            fixed[n_fixed++] = i;
    for (int32_t k = 0; k < s->n_user_fixed; ++k)
        if (s->live_mark[s->user_fixed[k]] == 1)
            fixed[n_fixed++] = local[s->user_fixed[k]];
    const facet_mesh sub = {sub_nv, sub_nf, NULL, face_start, face_vertices};
    status = facet_planarizer_create(&sub, &s->live, error);
    if (status < 0)
        goto done;
    if (n_fixed && (status = facet_planarizer_set_fixed(s->live, n_fixed, fixed, error)) < 0)
        goto done;
    if (face_weight && (status = facet_planarizer_set_face_weights(s->live, face_weight, error)) < 0)
        goto done;
    if (s->reference && (status = facet_planarizer_set_reference(s->live, s->reference, error)) < 0)
        goto done;
    memcpy(s->live_changed, changed, sizeof(int32_t) * (size_t)n_changed);
    s->live_n_changed = n_changed;
    s->live_nv = sub_nv;
    s->live_rings = rings;
    status = FACET_OK;
done:
    free(local);
    free(face_start);
    free(face_vertices);
    free(face_weight);
    free(fixed);
    if (status < 0) {
        snprintf(s->message, sizeof s->message, "%s", error ? error->message : "live region failed");
        drop_region(s);
    }
    return status;
}

facet_status facet_planarizer_update(facet_planarizer *s, const double *xyz_in,
                                     const facet_planarize_options *options, int32_t rings,
                                     double *xyz_out, facet_planarize_result *result,
                                     facet_error *error)
{
    facet_error_clear(error);
    const double t0 = facet_now();
    if (!s || !xyz_in || !options || !xyz_out)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1,
                          "planarizer, xyz_in, options and xyz_out must not be NULL");
    if (!s->has_previous)
        return facet_pl_fail(s, error, FACET_ERROR_INVALID_ARGUMENT,
                             "a live update needs a previous solve of this planarizer");
    if (rings < 0) {
        snprintf(s->message, sizeof s->message, "rings must be >= 0 (0: the default, 4), not %d", (int)rings);
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1, "%s", s->message);
    }
    if (rings == 0)
        rings = 4;
    /* checked whether or not a vertex moved (a region solve would check them too) */
    facet_status status = facet_pl_check_options(s, options, error);
    if (status < 0)
        return status;
    const int32_t nv = s->nv;
    for (int32_t v = 0; v < nv; ++v) {
        const double *p = xyz_in + 3 * (size_t)v;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
            snprintf(s->message, sizeof s->message, "vertex %d has a non-finite coordinate (%g, %g, %g)",
                     (int)v, p[0], p[1], p[2]);
            return facet_fail(error, FACET_ERROR_NONFINITE, -1, v, "%s", s->message);
        }
    }
    /* the edited vertices; a vertex of no face has no region (it has nothing to keep
     * planar: it goes where it was moved, as in a solve) */
    int32_t n_changed = 0;
    int32_t *changed = malloc(sizeof(int32_t) * (size_t)nv);
    if (!changed)
        return facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory");
    for (int32_t v = 0; v < nv; ++v) {
        const double *a = xyz_in + 3 * (size_t)v, *b = s->previous_control + 3 * (size_t)v;
        if ((a[0] != b[0] || a[1] != b[1] || a[2] != b[2]) && s->vertex_start[v + 1] > s->vertex_start[v])
            changed[n_changed++] = v;
    }
    if (s->live_stale) { /* held vertices, weights or reference changed: all of it */
        free(changed);
        facet_planarize_options full = *options;
        full.warm = 1;
        return facet_planarizer_solve(s, xyz_in, &full, xyz_out, result, error);
    }
    facet_planarize_options o = *options;
    o.warm = 0;
    o.quality_angle = 0.0; /* no re-solve within a frame (planarize_quality.c) */
    facet_planarize_result sub_result;
    memset(&sub_result, 0, sizeof sub_result);
    int32_t iterations = 0;
    if (n_changed > 0) {
        for (;;) {
            if (!s->live || s->live_rings != rings || s->live_n_changed != n_changed ||
                memcmp(s->live_changed, changed, sizeof(int32_t) * (size_t)n_changed) != 0) {
                status = build_region(s, changed, n_changed, rings, error);
                if (status < 0)
                    break;
            }
            const int32_t m = s->live_nv;
            double *control = s->live_xyz, *out = s->live_xyz + 3 * (size_t)m;
            for (int32_t i = 0; i < m; ++i) { /* previous result moved by the edit */
                const int32_t v = s->live_vertex[i];
                for (int a = 0; a < 3; ++a) {
                    const size_t k = 3 * (size_t)v + a;
                    /* a held vertex is held at its control position, bit for bit */
                    control[3 * (size_t)i + a] = s->fixed[v] ? xyz_in[k]
                                                 : s->previous[k] + (xyz_in[k] - s->previous_control[k]);
                }
            }
            status = facet_planarizer_solve(s->live, control, &o, out, &sub_result, error);
            iterations += sub_result.iterations;
            if (status < 0) {
                snprintf(s->message, sizeof s->message, "%s", facet_planarizer_message(s->live));
                break;
            }
            /* the whole mesh, or all of it the edit reaches (a mesh in pieces): no larger
             * region would do better, nor solving this one again */
            const int whole = (m == nv && s->live->nf == s->nf) || s->live_complete;
            if (sub_result.stop_reason == FACET_STOP_TOLERANCE || sub_result.stop_reason == FACET_STOP_ITERATIONS ||
                sub_result.stop_reason == FACET_STOP_TIME || whole)
                break;
            rings = rings > nv / 2 ? nv : 2 * rings; /* the rim held it back: a larger region */
        }
    }
    free(changed);
    if (status < 0)
        return status;
    /* the result: the previous one moved by the edit at the vertices of no face (nothing
     * holds them: as in a solve), with the region replaced. The control positions are
     * kept before xyz_out is written, which may be xyz_in */
    for (int32_t v = 0; v < nv; ++v)
        if (s->vertex_start[v + 1] == s->vertex_start[v])
            for (int a = 0; a < 3; ++a) {
                const size_t k = 3 * (size_t)v + a;
                if (xyz_in[k] != s->previous_control[k])
                    s->previous[k] += xyz_in[k] - s->previous_control[k];
            }
    memmove(s->previous_control, xyz_in, sizeof(double) * 3 * (size_t)nv);
    if (xyz_out != s->previous)
        memmove(xyz_out, s->previous, sizeof(double) * 3 * (size_t)nv);
    if (n_changed > 0) {
        const double *out = s->live_xyz + 3 * (size_t)s->live_nv;
        for (int32_t i = 0; i < s->live_nv; ++i) {
            const int32_t v = s->live_vertex[i];
            if (s->live_mark[v] == 1)
                memcpy(xyz_out + 3 * (size_t)v, out + 3 * (size_t)i, 3 * sizeof(double));
        }
    }
    if (s->previous != xyz_out)
        memmove(s->previous, xyz_out, sizeof(double) * 3 * (size_t)nv);
    /* planarity per face: the region's faces changed, the others kept theirs */
    const int32_t nf = s->nf;
    if (!s->live_face_dev && !(s->live_face_dev = malloc(sizeof(double) * 2 * (size_t)nf)))
        return facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory");
    double *dev_abs = s->live_face_dev, *dev_rel = s->live_face_dev + nf;
    for (int32_t f = 0; f < nf; ++f) {
        if (s->live_face_valid && n_changed > 0) {
            if (!in_region(s, f))
                continue;
        } else if (s->live_face_valid) {
            break;
        }
        const int32_t b = s->face_start[f];
        double normal[3], dev;
        const double edge = facet_face_measure(s->face_start[f + 1] - b, xyz_out, s->face_vertices + b,
                                               normal, NULL, &dev, NULL);
        dev_abs[f] = dev;
        dev_rel[f] = edge > 0.0 ? dev / edge : 0.0;
    }
    s->live_face_valid = 1;
    if (result) {
        double max_abs = 0.0, max_rel = 0.0;
        for (int32_t f = 0; f < nf; ++f)
            if (!s->face_weight || s->face_weight[f] > 0.0) {
                max_abs = facet_max(max_abs, dev_abs[f]);
                max_rel = facet_max(max_rel, dev_rel[f]);
            }
        result->iterations = iterations;
        result->stop_reason = n_changed ? sub_result.stop_reason : FACET_STOP_TOLERANCE;
        result->mu = sub_result.mu;
        result->planarity_max_abs = max_abs;
        result->planarity_max_rel = max_rel;
        result->constraint_max_rel = sub_result.constraint_max_rel;
        result->seconds = facet_now() - t0;
        result->anderson_accepted = sub_result.anderson_accepted;
        result->anderson_rejected = sub_result.anderson_rejected;
        result->method = n_changed ? sub_result.method
                         : options->method == FACET_METHOD_AUTO
                             ? facet_planarizer_choose_method(s->live ? s->live : s, options)
                             : options->method;
        /* the region solves are not checked (planarize_quality.c) */
        result->quality = FACET_QUALITY_NOT_CHECKED;
        result->narrow_corners = 0;
        result->quality_resolves = 0;
        result->quality_timed_out = 0;
        result->first_iterations = iterations;
        result->data_tangent = options->data_tangent;
        result->threads = n_changed ? sub_result.threads : 0; /* the region's (0: none solved) */
    }
    return status;
}
