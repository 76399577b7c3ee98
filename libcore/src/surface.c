/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Closest points on a triangle surface: an AABB tree over the triangles,
 * best-first descent with pruning by box distance, and the closest point on
 * a triangle by Voronoi regions (Ericson, Real-Time Collision Detection,
 * 5.1.5), with zero-area triangles handled on their edges. */
#include "internal.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define LEAF_SIZE 4
#define STACK_SIZE 128
/* queries farther than this from the centre, in surface sizes, are pulled in */
#define FAR_LIMIT 1e100

typedef struct {
    double lo[3], hi[3];
    int32_t left;  /* child index, or -1 for a leaf */
    int32_t right; /* child index; for a leaf: first of order[] */
    int32_t count; /* leaf: number of triangles */
} node;

struct facet_surface {
    int32_t n_triangles;
    double centre[3];
    double scale;          /* normalised = (x - centre) * scale */
    double *corners;       /* 9 per triangle, normalised, in tree order */
    int32_t *order;        /* tree slot -> triangle index */
    unsigned char *flat;   /* per tree slot: 1 when the triangle has zero area */
    double *normals;       /* 3 per triangle (by triangle index), unit or 0 */
    int32_t *face;         /* triangle -> mesh face, or NULL */
    node *nodes;
    int32_t n_nodes;
};

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void sub3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[0] - b[0], c[1] = a[1] - b[1], c[2] = a[2] - b[2];
}

static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* Closest point to p on the segment a-b (a point when a == b). */
static void closest_on_segment(const double p[3], const double a[3], const double b[3],
                               double out[3])
{
    double ab[3], ap[3];
    sub3(b, a, ab);
    sub3(p, a, ap);
    const double len2 = dot3(ab, ab);
    double t = len2 > 0.0 ? dot3(ap, ab) / len2 : 0.0;
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    out[0] = a[0] + t * ab[0], out[1] = a[1] + t * ab[1], out[2] = a[2] + t * ab[2];
}

static double dist2(const double a[3], const double b[3])
{
    const double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return dot3(d, d);
}

/* Closest point on a zero-area triangle: the best of its three edges. */
static void closest_on_flat(const double p[3], const double *t, double out[3])
{
    double best = DBL_MAX;
    for (int k = 0; k < 3; ++k) {
        double q[3];
        closest_on_segment(p, t + 3 * k, t + 3 * ((k + 1) % 3), q);
        const double d = dist2(p, q);
        if (d < best) {
            best = d;
            out[0] = q[0], out[1] = q[1], out[2] = q[2];
        }
    }
}

/* Ericson's ClosestPtPointTriangle. */
static void closest_on_triangle(const double p[3], const double *t, double out[3])
{
    const double *a = t, *b = t + 3, *c = t + 6;
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    sub3(b, a, ab);
    sub3(c, a, ac);
    sub3(p, a, ap);
    const double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) {
        memcpy(out, a, 3 * sizeof *out);
        return;
    }
    sub3(p, b, bp);
    const double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) {
        memcpy(out, b, 3 * sizeof *out);
        return;
    }
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        const double v = d1 / (d1 - d3);
        out[0] = a[0] + v * ab[0], out[1] = a[1] + v * ab[1], out[2] = a[2] + v * ab[2];
        return;
    }
    sub3(p, c, cp);
    const double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) {
        memcpy(out, c, 3 * sizeof *out);
        return;
    }
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        const double w = d2 / (d2 - d6);
        out[0] = a[0] + w * ac[0], out[1] = a[1] + w * ac[1], out[2] = a[2] + w * ac[2];
        return;
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        out[0] = b[0] + w * (c[0] - b[0]);
        out[1] = b[1] + w * (c[1] - b[1]);
        out[2] = b[2] + w * (c[2] - b[2]);
        return;
    }
    const double denom = 1.0 / (va + vb + vc);
    const double v = vb * denom, w = vc * denom;
    out[0] = a[0] + ab[0] * v + ac[0] * w;
    out[1] = a[1] + ab[1] * v + ac[1] * w;
    out[2] = a[2] + ab[2] * v + ac[2] * w;
}

