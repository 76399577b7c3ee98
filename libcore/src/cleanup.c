/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Cleanup (paper section 5): collapse edges shorter than a threshold.
 *
 * Passes over the current edges, shortest first. A collapse merges vertex b
 * into vertex a (a union-find keeps the input vertices of each merged
 * vertex); the faces around a and b are rewritten with b replaced by a and
 * repeated neighbours removed, so a face loses a corner, and a face left with
 * fewer than 3 vertices goes. Before a collapse the rewritten faces are
 * checked (where the input was manifold around a and b): no edge at a in
 * more than two faces or twice in one direction, no vertex twice in a face,
 * no two faces on the same vertices, and a is inside (no boundary edges) or
 * on one stretch of boundary (two boundary edges). Nor may a collapse turn a
 * face over: every rewritten face's vector area (Newell) must keep a
 * positive dot product with the input face's. */
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    double length;
    uint64_t key;
} edge_item;

static int compare_edge_item(const void *x, const void *y)
{
    const edge_item *a = x, *b = y;
    if (a->length != b->length)
        return a->length < b->length ? -1 : 1;
    return (a->key > b->key) - (a->key < b->key);
}

static int compare_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

static double distance(const double *xyz, int32_t u, int32_t v)
{
    const double *p = xyz + 3 * (size_t)u, *q = xyz + 3 * (size_t)v;
    const double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

static uint64_t edge_key(int32_t u, int32_t v)
{
    uint32_t a = (uint32_t)u, b = (uint32_t)v;
    if (a > b) {
        uint32_t t = a;
        a = b;
        b = t;
    }
    return ((uint64_t)a << 32) | b;
}

typedef struct {
    int32_t nv, nf;
    double *xyz;             /* working positions */
    const int32_t *start;    /* input face offsets: face f has room for its input degree */
    int32_t *verts;          /* current face vertices, packed at start[f] */
    int32_t *len;            /* current degree of each face (0: removed) */
    int32_t *parent;         /* union-find: a merged vertex's representative */
    int32_t *next_member, *tail;
    int32_t *vf_start, *vf;  /* input vertex -> input faces */
    int32_t *stamp;          /* per face */
    int32_t tag;
    /* scratch for one collapse */
    int32_t *around;         /* faces around a and b */
    int32_t n_around;
    int32_t *scratch;        /* rewritten faces, packed */
    int32_t *scratch_start;
    int32_t cap_around, cap_scratch;
    uint64_t *pairs;         /* directed edges at a: (a<<32|w) or (w<<32|a) */
    int32_t cap_pairs;
    double *normal0;         /* input faces' vector areas, 3 per face */
} state;

/* Vector area of the face v[0..n) with vertex `moved` at p (others at xyz). */
static void vector_area(const double *xyz, const int32_t *v, int32_t n, int32_t moved,
                        const double p[3], double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    const double *o = v[0] == moved ? p : xyz + 3 * (size_t)v[0];
    for (int32_t k = 1; k + 1 < n; ++k) {
        const double *b = v[k] == moved ? p : xyz + 3 * (size_t)v[k];
        const double *c = v[k + 1] == moved ? p : xyz + 3 * (size_t)v[k + 1];
        const double e[3] = {b[0] - o[0], b[1] - o[1], b[2] - o[2]};
        const double f[3] = {c[0] - o[0], c[1] - o[1], c[2] - o[2]};
        out[0] += e[1] * f[2] - e[2] * f[1];
        out[1] += e[2] * f[0] - e[0] * f[2];
        out[2] += e[0] * f[1] - e[1] * f[0];
    }
}

static int grow(void **buf, int32_t *cap, int32_t need, size_t item)
{
    if (need <= *cap)
        return 0;
    int32_t n = *cap ? *cap : 64;
    while (n < need)
        n *= 2;
    void *p = realloc(*buf, item * (size_t)n);
    if (!p)
        return -1;
    *buf = p;
    *cap = n;
    return 0;
}

/* Collects the live faces of the merged vertices a and b into s->around. */
static int gather(state *s, int32_t a, int32_t b)
{
    ++s->tag;
    s->n_around = 0;
    const int32_t roots[2] = {a, b};
    for (int r = 0; r < 2; ++r)
        for (int32_t m = roots[r]; m >= 0; m = s->next_member[m])
            for (int32_t k = s->vf_start[m]; k < s->vf_start[m + 1]; ++k) {
                const int32_t f = s->vf[k];
                if (s->len[f] == 0 || s->stamp[f] == s->tag)
                    continue;
                s->stamp[f] = s->tag;
                if (grow((void **)&s->around, &s->cap_around, s->n_around + 1, sizeof(int32_t)))
                    return -1;
                s->around[s->n_around++] = f;
            }
    return 0;
}

/* Counts, over the faces in s->around as stored (rewritten=0) or as in
 * s->scratch (rewritten=1), the edges at vertex x: returns -1 on out of
 * memory, else sets *max_count (undirected), *same_dir (an edge twice in one
 * direction) and *boundary (edges in one face). */
static int edges_at(state *s, int32_t x, int rewritten, int *max_count, int *same_dir,
                    int *boundary)
{
    int32_t np = 0;
    for (int32_t i = 0; i < s->n_around; ++i) {
        const int32_t f = s->around[i];
        const int32_t *v = rewritten ? s->scratch + s->scratch_start[i] : s->verts + s->start[f];
        const int32_t n = rewritten ? s->scratch_start[i + 1] - s->scratch_start[i] : s->len[f];
        if (n < 3)
            continue;
        for (int32_t k = 0; k < n; ++k) {
            const int32_t u = v[k], w = v[k + 1 < n ? k + 1 : 0];
            if (u != x && w != x)
                continue;
            if (grow((void **)&s->pairs, &s->cap_pairs, np + 1, sizeof(uint64_t)))
                return -1;
            s->pairs[np++] = ((uint64_t)(uint32_t)u << 32) | (uint32_t)w;
        }
    }
    qsort(s->pairs, (size_t)np, sizeof *s->pairs, compare_u64);
    *same_dir = 0;
    for (int32_t k = 1; k < np; ++k)
        if (s->pairs[k] == s->pairs[k - 1])
            *same_dir = 1;
    for (int32_t k = 0; k < np; ++k) {
        const uint32_t u = (uint32_t)(s->pairs[k] >> 32), w = (uint32_t)s->pairs[k];
        s->pairs[k] = edge_key((int32_t)u, (int32_t)w);
    }
    qsort(s->pairs, (size_t)np, sizeof *s->pairs, compare_u64);
    *max_count = 0;
    *boundary = 0;
    for (int32_t k = 0; k < np;) {
        int32_t m = k + 1;
        while (m < np && s->pairs[m] == s->pairs[k])
            ++m;
        if (m - k > *max_count)
            *max_count = m - k;
        if (m - k == 1)
            ++*boundary;
        k = m;
    }
    return 0;
}

/* Writes the faces around a and b with b replaced by a into s->scratch.
 * Returns -1 on out of memory, 1 when some face would repeat a vertex
 * (other than the merged neighbours) or two faces would have the same
 * vertices, 0 otherwise. */
static int rewrite(state *s, int32_t a, int32_t b)
{
    int32_t total = 0;
    for (int32_t i = 0; i < s->n_around; ++i)
        total += s->len[s->around[i]];
    if (grow((void **)&s->scratch, &s->cap_scratch, total, sizeof(int32_t)))
        return -1;
    free(s->scratch_start);
    s->scratch_start = malloc(sizeof(int32_t) * ((size_t)s->n_around + 1));
    if (!s->scratch_start)
        return -1;
    int32_t at = 0;
    for (int32_t i = 0; i < s->n_around; ++i) {
        const int32_t f = s->around[i];
        const int32_t *v = s->verts + s->start[f];
        const int32_t n = s->len[f];
        s->scratch_start[i] = at;
        int32_t m = 0;
        int32_t *out = s->scratch + at;
        for (int32_t k = 0; k < n; ++k) {
            const int32_t x = v[k] == b ? a : v[k];
            if (m > 0 && out[m - 1] == x)
                continue;
            out[m++] = x;
        }
        while (m > 1 && out[m - 1] == out[0])
            --m;
        /* a vertex twice (not next to itself): the face would be pinched */
        for (int32_t p = 0; p < m && m >= 3; ++p)
            for (int32_t q = p + 1; q < m; ++q)
                if (out[p] == out[q])
                    return 1;
        at += m;
    }
    s->scratch_start[s->n_around] = at;
    /* two faces on the same vertex set (a pillow): compare sorted copies;
     * faces around one vertex are few, so pairwise is fine */
    for (int32_t i = 0; i < s->n_around; ++i) {
        const int32_t ni = s->scratch_start[i + 1] - s->scratch_start[i];
        if (ni < 3)
            continue;
        for (int32_t j = i + 1; j < s->n_around; ++j) {
            const int32_t nj = s->scratch_start[j + 1] - s->scratch_start[j];
            if (nj != ni)
                continue;
            int same = 1;
            for (int32_t p = 0; p < ni && same; ++p) {
                const int32_t x = s->scratch[s->scratch_start[i] + p];
                int found = 0;
                for (int32_t q = 0; q < nj; ++q)
                    if (s->scratch[s->scratch_start[j] + q] == x)
                        found = 1;
                same = found;
            }
            if (same)
                return 1;
        }
    }
    return 0;
}

static int manifold_at(int max_count, int same_dir, int boundary)
{
    return max_count <= 2 && !same_dir && (boundary == 0 || boundary == 2);
}

/* Tries to collapse edge a-b. Returns 1 when done, 0 when skipped, -1 on
 * out of memory. *removed receives removed faces. */
static int try_collapse(state *s, int32_t a, int32_t b, int32_t *removed, int32_t *n_removed)
{
    if (gather(s, a, b) < 0)
        return -1;
    /* is a-b still an edge of some face? */
    int adjacent = 0;
    for (int32_t i = 0; i < s->n_around && !adjacent; ++i) {
        const int32_t f = s->around[i];
        const int32_t *v = s->verts + s->start[f];
        const int32_t n = s->len[f];
        for (int32_t k = 0; k < n; ++k) {
            const int32_t u = v[k], w = v[k + 1 < n ? k + 1 : 0];
            if ((u == a && w == b) || (u == b && w == a))
                adjacent = 1;
        }
    }
    if (!adjacent)
        return 0;
    int mc, sd, ba, bb;
    if (edges_at(s, a, 0, &mc, &sd, &ba) < 0)
        return -1;
    const int manifold_a = manifold_at(mc, sd, ba);
    if (edges_at(s, b, 0, &mc, &sd, &bb) < 0)
        return -1;
    const int manifold = manifold_a && manifold_at(mc, sd, bb);
    const int r = rewrite(s, a, b);
    if (r < 0)
        return -1;
    if (manifold) {
        if (r == 1)
            return 0;
        int bn;
        if (edges_at(s, a, 1, &mc, &sd, &bn) < 0)
            return -1;
        if (!manifold_at(mc, sd, bn))
            return 0;
        /* an inner edge between two boundary vertices would pinch: caught
         * above as 4 boundary edges at a. Keep at least one face. */
        int left = 0;
        for (int32_t i = 0; i < s->n_around; ++i)
            left += s->scratch_start[i + 1] - s->scratch_start[i] >= 3;
        if (left == 0)
            return 0;
    } else if (r == 1) {
        return 0; /* never write a face with a repeated vertex */
    }
    /* the merged position: onto the boundary when one end is on it */
    double *pa = s->xyz + 3 * (size_t)a, *pb = s->xyz + 3 * (size_t)b;
    double p[3] = {pa[0], pa[1], pa[2]};
    if (bb > 0 && ba == 0) {
        p[0] = pb[0], p[1] = pb[1], p[2] = pb[2];
    } else if (!(ba > 0 && bb == 0)) {
        for (int k = 0; k < 3; ++k)
            p[k] = 0.5 * (pa[k] + pb[k]);
    }
    /* no face may turn over against the input */
    for (int32_t i = 0; i < s->n_around; ++i) {
        const int32_t n = s->scratch_start[i + 1] - s->scratch_start[i];
        if (n < 3)
            continue;
        const double *n0 = s->normal0 + 3 * (size_t)s->around[i];
        double n1[3];
        vector_area(s->xyz, s->scratch + s->scratch_start[i], n, a, p, n1);
        const double d = n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2];
        if ((n0[0] != 0.0 || n0[1] != 0.0 || n0[2] != 0.0) && !(d > 0.0))
            return 0;
    }
    /* apply: position, faces, union-find */
    pa[0] = p[0], pa[1] = p[1], pa[2] = p[2];
    for (int32_t i = 0; i < s->n_around; ++i) {
        const int32_t f = s->around[i];
        const int32_t n = s->scratch_start[i + 1] - s->scratch_start[i];
        if (n < 3) {
            s->len[f] = 0;
            removed[(*n_removed)++] = f;
        } else {
            memcpy(s->verts + s->start[f], s->scratch + s->scratch_start[i],
                   sizeof(int32_t) * (size_t)n);
            s->len[f] = n;
        }
    }
    s->parent[b] = a;
    s->next_member[s->tail[a]] = b;
    s->tail[a] = s->tail[b];
    return 1;
}

