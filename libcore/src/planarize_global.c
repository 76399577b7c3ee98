/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* The local/global step: with the planes (and shapes, circles, boundary
 * targets) fixed, one sparse SPD solve gives every vertex and every plane
 * offset at once.
 *
 * Unknowns: q (3 nv, vertex-major) then the offsets d (nf). The matrix is
 *   vertex 3x3 blocks        data, sliding, circle and the K diagonal;
 *   vertex-vertex couplings  K (x) I3, K the scalar matrix of the coupled
 *                            terms (Laplacian, boundary fairness, shape,
 *                            parallelogram), fixed per pattern;
 *   vertex-offset couplings  planarity, w_f n_f per corner;
 *   offset diagonal          w_f * corners of f.
 * Stored as CHOLMOD's upper triangle in CSC. Column 3v+a holds, in row
 * order: 3u+a for each coupled u < v, then 3v .. 3v+a. Column 3nv+f holds
 * 3v..3v+2 for each vertex of f (ascending), then its diagonal. The pattern
 * depends on the topology and on which coupled terms are on, so CHOLMOD's
 * symbolic analysis runs once per (topology, coupled terms); each iteration
 * refactorises numerically.
 *
 * Without coupled terms (the default) no two vertices share an entry: each
 * vertex block touches only its own faces' offsets, so eliminating the
 * vertices first costs a 3x3 block each and leaves the offsets' system,
 * whose graph is the faces' (two faces adjacent when they share a vertex).
 * The offsets are numbered in a nested dissection order of that graph
 * (face_col), the vertices are eliminated here (schur_assemble, an LDL' of
 * each 3x3 block) and CHOLMOD factorizes the offsets' system (nf x nf) in
 * that order: Level 5 (3,072 quads) 2.70 Mflop and 72k entries in L per
 * factorization, against 4.15 Mflop and 138k for AMD on the whole system;
 * 100k quads 4.2M entries in L against 6.4M. Eliminating the offsets first
 * instead (a 3 nv system) is far worse: a face's offset couples all its
 * corners, and the vertex graph's fill is 5.5x (Level 5: 0.71-0.77M
 * entries in L against 0.13M). The (3 nv + nf) matrix is then never
 * stored: each step computes its residual while it assembles the vertices'
 * blocks, eliminates the vertices and solves the offsets' system for the
 * offsets' increment (schur_step), so the conjugate gradients run on
 * vectors of nf instead of 3 nv + nf (docs/benchmarks.md, "L/G memory").
 *
 * Fixed vertices stay unknowns with identity rows: their couplings move to
 * the right-hand side, so the pattern does not change when they do. */
#include "planarize_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void facet_pl_global_free(facet_planarizer *s)
{
    if (s->cholmod_started) {
        cholmod_free_sparse(&s->matrix, &s->cm);
        cholmod_free_factor(&s->factor, &s->cm);
        cholmod_free_dense(&s->rhs, &s->cm);
        cholmod_free_dense(&s->pcg_p, &s->cm);
        cholmod_free_dense(&s->pcg_ap, &s->cm);
        cholmod_free_dense(&s->pcg_r, &s->cm);
        cholmod_free_dense(&s->pcg_x, &s->cm);
        cholmod_free_dense(&s->pcg_y, &s->cm);
        cholmod_free_dense(&s->pcg_e, &s->cm);
        cholmod_free_sparse(&s->pmatrix, &s->cm);
        cholmod_free_dense(&s->perm_b, &s->cm);
        cholmod_free_dense(&s->perm_x, &s->cm);
        cholmod_free_sparse(&s->schur, &s->cm);
        cholmod_free_dense(&s->schur_b, &s->cm);
        cholmod_free_dense(&s->schur_x, &s->cm);
    }
    free(s->block);
    free(s->schur_u);
    free(s->schur_vec);
    s->block = s->schur_u = s->schur_vec = NULL;
    free(s->pmap);
    free(s->perm);
    free(s->face_col);
    s->pmap = s->perm = s->face_col = NULL;
    s->factor_ready = 0;
    free(s->corner_slot);
    free(s->couple_start);
    free(s->couple_vertex);
    free(s->couple_mu);
    free(s->couple_con);
    free(s->couple_diag_mu);
    free(s->couple_diag_con);
    s->corner_slot = NULL;
    s->couple_start = s->couple_vertex = NULL;
    s->couple_mu = s->couple_con = s->couple_diag_mu = s->couple_diag_con = NULL;
    s->couple_key = -1;
}

/* ---- the coupling matrix K ------------------------------------------------ */

typedef struct {
    int32_t hi, lo; /* hi >= lo */
    double mu, con;
} triplet;

typedef struct {
    triplet *t;
    size_t n, cap;
} triplets;

static int push(triplets *list, int32_t i, int32_t j, double mu, double con)
{
    if (list->n == list->cap) {
        const size_t cap = list->cap ? 2 * list->cap : 1024;
        triplet *t = realloc(list->t, cap * sizeof *t);
        if (!t)
            return 0;
        list->t = t, list->cap = cap;
    }
    triplet *e = &list->t[list->n++];
    e->hi = i > j ? i : j, e->lo = i > j ? j : i, e->mu = mu, e->con = con;
    return 1;
}

/* Adds weight * r r^T for the sparse row r (vertices idx, coefficients c). */
static int push_outer(triplets *list, int32_t n, const int32_t *idx, const double *c, double mu,
                      double con)
{
    for (int32_t a = 0; a < n; ++a)
        for (int32_t b = a; b < n; ++b) {
            const double cc = c[a] * c[b] * (a == b ? 1.0 : (idx[a] == idx[b] ? 2.0 : 1.0));
            if (!push(list, idx[a], idx[b], mu * cc, con * cc))
                return 0;
        }
    return 1;
}

static int compare_triplet(const void *x, const void *y)
{
    const triplet *a = x, *b = y;
    if (a->hi != b->hi)
        return a->hi < b->hi ? -1 : 1;
    return a->lo < b->lo ? -1 : (a->lo > b->lo ? 1 : 0);
}

/* Builds K for the options' coupled terms, with their weights. The pattern
 * depends only on which terms are on; the values on their weights and on the
 * control mesh (Laplacian weights), so it is rebuilt every solve. */