static double box_dist2(const node *nd, const double p[3])
{
    double d = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double e = p[k] < nd->lo[k] ? nd->lo[k] - p[k] : (p[k] > nd->hi[k] ? p[k] - nd->hi[k] : 0.0);
        d += e * e;
    }
    return d;
}

/* ---- building ------------------------------------------------------------ */

typedef struct {
    const double *corners;  /* 9 per triangle (normalised), by triangle index */
    int32_t *order;
    node *nodes;
    int32_t n_nodes;
} builder;

/* Coordinate `axis` of triangle t's centroid (computed where needed: an
 * array of them would add a third to the memory a surface takes while it
 * is built). */
static inline double centroid(const builder *b, int32_t t, int axis)
{
    const double *c = b->corners + 9 * (size_t)t;
    return (c[axis] + c[3 + axis] + c[6 + axis]) / 3.0;
}

/* Quickselect: order[lo..hi) partitioned so that position mid holds the
 * element of rank mid by the centroids' coordinate `axis` (ties by triangle
 * index, so the tree does not depend on anything but the input). */
static int tri_less(const builder *b, int axis, int32_t x, int32_t y)
{
    const double cx = centroid(b, x, axis), cy = centroid(b, y, axis);
    return cx < cy || (cx == cy && x < y);
}

static void select_median(const builder *b, int axis, int32_t lo, int32_t hi, int32_t mid)
{
    int32_t *o = b->order;
    while (hi - lo > 1) {
        /* median of three as pivot */
        int32_t i0 = lo, i1 = lo + (hi - lo) / 2, i2 = hi - 1;
        if (tri_less(b, axis, o[i1], o[i0])) {
            int32_t t = i0; i0 = i1; i1 = t;
        }
        if (tri_less(b, axis, o[i2], o[i1])) {
            i1 = i2;
            if (tri_less(b, axis, o[i1], o[i0]))
                i1 = i0;
        }
        const int32_t pivot = o[i1];
        int32_t i = lo, j = hi - 1;
        while (i <= j) {
            while (tri_less(b, axis, o[i], pivot))
                ++i;
            while (tri_less(b, axis, pivot, o[j]))
                --j;
            if (i <= j) {
                int32_t t = o[i];
                o[i] = o[j];
                o[j] = t;
                ++i, --j;
            }
        }
        if (mid <= j)
            hi = j + 1;
        else if (mid >= i)
            lo = i;
        else
            return;
    }
}

/* Builds node `self` over order[lo..hi): the split axis from the centroids'
 * bounds, the node's box from its children's (or its triangles' for a
 * leaf). Recursion depth is log2(n / LEAF_SIZE) + 1. */
static void build(builder *b, int32_t self, int32_t lo, int32_t hi)
{
    node *nd = &b->nodes[self];
    if (hi - lo <= LEAF_SIZE) {
        for (int k = 0; k < 3; ++k)
            nd->lo[k] = DBL_MAX, nd->hi[k] = -DBL_MAX;
        for (int32_t i = lo; i < hi; ++i) {
            const double *c = b->corners + 9 * (size_t)b->order[i];
            for (int v = 0; v < 3; ++v)
                for (int k = 0; k < 3; ++k) {
                    nd->lo[k] = fmin(nd->lo[k], c[3 * v + k]);
                    nd->hi[k] = fmax(nd->hi[k], c[3 * v + k]);
                }
        }
        nd->left = -1;
        nd->right = lo;
        nd->count = hi - lo;
        return;
    }
    double clo[3] = {DBL_MAX, DBL_MAX, DBL_MAX}, chi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX};
    for (int32_t i = lo; i < hi; ++i)
        for (int k = 0; k < 3; ++k) {
            const double c = centroid(b, b->order[i], k);
            clo[k] = fmin(clo[k], c);
            chi[k] = fmax(chi[k], c);
        }
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (chi[k] - clo[k] > chi[axis] - clo[axis])
            axis = k;
    const int32_t mid = lo + (hi - lo) / 2;
    select_median(b, axis, lo, hi, mid);
    const int32_t left = b->n_nodes++, right = b->n_nodes++;
    build(b, left, lo, mid);
    build(b, right, mid, hi);
    nd = &b->nodes[self];
    const node *l = &b->nodes[left], *r = &b->nodes[right];
    for (int k = 0; k < 3; ++k) {
        nd->lo[k] = fmin(l->lo[k], r->lo[k]);
        nd->hi[k] = fmax(l->hi[k], r->hi[k]);
    }
    nd->left = left;
    nd->right = right;
    nd->count = 0;
}

