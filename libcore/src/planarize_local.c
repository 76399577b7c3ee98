/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* The planarizer's local steps: with the vertices q fixed, every per-face and
 * per-vertex auxiliary variable has a closed form (paper sections 4 and 6.2):
 *
 *   plane of a face       smallest eigenvector of its scatter matrix
 *                         (with the face-normal Laplacian: of the scatter
 *                         minus lambda m m^T, m the mean neighbour normal);
 *   shape (ASAP/ARAP)     orthogonal Procrustes between control and current face;
 *   circle                algebraic (Kasa) circle fit in the face's plane;
 *   sliding boundary      closest point on the control boundary polyline.
 *
 * Each loop writes only its own face or vertex and every sum runs in a fixed
 * order, so results do not depend on the thread count. */
#include "planarize_internal.h"
#include "simd.h"

#include <math.h>
#include <string.h>

int32_t facet_pl_couple_key(const facet_planarize_options *o)
{
    int32_t key = 0;
    if (o->laplacian > 0.0)
        key |= COUPLE_LAPLACIAN;
    if (o->boundary_fairness > 0.0)
        key |= COUPLE_FAIRNESS;
    if (o->shape != FACET_SHAPE_NONE && o->shape_weight > 0.0)
        key |= COUPLE_SHAPE;
    if (o->parallelogram > 0.0)
        key |= COUPLE_PARALLELOGRAM;
    return key;
}

/* ---- small dense helpers ------------------------------------------------ */

static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double normalize3(double a[3])
{
    const double n = sqrt(dot3(a, a));
    if (n > 0.0) {
        a[0] /= n, a[1] /= n, a[2] /= n;
    }
    return n;
}

/* Eigen-decomposition of a symmetric 3x3 matrix (row-major a[9]) by cyclic
 * Jacobi rotations: eigenvalues w[3] descending, eigenvectors as the columns
 * of v[9]. A fixed sweep limit keeps it deterministic and bounded. */
static void sym3_eigen(const double a_in[9], double w[3], double v[9])
{
    double a[9];
    memcpy(a, a_in, sizeof a);
    for (int k = 0; k < 9; ++k)
        v[k] = (k % 4 == 0) ? 1.0 : 0.0;
    for (int sweep = 0; sweep < 32; ++sweep) {
        const double off = a[1] * a[1] + a[2] * a[2] + a[5] * a[5];
        const double diag = a[0] * a[0] + a[4] * a[4] + a[8] * a[8];
        if (off <= 1e-30 * diag || off == 0.0)
            break;
        for (int p = 0; p < 2; ++p)
            for (int r = p + 1; r < 3; ++r) {
                const double apr = a[3 * p + r];
                if (apr == 0.0)
                    continue;
                const double theta = (a[3 * r + r] - a[3 * p + p]) / (2.0 * apr);
                const double t = (theta >= 0.0 ? 1.0 : -1.0) /
                                 (fabs(theta) + sqrt(theta * theta + 1.0));
                const double c = 1.0 / sqrt(t * t + 1.0), sn = t * c;
                for (int k = 0; k < 3; ++k) { /* columns p, r */
                    const double akp = a[3 * k + p], akr = a[3 * k + r];
                    a[3 * k + p] = c * akp - sn * akr;
                    a[3 * k + r] = sn * akp + c * akr;
                }
                for (int k = 0; k < 3; ++k) { /* rows p, r */
                    const double apk = a[3 * p + k], ark = a[3 * r + k];
                    a[3 * p + k] = c * apk - sn * ark;
                    a[3 * r + k] = sn * apk + c * ark;
                }
                for (int k = 0; k < 3; ++k) {
                    const double vkp = v[3 * k + p], vkr = v[3 * k + r];
                    v[3 * k + p] = c * vkp - sn * vkr;
                    v[3 * k + r] = sn * vkp + c * vkr;
                }
            }
    }
    w[0] = a[0], w[1] = a[4], w[2] = a[8];
    /* sort descending, moving eigenvector columns along */
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2 - i; ++j)
            if (w[j] < w[j + 1]) {
                const double tw = w[j];
                w[j] = w[j + 1], w[j + 1] = tw;
                for (int k = 0; k < 3; ++k) {
                    const double tv = v[3 * k + j];
                    v[3 * k + j] = v[3 * k + j + 1], v[3 * k + j + 1] = tv;
                }
            }
}

/* The rotation R (similar: times the scale s) maximising trace(R^T C) for
 * C = sum y x^T, i.e. minimising sum |s R x - y|^2 (orthogonal Procrustes),
 * through the SVD C = U S V^T taken from the eigenvectors of C^T C. U and V
 * are completed to proper rotations, so R is never a reflection; for a flat
 * face (rank-2 C) that completion is the unique answer. sr is row-major. */
void facet_pl_procrustes(const double c[9], int similar, double sr[9])
{
    double ctc[9];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            ctc[3 * i + j] = c[i] * c[j] + c[3 + i] * c[3 + j] + c[6 + i] * c[6 + j];
    double w[3], vv[9];
    sym3_eigen(ctc, w, vv);
    double v0[3] = {vv[0], vv[3], vv[6]}, v1[3] = {vv[1], vv[4], vv[7]}, v2[3];
    double u0[3], u1[3], u2[3];
    for (int i = 0; i < 3; ++i) {
        u0[i] = c[3 * i] * v0[0] + c[3 * i + 1] * v0[1] + c[3 * i + 2] * v0[2];
        u1[i] = c[3 * i] * v1[0] + c[3 * i + 1] * v1[1] + c[3 * i + 2] * v1[2];
    }
    const double s0 = normalize3(u0);
    if (!(s0 > 0.0)) { /* no information: identity */
        for (int k = 0; k < 9; ++k)
            sr[k] = (k % 4 == 0) ? 1.0 : 0.0;
        return;
    }
    const double proj = dot3(u1, u0);
    for (int i = 0; i < 3; ++i)
        u1[i] -= proj * u0[i];
    if (!(normalize3(u1) > 1e-12 * s0)) { /* rank 1: any u1 orthogonal to u0 */
        const double axis[3] = {fabs(u0[0]) < 0.9 ? 1.0 : 0.0, fabs(u0[0]) < 0.9 ? 0.0 : 1.0, 0.0};
        cross3(u0, axis, u1);
        normalize3(u1);
    }
    cross3(u0, u1, u2);
    cross3(v0, v1, v2);
    double r[9];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r[3 * i + j] = u0[i] * v0[j] + u1[i] * v1[j] + u2[i] * v2[j];
    double scale = 1.0;
    if (similar) {
        /* s = trace(R^T C) / sum |x|^2 and sum |x|^2 = trace of the x scatter,
         * which the caller folds in: here s is returned relative, see below. */
        double tr = 0.0;
        for (int k = 0; k < 9; ++k)
            tr += r[k] * c[k];
        scale = tr; /* divided by sum |x|^2 by the caller */
    }
    for (int k = 0; k < 9; ++k)
        sr[k] = scale * r[k];
}

/* The mean of the points xyz[idx[k]], k < n. */
static void centroid_indexed(int32_t n, const double *xyz, const int32_t *idx, double c[3])
{
    c[0] = 0.0, c[1] = 0.0, c[2] = 0.0;
    for (int32_t k = 0; k < n; ++k)
        for (int a = 0; a < 3; ++a)
            c[a] += xyz[3 * (size_t)idx[k] + a];
    for (int a = 0; a < 3; ++a)
        c[a] /= (double)n;
}

/* Circle through the n points xyz[idx[k]] in the plane with unit normal
 * `normal` (an algebraic least-squares fit, exact for concyclic points and for
 * triangles): targets[3k] is point k moved radially onto the circle and into
 * the plane. Returns 0 (targets = the points projected into the plane) when
 * the points are collinear. */