static facet_status build_coupling(facet_planarizer *s, facet_error *error)
{
    const facet_planarize_options *o = &s->o;
    const int32_t nv = s->nv, nf = s->nf;
    triplets list = {NULL, 0, 0};
    int ok = 1;
    int32_t idx_buf[64];
    double c_buf[64];
    if (o->laplacian > 0.0) {
        for (int32_t v = 0; v < nv && ok; ++v) {
            if (s->on_boundary[v])
                continue;
            const int32_t b = s->vertex_adj_start[v], n = s->vertex_adj_start[v + 1] - b;
            int32_t *idx = n + 1 <= 64 ? idx_buf : malloc(sizeof(int32_t) * (size_t)(n + 1));
            double *c = n + 1 <= 64 ? c_buf : malloc(sizeof(double) * (size_t)(n + 1));
            if (!idx || !c) {
                ok = 0;
            } else {
                idx[0] = v, c[0] = 1.0;
                for (int32_t k = 0; k < n; ++k)
                    idx[k + 1] = s->vertex_adj[b + k], c[k + 1] = -s->laplace_weight[b + k];
                ok = push_outer(&list, n + 1, idx, c, o->laplacian, 0.0);
            }
            if (idx != idx_buf)
                free(idx);
            if (c != c_buf)
                free(c);
        }
    }
    if (o->boundary_fairness > 0.0)
        for (int32_t v = 0; v < nv && ok; ++v)
            if (s->boundary_prev[v] >= 0) {
                const int32_t idx[3] = {s->boundary_prev[v], v, s->boundary_next[v]};
                const double c[3] = {1.0, -2.0, 1.0};
                ok = push_outer(&list, 3, idx, c, o->boundary_fairness, 0.0);
            }
    if (o->shape != FACET_SHAPE_NONE && o->shape_weight > 0.0)
        for (int32_t f = 0; f < nf && ok; ++f) { /* projector I - 11^T/n on the face */
            const int32_t b = s->face_start[f], n = s->face_start[f + 1] - b;
            for (int32_t i = 0; i < n && ok; ++i)
                for (int32_t j = i; j < n && ok; ++j) {
                    const double value = (i == j ? 1.0 : 0.0) - 1.0 / (double)n;
                    ok = push(&list, s->face_vertices[b + i], s->face_vertices[b + j],
                              o->shape_weight * value, 0.0);
                }
        }
    if (o->parallelogram > 0.0)
        for (int32_t f = 0; f < nf && ok; ++f)
            if (s->face_start[f + 1] - s->face_start[f] == 4) {
                const double c[4] = {1.0, -1.0, 1.0, -1.0};
                ok = push_outer(&list, 4, s->face_vertices + s->face_start[f], c, 0.0, o->parallelogram);
            }
    if (!ok) {
        free(list.t);
        return facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory for the couplings");
    }
    if (list.n > 1) /* qsort(NULL, 0, ...) is undefined */
        qsort(list.t, list.n, sizeof *list.t, compare_triplet);
    /* merge duplicates; split into diagonal and strictly lower (u < v) */
    free(s->couple_start);
    free(s->couple_vertex);
    free(s->couple_mu);
    free(s->couple_con);
    free(s->couple_diag_mu);
    free(s->couple_diag_con);
    s->couple_start = calloc((size_t)nv + 1, sizeof(int32_t));
    s->couple_vertex = malloc(sizeof(int32_t) * (list.n ? list.n : 1));
    s->couple_mu = malloc(sizeof(double) * (list.n ? list.n : 1));
    s->couple_con = malloc(sizeof(double) * (list.n ? list.n : 1));
    /* the diagonal only with coupled terms (NULL: K = 0, the default) */
    s->couple_diag_mu = list.n ? calloc((size_t)nv, sizeof(double)) : NULL;
    s->couple_diag_con = list.n ? calloc((size_t)nv, sizeof(double)) : NULL;
    if (!s->couple_start || !s->couple_vertex || !s->couple_mu || !s->couple_con ||
        (list.n && (!s->couple_diag_mu || !s->couple_diag_con))) {
        free(list.t);
        return facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory for the couplings");
    }
    size_t m = 0;
    for (size_t k = 0; k < list.n;) {
        triplet e = list.t[k++];
        while (k < list.n && list.t[k].hi == e.hi && list.t[k].lo == e.lo) {
            e.mu += list.t[k].mu, e.con += list.t[k].con;
            ++k;
        }
        if (e.hi == e.lo) {
            s->couple_diag_mu[e.hi] += e.mu, s->couple_diag_con[e.hi] += e.con;
        } else {
            s->couple_vertex[m] = e.lo, s->couple_mu[m] = e.mu, s->couple_con[m] = e.con;
            s->couple_start[e.hi + 1]++;
            ++m;
        }
    }
    for (int32_t v = 0; v < nv; ++v)
        s->couple_start[v + 1] += s->couple_start[v];
    free(list.t);
    return FACET_OK;
}

/* A factorization that costs more than this many conjugate gradient steps
 * (the analysis's flops against two triangular solves and a product) is
 * costly: global_step keeps its factor longer. With the boundary's fairness
 * alone a factorization costs 5-8 steps, with a shape term or the Laplacian
 * 17-100 (Level 4 to the 1,008-hex torus). */
#define FACTOR_COSTLY 12.0

/* ---- the offsets' order ----------------------------------------------------- */

/* Fills face_col with 3 nv + the rank of each face in a nested dissection
 * order of the face graph (faces adjacent when they share a vertex), or in
 * AMD's order if METIS fails. Deterministic: METIS runs with its fixed seed. */
/* The pairs of faces h <= f around one vertex, summed over the vertices:
 * room for the faces' coupling pattern (a pair around two vertices counts
 * twice). */
static size_t face_pairs(const facet_planarizer *s)
{
    size_t pairs = 0;
    for (int32_t v = 0; v < s->nv; ++v) {
        const size_t k = (size_t)(s->vertex_start[v + 1] - s->vertex_start[v]);
        pairs += k * (k + 1) / 2;
    }
    return pairs;
}

static facet_status order_faces(facet_planarizer *s, facet_error *error)
{
    cholmod_common *cm = &s->cm;
    const int32_t nv = s->nv, nf = s->nf;
    /* the upper triangle, unpacked: column f lists the faces h <= f that
     * share a vertex with f, once each; its room: one per (vertex of f, face
     * h <= f around it) */
    const size_t count = face_pairs(s);
    int *col_count = calloc((size_t)nf + 1, sizeof(int));
    int *mark = malloc(sizeof(int) * (size_t)(nf ? nf : 1));
    cholmod_sparse *g = count <= (size_t)INT32_MAX
                            ? cholmod_allocate_sparse((size_t)nf, (size_t)nf, count, 0, 0, 1, CHOLMOD_PATTERN, cm)
                            : NULL;
    int *order = malloc(sizeof(int) * (size_t)(nf ? nf : 1));
    int *cparent = malloc(sizeof(int) * (size_t)(nf ? nf : 1));
    int *cmember = malloc(sizeof(int) * (size_t)(nf ? nf : 1));
    s->face_col = malloc(sizeof(int32_t) * (size_t)(nf ? nf : 1));
    facet_status status = FACET_OK;
    if (!col_count || !mark || !g || !order || !cparent || !cmember || !s->face_col) {
        status = facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory for the faces' order");
        goto done;
    }
    /* the faces at each vertex ascend (vertex_faces), so the pair (f, g),
     * g <= f, comes from every vertex they share: mark[] keeps one */
    for (int32_t v = 0; v < nv; ++v)
        for (int32_t i = s->vertex_start[v]; i < s->vertex_start[v + 1]; ++i)
            col_count[s->vertex_faces[i] + 1] += i - s->vertex_start[v] + 1;
    for (int32_t f = 0; f < nf; ++f)
        col_count[f + 1] += col_count[f];
    {
        int *gp = g->p, *gi = g->i, *gnz = g->nz;
        for (int32_t f = 0; f < nf; ++f)
            gp[f] = col_count[f], gnz[f] = 0;
        gp[nf] = col_count[nf];
        for (int32_t f = 0; f < nf; ++f)
            mark[f] = -1;
        /* per column f: the vertices of f, and the faces g <= f around them */
        for (int32_t f = 0; f < nf; ++f)
            for (int32_t c = s->face_start[f]; c < s->face_start[f + 1]; ++c) {
                const int32_t v = s->face_vertices[c];
                for (int32_t i = s->vertex_start[v]; i < s->vertex_start[v + 1]; ++i) {
                    const int32_t h = s->vertex_faces[i];
                    if (h > f)
                        break;
                    if (mark[h] != f) {
                        mark[h] = f;
                        gi[gp[f] + gnz[f]++] = h;
                    }
                }
            }
    }
    const int current = cm->current;
    const size_t nd_small = cm->method[0].nd_small;
    cm->current = 0;
    /* Level 5: 3.04 Mflop per factorization (the default 200: 3.32, 4: 3.01);
     * 100k quads: 607 Mflop (200: 613), 0.5 s once per topology */
    cm->method[0].nd_small = 20;
    const long ok = cholmod_nested_dissection(g, NULL, 0, order, cparent, cmember, cm);
    cm->current = current;
    cm->method[0].nd_small = nd_small;
    if (ok < 0 || cm->status < CHOLMOD_OK) {
        cm->status = CHOLMOD_OK;
        if (!cholmod_amd(g, NULL, 0, order, cm)) {
            status = facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory for the faces' order");
            goto done;
        }
    }
    for (int32_t k = 0; k < nf; ++k)
        s->face_col[order[k]] = 3 * nv + k;
done:
    free(col_count);
    free(mark);
    cholmod_free_sparse(&g, cm);
    free(order);
    free(cparent);
    free(cmember);
    return status;
}

