/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Optimal liftings of plan drawings (paper section 6.1).
 *
 * Unknowns: one height z_v per plan vertex. Face f with k corners is planar
 * when its heights lie in span(1, x, y) over its corners, i.e. when they are
 * orthogonal to the k-3 dimensional complement of that span. Those
 * complements, one orthonormal set per face (Householder QR of the k x 3
 * matrix [1 x y] on the face's own centred and scaled corners), are the rows
 * of the constraint matrix C (m x n, m = sum (k_f - 3)); the lifting space is
 * null(C).
 *
 * With W = diag(w) the weights, the optimal lifting of targets t is the
 * W-orthogonal projection of t onto null(C). Put A = W^-1/2 C' (n x m) and
 * factorize A P = Q R with SuiteSparseQR's rank-revealing sparse QR, rank r.
 * Q = [Q1 Q2] with Q1 (n x r) spanning range(A) = W^-1/2 range(C'), so Q2
 * (n x (n-r)) is an orthonormal basis of W^1/2 null(C) and
 *
 *     z = W^-1/2 Q2 Q2' W^1/2 t.
 *
 * The factorization stays in the handle. A solve applies the projector
 * with R alone (corrected semi-normal equations, see remove_range), which
 * is far cheaper than applying the Householder Q: at 10k vertices a
 * fundamental lifting takes under a millisecond. The bases use Q itself
 * (they need Q2 explicitly). The affine part of t (its W-projection onto span(1, x,
 * y), which is always a lifting) is taken out first and added back exactly,
 * so the projection works on the small remainder (georeferenced heights in
 * the hundreds of metres lose nothing), and z = a + W^-1/2 Q2 (Q2' s) lies
 * in the lifting space to rounding of the remainder alone.
 *
 * dim null(C) = n - r >= 3. */
#include "internal.h"

/* Smallest weight accepted, relative to the largest: below it the
 * normalised weight's square root leaves the range of useful doubles. */
#define FACET_LIFT_WEIGHT_RATIO 1e-100

#include <SuiteSparseQR_C.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* BLAS and LAPACK (Fortran interface). */
extern void dgemm_(const char *transa, const char *transb, const int *m, const int *n,
                   const int *k, const double *alpha, const double *a, const int *lda,
                   const double *b, const int *ldb, const double *beta, double *c,
                   const int *ldc);
extern void dgesvd_(const char *jobu, const char *jobvt, const int *m, const int *n, double *a,
                    const int *lda, double *s, double *u, const int *ldu, double *vt,
                    const int *ldvt, double *work, const int *lwork, int *info);
extern void dsyevr_(const char *jobz, const char *range, const char *uplo, const int *n, double *a,
                    const int *lda, const double *vl, const double *vu, const int *il,
                    const int *iu, const double *abstol, int *m, double *w, double *z,
                    const int *ldz, int *isuppz, double *work, const int *lwork, int *iwork,
                    const int *liwork, int *info);

/* OpenBLAS's process-wide thread control, when the BLAS linked in is OpenBLAS (weak: NULL
 * otherwise). SPQR's dense fronts and Householder applications go through BLAS, whose
 * multi-threaded kernels round differently for different thread counts; the lifter runs
 * them single-threaded and restores the setting, so its results are the same bits for any
 * OMP_NUM_THREADS or OPENBLAS_NUM_THREADS (tests/python/test_lift_determinism.py). */
extern void openblas_set_num_threads(int n) __attribute__((weak));
extern int openblas_get_num_threads(void) __attribute__((weak));

static int blas_serial_begin(void)
{
    if (!openblas_set_num_threads || !openblas_get_num_threads)
        return 0;
    int previous = openblas_get_num_threads();
    if (previous > 1)
        openblas_set_num_threads(1);
    return previous;
}

static void blas_serial_end(int previous)
{
    if (previous > 1 && openblas_set_num_threads)
        openblas_set_num_threads(previous);
}

#define EIGEN_MAX_DIMENSION 2000
#define EIGEN_MAX_ENTRIES 20000000.0
/* A face whose corners span less than this (relative) in plan is refused. */
#define PLAN_DEGENERATE_REL 1e-8
#define PLANARITY_TOL_REL 1e-9
/* Size of a refinement step of the corrected semi-normal equations,
 * relative to the vector projected, below which they count as converged. */
#define CSNE_TOL 1e-14
/* Default rank tolerance on the (unit-norm, weight-scaled) constraint
 * columns: a constraint dependent on the others to within this is treated as
 * dependent. Violating it by that much keeps every face planar to about
 * 1e-10 of the plan's size, inside the 1e-9 promise; enforcing it instead
 * would make the lifting space hinge on rounding of the drawing. */
#define RANK_TOL_DEFAULT 1e-10
/* See facet_lifter.rank_check. */
#define RANK_CHECK_TOL 1e-6

struct facet_lifter {
    int32_t nv, nf, nc, m, rank, dim, max_degree;
    int32_t *face_start, *face_vertices;
    double *plan_xy;     /* model units, 2*nv */
    double *sqw;         /* sqrt of the weights normalised to mean 1 */
    double *trivial;     /* 3*nv: W-orthonormal basis of span(1, x, y) */
    int32_t ne;
    int32_t *edges;      /* 2*ne, unique undirected edges */
    double *work, *work2, *save, *xyz; /* nv, nv, nv, 3*nv */
    int cm_started;
    cholmod_common cm;
    SuiteSparseQR_C_factorization *qr; /* NULL when m == 0 (Q = I) */
    cholmod_sparse *a;                 /* A = W^-1/2 C', n x m */
    cholmod_dense *rhs_m;              /* m x 1 workspace */
    /* Directions of range(Q1) that A's columns do not reach (hidden dependencies, see
     * find_hidden): nv x n_hidden, orthonormal; they belong to the lifting space. */
    double *hidden;
    int32_t n_hidden;
    /* How far the projection onto the lifting space moves the affine liftings, which are
     * in it exactly (relative): above RANK_CHECK_TOL, the constraints' rank was
     * overestimated by more than the hidden directions make up for. */
    double rank_check;
    double factor_seconds;
    char message[512];
};

static facet_status lifter_fail(facet_lifter *s, facet_error *error, facet_status status,
                                int64_t face, int64_t vertex, const char *format, ...)
    FACET_PRINTF(6, 7);

static facet_status lifter_fail(facet_lifter *s, facet_error *error, facet_status status,
                                int64_t face, int64_t vertex, const char *format, ...)
{
    char text[512];
    va_list ap;
    va_start(ap, format);
    vsnprintf(text, sizeof text, format, ap);
    va_end(ap);
    if (s)
        snprintf(s->message, sizeof s->message, "%s", text);
    return facet_fail(error, status, face, vertex, "%s", text);
}

void facet_lifter_free(facet_lifter **handle)
{
    if (!handle || !*handle)
        return;
    facet_lifter *s = *handle;
    if (s->cm_started) {
        if (s->qr)
            SuiteSparseQR_C_free(&s->qr, &s->cm);
        cholmod_l_free_sparse(&s->a, &s->cm);
        cholmod_l_free_dense(&s->rhs_m, &s->cm);
        cholmod_l_finish(&s->cm);
    }
    free(s->face_start);
    free(s->face_vertices);
    free(s->plan_xy);
    free(s->sqw);
    free(s->trivial);
    free(s->edges);
    free(s->work);
    free(s->save);
    free(s->work2);
    free(s->xyz);
    free(s->hidden);
    free(s);
    *handle = NULL;
}

/* Householder QR of the k x 3 column-major matrix a (overwritten by the
 * reflectors: column j holds v_j from row j on); beta[3], diag[3] = R_jj. */
static void householder3(int32_t k, double *a, double beta[3], double diag[3])
{
    for (int j = 0; j < 3; ++j) {
        double *col = a + (size_t)j * k;
        double norm = 0.0;
        for (int32_t i = j; i < k; ++i)
            norm += col[i] * col[i];
        norm = sqrt(norm);
        if (norm == 0.0) {
            beta[j] = 0.0;
            diag[j] = 0.0;
            continue;
        }
        double alpha = col[j] >= 0.0 ? -norm : norm;
        col[j] -= alpha;
        double vv = 0.0;
        for (int32_t i = j; i < k; ++i)
            vv += col[i] * col[i];
        beta[j] = 2.0 / vv;
        diag[j] = alpha;
        for (int c = j + 1; c < 3; ++c) {
            double *other = a + (size_t)c * k;
            double dot = 0.0;
            for (int32_t i = j; i < k; ++i)
                dot += col[i] * other[i];
            dot *= beta[j];
            for (int32_t i = j; i < k; ++i)
                other[i] -= dot * col[i];
        }
    }
}

/* x <- H_0 H_1 H_2 x (Q times x) for the reflectors of householder3. */
static void householder3_apply(int32_t k, const double *a, const double beta[3], double *x)
{
    for (int j = 2; j >= 0; --j) {
        if (beta[j] == 0.0)
            continue;
        const double *col = a + (size_t)j * k;
        double dot = 0.0;
        for (int32_t i = j; i < k; ++i)
            dot += col[i] * x[i];
        dot *= beta[j];
        for (int32_t i = j; i < k; ++i)
            x[i] -= dot * col[i];
    }
}

/* The basis of a face's affine height functions, [1, x, y] at its k corners
 * (centred on the corners' centroid and scaled by their RMS radius), in
 * h[3k] column-major, factorised in place by householder3: the constraint
 * rows of the face and its planarity measure both come from this QR. */
static void face_basis(const facet_lifter *s, const int32_t *idx, int32_t k, double *h,
                       double beta[3], double diag[3])
{
    double mx = 0.0, my = 0.0;
    for (int32_t i = 0; i < k; ++i) {
        mx += s->plan_xy[2 * idx[i]];
        my += s->plan_xy[2 * idx[i] + 1];
    }
    mx /= k, my /= k;
    double r2 = 0.0;
    for (int32_t i = 0; i < k; ++i) {
        double dx = s->plan_xy[2 * idx[i]] - mx, dy = s->plan_xy[2 * idx[i] + 1] - my;
        r2 += dx * dx + dy * dy;
    }
    double r = sqrt(r2 / k);
    for (int32_t i = 0; i < k; ++i) {
        h[i] = 1.0;
        h[k + i] = r > 0 ? (s->plan_xy[2 * idx[i]] - mx) / r : 0.0;
        h[2 * k + i] = r > 0 ? (s->plan_xy[2 * idx[i] + 1] - my) / r : 0.0;
    }
    householder3(k, h, beta, diag);
}

static int compare_edge(const void *pa, const void *pb)
{
    const int32_t *a = pa, *b = pb;
    if (a[0] != b[0])
        return a[0] < b[0] ? -1 : 1;
    if (a[1] != b[1])
        return a[1] < b[1] ? -1 : 1;
    return 0;
}

/* Y = Q' X (transpose != 0) or Q X for an n x k column-major X; Q = I when
 * there is no factorization. Returns 0 on failure. */
static int apply_q(facet_lifter *s, int transpose, int32_t k, double *x)
{
    if (!s->qr)
        return 1;
    cholmod_dense *in = cholmod_l_allocate_dense((size_t)s->nv, (size_t)k, (size_t)s->nv,
                                                 CHOLMOD_REAL, &s->cm);
    if (!in)
        return 0;
    memcpy(in->x, x, sizeof(double) * (size_t)s->nv * (size_t)k);
    cholmod_dense *out = SuiteSparseQR_C_qmult(transpose ? SPQR_QTX : SPQR_QX, s->qr, in, &s->cm);
    cholmod_l_free_dense(&in, &s->cm);
    if (!out)
        return 0;
    const double *ox = out->x;
    for (int32_t c = 0; c < k; ++c)
        memcpy(x + (size_t)c * s->nv, ox + (size_t)c * out->d, sizeof(double) * (size_t)s->nv);
    cholmod_l_free_dense(&out, &s->cm);
    return 1;
}

/* out[m] = A' u (u: nv values). */
static void a_transpose_times(const facet_lifter *s, const double *u, double *out)
{
    const int64_t *ap = s->a->p, *ai = s->a->i;
    const double *ax = s->a->x;
    for (int32_t j = 0; j < s->m; ++j) {
        double dot = 0.0;
        for (int64_t k = ap[j]; k < ap[j + 1]; ++k)
            dot += ax[k] * u[ai[k]];
        out[j] = dot;
    }
}

/* SPQR's rank detection (Heath's method: a column whose part outside the span of
 * the columns before it is within the tolerance is dead) can keep columns that
 * depend on the others, sets that only together are dependent, the last of
 * which meets a residual above the tolerance once rounding has grown through
 * the earlier steps. Voronoi-like plans (three faces at a vertex) show it from
 * a few hundred faces: the paraboloid's lifting and the boundary's freedoms
 * were lost, the dimension came out short of a dense SVD's count (even below
 * the 3 affine liftings) and the result was the best plane. Each such column
 * adds to range(Q1) a direction that no column of A reaches: a lifting.
 *
 * They are found without a rank decision: with N = A A' + delta I (CHOLMOD),
 * u <- delta N^-1 u keeps what A' sends to zero and shrinks a part that A'
 * reaches with singular value sigma by delta / (sigma^2 + delta) each step.
 * Random vectors of range(Q1) (Q times random leading coordinates) through a
 * few steps therefore span exactly those lost directions (the hidden ones),
 * with what is left of the rest far below; an SVD of the block tells the two
 * apart, and the block doubles while every vector in it is hidden. Where the
 * block can grow no more (HIDDEN_BLOCK_MAX, or its memory) and is still all
 * hidden, further blocks of that size are made orthogonal to the directions
 * found (deflated) and add theirs, until one is not all hidden: a 300,000-site
 * Voronoi plan (597,976 vertices) has more than the 32 its block could hold,
 * and the search had stopped there, the paraboloid's lifting coming back 3.4
 * times its range away (FACET_WARNING_LIFTING_RANK). Each is
 * kept only where A' sends it within the rank tolerance of zero. Run only
 * where SPQR found some constraints dependent (m > rank): where it kept them
 * all, there were no dependencies to misjudge; and not with a loose rank
 * tolerance (above HIDDEN_TOL_MAX), which the caller chose SPQR's way.
 * Returns 0 when out of memory. */
#define HIDDEN_BLOCK_FIRST 8
#define HIDDEN_BLOCK_MAX 512
#define HIDDEN_STEPS 6
/* delta, relative to the largest diagonal entry of A A'. */
#define HIDDEN_DELTA 1e-12
/* A singular value of the block below this, relative to the largest, is what the
 * steps left of a reached direction. */
#define HIDDEN_GAP 1e-4
/* Above this rank tolerance (a loose one, asked for) SPQR's decision stands. */
#define HIDDEN_TOL_MAX 1e-6

/* The largest block of the search, in entries (nv times its vectors: 160 MB). */
#define HIDDEN_BLOCK_ENTRIES 2e7
/* Above this many entries (nv times the count) the hidden directions found stop the
 * deflated search (480 MB); the rank check then warns. */
#define HIDDEN_TOTAL_MAX 6e7

/* col[nv x k] less its parts along the orthonormal h[nv x nh], twice (classical
 * Gram-Schmidt, repeated for rounding). Returns 0 when out of memory. */
static int deflate(double *col, int32_t nv, int32_t k, const double *h, int32_t nh)
{
    double *c = malloc(sizeof(double) * (size_t)nh * (size_t)k);
    if (!c)
        return 0;
    const int n = nv, kk = k, hh = nh;
    const double one = 1.0, zero = 0.0, minus = -1.0;
    for (int pass = 0; pass < 2; ++pass) {
        dgemm_("T", "N", &hh, &kk, &n, &one, h, &n, col, &n, &zero, c, &hh);
        dgemm_("N", "N", &n, &kk, &hh, &minus, h, &n, c, &hh, &one, col, &n);
    }
    free(c);
    return 1;
}

/* The candidates u[nv x p] (orthonormal) span directions that A' sends near zero, but a
 * near-dependency of the constraints (a singular value of A just above the rank
 * tolerance: on a Voronoi plan, a short edge that the snap collapsed into a vertex of
 * four faces) shrinks as slowly as the hidden directions and mixes into every one of
 * them. Then the directions of their span that A' sends within `reach` are taken: the
 * eigenvectors of G = (A'U)'(A'U) whose eigenvalue is at most reach^2, as U times
 * them, written over u; returns how many, `leading` (the leading candidates A' sends
 * within reach, u unchanged) when LAPACK fails, -1 when out of memory. G is summed from
 * A'U in chunks of rows (A'U itself is m x p). */
static int32_t within_reach(facet_lifter *s, double *u, int32_t p, double reach,
                            int32_t leading)
{
    const int32_t nv = s->nv, m = s->m, rows = 256;
    const int64_t *ap = s->a->p, *ai = s->a->i;
    const double *ax = s->a->x;
    double *g = calloc((size_t)p * (size_t)p, sizeof(double));
    double *chunk = malloc(sizeof(double) * (size_t)rows * (size_t)p);
    double *evals = malloc(sizeof(double) * (size_t)p);
    double *evecs = malloc(sizeof(double) * (size_t)p * (size_t)p);
    int *isuppz = malloc(sizeof(int) * 2 * (size_t)p);
    double *kept = malloc(sizeof(double) * (size_t)nv * (size_t)p);
    double *work = NULL;
    int *iwork = NULL;
    int32_t found = -1;
    if (!g || !chunk || !evals || !evecs || !isuppz || !kept)
        goto done;
    const int pp = p, rr = rows;
    const double one = 1.0, zero = 0.0;
    for (int32_t c0 = 0; c0 < m; c0 += rows) {
        const int32_t r = m - c0 < rows ? m - c0 : rows;
        const int ri = r;
        for (int32_t i = 0; i < r; ++i)
            for (int32_t j = 0; j < p; ++j) {
                double dot = 0.0;
                const double *uj = u + (size_t)j * nv;
                for (int64_t k = ap[c0 + i]; k < ap[c0 + i + 1]; ++k)
                    dot += ax[k] * uj[ai[k]];
                chunk[(size_t)j * rows + i] = dot;
            }
        dgemm_("T", "N", &pp, &pp, &ri, &one, chunk, &rr, chunk, &rr, &one, g, &pp);
    }
    int n_found = 0, info = 0, lwork = -1, liwork = -1, iwork_query = 0, il = 1, iu = p;
    double work_query = 0.0, vl = 0.0, vu = 0.0, abstol = 0.0;
    dsyevr_("V", "A", "U", &pp, g, &pp, &vl, &vu, &il, &iu, &abstol, &n_found, evals, evecs,
            &pp, isuppz, &work_query, &lwork, &iwork_query, &liwork, &info);
    if (info != 0) {
        found = leading;
        goto done;
    }
    lwork = (int)work_query;
    liwork = iwork_query;
    work = malloc(sizeof(double) * (size_t)(lwork > 1 ? lwork : 1));
    iwork = malloc(sizeof(int) * (size_t)(liwork > 1 ? liwork : 1));
    if (!work || !iwork)
        goto done;
    dsyevr_("V", "A", "U", &pp, g, &pp, &vl, &vu, &il, &iu, &abstol, &n_found, evals, evecs,
            &pp, isuppz, work, &lwork, iwork, &liwork, &info);
    if (info != 0 || n_found != p) {
        found = leading;
        goto done;
    }
    /* ascending: the first ones are the hidden directions */
    found = 0;
    while (found < p && evals[found] <= reach * reach)
        ++found;
    if (found > 0) {
        const int nn = nv, q = found;
        dgemm_("N", "N", &nn, &q, &pp, &one, u, &nn, evecs, &pp, &zero, kept, &nn);
        memcpy(u, kept, sizeof(double) * (size_t)nv * (size_t)found);
    }
done:
    free(g), free(chunk), free(evals), free(evecs), free(isuppz), free(kept);
    free(work), free(iwork);
    return found;
}

/* The hidden directions among k random vectors of range(Q1): they replace
 * s->hidden, or with `more` (the deflated search) the vectors are first made
 * orthogonal to s->hidden and add to it. Returns how many (k: perhaps more), or -1 on
 * failure; `candidates`: how many of the block shrank as slowly as hidden directions (k:
 * perhaps more of them, hidden or near-dependencies, than the block holds). */
static int32_t hidden_block(facet_lifter *s, cholmod_factor *factor, double delta, int32_t k,
                            double reach, int more, int32_t *candidates)
{
    const int32_t nv = s->nv;
    cholmod_dense *u = cholmod_l_allocate_dense((size_t)nv, (size_t)k, (size_t)nv, CHOLMOD_REAL,
                                                &s->cm);
    double *sv = malloc(sizeof(double) * (size_t)k);
    double *left = malloc(sizeof(double) * (size_t)nv * (size_t)k);
    if (!u || !sv || !left) {
        cholmod_l_free_dense(&u, &s->cm);
        free(sv), free(left);
        return -1;
    }
    double *x = u->x;
    /* the same start every time; another for each deflated block */
    uint64_t state = 0x9E3779B97F4A7C15ull + (more ? (uint64_t)s->n_hidden : 0u);
    for (int32_t j = 0; j < k; ++j)
        for (int32_t v = 0; v < nv; ++v) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            x[(size_t)j * nv + v] = v < s->rank ? (double)(state >> 11) * 0x1p-53 - 0.5 : 0.0;
        }
    int32_t found = -1;
    *candidates = 0;
    cholmod_dense *q = SuiteSparseQR_C_qmult(SPQR_QX, s->qr, u, &s->cm);
    for (int step = 0; q && step < HIDDEN_STEPS; ++step) {
        cholmod_dense *next = cholmod_l_solve(CHOLMOD_A, factor, q, &s->cm);
        cholmod_l_free_dense(&q, &s->cm);
        q = next;
        if (q) {
            double *qx = q->x;
            for (size_t i = 0; i < (size_t)nv * (size_t)k; ++i)
                qx[i] *= delta;
        }
    }
    if (q) {
        /* back into range(Q1): the solves' rounding leaves parts along Q2 (also reached
         * by no column), which the projection counts already */
        cholmod_dense *c = SuiteSparseQR_C_qmult(SPQR_QTX, s->qr, q, &s->cm);
        cholmod_l_free_dense(&q, &s->cm);
        if (c)
            for (int32_t j = 0; j < k; ++j)
                memset((double *)c->x + (size_t)j * c->d + s->rank, 0,
                       sizeof(double) * (size_t)(nv - s->rank));
        q = c ? SuiteSparseQR_C_qmult(SPQR_QX, s->qr, c, &s->cm) : NULL;
        cholmod_l_free_dense(&c, &s->cm);
    }
    if (q) {
        for (int32_t j = 0; j < k; ++j)
            memcpy(x + (size_t)j * nv, (const double *)q->x + (size_t)j * q->d,
                   sizeof(double) * (size_t)nv);
        if (more && !deflate(x, nv, k, s->hidden, s->n_hidden))
            cholmod_l_free_dense(&q, &s->cm);
    }
    if (q) {
        int mm = nv, kk = k, lwork = -1, info = 0, one = 1;
        double query = 0.0, vt = 0.0;
        dgesvd_("S", "N", &mm, &kk, x, &mm, sv, left, &mm, &vt, &one, &query, &lwork, &info);
        lwork = (int)query;
        double *work = info == 0 ? malloc(sizeof(double) * (size_t)(lwork > 1 ? lwork : 1))
                                 : NULL;
        if (work) {
            dgesvd_("S", "N", &mm, &kk, x, &mm, sv, left, &mm, &vt, &one, work, &lwork, &info);
            free(work);
            /* kept: the left singular vectors above the gap that A' sends within `reach`
             * of zero (a part that A' reaches weakly shrinks slowly: below the rank
             * tolerance it is a dependency, above it a constraint) */
            found = 0;
            int32_t above = 0; /* the candidates: above the gap */
            while (info == 0 && sv[0] > 0.0 && above < k && isfinite(sv[above]) &&
                   sv[above] > HIDDEN_GAP * sv[0])
                ++above;
            *candidates = above;
            for (int32_t j = 0; j < above; ++j) {
                double *reached = s->rhs_m->x, sum = 0.0;
                a_transpose_times(s, left + (size_t)j * nv, reached);
                for (int32_t c = 0; c < s->m; ++c)
                    sum += reached[c] * reached[c];
                if (!(sqrt(sum) <= reach))
                    break;
                ++found;
            }
            /* one that A' reaches: the span's hidden directions instead (a near-dependency
             * mixed into them had hidden every one after it: a 1,000-site Voronoi plan
             * with one short edge snapped lost the affine liftings: dimension 3, 6 by SVD) */
            if (found < above)
                found = within_reach(s, left, above, reach, found);
        }
    }
    cholmod_l_free_dense(&q, &s->cm);
    cholmod_l_free_dense(&u, &s->cm);
    if (found > 0) {
        const int32_t base = more ? s->n_hidden : 0;
        double *h = realloc(s->hidden, sizeof(double) * (size_t)nv * (size_t)(base + found));
        if (h) {
            s->hidden = h;
            memcpy(h + (size_t)nv * (size_t)base, left, sizeof(double) * (size_t)nv * (size_t)found);
            s->n_hidden = base + found;
        } else {
            found = -1;
        }
    }
    free(sv), free(left);
    return found;
}

static int check_rank(facet_lifter *s);

/* The create step's progress, stage `done` of 3 ended (facet_lift_options): nonzero when
 * the caller cancels. */
static int create_progress(const facet_lift_options *o, int64_t done)
{
    return o && o->progress && o->progress(o->progress_user, done, 3) != 0;
}

/* 1, 0 when out of memory, -1 when cancelled (between blocks). */
static int find_hidden(facet_lifter *s, double tol, const facet_lift_options *options)
{
    if (s->m <= s->rank || tol > HIDDEN_TOL_MAX)
        return 1;
    cholmod_factor *factor = cholmod_l_analyze(s->a, &s->cm); /* of A A' */
    double largest = 0.0; /* of A A''s diagonal */
    double reach = 0.0;   /* tol times A's largest column norm */
    {
        const int64_t *ap = s->a->p, *ai = s->a->i;
        const double *ax = s->a->x;
        double *diag = s->work;
        memset(diag, 0, sizeof(double) * (size_t)s->nv);
        for (int32_t j = 0; j < s->m; ++j) {
            double sum = 0.0;
            for (int64_t p = ap[j]; p < ap[j + 1]; ++p) {
                diag[ai[p]] += ax[p] * ax[p];
                sum += ax[p] * ax[p];
            }
            reach = fmax(reach, sqrt(sum));
        }
        for (int32_t v = 0; v < s->nv; ++v)
            largest = fmax(largest, diag[v]);
        reach *= tol;
    }
    const double delta = HIDDEN_DELTA * (largest > 0.0 ? largest : 1.0);
    double beta[2] = {delta, 0.0};
    int ok = factor && cholmod_l_factorize_p(s->a, beta, NULL, 0, factor, &s->cm) &&
             s->cm.status == CHOLMOD_OK;
    if (!ok && s->cm.status != CHOLMOD_OUT_OF_MEMORY) {
        /* (not positive definite to rounding: no search; check_rank still looks) */
        cholmod_l_free_factor(&factor, &s->cm);
        return 1;
    }
    const double nv = (double)s->nv;
    /* FACET_LIFT_HIDDEN_BLOCK_MAX (a diagnostic: tests/python/test_lift.py) lowers the
     * largest block, so that the deflated search is taken on plans of test size */
    int32_t block_max = HIDDEN_BLOCK_MAX;
    const char *given = getenv("FACET_LIFT_HIDDEN_BLOCK_MAX");
    if (given && atoi(given) > 0 && atoi(given) < block_max)
        block_max = atoi(given);
    int more = 0; /* the blocks are deflated */
    for (int32_t k = HIDDEN_BLOCK_FIRST, block = 0; ok; ++block) {
        if (block > 0 && create_progress(options, 1)) {
            ok = -1; /* (a 300,000-site Voronoi plan searches for a minute) */
            break;
        }
        const int32_t left = more ? s->rank - s->n_hidden : s->rank;
        if (k > block_max)
            k = block_max;
        if (k > left)
            k = left;
        if (k <= 0 || (double)k * nv > HIDDEN_BLOCK_ENTRIES)
            break;
        int32_t candidates = 0;
        int32_t found = hidden_block(s, factor, delta, k, reach, more, &candidates);
        ok = found >= 0 ? 1 : 0;
        /* reached past them; or a deflated block of near-dependencies alone */
        if (candidates < k || k >= left || (more && found == 0))
            break;
        if (!more && 2 * k <= block_max && 2.0 * k * nv <= HIDDEN_BLOCK_ENTRIES)
            k *= 2;
        else if ((double)(s->n_hidden + k) * nv <= HIDDEN_TOTAL_MAX)
            more = 1; /* blocks of this size, orthogonal to the directions found */
        else
            break;
    }
    cholmod_l_free_factor(&factor, &s->cm);
    return ok;
}

facet_status facet_lifter_create(const facet_mesh *plan, const double *weights,
                                 const facet_lift_options *options, facet_lifter **out,
                                 facet_error *error)
{
    facet_error_clear(error);
    if (!out)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1, "out is NULL");
    *out = NULL;
    facet_mesh_report report;
    facet_status status = facet_mesh_validate_topology(plan, 0, &report, error);
    if (status < 0)
        return status;
    facet_error_clear(error);
    const int32_t nv = plan->n_vertices, nf = plan->n_faces, nc = plan->face_start[nf];
    if (!plan->xyz)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1, "plan xyz is NULL");
    for (int32_t v = 0; v < nv; ++v)
        if (!isfinite(plan->xyz[3 * v]) || !isfinite(plan->xyz[3 * v + 1]))
            return facet_fail(error, FACET_ERROR_NONFINITE, -1, v,
                              "plan vertex %d has a NaN or infinite x or y", (int)v);
    for (int32_t v = 0; v < nv; ++v)
        if (!facet_point_in_range(plan->xyz + 3 * v, 2))
            return facet_fail(error, FACET_ERROR_COORDINATE_RANGE, -1, v,
                              "plan vertex %d has x or y beyond 1e30 in magnitude (%g, %g)",
                              (int)v, plan->xyz[3 * v], plan->xyz[3 * v + 1]);
    if (weights)
        for (int32_t v = 0; v < nv; ++v)
            if (!(weights[v] > 0.0) || !isfinite(weights[v]))
                return facet_fail(error, FACET_ERROR_BAD_WEIGHT, -1, v,
                                  "weight of vertex %d is %g: weights must be finite and > 0",
                                  (int)v, weights[v]);
    if (weights) {
        double wmax = 0.0;
        for (int32_t v = 0; v < nv; ++v)
            wmax = fmax(wmax, weights[v]);
        for (int32_t v = 0; v < nv; ++v)
            if (weights[v] < FACET_LIFT_WEIGHT_RATIO * wmax)
                return facet_fail(error, FACET_ERROR_BAD_WEIGHT, -1, v,
                                  "weight of vertex %d is %g, less than 1e-100 of the largest "
                                  "weight (%g)", (int)v, weights[v], wmax);
    }
    if ((int64_t)nc > INT32_MAX / 4)
        return facet_fail(error, FACET_ERROR_TOO_LARGE, -1, -1, "plan too large: %d corners",
                          (int)nc);
    double t0 = facet_now();
    facet_lifter *s = calloc(1, sizeof *s);
    if (!s)
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    s->nv = nv, s->nf = nf, s->nc = nc;
    s->face_start = malloc(sizeof(int32_t) * (size_t)(nf + 1));
    s->face_vertices = malloc(sizeof(int32_t) * (size_t)nc);
    s->plan_xy = malloc(sizeof(double) * 2 * (size_t)nv);
    s->sqw = malloc(sizeof(double) * (size_t)nv);
    s->trivial = malloc(sizeof(double) * 3 * (size_t)nv);
    s->edges = malloc(sizeof(int32_t) * 2 * (size_t)nc);
    s->work = malloc(sizeof(double) * (size_t)nv);
    s->save = malloc(sizeof(double) * (size_t)nv);
    s->work2 = malloc(sizeof(double) * (size_t)nv);
    s->xyz = malloc(sizeof(double) * 3 * (size_t)nv);
    int32_t kmax = report.max_degree;
    s->max_degree = kmax;
    double *scratch = malloc(sizeof(double) * (size_t)kmax * 5);
    int64_t *order = malloc(sizeof(int64_t) * (size_t)kmax);
    if (!s->face_start || !s->face_vertices || !s->plan_xy || !s->sqw || !s->trivial ||
        !s->edges || !s->work || !s->work2 || !s->save || !s->xyz || !scratch || !order) {
        free(scratch);
        free(order);
        facet_lifter_free(&s);
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    }
    memcpy(s->face_start, plan->face_start, sizeof(int32_t) * (size_t)(nf + 1));
    memcpy(s->face_vertices, plan->face_vertices, sizeof(int32_t) * (size_t)nc);
    for (int32_t v = 0; v < nv; ++v) {
        s->plan_xy[2 * v] = plan->xyz[3 * v];
        s->plan_xy[2 * v + 1] = plan->xyz[3 * v + 1];
    }
    /* Weights normalised to mean 1, through w / wmax so that neither the sum
     * (weights near DBL_MAX) nor the normalised weight (a denormal weight
     * became 0, then 0/0 in the projection: found by fuzzing) leaves the
     * range of doubles; create refused ratios below FACET_LIFT_WEIGHT_RATIO. */
    double wmax = 0.0, wsum = 0.0;
    for (int32_t v = 0; v < nv; ++v)
        wmax = fmax(wmax, weights ? weights[v] : 1.0);
    for (int32_t v = 0; v < nv; ++v)
        wsum += (weights ? weights[v] : 1.0) / wmax;
    for (int32_t v = 0; v < nv; ++v)
        s->sqw[v] = sqrt((weights ? weights[v] : 1.0) / wmax * nv / wsum);

    /* Unique edges, for the Laplacian. */
    int32_t ne = 0;
    for (int32_t f = 0; f < nf; ++f) {
        int32_t b = s->face_start[f], e = s->face_start[f + 1];
        for (int32_t k = b; k < e; ++k) {
            int32_t u = s->face_vertices[k], w = s->face_vertices[k + 1 < e ? k + 1 : b];
            s->edges[2 * ne] = u < w ? u : w;
            s->edges[2 * ne + 1] = u < w ? w : u;
            ++ne;
        }
    }
    qsort(s->edges, (size_t)ne, 2 * sizeof(int32_t), compare_edge);
    int32_t unique = 0;
    for (int32_t i = 0; i < ne; ++i)
        if (unique == 0 || compare_edge(s->edges + 2 * i, s->edges + 2 * (unique - 1)) != 0) {
            s->edges[2 * unique] = s->edges[2 * i];
            s->edges[2 * unique + 1] = s->edges[2 * i + 1];
            ++unique;
        }
    s->ne = unique;

    /* The trivial liftings 1, x, y on centred and scaled coordinates, made
     * W-orthonormal by modified Gram-Schmidt, twice. */
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int32_t v = 0; v < nv; ++v)
        for (int c = 0; c < 2; ++c) {
            lo[c] = fmin(lo[c], s->plan_xy[2 * v + c]);
            hi[c] = fmax(hi[c], s->plan_xy[2 * v + c]);
        }
    double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]);
    double scale = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(scale > 0.0))
        scale = 1.0;
    for (int32_t v = 0; v < nv; ++v) {
        s->trivial[v] = s->sqw[v] * s->sqw[v] > 0 ? 1.0 : 0.0;
        s->trivial[nv + v] = (s->plan_xy[2 * v] - cx) / scale;
        s->trivial[2 * nv + v] = (s->plan_xy[2 * v + 1] - cy) / scale;
    }
    for (int pass = 0; pass < 2; ++pass)
        for (int j = 0; j < 3; ++j) {
            double *g = s->trivial + (size_t)j * nv;
            for (int i = 0; i < j; ++i) {
                const double *h = s->trivial + (size_t)i * nv;
                double dot = 0.0;
                for (int32_t v = 0; v < nv; ++v)
                    dot += s->sqw[v] * s->sqw[v] * g[v] * h[v];
                for (int32_t v = 0; v < nv; ++v)
                    g[v] -= dot * h[v];
            }
            double norm = 0.0;
            for (int32_t v = 0; v < nv; ++v)
                norm += s->sqw[v] * s->sqw[v] * g[v] * g[v];
            norm = sqrt(norm);
            if (!(norm > 1e-12 * sqrt((double)nv))) {
                free(scratch);
                free(order);
                facet_lifter_free(&s);
                return facet_fail(error, FACET_ERROR_PLAN_DEGENERATE_FACE, -1, -1,
                                  "the plan's vertices are collinear: it has no area");
            }
            for (int32_t v = 0; v < nv; ++v)
                g[v] /= norm;
        }

    /* Constraint rows, one column of A = W^-1/2 C' each. */
    int64_t m = 0;
    for (int32_t f = 0; f < nf; ++f)
        m += s->face_start[f + 1] - s->face_start[f] - 3;
    s->m = (int32_t)m;
    cholmod_l_start(&s->cm);
    s->cm_started = 1;
    s->cm.print = 0;
    s->cm.error_handler = NULL;
    s->cm.SPQR_nthreads = 1;
    {
        int64_t nnz = 0;
        for (int32_t f = 0; f < nf; ++f) {
            int64_t k = s->face_start[f + 1] - s->face_start[f];
            nnz += (k - 3) * k;
        }
        cholmod_sparse *a = cholmod_l_allocate_sparse((size_t)nv, (size_t)m, (size_t)(nnz + 1),
                                                      1, 1, 0, CHOLMOD_REAL, &s->cm);
        if (!a) {
            free(scratch);
            free(order);
            facet_lifter_free(&s);
            return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1,
                              "out of memory for %lld constraints", (long long)m);
        }
        int64_t *ap = a->p, *ai = a->i;
        double *ax = a->x;
        int64_t col = 0, pos = 0;
        ap[0] = 0;
        for (int32_t f = 0; f < nf; ++f) {
            const int32_t b = s->face_start[f], k = s->face_start[f + 1] - b;
            const int32_t *idx = s->face_vertices + b;
            double *h = scratch, *x = scratch + 3 * (size_t)k;
            double beta[3], diag[3];
            face_basis(s, idx, k, h, beta, diag);
            double sk = sqrt((double)k);
            if (!(fabs(diag[1]) > PLAN_DEGENERATE_REL * sk) ||
                !(fabs(diag[2]) > PLAN_DEGENERATE_REL * sk)) {
                cholmod_l_free_sparse(&a, &s->cm);
                free(scratch);
                free(order);
                facet_lifter_free(&s);
                return facet_fail(error, FACET_ERROR_PLAN_DEGENERATE_FACE, f, -1,
                                  "face %d has collinear corners in plan (it would be a "
                                  "vertical wall)",
                                  (int)f);
            }
            /* Corners in ascending vertex order for the CSC column. */
            for (int32_t i = 0; i < k; ++i) {
                int32_t j = i;
                while (j > 0 && idx[order[j - 1]] > idx[i]) {
                    order[j] = order[j - 1];
                    --j;
                }
                order[j] = i;
            }
            for (int32_t c = 3; c < k; ++c) {
                memset(x, 0, sizeof(double) * (size_t)k);
                x[c] = 1.0;
                householder3_apply(k, h, beta, x);
                for (int32_t i = 0; i < k; ++i) {
                    int32_t corner = (int32_t)order[i];
                    int32_t v = idx[corner];
                    ai[pos] = v;
                    ax[pos] = x[corner] / s->sqw[v];
                    ++pos;
                }
                ap[++col] = pos;
            }
        }
        double tol = options && options->rank_tol > 0 ? options->rank_tol : RANK_TOL_DEFAULT;
        if (m > 0)
        {
            int blas = blas_serial_begin();
            s->qr = SuiteSparseQR_C_factorize(SPQR_ORDERING_DEFAULT, tol, a, &s->cm);
            blas_serial_end(blas);
        }
        s->a = a;
        if (m > 0 && !s->qr) {
            facet_status st = s->cm.status == CHOLMOD_OUT_OF_MEMORY ? FACET_ERROR_OUT_OF_MEMORY
                                                                     : FACET_ERROR_NUMERICAL;
            free(scratch);
            free(order);
            facet_lifter_free(&s);
            return facet_fail(error, st, -1, -1,
                              "sparse QR of the %lld planarity constraints failed (status %d)",
                              (long long)m, st);
        }
        if (create_progress(options, 1)) {
            free(scratch);
            free(order);
            facet_lifter_free(&s);
            return facet_fail(error, FACET_ERROR_CANCELLED, -1, -1, "cancelled");
        }
        if (m > 0) {
            s->rank = (int32_t)s->cm.SPQR_istat[4];
            s->rhs_m = cholmod_l_allocate_dense((size_t)m, 1, (size_t)m, CHOLMOD_REAL, &s->cm);
            if (!s->rhs_m) {
                free(scratch);
                free(order);
                facet_lifter_free(&s);
                return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
            }
            int blas = blas_serial_begin();
            int found = find_hidden(s, tol, options);
            blas_serial_end(blas);
            if (found <= 0) {
                free(scratch);
                free(order);
                facet_lifter_free(&s);
                if (found < 0)
                    return facet_fail(error, FACET_ERROR_CANCELLED, -1, -1, "cancelled");
                return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1,
                                  "out of memory checking the planarity constraints' rank");
            }
        }
    }
    free(scratch);
    free(order);
    s->dim = nv - s->rank + s->n_hidden;
    if (create_progress(options, 2)) {
        facet_lifter_free(&s);
        return facet_fail(error, FACET_ERROR_CANCELLED, -1, -1, "cancelled");
    }
    if (s->qr && !check_rank(s)) {
        facet_lifter_free(&s);
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    }
    if (create_progress(options, 3)) {
        facet_lifter_free(&s);
        return facet_fail(error, FACET_ERROR_CANCELLED, -1, -1, "cancelled");
    }
    s->factor_seconds = facet_now() - t0;
    *out = s;
    return FACET_OK;
}