static int32_t find(int32_t *parent, int32_t v)
{
    while (parent[v] != v) {
        parent[v] = parent[parent[v]];
        v = parent[v];
    }
    return v;
}

/* Current unique edges of live faces, sorted by length; returns count or -1. */
static int64_t current_edges(const state *s, edge_item **items)
{
    size_t nc = 0;
    for (int32_t f = 0; f < s->nf; ++f)
        nc += (size_t)s->len[f];
    uint64_t *keys = malloc(sizeof *keys * (nc ? nc : 1));
    if (!keys)
        return -1;
    size_t at = 0;
    for (int32_t f = 0; f < s->nf; ++f) {
        const int32_t *v = s->verts + s->start[f];
        const int32_t n = s->len[f];
        for (int32_t k = 0; k < n; ++k)
            keys[at++] = edge_key(v[k], v[k + 1 < n ? k + 1 : 0]);
    }
    qsort(keys, nc, sizeof *keys, compare_u64);
    size_t ne = 0;
    for (size_t k = 0; k < nc; ++k)
        if (k == 0 || keys[k] != keys[k - 1])
            keys[ne++] = keys[k];
    edge_item *e = malloc(sizeof *e * (ne ? ne : 1));
    if (!e) {
        free(keys);
        return -1;
    }
    for (size_t k = 0; k < ne; ++k) {
        e[k].key = keys[k];
        e[k].length = distance(s->xyz, (int32_t)(keys[k] >> 32), (int32_t)(keys[k] & 0xffffffffu));
    }
    free(keys);
    qsort(e, ne, sizeof *e, compare_edge_item);
    *items = e;
    return (int64_t)ne;
}