/* ---- the offsets' system (no couplings) -------------------------------------- */

static int compare_int(const void *x, const void *y)
{
    const int a = *(const int *)x, b = *(const int *)y;
    return (a > b) - (a < b);
}

/* The pattern of the offsets' system after the vertices' elimination (two
 * faces coupled when they share a vertex), after order_faces; also the
 * vertices' blocks and the step's vectors. */
static facet_status schur_setup(facet_planarizer *s, facet_error *error)
{
    cholmod_common *cm = &s->cm;
    const int32_t nv = s->nv, nf = s->nf;
    const size_t pairs = face_pairs(s);
    if (pairs > (size_t)INT32_MAX)
        return facet_pl_fail(s, error, FACET_ERROR_TOO_LARGE, "mesh too large for the sparse system");
    int *room = calloc((size_t)nf + 1, sizeof(int));
    int *mark = malloc(sizeof(int) * (size_t)(nf ? nf : 1));
    s->block = malloc(sizeof(double) * 6 * (size_t)(nv ? nv : 1));
    s->schur_u = malloc(sizeof(double) * 3 * (size_t)(nv ? nv : 1));
    s->schur_vec = malloc(sizeof(double) * 2 * (size_t)(nf ? nf : 1));
    s->schur_b = cholmod_allocate_dense((size_t)nf, 1, (size_t)nf, CHOLMOD_REAL, cm);
    facet_status status = FACET_OK;
    if (!room || !mark || !s->block || !s->schur_u ||
        !s->schur_vec || !s->schur_b) {
        status = facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory for the sparse system");
        goto done;
    }
    const int32_t base = 3 * nv;
    /* room per column (in the offsets' order): one per pair with it the later */
    for (int32_t v = 0; v < nv; ++v)
        for (int32_t i = s->vertex_start[v]; i < s->vertex_start[v + 1]; ++i)
            for (int32_t j = s->vertex_start[v]; j <= i; ++j) {
                const int32_t a = s->face_col[s->vertex_faces[i]] - base;
                const int32_t b = s->face_col[s->vertex_faces[j]] - base;
                room[(a > b ? a : b) + 1]++;
            }
    for (int32_t f = 0; f < nf; ++f)
        room[f + 1] += room[f];
    /* the distinct rows of each column, ascending, packed: in a scratch
     * array as large as the pairs, then into a matrix of their own size (a
     * pair around two vertices counts twice: quads, half the room) */
    int *face_of = mark; /* face of each column */
    for (int32_t f = 0; f < nf; ++f)
        face_of[s->face_col[f] - base] = f;
    int *rows = malloc(sizeof(int) * (size_t)(room[nf] ? room[nf] : 1));
    if (!rows) {
        status = facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory for the sparse system");
        goto done;
    }
    size_t at = 0;
    for (int32_t col = 0; col < nf; ++col) {
        const int32_t f = face_of[col];
        const size_t first = at;
        for (int32_t c = s->face_start[f]; c < s->face_start[f + 1]; ++c) {
            const int32_t v = s->face_vertices[c];
            for (int32_t i = s->vertex_start[v]; i < s->vertex_start[v + 1]; ++i) {
                const int32_t row = s->face_col[s->vertex_faces[i]] - base;
                int seen = row > col;
                for (size_t k = first; k < at && !seen; ++k)
                    seen = rows[k] == row;
                if (!seen)
                    rows[at++] = row;
            }
        }
        qsort(rows + first, at - first, sizeof(int), compare_int);
        room[col] = (int)first; /* room[col] is no longer needed */
    }
    room[nf] = (int)at;
    s->schur = cholmod_allocate_sparse((size_t)nf, (size_t)nf, at, 1, 1, 1, CHOLMOD_REAL, cm);
    if (!s->schur) {
        free(rows);
        status = facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory for the sparse system");
        goto done;
    }
    int *sp = s->schur->p, *si = s->schur->i;
    memcpy(sp, room, sizeof(int) * ((size_t)nf + 1));
    memcpy(si, rows, sizeof(int) * at);
    free(rows);
done:
    free(room);
    free(mark);
    return status;
}

/* The coupling of a face's offset to each of its free corners, w_f n_f,
 * and its offset's diagonal (w_f times its corners; 1 for an exempt face,
 * whose offset is decoupled), at w = 1 - mu. */
static inline void face_coupling(const facet_planarizer *s, int32_t f, double w, double *c)
{
    const double pw = w * (s->face_weight ? s->face_weight[f] : 1.0);
    const double *n = s->normal + 3 * (size_t)f;
    c[0] = pw * n[0], c[1] = pw * n[1], c[2] = pw * n[2];
}

static inline double face_diagonal(const facet_planarizer *s, int32_t f, double w)
{
    const double pw = w * (s->face_weight ? s->face_weight[f] : 1.0);
    return pw > 0.0 ? pw * (double)(s->face_start[f + 1] - s->face_start[f]) : 1.0;
}

/* LDL' of the 3x3 block a (a00 a01 a11 a02 a12 a22) into bl (l10 l20 l21
 * 1/d0 1/d1 1/d2); 0 if it is not positive definite. */
static inline int block_ldl(const double *a, double *bl)
{
    const double a00 = a[0], a01 = a[1], a11 = a[2], a02 = a[3], a12 = a[4], a22 = a[5];
    const double d0 = a00;
    if (!(d0 > 0.0))
        return 0;
    const double l10 = a01 / d0, l20 = a02 / d0;
    const double d1 = a11 - l10 * a01;
    if (!(d1 > 0.0))
        return 0;
    const double l21 = (a12 - l20 * a01) / d1;
    const double d2 = a22 - l20 * a02 - l21 * l21 * d1;
    if (!(d2 > 0.0))
        return 0;
    bl[0] = l10, bl[1] = l20, bl[2] = l21, bl[3] = 1.0 / d0, bl[4] = 1.0 / d1, bl[5] = 1.0 / d2;
    return 1;
}

/* z = B^-1 y for the block's LDL' bl (z may be y) */
static inline void block_solve(const double *bl, const double *y, double *z)
{
    const double y0 = y[0], y1 = y[1] - bl[0] * y0, y2 = y[2] - bl[1] * y0 - bl[2] * y1;
    const double z2 = y2 * bl[5], z1 = y1 * bl[4] - bl[2] * z2, z0 = y0 * bl[3] - bl[0] * z1 - bl[1] * z2;
    z[0] = z0, z[1] = z1, z[2] = z2;
}

/* t = B_v^-1 sum over v's faces of c_f x_f: vertex v's share of the
 * offsets' x (x by offsets' index, face_col - 3 nv) */
static inline void coupled_solve(const facet_planarizer *s, int32_t v, double w, const double *x, double t[3])
{
    const int32_t base = 3 * s->nv;
    double c[3];
    t[0] = t[1] = t[2] = 0.0;
    for (int32_t i = s->vertex_start[v]; i < s->vertex_start[v + 1]; ++i) {
        const int32_t f = s->vertex_faces[i];
        const double xf = x[s->face_col[f] - base];
        face_coupling(s, f, w, c);
        t[0] += c[0] * xf, t[1] += c[1] * xf, t[2] += c[2] * xf;
    }
    block_solve(s->block + 6 * (size_t)v, t, t);
}