int32_t facet_lifter_dimension(const facet_lifter *lifter)
{
    return lifter ? lifter->dim : 0;
}

double facet_lifter_factor_seconds(const facet_lifter *lifter)
{
    return lifter ? lifter->factor_seconds : 0.0;
}

const char *facet_lifter_message(const facet_lifter *lifter)
{
    return lifter ? lifter->message : "";
}

/* u <- u - Q1 Q1' u + H H' u (H: the hidden directions, within range(Q1) and
 * reached by no column of A, so part of the lifting space), with the orthogonal Q. */
static int remove_range_q(facet_lifter *s, double *u)
{
    const int32_t nv = s->nv, nh = s->n_hidden;
    double *hidden_part = s->work2;
    memset(hidden_part, 0, sizeof(double) * (size_t)nv);
    for (int32_t h = 0; h < nh; ++h) {
        const double *q = s->hidden + (size_t)h * nv;
        double dot = 0.0;
        for (int32_t v = 0; v < nv; ++v)
            dot += q[v] * u[v];
        for (int32_t v = 0; v < nv; ++v)
            hidden_part[v] += dot * q[v];
    }
    if (!apply_q(s, 1, 1, u))
        return 0;
    memset(u, 0, sizeof(double) * (size_t)s->rank);
    if (!apply_q(s, 0, 1, u))
        return 0;
    for (int32_t v = 0; v < nv; ++v)
        u[v] += hidden_part[v];
    return 1;
}