int facet_pl_circle_targets(int32_t n, const double *xyz, const int32_t *idx,
                            const double normal[3], double *targets)
{
    double c[3];
    centroid_indexed(n, xyz, idx, c);
    /* in-plane frame */
    double e1[3], e2[3];
    const double *x0 = xyz + 3 * (size_t)idx[0];
    for (int a = 0; a < 3; ++a)
        e1[a] = x0[a] - c[a];
    const double along = dot3(e1, normal);
    for (int a = 0; a < 3; ++a)
        e1[a] -= along * normal[a];
    if (!(normalize3(e1) > 0.0)) {
        const double axis[3] = {fabs(normal[0]) < 0.9 ? 1.0 : 0.0, fabs(normal[0]) < 0.9 ? 0.0 : 1.0, 0.0};
        cross3(normal, axis, e1);
        normalize3(e1);
    }
    cross3(normal, e1, e2);
    /* Kasa fit: minimise sum (x^2 + y^2 + D x + E y + F)^2, centred data */
    double m[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0}, rhs[3] = {0.0, 0.0, 0.0};
    for (int32_t k = 0; k < n; ++k) {
        const double *x = xyz + 3 * (size_t)idx[k];
        const double d[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
        const double u = dot3(d, e1), v = dot3(d, e2), r2 = u * u + v * v;
        m[0] += u * u, m[1] += u * v, m[2] += u, m[3] += v * v, m[4] += v, m[5] += 1.0;
        rhs[0] -= r2 * u, rhs[1] -= r2 * v, rhs[2] -= r2;
    }
    /* 3x3 symmetric solve by Cramer's rule */
    const double a00 = m[0], a01 = m[1], a02 = m[2], a11 = m[3], a12 = m[4], a22 = m[5];
    const double c00 = a11 * a22 - a12 * a12, c01 = a02 * a12 - a01 * a22, c02 = a01 * a12 - a02 * a11;
    const double det = a00 * c00 + a01 * c01 + a02 * c02;
    const double scale = a00 + a11; /* sum of squared radii, a length^2 */
    int ok = det > 1e-12 * scale * scale * a22 && isfinite(det);
    double cu = 0.0, cv = 0.0, radius = 0.0;
    if (ok) {
        const double c11 = a00 * a22 - a02 * a02, c12 = a01 * a02 - a00 * a12,
                     c22 = a00 * a11 - a01 * a01;
        const double D = (c00 * rhs[0] + c01 * rhs[1] + c02 * rhs[2]) / det;
        const double E = (c01 * rhs[0] + c11 * rhs[1] + c12 * rhs[2]) / det;
        const double F = (c02 * rhs[0] + c12 * rhs[1] + c22 * rhs[2]) / det;
        cu = -0.5 * D, cv = -0.5 * E;
        const double r2 = cu * cu + cv * cv - F;
        ok = r2 > 0.0 && isfinite(r2);
        radius = ok ? sqrt(r2) : 0.0;
    }
    for (int32_t k = 0; k < n; ++k) {
        const double *x = xyz + 3 * (size_t)idx[k];
        const double d[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
        double u = dot3(d, e1), v = dot3(d, e2);
        if (ok) {
            const double du = u - cu, dv = v - cv, len = sqrt(du * du + dv * dv);
            if (len > 0.0)
                u = cu + radius * du / len, v = cv + radius * dv / len;
        }
        for (int a = 0; a < 3; ++a)
            targets[3 * k + a] = c[a] + u * e1[a] + v * e2[a];
    }
    return ok;
}

/* Closest point to x on segment a-b: writes it and the unit direction. */
static double closest_on_segment(const double x[3], const double a[3], const double b[3],
                                 double point[3], double tangent[3])
{
    double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double len2 = dot3(ab, ab);
    double t = len2 > 0.0 ? ((x[0] - a[0]) * ab[0] + (x[1] - a[1]) * ab[1] + (x[2] - a[2]) * ab[2]) / len2
                          : 0.0;
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    for (int k = 0; k < 3; ++k) {
        point[k] = a[k] + t * ab[k];
        tangent[k] = ab[k];
    }
    normalize3(tangent);
    const double d[3] = {x[0] - point[0], x[1] - point[1], x[2] - point[2]};
    return dot3(d, d);
}

/* ---- per solve ------------------------------------------------------------ */

/* What depends on the control positions p and the options only: fixed
 * vertices, control normals, control face centroids, Laplacian weights. */
/* Cosine of the corner angle at c between a and b (1 when an edge has no length). */
static double corner_cosine(const double *xyz, int32_t a, int32_t c, int32_t b)
{
    const double *pa = xyz + 3 * (size_t)a, *pc = xyz + 3 * (size_t)c, *pb = xyz + 3 * (size_t)b;
    const double u[3] = {pa[0] - pc[0], pa[1] - pc[1], pa[2] - pc[2]};
    const double v[3] = {pb[0] - pc[0], pb[1] - pc[1], pb[2] - pc[2]};
    const double uu = dot3(u, u), vv = dot3(v, v);
    if (!(uu > 0.0 && vv > 0.0))
        return 1.0;
    return dot3(u, v) / sqrt(uu * vv);
}

/* Rotates x about the unit axis n by the angle with this cosine and sine. */
static void rotate3(const double x[3], const double n[3], double c, double s, double out[3])
{
    double nx[3];
    cross3(n, x, nx);
    const double d = dot3(n, x) * (1.0 - c);
    for (int a = 0; a < 3; ++a)
        out[a] = x[a] * c + nx[a] * s + n[a] * d;
}

/* The angle floor's projection of one corner (a, c, b) of a face with unit
 * normal n whose angle has the cosine `now` > `floor` (the floor's cosine):
 * both edges turn apart about n by half the missing angle, and the three
 * points shift together so that their centroid stays. Writes the target of
 * corner `role` (0 a, 1 c, 2 b) to t. */
static void corner_target(const double *xyz, int32_t a, int32_t c, int32_t b, const double n[3],
                          double now, double floor, int role, double t[3])
{
    const double *pa = xyz + 3 * (size_t)a, *pc = xyz + 3 * (size_t)c, *pb = xyz + 3 * (size_t)b;
    const double u[3] = {pa[0] - pc[0], pa[1] - pc[1], pa[2] - pc[2]};
    const double v[3] = {pb[0] - pc[0], pb[1] - pc[1], pb[2] - pc[2]};
    double uv[3];
    cross3(u, v, uv);
    /* turning from u towards v is positive about n when u x v points along n */
    const double sign = dot3(uv, n) >= 0.0 ? 1.0 : -1.0;
    const double half = 0.5 * (acos(facet_min(1.0, floor)) - acos(facet_min(1.0, now)));
    const double ch = cos(half), sh = sin(half);
    double ua[3], vb[3];
    rotate3(u, n, ch, -sign * sh, ua); /* u turns away from v, v away from u */
    rotate3(v, n, ch, sign * sh, vb);
    double shift[3];
    for (int k = 0; k < 3; ++k)
        shift[k] = ((ua[k] - u[k]) + (vb[k] - v[k])) / 3.0;
    for (int k = 0; k < 3; ++k)
        t[k] = (role == 0 ? pc[k] + ua[k] : role == 1 ? pc[k] : pc[k] + vb[k]) - shift[k];
}

void facet_pl_prepare_solve(facet_planarizer *s)
{
    const int32_t nv = s->nv, nf = s->nf;
    const facet_planarize_options *o = &s->o;
    /* no corner held yet: a held corner's targets left by an earlier solve
     * (one whose last step held a corner, followed by one without the angle
     * floor, which never clears them) would steer this solve's first global
     * steps (the planarize fuzzer's same-input oracle: one handle solving the
     * same input twice took 10, then 18 iterations) */
    if (s->guard_count)
        memset(s->guard_count, 0, sizeof(double) * (size_t)nv);
    s->guard_on = 0;
    memset(s->fixed, 0, (size_t)nv);
    for (int32_t k = 0; k < s->n_user_fixed; ++k)
        s->fixed[s->user_fixed[k]] = 1;
    for (int32_t v = 0; v < nv; ++v) {
        if (o->boundary == FACET_BOUNDARY_FIXED && s->on_boundary[v])
            s->fixed[v] = 1;
        /* a pinch vertex (two boundary loops meet) cannot slide along one
         * curve, and a corner (the boundary turns by more than 45 degrees)
         * stays a corner */
        if (o->boundary == FACET_BOUNDARY_SLIDING && s->on_boundary[v]) {
            if (s->boundary_prev[v] < 0) {
                s->fixed[v] = 1;
            } else {
                const double *a = s->p + 3 * (size_t)s->boundary_prev[v], *x = s->p + 3 * (size_t)v;
                const double *b = s->p + 3 * (size_t)s->boundary_next[v];
                double in[3] = {x[0] - a[0], x[1] - a[1], x[2] - a[2]};
                double out[3] = {b[0] - x[0], b[1] - x[1], b[2] - x[2]};
                normalize3(in);
                normalize3(out);
                if (dot3(in, out) < 0.70710678118654752)
                    s->fixed[v] = 1;
            }
        }
    }
    /* vertex normals: sum of the faces' vector areas (Newell), normalised */
    memset(s->vertex_normal, 0, sizeof(double) * 3 * (size_t)nv);
    for (int32_t f = 0; f < nf; ++f) {
        const int32_t b = s->face_start[f], e = s->face_start[f + 1];
        double area[3] = {0.0, 0.0, 0.0}, centroid[3] = {0.0, 0.0, 0.0};
        for (int32_t k = b; k < e; ++k) {
            const double *x = s->p + 3 * (size_t)s->face_vertices[k];
            const double *y = s->p + 3 * (size_t)s->face_vertices[k + 1 < e ? k + 1 : b];
            area[0] += (x[1] - y[1]) * (x[2] + y[2]);
            area[1] += (x[2] - y[2]) * (x[0] + y[0]);
            area[2] += (x[0] - y[0]) * (x[1] + y[1]);
            for (int a = 0; a < 3; ++a)
                centroid[a] += x[a];
        }
        if (s->control_centroid) /* (the shape term's) */
            for (int a = 0; a < 3; ++a)
                s->control_centroid[3 * (size_t)f + a] = centroid[a] / (double)(e - b);
        for (int32_t k = b; k < e; ++k)
            for (int a = 0; a < 3; ++a)
                s->vertex_normal[3 * (size_t)s->face_vertices[k] + a] += area[a];
    }
    for (int32_t v = 0; v < nv; ++v) {
        double *n = s->vertex_normal + 3 * (size_t)v;
        if (!(normalize3(n) > 0.0))
            n[0] = 0.0, n[1] = 0.0, n[2] = 1.0;
    }
    /* angle floor: per corner, the cosine of min(floor, control angle) */
    if (o->angle_floor > 0.0) {
        const double floor_cos = cos(o->angle_floor * 3.14159265358979323846 / 180.0);
        for (int32_t f = 0; f < nf; ++f) {
            const int32_t b = s->face_start[f], n = s->face_start[f + 1] - b;
            for (int32_t k = 0; k < n; ++k) {
                const double c = corner_cosine(s->p, s->face_vertices[b + (k + n - 1) % n],
                                               s->face_vertices[b + k], s->face_vertices[b + (k + 1) % n]);
                s->corner_floor[b + k] = facet_max(floor_cos, c);
            }
        }
    }
    /* Laplacian weights, normalised to sum 1 around each vertex; read only
     * while the Laplacian is on (not written otherwise: 32 bytes per face on
     * quads that a solve without it does not touch) */
    for (int32_t v = 0; o->laplacian > 0.0 && v < nv; ++v) {
        const int32_t b = s->vertex_adj_start[v], e = s->vertex_adj_start[v + 1];
        double sum = 0.0;
        for (int32_t k = b; k < e; ++k) {
            double w = 1.0;
            if (o->laplacian_weights == FACET_LAPLACIAN_INVERSE_EDGE) {
                const double *x = s->p + 3 * (size_t)v, *y = s->p + 3 * (size_t)s->vertex_adj[k];
                const double d[3] = {x[0] - y[0], x[1] - y[1], x[2] - y[2]};
                const double len = sqrt(dot3(d, d));
                w = len > 1e-9 ? 1.0 / len : 1e9;
            }
            s->laplace_weight[k] = w;
            sum += w;
        }
        for (int32_t k = b; k < e; ++k)
            s->laplace_weight[k] /= sum;
    }
}

static double face_weight(const facet_planarizer *s, int32_t f)
{
    return s->face_weight ? s->face_weight[f] : 1.0;
}

enum { FIT_MAX_CORNERS = 8 }; /* faces up to this size take the one-pass fit below */

/* One face of at most FIT_MAX_CORNERS corners in one pass over its points,
 * in two halves around the eigenvector (so that two faces can share
 * facet_sym3_smallest_eigenvector2): what facet_face_measure gives (the
 * same arithmetic in the same order, so the same bits) and, when floor is
 * not NULL, the angle floor's test of each corner (a corner's exact cosine
 * is taken only where a squared test with a margin says it may be below its
 * floor, whose cosine is > 0.5). The corner vectors are the edges': at
 * corner k, u = -e(k-1) and v = e(k), exactly. */
typedef struct {
    double x[FIT_MAX_CORNERS][3]; /* the points */
    double c[3];                  /* their centroid */
    double a[6];                  /* their scatter */
} face_fit;

static inline __attribute__((always_inline)) void fit_face_begin(int32_t n, const double *xyz,
                                                                 const int32_t *idx, face_fit *w)
{
    double c[3] = {0.0, 0.0, 0.0};
    for (int32_t k = 0; k < n; ++k) {
        const double *p = xyz + 3 * (size_t)idx[k];
        w->x[k][0] = p[0], w->x[k][1] = p[1], w->x[k][2] = p[2];
        c[0] += p[0], c[1] += p[1], c[2] += p[2];
    }
    const double inv = 1.0 / (double)n;
    c[0] *= inv, c[1] *= inv, c[2] *= inv;
    double a[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    for (int32_t k = 0; k < n; ++k) {
        const double dx = w->x[k][0] - c[0], dy = w->x[k][1] - c[1], dz = w->x[k][2] - c[2];
        a[0] += dx * dx, a[1] += dx * dy, a[2] += dx * dz;
        a[3] += dy * dy, a[4] += dy * dz, a[5] += dz * dz;
    }
    memcpy(w->c, c, sizeof c);
    memcpy(w->a, a, sizeof a);
}

/* Given the unit normal nn of the face: its offset, largest distance, sum
 * of squared distances, mean edge length, and the floor's test. Returns
 * whether some corner is below its floor. */
static inline __attribute__((always_inline)) int fit_face_end(
    int32_t n, const face_fit *w, const double nn[3], double normal[3], double *offset,
    double *max_distance, double *square_sum, double *edge_mean, const double *floor,
    double *corner_cos)
{
    const double *c = w->c;
    double dmax = 0.0, dsum = 0.0, esum = 0.0;
    double e[FIT_MAX_CORNERS][3], ee[FIT_MAX_CORNERS];
    for (int32_t k = 0; k < n; ++k) {
        const double *p = w->x[k], *q = w->x[k + 1 < n ? k + 1 : 0];
        const double d = fabs(nn[0] * (p[0] - c[0]) + nn[1] * (p[1] - c[1]) + nn[2] * (p[2] - c[2]));
        if (d > dmax)
            dmax = d;
        dsum += d * d;
        e[k][0] = q[0] - p[0], e[k][1] = q[1] - p[1], e[k][2] = q[2] - p[2];
        ee[k] = dot3(e[k], e[k]);
        esum += sqrt(ee[k]);
    }
    normal[0] = nn[0], normal[1] = nn[1], normal[2] = nn[2];
    *offset = -dot3(nn, c);
    *max_distance = dmax;
    const double rms = sqrt(dsum / (double)n);
    *square_sum = rms * rms * (double)n;
    *edge_mean = esum / (double)n;
    int below = 0;
    if (floor)
        for (int32_t k = 0; k < n; ++k) {
            const int32_t before = k > 0 ? k - 1 : n - 1;
            const double uv = -dot3(e[before], e[k]), uu = ee[before], vv = ee[k];
            double cosine = -1.0; /* any value not above the floor */
            if (!(uu > 0.0 && vv > 0.0))
                cosine = 1.0; /* as corner_cosine: an edge without length */
            else if (uv > 0.0 && uv * uv > (1.0 - 1e-9) * (floor[k] * floor[k]) * (uu * vv))
                cosine = uv / sqrt(uu * vv);
            corner_cos[k] = cosine;
            below |= cosine > floor[k];
        }
    return below;
}

/* Face f the general way: facet_face_measure, then the floor's test. */
static int fit_face_general(facet_planarizer *s, int32_t f, int floor_on)
{
    const int32_t b = s->face_start[f], n = s->face_start[f + 1] - b;
    const int32_t *fv = s->face_vertices;
    double rms;
    s->face_edge[f] = facet_face_measure(n, s->q, fv + b, s->normal + 3 * (size_t)f, &s->offset[f],
                                         &s->face_dev[f], &rms);
    s->face_sq[f] = rms * rms * (double)n;
    int below = 0;
    for (int32_t k = 0; floor_on && k < n; ++k) {
        const double c = corner_cosine(s->q, fv[b + (k > 0 ? k - 1 : n - 1)], fv[b + k],
                                       fv[b + (k + 1 < n ? k + 1 : 0)]);
        s->corner_cos[b + k] = c;
        below |= c > s->corner_floor[b + k];
    }
    return below;
}

#define FIT_FACE_END(n_, f_, w_, nn_)                                                             \
    fit_face_end((n_), (w_), (nn_), s->normal + 3 * (size_t)(f_), &s->offset[f_], &s->face_dev[f_], \
                 &s->face_sq[f_], &s->face_edge[f_], floor_on ? s->corner_floor + start[f_] : NULL, \
                 floor_on ? s->corner_cos + start[f_] : NULL)

/* Faces f and g = f + 1 (g may be past the last face): in a pair through the
 * eigenvector solver (facet_sym3_smallest_eigenvector2) when both have at
 * most FIT_MAX_CORNERS corners, quads with their loops unrolled. */
static inline __attribute__((always_inline)) int fit_pair(facet_planarizer *s, int32_t f, int floor_on)
{
    const int32_t nf = s->nf, g = f + 1;
    const int32_t *start = s->face_start, *fv = s->face_vertices;
    const double *q = s->q;
    const int32_t nf0 = start[f + 1] - start[f], ng = g < nf ? start[g + 1] - start[g] : 0;
    int below_f = 0, below_g = 0;
    if (nf0 == 4 && ng == 4) {
        face_fit wf, wg;
        double nnf[3], nng[3];
        fit_face_begin(4, q, fv + start[f], &wf);
        fit_face_begin(4, q, fv + start[g], &wg);
        facet_sym3_smallest_eigenvector2(wf.a, wg.a, nnf, nng);
        below_f = FIT_FACE_END(4, f, &wf, nnf);
        below_g = FIT_FACE_END(4, g, &wg, nng);
    } else if (nf0 <= FIT_MAX_CORNERS && ng >= 3 && ng <= FIT_MAX_CORNERS) {
        face_fit wf, wg;
        double nnf[3], nng[3];
        fit_face_begin(nf0, q, fv + start[f], &wf);
        fit_face_begin(ng, q, fv + start[g], &wg);
        facet_sym3_smallest_eigenvector2(wf.a, wg.a, nnf, nng);
        below_f = FIT_FACE_END(nf0, f, &wf, nnf);
        below_g = FIT_FACE_END(ng, g, &wg, nng);
    } else {
        below_f = fit_face_general(s, f, floor_on);
        if (g < nf)
            below_g = fit_face_general(s, g, floor_on);
    }
    if (floor_on) {
        s->face_guard[f] = (uint8_t)below_f;
        if (g < nf)
            s->face_guard[g] = (uint8_t)below_g;
    }
    return below_f || below_g;
}

/* Elements per block of the energy's sums (FACET_ENERGY_BLOCKS): a multiple
 * of 8, so that the plane fit's groups of eight faces fall in one block. */
int32_t facet_pl_energy_block_size(int32_t n)
{
    int32_t size = n / FACET_ENERGY_BLOCKS + (n % FACET_ENERGY_BLOCKS != 0);
    size = size > FACET_ENERGY_BLOCK_MIN ? size : FACET_ENERGY_BLOCK_MIN;
    return (size + 7) / 8 * 8;
}

/* The corner count of faces f..f+3 when they exist, have one size that the
 * SIMD lanes take, and sit one after another in face_vertices; else 0. */
static inline int32_t same_size4(const int32_t *start, int32_t nf, int32_t f)
{
    if (f + 4 > nf)
        return 0;
    const int32_t n = start[f + 1] - start[f];
    return n >= 3 && n <= FACET_LANE_CORNERS_MAX && start[f + 2] - start[f + 1] == n &&
                   start[f + 3] - start[f + 2] == n && start[f + 4] - start[f + 3] == n
               ? n
               : 0;
}

/* The corner count of faces f..f+15 when they are two same_size4 fours of
 * one size each and of one size together (sixteen faces one after another
 * in face_vertices); else 0. */
static inline int32_t same_size16(const int32_t *start, int32_t nf, int32_t f)
{
    const int32_t n = same_size4(start, nf, f);
    return n && same_size4(start, nf, f + 4) == n && same_size4(start, nf, f + 8) == n &&
                   same_size4(start, nf, f + 12) == n
               ? n
               : 0;
}

/* The SIMD lanes' outputs from face f_ on (facet_face_measure4/8/16) */
#define LANE_OUTPUTS(f_)                                                                           \
    s->normal + 3 * (size_t)(f_), s->offset + (f_), s->face_dev + (f_), s->face_sq + (f_),         \
        s->face_edge + (f_), floor_on ? s->corner_floor + start[f_] : NULL,                        \
        floor_on ? s->corner_cos + start[f_] : NULL, floor_on ? s->face_guard + (f_) : NULL

/* The planes: best fit (the planarity measurement), then the regularised
 * normals when the face-normal Laplacian is on. With the angle floor on, the
 * same pass tests the corners against it (face_guard, corner_cos); returns
 * whether some corner is below its floor. Faces go in eights: four faces of
 * one size in SIMD lanes, two such fours side by side (facet_face_measure8,
 * facet_face_measure4); others in pairs (fit_pair), so that their
 * eigenvectors' Newton steps overlap. Two eights of one size go together
 * (facet_face_measure16: in the AVX-512 copy, two vectors of eight whose
 * Newton steps overlap; 12% less time per L/L iteration on quads). Every
 * face gets the same bits as alone, whatever its group. */
/* Faces f..f+7 (those < nf), as fit_planes says; returns whether some
 * corner is below its floor. */
static inline int fit_group(facet_planarizer *s, int32_t f, int lanes, int floor_on)
{
    const int32_t nf = s->nf;
    const int32_t *start = s->face_start, *fv = s->face_vertices;
    const double *q = s->q;
    const int32_t na = lanes ? same_size4(start, nf, f) : 0;
    const int32_t nb = lanes ? same_size4(start, nf, f + 4) : 0;
    if (na && nb)
        return facet_face_measure8(na, nb, q, fv + start[f], fv + start[f + 4], LANE_OUTPUTS(f));
    int below = 0;
    for (int32_t h = f; h < f + 8 && h < nf; h += 4) {
        const int32_t n = h == f ? na : nb;
        if (n) {
            below = facet_face_measure4(n, q, fv + start[h], LANE_OUTPUTS(h)) || below;
            continue;
        }
        below = fit_pair(s, h, floor_on) || below;
        if (h + 2 < nf)
            below = fit_pair(s, h + 2, floor_on) || below;
    }
    return below;
}

static int fit_planes(facet_planarizer *s, double mu, int nthreads, int energy)
{
    const int32_t nf = s->nf;
    const int32_t *start = s->face_start, *fv = s->face_vertices;
    const double *q = s->q;
    const int floor_on = s->o.angle_floor > 0.0;
    const int lanes = !s->scalar_kernels;
    const int32_t groups = nf / 8 + (nf % 8 != 0);
    /* The groups go to the threads in the energy's blocks; with energy, the
     * faces' planarity energies (the face pass's e_con when no other term
     * is on) are summed per block as they are fitted. */
    const int32_t size = facet_pl_energy_block_size(nf), blocks = nf / size + (nf % size != 0);
    const int32_t per_block = size / 8;
    if (energy)
        s->energy_blocks[0] = blocks;
    int guard = 0;
    /* and the largest planarity, read from cache after each group (maxima
     * are exact in any order: the same bits for any thread count) */
    double m_abs = 0.0, m_rel = 0.0;
    const double *weight = s->face_weight, *dev = s->face_dev, *edge = s->face_edge;
#pragma omp parallel for schedule(static) num_threads(nthreads) reduction(|| : guard) \
    reduction(max : m_abs, m_rel)
    for (int32_t block = 0; block < blocks; ++block) {
        double sum = 0.0;
        const int32_t last = groups - block * per_block < per_block ? groups : (block + 1) * per_block;
        for (int32_t group = block * per_block; group < last;) {
            const int32_t f = 8 * group;
            /* two groups at once where they are sixteen faces of one size */
            const int32_t n16 = lanes && group + 1 < last ? same_size16(start, nf, f) : 0;
            if (n16)
                guard = facet_face_measure16(n16, q, fv + start[f], LANE_OUTPUTS(f)) || guard;
            else
                guard = fit_group(s, f, lanes, floor_on) || guard;
            const int32_t end = f + (n16 ? 16 : 8) < nf ? f + (n16 ? 16 : 8) : nf;
            group += n16 ? 2 : 1;
            for (int32_t h = f; energy && h < end; ++h)
                sum += face_weight(s, h) * s->face_sq[h];
            for (int32_t h = f; h < end; ++h) {
                if (weight && !(weight[h] > 0.0))
                    continue;
                const double d = dev[h], e = edge[h];
                m_abs = facet_max(m_abs, d);
                /* divide only where the quotient may be a new largest (a
                 * multiplication with a margin of rounding says where) */
                if (!(d <= m_rel * e * (1.0 - 1e-12)))
                    m_rel = facet_max(m_rel, e > 0.0 ? d / e : (d > 0.0 ? INFINITY : 0.0));
            }
        }
        if (energy)
            s->energy_block[0][0][block] = 0.0, s->energy_block[0][1][block] = sum;
    }
    s->fit_max_abs = m_abs, s->fit_max_rel = m_rel;
    /* a regularizer: weighed by mu against the planarity's 1 - mu, so it
     * fades as the penalty hardens */
    const double lambda = mu < 1.0 ? s->o.normal_laplacian * mu / (1.0 - mu) : 0.0;
    if (!(lambda > 0.0))
        return guard;
    memcpy(s->normal_fit, s->normal, sizeof(double) * 3 * (size_t)nf);
#pragma omp parallel for schedule(static) num_threads(nthreads)
    for (int32_t f = 0; f < nf; ++f) {
        const double *nf0 = s->normal_fit + 3 * (size_t)f;
        double m[3] = {0.0, 0.0, 0.0};
        const int32_t b = s->face_adj_start[f], e = s->face_adj_start[f + 1];
        if (e == b)
            continue;
        for (int32_t k = b; k < e; ++k) {
            const double *ng = s->normal_fit + 3 * (size_t)s->face_adj[k];
            const double sign = dot3(ng, nf0) < 0.0 ? -1.0 : 1.0;
            for (int a = 0; a < 3; ++a)
                m[a] += sign * ng[a];
        }
        for (int a = 0; a < 3; ++a)
            m[a] /= (double)(e - b);
        /* scatter of the face about its centroid */
        const int32_t n = start[f + 1] - start[f];
        const int32_t *idx = fv + start[f];
        double c[3];
        centroid_indexed(n, q, idx, c);
        double sc[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
        for (int32_t k = 0; k < n; ++k) {
            const double *x = q + 3 * (size_t)idx[k];
            const double d[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
            sc[0] += d[0] * d[0], sc[1] += d[0] * d[1], sc[2] += d[0] * d[2];
            sc[3] += d[1] * d[1], sc[4] += d[1] * d[2], sc[5] += d[2] * d[2];
        }
        /* minimise n^T S n - lambda * corners * (m . n)^2 over unit n */
        const double w = lambda * (double)n;
        sc[0] -= w * m[0] * m[0], sc[1] -= w * m[0] * m[1], sc[2] -= w * m[0] * m[2];
        sc[3] -= w * m[1] * m[1], sc[4] -= w * m[1] * m[2], sc[5] -= w * m[2] * m[2];
        double nn[3];
        facet_sym3_smallest_eigenvector(sc, nn);
        if (dot3(nn, nf0) < 0.0)
            nn[0] = -nn[0], nn[1] = -nn[1], nn[2] = -nn[2];
        double *out = s->normal + 3 * (size_t)f;
        if (isfinite(nn[0]) && isfinite(nn[1]) && isfinite(nn[2]) && normalize3(nn) > 0.0) {
            out[0] = nn[0], out[1] = nn[1], out[2] = nn[2];
            s->offset[f] = -dot3(nn, c);
        }
    }
    return guard;
}

/* A vertex's data term at x: the tangential and normal parts of its move
 * from the control position (the control normal splits them). */
static inline double vertex_data_energy(const facet_planarizer *s, const double *x, int32_t v)
{
    const double *pv = s->p + 3 * (size_t)v, *nu = s->vertex_normal + 3 * (size_t)v;
    const double d[3] = {x[0] - pv[0], x[1] - pv[1], x[2] - pv[2]};
    const double dn = dot3(d, nu), dd = dot3(d, d);
    return s->o.data_tangent * (dd - dn * dn) + s->o.data_normal * dn * dn;
}

/* Whether the vertices' part of the safeguard's energy is the data term
 * alone (the default): no term that reads a neighbour, the reference
 * surface or the boundary, no angle floor. Anderson's extrapolation then
 * sums it as it writes the iterate (facet_pl_vertex_data_energy), in the
 * blocks and the order of facet_pl_local_step's pass, which it saves: at a
 * million faces that pass read 72 MB per iteration. */
int facet_pl_vertex_energy_plain(const facet_planarizer *s)
{
    const facet_planarize_options *o = &s->o;
    return o->anderson > 0 && !(o->surface_weight > 0.0 && s->reference) && !(o->laplacian > 0.0) &&
           !(o->boundary_fairness > 0.0) && o->boundary != FACET_BOUNDARY_SLIDING &&
           !(o->angle_floor > 0.0);
}

/* The data energy of vertices v0..v1-1 at q, summed in vertex order: one
 * block of facet_pl_local_step's vertex pass when the energy is plain. */
double facet_pl_vertex_data_energy(const facet_planarizer *s, const double *q, int32_t v0, int32_t v1)
{
    double sum = 0.0;
    for (int32_t v = v0; v < v1; ++v)
        if (!s->fixed[v])
            sum += vertex_data_energy(s, q + 3 * (size_t)v, v);
    return sum;
}

facet_status facet_pl_local_step(facet_planarizer *s, double mu, int nthreads, facet_error *error)
{
    const int32_t nv = s->nv, nf = s->nf;
    const facet_planarize_options *o = &s->o;
    const double *p = s->p, *q = s->q;
    const int shape = o->shape != FACET_SHAPE_NONE && o->shape_weight > 0.0;
    const int circular = o->circular > 0.0, parallel = o->parallelogram > 0.0;
    const int energies = o->anderson > 0; /* only the safeguard reads them */
    /* some corner below its angle floor; the faces' energies summed by the
     * fit unless another face term is on (the face pass below then) */
    const int guard = fit_planes(s, mu, nthreads, energies && !shape && !circular && !parallel);
    const int surface = o->surface_weight > 0.0 && s->reference;
    if (surface) { /* closest points of the reference surface, in model units */
        for (size_t k = 0; k < 3 * (size_t)nv; ++k)
            s->surface_query[k] = q[k] * s->scale + s->centre[k % 3];
        const facet_status status = facet_surface_closest(s->reference, nv, s->surface_query, nthreads,
                                                          s->surface_point, NULL, NULL,
                                                          s->surface_normal, error);
        if (status < 0)
            return status;
        const double inv = 1.0 / s->scale;
        for (size_t k = 0; k < 3 * (size_t)nv; ++k)
            s->surface_point[k] = (s->surface_point[k] - s->centre[k % 3]) * inv;
    }
    const int sliding = o->boundary == FACET_BOUNDARY_SLIDING;
    /* the residuals are read only while their terms are on (planarize.c) */
    const int face_residuals = circular || parallel;
    if (shape || circular || parallel) {
        const int32_t size = facet_pl_energy_block_size(nf), blocks = nf / size + (nf % size != 0);
        s->energy_blocks[0] = blocks;
#pragma omp parallel for schedule(static) num_threads(nthreads)
        for (int32_t block = 0; block < blocks; ++block) {
            double sum_mu = 0.0, sum_con = 0.0;
            const int32_t last = nf - block * size < size ? nf : (block + 1) * size;
            for (int32_t f = block * size; f < last; ++f) {
                const int32_t b = s->face_start[f], n = s->face_start[f + 1] - b;
                const int32_t *idx = s->face_vertices + b;
                double e_mu = 0.0, e_con = face_weight(s, f) * s->face_sq[f], residual = 0.0;
                if (shape) {
                    const double *cp = s->control_centroid + 3 * (size_t)f;
                    double cq[3];
                    centroid_indexed(n, q, idx, cq);
                    double c[9] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0}, xx = 0.0;
                    for (int32_t k = 0; k < n; ++k) {
                        const double *x = p + 3 * (size_t)idx[k], *y = q + 3 * (size_t)idx[k];
                        const double dx[3] = {x[0] - cp[0], x[1] - cp[1], x[2] - cp[2]};
                        const double dy[3] = {y[0] - cq[0], y[1] - cq[1], y[2] - cq[2]};
                        for (int i = 0; i < 3; ++i)
                            for (int j = 0; j < 3; ++j)
                                c[3 * i + j] += dy[i] * dx[j];
                        xx += dot3(dx, dx);
                    }
                    double *sr = s->shape + 9 * (size_t)f;
                    facet_pl_procrustes(c, o->shape == FACET_SHAPE_ASAP, sr);
                    if (o->shape == FACET_SHAPE_ASAP) {
                        const double inv = xx > 0.0 ? 1.0 / xx : 0.0;
                        for (int k = 0; k < 9; ++k)
                            sr[k] *= inv;
                    }
                    double e = 0.0;
                    for (int32_t k = 0; k < n; ++k) {
                        const double *x = p + 3 * (size_t)idx[k], *y = q + 3 * (size_t)idx[k];
                        const double dx[3] = {x[0] - cp[0], x[1] - cp[1], x[2] - cp[2]};
                        for (int i = 0; i < 3; ++i) {
                            const double t = sr[3 * i] * dx[0] + sr[3 * i + 1] * dx[1] + sr[3 * i + 2] * dx[2];
                            const double r = y[i] - cq[i] - t;
                            e += r * r;
                        }
                    }
                    e_mu += o->shape_weight * e;
                }
                if (circular) {
                    double *t = s->circle_target + 3 * (size_t)b;
                    facet_pl_circle_targets(n, q, idx, s->normal + 3 * (size_t)f, t);
                    double e = 0.0, worst = 0.0;
                    for (int32_t k = 0; k < n; ++k) {
                        const double *y = q + 3 * (size_t)idx[k];
                        const double d[3] = {y[0] - t[3 * k], y[1] - t[3 * k + 1], y[2] - t[3 * k + 2]};
                        const double d2 = dot3(d, d);
                        e += d2;
                        worst = facet_max(worst, d2);
                    }
                    e_con += o->circular * e;
                    residual = facet_max(residual, sqrt(worst) / facet_max(s->face_edge[f], 1e-300));
                }
                if (parallel && n == 4) {
                    const double *y0 = q + 3 * (size_t)idx[0], *y1 = q + 3 * (size_t)idx[1];
                    const double *y2 = q + 3 * (size_t)idx[2], *y3 = q + 3 * (size_t)idx[3];
                    const double r[3] = {y0[0] - y1[0] + y2[0] - y3[0], y0[1] - y1[1] + y2[1] - y3[1],
                                         y0[2] - y1[2] + y2[2] - y3[2]};
                    const double r2 = dot3(r, r);
                    e_con += o->parallelogram * r2;
                    residual = facet_max(residual, sqrt(r2) / facet_max(s->face_edge[f], 1e-300));
                }
                sum_mu += e_mu, sum_con += e_con;
                if (face_residuals)
                    s->face_residual[f] = residual;
            }
            s->energy_block[0][0][block] = sum_mu, s->energy_block[0][1][block] = sum_con;
        }
    }

    if (o->angle_floor > 0.0) {
        if (!guard && s->guard_on) /* (all zero already unless the last step held a corner) */
            memset(s->guard_count, 0, sizeof(double) * (size_t)nv);
    }
    s->guard_on = guard;
    if (!energies && !sliding && !guard)
        return FACET_OK;
    if (s->vertex_energy_done) { /* summed by Anderson's extrapolation */
        s->vertex_energy_done = 0;
        return FACET_OK;
    }
    const int32_t size = facet_pl_energy_block_size(nv), blocks = nv / size + (nv % size != 0);
    s->energy_blocks[1] = blocks;
#pragma omp parallel for schedule(static) num_threads(nthreads)
    for (int32_t block = 0; block < blocks; ++block) {
        double sum_mu = 0.0, sum_con = 0.0;
        const int32_t last = nv - block * size < size ? nv : (block + 1) * size;
        for (int32_t v = block * size; v < last; ++v) {
            const double *x = q + 3 * (size_t)v;
            double e_mu = 0.0, e_con = 0.0, residual = 0.0;
            if (!s->fixed[v]) {
                e_mu += vertex_data_energy(s, x, v);
                if (surface) {
                    const double *sp = s->surface_point + 3 * (size_t)v, *sn = s->surface_normal + 3 * (size_t)v;
                    const double ds = (x[0] - sp[0]) * sn[0] + (x[1] - sp[1]) * sn[1] + (x[2] - sp[2]) * sn[2];
                    e_mu += o->surface_weight * ds * ds;
                }
            }
            if (o->laplacian > 0.0 && !s->on_boundary[v]) {
                double r[3] = {x[0], x[1], x[2]};
                for (int32_t k = s->vertex_adj_start[v]; k < s->vertex_adj_start[v + 1]; ++k) {
                    const double *y = q + 3 * (size_t)s->vertex_adj[k];
                    for (int a = 0; a < 3; ++a)
                        r[a] -= s->laplace_weight[k] * y[a];
                }
                e_mu += o->laplacian * dot3(r, r);
            }
            if (o->boundary_fairness > 0.0 && s->boundary_prev[v] >= 0) {
                const double *a = q + 3 * (size_t)s->boundary_prev[v], *c = q + 3 * (size_t)s->boundary_next[v];
                const double r[3] = {a[0] - 2.0 * x[0] + c[0], a[1] - 2.0 * x[1] + c[1], a[2] - 2.0 * x[2] + c[2]};
                e_mu += o->boundary_fairness * dot3(r, r);
            }
            if (sliding && s->boundary_prev[v] >= 0 && !s->fixed[v]) {
                /* closest point on the control boundary within two segments either side */
                int32_t chain[5];
                chain[2] = v;
                chain[1] = s->boundary_prev[v], chain[0] = s->boundary_prev[chain[1]];
                chain[3] = s->boundary_next[v], chain[4] = s->boundary_next[chain[3]];
                double best = INFINITY, point[3], tangent[3];
                for (int k = 0; k < 4; ++k) {
                    if (chain[k] < 0 || chain[k + 1] < 0)
                        continue;
                    double pt[3], tg[3];
                    const double d2 = closest_on_segment(x, p + 3 * (size_t)chain[k],
                                                         p + 3 * (size_t)chain[k + 1], pt, tg);
                    if (d2 < best) {
                        best = d2;
                        memcpy(point, pt, sizeof point);
                        memcpy(tangent, tg, sizeof tangent);
                    }
                }
                memcpy(s->slide_target + 3 * (size_t)v, point, sizeof point);
                memcpy(s->slide_tangent + 3 * (size_t)v, tangent, sizeof tangent);
                e_con += best;
                residual = sqrt(best);
            }
            if (guard) { /* the corners below their floor that v belongs to */
                double count = 0.0, sum[3] = {0.0, 0.0, 0.0};
                for (int32_t k = s->vertex_start[v]; k < s->vertex_start[v + 1]; ++k) {
                    const int32_t f = s->vertex_faces[k];
                    if (!s->face_guard[f])
                        continue;
                    const int32_t b = s->face_start[f], n = s->face_start[f + 1] - b;
                    int32_t at = 0;
                    while (s->face_vertices[b + at] != v)
                        ++at;
                    for (int role = 0; role < 3; ++role) { /* v as a, c or b of a corner */
                        const int32_t corner = (at + 1 - role + n) % n;
                        if (!(s->corner_cos[b + corner] > s->corner_floor[b + corner]))
                            continue;
                        double t[3];
                        corner_target(q, s->face_vertices[b + (corner + n - 1) % n], s->face_vertices[b + corner],
                                      s->face_vertices[b + (corner + 1) % n], s->normal + 3 * (size_t)f,
                                      s->corner_cos[b + corner], s->corner_floor[b + corner], role, t);
                        const double d[3] = {x[0] - t[0], x[1] - t[1], x[2] - t[2]};
                        e_con += dot3(d, d);
                        sum[0] += t[0], sum[1] += t[1], sum[2] += t[2];
                        count += 1.0;
                    }
                }
                s->guard_count[v] = count;
                memcpy(s->guard_sum + 3 * (size_t)v, sum, sizeof sum);
            }
            sum_mu += e_mu, sum_con += e_con;
            if (sliding)
                s->vertex_residual[v] = residual;
        }
        s->energy_block[1][0][block] = sum_mu, s->energy_block[1][1][block] = sum_con;
    }
    return FACET_OK;
}

/* The energy: the blocks' sums (facet_pl_local_step) added in a fixed order. */
void facet_pl_energy(const facet_planarizer *s, double *energy_mu, double *energy_con)
{
    double mu = 0.0, con = 0.0;
    for (int part = 0; part < 2; ++part) /* faces, then vertices */
        for (int32_t block = 0; block < s->energy_blocks[part]; ++block)
            mu += s->energy_block[part][0][block], con += s->energy_block[part][1][block];
    *energy_mu = mu;
    *energy_con = con;
}

/* ---- the local/local vertex step ---------------------------------------- */

/* Adds w * (t t^T) to the 3x3 symmetric a[6] (00 01 02 11 12 22). */
static void add_outer(double a[6], double w, const double t[3])
{
    a[0] += w * t[0] * t[0], a[1] += w * t[0] * t[1], a[2] += w * t[0] * t[2];
    a[3] += w * t[1] * t[1], a[4] += w * t[1] * t[2], a[5] += w * t[2] * t[2];
}

static void add_matvec(double b[3], const double a[6], const double x[3])
{
    b[0] += a[0] * x[0] + a[1] * x[1] + a[2] * x[2];
    b[1] += a[1] * x[0] + a[3] * x[1] + a[4] * x[2];
    b[2] += a[2] * x[0] + a[4] * x[1] + a[5] * x[2];
}

/* The 3x3 solve A x = b of the vertex step (A's upper triangle a[6]) by
 * LDL^T: Cholesky's accuracy without its three square roots. The pivots
 * d0 = a0, d1 = e1 / a0 and d2 = h / (a0 e1) come from the 2x2 and 3x3
 * leading minors' products (e1 = a0 a3 - a1^2, h = e1 k - g^2), so that
 * the three reciprocals are independent divisions that run side by side,
 * not a chain of three (about 7% of an L/L iteration). The same
 * cancellations as in the usual order, so the same accuracy (unlike the
 * adjugate's one division, which loses L/L's floor). T is double, or v4d
 * for four vertices in SIMD lanes (the same operations in the same order). */
#define LDL3_SOLVE(T, a, b, x0, x1, x2)                                                            \
    do {                                                                                           \
        const T e1_ = (a)[0] * (a)[3] - (a)[1] * (a)[1];                                           \
        const T g_ = (a)[0] * (a)[4] - (a)[1] * (a)[2];                                            \
        const T k_ = (a)[0] * (a)[5] - (a)[2] * (a)[2];                                            \
        const T h_ = e1_ * k_ - g_ * g_;                                                           \
        const T i0_ = 1.0 / (a)[0], r1_ = 1.0 / e1_, i2_ = ((a)[0] * e1_) / h_;                   \
        const T i1_ = (a)[0] * r1_, l21_ = g_ * r1_;                                               \
        const T l10_ = (a)[1] * i0_, l20_ = (a)[2] * i0_;                                          \
        const T z1_ = (b)[1] - l10_ * (b)[0];                                                      \
        const T z2_ = (b)[2] - l20_ * (b)[0] - l21_ * z1_;                                         \
        (x2) = z2_ * i2_;                                                                          \
        (x1) = z1_ * i1_ - l21_ * (x2);                                                            \
        (x0) = (b)[0] * i0_ - l10_ * (x1) - l20_ * (x2);                                           \
    } while (0)

/* The 3x3 systems of vertices v0..v0+3 in SIMD lanes (lanes past the last
 * vertex repeat v0), when the only terms are the data term and the faces'
 * planes: the scalar loop's arithmetic in its order, every lane adding its
 * own faces' terms (pw n n^T, pw d n, formed from the face's plane as the
 * scalar loop's per-face pass forms them) in its own order; a lane with
 * fewer faces than another keeps its sums (a select, not an addition). */
/* face j's term of the four lanes' faces f0..f3 (plain4_system) */
#define ADD_ALL(sum, term) ((sum) + (term))
#define ADD_TAKEN(sum, term) v4_select(take, (sum) + (term), (sum))
#define PLAIN4_FACE(ADD)                                                                           \
    do {                                                                                           \
        const v4d n0 = FACE_LANES(normal, 3, 0), n1 = FACE_LANES(normal, 3, 1), n2 = FACE_LANES(normal, 3, 2);    \
        const v4d d = FACE_LANES(offset, 1, 0);                                                         \
        const v4d pw = fw ? w * FACE_LANES(fw, 1, 0) : (v4d){w, w, w, w} * 1.0;                         \
        const v4d pn0 = pw * n0, pn1 = pw * n1, pn2 = pw * n2, pd = pw * d;                        \
        a[0] = ADD(a[0], pn0 * n0), a[1] = ADD(a[1], pn0 * n1), a[2] = ADD(a[2], pn0 * n2);        \
        a[3] = ADD(a[3], pn1 * n1), a[4] = ADD(a[4], pn1 * n2), a[5] = ADD(a[5], pn2 * n2);        \
        b[0] = ADD(b[0], -(pd * n0)), b[1] = ADD(b[1], -(pd * n1)), b[2] = ADD(b[2], -(pd * n2));  \
    } while (0)
#define FACE_LANES(array, k, c) ((v4d){(array)[(k) * (size_t)f0 + (c)], (array)[(k) * (size_t)f1 + (c)], \
                                 (array)[(k) * (size_t)f2 + (c)], (array)[(k) * (size_t)f3 + (c)]})

static inline __attribute__((always_inline)) void plain4_system(const facet_planarizer *s, int32_t v0,
                                                                 double mu, v4d a[6], v4d b[3])
{
    const facet_planarize_options *o = &s->o;
    const double w = 1.0 - mu, data_t = mu * o->data_tangent;
    const double data_nt = mu * (o->data_normal - o->data_tangent);
    const int32_t *vs = s->vertex_start, *vf = s->vertex_faces;
    const double *normal = s->normal, *offset = s->offset, *fw = s->face_weight;
    /* vectors built from scalars in registers (lane stores then a vector
     * load would stall) */
    const int32_t nv = s->nv;
    const int32_t u1 = v0 + 1 < nv ? v0 + 1 : v0, u2 = v0 + 2 < nv ? v0 + 2 : v0;
    const int32_t u3 = v0 + 3 < nv ? v0 + 3 : v0;
    const double *vn = s->vertex_normal, *vp = s->p;
#define LANES(array, c) ((v4d){(array)[3 * (size_t)v0 + (c)], (array)[3 * (size_t)u1 + (c)], \
                              (array)[3 * (size_t)u2 + (c)], (array)[3 * (size_t)u3 + (c)]})
    const v4d p[3] = {LANES(vp, 0), LANES(vp, 1), LANES(vp, 2)};
    const int32_t start[4] = {vs[v0], vs[u1], vs[u2], vs[u3]};
    const int32_t degree[4] = {vs[v0 + 1] - start[0], vs[u1 + 1] - start[1], vs[u2 + 1] - start[2],
                               vs[u3 + 1] - start[3]};
    int32_t most = degree[0], least = degree[0];
    for (int l = 1; l < 4; ++l) {
        most = degree[l] > most ? degree[l] : most;
        least = degree[l] < least ? degree[l] : least;
    }
    /* data: mu (a_t I + (a_n - a_t) nu nu^T) (q - p), as add_outer and
     * add_matvec form it; with a_n = a_t (point data, the default) the
     * control normals' terms are zeros that leave the sums' bits as they
     * are (data_t + -0 = data_t, 0 + -0 = +0), so they are not read: at a
     * million faces, 24 MB a step */
    if (data_nt != 0.0) {
        const v4d nu[3] = {LANES(vn, 0), LANES(vn, 1), LANES(vn, 2)};
        a[0] = data_t + data_nt * nu[0] * nu[0], a[1] = 0.0 + data_nt * nu[0] * nu[1];
        a[2] = 0.0 + data_nt * nu[0] * nu[2], a[3] = data_t + data_nt * nu[1] * nu[1];
        a[4] = 0.0 + data_nt * nu[1] * nu[2], a[5] = data_t + data_nt * nu[2] * nu[2];
    } else {
        const v4d diagonal = {data_t, data_t, data_t, data_t}, off = {0.0, 0.0, 0.0, 0.0};
        a[0] = diagonal, a[1] = off, a[2] = off, a[3] = diagonal, a[4] = off, a[5] = diagonal;
    }
#undef LANES
    b[0] = 0.0 + (a[0] * p[0] + a[1] * p[1] + a[2] * p[2]);
    b[1] = 0.0 + (a[1] * p[0] + a[3] * p[1] + a[4] * p[2]);
    b[2] = 0.0 + (a[2] * p[0] + a[4] * p[1] + a[5] * p[2]);
    /* every lane's faces up to the least degree, then the rest with a
     * select (a lane past its own faces keeps its sums) */
    for (int32_t j = 0; j < least; ++j) {
        const int32_t f0 = vf[start[0] + j], f1 = vf[start[1] + j], f2 = vf[start[2] + j];
        const int32_t f3 = vf[start[3] + j];
        PLAIN4_FACE(ADD_ALL);
    }
    for (int32_t j = least; j < most; ++j) {
        const int32_t f0 = j < degree[0] ? vf[start[0] + j] : vf[start[0]];
        const int32_t f1 = j < degree[1] ? vf[start[1] + j] : f0;
        const int32_t f2 = j < degree[2] ? vf[start[2] + j] : f0;
        const int32_t f3 = j < degree[3] ? vf[start[3] + j] : f0;
        const v4i take = {-(int64_t)(j < degree[0]), -(int64_t)(j < degree[1]), -(int64_t)(j < degree[2]),
                          -(int64_t)(j < degree[3])};
        PLAIN4_FACE(ADD_TAKEN);
    }
#undef PLAIN4_FACE
#undef FACE_LANES
#undef ADD_ALL
#undef ADD_TAKEN
}