/* The offsets' system D - C^T B^-1 C into schur from this step's blocks
 * (block) and couplings at w. Serial: the faces' entries gather from
 * several vertices. */
static void schur_assemble(facet_planarizer *s, double w)
{
    const int32_t nv = s->nv, nf = s->nf, base = 3 * nv;
    double *sx = s->schur->x;
    const int *sp = s->schur->p, *si = s->schur->i;
    memset(sx, 0, sizeof(double) * (size_t)sp[nf]);
    for (int32_t f = 0; f < nf; ++f) /* the diagonal is each column's last entry */
        sx[sp[s->face_col[f] - base + 1] - 1] = face_diagonal(s, f, w);
    for (int32_t v = 0; v < nv; ++v) {
        if (s->fixed[v]) /* an identity block, no coupling */
            continue;
        const double *bl = s->block + 6 * (size_t)v;
        const int32_t b = s->vertex_start[v], k = s->vertex_start[v + 1] - b;
        const int32_t *faces = s->vertex_faces + b;
        for (int32_t i = 0; i < k; ++i) { /* z = B^-1 c_i; S_ij -= c_j . z */
            double c[3], z[3];
            face_coupling(s, faces[i], w, c);
            block_solve(bl, c, z);
            const int32_t ci = s->face_col[faces[i]] - base;
            for (int32_t j = 0; j <= i; ++j) {
                double cj[3];
                face_coupling(s, faces[j], w, cj);
                /* the pair's entry: row min, column max (rows ascend) */
                const int32_t cj_col = s->face_col[faces[j]] - base;
                const int32_t col = ci > cj_col ? ci : cj_col, row = ci > cj_col ? cj_col : ci;
                int at = sp[col];
                while (si[at] != row)
                    ++at;
                sx[at] -= cj[0] * z[0] + cj[1] * z[1] + cj[2] * z[2];
            }
        }
    }
}

/* y = S x for the offsets' system at w without storing it: D x - C^T
 * B^-1 C x, vertex by vertex (serial: each scatters to its faces; vectors
 * in schur's order). */
static void schur_product(const facet_planarizer *s, double w, const double *x, double *y)
{
    const int32_t nv = s->nv, nf = s->nf, base = 3 * nv;
    for (int32_t f = 0; f < nf; ++f) {
        const int32_t col = s->face_col[f] - base;
        y[col] = face_diagonal(s, f, w) * x[col];
    }
    for (int32_t v = 0; v < nv; ++v) {
        if (s->fixed[v])
            continue;
        double t[3], c[3];
        coupled_solve(s, v, w, x, t);
        for (int32_t i = s->vertex_start[v]; i < s->vertex_start[v + 1]; ++i) {
            const int32_t f = s->vertex_faces[i];
            face_coupling(s, f, w, c);
            y[s->face_col[f] - base] -= c[0] * t[0] + c[1] * t[1] + c[2] * t[2];
        }
    }
}

/* schur_x = S_old^-1 schur_b by the factorization */
static int schur_precondition(facet_planarizer *s)
{
    return cholmod_solve2(CHOLMOD_A, s->factor, s->schur_b, NULL, &s->schur_x, NULL, &s->pcg_y, &s->pcg_e,
                          &s->cm);
}
/* ---- pattern and analysis ------------------------------------------------- */

/* The symbolic factorization of a matrix already in its fill-reducing
 * order (factorized as it is), for the pattern of options key. */
static facet_status analyze_natural(facet_planarizer *s, cholmod_sparse *a, int32_t key, facet_error *error)
{
    const int nmethods = s->cm.nmethods, postorder = s->cm.postorder;
    const int ordering = s->cm.method[0].ordering;
    s->cm.nmethods = 1, s->cm.method[0].ordering = CHOLMOD_NATURAL, s->cm.postorder = 0;
    s->factor = cholmod_analyze(a, &s->cm);
    /* the analysis leaves 32 B per column of workspace in cm (Iwork of 6n);
     * the factorization then allocates the 16 it needs: -16 B/face */
    cholmod_free_work(&s->cm);
    s->cm.nmethods = nmethods, s->cm.method[0].ordering = ordering, s->cm.postorder = postorder;
    if (!s->factor || s->cm.status < CHOLMOD_OK)
        return facet_pl_fail(s, error, FACET_ERROR_NUMERICAL, "sparse analysis failed");
    s->couple_key = key;
    return FACET_OK;
}

facet_status facet_pl_global_setup(facet_planarizer *s, facet_error *error)
{
    const int32_t key = facet_pl_couple_key(&s->o);
    const int32_t nv = s->nv, nf = s->nf, nc = s->nc;
    if (!s->cholmod_started) {
        cholmod_start(&s->cm);
        s->cm.print = 0;
        s->cm.error_handler = NULL;
        /* Simplicial LDL': the system's supernodes are small (vertex blocks
         * and face offsets), and the supernodal path spends its time in BLAS
         * and OpenMP synchronisation (futex calls) instead (docs/benchmarks.md). */
        s->cm.supernodal = CHOLMOD_SIMPLICIAL;
        s->cholmod_started = 1;
    }
    if (s->factor && key == s->couple_key)
        return build_coupling(s, error); /* same pattern: new values only */
    facet_pl_global_free(s);
    facet_status status = build_coupling(s, error);
    if (status != FACET_OK)
        return status;
    const size_t n_couple = (size_t)s->couple_start[nv];
    const size_t n = 3 * (size_t)nv + (size_t)nf;
    const size_t nnz = 6 * (size_t)nv + 3 * n_couple + 3 * (size_t)nc + (size_t)nf;
    if (nnz > (size_t)INT32_MAX)
        return facet_pl_fail(s, error, FACET_ERROR_TOO_LARGE, "mesh too large for the sparse system");
    /* no couplings: the offsets in the faces' nested dissection order, after
     * every vertex; else in face order, and the analysis finds the order */
    const int natural = n_couple == 0;
    if (natural) { /* the matrix is not stored (schur_step) */
        status = order_faces(s, error);
        if (status != FACET_OK)
            return status;
        status = schur_setup(s, error); /* the offsets' system, already in order */
        if (status != FACET_OK)
            return status;
        return analyze_natural(s, s->schur, key, error);
    }
    s->rhs = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &s->cm);
    s->pcg_p = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &s->cm);
    s->pcg_ap = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &s->cm);
    s->pcg_r = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &s->cm);
    s->pcg_x = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &s->cm);
    s->matrix = cholmod_allocate_sparse(n, n, nnz, 1, 1, 1, CHOLMOD_REAL, &s->cm);
    s->corner_slot = malloc(sizeof(int32_t) * (size_t)nc);
    if (!s->rhs || !s->pcg_p || !s->pcg_ap || !s->pcg_r || !s->pcg_x || !s->matrix || !s->corner_slot)
        return facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory for the sparse system");
    s->face_col = malloc(sizeof(int32_t) * (size_t)(nf ? nf : 1));
    if (!s->face_col)
        return facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory for the sparse system");
    for (int32_t f = 0; f < nf; ++f)
        s->face_col[f] = 3 * nv + f;
    int32_t *face_of_col = malloc(sizeof(int32_t) * (size_t)(nf ? nf : 1));
    if (!face_of_col)
        return facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory for the sparse system");
    for (int32_t f = 0; f < nf; ++f)
        face_of_col[s->face_col[f] - 3 * nv] = f;
    int *cp = s->matrix->p, *ri = s->matrix->i;
    size_t at = 0;
    for (int32_t v = 0; v < nv; ++v)
        for (int a = 0; a < 3; ++a) {
            cp[3 * v + a] = (int)at;
            for (int32_t k = s->couple_start[v]; k < s->couple_start[v + 1]; ++k)
                ri[at++] = 3 * s->couple_vertex[k] + a;
            for (int b = 0; b <= a; ++b)
                ri[at++] = 3 * v + b;
        }
    int32_t order[64];
    for (int32_t col = 0; col < nf; ++col) {
        const int32_t f = face_of_col[col];
        cp[3 * nv + col] = (int)at;
        const int32_t b = s->face_start[f], n_f = s->face_start[f + 1] - b;
        int32_t *ord = n_f <= 64 ? order : malloc(sizeof(int32_t) * (size_t)n_f);
        if (!ord) {
            free(face_of_col);
            return facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory");
        }
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
        ri[at++] = 3 * nv + col;
        if (ord != order)
            free(ord);
    }
    free(face_of_col);
    cp[n] = (int)at;
    double *x = s->matrix->x;
    for (size_t k = 0; k < at; ++k)
        x[k] = 1.0;
    cholmod_factor *analysis = cholmod_analyze(s->matrix, &s->cm);
    if (!analysis || s->cm.status < CHOLMOD_OK) {
        cholmod_free_factor(&analysis, &s->cm);
        return facet_pl_fail(s, error, FACET_ERROR_NUMERICAL, "sparse analysis failed");
    }
    /* Permute once: cholmod_factorize of the upper triangle in a
     * fill-reducing order transposes the matrix twice per call (a tenth of
     * an L/G iteration at 3k faces). The same two transposes, done here on
     * the entries' own indices, give the permuted matrix and where each of
     * its entries comes from; every factorization then gathers the values
     * and factorizes in the natural order: the same arithmetic. */
    s->perm = malloc(sizeof(int32_t) * n);
    s->pmap = malloc(sizeof(int32_t) * at);
    s->perm_b = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &s->cm);
    s->perm_x = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &s->cm);
    if (!s->perm || !s->pmap || !s->perm_b || !s->perm_x) {
        cholmod_free_factor(&analysis, &s->cm);
        return facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory for the sparse system");
    }
    const int *order_perm = analysis->Perm;
    for (size_t k = 0; k < n; ++k)
        s->perm[k] = order_perm[k];
    for (size_t k = 0; k < at; ++k)
        x[k] = (double)k; /* exact: at < 2^31 */
    cholmod_sparse *lower = cholmod_ptranspose(s->matrix, 2, analysis->Perm, NULL, 0, &s->cm);
    cholmod_free_factor(&analysis, &s->cm);
    s->pmatrix = lower ? cholmod_ptranspose(lower, 2, NULL, NULL, 0, &s->cm) : NULL;
    cholmod_free_sparse(&lower, &s->cm);
    if (!s->pmatrix || (size_t)((int *)s->pmatrix->p)[n] != at)
        return facet_pl_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, "out of memory for the sparse system");
    const double *px = s->pmatrix->x;
    for (size_t k = 0; k < at; ++k)
        s->pmap[k] = (int32_t)px[k];
    status = analyze_natural(s, s->pmatrix, key, error);
    /* a conjugate gradient step: two triangular solves and the product */
    const double step_flops = 4.0 * s->cm.lnz + 4.0 * (double)at;
    s->factor_costly = status == FACET_OK && s->cm.fl > FACTOR_COSTLY * step_flops;
    return status;
}