facet_status facet_cleanup(const facet_mesh *mesh, const facet_cleanup_options *options,
                           double *xyz_out, int32_t *face_start_out, int32_t *face_vertices_out,
                           int32_t *vertex_map, int32_t *collapsed_edges,
                           int32_t *removed_faces, facet_cleanup_result *result,
                           facet_error *error)
{
    facet_error_clear(error);
    if (!options || !xyz_out || !face_start_out || !face_vertices_out || !result)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1,
                          "options, output arrays and result must not be NULL");
    if (!(options->min_edge > 0.0) || !isfinite(options->min_edge))
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1,
                          "min_edge must be a finite number > 0, not %g", options->min_edge);
    facet_status status = facet_mesh_validate(mesh, NULL, error);
    if (status < 0)
        return status;
    facet_error_clear(error);
    const int32_t nv = mesh->n_vertices, nf = mesh->n_faces;
    const int32_t *start = mesh->face_start;
    const size_t nc = (size_t)start[nf];

    state s;
    memset(&s, 0, sizeof s);
    s.nv = nv, s.nf = nf, s.start = start;
    s.xyz = malloc(sizeof *s.xyz * 3 * (size_t)nv);
    s.verts = malloc(sizeof *s.verts * (nc ? nc : 1));
    s.len = malloc(sizeof *s.len * (size_t)nf);
    s.parent = malloc(sizeof *s.parent * (size_t)nv);
    s.next_member = malloc(sizeof *s.next_member * (size_t)nv);
    s.tail = malloc(sizeof *s.tail * (size_t)nv);
    s.vf_start = calloc((size_t)nv + 1, sizeof *s.vf_start);
    s.vf = malloc(sizeof *s.vf * (nc ? nc : 1));
    s.stamp = malloc(sizeof *s.stamp * (size_t)nf);
    s.normal0 = malloc(sizeof *s.normal0 * 3 * (size_t)nf);
    int32_t *removed = malloc(sizeof *removed * (size_t)nf);
    int32_t *collapsed = malloc(sizeof *collapsed * 2 * (size_t)nv);
    int32_t *new_index = malloc(sizeof *new_index * (size_t)nv);
    unsigned char *used = calloc((size_t)nv, 1);
    edge_item *edges = NULL;
    status = FACET_OK;
    if (!s.xyz || !s.verts || !s.len || !s.parent || !s.next_member || !s.tail || !s.vf_start ||
        !s.vf || !s.stamp || !s.normal0 || !removed || !collapsed || !new_index || !used) {
        status = facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
        goto done;
    }
    memcpy(s.xyz, mesh->xyz, sizeof *s.xyz * 3 * (size_t)nv);
    memcpy(s.verts, mesh->face_vertices, sizeof *s.verts * nc);
    for (int32_t f = 0; f < nf; ++f) {
        s.len[f] = start[f + 1] - start[f];
        s.stamp[f] = 0;
        const double none[3] = {0.0, 0.0, 0.0};
        vector_area(mesh->xyz, mesh->face_vertices + start[f], s.len[f], -1, none,
                    s.normal0 + 3 * (size_t)f);
    }
    for (int32_t v = 0; v < nv; ++v)
        s.parent[v] = v, s.next_member[v] = -1, s.tail[v] = v;
    for (size_t k = 0; k < nc; ++k)
        ++s.vf_start[mesh->face_vertices[k] + 1];
    for (int32_t v = 0; v < nv; ++v)
        s.vf_start[v + 1] += s.vf_start[v];
    {
        int32_t *fill = malloc(sizeof *fill * (size_t)nv);
        if (!fill) {
            status = facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
            goto done;
        }
        memcpy(fill, s.vf_start, sizeof *fill * (size_t)nv);
        for (int32_t f = 0; f < nf; ++f)
            for (int32_t k = start[f]; k < start[f + 1]; ++k)
                s.vf[fill[mesh->face_vertices[k]]++] = f;
        free(fill);
    }

    /* threshold */
    int64_t ne = current_edges(&s, &edges);
    if (ne < 0) {
        status = facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
        goto done;
    }
    double threshold = options->min_edge;
    if (options->relative) {
        double sum = 0.0;
        for (int64_t k = 0; k < ne; ++k)
            sum += edges[k].length;
        threshold *= ne > 0 ? sum / (double)ne : 0.0;
    }
    if (ne > 0 && edges[ne - 1].length < threshold) {
        status = facet_fail(error, FACET_ERROR_NOTHING_LEFT, -1, -1,
                            "min_edge %g (%g model units) is longer than every edge of the mesh "
                            "(longest %g): every face would collapse",
                            options->min_edge, threshold, edges[ne - 1].length);
        goto done;
    }
    int32_t n_removed = 0, n_collapsed = 0;
    for (int pass = 0; pass < 1000; ++pass) {
        if (pass > 0) {
            free(edges);
            edges = NULL;
            ne = current_edges(&s, &edges);
            if (ne < 0) {
                status = facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
                goto done;
            }
        }
        int32_t done_now = 0;
        for (int64_t k = 0; k < ne && edges[k].length < threshold; ++k) {
            const int32_t u = (int32_t)(edges[k].key >> 32);
            const int32_t w = (int32_t)(edges[k].key & 0xffffffffu);
            if (s.parent[u] != u || s.parent[w] != w)
                continue; /* merged earlier in this pass: next pass */
            if (!(distance(s.xyz, u, w) < threshold))
                continue;
            const int r = try_collapse(&s, u, w, removed, &n_removed);
            if (r < 0) {
                status = facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
                goto done;
            }
            if (r == 1) {
                collapsed[2 * (size_t)n_collapsed] = u;
                collapsed[2 * (size_t)n_collapsed + 1] = w;
                ++n_collapsed;
                ++done_now;
            }
        }
        if (done_now == 0)
            break;
    }
    /* what is left short */
    int32_t n_short = 0;
    free(edges);
    edges = NULL;
    ne = current_edges(&s, &edges);
    if (ne < 0) {
        status = facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
        goto done;
    }
    for (int64_t k = 0; k < ne && edges[k].length < threshold; ++k)
        ++n_short;

    /* output: vertices used by a live face, and input vertices no face used */
    int32_t n_faces_out = 0;
    for (int32_t f = 0; f < nf; ++f)
        if (s.len[f] >= 3) {
            ++n_faces_out;
            for (int32_t k = 0; k < s.len[f]; ++k)
                used[s.verts[start[f] + k]] = 1;
        }
    if (n_faces_out == 0) {
        status = facet_fail(error, FACET_ERROR_NOTHING_LEFT, -1, -1,
                            "every face would collapse: collapsing %d edge%s shorter than "
                            "min_edge %g (%g model units) leaves no face of three corners",
                            (int)n_collapsed, n_collapsed == 1 ? "" : "s", options->min_edge,
                            threshold);
        goto done;
    }
    for (int32_t v = 0; v < nv; ++v)
        if (s.vf_start[v + 1] == s.vf_start[v])
            used[v] = 1; /* isolated in the input: kept */
    int32_t n_out = 0;
    for (int32_t v = 0; v < nv; ++v) {
        new_index[v] = -1;
        if (s.parent[v] == v && used[v]) {
            new_index[v] = n_out;
            memcpy(xyz_out + 3 * (size_t)n_out, s.xyz + 3 * (size_t)v, 3 * sizeof *xyz_out);
            ++n_out;
        }
    }
    int32_t at = 0, fo = 0;
    face_start_out[0] = 0;
    for (int32_t f = 0; f < nf; ++f) {
        if (s.len[f] < 3)
            continue;
        for (int32_t k = 0; k < s.len[f]; ++k)
            face_vertices_out[at++] = new_index[s.verts[start[f] + k]];
        face_start_out[++fo] = at;
    }
    if (vertex_map)
        for (int32_t v = 0; v < nv; ++v)
            vertex_map[v] = new_index[find(s.parent, v)];
    if (collapsed_edges)
        memcpy(collapsed_edges, collapsed, sizeof *collapsed * 2 * (size_t)n_collapsed);
    if (removed_faces)
        memcpy(removed_faces, removed, sizeof *removed * (size_t)n_removed);
    result->n_vertices = n_out;
    result->n_faces = n_faces_out;
    result->n_corners = at;
    result->n_collapsed = n_collapsed;
    result->n_removed_faces = n_removed;
    result->n_skipped = n_short;
    result->threshold = threshold;
    if (n_short > 0)
        status = facet_fail(error, FACET_WARNING_COLLAPSE_SKIPPED, -1, -1,
                            "%d edges shorter than %g were kept: collapsing them would make the "
                            "mesh non-manifold or turn a face over",
                            (int)n_short, threshold);
done:
    free(s.xyz);
    free(s.verts);
    free(s.len);
    free(s.parent);
    free(s.next_member);
    free(s.tail);
    free(s.vf_start);
    free(s.vf);
    free(s.stamp);
    free(s.normal0);
    free(s.around);
    free(s.scratch);
    free(s.scratch_start);
    free(s.pairs);
    free(removed);
    free(collapsed);
    free(new_index);
    free(used);
    free(edges);
    return status;
}