void facet_surface_free(facet_surface **surface)
{
    if (!surface || !*surface)
        return;
    facet_surface *s = *surface;
    free(s->corners);
    free(s->order);
    free(s->flat);
    free(s->normals);
    free(s->face);
    free(s->nodes);
    free(s);
    *surface = NULL;
}

/* Builds from triangles given by corner coordinates in caller units
 * (9 per triangle). Takes ownership of face (may be NULL). */
static facet_status create_from_corners(int32_t nt, double *corners, int32_t *face,
                                        facet_surface **out, facet_error *error)
{
    /* a bounding box wider than a double can hold would scale everything to
     * 0 and give NaN answers */
    for (int k = 0; k < 3; ++k) {
        double lo = DBL_MAX, hi = -DBL_MAX;
        for (size_t i = k; i < 9 * (size_t)nt; i += 3)
            lo = fmin(lo, corners[i]), hi = fmax(hi, corners[i]);
        if (!isfinite(hi - lo)) {
            free(corners);
            free(face);
            return facet_fail(error, FACET_ERROR_TOO_LARGE, -1, -1,
                              "coordinates too large: the surface's extent overflows a double");
        }
    }
    facet_surface *s = calloc(1, sizeof *s);
    if (!s) {
        free(corners);
        free(face);
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    }
    s->n_triangles = nt;
    s->face = face;
    /* normalisation: bounding box centre, largest side */
    double lo[3] = {DBL_MAX, DBL_MAX, DBL_MAX}, hi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX};
    for (size_t i = 0; i < 3 * (size_t)nt * 3; i += 3)
        for (int k = 0; k < 3; ++k) {
            lo[k] = fmin(lo[k], corners[i + k]);
            hi[k] = fmax(hi[k], corners[i + k]);
        }
    double extent = 0.0;
    for (int k = 0; k < 3; ++k) {
        s->centre[k] = 0.5 * (lo[k] + hi[k]);
        extent = fmax(extent, hi[k] - lo[k]);
    }
    /* A floor on the extent keeps every scaled query finite and its squared
     * distance too: |query - centre| <= 2e30 (FACET_COORDINATE_MAX), times
     * 1e110 is 2e140, squared 4e280. Without it a surface a denormal wide
     * had scale inf, and any surface under 1e-140 wide lost its closest
     * triangle to an infinite distance (found by fuzzing). */
    s->scale = 1.0 / fmax(extent, 1e-110);
    s->normals = malloc(sizeof *s->normals * 3 * (size_t)nt);
    s->order = malloc(sizeof *s->order * (size_t)nt);
    s->flat = calloc((size_t)nt, 1); /* zero: no slot in tree order yet (below) */
    s->nodes = malloc(sizeof *s->nodes * (2 * (size_t)nt + 1));
    if (!s->normals || !s->order || !s->flat || !s->nodes) {
        free(corners);
        facet_surface_free(&s);
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    }
    for (int32_t t = 0; t < nt; ++t) {
        double *c = corners + 9 * (size_t)t;
        for (int v = 0; v < 3; ++v)
            for (int k = 0; k < 3; ++k)
                c[3 * v + k] = (c[3 * v + k] - s->centre[k]) * s->scale;
        double e1[3], e2[3], n[3];
        sub3(c + 3, c, e1);
        sub3(c + 6, c, e2);
        cross3(e1, e2, n);
        const double len = sqrt(dot3(n, n));
        /* zero area relative to the triangle's own size: the Voronoi-region
         * formulas would divide by (nearly) zero */
        const double size2 = fmax(dot3(e1, e1), dot3(e2, e2));
        double *nn = s->normals + 3 * (size_t)t;
        if (len > 1e-14 * size2 && len > 0.0) {
            nn[0] = n[0] / len, nn[1] = n[1] / len, nn[2] = n[2] / len;
        } else {
            nn[0] = nn[1] = nn[2] = 0.0;
        }
        s->order[t] = t;
    }
    builder b = {corners, s->order, s->nodes, 1};
    build(&b, 0, 0, nt);
    s->n_nodes = b.n_nodes;
    node *fit = realloc(s->nodes, sizeof *s->nodes * (size_t)b.n_nodes); /* (shrinks) */
    s->nodes = fit ? fit : s->nodes;
    /* the corners into tree order in place (slot i takes triangle order[i]),
     * cycle by cycle, flat marking the slots done; then flat's own values */
    for (int32_t i = 0; i < nt; ++i) {
        if (s->flat[i])
            continue;
        double first[9];
        memcpy(first, corners + 9 * (size_t)i, sizeof first);
        int32_t j = i;
        for (;;) {
            s->flat[j] = 1;
            const int32_t from = s->order[j];
            if (from == i) {
                memcpy(corners + 9 * (size_t)j, first, sizeof first);
                break;
            }
            memcpy(corners + 9 * (size_t)j, corners + 9 * (size_t)from, sizeof first);
            j = from;
        }
    }
    for (int32_t i = 0; i < nt; ++i) {
        const double *nn = s->normals + 3 * (size_t)s->order[i];
        s->flat[i] = (nn[0] == 0.0 && nn[1] == 0.0 && nn[2] == 0.0);
    }
    s->corners = corners;
    *out = s;
    return FACET_OK;
}