/* y = A^-1 b by the factorization, in the unknowns' own order (y and b
 * distinct). */
static int factor_solve(facet_planarizer *s, const double *b, double *y)
{
    const size_t n = 3 * (size_t)s->nv + (size_t)s->nf;
    double *pb = s->perm_b->x;
    for (size_t k = 0; k < n; ++k)
        pb[k] = b[s->perm[k]];
    if (!cholmod_solve2(CHOLMOD_A, s->factor, s->perm_b, NULL, &s->perm_x, NULL, &s->pcg_y, &s->pcg_e,
                        &s->cm))
        return 0;
    const double *px = s->perm_x->x;
    for (size_t k = 0; k < n; ++k)
        y[s->perm[k]] = px[k];
    return 1;
}

/* ---- one global step ---------------------------------------------------- */

enum {
    FACTOR_AGE = 8,     /* steps a factorization serves as a preconditioner */
    PCG_MAX = 20,       /* conjugate gradient steps before refactorizing instead */
    PCG_SLOW = 4,       /* more steps than this: refactorize at the next step */
    PCG_SLOW_COSTLY = 8 /* the same for a costly factorization, whatever its age */
};

/* Residual of the increment, relative. 1e-4 instead of 1e-6: 2-3 steps
 * instead of 3-7 (Level 5, L/G x30 default schedule 59 -> 49 ms CPU); over
 * the 13 generated meshes up to 12k faces and 20 public ones, default L/G to
 * 1e-6 takes 2,772 iterations in all against 2,775 (AMD, 1e-6), the RMS
 * distance from the input is the same on geometric mean (0.99986; from
 * 0.984 to 1.013 per mesh) and the CPU time 6.9 s against 10.4 s (8.1 s with
 * 1e-6 and the nested dissection order). 1e-3: 2,784 iterations, 6.2 s; 1e-2:
 * 2,819, 5.3 s, distances 0.85-1.10. */
#ifndef PCG_TOL
#define PCG_TOL 1e-4
#endif
/* The same for the offsets' system (schur_step), relative to its own
 * right-hand side. 1e-5: its steps are cheap (vectors of nf), and a live
 * update's result then follows a drag as exact solves do: over ten drags of
 * the 24 x 24 grid of test_planarize_live, the dragged vertex follows by
 * 0.619 of the drag on mean (exact solves, 1e-13: 0.614; 1e-4: 0.580; the
 * stored matrix's 1e-4 on the whole system: 0.640), at +9.5% instructions
 * for Level 5 L/G x30 (985M against 899M with 1e-4; the whole-system
 * solve took 1,228M). Over the 28 public and generated meshes of
 * docs/benchmarks.md ("L/G memory"), 2,194 iterations to 1e-6 in all
 * against 2,208 with 1e-4 and 2,208 before. */
#ifndef SCHUR_PCG_TOL
#define SCHUR_PCG_TOL 1e-5
#endif

static double dot_n(const double *a, const double *b, size_t n)
{
    double sum = 0.0;
    for (size_t k = 0; k < n; ++k)
        sum += a[k] * b[k];
    return sum;
}

/* y = beta y + alpha A x for the matrix's upper triangle (every column ends
 * with its diagonal), alpha = +-1 and beta = 0 or 1: cholmod_sdmult's
 * symmetric case for one column, operation for operation (the same bits),
 * without its per-entry tests (it took about 20 instructions per stored
 * entry, a fifth of the default schedule's). */
static void sym_matvec(const cholmod_sparse *a, double alpha, int beta, const double *x, double *y)
{
    const int *cp = a->p, *ri = a->i;
    const double *ax = a->x;
    const size_t n = a->ncol;
    if (!beta)
        memset(y, 0, sizeof(double) * n);
    for (size_t j = 0; j < n; ++j) {
        const double xj = alpha * x[j];
        const int end = cp[j + 1] - 1;
        double yj = 0.0;
        for (int p = cp[j]; p < end; ++p) {
            const int i = ri[p];
            y[i] += ax[p] * xj;
            yj += ax[p] * x[i];
        }
        y[j] += ax[end] * xj;
        y[j] += alpha * yj;
    }
}

/* A system for pcg_run: y = A p into a vector of the solve's (returned), and
 * z = M^-1 r into the same vector (returned; NULL on failure). */
typedef struct {
    double *(*apply)(void *ctx, const double *p);
    double *(*precondition)(void *ctx, const double *r);
    void *ctx;
} pcg_system;

/* Conjugate gradients on sys from x = 0 (x is zeroed), r the right-hand side
 * and then the residual, p the search direction, to a residual of tol times
 * the right-hand side's. Returns the steps taken, or 0 if it did not get
 * there (or failed). Serial and in a fixed order: the same bits for any
 * thread count. A p and then z = M^-1 r share one vector (A p is dead once
 * r is updated), so the solve needs four: r, p, x and that one. */
