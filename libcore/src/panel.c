/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Panel geometry: consistent orientation, offset and edge planes, top and
 * bottom outlines, per-edge angles, node (torsion) deviation, unfold frames.
 * See the Panels section of facet.h for the contract. */
#include "internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

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

static double norm3(const double a[3])
{
    return sqrt(dot3(a, a));
}

void facet_panel_options_default(facet_panel_options *options)
{
    if (!options)
        return;
    memset(options, 0, sizeof *options);
    options->thickness = 1.0;
    options->offset = FACET_PANEL_OFFSET_OUTER;
    options->gap = 0.0;
    options->edge = FACET_PANEL_EDGE_SQUARE;
    options->flip = 0;
    options->planarity_tol_abs = 0.0;
    options->planarity_tol_rel = 1e-6;
    options->repair_consumed = 1;
}

/* A half-edge keyed by its undirected edge, for grouping. */
typedef struct {
    uint64_t key;
    int64_t corner; /* global corner index */
} half_edge;

static int half_edge_cmp(const void *pa, const void *pb)
{
    const half_edge *a = pa, *b = pb;
    if (a->key != b->key)
        return a->key < b->key ? -1 : 1;
    return (a->corner > b->corner) - (a->corner < b->corner);
}

/* Workspace of one call. */
typedef struct {
    const facet_mesh *mesh;
    int64_t nc;
    int32_t *corner_face; /* nc */
    int32_t *nbr;         /* nc: neighbour face across edge k, -1 */
    int32_t *nbr_corner;  /* nc: the neighbour's corner of the same edge, -1 */
    int8_t *sign;         /* n_faces: +1 keep winding, -1 reverse */
    double *xyz;          /* normalized coordinates, 3*n_vertices */
    double *plane;        /* 4*n_faces, normalized, oriented */
    double *eplane;       /* 4*nc: inward edge plane p.x = d (p unit) */
    double *fold;         /* nc: signed fold angle at the edge (>0 convex on top) */
    int8_t *drop;         /* nc: the outline drops edge k (the gap consumes it) */
    int8_t *square;       /* nc: how edge k is cut: CUT_MITRE, CUT_SQUARE, ... */
    double *ctop, *cbot;  /* 3*nc: the outlines' corners, normalized */
} work;

static void work_free(work *w)
{
    free(w->corner_face);
    free(w->nbr);
    free(w->nbr_corner);
    free(w->sign);
    free(w->xyz);
    free(w->plane);
    free(w->eplane);
    free(w->fold);
    free(w->drop);
    free(w->square);
    free(w->ctop);
    free(w->cbot);
}

/* How an edge is cut (work.square): on the bisector plane; square to its
 * panel (asked, a boundary or a flat joint); square because its mitre could
 * not be cut; or on its neighbour's square plane (the other half of a butt
 * joint whose neighbour is cut square: it takes the whole fold). */
enum { CUT_MITRE = 0, CUT_SQUARE = 1, CUT_SQUARED = 2, CUT_BUTT = 3 };

static int is_square(int8_t cut)
{
    return cut == CUT_SQUARE || cut == CUT_SQUARED;
}

/* The next corner of a corner within its face, in input order. */
static int64_t next_corner(const facet_mesh *m, int32_t f, int64_t c)
{
    return c + 1 < m->face_start[f + 1] ? c + 1 : m->face_start[f];
}

static int64_t prev_corner(const facet_mesh *m, int32_t f, int64_t c)
{
    return c > m->face_start[f] ? c - 1 : m->face_start[f + 1] - 1;
}

/* The last edge at or before the corner's previous edge that the outline
 * keeps (edge k runs from corner k to k + 1; w->drop marks dropped edges). A
 * face keeps at least three edges, so the walks end. */
static int64_t active_before(const work *w, int32_t f, int64_t c)
{
    int64_t e = prev_corner(w->mesh, f, c);
    while (w->drop[e])
        e = prev_corner(w->mesh, f, e);
    return e;
}

/* The first edge after edge c that the outline keeps. */
static int64_t active_after(const work *w, int32_t f, int64_t c)
{
    int64_t e = next_corner(w->mesh, f, c);
    while (w->drop[e])
        e = next_corner(w->mesh, f, e);
    return e;
}

/* Groups half-edges into edges: neighbours across manifold edges. */
static facet_status build_adjacency(work *w, int64_t *n_non_manifold, facet_error *error)
{
    const facet_mesh *m = w->mesh;
    half_edge *he = malloc((size_t)(w->nc ? w->nc : 1) * sizeof *he);
    if (!he)
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory (edge table)");
    for (int32_t f = 0; f < m->n_faces; ++f)
        for (int64_t c = m->face_start[f]; c < m->face_start[f + 1]; ++c) {
            uint64_t a = (uint64_t)(uint32_t)m->face_vertices[c];
            uint64_t b = (uint64_t)(uint32_t)m->face_vertices[next_corner(m, f, c)];
            he[c].key = a < b ? (a << 32) | b : (b << 32) | a;
            he[c].corner = c;
            w->corner_face[c] = f;
            w->nbr[c] = -1;
            w->nbr_corner[c] = -1;
        }
    qsort(he, (size_t)w->nc, sizeof *he, half_edge_cmp);
    *n_non_manifold = 0;
    for (int64_t i = 0; i < w->nc;) {
        int64_t j = i + 1;
        while (j < w->nc && he[j].key == he[i].key)
            ++j;
        if (j - i == 2) {
            int64_t c0 = he[i].corner, c1 = he[i + 1].corner;
            if (w->corner_face[c0] != w->corner_face[c1]) {
                w->nbr[c0] = w->corner_face[c1];
                w->nbr_corner[c0] = (int32_t)c1;
                w->nbr[c1] = w->corner_face[c0];
                w->nbr_corner[c1] = (int32_t)c0;
            }
        } else if (j - i > 2) {
            ++*n_non_manifold;
        }
        i = j;
    }
    free(he);
    return FACET_OK;
}

/* Propagates a consistent winding across manifold edges (breadth first). */
static facet_status orient(work *w, int flip, int32_t *n_components, facet_error *error)
{
    const facet_mesh *m = w->mesh;
    int32_t *queue = malloc((size_t)m->n_faces * sizeof *queue);
    if (!queue)
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory (queue)");
    memset(w->sign, 0, (size_t)m->n_faces);
    *n_components = 0;
    for (int32_t seed = 0; seed < m->n_faces; ++seed) {
        if (w->sign[seed])
            continue;
        ++*n_components;
        w->sign[seed] = flip ? -1 : 1;
        int32_t head = 0, tail = 0;
        queue[tail++] = seed;
        while (head < tail) {
            const int32_t f = queue[head++];
            for (int64_t c = m->face_start[f]; c < m->face_start[f + 1]; ++c) {
                const int32_t h = w->nbr[c];
                if (h < 0)
                    continue;
                /* Same input direction on both sides means the windings
                 * disagree: the neighbour needs the opposite sign. */
                const int64_t ch = w->nbr_corner[c];
                const int same = m->face_vertices[c] == m->face_vertices[ch];
                const int8_t want = (int8_t)(same ? -w->sign[f] : w->sign[f]);
                if (!w->sign[h]) {
                    w->sign[h] = want;
                    queue[tail++] = h;
                } else if (w->sign[h] != want) {
                    free(queue);
                    return facet_fail(error, FACET_ERROR_NOT_ORIENTABLE, h,
                                      m->face_vertices[c],
                                      "faces %d and %d cannot be oriented consistently (the "
                                      "surface is non-orientable, e.g. a Moebius strip)",
                                      (int)f, (int)h);
                }
            }
        }
    }
    free(queue);
    return FACET_OK;
}

/* Solves the 3x3 system rows a, b, c . x = (da, db, dc). Returns the
 * determinant of the unit-normal rows (0 when singular). */
static double solve3(const double a[3], double da, const double b[3], double db,
                     const double c[3], double dc, double x[3])
{
    double bc[3], ca[3], ab[3];
    cross3(b, c, bc);
    cross3(c, a, ca);
    cross3(a, b, ab);
    const double det = dot3(a, bc);
    if (fabs(det) < 1e-12)
        return 0.0;
    for (int i = 0; i < 3; ++i)
        x[i] = (da * bc[i] + db * ca[i] + dc * ab[i]) / det;
    return det;
}

/* The corner of a panel's outline on the plane n.x = h (n the face's unit
 * normal) between the edge planes a (before) and b (after) of vertex p: where
 * the three planes meet. At a straight corner (a vertex on a straight edge, as
 * where two panels meet along one side of a third) a and b meet that plane in
 * one line when they are cut alike: the corner is then the point of that line
 * nearest p. Returns 0 where there is no one corner (a and b parallel and
 * apart there). */
static int corner_point(const double n[3], double h, const double a[4], const double b[4],
                        const double p[3], double x[3])
{
    const double det = solve3(n, h, a, a[3], b, b[3], x);
    if (fabs(det) >= 1e-9)
        return 1;
    /* p + s n + t a on both n and a: a 2 x 2 system (n, a unit, not parallel) */
    const double c = dot3(n, a), r1 = h - dot3(n, p), r2 = a[3] - dot3(a, p);
    const double g = 1.0 - c * c;
    if (!(g > 1e-12))
        return det != 0.0;
    const double s = (r1 - c * r2) / g, t = (r2 - c * r1) / g;
    const double y[3] = {p[0] + s * n[0] + t * a[0], p[1] + s * n[1] + t * a[1],
                         p[2] + s * n[2] + t * a[2]};
    if (fabs(dot3(b, y) - b[3]) <= 1e-9) {
        x[0] = y[0], x[1] = y[1], x[2] = y[2];
        return 1;
    }
    return det != 0.0;
}