/* 3x3 LDL^T, as the scalar loop, and the lanes' results written */
static inline __attribute__((always_inline)) int plain4_solve(const facet_planarizer *s, int32_t v0,
                                                              const v4d a[6], const v4d b[3], double *q_new)
{
    v4d x0, x1, x2;
    LDL3_SOLVE(v4d, a, b, x0, x1, x2);
    int finite = 1;
    for (int l = 0; l < 4 && v0 + l < s->nv; ++l) {
        const int32_t v = v0 + l;
        double *out = q_new + 3 * (size_t)v;
        const double *from = NULL;
        if (s->fixed[v])
            from = s->p + 3 * (size_t)v;
        else if (!(isfinite(x0[l]) && isfinite(x1[l]) && isfinite(x2[l])))
            from = s->q + 3 * (size_t)v, finite = 0;
        if (from)
            out[0] = from[0], out[1] = from[1], out[2] = from[2];
        else
            out[0] = x0[l], out[1] = x1[l], out[2] = x2[l];
    }
    return finite;
}

/* The vertex step of vertices v0..v0+7 (those < nv), when vertex_step_plain
 * says it may take the lanes. A fixed vertex keeps its control position.
 * Returns 0 if some result was not finite (that vertex keeps its previous
 * position). */
static inline __attribute__((always_inline)) int vertex_step_plain4_lanes(const facet_planarizer *s,
                                                                          int32_t v0, double mu,
                                                                          double *q_new)
{
    /* two fours of vertices: the solves' chains of dependent divisions side
     * by side */
    v4d a[6], b[3], a2[6], b2[3];
    plain4_system(s, v0, mu, a, b);
    if (v0 + 4 >= s->nv)
        return plain4_solve(s, v0, a, b, q_new);
    plain4_system(s, v0 + 4, mu, a2, b2);
    const int finite = plain4_solve(s, v0, a, b, q_new);
    return plain4_solve(s, v0 + 4, a2, b2, q_new) && finite;
}