static int pcg_run(const pcg_system *sys, size_t n, double tol, double *x, double *r, double *p)
{
    memset(x, 0, sizeof(double) * n);
    const double r0 = sqrt(dot_n(r, r, n));
    if (!(r0 > 0.0))
        return 1; /* x = 0 */
    const double *z = sys->precondition(sys->ctx, r);
    if (!z)
        return 0;
    memcpy(p, z, sizeof(double) * n);
    double rz = dot_n(r, z, n);
    for (int step = 1; step <= PCG_MAX; ++step) {
        const double *ap = sys->apply(sys->ctx, p);
        const double pap = dot_n(p, ap, n);
        if (!(pap > 0.0) || !isfinite(pap))
            return 0;
        const double alpha = rz / pap;
        for (size_t k = 0; k < n; ++k) {
            x[k] += alpha * p[k];
            r[k] -= alpha * ap[k];
        }
        if (sqrt(dot_n(r, r, n)) <= tol * r0)
            return step;
        if (!(z = sys->precondition(sys->ctx, r)))
            return 0;
        const double rz_next = dot_n(r, z, n), beta = rz_next / rz;
        rz = rz_next;
        for (size_t k = 0; k < n; ++k)
            p[k] = z[k] + beta * p[k];
    }
    return 0;
}

static double *stored_apply(void *ctx, const double *p)
{
    facet_planarizer *s = ctx;
    sym_matvec(s->matrix, 1.0, 0, p, s->pcg_ap->x);
    return s->pcg_ap->x;
}

static double *stored_precondition(void *ctx, const double *r)
{
    facet_planarizer *s = ctx;
    return factor_solve(s, r, s->pcg_ap->x) ? s->pcg_ap->x : NULL;
}

/* Solves matrix * pcg_x = rhs by conjugate gradients preconditioned with
 * the (older) factorization, to a residual PCG_TOL of the right-hand side's.
 * Returns the steps taken, or 0 if it did not get there (or failed); rhs is
 * left as it was (a failure falls back to a factorization of it). */
static int pcg_solve(facet_planarizer *s)
{
    const size_t n = 3 * (size_t)s->nv + (size_t)s->nf;
    memcpy(s->pcg_r->x, s->rhs->x, sizeof(double) * n);
    const pcg_system sys = {stored_apply, stored_precondition, s};
    return pcg_run(&sys, n, PCG_TOL, s->pcg_x->x, s->pcg_r->x, s->pcg_p->x);
}

static double face_weight(const facet_planarizer *s, int32_t f)
{
    return s->face_weight ? s->face_weight[f] : 1.0;
}

/* The vertex v's 3x3 block (a00 a01 a11 a02 a12 a22) and right-hand side
 * of the step at mu: its data, surface, planarity (the sum of its faces'
 * w_f n_f n_f^T), shape, circle, sliding and angle floor terms and the
 * diagonal of K. */
static inline void vertex_terms(const facet_planarizer *s, int32_t v, double mu, double *av, double *bv)
{
    const facet_planarize_options *o = &s->o;
    const double w = 1.0 - mu;
    const int shape = o->shape != FACET_SHAPE_NONE && o->shape_weight > 0.0;
    const int sliding = o->boundary == FACET_BOUNDARY_SLIDING;
    const double *p = s->p;
    const double *pv = p + 3 * (size_t)v, *nu = s->vertex_normal + 3 * (size_t)v;
    const double dt = mu * o->data_tangent, dn = mu * o->data_normal;
    const double kd = s->couple_diag_mu ? mu * s->couple_diag_mu[v] + w * s->couple_diag_con[v] : 0.0;
    double a00 = dt + kd, a11 = dt + kd, a22 = dt + kd, a01 = 0.0, a02 = 0.0, a12 = 0.0;
    const double e = dn - dt;
    a00 += e * nu[0] * nu[0], a01 += e * nu[0] * nu[1], a02 += e * nu[0] * nu[2];
    a11 += e * nu[1] * nu[1], a12 += e * nu[1] * nu[2], a22 += e * nu[2] * nu[2];
    double b0 = a00 * pv[0] + a01 * pv[1] + a02 * pv[2];
    double b1 = a01 * pv[0] + a11 * pv[1] + a12 * pv[2];
    double b2 = a02 * pv[0] + a12 * pv[1] + a22 * pv[2];
    /* the K diagonal belongs to the matrix, not to the data target */
    b0 -= kd * pv[0], b1 -= kd * pv[1], b2 -= kd * pv[2];
    if (o->surface_weight > 0.0 && s->reference) { /* mu w (n . (q - s))^2 */
        const double *sn = s->surface_normal + 3 * (size_t)v, *sp = s->surface_point + 3 * (size_t)v;
        const double sw = mu * o->surface_weight, ns = sn[0] * sp[0] + sn[1] * sp[1] + sn[2] * sp[2];
        a00 += sw * sn[0] * sn[0], a01 += sw * sn[0] * sn[1], a02 += sw * sn[0] * sn[2];
        a11 += sw * sn[1] * sn[1], a12 += sw * sn[1] * sn[2], a22 += sw * sn[2] * sn[2];
        b0 += sw * ns * sn[0], b1 += sw * ns * sn[1], b2 += sw * ns * sn[2];
    }
    for (int32_t k = s->vertex_start[v]; k < s->vertex_start[v + 1]; ++k) {
        const int32_t f = s->vertex_faces[k];
        const double *n = s->normal + 3 * (size_t)f;
        const double pw = w * face_weight(s, f);
        a00 += pw * n[0] * n[0], a01 += pw * n[0] * n[1], a02 += pw * n[0] * n[2];
        a11 += pw * n[1] * n[1], a12 += pw * n[1] * n[2], a22 += pw * n[2] * n[2];
        if (!shape && !(o->circular > 0.0))
            continue;
        const int32_t fb = s->face_start[f];
        int32_t corner = 0;
        while (s->face_vertices[fb + corner] != v)
            ++corner;
        if (shape) { /* right-hand side of lambda |P q - s R x|^2: s R x */
            const double *sr = s->shape + 9 * (size_t)f, *cpf = s->control_centroid + 3 * (size_t)f;
            const double dx[3] = {pv[0] - cpf[0], pv[1] - cpf[1], pv[2] - cpf[2]};
            const double lw = mu * o->shape_weight;
            b0 += lw * (sr[0] * dx[0] + sr[1] * dx[1] + sr[2] * dx[2]);
            b1 += lw * (sr[3] * dx[0] + sr[4] * dx[1] + sr[5] * dx[2]);
            b2 += lw * (sr[6] * dx[0] + sr[7] * dx[1] + sr[8] * dx[2]);
        }
        if (o->circular > 0.0) {
            const double *t = s->circle_target + 3 * (size_t)(fb + corner);
            const double cw = w * o->circular;
            b0 += cw * t[0], b1 += cw * t[1], b2 += cw * t[2];
            a00 += cw, a11 += cw, a22 += cw;
        }
    }
    if (sliding && s->boundary_prev[v] >= 0) {
        const double *t = s->slide_tangent + 3 * (size_t)v, *g = s->slide_target + 3 * (size_t)v;
        const double m00 = w * (1.0 - t[0] * t[0]), m01 = -w * t[0] * t[1], m02 = -w * t[0] * t[2];
        const double m11 = w * (1.0 - t[1] * t[1]), m12 = -w * t[1] * t[2], m22 = w * (1.0 - t[2] * t[2]);
        a00 += m00, a01 += m01, a02 += m02, a11 += m11, a12 += m12, a22 += m22;
        b0 += m00 * g[0] + m01 * g[1] + m02 * g[2];
        b1 += m01 * g[0] + m11 * g[1] + m12 * g[2];
        b2 += m02 * g[0] + m12 * g[1] + m22 * g[2];
    }
    if (o->angle_floor > 0.0 && s->guard_count[v] > 0.0) { /* angle floor targets */
        const double *t = s->guard_sum + 3 * (size_t)v, g = w * s->guard_count[v];
        b0 += w * t[0], b1 += w * t[1], b2 += w * t[2];
        a00 += g, a11 += g, a22 += g;
    }
    av[0] = a00, av[1] = a01, av[2] = a11, av[3] = a02, av[4] = a12, av[5] = a22;
    bv[0] = b0, bv[1] = b1, bv[2] = b2;
}