facet_status facet_surface_create(int32_t n_vertices, const double *xyz, int32_t n_triangles,
                                  const int32_t *tri, facet_surface **out, facet_error *error)
{
    facet_error_clear(error);
    if (!out)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1, "out is NULL");
    *out = NULL;
    if (n_vertices <= 0 || n_triangles <= 0)
        return facet_fail(error, FACET_ERROR_EMPTY_MESH, -1, -1,
                          "empty surface: %d vertices and %d triangles", (int)n_vertices,
                          (int)n_triangles);
    if (!xyz || !tri)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1,
                          "surface has no coordinates or no triangles");
    if ((size_t)n_triangles > (SIZE_MAX / 72) || n_triangles > INT32_MAX / 2 - 1)
        return facet_fail(error, FACET_ERROR_TOO_LARGE, -1, -1, "too many triangles: %d",
                          (int)n_triangles);
    for (int32_t t = 0; t < n_triangles; ++t)
        for (int k = 0; k < 3; ++k) {
            const int32_t v = tri[3 * (size_t)t + k];
            if (v < 0 || v >= n_vertices)
                return facet_fail(error, FACET_ERROR_INDEX_OUT_OF_RANGE, t, -1,
                                  "triangle %d has vertex index %d out of range (%d vertices)",
                                  (int)t, (int)v, (int)n_vertices);
            const double *p = xyz + 3 * (size_t)v;
            if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
                return facet_fail(error, FACET_ERROR_NONFINITE, t, v,
                                  "vertex %d of triangle %d has a non-finite coordinate", (int)v,
                                  (int)t);
            if (!facet_point_in_range(p, 3))
                return facet_fail(error, FACET_ERROR_COORDINATE_RANGE, t, v,
                                  "vertex %d of triangle %d has a coordinate beyond 1e30 in "
                                  "magnitude", (int)v, (int)t);
        }
    double *corners = malloc(sizeof *corners * 9 * (size_t)n_triangles);
    if (!corners)
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    for (int32_t t = 0; t < n_triangles; ++t)
        for (int k = 0; k < 3; ++k)
            memcpy(corners + 9 * (size_t)t + 3 * k, xyz + 3 * (size_t)tri[3 * (size_t)t + k],
                   3 * sizeof *corners);
    return create_from_corners(n_triangles, corners, NULL, out, error);
}