/* u <- u - P u, P the orthogonal projector onto range(A_live), the columns
 * of A that SPQR kept (the others lie within its tolerance of their span).
 * With A_live E = Q1 R11, P = A_live R11^-1 R11^-T A_live', applied with
 * the stored R alone (two sparse triangular solves: the corrected
 * semi-normal equations, refined until A'u is at rounding level) instead of
 * the Householder Q, which is several times larger and slower to apply. */
static int remove_range(facet_lifter *s, double *u)
{
    const int64_t *ap = s->a->p, *ai = s->a->i;
    const double *ax = s->a->x;
    const int32_t m = s->m, nv = s->nv;
    double scale = 0.0;
    for (int32_t v = 0; v < nv; ++v)
        scale = fmax(scale, fabs(u[v]));
    if (scale == 0.0)
        return 1;
    if (s->n_hidden > 0) /* R is singular: the semi-normal equations cannot serve */
        return remove_range_q(s, u);
    memcpy(s->save, u, sizeof(double) * (size_t)nv); /* kept for the fallback */
    double *b = s->rhs_m->x;
    int converged = 0;
    /* Refinement converges (to the exact projection: the residual A'u is
     * formed afresh each step) when eps cond(R)^2 < 1; the size of each
     * correction tells. A small A'u alone would not: with a tiny singular
     * value, u may keep a large part in range(A) that A' barely sees. */
    for (int step = 0; step < 6 && !converged; ++step) {
        a_transpose_times(s, u, b);
        cholmod_dense *y = SuiteSparseQR_C_solve(SPQR_RTX_EQUALS_ETB, s->qr, s->rhs_m, &s->cm);
        if (!y)
            return 0;
        cholmod_dense *x = SuiteSparseQR_C_solve(SPQR_RETX_EQUALS_B, s->qr, y, &s->cm);
        cholmod_l_free_dense(&y, &s->cm);
        if (!x)
            return 0;
        const double *xx = x->x;
        double *delta = s->work2;
        memset(delta, 0, sizeof(double) * (size_t)nv);
        for (int32_t j = 0; j < m; ++j)
            for (int64_t k = ap[j]; k < ap[j + 1]; ++k)
                delta[ai[k]] += ax[k] * xx[j];
        cholmod_l_free_dense(&x, &s->cm);
        double largest = 0.0;
        for (int32_t v = 0; v < nv; ++v) {
            u[v] -= delta[v];
            largest = fmax(largest, fabs(delta[v]));
        }
        if (!(largest < 1e300))
            break;
        if (step > 0 && largest <= CSNE_TOL * scale)
            converged = 1;
    }
    if (converged)
        return 1;
    /* R is too ill-conditioned for the semi-normal equations (constraints
     * independent, but only just): project with the orthogonal Q, whose
     * accuracy does not depend on the conditioning. */
    memcpy(u, s->save, sizeof(double) * (size_t)nv);
    return remove_range_q(s, u);
}