/* One global step with vertex couplings: the stored (3 nv + nf) matrix. */
static facet_status stored_step(facet_planarizer *s, double mu, int nthreads, facet_error *error)
{
    const int32_t nv = s->nv, nf = s->nf;
    const double w = 1.0 - mu;
    double *x = s->matrix->x;
    const int *cp = s->matrix->p;
    const int *ri = s->matrix->i;
    double *b = s->rhs->x;
    const double *p = s->p;
    /* vertex columns: couplings, then the 3x3 block; right-hand side */
#pragma omp parallel for schedule(static) num_threads(nthreads)
    for (int32_t v = 0; v < nv; ++v) {
        double a[6], bv[3];
        vertex_terms(s, v, mu, a, bv);
        const int32_t nk = s->couple_start[v + 1] - s->couple_start[v];
        for (int c = 0; c < 3; ++c) {
            double *col = x + cp[3 * v + c];
            for (int32_t k = 0; k < nk; ++k) {
                const int32_t e2 = s->couple_start[v] + k;
                col[k] = mu * s->couple_mu[e2] + w * s->couple_con[e2];
            }
        }
        x[cp[3 * v] + nk] = a[0];
        x[cp[3 * v + 1] + nk] = a[1], x[cp[3 * v + 1] + nk + 1] = a[2];
        x[cp[3 * v + 2] + nk] = a[3], x[cp[3 * v + 2] + nk + 1] = a[4], x[cp[3 * v + 2] + nk + 2] = a[5];
        b[3 * v] = bv[0], b[3 * v + 1] = bv[1], b[3 * v + 2] = bv[2];
    }
    /* offset columns */
#pragma omp parallel for schedule(static) num_threads(nthreads)
    for (int32_t f = 0; f < nf; ++f) {
        const double *n = s->normal + 3 * (size_t)f;
        const double pw = w * face_weight(s, f);
        const int32_t b0 = s->face_start[f], b1 = s->face_start[f + 1];
        /* an exempt face's offset is decoupled: identity row */
        const double diag = pw > 0.0 ? pw * (double)(b1 - b0) : 1.0;
        const int32_t col = s->face_col[f];
        for (int32_t k = b0; k < b1; ++k) {
            const int32_t at = s->corner_slot[k];
            x[at] = pw * n[0], x[at + 1] = pw * n[1], x[at + 2] = pw * n[2];
        }
        x[cp[col + 1] - 1] = diag;
        b[col] = 0.0;
    }
    /* fixed vertices: identity rows, couplings moved to the right-hand side
     * (serial: a column's entries update other rows) */
    int any_fixed = 0;
    for (int32_t v = 0; v < nv && !any_fixed; ++v)
        any_fixed = s->fixed[v];
    if (any_fixed) {
        const int32_t n = 3 * nv + nf;
        for (int32_t c = 0; c < n; ++c) {
            const int fc = c < 3 * nv && s->fixed[c / 3];
            for (int k = cp[c]; k < cp[c + 1]; ++k) {
                const int r = ri[k];
                const int fr = r < 3 * nv && s->fixed[r / 3];
                if (r == c) {
                    if (fc)
                        x[k] = 1.0;
                } else if (fr && fc) {
                    x[k] = 0.0;
                } else if (fr) {
                    b[c] -= x[k] * p[r];
                    x[k] = 0.0;
                } else if (fc) {
                    b[r] -= x[k] * p[c];
                    x[k] = 0.0;
                }
            }
        }
        for (int32_t v = 0; v < nv; ++v)
            if (s->fixed[v])
                for (int a = 0; a < 3; ++a)
                    b[3 * v + a] = p[3 * (size_t)v + a];
    }
    /* Solve for the increment from the current iterate: A dx = b - A x. At
     * small mu the matrix's condition grows like 1/mu (a vertex may slide
     * along its planes almost freely), and the rounding error of a solve is
     * relative to what it solves for: the increment, which vanishes as the
     * iteration converges, rather than the positions. */
    double *cur = s->pcg_p->x; /* [q; d] of the iterate (the solve overwrites it) */
    memcpy(cur, s->q, sizeof(double) * 3 * (size_t)nv);
    for (int32_t f = 0; f < nf; ++f)
        cur[s->face_col[f]] = s->offset[f];
    sym_matvec(s->matrix, -1.0, 1, cur, b);
    /* Between the planes' steps only the normals turn (and mu stays within a
     * level of the schedule), so the last factorization stays a very good
     * preconditioner: conjugate gradients with it replace a refactorization
     * (each costs a sparse product and two triangular solves, against the
     * factorization's fill), and the factor is renewed when mu changed, when it
     * is FACTOR_AGE steps old, or when the iteration needed many steps. A shape
     * term couples every vertex of a face, and its factor is 6-16 times the
     * uncoupled offsets' system's (Level 5 with ASAP: 0.82M entries, a
     * factorization 58 ms, a conjugate gradient step 1.4 ms): such a costly
     * factor (factor_costly) serves whatever its age, until a solve needs more
     * than PCG_SLOW_COSTLY steps. On the 2,006-hex torus with surface data:
     * 16 factorizations in 243 steps instead of 37 (docs/solver-notes.md,
     * "L/G with coupled terms: a costly factor serves longer"). */
    const double *y = NULL;
    if (s->factor_ready && s->factor_mu == mu && (s->factor_costly || s->factor_age < FACTOR_AGE)) {
        const int steps = pcg_solve(s);
        if (steps > 0) {
            y = s->pcg_x->x;
            if (s->factor_costly)
                s->factor_ready = steps <= PCG_SLOW_COSTLY; /* else refactorize at the next step */
            else
                s->factor_age += steps > PCG_SLOW ? FACTOR_AGE : 1;
        }
    }
    if (!y) {
        {
            const double *ax = s->matrix->x;
            double *px = s->pmatrix->x;
            const size_t nnz = (size_t)cp[3 * (size_t)nv + (size_t)nf];
            for (size_t k = 0; k < nnz; ++k)
                px[k] = ax[s->pmap[k]];
        }
        const int factorized = cholmod_factorize(s->pmatrix, s->factor, &s->cm);
        if (!factorized || s->cm.status != CHOLMOD_OK) {
            s->factor_ready = 0;
            return facet_pl_fail(s, error, FACET_ERROR_NUMERICAL,
                                 "the sparse factorization failed (matrix not positive definite)");
        }
        s->factor_ready = 1, s->factor_mu = mu, s->factor_age = 0;
        s->factorizations++;
        if (!factor_solve(s, s->rhs->x, s->pcg_x->x))
            return facet_pl_fail(s, error, FACET_ERROR_NUMERICAL, "the sparse solve failed");
        y = s->pcg_x->x;
    }
    int finite = 1;
    for (size_t k = 0; k < 3 * (size_t)nv; ++k)
        if (!isfinite(y[k]))
            finite = 0;
    if (finite)
        for (size_t k = 0; k < 3 * (size_t)nv; ++k)
            s->q[k] += y[k];
    if (!finite)
        return facet_pl_fail(s, error, FACET_ERROR_NUMERICAL,
                             "the sparse solve gave a non-finite result");
    return FACET_OK;
}