facet_status facet_surface_create_from_mesh(const facet_mesh *mesh, facet_surface **out,
                                            facet_error *error)
{
    facet_error_clear(error);
    if (!out)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1, "out is NULL");
    *out = NULL;
    facet_status status = facet_mesh_check_measurable(mesh, error);
    if (status != FACET_OK)
        return status;
    const int32_t nf = mesh->n_faces;
    const int32_t *start = mesh->face_start, *fv = mesh->face_vertices;
    const double *xyz = mesh->xyz;
    int64_t nt = 0;
    for (int32_t f = 0; f < nf; ++f) {
        const int32_t n = start[f + 1] - start[f];
        if (n < 3)
            return facet_fail(error, FACET_ERROR_DEGENERATE_FACE, f, -1,
                              "face %d has %d vertices (at least 3 needed)", (int)f, (int)n);
        nt += n == 3 ? 1 : (n == 4 ? 2 : n);
        for (int32_t k = start[f]; k < start[f + 1]; ++k) {
            const double *p = xyz + 3 * (size_t)fv[k];
            if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
                return facet_fail(error, FACET_ERROR_NONFINITE, f, fv[k],
                                  "vertex %d has a non-finite coordinate", (int)fv[k]);
            if (!facet_point_in_range(p, 3))
                return facet_fail(error, FACET_ERROR_COORDINATE_RANGE, f, fv[k],
                                  "vertex %d has a coordinate beyond 1e30 in magnitude",
                                  (int)fv[k]);
        }
    }
    if (nt > INT32_MAX / 2 - 1)
        return facet_fail(error, FACET_ERROR_TOO_LARGE, -1, -1, "too many triangles: %lld",
                          (long long)nt);
    double *corners = malloc(sizeof *corners * 9 * (size_t)nt);
    int32_t *face = malloc(sizeof *face * (size_t)nt);
    if (!corners || !face) {
        free(corners);
        free(face);
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory");
    }
    size_t t = 0;
#define PUT(P0, P1, P2)                                                \
    do {                                                               \
        memcpy(corners + 9 * t, (P0), 3 * sizeof *corners);            \
        memcpy(corners + 9 * t + 3, (P1), 3 * sizeof *corners);        \
        memcpy(corners + 9 * t + 6, (P2), 3 * sizeof *corners);        \
        face[t++] = f;                                                 \
    } while (0)
    for (int32_t f = 0; f < nf; ++f) {
        const int32_t n = start[f + 1] - start[f];
        const int32_t *idx = fv + start[f];
        const double *p0 = xyz + 3 * (size_t)idx[0];
        if (n == 3) {
            PUT(p0, xyz + 3 * (size_t)idx[1], xyz + 3 * (size_t)idx[2]);
        } else if (n == 4) {
            const double *p1 = xyz + 3 * (size_t)idx[1], *p2 = xyz + 3 * (size_t)idx[2];
            const double *p3 = xyz + 3 * (size_t)idx[3];
            if (dist2(p0, p2) <= dist2(p1, p3)) {
                PUT(p0, p1, p2);
                PUT(p0, p2, p3);
            } else {
                PUT(p1, p2, p3);
                PUT(p1, p3, p0);
            }
        } else {
            double c[3] = {0.0, 0.0, 0.0};
            for (int32_t k = 0; k < n; ++k)
                for (int j = 0; j < 3; ++j)
                    c[j] += xyz[3 * (size_t)idx[k] + j];
            for (int j = 0; j < 3; ++j)
                c[j] /= (double)n;
            for (int32_t k = 0; k < n; ++k)
                PUT(c, xyz + 3 * (size_t)idx[k], xyz + 3 * (size_t)idx[(k + 1) % n]);
        }
    }
#undef PUT
    return create_from_corners((int32_t)nt, corners, face, out, error);
}

int32_t facet_surface_triangle_count(const facet_surface *surface)
{
    return surface ? surface->n_triangles : 0;
}

int32_t facet_surface_face(const facet_surface *surface, int32_t triangle)
{
    if (!surface || !surface->face || triangle < 0 || triangle >= surface->n_triangles)
        return -1;
    return surface->face[triangle];
}