static int vertex_step_plain4_base(const facet_planarizer *s, int32_t v0, double mu, double *q_new)
{
    return vertex_step_plain4_lanes(s, v0, mu, q_new);
}

#if FACET_HAVE_AVX2_CLONE
FACET_TARGET_AVX2 static int vertex_step_plain4_avx2(const facet_planarizer *s, int32_t v0, double mu,
                                                     double *q_new)
{
    return vertex_step_plain4_lanes(s, v0, mu, q_new);
}

FACET_TARGET_AVX512 static int vertex_step_plain4_avx512(const facet_planarizer *s, int32_t v0, double mu,
                                                         double *q_new)
{
    return vertex_step_plain4_lanes(s, v0, mu, q_new);
}
#endif

/* Whether the vertex step has only the data term (no surface) and the
 * faces' planes. */
static int vertex_step_plain(const facet_planarizer *s)
{
    const facet_planarize_options *o = &s->o;
    return !(o->surface_weight > 0.0 && s->reference) &&
           !(o->shape != FACET_SHAPE_NONE && o->shape_weight > 0.0) && !(o->circular > 0.0) &&
           !(o->parallelogram > 0.0) && !(o->laplacian > 0.0) && !(o->boundary_fairness > 0.0) &&
           o->boundary != FACET_BOUNDARY_SLIDING && !(o->angle_floor > 0.0 && s->guard_on);
}