/* Largest vertical distance of face f's corners (heights z) from the
 * least-squares plane z = a x + b y + c over them: the norm of z's part
 * outside span(1, x, y), computed with the same well-conditioned per-face
 * Householder QR as the constraints (a sliver face does not spoil it the way
 * a 3D plane fit does). An upper bound on the true distance from that plane;
 * 0 for triangles. scratch holds 5 * max_degree doubles. */
static double face_vertical_residual(const facet_lifter *s, int32_t f, const double *z,
                                     double *scratch)
{
    const int32_t b = s->face_start[f], k = s->face_start[f + 1] - b;
    if (k <= 3)
        return 0.0;
    const int32_t *idx = s->face_vertices + b;
    double mz = 0.0;
    for (int32_t i = 0; i < k; ++i)
        mz += z[idx[i]];
    mz /= k;
    double *h = scratch, *x = scratch + 3 * (size_t)k;
    for (int32_t i = 0; i < k; ++i)
        x[i] = z[idx[i]] - mz;
    double beta[3], diag[3];
    face_basis(s, idx, k, h, beta, diag);
    /* x <- Q' x: reflectors in forward order. */
    for (int j = 0; j < 3; ++j) {
        if (beta[j] == 0.0)
            continue;
        const double *col = h + (size_t)j * k;
        double dot = 0.0;
        for (int32_t i = j; i < k; ++i)
            dot += col[i] * x[i];
        dot *= beta[j];
        for (int32_t i = j; i < k; ++i)
            x[i] -= dot * col[i];
    }
    x[0] = x[1] = x[2] = 0.0;
    householder3_apply(k, h, beta, x);
    double largest = 0.0;
    for (int32_t i = 0; i < k; ++i)
        largest = fmax(largest, fabs(x[i]));
    return largest;
}