/* ---- queries ------------------------------------------------------------- */

/* Squared distances (normalised: the surface is 1 wide) within this much of
 * the nearest, relative and absolute, are a tie: a query on a corner or an edge
 * that triangles share, where rounding alone told them apart. */
#define TIE_REL 1e-12
#define TIE_ABS 1e-24

static double tie_bound(double nearest)
{
    return nearest + TIE_REL * nearest + TIE_ABS;
}

static double triangle_dist2(const facet_surface *s, int32_t slot, const double p[3], double q[3])
{
    const double *t = s->corners + 9 * (size_t)slot;
    if (s->flat[slot])
        closest_on_flat(p, t, q);
    else
        closest_on_triangle(p, t, q);
    return dist2(p, q);
}

/* Triangles kept as candidates for a tie while the tree is searched: those
 * around a shared corner (a mesh's valence), with room to spare; more (a
 * fan of hundreds) take a second search. */
#define TIE_CANDIDATES 32

static int ranks_before(const facet_surface *s, int32_t a, int32_t b)
{
    /* a triangle with area first, then the lowest triangle index */
    return s->flat[a] != s->flat[b] ? !s->flat[a] : s->order[a] < s->order[b];
}

/* Visit the leaves whose boxes are within *bound of p, nearest first. With
 * shrink, *bound falls to the tie bound of the nearest triangle met, and the
 * triangles within it when met are kept in cand (up to TIE_CANDIDATES; *n
 * counts them all). Without, the best ranked triangle within *bound is taken
 * (the second search, when the candidates overflowed). Returns the nearest
 * squared distance. */
static double search(const facet_surface *s, const double p[3], double *bound, int shrink,
                     int32_t *cand, double *cand_d, int *n, int32_t *slot)
{
    int32_t stack[STACK_SIZE];
    double stack_d[STACK_SIZE];
    int top = 0;
    double nearest = DBL_MAX;
    stack[top] = 0;
    stack_d[top++] = box_dist2(&s->nodes[0], p);
    while (top > 0) {
        --top;
        if (stack_d[top] > *bound)
            continue;
        const node *nd = &s->nodes[stack[top]];
        if (nd->left < 0) {
            for (int32_t i = nd->right; i < nd->right + nd->count; ++i) {
                double q[3];
                const double d = triangle_dist2(s, i, p, q);
                nearest = fmin(nearest, d);
                if (d > *bound)
                    continue;
                if (shrink) {
                    *bound = fmin(*bound, tie_bound(d));
                    if (*n < TIE_CANDIDATES)
                        cand[*n] = i, cand_d[*n] = d;
                    ++*n;
                } else if (*slot < 0 || ranks_before(s, i, *slot)) {
                    *slot = i;
                }
            }
            continue;
        }
        const node *l = &s->nodes[nd->left], *r = &s->nodes[nd->right];
        const double dl = box_dist2(l, p), dr = box_dist2(r, p);
        /* push the farther first so the nearer is searched first */
        if (top + 2 > STACK_SIZE)
            break; /* cannot happen: depth <= log2(n) + 1 < 64 */
        if (dl <= dr) {
            if (dr <= *bound)
                stack[top] = nd->right, stack_d[top++] = dr;
            if (dl <= *bound)
                stack[top] = nd->left, stack_d[top++] = dl;
        } else {
            if (dl <= *bound)
                stack[top] = nd->left, stack_d[top++] = dl;
            if (dr <= *bound)
                stack[top] = nd->right, stack_d[top++] = dr;
        }
    }
    return nearest;
}

/* The closest triangle to p (normalised). Triangles within tie_bound of the
 * nearest distance tie; among them one with area wins over a zero-area one,
 * whose normal says nothing, then the lowest triangle index: the same
 * triangle, and normal, in any units or place, whatever order the tree is
 * searched in. The search keeps the triangles within the tie bound of the
 * nearest met so far (the bound only shrinks, so every tied one is among
 * them) and ranks those within the final bound; a second search does it when
 * they overflow. Before, the first strictly closer one won, which rounding
 * chose at the corners where a planarization's control vertices start: the
 * surface term then took a different path in mm than in m. */