/* Whether the corner (xt on the top plane n.x = up - n[3], xb on the bottom
 * one) of edge planes a and b at vertex p (between its neighbours o and q) is
 * a nearly straight corner between cuts of different angles, far along the
 * edges: two cuts whose offsets from the edge differ by e meet e / sin(turn)
 * along it, 554 mm at a turn of 0.57 degrees for a 30-degree fold's mitre
 * beside a free edge (20 mm thick), where the panel's top reached 5.4 mm into
 * the mitred joint over that length (a reflex corner; a convex one bevelled
 * the free edge's top as far). The caller asks it of a free edge beside a
 * joint, where squaring the joint's cut on this panel leaves the joint a slot
 * (a butt joint) and squares no joint on both panels. Nearly straight is a turn under
 * FAR_CORNER_TURN, far beyond FAR_CORNER thicknesses from the vertex, and
 * different bevels a degree apart or more (alike cuts at a nearly straight
 * corner meet near it). */
#define FAR_CORNER 4.0
#define FAR_CORNER_TURN 0.17365 /* sin(10 degrees) */
static int far_corner(const double n[4], double up, double down, const double a[4],
                      const double b[4], const double o[3], const double p[3],
                      const double q[3], const double xt[3], const double xb[3], double th)
{
    /* the sines of the two cuts' bevels from square */
    if (!(fabs(dot3(a, n) - dot3(b, n)) > 0.01745))
        return 0;
    const double u[3] = {p[0] - o[0], p[1] - o[1], p[2] - o[2]};
    const double v[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    double uv[3];
    cross3(u, v, uv);
    if (!(dot3(u, v) > 0.0 && norm3(uv) < FAR_CORNER_TURN * norm3(u) * norm3(v)))
        return 0;
    const double pd = dot3(n, p) + n[3];
    for (int side = 0; side < 2; ++side) {
        const double *x = side ? xb : xt;
        const double h = (side ? down : up) - pd; /* p's projection: p + h n */
        const double d[3] = {x[0] - p[0] - h * n[0], x[1] - p[1] - h * n[1],
                             x[2] - p[2] - h * n[2]};
        if (norm3(d) > FAR_CORNER * th)
            return 1;
    }
    return 0;
}

/* v projected onto the plane of unit normal n, then made a unit vector (when
 * not zero); returns its length before that. */
static double in_plane_unit(double v[3], const double n[3])
{
    const double vn = dot3(v, n);
    for (int k = 0; k < 3; ++k)
        v[k] -= vn * n[k];
    const double l = norm3(v);
    if (l > 0.0)
        for (int k = 0; k < 3; ++k)
            v[k] /= l;
    return l;
}

/* An orthonormal basis ex, ey of the plane of unit normal n. */
static void plane_basis(const double n[3], double ex[3], double ey[3])
{
    ex[0] = fabs(n[0]) < 0.6 ? 1.0 : 0.0, ex[1] = fabs(n[0]) < 0.6 ? 0.0 : 1.0, ex[2] = 0.0;
    in_plane_unit(ex, n);
    cross3(n, ex, ey);
}

/* The plane of edge c (corner c to the next) of face f, its fold angle and
 * its outputs: as w->square[c] says (square: perpendicular to the face; a
 * mitre: the bisector of the two panels' planes; a butt: the neighbour's
 * square plane), moved half the gap inwards. */
static facet_status edge_plane(work *w, int32_t f, int64_t c, double half_gap, facet_panel_output *out,
                               facet_error *error)
{
    const facet_mesh *m = w->mesh;
    const double *nf_ = w->plane + 4 * f;
    const double sg = w->sign[f];
    const double *p = w->xyz + 3 * m->face_vertices[c];
    const double *q = w->xyz + 3 * m->face_vertices[next_corner(m, f, c)];
    /* Consistent direction of this edge: along the winding. */
    double e[3] = {sg * (q[0] - p[0]), sg * (q[1] - p[1]), sg * (q[2] - p[2])};
    /* Project onto the face's plane, then normalise. */
    if (!(in_plane_unit(e, nf_) > 1e-14))
        return facet_fail(error, FACET_ERROR_PANEL_GEOMETRY, f, m->face_vertices[c],
                          "face %d: edge from vertex %d has no length in the face's plane",
                          (int)f, (int)m->face_vertices[c]);
    double mi[3]; /* inward in the face's plane */
    cross3(nf_, e, mi);
    double pl[3] = {mi[0], mi[1], mi[2]};
    double fold = 0.0;
    const int32_t h = w->nbr[c];
    if (h >= 0) {
        const double *nh = w->plane + 4 * h;
        double x[3];
        cross3(nf_, nh, x);
        const double sn = norm3(x), cs = dot3(nf_, nh);
        const double psi = atan2(sn, cs);
        /* Convex on top (a ridge) when the neighbour's normal leans
         * away from this face's interior. */
        fold = dot3(nh, mi) < 0.0 ? psi : -psi;
        if (psi > PI - 1e-6)
            return facet_fail(error, FACET_ERROR_PANEL_GEOMETRY, f, m->face_vertices[c],
                              "faces %d and %d fold back onto each other at vertex %d",
                              (int)f, (int)h, (int)m->face_vertices[c]);
        if (w->square[c] == CUT_BUTT) {
            /* the neighbour's square plane, facing this panel */
            double eh[3] = {-e[0], -e[1], -e[2]}, mh[3];
            in_plane_unit(eh, nh);
            cross3(nh, eh, mh);
            pl[0] = -mh[0], pl[1] = -mh[1], pl[2] = -mh[2];
        } else if (w->square[c] == CUT_MITRE && psi > 1e-12) {
            double avg[3] = {nf_[0] + nh[0], nf_[1] + nh[1], nf_[2] + nh[2]};
            double b[3];
            cross3(e, avg, b);
            const double lb = norm3(b);
            for (int k = 0; k < 3; ++k)
                b[k] /= lb;
            if (dot3(b, mi) < 0.0)
                for (int k = 0; k < 3; ++k)
                    b[k] = -b[k];
            pl[0] = b[0], pl[1] = b[1], pl[2] = b[2];
        }
    }
    /* The edge line on the face's plane: p projected. */
    const double pd = dot3(nf_, p) + nf_[3];
    const double p0[3] = {p[0] - pd * nf_[0], p[1] - pd * nf_[1], p[2] - pd * nf_[2]};
    w->eplane[4 * c + 0] = pl[0];
    w->eplane[4 * c + 1] = pl[1];
    w->eplane[4 * c + 2] = pl[2];
    w->eplane[4 * c + 3] = dot3(pl, p0) + half_gap;
    w->fold[c] = fold;
    if (out->neighbor)
        out->neighbor[c] = h;
    if (out->dihedral)
        out->dihedral[c] = h >= 0 ? PI - fold : 0.0;
    if (out->bevel)
        out->bevel[c] = atan2(dot3(pl, nf_), dot3(pl, mi));
    return FACET_OK;
}

/* Cuts the joints of corners around[0] and around[1] of face f square on
 * this panel: butt joints, the neighbour taking the whole fold (or, if it is
 * square already, square on both). *again is the first face they touch, to
 * outline again from. */
static facet_status square_joints(work *w, int32_t f, const int64_t around[2], double half_gap,
                                  facet_panel_output *out, facet_error *error, int32_t *again)
{
    *again = f;
    for (int k = 0; k < 2; ++k) {
        const int64_t c = around[k], t = w->nbr_corner[c];
        if (is_square(w->square[c]))
            continue;
        w->square[c] = CUT_SQUARED;
        facet_status status = edge_plane(w, f, c, half_gap, out, error);
        if (status < 0)
            return status;
        if (t >= 0 && w->square[t] == CUT_MITRE) {
            w->square[t] = CUT_BUTT;
            status = edge_plane(w, w->corner_face[t], t, half_gap, out, error);
            if (status < 0)
                return status;
            *again = *again < w->corner_face[t] ? *again : w->corner_face[t];
        }
    }
    return FACET_OK;
}

/* At the straight corner c of face f between the edges before and c, one a
 * butt joint (its neighbour cut square by another repair) and the other a
 * mitre: where the mitre, cut as a butt joint too (its neighbour square), would
 * meet the butt joint's plane in one line on the top and bottom planes (the
 * panels across coplanar, as a planar mesh makes them), it is: the panel takes
 * the whole fold along the edge on both sides of the corner, and no joint is
 * square on both panels (which, on a fold, makes them overlap). Returns 1
 * then, *again the first face it touches; 0 with the cuts as they were. */
static int butt_beside_mitre(work *w, int32_t f, int64_t before, int64_t c, double up,
                             double down, double half_gap, facet_panel_output *out,
                             facet_error *error, int32_t *again, facet_status *status)
{
    int64_t mitre = -1;
    if (w->square[before] == CUT_BUTT && w->square[c] == CUT_MITRE)
        mitre = c;
    else if (w->square[c] == CUT_BUTT && w->square[before] == CUT_MITRE)
        mitre = before;
    const int64_t t = mitre >= 0 ? w->nbr_corner[mitre] : -1;
    *status = FACET_OK;
    if (t < 0 || w->square[t] != CUT_MITRE)
        return 0;
    const double *n = w->plane + 4 * f;
    const double *p = w->xyz + 3 * w->mesh->face_vertices[c];
    w->square[mitre] = CUT_BUTT;
    *status = edge_plane(w, f, mitre, half_gap, out, error);
    if (*status < 0)
        return 0;
    const double *a = w->eplane + 4 * before, *b = w->eplane + 4 * c;
    double x[3];
    if (!(corner_point(n, up - n[3], a, b, p, x) && corner_point(n, down - n[3], a, b, p, x))) {
        w->square[mitre] = CUT_MITRE; /* not one plane (the panels across fold) */
        *status = edge_plane(w, f, mitre, half_gap, out, error);
        return 0;
    }
    w->square[t] = CUT_SQUARED;
    *status = edge_plane(w, w->corner_face[t], t, half_gap, out, error);
    if (*status < 0)
        return 0;
    *again = f < w->corner_face[t] ? f : w->corner_face[t];
    return 1;
}

/* The squared distance from x to the segment from a to b. */
static double segment_distance2(const double x[3], const double a[3], const double b[3])
{
    const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, ax[3] = {x[0] - a[0], x[1] - a[1], x[2] - a[2]};
    const double l2 = dot3(ab, ab);
    const double t = l2 > 0.0 ? fmin(1.0, fmax(0.0, dot3(ax, ab) / l2)) : 0.0;
    const double d[3] = {ax[0] - t * ab[0], ax[1] - t * ab[1], ax[2] - t * ab[2]};
    return dot3(d, d);
}

/* The squared distance from x to a panel's cross-section at a joint: the
 * half-strip bounded by its side face's section (lo to hi) and the rays from lo
 * and hi into the panel along in (unit). x must lie outside it. */
static double section_distance2(const double x[3], const double lo[3], const double hi[3],
                                const double in[3])
{
    double d = segment_distance2(x, lo, hi);
    for (int k = 0; k < 2; ++k) {
        const double *a = k ? hi : lo;
        const double ax[3] = {x[0] - a[0], x[1] - a[1], x[2] - a[2]};
        const double s = fmax(0.0, dot3(ax, in));
        const double r[3] = {ax[0] - s * in[0], ax[1] - s * in[1], ax[2] - s * in[2]};
        d = fmin(d, dot3(r, r));
    }
    return d;
}

/* Panels that overlap by no more than this (normalised units, 1e-9 of the
 * mesh's size) touch: their joint is 0 wide, not an overlap. */
#define JOINT_TOUCH 1e-9

/* How deep two panels' sections at a joint overlap (0 when they do not): the
 * least overlap of the two along the normals of their edges (each panel's
 * plane and its side plane), as the node test measures two convex pieces
 * (piece_overlap). Both sections are convex, so they overlap exactly when
 * every axis does (separating axes). x[i]: the ends of panel i's side face's
 * section (bottom, top), in[i]: the direction its section runs into it (it is
 * unbounded that way); n[i], side[i]: the planes (unit normals first). The
 * deepest corner of one inside the other saw no overlap on a fold of 90
 * degrees or more with square cuts: there no corner lies inside the other
 * panel (at 90 degrees each lies on the other's faces), though the panels
 * overlap by their whole thickness. */
static double section_overlap(double x[2][2][3], double in[2][3], const double *n0,
                              const double *n1, const double *side0, const double *side1)
{
    const double *axes[4] = {n0, n1, side0, side1};
    double least = INFINITY;
    for (int a = 0; a < 4; ++a) {
        double lo[2], hi[2];
        for (int i = 0; i < 2; ++i) {
            const double p = dot3(axes[a], x[i][0]), q = dot3(axes[a], x[i][1]);
            const double run = dot3(axes[a], in[i]);
            lo[i] = run < -1e-12 ? -INFINITY : fmin(p, q);
            hi[i] = run > 1e-12 ? INFINITY : fmax(p, q);
        }
        least = fmin(least, fmin(hi[0], hi[1]) - fmax(lo[0], lo[1]));
    }
    return least > 0.0 ? least : 0.0;
}

/* The most corners a panel may have for the node test by convex pieces (more:
 * its corners inside the other panel). */
#define FACET_PIECE_MAX 32

/* How deep the panels of edge c (face f) and of its twin overlap, normalised
 * units (0 when they do not), with both side planes moved widen farther into
 * their panels (half of a wider gap): in the cross-section at the edge's
 * midpoint, the least overlap of the two sections along their edges' normals
 * (section_overlap). The
 * section is the same all along the edge, as every plane of the joint
 * contains the edge's direction. *narrowest: the joint's narrowest width
 * there, the least distance from a corner of one side face to the other
 * panel's section (minus the depth where they overlap). A mitred or butt
 * joint keeps the gap; a square one on a fold closes the joint on the
 * fold's inner side, and with too small a gap the panels overlap there. */
static double joint_overlap(const work *w, int32_t f, int64_t c, double up, double down,
                            double widen, double *narrowest)
{
    const facet_mesh *m = w->mesh;
    const int64_t t = w->nbr_corner[c];
    *narrowest = INFINITY;
    if (t < 0)
        return 0.0;
    const int32_t h = w->corner_face[t];
    const double *p = w->xyz + 3 * m->face_vertices[c];
    const double *q = w->xyz + 3 * m->face_vertices[next_corner(m, f, c)];
    double e[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    const double le = norm3(e);
    if (!(le > 0.0))
        return 0.0;
    for (int k = 0; k < 3; ++k)
        e[k] /= le;
    const double mid = 0.5 * (dot3(e, p) + dot3(e, q));
    const int32_t faces[2] = {f, h};
    const int64_t corners[2] = {c, t};
    double x[2][2][3]; /* [panel][bottom, top]: its side face's section's ends */
    double in[2][3];   /* [panel]: into the panel, in its plane, across the edge */
    for (int i = 0; i < 2; ++i) {
        const double *n = w->plane + 4 * faces[i], *side = w->eplane + 4 * corners[i];
        for (int top = 0; top < 2; ++top)
            if (solve3(e, mid, side, side[3] + widen, n, (top ? up : down) - n[3], x[i][top]) ==
                0.0)
                return 0.0;
        cross3(n, e, in[i]);
        const double li = norm3(in[i]), sg = dot3(in[i], side) < 0.0 ? -1.0 : 1.0;
        for (int k = 0; k < 3; ++k)
            in[i][k] *= sg / li;
    }
    double nearest2 = INFINITY;
    for (int i = 0; i < 2; ++i)
        for (int top = 0; top < 2; ++top)
            nearest2 = fmin(nearest2, section_distance2(x[i][top], x[1 - i][0], x[1 - i][1],
                                                        in[1 - i]));
    const double deepest = section_overlap(x, in, w->plane + 4 * f, w->plane + 4 * h,
                                           w->eplane + 4 * c, w->eplane + 4 * t);
    *narrowest = deepest > JOINT_TOUCH ? -deepest : sqrt(nearest2);
    return deepest;
}

/* The gap at which the joint of edge c (face f), overlapping with half_gap,
 * would clear, normalised units: the least widening that leaves no overlap,
 * by bisection (the overlap shrinks as both side planes move apart). */
static double clearing_gap(const work *w, int32_t f, int64_t c, double up, double down,
                           double half_gap)
{
    double width, lo = 0.0, hi = fmax(half_gap, up - down);
    for (int k = 0; k < 64 && joint_overlap(w, f, c, up, down, hi, &width) > 0.0; ++k)
        lo = hi, hi *= 2.0;
    for (int k = 0; k < 64 && hi - lo > 1e-12 * hi; ++k) {
        const double mid = 0.5 * (lo + hi);
        if (joint_overlap(w, f, c, up, down, mid, &width) > 0.0)
            lo = mid;
        else
            hi = mid;
    }
    return 2.0 * (half_gap + hi);
}

/* How deep x lies inside face f's panel, normalised units (0 outside): the
 * least of its distances from the top and bottom planes and, in the solid's
 * slice through x parallel to them, from the slice's outline (each side face
 * is planar, so the slice's corners lie between the bottom and top corners, at
 * x's height). The outline may be concave; dropped edges are corners that
 * coincide. */
static double depth_in_panel(const work *w, int32_t f, const double x[3], double up, double down)
{
    const double *n = w->plane + 4 * f;
    const double h = dot3(n, x) + n[3];
    const double slab = fmin(h - down, up - h);
    if (!(slab > JOINT_TOUCH))
        return 0.0;
    const double lambda = (h - down) / (up - down);
    double ex[3], ey[3];
    plane_basis(n, ex, ey);
    const double px = dot3(ex, x), py = dot3(ey, x);
    const int64_t s = w->mesh->face_start[f], e = w->mesh->face_start[f + 1];
    double prev[3], u0 = 0.0, v0 = 0.0, nearest2 = INFINITY;
    int inside = 0;
    for (int64_t c = e - 1, k = 0; k <= e - s; c = s + k++) {
        double p[3];
        for (int i = 0; i < 3; ++i)
            p[i] = w->cbot[3 * c + i] + lambda * (w->ctop[3 * c + i] - w->cbot[3 * c + i]);
        const double u1 = dot3(ex, p), v1 = dot3(ey, p);
        if (k > 0) { /* the slice's edge from prev to p, in the plane of x */
            if ((v0 > py) != (v1 > py) && px < u0 + (py - v0) * (u1 - u0) / (v1 - v0))
                inside = !inside;
            nearest2 = fmin(nearest2, segment_distance2(x, prev, p));
        }
        memcpy(prev, p, sizeof prev);
        u0 = u1, v0 = v1;
    }
    return inside ? fmin(slab, sqrt(nearest2)) : 0.0;
}

/* Where face f's panel and face h's meet across a joint at corner c (its
 * edges from and into c), which the joints' widths measure: the joint's edge
 * (a corner of f), or -1 when none; an edge either panel dropped is no joint. */
static int64_t joint_at(const work *w, int32_t f, int64_t c, int32_t h)
{
    const int64_t edges[2] = {c, prev_corner(w->mesh, f, c)};
    for (int k = 0; k < 2; ++k) {
        const int64_t t = w->nbr_corner[edges[k]];
        if (w->nbr[edges[k]] == h && !w->drop[edges[k]] && t >= 0 && !w->drop[t])
            return edges[k];
    }
    return -1;
}

/* How the outline x (a panel's top or bottom corners) of face f turns at corner c about
 * the face's normal: > 0 left, < 0 right, 0 where it does not turn (corners that
 * coincide, where an edge was dropped, and straight ones). */
static double corner_turn(const work *w, int32_t f, int64_t c, const double *x)
{
    const facet_mesh *m = w->mesh;
    const double *a = x + 3 * prev_corner(m, f, c), *b = x + 3 * c,
                 *d = x + 3 * next_corner(m, f, c);
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {d[0] - b[0], d[1] - b[1], d[2] - b[2]};
    double k[3];
    cross3(u, v, k);
    const double turn = dot3(k, w->plane + 4 * f);
    return fabs(turn) > 1e-12 * (dot3(u, u) + dot3(v, v)) ? turn : 0.0;
}

/* Whether face f's panel is convex: every corner of its top and bottom
 * outlines turns the same way about its normal (corners that coincide, where
 * an edge was dropped, and straight ones left out). */
static int panel_convex(const work *w, int32_t f)
{
    const facet_mesh *m = w->mesh;
    const int64_t s = m->face_start[f], e = m->face_start[f + 1];
    int sign = 0;
    for (int side = 0; side < 2; ++side) {
        const double *x = side ? w->cbot : w->ctop;
        for (int64_t c = s; c < e; ++c) {
            const double turn = corner_turn(w, f, c, x);
            if (turn == 0.0)
                continue;
            if (sign == 0)
                sign = turn > 0.0 ? 1 : -1;
            else if ((turn > 0.0 ? 1 : -1) != sign)
                return 0;
        }
    }
    return 1;
}

/* Whether face f's panel turns back at corner c: its top or bottom outline
 * turns there against the outline's own sense about the panel's normal (a
 * reflex corner; corners that coincide, where an edge was dropped, and
 * straight ones are not). */
static int corner_reflex(const work *w, int32_t f, int64_t c)
{
    const facet_mesh *m = w->mesh;
    const double *n = w->plane + 4 * f;
    const int64_t s = m->face_start[f], e = m->face_start[f + 1];
    for (int side = 0; side < 2; ++side) {
        const double *x = side ? w->cbot : w->ctop;
        double area = 0.0;
        for (int64_t i = s; i < e; ++i) {
            double k[3];
            cross3(x + 3 * i, x + 3 * next_corner(m, f, i), k);
            area += dot3(k, n);
        }
        const double turn = corner_turn(w, f, c, x);
        if (turn != 0.0 && (turn > 0.0) != (area > 0.0))
            return 1;
    }
    return 0;
}

/* A convex piece of a panel: the solid between the top and bottom corners
 * of k of its corners, as indices into work.ctop and work.cbot: a triangle of
 * a concave panel's outline (corner), or a convex panel whole (corner NULL:
 * first, first + 1, ...). */
typedef struct {
    int64_t k;
    const int64_t *corner;
    int64_t first;
} piece;

static int64_t piece_corner(const piece *p, int64_t j)
{
    return p->corner ? p->corner[j] : p->first + j;
}

/* How far two pieces overlap along the unit axis u (negative: apart). */
static double piece_axis_overlap(const work *w, const piece *a, const piece *b, const double u[3])
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    const piece *pc[2] = {a, b};
    for (int i = 0; i < 2; ++i)
        for (int64_t j = 0; j < pc[i]->k; ++j)
            for (int side = 0; side < 2; ++side) {
                const double x = dot3(u, (side ? w->cbot : w->ctop) + 3 * piece_corner(pc[i], j));
                lo[i] = fmin(lo[i], x), hi[i] = fmax(hi[i], x);
            }
    return fmin(hi[0], hi[1]) - fmax(lo[0], lo[1]);
}

/* Direction kind of side j of the piece (its corners j and j + 1): 0 its top
 * edge, 1 its edge from bottom to top at corner j, 2 and 3 the diagonals of the
 * side (which is twisted where an inner side of a mitred panel's piece is). */
static void piece_edge(const work *w, const piece *p, int64_t j, int kind, double d[3])
{
    const int64_t a = piece_corner(p, j), b = piece_corner(p, j + 1 < p->k ? j + 1 : 0);
    const double *from = 3 * (kind == 3 ? b : a) + (kind == 0 ? w->ctop : w->cbot);
    const double *to = 3 * (kind == 0 || kind == 2 ? b : a) + w->ctop;
    for (int i = 0; i < 3; ++i)
        d[i] = to[i] - from[i];
}

/* The normals of the piece's sides into n[4 k][3], unnormalised: of each side
 * both triangles of each diagonal (they cover the side whichever way its convex
 * hull folds it). */
static void piece_normals(const work *w, const piece *p, double (*n)[3])
{
    for (int64_t j = 0; j < p->k; ++j) {
        const int64_t a = piece_corner(p, j), b = piece_corner(p, j + 1 < p->k ? j + 1 : 0);
        const double *tb = w->ctop + 3 * b, *ba = w->cbot + 3 * a, *bb = w->cbot + 3 * b;
        double up_a[3], diag_b[3], diag_a[3];
        piece_edge(w, p, j, 1, up_a);   /* ba ta */
        piece_edge(w, p, j, 2, diag_b); /* ba tb */
        piece_edge(w, p, j, 3, diag_a); /* bb ta */
        const double bottom[3] = {bb[0] - ba[0], bb[1] - ba[1], bb[2] - ba[2]};
        const double up_b[3] = {tb[0] - bb[0], tb[1] - bb[1], tb[2] - bb[2]};
        cross3(bottom, diag_b, n[4 * j]);     /* ba bb tb */
        cross3(diag_b, up_a, n[4 * j + 1]);   /* ba tb ta */
        cross3(bottom, up_a, n[4 * j + 2]);   /* ba bb ta */
        cross3(up_b, diag_a, n[4 * j + 3]);   /* bb tb ta */
    }
}

/* The least of `least` and the overlaps along the cross products of a's and
 * b's edge directions (piece_edge; of each side's four kinds, the first use:
 * 2, its top edge and its edge from bottom to top, are all a planar side has),
 * until they are parted. */
static double edge_axes_overlap(const work *w, const piece *a, const piece *b, int use,
                                double least)
{
    for (int64_t i = 0; i < a->k && least > JOINT_TOUCH; ++i)
        for (int ka = 0; ka < use && least > JOINT_TOUCH; ++ka) {
            double da[3];
            piece_edge(w, a, i, ka, da);
            for (int64_t j = 0; j < b->k && least > JOINT_TOUCH; ++j)
                for (int kb = 0; kb < use && least > JOINT_TOUCH; ++kb) {
                    double db[3], u[3];
                    piece_edge(w, b, j, kb, db);
                    cross3(da, db, u);
                    const double l = norm3(u);
                    if (!(l > 1e-9 * sqrt(dot3(da, da) * dot3(db, db))))
                        continue; /* parallel, or an edge of no length */
                    for (int k = 0; k < 3; ++k)
                        u[k] /= l;
                    least = fmin(least, piece_axis_overlap(w, a, b, u));
                }
        }
    return least;
}

/* How deep two convex pieces of the panels of faces f and h overlap (0 when
 * a separating axis parts them): separating axes of their convex hulls (the
 * panels' planes, the pieces' side planes and the cross products of their
 * edges' directions). */
static double piece_overlap(const work *w, int32_t f, int32_t h, const piece *a, const piece *b)
{
    double na[4 * FACET_PIECE_MAX][3], nb[4 * FACET_PIECE_MAX][3];
    piece_normals(w, a, na);
    piece_normals(w, b, nb);
    double least = fmin(piece_axis_overlap(w, a, b, w->plane + 4 * f),
                        piece_axis_overlap(w, a, b, w->plane + 4 * h));
    double(*normals[2])[3] = {na, nb};
    const int64_t count[2] = {4 * a->k, 4 * b->k};
    for (int i = 0; i < 2 && least > JOINT_TOUCH; ++i)
        for (int64_t j = 0; j < count[i] && least > JOINT_TOUCH; ++j) {
            double u[3] = {normals[i][j][0], normals[i][j][1], normals[i][j][2]};
            const double l = norm3(u);
            if (!(l > 0.0))
                continue;
            for (int k = 0; k < 3; ++k)
                u[k] /= l;
            least = fmin(least, piece_axis_overlap(w, a, b, u));
        }
    least = edge_axes_overlap(w, a, b, 4, least);
    return least > JOINT_TOUCH ? least : 0.0;
}

/* The triangles of face f's bottom outline (ear clipping in the face's plane;
 * corners that coincide, where an edge was dropped, taken once), 3 corner
 * indices each into tri; returns how many (0 when the outline has more than
 * FACET_PIECE_MAX corners or no ear is found). */
static int outline_triangles(const work *w, int32_t f, int64_t *tri)
{
    const facet_mesh *m = w->mesh;
    double ex[3], ey[3];
    plane_basis(w->plane + 4 * f, ex, ey);
    int64_t c[FACET_PIECE_MAX];
    double u[FACET_PIECE_MAX], v[FACET_PIECE_MAX];
    int k = 0;
    for (int64_t x = m->face_start[f]; x < m->face_start[f + 1]; ++x) {
        const double *p = w->cbot + 3 * x;
        const double px = dot3(ex, p), py = dot3(ey, p);
        if (k > 0 && px == u[k - 1] && py == v[k - 1])
            continue;
        if (k == FACET_PIECE_MAX)
            return 0;
        c[k] = x, u[k] = px, v[k] = py, ++k;
    }
    if (k > 1 && u[k - 1] == u[0] && v[k - 1] == v[0])
        --k;
    double area = 0.0;
    for (int i = 0; i < k; ++i) {
        const int j = i + 1 < k ? i + 1 : 0;
        area += u[i] * v[j] - u[j] * v[i];
    }
    const double sgn = area < 0.0 ? -1.0 : 1.0;
    int count = 0;
    while (k > 3) {
        int ear = -1;
        for (int i = 0; i < k && ear < 0; ++i) {
            const int a = i > 0 ? i - 1 : k - 1, b = i + 1 < k ? i + 1 : 0;
            const double turn = (u[i] - u[a]) * (v[b] - v[i]) - (v[i] - v[a]) * (u[b] - u[i]);
            if (!(sgn * turn > 0.0))
                continue;
            int inside = 0;
            for (int j = 0; j < k && !inside; ++j) {
                if (j == a || j == i || j == b)
                    continue;
                const double d0 = (u[i] - u[a]) * (v[j] - v[a]) - (v[i] - v[a]) * (u[j] - u[a]);
                const double d1 = (u[b] - u[i]) * (v[j] - v[i]) - (v[b] - v[i]) * (u[j] - u[i]);
                const double d2 = (u[a] - u[b]) * (v[j] - v[b]) - (v[a] - v[b]) * (u[j] - u[b]);
                inside = sgn * d0 >= 0.0 && sgn * d1 >= 0.0 && sgn * d2 >= 0.0;
            }
            if (!inside)
                ear = i;
        }
        if (ear < 0)
            return 0;
        const int a = ear > 0 ? ear - 1 : k - 1, b = ear + 1 < k ? ear + 1 : 0;
        tri[3 * count] = c[a], tri[3 * count + 1] = c[ear], tri[3 * count + 2] = c[b];
        ++count;
        for (int j = ear; j + 1 < k; ++j)
            c[j] = c[j + 1], u[j] = u[j + 1], v[j] = v[j + 1];
        --k;
    }
    if (k == 3) {
        tri[3 * count] = c[0], tri[3 * count + 1] = c[1], tri[3 * count + 2] = c[2];
        ++count;
    }
    return count;
}

/* How deep the panels of faces f and h overlap where they meet at a node,
 * normalised units (0 when they do not). Both convex: by separating axes,
 * exactly (the planes of either solid and the cross products of their edges'
 * directions; the least overlap along them, the distance that would part
 * them). A concave panel by convex pieces: its outline's triangles (each the
 * convex hull of its six corners; piece_overlap), against the other panel's
 * pieces, the deepest pair's overlap; one of more than FACET_PIECE_MAX
 * corners (or whose outline has no ear) by its corners inside the other
 * (depth_in_panel), which can miss two panels that cross without a corner
 * inside. */
static double node_overlap(const work *w, const int8_t *convex, int32_t f, int32_t h, double up,
                           double down)
{
    const facet_mesh *m = w->mesh;
    const int32_t faces[2] = {f, h};
    const piece whole[2] = {{m->face_start[f + 1] - m->face_start[f], NULL, m->face_start[f]},
                            {m->face_start[h + 1] - m->face_start[h], NULL, m->face_start[h]}};
    double deepest = 0.0;
    if (!convex[f] || !convex[h]) {
        /* convex pieces: a concave panel's triangles, a convex one whole */
        int64_t tri[2][3 * FACET_PIECE_MAX];
        int np[2] = {0, 0};
        for (int i = 0; i < 2; ++i)
            np[i] = convex[faces[i]] && whole[i].k <= FACET_PIECE_MAX
                        ? 1
                        : outline_triangles(w, faces[i], tri[i]);
        if (np[0] > 0 && np[1] > 0) {
            for (int i = 0; i < np[0]; ++i)
                for (int j = 0; j < np[1]; ++j) {
                    const piece a = convex[f] ? whole[0] : (piece){3, tri[0] + 3 * i, 0};
                    const piece b = convex[h] ? whole[1] : (piece){3, tri[1] + 3 * j, 0};
                    deepest = fmax(deepest, piece_overlap(w, f, h, &a, &b));
                }
            return deepest;
        }
        /* a panel of more corners than pieces take: its corners inside the other */
        for (int i = 0; i < 2; ++i)
            for (int64_t c = m->face_start[faces[i]]; c < m->face_start[faces[i] + 1]; ++c) {
                deepest = fmax(deepest, depth_in_panel(w, faces[1 - i], w->ctop + 3 * c, up, down));
                deepest = fmax(deepest, depth_in_panel(w, faces[1 - i], w->cbot + 3 * c, up, down));
            }
        return deepest;
    }
    double least = INFINITY;
    /* the solids' planes: top and bottom, and each side face's (its edge's
     * plane; a dropped edge has no side face) */
    for (int i = 0; i < 2; ++i) {
        least = fmin(least, piece_axis_overlap(w, &whole[0], &whole[1], w->plane + 4 * faces[i]));
        for (int64_t c = m->face_start[faces[i]]; c < m->face_start[faces[i] + 1]; ++c)
            if (!w->drop[c])
                least = fmin(least, piece_axis_overlap(w, &whole[0], &whole[1], w->eplane + 4 * c));
        if (!(least > JOINT_TOUCH))
            return 0.0;
    }
    /* edge against edge: the top edges (the bottom edges are parallel to them)
     * and the edges from bottom to top */
    least = edge_axes_overlap(w, &whole[0], &whole[1], 2, least);
    return least > JOINT_TOUCH ? least : 0.0;
}

facet_status facet_panels(const facet_mesh *mesh, const facet_panel_options *options,
                          facet_panel_output *out, facet_panel_result *result,
                          facet_error *error)
{
    const double t_start = facet_now();
    facet_error_clear(error);
    facet_status status = facet_mesh_check_arrays(mesh, error);
    if (status < 0)
        return status;
    if (!mesh->xyz) /* was read unchecked */
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1, "mesh has no coordinates");
    status = facet_mesh_check_indices(mesh, error);
    if (status < 0)
        return status;
    if (!options || !out)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1,
                          "options and out must not be NULL");
    const facet_panel_options *o = options;
    /* " mm": written after every length in a message (nothing in model units) */
    char unit[40] = "";
    if (o->length_unit && o->length_unit[0])
        snprintf(unit, sizeof unit, " %s", o->length_unit);
    if (!(o->thickness > 0.0) || !isfinite(o->thickness))
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1,
                          "thickness must be a finite number > 0, not %.17g%s", o->thickness,
                          isfinite(o->thickness) ? unit : "");
    if (!(o->gap >= 0.0) || !isfinite(o->gap))
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1,
                          "gap must be a finite number >= 0, not %.17g%s", o->gap,
                          isfinite(o->gap) ? unit : "");
    if (o->offset != FACET_PANEL_OFFSET_OUTER && o->offset != FACET_PANEL_OFFSET_INNER &&
        o->offset != FACET_PANEL_OFFSET_CENTER)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1,
                          "offset must be outer, inner or center (%d)", (int)o->offset);
    if (o->edge != FACET_PANEL_EDGE_SQUARE && o->edge != FACET_PANEL_EDGE_BISECTOR)
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1,
                          "edge must be square or bisector (%d)", (int)o->edge);
    if (!(o->planarity_tol_abs >= 0.0) || !(o->planarity_tol_rel >= 0.0) ||
        !isfinite(o->planarity_tol_abs) || !isfinite(o->planarity_tol_rel))
        return facet_fail(error, FACET_ERROR_INVALID_ARGUMENT, -1, -1,
                          "planarity tolerances must be finite numbers >= 0");

    const facet_mesh *m = mesh;
    const int32_t nf = m->n_faces, nv = m->n_vertices;
    work w;
    memset(&w, 0, sizeof w);
    w.mesh = m;
    w.nc = m->face_start[nf];
    const size_t nc = (size_t)w.nc;
    w.corner_face = malloc(nc * sizeof *w.corner_face);
    w.nbr = malloc(nc * sizeof *w.nbr);
    w.nbr_corner = malloc(nc * sizeof *w.nbr_corner);
    w.sign = malloc((size_t)nf);
    w.xyz = malloc(3 * (size_t)nv * sizeof *w.xyz);
    w.plane = malloc(4 * (size_t)nf * sizeof *w.plane);
    w.eplane = malloc(4 * nc * sizeof *w.eplane);
    w.fold = malloc(nc * sizeof *w.fold);
    w.drop = malloc(nc * sizeof *w.drop);
    w.square = malloc(nc * sizeof *w.square);
    w.ctop = malloc(3 * nc * sizeof *w.ctop);
    w.cbot = malloc(3 * nc * sizeof *w.cbot);
    if (!w.corner_face || !w.nbr || !w.nbr_corner || !w.sign || !w.xyz || !w.plane ||
        !w.eplane || !w.fold || !w.drop || !w.square || !w.ctop || !w.cbot) {
        work_free(&w);
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1,
                          "out of memory for %d faces", (int)nf);
    }
    facet_panel_result r;
    memset(&r, 0, sizeof r);
    r.worst_node = -1;
    r.narrowest_repaired_joint = -1.0;
    r.narrowest_joint_vertex = -1;
    r.narrowest_joint_faces[0] = r.narrowest_joint_faces[1] = -1;
    r.node_clash_vertex = -1;
    r.node_clash_faces[0] = r.node_clash_faces[1] = -1;
    r.failed_joint_faces[0] = r.failed_joint_faces[1] = -1;

    /* Centre and scale. */
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int32_t v = 0; v < nv; ++v)
        for (int k = 0; k < 3; ++k) {
            const double x = m->xyz[3 * v + k];
            if (!isfinite(x)) {
                work_free(&w);
                return facet_fail(error, FACET_ERROR_NONFINITE, -1, v,
                                  "vertex %d has a NaN or infinite coordinate", (int)v);
            }
            if (!facet_point_in_range(&x, 1)) {
                work_free(&w);
                return facet_fail(error, FACET_ERROR_COORDINATE_RANGE, -1, v,
                                  "vertex %d has a coordinate beyond 1e30 in magnitude (%g%s)",
                                  (int)v, x, unit);
            }
            lo[k] = fmin(lo[k], x), hi[k] = fmax(hi[k], x);
        }
    double centre[3], scale = 0.0;
    for (int k = 0; k < 3; ++k) {
        centre[k] = 0.5 * (lo[k] + hi[k]);
        scale = fmax(scale, hi[k] - lo[k]);
    }
    if (!isfinite(scale)) { /* would scale every vertex to 0 and give NaN planes */
        work_free(&w);
        return facet_fail(error, FACET_ERROR_TOO_LARGE, -1, -1,
                          "coordinates too large: the mesh's extent overflows a double");
    }
    if (!(scale > 0.0))
        scale = 1.0;
    const double inv = 1.0 / scale;
    for (int32_t v = 0; v < nv; ++v)
        for (int k = 0; k < 3; ++k)
            w.xyz[3 * v + k] = (m->xyz[3 * v + k] - centre[k]) * inv;
    const double th = o->thickness * inv, half_gap = 0.5 * o->gap * inv;

    status = build_adjacency(&w, &r.n_non_manifold_edges, error);
    if (status == FACET_OK)
        status = orient(&w, o->flip != 0, &r.n_components, error);
    if (status < 0) {
        work_free(&w);
        return status;
    }

    /* Planes and planarity. */
    int64_t n_bad = 0;
    for (int32_t f = 0; f < nf; ++f) {
        const int32_t s = m->face_start[f], d = m->face_start[f + 1] - s;
        double n[3], off, maxd;
        const double mean_edge =
            facet_face_measure(d, w.xyz, m->face_vertices + s, n, &off, &maxd, NULL);
        /* Newell normal gives the winding's side. */
        double nw[3] = {0, 0, 0};
        for (int32_t k = 0; k < d; ++k) {
            const double *p = w.xyz + 3 * m->face_vertices[s + k];
            const double *q = w.xyz + 3 * m->face_vertices[s + (k + 1) % d];
            nw[0] += (p[1] - q[1]) * (p[2] + q[2]);
            nw[1] += (p[2] - q[2]) * (p[0] + q[0]);
            nw[2] += (p[0] - q[0]) * (p[1] + q[1]);
        }
        double sg = dot3(n, nw) < 0.0 ? -1.0 : 1.0;
        sg *= w.sign[f];
        w.plane[4 * f + 0] = sg * n[0];
        w.plane[4 * f + 1] = sg * n[1];
        w.plane[4 * f + 2] = sg * n[2];
        w.plane[4 * f + 3] = sg * off;
        const double dist = maxd * scale;
        if (out->planarity)
            out->planarity[f] = dist;
        r.max_planarity = fmax(r.max_planarity, dist);
        const double tol = fmax(o->planarity_tol_abs, o->planarity_tol_rel * mean_edge * scale);
        if (dist > tol) {
            if (out->nonplanar)
                out->nonplanar[n_bad] = f;
            ++n_bad;
        }
        if (w.sign[f] < 0)
            ++r.n_reversed;
        if (out->reversed)
            out->reversed[f] = w.sign[f] < 0;
    }
    r.n_nonplanar = n_bad;
    if (n_bad > 0) {
        char list[160] = "";
        size_t used = 0;
        int64_t shown = 0;
        for (int32_t f = 0; f < nf && shown < 5; ++f) {
            const int32_t s = m->face_start[f];
            double n[3], maxd;
            const double me =
                facet_face_measure(m->face_start[f + 1] - s, w.xyz, m->face_vertices + s, n,
                                   NULL, &maxd, NULL);
            const double tol = fmax(o->planarity_tol_abs, o->planarity_tol_rel * me * scale);
            if (maxd * scale > tol) {
                int len = snprintf(list + used, sizeof list - used, "%s%d (%.3g%s)",
                                   shown ? ", " : "", (int)f, maxd * scale, unit);
                if (len > 0 && (size_t)len < sizeof list - used)
                    used += (size_t)len;
                ++shown;
            }
        }
        work_free(&w);
        r.seconds = facet_now() - t_start;
        if (result)
            *result = r;
        return facet_fail(error, FACET_ERROR_NOT_PLANAR, -1, -1,
                          "%lld face%s not planar within the tolerance: %s%s; planarize first",
                          (long long)n_bad, n_bad == 1 ? " is" : "s are", list,
                          n_bad > shown ? ", ..." : "");
    }

    /* Edge planes and fold angles, per input corner (edge corner -> next). */
    for (int32_t f = 0; f < nf; ++f) {
        for (int64_t c = m->face_start[f]; c < m->face_start[f + 1]; ++c) {
            w.square[c] = o->edge == FACET_PANEL_EDGE_SQUARE || w.nbr[c] < 0 ? CUT_SQUARE : CUT_MITRE;
            status = edge_plane(&w, f, c, half_gap, out, error);
            if (status < 0) {
                work_free(&w);
                return status;
            }
            if (fabs(w.fold[c]) <= 1e-12) /* flat: the mitre is square */
                w.square[c] = CUT_SQUARE;
        }
        if (o->progress && (f & 1023) == 1023 && o->progress(o->progress_user, f + 1, 2 * (int64_t)nf)) {
            work_free(&w);
            return facet_fail(error, FACET_ERROR_CANCELLED, -1, -1, "cancelled");
        }
    }

    /* Offsets of the top and bottom planes from the mesh plane. */
    double up = th, down = 0.0;
    if (o->offset == FACET_PANEL_OFFSET_INNER)
        up = 0.0, down = -th;
    else if (o->offset == FACET_PANEL_OFFSET_CENTER)
        up = 0.5 * th, down = -0.5 * th;

    /* Outlines: each corner is where the top (bottom) plane meets the planes
     * of the two edges at that corner. Every edge of the offset outlines must
     * keep its direction: a gap or bevel wider than the panel turns an edge
     * around. Where the edge and the kept edges on either side of it are
     * square, the outlines there are the face's outline offset in its plane
     * (a mitred offset), and such an edge is dropped, as a CAD offset drops
     * it: its two corners become the one where its neighbours' edge lines
     * meet, in both outlines (a quad becomes a triangle panel). A mitred
     * joint there cannot be cut (the mitre of a short edge, or two mitres of
     * different angles meeting beyond a nearly straight corner): the mitres
     * beside the edge, then its own, become butt joints (square on this
     * panel, the whole fold on the neighbour's), and the faces they touch are
     * outlined again. With repair_consumed 0 either is an error. */
    const int repair = o->repair_consumed != 0;
    int32_t reported = 0; /* faces outlined, as progress told (a repair outlines some again) */
    for (int32_t f = 0; f < nf; ++f) {
        const double *n = w.plane + 4 * f;
        const int32_t s = m->face_start[f], d = m->face_start[f + 1] - s;
        int32_t active = d, again = -1;
        for (int64_t c = s; c < s + d; ++c)
            w.drop[c] = 0;
        for (;;) {
            /* the edge turned around the most, if any */
            int64_t worst = -1;
            int worst_side = 0;
            double worst_ratio = 0.0, worst_length = 0.0;
            for (int64_t c = s; c < s + d; ++c) {
                if (w.drop[c])
                    continue;
                const int64_t cn = next_corner(m, f, c);
                const double *p = w.xyz + 3 * m->face_vertices[c];
                const double *q = w.xyz + 3 * m->face_vertices[cn];
                const double *a = w.eplane + 4 * active_before(&w, f, c), *b = w.eplane + 4 * c,
                             *bb = w.eplane + 4 * active_after(&w, f, c);
                const double ed[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
                for (int side = 0; side < 2; ++side) {
                    const double h = side ? down : up;
                    double x0[3], x1[3];
                    /* parallel planes apart: no corner, which the corners'
                     * pass below reports (collinear edges) */
                    if (!corner_point(n, h - n[3], a, b, p, x0) ||
                        !corner_point(n, h - n[3], b, bb, q, x1))
                        continue;
                    const double od[3] = {x1[0] - x0[0], x1[1] - x0[1], x1[2] - x0[2]};
                    const double ratio = dot3(ed, od) / dot3(ed, ed);
                    if (!(ratio > 1e-9) && (worst < 0 || !(ratio >= worst_ratio))) {
                        worst = c, worst_side = side, worst_ratio = ratio;
                        worst_length = norm3(ed) * scale;
                    }
                }
            }
            if (worst < 0)
                break;
            /* the mitres beside the edge first (theirs are what consume a
             * short edge), then its own (a dropped edge's corners are the
             * same in both outlines only when all three are square) */
            int64_t around[2] = {active_before(&w, f, worst), active_after(&w, f, worst)};
            if (is_square(w.square[around[0]]) && is_square(w.square[around[1]]))
                around[0] = around[1] = worst;
            if (repair && !(is_square(w.square[around[0]]) && is_square(w.square[around[1]]))) {
                status = square_joints(&w, f, around, half_gap, out, error, &again);
                if (status < 0) {
                    work_free(&w);
                    return status;
                }
                break;
            }
            if (!repair || active <= 3) {
                work_free(&w);
                if (repair)
                    return facet_fail(error, FACET_ERROR_PANEL_GEOMETRY, f, m->face_vertices[worst],
                                      "face %d: the gap %.6g%s leaves fewer than three edges of its "
                                      "outline (the edge from vertex %d is %.6g%s long)",
                                      (int)f, o->gap, unit, (int)m->face_vertices[worst],
                                      worst_length, unit);
                return facet_fail(error, FACET_ERROR_PANEL_GEOMETRY, f, m->face_vertices[worst],
                                  "face %d: the %s outline loses its edge from vertex %d, %.6g%s "
                                  "long (gap %.6g%s or bevel too large for the panel; or collapse "
                                  "short edges first)",
                                  (int)f, worst_side ? "bottom" : "top",
                                  (int)m->face_vertices[worst], worst_length, unit, o->gap, unit);
            }
            w.drop[worst] = 1;
            --active;
        }
        if (again >= 0) {
            f = again - 1; /* (the loop's ++f) */
            continue;
        }
        for (int64_t c = s; c < s + d; ++c) {
            /* the edges before and after the corner that are kept: the input's
             * edges, or two that the gap brought together by consuming those
             * between them (an L's arm) */
            const int64_t before = active_before(&w, f, c);
            const double *a = w.eplane + 4 * before,
                         *b = w.eplane + 4 * (w.drop[c] ? active_after(&w, f, c) : c);
            const int dropped = w.drop[c] || before != prev_corner(m, f, c);
            const double *p = w.xyz + 3 * m->face_vertices[c];
            double xt[3], xb[3];
            int found = dropped ? solve3(n, up - n[3], a, a[3], b, b[3], xt) != 0.0 &&
                                      solve3(n, down - n[3], a, a[3], b, b[3], xb) != 0.0
                                : corner_point(n, up - n[3], a, b, p, xt) &&
                                      corner_point(n, down - n[3], a, b, p, xb);
            if (found && !dropped && repair && (w.nbr[before] < 0) != (w.nbr[c] < 0) &&
                far_corner(n, up, down, a, b, w.xyz + 3 * m->face_vertices[prev_corner(m, f, c)],
                           p, w.xyz + 3 * m->face_vertices[next_corner(m, f, c)], xt, xb, th))
                found = 0; /* a nearly straight corner between different cuts: as a straight one */
            if (!found) {
                /* a straight corner between joints cut at different angles
                 * (a mitre beside a free edge, or beside a repaired joint):
                 * beside a butt joint the mitre becomes one too where the two
                 * meet; else square them, as a consumed mitre is */
                const int64_t around[2] = {before, c};
                if (!dropped && repair &&
                    !(is_square(w.square[before]) && is_square(w.square[c]))) {
                    if (!butt_beside_mitre(&w, f, before, c, up, down, half_gap, out, error,
                                           &again, &status) &&
                        status == FACET_OK)
                        status = square_joints(&w, f, around, half_gap, out, error, &again);
                    if (status < 0) {
                        work_free(&w);
                        return status;
                    }
                    break;
                }
                work_free(&w);
                if (dropped) /* the gap is what to change */
                    return facet_fail(error, FACET_ERROR_PANEL_GEOMETRY, f, m->face_vertices[c],
                                      "face %d: the gap %.6g%s consumes edges of its outline until "
                                      "two parallel ones meet (at vertex %d); use a smaller gap "
                                      "or split the face",
                                      (int)f, o->gap, unit, (int)m->face_vertices[c]);
                return facet_fail(error, FACET_ERROR_PANEL_GEOMETRY, f, m->face_vertices[c],
                                  "face %d: the edges at vertex %d are collinear and their joints "
                                  "are cut at different angles, which would need a step in the "
                                  "panel's side; cut them square or split the face",
                                  (int)f, (int)m->face_vertices[c]);
            }
            for (int k = 0; k < 3; ++k) {
                w.ctop[3 * c + k] = xt[k];
                w.cbot[3 * c + k] = xb[k];
                if (out->top)
                    out->top[3 * c + k] = xt[k] * scale + centre[k];
                if (out->bottom)
                    out->bottom[3 * c + k] = xb[k] * scale + centre[k];
            }
            if (out->dropped)
                out->dropped[c] = w.drop[c];
        }
        if (again >= 0) {
            f = again - 1; /* (the loop's ++f) */
            continue;
        }
        if (out->plane) {
            out->plane[4 * f + 0] = n[0];
            out->plane[4 * f + 1] = n[1];
            out->plane[4 * f + 2] = n[2];
            out->plane[4 * f + 3] = n[3] * scale - dot3(n, centre);
        }
        if (out->frame) {
            const double *p = w.xyz + 3 * m->face_vertices[s];
            const double *q = w.xyz + 3 * m->face_vertices[s + 1];
            const double pd = dot3(n, p) + n[3];
            const double p0[3] = {p[0] - pd * n[0], p[1] - pd * n[1], p[2] - pd * n[2]};
            double ex[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
            in_plane_unit(ex, n);
            double ey[3];
            cross3(n, ex, ey);
            double *F = out->frame + 12 * f;
            const double *rows[3] = {ex, ey, n};
            /* flat = R (x - origin) with origin = p0 * scale + centre. */
            for (int i = 0; i < 3; ++i) {
                double org = 0.0;
                for (int k = 0; k < 3; ++k) {
                    F[3 * i + k] = rows[i][k];
                    org += rows[i][k] * (p0[k] * scale + centre[k]);
                }
                F[9 + i] = -org;
            }
        }
        if (o->progress && (f & 1023) == 1023 && f + 1 > reported &&
            o->progress(o->progress_user, nf + (reported = f + 1), 2 * (int64_t)nf)) {
            work_free(&w);
            return facet_fail(error, FACET_ERROR_CANCELLED, -1, -1, "cancelled");
        }
    }
    /* What the repairs did, and every joint's narrowest width (joint_overlap).
     * A repaired joint that had to be square on both panels must not close on
     * them (an error: the repair is this function's); any other joint whose
     * panels overlap (square cuts on the inner side of a fold, with too small
     * a gap) is counted, with the gap that would clear it. */
    double narrowest = INFINITY, narrowest_repaired = INFINITY, clearing = 0.0;
    int64_t narrowest_c = -1;
    if (out->clash)
        for (int32_t f = 0; f < nf; ++f)
            out->clash[f] = 0.0;
    for (int32_t f = 0; f < nf; ++f)
        for (int64_t c = m->face_start[f]; c < m->face_start[f + 1]; ++c) {
            r.n_dropped_edges += w.drop[c];
            r.n_squared_edges += w.square[c] == CUT_SQUARED;
            r.n_butt_edges += w.square[c] == CUT_BUTT;
            if (out->squared)
                out->squared[c] = w.square[c] == CUT_SQUARED ? 1 : w.square[c] == CUT_BUTT ? 2 : 0;
            const int64_t t = w.nbr_corner[c];
            if (t < 0 && out->joint)
                out->joint[c] = 0.0;
            if (t < c) /* the boundary, or measured from its twin */
                continue;
            double width;
            const double depth = joint_overlap(&w, f, c, up, down, 0.0, &width);
            const int repaired = w.square[c] == CUT_SQUARED || w.square[t] == CUT_SQUARED;
            /* a panel has no side there (or the section has no corners: planes
             * that do not meet, which the outlines would have refused): no joint.
             * The section would have measured a side the panel does not have (the
             * dropped edge's plane): its panels are measured as a node's (the
             * node test below), an overlap there counted, not an error. */
            if (w.drop[c] || w.drop[t] || !isfinite(width)) {
                if (out->joint)
                    out->joint[c] = out->joint[t] = 0.0;
                continue;
            }
            if (repaired) {
                narrowest_repaired = fmin(narrowest_repaired, width);
                if (depth > JOINT_TOUCH) {
                    const int32_t other = w.corner_face[t];
                    work_free(&w);
                    r.failed_joint_faces[0] = f, r.failed_joint_faces[1] = other;
                    r.failed_joint_overlap = depth * scale;
                    r.seconds = facet_now() - t_start;
                    if (result)
                        *result = r;
                    return facet_fail(error, FACET_ERROR_PANEL_GEOMETRY, f, m->face_vertices[c],
                                      "faces %d and %d: their mitre at the edge from vertex %d "
                                      "cannot be cut (it would consume a short edge or meet "
                                      "beyond a nearly straight corner on both panels), and "
                                      "cut square on both the panels overlap by %.3g%s there",
                                      (int)f, (int)other, (int)m->face_vertices[c],
                                      depth * scale, unit);
                }
            }
            if (out->joint)
                out->joint[c] = out->joint[t] = width * scale;
            if (width < narrowest)
                narrowest = width, narrowest_c = c;
            if (!repaired && depth > JOINT_TOUCH) {
                ++r.n_overlapping_joints;
                if (out->clash) {
                    const int32_t h = w.corner_face[t];
                    out->clash[f] = fmax(out->clash[f], depth * scale);
                    out->clash[h] = fmax(out->clash[h], depth * scale);
                }
                clearing = fmax(clearing, clearing_gap(&w, f, c, up, down, half_gap));
            }
        }
    if (isfinite(narrowest_repaired))
        r.narrowest_repaired_joint = narrowest_repaired * scale;
    if (narrowest_c >= 0) {
        r.narrowest_joint = narrowest * scale;
        r.narrowest_joint_vertex = m->face_vertices[narrowest_c];
        r.narrowest_joint_faces[0] = w.corner_face[narrowest_c];
        r.narrowest_joint_faces[1] = w.corner_face[w.nbr_corner[narrowest_c]];
    }
    r.clearing_gap = clearing * scale;

    /* Nodes: panels that meet at a vertex but not across a joint there (a
     * node's diagonal neighbours, or across an edge one of them dropped), and
     * across a joint at a reflex corner of either, must not overlap either.
     * Where the node's edge planes miss a common axis, or with square cuts, a
     * corner of one can lie inside the other. */
    int64_t *node_start = calloc((size_t)nv + 1, sizeof *node_start);
    int64_t *node_corner = malloc((nc ? nc : 1) * sizeof *node_corner);
    int8_t *convex = malloc((size_t)(nf ? nf : 1));
    if (!node_start || !node_corner || !convex) {
        free(node_start);
        free(node_corner);
        free(convex);
        work_free(&w);
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory (nodes)");
    }
    for (int64_t c = 0; c < (int64_t)nc; ++c)
        ++node_start[m->face_vertices[c] + 1];
    for (int32_t v = 0; v < nv; ++v)
        node_start[v + 1] += node_start[v];
    for (int64_t c = 0; c < (int64_t)nc; ++c)
        node_corner[node_start[m->face_vertices[c]]++] = c;
    for (int32_t v = nv; v > 0; --v) /* back to the starts */
        node_start[v] = node_start[v - 1];
    node_start[0] = 0;
    for (int32_t f = 0; f < nf; ++f)
        convex[f] = (int8_t)panel_convex(&w, f);
    double deepest_node = 0.0;
    for (int32_t v = 0; v < nv; ++v) {
        if (out->node_clash)
            out->node_clash[v] = 0.0;
        for (int64_t i = node_start[v]; i < node_start[v + 1]; ++i)
            for (int64_t j = i + 1; j < node_start[v + 1]; ++j) {
                const int64_t ci = node_corner[i];
                const int32_t f = w.corner_face[ci], h = w.corner_face[node_corner[j]];
                if (f == h)
                    continue;
                /* across a joint the joint's width measures them, in its section:
                 * exactly when both are convex (each lies behind its side plane);
                 * a concave panel reaches past the side plane at a reflex corner
                 * (its other edge's bevel there), so a pair with a reflex corner at
                 * this end of their joint is tested whole too, unless the joint
                 * already overlaps (counted there) */
                const int64_t jc = joint_at(&w, f, ci, h);
                if (jc >= 0) {
                    double width;
                    if ((convex[f] && convex[h]) ||
                        !(corner_reflex(&w, f, ci) || corner_reflex(&w, h, node_corner[j])) ||
                        joint_overlap(&w, f, jc, up, down, 0.0, &width) > JOINT_TOUCH)
                        continue;
                }
                const double depth = node_overlap(&w, convex, f, h, up, down);
                if (!(depth > JOINT_TOUCH))
                    continue;
                ++r.n_node_clashes;
                if (out->node_clash)
                    out->node_clash[v] = fmax(out->node_clash[v], depth * scale);
                if (out->clash) {
                    out->clash[f] = fmax(out->clash[f], depth * scale);
                    out->clash[h] = fmax(out->clash[h], depth * scale);
                }
                if (depth > deepest_node) {
                    deepest_node = depth;
                    r.node_clash_faces[0] = f, r.node_clash_faces[1] = h;
                    r.node_clash_vertex = v;
                }
            }
    }
    r.deepest_node_clash = deepest_node * scale;
    free(node_start);
    free(node_corner);
    free(convex);

    /* Node deviation from the bisector planes (the mesh's own property,
     * whatever the edge mode): each undirected edge once. */
    double *acc = calloc(7 * (size_t)(nv ? nv : 1), sizeof *acc);
    double *axis = malloc(3 * (size_t)(nv ? nv : 1) * sizeof *axis);
    if (!acc || !axis) {
        free(acc);
        free(axis);
        work_free(&w);
        return facet_fail(error, FACET_ERROR_OUT_OF_MEMORY, -1, -1, "out of memory (nodes)");
    }
    for (int pass = 0; pass < 2; ++pass) {
        for (int32_t f = 0; f < nf; ++f) {
            const double *n = w.plane + 4 * f;
            const double sg = w.sign[f];
            for (int64_t c = m->face_start[f]; c < m->face_start[f + 1]; ++c) {
                const int32_t h = w.nbr[c];
                if (h >= 0 && h < f)
                    continue;
                const int32_t va = m->face_vertices[c];
                const int32_t vb = m->face_vertices[next_corner(m, f, c)];
                const double *p = w.xyz + 3 * va, *q = w.xyz + 3 * vb;
                double e[3] = {sg * (q[0] - p[0]), sg * (q[1] - p[1]), sg * (q[2] - p[2])};
                double b[3];
                if (h >= 0) {
                    const double *nh = w.plane + 4 * h;
                    const double avg[3] = {n[0] + nh[0], n[1] + nh[1], n[2] + nh[2]};
                    cross3(e, avg, b);
                } else {
                    cross3(n, e, b);
                }
                const double lb = norm3(b);
                if (!(lb > 0.0))
                    continue;
                for (int k = 0; k < 3; ++k)
                    b[k] /= lb;
                const int32_t ends[2] = {va, vb};
                for (int j = 0; j < 2; ++j) {
                    const int32_t v = ends[j];
                    if (pass == 0) {
                        double *A = acc + 7 * v;
                        A[0] += b[0] * b[0], A[1] += b[0] * b[1], A[2] += b[0] * b[2];
                        A[3] += b[1] * b[1], A[4] += b[1] * b[2], A[5] += b[2] * b[2];
                        A[6] += 1.0;
                    } else if (acc[7 * v + 6] >= 3.0) {
                        const double dev = asin(fmin(1.0, fabs(dot3(b, axis + 3 * v))));
                        if (dev > acc[7 * v]) /* acc[7v] reused as the max */
                            acc[7 * v] = dev;
                    }
                }
            }
        }
        if (pass == 0)
            for (int32_t v = 0; v < nv; ++v) {
                if (acc[7 * v + 6] >= 3.0)
                    facet_sym3_smallest_eigenvector(acc + 7 * v, axis + 3 * v);
                acc[7 * v] = 0.0; /* from now on: the largest deviation */
            }
    }
    for (int32_t v = 0; v < nv; ++v) {
        const double dev = acc[7 * v];
        if (out->node_deviation)
            out->node_deviation[v] = dev;
        if (dev > r.max_node_deviation) {
            r.max_node_deviation = dev;
            r.worst_node = v;
        }
    }
    free(acc);
    free(axis);
    work_free(&w);
    r.seconds = facet_now() - t_start;
    if (result)
        *result = r;
    if (r.n_non_manifold_edges > 0)
        return facet_fail(error, FACET_WARNING_PANEL_NON_MANIFOLD, -1, -1,
                          "%lld non-manifold edges treated as boundary",
                          (long long)r.n_non_manifold_edges);
    return FACET_OK;
}