/* s->rank_check: the affine liftings (W^1/2 g, unit vectors of the lifting space)
 * through remove_range, which must leave them where they are. 0 on failure. */
static int check_rank(facet_lifter *s)
{
    const int32_t nv = s->nv;
    double *u = s->work;
    for (int j = 0; j < 3; ++j) {
        const double *g = s->trivial + (size_t)j * nv;
        for (int32_t v = 0; v < nv; ++v)
            u[v] = s->sqw[v] * g[v];
        int blas = blas_serial_begin();
        int ok = remove_range(s, u);
        blas_serial_end(blas);
        if (!ok)
            return 0;
        double moved = 0.0;
        for (int32_t v = 0; v < nv; ++v)
            moved += (u[v] - s->sqw[v] * g[v]) * (u[v] - s->sqw[v] * g[v]);
        s->rank_check = fmax(s->rank_check, isfinite(moved) ? sqrt(moved) : INFINITY);
    }
    return 1;
}

/* heights = the optimal lifting of t (may alias). Returns 0 on failure of Q. */
static int project(facet_lifter *s, const double *t, double *heights)
{
    const int32_t nv = s->nv;
    double a[3] = {0.0, 0.0, 0.0};
    for (int j = 0; j < 3; ++j) {
        const double *g = s->trivial + (size_t)j * nv;
        double dot = 0.0;
        for (int32_t v = 0; v < nv; ++v)
            dot += s->sqw[v] * s->sqw[v] * g[v] * t[v];
        a[j] = dot;
    }
    double *r = s->work;
    for (int32_t v = 0; v < nv; ++v) {
        double affine = a[0] * s->trivial[v] + a[1] * s->trivial[nv + v] +
                        a[2] * s->trivial[2 * nv + v];
        r[v] = s->sqw[v] * (t[v] - affine);
    }
    if (s->dim == 3 && s->qr) {
        memset(r, 0, sizeof(double) * (size_t)nv);
    } else if (s->qr) {
        int blas = blas_serial_begin();
        int ok = remove_range(s, r);
        blas_serial_end(blas);
        if (!ok)
            return 0;
    }
    for (int32_t v = 0; v < nv; ++v) {
        double affine = a[0] * s->trivial[v] + a[1] * s->trivial[nv + v] +
                        a[2] * s->trivial[2 * nv + v];
        heights[v] = affine + r[v] / s->sqw[v];
    }
    return 1;
}