static void query_one(const facet_surface *s, const double p[3], double best_point[3],
                      double *best_d2, int32_t *best_slot)
{
    int32_t cand[TIE_CANDIDATES];
    double cand_d[TIE_CANDIDATES];
    int n = 0;
    double bound = DBL_MAX;
    int32_t slot = -1;
    const double nearest = search(s, p, &bound, 1, cand, cand_d, &n, &slot);
    bound = tie_bound(nearest);
    if (n <= TIE_CANDIDATES) {
        for (int k = 0; k < n; ++k)
            if (cand_d[k] <= bound && (slot < 0 || ranks_before(s, cand[k], slot)))
                slot = cand[k];
    } else {
        search(s, p, &bound, 0, NULL, NULL, &n, &slot);
    }
    *best_d2 = triangle_dist2(s, slot, p, best_point);
    *best_slot = slot;
}

facet_status facet_surface_closest(const facet_surface *surface, int64_t n, const double *query,
                                   int32_t threads, double *closest, double *distance,
                                   int32_t *triangle, double *normal, facet_error *error)
{
    facet_error_clear(error);
    if (!surface)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1, "surface is NULL");
    if (n < 0)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1,
                          "query count %lld is negative", (long long)n);
    if (n == 0)
        return FACET_OK;
    if (!query)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1, "query is NULL");
    for (int64_t i = 0; i < n; ++i) {
        const double *p = query + 3 * (size_t)i;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
            return facet_fail(error, FACET_ERROR_NONFINITE, -1, i,
                              "query point %lld has a non-finite coordinate (%g, %g, %g)",
                              (long long)i, p[0], p[1], p[2]);
        if (!facet_point_in_range(p, 3))
            return facet_fail(error, FACET_ERROR_COORDINATE_RANGE, -1, i,
                              "query point %lld has a coordinate beyond 1e30 in magnitude "
                              "(%g, %g, %g)", (long long)i, p[0], p[1], p[2]);
    }
    const facet_surface *s = surface;
    const int nthreads = facet_thread_count(threads);
    (void)nthreads;
#pragma omp parallel for schedule(dynamic, 256) num_threads(nthreads)
    for (int64_t i = 0; i < n; ++i) {
        const double *p = query + 3 * (size_t)i;
        double q[3] = {(p[0] - s->centre[0]) * s->scale, (p[1] - s->centre[1]) * s->scale,
                       (p[2] - s->centre[2]) * s->scale};
        /* A point more than FAR_LIMIT surface sizes away would overflow the
         * squared distances (and find no triangle): search from the point at
         * FAR_LIMIT on the same ray from the centre, whose closest point is
         * the same to rounding, and add the rest of the way to the distance. */
        double beyond = 0.0;
        const double m = facet_max(fabs(q[0]), facet_max(fabs(q[1]), fabs(q[2])));
        if (m > FAR_LIMIT) {
            const double u[3] = {q[0] / m, q[1] / m, q[2] / m};
            const double len = m * sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
            for (int k = 0; k < 3; ++k)
                q[k] = q[k] / len * FAR_LIMIT;
            beyond = len - FAR_LIMIT;
        }
        double c[3] = {0.0, 0.0, 0.0}, d2 = 0.0;
        int32_t slot = -1;
        query_one(s, q, c, &d2, &slot);
        const int32_t t = slot >= 0 ? s->order[slot] : -1;
        if (closest)
            for (int k = 0; k < 3; ++k)
                closest[3 * (size_t)i + k] = c[k] / s->scale + s->centre[k];
        if (distance)
            distance[i] = (sqrt(d2) + beyond) / s->scale;
        if (triangle)
            triangle[i] = t;
        if (normal)
            for (int k = 0; k < 3; ++k)
                normal[3 * (size_t)i + k] = t >= 0 ? s->normals[3 * (size_t)t + k] : 0.0;
    }
    return FACET_OK;
}