typedef struct {
    facet_planarizer *s;
    double w;
} schur_system;

static double *schur_apply(void *ctx, const double *p)
{
    const schur_system *c = ctx;
    schur_product(c->s, c->w, p, c->s->schur_x->x);
    return c->s->schur_x->x;
}

/* (r is schur_b, which the factorization's solve reads) */
static double *schur_apply_precondition(void *ctx, const double *r)
{
    const schur_system *c = ctx;
    (void)r;
    return schur_precondition(c->s) ? c->s->schur_x->x : NULL;
}

/* Solves the offsets' system S x = g (g in schur_b, which becomes the
 * residual; schur_vec: the search direction and x) by conjugate gradients
 * preconditioned with the (older) factorization, to a residual
 * SCHUR_PCG_TOL of g's (pcg_run). Returns the steps taken, or 0 if it did
 * not get there (or failed; schur_rhs gives g again). schur_x takes S p and
 * then z = M^-1 r. */
static int schur_pcg(facet_planarizer *s, double w)
{
    const size_t nf = (size_t)s->nf;
    schur_system c = {s, w};
    const pcg_system sys = {schur_apply, schur_apply_precondition, &c};
    return pcg_run(&sys, nf, SCHUR_PCG_TOL, s->schur_vec + nf, s->schur_b->x, s->schur_vec);
}

/* The offsets' right-hand side g_f = r_f - sum over f's free corners of
 * c_f . u_v into schur_b, in schur's order (r_f: the offset's residual, a
 * held corner's terms moved to it). */
static void schur_rhs(facet_planarizer *s, double w, int nthreads)
{
    const int32_t nf = s->nf, base = 3 * s->nv;
    const double *p = s->p, *q = s->q, *u = s->schur_u, *offset = s->offset;
    double *g = s->schur_b->x;
#pragma omp parallel for schedule(static) num_threads(nthreads)
    for (int32_t f = 0; f < nf; ++f) {
        double c[3];
        face_coupling(s, f, w, c);
        double r = -face_diagonal(s, f, w) * offset[f];
        for (int32_t k = s->face_start[f]; k < s->face_start[f + 1]; ++k) {
            const size_t v = (size_t)s->face_vertices[k];
            if (s->fixed[v])
                r -= c[0] * p[3 * v] + c[1] * p[3 * v + 1] + c[2] * p[3 * v + 2];
            else
                r -= c[0] * (q[3 * v] + u[3 * v]) + c[1] * (q[3 * v + 1] + u[3 * v + 1]) +
                     c[2] * (q[3 * v + 2] + u[3 * v + 2]);
        }
        g[s->face_col[f] - base] = r;
    }
}

/* One global step without vertex couplings: the increment [dq; dd] from
 * the iterate [q; d] solves A [dq; dd] = b - A [q; d]. Per vertex, with
 * its block B_v (this step's LDL' into block) and residual r_v: u_v =
 * B_v^-1 r_v; per face, the offsets' right-hand side g_f = r_f - sum over
 * its free corners of c_f . u_v; S dd = g; then dq_v = u_v - B_v^-1 sum
 * over its faces of c_f dd_f. A held vertex has an identity row (dq = p -
 * q) and no coupling: its corners' terms move to its faces' right-hand
 * side. The offsets themselves are not updated (the planes' step refits
 * them). */
static facet_status schur_step(facet_planarizer *s, double mu, int nthreads, facet_error *error)
{
    const int32_t nv = s->nv, nf = s->nf;
    const double w = 1.0 - mu;
    const double *p = s->p, *offset = s->offset;
    double *q = s->q, *u = s->schur_u;
    int bad = 0;
#pragma omp parallel for schedule(static) num_threads(nthreads) reduction(| : bad)
    for (int32_t v = 0; v < nv; ++v) {
        double *bl = s->block + 6 * (size_t)v, *uv = u + 3 * (size_t)v;
        const double *qv = q + 3 * (size_t)v;
        if (s->fixed[v]) {
            bl[0] = bl[1] = bl[2] = 0.0, bl[3] = bl[4] = bl[5] = 1.0;
            uv[0] = p[3 * (size_t)v] - qv[0], uv[1] = p[3 * (size_t)v + 1] - qv[1];
            uv[2] = p[3 * (size_t)v + 2] - qv[2];
            continue;
        }
        double a[6], b[3], c[3];
        vertex_terms(s, v, mu, a, b);
        if (!block_ldl(a, bl)) {
            bad = 1;
            continue;
        }
        double r[3] = {b[0] - (a[0] * qv[0] + a[1] * qv[1] + a[3] * qv[2]),
                       b[1] - (a[1] * qv[0] + a[2] * qv[1] + a[4] * qv[2]),
                       b[2] - (a[3] * qv[0] + a[4] * qv[1] + a[5] * qv[2])};
        for (int32_t i = s->vertex_start[v]; i < s->vertex_start[v + 1]; ++i) {
            const int32_t f = s->vertex_faces[i];
            face_coupling(s, f, w, c);
            r[0] -= c[0] * offset[f], r[1] -= c[1] * offset[f], r[2] -= c[2] * offset[f];
        }
        block_solve(bl, r, uv);
    }
    if (bad) {
        s->factor_ready = 0;
        return facet_pl_fail(s, error, FACET_ERROR_NUMERICAL,
                             "the sparse factorization failed (matrix not positive definite)");
    }
    schur_rhs(s, w, nthreads);
    /* the offsets' increment: conjugate gradients with the last
     * factorization while it serves (global_step), else refactorized */
    const double *dd = NULL;
    if (s->factor_ready && s->factor_mu == mu && s->factor_age < FACTOR_AGE) {
        const int steps = schur_pcg(s, w);
        if (steps > 0) {
            s->factor_age += steps > PCG_SLOW ? FACTOR_AGE : 1;
            dd = s->schur_vec + (size_t)nf;
        } else {
            schur_rhs(s, w, nthreads); /* g again */
        }
    }
    if (!dd) {
        schur_assemble(s, w);
        if (!cholmod_factorize(s->schur, s->factor, &s->cm) || s->cm.status != CHOLMOD_OK) {
            s->factor_ready = 0;
            return facet_pl_fail(s, error, FACET_ERROR_NUMERICAL,
                                 "the sparse factorization failed (matrix not positive definite)");
        }
        s->factor_ready = 1, s->factor_mu = mu, s->factor_age = 0;
        s->factorizations++;
        if (!schur_precondition(s))
            return facet_pl_fail(s, error, FACET_ERROR_NUMERICAL, "the sparse solve failed");
        dd = s->schur_x->x;
    }
    int finite = 1;
#pragma omp parallel for schedule(static) num_threads(nthreads) reduction(& : finite)
    for (int32_t v = 0; v < nv; ++v) {
        double *uv = u + 3 * (size_t)v;
        if (!s->fixed[v]) {
            double t[3];
            coupled_solve(s, v, w, dd, t);
            uv[0] -= t[0], uv[1] -= t[1], uv[2] -= t[2];
        }
        finite &= isfinite(uv[0]) && isfinite(uv[1]) && isfinite(uv[2]);
    }
    if (!finite)
        return facet_pl_fail(s, error, FACET_ERROR_NUMERICAL,
                             "the sparse solve gave a non-finite result");
#pragma omp parallel for schedule(static) num_threads(nthreads)
    for (int32_t k = 0; k < 3 * nv; ++k)
        q[k] += u[k];
    return FACET_OK;
}

facet_status facet_pl_global_step(facet_planarizer *s, double mu, int nthreads, facet_error *error)
{
    return s->matrix ? stored_step(s, mu, nthreads, error) : schur_step(s, mu, nthreads, error);
}