/* Per vertex, with everything else fixed: minimise the vertex's own terms
 * (the paper's local forms, eq. 8), a 3x3 SPD system. Vertices are updated
 * Jacobi-style from the previous iterate, so the result does not depend on
 * the order or the thread count. Returns 0 if some result was not finite. */
int facet_pl_vertex_step(facet_planarizer *s, double mu, int nthreads)
{
    const int32_t nv = s->nv;
    const facet_planarize_options *o = &s->o;
    const double w = 1.0 - mu;
    const int shape = o->shape != FACET_SHAPE_NONE && o->shape_weight > 0.0;
    const int sliding = o->boundary == FACET_BOUNDARY_SLIDING;
    const double *q_old = s->q;
    double *q_new = s->q_next;
    const int extra = shape || o->circular > 0.0 || o->parallelogram > 0.0; /* per-face terms */
    if (!s->scalar_kernels && vertex_step_plain(s)) {
        int (*step4)(const facet_planarizer *, int32_t, double, double *) = vertex_step_plain4_base;
#if FACET_HAVE_AVX2_CLONE
        const int level = facet_simd_level();
        if (level > 0)
            step4 = level == 2 ? vertex_step_plain4_avx512 : vertex_step_plain4_avx2;
#endif
        const int32_t groups = nv / 8 + (nv % 8 != 0);
        int finite = 1;
#pragma omp parallel for schedule(static) num_threads(nthreads) reduction(&& : finite)
        for (int32_t g = 0; g < groups; ++g)
            finite = step4(s, 8 * g, mu, q_new) && finite;
        if (finite) { /* the new iterate becomes the current one */
            s->q_next = s->q;
            s->q = q_new;
        }
        return finite;
    }
    /* Each face's planarity term once per face rather than once per corner:
     * pw n n^T and pw d n, the same products the vertices add up. */
    double *terms = s->face_plane_terms;
#pragma omp parallel for schedule(static) num_threads(nthreads)
    for (int32_t f = 0; f < s->nf; ++f) {
        const double *n = s->normal + 3 * (size_t)f;
        const double pw = w * face_weight(s, f), d = s->offset[f];
        double *t = terms + 9 * (size_t)f;
        t[0] = pw * n[0] * n[0], t[1] = pw * n[0] * n[1], t[2] = pw * n[0] * n[2];
        t[3] = pw * n[1] * n[1], t[4] = pw * n[1] * n[2], t[5] = pw * n[2] * n[2];
        t[6] = pw * d * n[0], t[7] = pw * d * n[1], t[8] = pw * d * n[2];
    }
    int finite = 1;
#pragma omp parallel for schedule(static) num_threads(nthreads) reduction(&& : finite)
    for (int32_t v = 0; v < nv; ++v) {
        const double *pv = s->p + 3 * (size_t)v, *nu = s->vertex_normal + 3 * (size_t)v;
        double *out = q_new + 3 * (size_t)v;
        if (s->fixed[v]) {
            out[0] = pv[0], out[1] = pv[1], out[2] = pv[2];
            continue;
        }
        /* data: mu (a_t I + (a_n - a_t) nu nu^T) (q - p) */
        double a[6] = {mu * o->data_tangent, 0.0, 0.0, mu * o->data_tangent, 0.0, mu * o->data_tangent};
        add_outer(a, mu * (o->data_normal - o->data_tangent), nu);
        double b[3] = {0.0, 0.0, 0.0};
        add_matvec(b, a, pv);
        if (o->surface_weight > 0.0 && s->reference) { /* mu w (n . (q - s))^2 */
            const double *sn = s->surface_normal + 3 * (size_t)v, *sp = s->surface_point + 3 * (size_t)v;
            double m[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
            add_outer(m, mu * o->surface_weight, sn);
            for (int c = 0; c < 6; ++c)
                a[c] += m[c];
            /* during L/L's finish anchored at the iterate (pv), like the data
             * term: with its point on the surface, at mu_min, it held the
             * planarity at 1e-7 to 5e-6 (docs/solver-notes.md, "L/L's finish
             * with surface data") */
            add_matvec(b, m, s->finishing ? pv : sp);
        }
        for (int32_t k = s->vertex_start[v]; k < s->vertex_start[v + 1]; ++k) {
            const int32_t f = s->vertex_faces[k];
            const double *pt = terms + 9 * (size_t)f;
            a[0] += pt[0], a[1] += pt[1], a[2] += pt[2], a[3] += pt[3], a[4] += pt[4], a[5] += pt[5];
            b[0] -= pt[6], b[1] -= pt[7], b[2] -= pt[8];
            if (!extra)
                continue;
            const int32_t fb = s->face_start[f], fn = s->face_start[f + 1] - fb;
            int32_t corner = 0;
            while (s->face_vertices[fb + corner] != v)
                ++corner;
            if (shape && s->finishing) { /* anchored at the iterate (pv): a proximal pull */
                const double lw = mu * o->shape_weight;
                b[0] += lw * pv[0], b[1] += lw * pv[1], b[2] += lw * pv[2];
                a[0] += lw, a[3] += lw, a[5] += lw;
            } else if (shape) { /* target: current centroid + s R (p - control centroid) */
                const double *sr = s->shape + 9 * (size_t)f, *cp = s->control_centroid + 3 * (size_t)f;
                double cq[3] = {0.0, 0.0, 0.0};
                for (int32_t m = 0; m < fn; ++m)
                    for (int c = 0; c < 3; ++c)
                        cq[c] += q_old[3 * (size_t)s->face_vertices[fb + m] + c];
                const double dx[3] = {pv[0] - cp[0], pv[1] - cp[1], pv[2] - cp[2]};
                const double lw = mu * o->shape_weight;
                for (int c = 0; c < 3; ++c) {
                    const double t = cq[c] / (double)fn + sr[3 * c] * dx[0] + sr[3 * c + 1] * dx[1] +
                                     sr[3 * c + 2] * dx[2];
                    b[c] += lw * t;
                }
                a[0] += lw, a[3] += lw, a[5] += lw;
            }
            if (o->circular > 0.0) {
                const double *t = s->circle_target + 3 * (size_t)(fb + corner);
                const double cw = w * o->circular;
                b[0] += cw * t[0], b[1] += cw * t[1], b[2] += cw * t[2];
                a[0] += cw, a[3] += cw, a[5] += cw;
            }
            if (o->parallelogram > 0.0 && fn == 4) { /* v = prev + next - opposite */
                const double *yp = q_old + 3 * (size_t)s->face_vertices[fb + (corner + 3) % 4];
                const double *yn = q_old + 3 * (size_t)s->face_vertices[fb + (corner + 1) % 4];
                const double *yo = q_old + 3 * (size_t)s->face_vertices[fb + (corner + 2) % 4];
                const double cw = w * o->parallelogram;
                for (int c = 0; c < 3; ++c)
                    b[c] += cw * (yp[c] + yn[c] - yo[c]);
                a[0] += cw, a[3] += cw, a[5] += cw;
            }
        }
        /* the regularizers' targets: their neighbours' average, or during L/L's
         * finish the iterate itself (pv), like the data and shape terms */
        if (o->laplacian > 0.0 && !s->on_boundary[v]) {
            double t[3] = {pv[0], pv[1], pv[2]};
            if (!s->finishing) {
                t[0] = t[1] = t[2] = 0.0;
                for (int32_t k = s->vertex_adj_start[v]; k < s->vertex_adj_start[v + 1]; ++k)
                    for (int c = 0; c < 3; ++c)
                        t[c] += s->laplace_weight[k] * q_old[3 * (size_t)s->vertex_adj[k] + c];
            }
            const double lw = mu * o->laplacian;
            for (int c = 0; c < 3; ++c)
                b[c] += lw * t[c];
            a[0] += lw, a[3] += lw, a[5] += lw;
        }
        if (o->boundary_fairness > 0.0 && s->boundary_prev[v] >= 0) {
            const double *ya = q_old + 3 * (size_t)s->boundary_prev[v];
            const double *yc = q_old + 3 * (size_t)s->boundary_next[v];
            const double lw = 4.0 * mu * o->boundary_fairness;
            for (int c = 0; c < 3; ++c)
                b[c] += lw * (s->finishing ? pv[c] : 0.5 * (ya[c] + yc[c]));
            a[0] += lw, a[3] += lw, a[5] += lw;
        }
        if (sliding && s->boundary_prev[v] >= 0) { /* (I - t t^T)(q - target) */
            const double *t = s->slide_tangent + 3 * (size_t)v, *target = s->slide_target + 3 * (size_t)v;
            double m[6] = {w, 0.0, 0.0, w, 0.0, w};
            add_outer(m, -w, t);
            for (int c = 0; c < 6; ++c)
                a[c] += m[c];
            add_matvec(b, m, target);
        }
        if (o->angle_floor > 0.0 && s->guard_count[v] > 0.0) { /* angle floor targets */
            const double *t = s->guard_sum + 3 * (size_t)v, g = w * s->guard_count[v];
            b[0] += w * t[0], b[1] += w * t[1], b[2] += w * t[2];
            a[0] += g, a[3] += g, a[5] += g;
        }
        double x0, x1, x2;
        LDL3_SOLVE(double, a, b, x0, x1, x2);
        if (isfinite(x0) && isfinite(x1) && isfinite(x2)) {
            out[0] = x0, out[1] = x1, out[2] = x2;
        } else {
            out[0] = q_old[3 * (size_t)v], out[1] = q_old[3 * (size_t)v + 1], out[2] = q_old[3 * (size_t)v + 2];
            finite = 0;
        }
    }
    if (finite) { /* the new iterate becomes the current one: swap, no copy */
        s->q_next = s->q;
        s->q = q_new;
    }
    return finite;
}