facet_status facet_lifter_solve(facet_lifter *s, const double *targets, double *heights,
                                facet_lift_result *result, facet_error *error)
{
    facet_error_clear(error);
    if (!s || !targets || !heights)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1,
                          "lifter, targets or heights is NULL");
    s->message[0] = '\0';
    const int32_t nv = s->nv;
    for (int32_t v = 0; v < nv; ++v)
        if (!isfinite(targets[v]))
            return lifter_fail(s, error, FACET_ERROR_BAD_TARGET, -1, v,
                               "target height of vertex %d is not finite", (int)v);
        else if (!facet_point_in_range(targets + v, 1))
            return lifter_fail(s, error, FACET_ERROR_BAD_TARGET, -1, v,
                               "target height of vertex %d is %g, beyond 1e30 in magnitude",
                               (int)v, targets[v]);
    double t0 = facet_now();
    /* targets may alias heights: keep a copy in xyz's z slots. */
    for (int32_t v = 0; v < nv; ++v)
        s->xyz[3 * v + 2] = targets[v];
    double *z = calloc(nv > 0 ? (size_t)nv : 1, sizeof(double));
    if (!z)
        return lifter_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    for (int32_t v = 0; v < nv; ++v)
        z[v] = s->xyz[3 * v + 2];
    if (!project(s, z, z)) {
        free(z);
        return lifter_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, -1, -1,
                           "applying the stored Q failed (out of memory)");
    }
    for (int32_t v = 0; v < nv; ++v)
        if (!isfinite(z[v])) {
            free(z);
            return lifter_fail(s, error, FACET_ERROR_NUMERICAL, -1, v,
                               "the lifting is not finite at vertex %d", (int)v);
        }
    facet_lift_result r;
    memset(&r, 0, sizeof r);
    r.dimension = s->dim;
    r.trivial_dimension = 3;
    double sum2 = 0.0;
    r.target_max_vertex = -1;
    for (int32_t v = 0; v < nv; ++v) {
        double d = fabs(z[v] - s->xyz[3 * v + 2]);
        sum2 += d * d;
        if (d > r.target_max || r.target_max_vertex < 0) {
            r.target_max = d;
            r.target_max_vertex = v;
        }
        s->xyz[3 * v] = s->plan_xy[2 * v];
        s->xyz[3 * v + 1] = s->plan_xy[2 * v + 1];
        s->xyz[3 * v + 2] = z[v];
    }
    r.target_rms = nv ? sqrt(sum2 / nv) : 0.0;
    int32_t worst = -1;
    double *scratch = malloc(sizeof(double) * 5 * (size_t)(s->max_degree > 0 ? s->max_degree : 1));
    if (!scratch) {
        free(z);
        return lifter_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    }
    for (int32_t f = 0; f < s->nf; ++f) {
        const int32_t b = s->face_start[f], k = s->face_start[f + 1] - b;
        double dev = face_vertical_residual(s, f, z, scratch);
        double edge = 0.0;
        for (int32_t i = 0; i < k; ++i) {
            const double *p = s->xyz + 3 * (size_t)s->face_vertices[b + i];
            const double *q = s->xyz + 3 * (size_t)s->face_vertices[b + (i + 1) % k];
            edge += sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                         (p[2] - q[2]) * (p[2] - q[2]));
        }
        edge /= k;
        double rel = edge > 0 ? dev / edge : 0.0;
        if (dev > r.planarity_max_abs)
            r.planarity_max_abs = dev;
        if (rel > r.planarity_max_rel) {
            r.planarity_max_rel = rel;
            worst = f;
        }
    }
    free(scratch);
    memcpy(heights, z, sizeof(double) * (size_t)nv);
    free(z);
    r.seconds = facet_now() - t0;
    if (result)
        *result = r;
    /* The rank warning first, the planarity one added to it: the planarity miss alone
     * hid that the result was far from the closest lifting (a 1,000-site Voronoi plan at
     * rank tolerance 1e-5 missed the paraboloid's lifting by 12% of its range, reported as
     * a face planar to 5.05e-6 only: test_lift.py). */
    char planar[128] = ""; /* the planarity finding, when a face misses */
    if (r.planarity_max_rel > PLANARITY_TOL_REL)
        snprintf(planar, sizeof planar,
                 "face %d is planar only to %.3g of its mean edge length (> 1e-9)", (int)worst,
                 r.planarity_max_rel);
    if (s->rank_check > RANK_CHECK_TOL)
        return lifter_fail(s, error, FACET_WARNING_LIFTING_RANK, planar[0] ? worst : -1, -1,
                           "the planarity constraints' dependencies could not be told from "
                           "rounding (the affine liftings move by %.2g when projected): the "
                           "lifting space may be larger than the %d dimensions found, and "
                           "the result farther from the targets than the closest lifting%s%s",
                           s->rank_check, (int)s->dim, planar[0] ? "; and " : "", planar);
    if (planar[0])
        return lifter_fail(s, error, FACET_WARNING_PLANARITY, worst, -1, "%s", planar);
    if (s->dim <= 3)
        return lifter_fail(s, error, FACET_WARNING_TRIVIAL_LIFTING, -1, -1,
                           "the plan admits only the trivial (affine) liftings: the result "
                           "is the best-fitting plane");
    return FACET_OK;
}

facet_status facet_lifter_fundamental(facet_lifter *s, int32_t vertex, double *heights,
                                      facet_error *error)
{
    facet_error_clear(error);
    if (!s || !heights)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1,
                          "lifter or heights is NULL");
    if (vertex < 0 || vertex >= s->nv)
        return lifter_fail(s, error, FACET_ERROR_INDEX_OUT_OF_RANGE, -1, vertex,
                           "vertex %d is out of range (the plan has %d vertices)", (int)vertex,
                           (int)s->nv);
    memset(heights, 0, sizeof(double) * (size_t)s->nv);
    heights[vertex] = 1.0;
    if (!project(s, heights, heights))
        return lifter_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, -1, -1,
                           "applying the stored Q failed (out of memory)");
    for (int32_t v = 0; v < s->nv; ++v)
        if (!isfinite(heights[v]))
            return lifter_fail(s, error, FACET_ERROR_NUMERICAL, -1, v,
                               "the fundamental lifting of vertex %d is not finite at vertex %d",
                               (int)vertex, (int)v);
    return FACET_OK;
}

/* Laplacian energy z' L z of one function. */
static double dirichlet(const facet_lifter *s, const double *z)
{
    double e = 0.0;
    for (int32_t i = 0; i < s->ne; ++i) {
        double d = z[s->edges[2 * i]] - z[s->edges[2 * i + 1]];
        e += d * d;
    }
    return e;
}

static void fix_sign(int32_t n, double *z)
{
    int32_t best = 0;
    for (int32_t v = 1; v < n; ++v)
        if (fabs(z[v]) > fabs(z[best]) * (1.0 + 1e-12))
            best = v;
    if (z[best] < 0)
        for (int32_t v = 0; v < n; ++v)
            z[v] = -z[v];
}

static facet_status basis_serial(facet_lifter *s, facet_basis_kind kind, int32_t count,
                                 double *basis, double *values, facet_error *error);

facet_status facet_lifter_basis(facet_lifter *s, facet_basis_kind kind, int32_t count,
                                double *basis, double *values, facet_error *error)
{
    int blas = blas_serial_begin();
    facet_status status = basis_serial(s, kind, count, basis, values, error);
    blas_serial_end(blas);
    if (status >= 0 && count > 0)
        for (size_t i = 0; i < (size_t)count * (size_t)s->nv; ++i)
            if (!isfinite(basis[i]) || (values && i < (size_t)count && !isfinite(values[i])))
                return lifter_fail(s, error, FACET_ERROR_NUMERICAL, -1, -1,
                                   "basis function %d is not finite", (int)(i / (size_t)s->nv));
    return status;
}

static facet_status basis_serial(facet_lifter *s, facet_basis_kind kind, int32_t count,
                                 double *basis, double *values, facet_error *error)
{
    facet_error_clear(error);
    if (!s || (!basis && count > 0))
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1, "lifter or basis is NULL");
    if (kind != FACET_BASIS_ORTHONORMAL && kind != FACET_BASIS_EIGEN)
        return lifter_fail(s, error, FACET_ERROR_INVALID_ARGUMENT, -1, -1,
                           "unknown basis kind %d", (int)kind);
    const int32_t nv = s->nv, d = s->dim;
    if (count < 0 || count > d)
        return lifter_fail(s, error, FACET_ERROR_INVALID_ARGUMENT, -1, -1,
                           "count %d is not between 0 and the dimension %d", (int)count, (int)d);
    if (kind == FACET_BASIS_EIGEN &&
        (d > EIGEN_MAX_DIMENSION || (double)nv * d > EIGEN_MAX_ENTRIES))
        return lifter_fail(s, error, FACET_ERROR_TOO_LARGE, -1, -1,
                           "eigen-liftings are dense: dimension %d with %d vertices is over the "
                           "limit (dimension %d, vertices x dimension %.0f)",
                           (int)d, (int)nv, EIGEN_MAX_DIMENSION, EIGEN_MAX_ENTRIES);
    const int32_t ntriv = count < 3 ? count : 3;
    for (int32_t j = 0; j < ntriv; ++j) {
        memcpy(basis + (size_t)j * nv, s->trivial + (size_t)j * nv, sizeof(double) * (size_t)nv);
        if (values)
            values[j] = dirichlet(s, basis + (size_t)j * nv);
    }
    if (count <= 3)
        return FACET_OK;
    /* How many non-trivial functions to build. */
    const int32_t nt = d - 3;
    const int32_t nbuild = kind == FACET_BASIS_EIGEN ? nt : count - 3;
    /* Coordinates in the lifting space's orthonormal basis (of W^1/2 null(C)): the
     * hidden directions H first (nh), then Q2, the last nv - rank columns of Q.
     * Those of the trivial liftings: c_j = [H' W^1/2 g_j; (Q' W^1/2 g_j)[rank:]]. */
    const int32_t nh = s->n_hidden, tail = nv - s->rank;
    double *c = malloc(sizeof(double) * 3 * (size_t)nv);
    double *z = malloc(sizeof(double) * (size_t)nv * (size_t)nbuild);
    double *hv = malloc(sizeof(double) * (size_t)d);
    double *heads = malloc(sizeof(double) * (size_t)(nh > 0 ? nh : 1) * (size_t)nbuild);
    double *h = malloc(sizeof(double) * 3 * (size_t)d);
    if (!c || !z || !hv || !heads || !h) {
        free(c), free(z), free(hv), free(heads), free(h);
        return lifter_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    }
    for (int j = 0; j < 3; ++j)
        for (int32_t v = 0; v < nv; ++v)
            c[(size_t)j * nv + v] = s->sqw[v] * s->trivial[(size_t)j * nv + v];
    for (int j = 0; j < 3; ++j)
        for (int32_t k = 0; k < nh; ++k) {
            const double *q = s->hidden + (size_t)k * nv, *cj = c + (size_t)j * nv;
            double dot = 0.0;
            for (int32_t v = 0; v < nv; ++v)
                dot += q[v] * cj[v];
            h[(size_t)j * d + k] = dot;
        }
    if (!apply_q(s, 1, 3, c)) {
        free(c), free(z), free(hv), free(heads), free(h);
        return lifter_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "applying Q failed");
    }
    /* Householder QR of the d x 3 matrix of those coordinates (in place); its last
     * d-3 Q columns span the rest. */
    for (int j = 0; j < 3; ++j)
        memcpy(h + (size_t)j * d + nh, c + (size_t)j * nv + s->rank,
               sizeof(double) * (size_t)tail);
    free(c);
    double beta[3], diag[3];
    householder3(d, h, beta, diag);
    for (int32_t j = 0; j < nbuild; ++j) {
        double *col = z + (size_t)j * nv;
        memset(col, 0, sizeof(double) * (size_t)nv);
        memset(hv, 0, sizeof(double) * (size_t)d);
        hv[3 + j] = 1.0;
        householder3_apply(d, h, beta, hv);
        memcpy(heads + (size_t)j * nh, hv, sizeof(double) * (size_t)nh);
        memcpy(col + s->rank, hv + nh, sizeof(double) * (size_t)tail);
    }
    free(h);
    free(hv);
    if (!apply_q(s, 0, nbuild, z)) {
        free(z), free(heads);
        return lifter_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "applying Q failed");
    }
    for (int32_t j = 0; j < nbuild; ++j)
        for (int32_t k = 0; k < nh; ++k) {
            const double *q = s->hidden + (size_t)k * nv;
            const double a = heads[(size_t)j * nh + k];
            double *col = z + (size_t)j * nv;
            for (int32_t v = 0; v < nv; ++v)
                col[v] += a * q[v];
        }
    free(heads);
    for (int32_t j = 0; j < nbuild; ++j)
        for (int32_t v = 0; v < nv; ++v)
            z[(size_t)j * nv + v] /= s->sqw[v];
    if (kind == FACET_BASIS_ORTHONORMAL) {
        for (int32_t j = 0; j < nbuild; ++j) {
            double *out = basis + (size_t)(3 + j) * nv;
            memcpy(out, z + (size_t)j * nv, sizeof(double) * (size_t)nv);
            fix_sign(nv, out);
            if (values)
                values[3 + j] = dirichlet(s, out);
        }
        free(z);
        return FACET_OK;
    }
    /* Eigen: M = Z' L Z (nt x nt), lowest count-3 eigenpairs. */
    double *lz = malloc(sizeof(double) * (size_t)nv * (size_t)nt);
    double *mm = malloc(sizeof(double) * (size_t)nt * (size_t)nt);
    if (!lz || !mm) {
        free(z), free(lz), free(mm);
        return lifter_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    }
    memset(lz, 0, sizeof(double) * (size_t)nv * (size_t)nt);
#pragma omp parallel for schedule(static)
    for (int32_t j = 0; j < nt; ++j) {
        const double *zj = z + (size_t)j * nv;
        double *lj = lz + (size_t)j * nv;
        for (int32_t i = 0; i < s->ne; ++i) {
            int32_t a = s->edges[2 * i], b = s->edges[2 * i + 1];
            double diff = zj[a] - zj[b];
            lj[a] += diff;
            lj[b] -= diff;
        }
    }
#pragma omp parallel for schedule(dynamic, 4)
    for (int32_t j = 0; j < nt; ++j)
        for (int32_t i = 0; i <= j; ++i) {
            const double *zi = z + (size_t)i * nv, *lj = lz + (size_t)j * nv;
            double dot = 0.0;
            for (int32_t v = 0; v < nv; ++v)
                dot += zi[v] * lj[v];
            mm[(size_t)j * nt + i] = dot;
            mm[(size_t)i * nt + j] = dot;
        }
    free(lz);
    const int ne_want = count - 3, n_int = nt, il = 1, iu = ne_want;
    double vl = 0, vu = 0, abstol = 0;
    int found = 0, info = 0, lwork = -1, liwork = -1, iwork_query = 0;
    double work_query = 0;
    double *evals = malloc(sizeof(double) * (size_t)nt);
    double *evecs = malloc(sizeof(double) * (size_t)nt * (size_t)(ne_want > 0 ? ne_want : 1));
    int *isuppz = malloc(sizeof(int) * 2 * (size_t)(nt > 0 ? nt : 1));
    if (!evals || !evecs || !isuppz) {
        free(z), free(mm), free(evals), free(evecs), free(isuppz);
        return lifter_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    }
    dsyevr_("V", "I", "U", &n_int, mm, &n_int, &vl, &vu, &il, &iu, &abstol, &found, evals, evecs,
            &n_int, isuppz, &work_query, &lwork, &iwork_query, &liwork, &info);
    lwork = (int)work_query;
    liwork = iwork_query;
    double *work = malloc(sizeof(double) * (size_t)(lwork > 1 ? lwork : 1));
    int *iwork = malloc(sizeof(int) * (size_t)(liwork > 1 ? liwork : 1));
    if (!work || !iwork) {
        free(z), free(mm), free(evals), free(evecs), free(isuppz), free(work), free(iwork);
        return lifter_fail(s, error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    }
    if (info == 0)
        dsyevr_("V", "I", "U", &n_int, mm, &n_int, &vl, &vu, &il, &iu, &abstol, &found, evals,
                evecs, &n_int, isuppz, work, &lwork, iwork, &liwork, &info);
    free(work), free(iwork), free(isuppz), free(mm);
    if (info != 0 || found != ne_want) {
        free(z), free(evals), free(evecs);
        return lifter_fail(s, error, FACET_ERROR_NUMERICAL, -1, -1,
                           "the eigen-solver (LAPACK dsyevr) failed with info %d", info);
    }
#pragma omp parallel for schedule(static)
    for (int32_t e = 0; e < ne_want; ++e) {
        double *out = basis + (size_t)(3 + e) * nv;
        const double *vec = evecs + (size_t)e * nt;
        for (int32_t v = 0; v < nv; ++v) {
            double sum = 0.0;
            for (int32_t j = 0; j < nt; ++j)
                sum += z[(size_t)j * nv + v] * vec[j];
            out[v] = sum;
        }
        fix_sign(nv, out);
    }
    if (values)
        for (int32_t e = 0; e < ne_want; ++e)
            values[3 + e] = evals[e];
    free(z), free(evals), free(evecs);
    return FACET_OK;
}
