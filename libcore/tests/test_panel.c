/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Panel geometry against known answers: a planar-quad grid on a cylinder
 * (exactly planar, torsion-free) and a roof ridge. */
#include "check.h"
#include "facet.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

/* nu x nv quads on a cylinder of radius R (vertices on the circle at
 * angles i*da, heights j*h). Faces wound (i,j) (i+1,j) (i+1,j+1) (i,j+1). */
enum { NU = 4, NV = 3 };
static double xyz[3 * (NU + 1) * (NV + 1)];
static int32_t start[NU * NV + 1], fv[4 * NU * NV];

static void cylinder(double R, double da, double h)
{
    for (int j = 0; j <= NV; ++j)
        for (int i = 0; i <= NU; ++i) {
            double *p = xyz + 3 * (j * (NU + 1) + i);
            p[0] = R * cos(i * da), p[1] = R * sin(i * da), p[2] = j * h;
        }
    int f = 0;
    for (int j = 0; j < NV; ++j)
        for (int i = 0; i < NU; ++i, ++f) {
            start[f] = 4 * f;
            int32_t *q = fv + 4 * f;
            q[0] = j * (NU + 1) + i, q[1] = q[0] + 1, q[2] = q[1] + NU + 1, q[3] = q[0] + NU + 1;
        }
    start[f] = 4 * f;
}

static double dist3(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

static int cancel_now(void *user, int64_t done, int64_t total)
{
    (void)user, (void)done, (void)total;
    return 1;
}

/* Distance of the point from the line through a and b (in the xy plane). */
static double line_distance(const double *x, const double *a, const double *b)
{
    const double ux = b[0] - a[0], uy = b[1] - a[1], l = sqrt(ux * ux + uy * uy);
    return fabs((x[0] - a[0]) * uy - (x[1] - a[1]) * ux) / l;
}

/* A gap that consumes a short edge: square edges drop it (the quad becomes a
 * triangle panel whose corners lie half the gap inside the other three edge
 * lines, the same point in both outlines); mitred edges, or repair_consumed 0,
 * name it in an error; a gap that leaves fewer than three edges is an error. */
static void consumed_edge(void)
{
    /* at georeferenced coordinates: the test is of the geometry, not of the
     * coordinates' size */
    const double ox = 2.5e6, oy = 1.2e6;
    /* a sharp triangle with its tip cut off by an edge 0.2 long */
    double q[12] = {0, 0, 0, 10, 0, 0, 5.1, 20, 0, 4.9, 20, 0};
    for (int v = 0; v < 4; ++v)
        q[3 * v] += ox, q[3 * v + 1] += oy;
    int32_t qs[2] = {0, 4}, qf[4] = {0, 1, 2, 3};
    facet_mesh qm = {4, 1, q, qs, qf};
    double top[12], bottom[12];
    int32_t dropped[4] = {-1, -1, -1, -1};
    facet_panel_output out;
    memset(&out, 0, sizeof out);
    out.top = top, out.bottom = bottom, out.dropped = dropped;
    facet_panel_options o;
    facet_panel_options_default(&o);
    CHECK(o.repair_consumed == 1);
    o.thickness = 0.05;
    o.gap = 0.4; /* the edge from vertex 2 (0.2 long) shrinks by 1.57 gap / 2 */
    facet_panel_result r;
    facet_error e;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
    CHECK(r.n_dropped_edges == 1);
    CHECK(dropped[0] == 0 && dropped[1] == 0 && dropped[2] == 1 && dropped[3] == 0);
    CHECK(memcmp(top + 6, top + 9, 3 * sizeof(double)) == 0);
    CHECK(memcmp(bottom + 6, bottom + 9, 3 * sizeof(double)) == 0);
    /* every corner half the gap inside the lines of the edges it joins
     * (corner 2 = corner 3 joins edges 1 and 3); top above bottom by t */
    const int before[4] = {3, 0, 1, 1}, after[4] = {0, 1, 3, 3};
    for (int c = 0; c < 4; ++c) {
        const int a = before[c], b = after[c];
        CHECK_NEAR(line_distance(bottom + 3 * c, q + 3 * a, q + 3 * ((a + 1) % 4)), 0.2, 1e-7);
        CHECK_NEAR(line_distance(bottom + 3 * c, q + 3 * b, q + 3 * ((b + 1) % 4)), 0.2, 1e-7);
        CHECK_NEAR(top[3 * c + 2] - bottom[3 * c + 2], 0.05, 1e-9);
        CHECK_NEAR(top[3 * c] - bottom[3 * c], 0.0, 1e-7);
    }
    /* just under the consuming gap the quad keeps its four edges */
    o.gap = 0.2;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
    CHECK(r.n_dropped_edges == 0 && dropped[2] == 0);
    CHECK(dist3(top + 6, top + 9) > 0.01);
    /* asked not to repair: an error naming the edge */
    o.gap = 0.4;
    o.repair_consumed = 0;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_ERROR_PANEL_GEOMETRY);
    CHECK(strstr(e.message, "face 0") != NULL && strstr(e.message, "vertex 2, 0.2 long") != NULL);
    o.repair_consumed = 1;
    /* mitred: a lone face's edges are boundary edges, square, so it is dropped too */
    o.edge = FACET_PANEL_EDGE_BISECTOR;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
    CHECK(r.n_dropped_edges == 1 && r.n_squared_edges == 0 && dropped[2] == 1);
    /* a gap as wide as the panel: fewer than three edges left */
    o.edge = FACET_PANEL_EDGE_SQUARE;
    o.gap = 12.0;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_ERROR_PANEL_GEOMETRY);
    CHECK(strstr(e.message, "fewer than three edges") != NULL);
}

/* p rotated by angle about the line through a and b. */
/* The default options with this thickness, gap and edge cut. */
static facet_panel_options panel_options(double thickness, double gap, facet_panel_edge edge)
{
    facet_panel_options o;
    facet_panel_options_default(&o);
    o.thickness = thickness;
    o.gap = gap;
    o.edge = edge;
    return o;
}

static void rotate_about(double p[3], const double a[3], const double b[3], double angle)
{
    double k[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    const double lk = sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]);
    for (int i = 0; i < 3; ++i)
        k[i] /= lk;
    const double kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    const double kxv[3] = {k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]};
    for (int i = 0; i < 3; ++i)
        p[i] = a[i] + v[i] * cos(angle) + kxv[i] * sin(angle) + k[i] * kv * (1.0 - cos(angle));
}

/* A mitre that cannot be cut: the cut-tip quad (face 0) with a quad on each
 * long side (faces 1 and 2), both folded up by 30 degrees (valleys). Thick
 * panels' top outline loses the short tip edge to the long sides' 15-degree
 * mitres: those joints become butt joints, square on face 0 and cut with the
 * whole fold on faces 1 and 2, and the quad keeps its four corners. */
static void squared_mitre(void)
{
    const double fold = 30.0 * PI / 180.0;
    double q[30] = {0, 0, 0, 10, 0, 0, 5.1, 20, 0, 4.9, 20, 0,
                    15, 0, 0, 10.1, 20, 0,      /* 4, 5: beyond the edge from 1 to 2 */
                    -0.1, 20, 0, -5, 0, 0};     /* 6, 7: beyond the edge from 3 to 0 */
    /* the side quads fold up about their edges with face 0 */
    for (int v = 4; v <= 5; ++v)
        rotate_about(q + 3 * v, q + 3, q + 6, -fold);
    for (int v = 6; v <= 7; ++v)
        rotate_about(q + 3 * v, q + 0, q + 9, fold);
    CHECK(q[3 * 4 + 2] > 0.5 && q[3 * 6 + 2] > 0.5);
    int32_t qs[4] = {0, 4, 8, 12}, qf[12] = {0, 1, 2, 3, 2, 1, 4, 5, 0, 3, 6, 7};
    facet_mesh qm = {8, 3, q, qs, qf};
    double top[36], bottom[36], bevel[12];
    int32_t dropped[12], squared[12];
    facet_panel_output out;
    memset(&out, 0, sizeof out);
    out.top = top, out.bottom = bottom, out.bevel = bevel, out.dropped = dropped, out.squared = squared;
    facet_panel_options o;
    facet_panel_options_default(&o);
    o.edge = FACET_PANEL_EDGE_BISECTOR;
    o.gap = 0.2;
    facet_panel_result r;
    facet_error e;
    /* thin panels: the mitres are cut, at half the fold */
    o.thickness = 0.01;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
    CHECK(r.n_squared_edges == 0 && r.n_dropped_edges == 0 && r.narrowest_repaired_joint == -1.0);
    const int joints[4] = {1, 3, 4, 8}; /* face 0's long sides, and the same edges in faces 1, 2 */
    for (int k = 0; k < 4; ++k)
        CHECK_NEAR(fabs(bevel[joints[k]]), 0.5 * fold, 1e-9);
    /* thick: the top outline would lose the tip's edge (shrunk by 1.57 x
     * (0.1 + 0.2 tan 15)); cut square it shrinks by 1.57 x 0.1 and stays */
    o.thickness = 0.2;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
    CHECK(r.n_squared_edges == 2 && r.n_butt_edges == 2 && r.n_dropped_edges == 0);
    CHECK_NEAR(r.narrowest_repaired_joint, 0.2, 1e-9); /* a butt joint keeps the gap */
    for (int c = 0; c < 12; ++c) {
        const int square = c == 1 || c == 3, butt = c == 4 || c == 8;
        CHECK(squared[c] == (square ? 1 : butt ? 2 : 0) && dropped[c] == 0);
        if (square)
            CHECK_NEAR(bevel[c], 0.0, 1e-12);
        if (butt)
            CHECK_NEAR(fabs(bevel[c]), fold, 1e-9);
    }
    CHECK(dist3(top + 6, top + 9) > 0.01 && dist3(bottom + 6, bottom + 9) > 0.01);
    o.repair_consumed = 0;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_ERROR_PANEL_GEOMETRY);
    CHECK(strstr(e.message, "face 0: the top outline loses its edge from vertex 2") != NULL);
    o.repair_consumed = 1;
    /* a butt joint keeps the gap, however thick the panels */
    o.thickness = 0.5;
    o.gap = 0.02;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
    CHECK(r.n_squared_edges == 2 && r.n_butt_edges == 2);
}

/* Two cut-tip quads on either side of a long edge, folded by 30 degrees (a
 * valley): the mitre consumes both tips, so the joint must be square on both
 * panels, and with thick panels and a thin gap they would overlap: an error
 * naming both faces. */
static void square_joint_overlap(void)
{
    const double fold = 30.0 * PI / 180.0;
    double q[18] = {0, 0, 0, 10, 0, 0, 5.1, 20, 0, 4.9, 20, 0, 15, 0, 0, 5.3, 20, 0};
    for (int v = 4; v <= 5; ++v)
        rotate_about(q + 3 * v, q + 3, q + 6, -fold);
    int32_t qs[3] = {0, 4, 8}, qf[8] = {0, 1, 2, 3, 2, 1, 4, 5};
    facet_mesh qm = {6, 2, q, qs, qf};
    int32_t squared[8];
    facet_panel_output out;
    memset(&out, 0, sizeof out);
    out.squared = squared;
    facet_panel_options o = panel_options(1.0, 0.02, FACET_PANEL_EDGE_BISECTOR);
    facet_panel_result r;
    facet_error e;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_ERROR_PANEL_GEOMETRY);
    CHECK(strstr(e.message, "faces 0 and 1") != NULL && strstr(e.message, "overlap by") != NULL);
    /* a gap wider than the fold closes: square on both, and cut */
    o.gap = 0.8;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
    CHECK(squared[1] == 1 && squared[4] == 1);
    /* narrower than the gap at the valley's top: the distance between the
     * two panels' top corners (each half the gap off the edge in its plane,
     * a thickness up), in the cross-section */
    const double half = 0.4, width = 2.0 * (half * cos(0.5 * fold) - 1.0 * sin(0.5 * fold));
    CHECK_NEAR(r.narrowest_repaired_joint, width, 1e-9);
}

/* A valley folded 90 degrees (an inner corner) or more, cut square: no corner
 * of one panel's section lies inside the other (at 90 degrees each lies on the
 * other's faces), yet the panels overlap by their thickness less half the gap.
 * The deepest corner inside the other found 0: the joint touching (gap 0) or
 * open, nothing counted. */
static void sharp_valley_joints(void)
{
    const double L = 1000.0, t = 40.0;
    int32_t qs[3] = {0, 4, 8}, qf[8] = {0, 1, 2, 3, 1, 0, 4, 5};
    for (int k = 0; k < 2; ++k) {
        const double fold = (k ? 120.0 : 90.0) * PI / 180.0;
        const double clear = 2.0 * t * tan(0.5 * fold);
        double q[18] = {0, 0, 0, L, 0, 0, L, L, 0, 0, L, 0,
                        0, -L * cos(fold), L * sin(fold), L, -L * cos(fold), L * sin(fold)};
        facet_mesh qm = {6, 2, q, qs, qf};
        for (int g = 0; g < 2; ++g) {
            facet_panel_options o = panel_options(t, g ? 8.0 : 0.0, FACET_PANEL_EDGE_SQUARE);
            facet_panel_output out;
            memset(&out, 0, sizeof out);
            facet_panel_result r;
            facet_error e;
            CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
            CHECK(r.n_overlapping_joints == 1);
            CHECK_NEAR(r.clearing_gap, clear, 1e-9 * clear);
            if (k == 0)
                CHECK_NEAR(r.narrowest_joint, -(t - 0.5 * o.gap), 1e-9);
            else
                CHECK(r.narrowest_joint < -0.5 * t);
        }
    }
}

/* Every joint's narrowest width (facet_panel_output.joint): two 1000 mm
 * quads folded by 30 degrees about their shared edge, 40 mm thick, at
 * georeferenced coordinates. Valley (the second quad rising on the top
 * side): square cuts close the joint on top, to g cos(fold/2) - 2 t
 * sin(fold/2) between the two top corners, and overlap below the clearing
 * gap 2 t tan(fold/2); a ridge opens it (g cos(fold/2) between the bottom
 * corners); a mitre keeps g. */
static void joint_widths(void)
{
    const double L = 1000.0, t = 40.0, fold = 30.0 * PI / 180.0;
    const double clear = 2.0 * t * tan(0.5 * fold);
    int32_t qs[3] = {0, 4, 8}, qf[8] = {0, 1, 2, 3, 1, 0, 4, 5};
    for (int valley = 0; valley < 2; ++valley) {
        const double up = valley ? 1.0 : -1.0;
        const double y = -L * cos(fold), z = up * L * sin(fold);
        double q[18] = {0, 0, 0, L, 0, 0, L, L, 0, 0, L, 0, 0, y, z, L, y, z};
        for (int v = 0; v < 6; ++v)
            q[3 * v] += 2.5e6, q[3 * v + 1] += 1.2e6, q[3 * v + 2] += 350.0;
        facet_mesh qm = {6, 2, q, qs, qf};
        double joint[8];
        int32_t nbr[8];
        facet_panel_output out;
        memset(&out, 0, sizeof out);
        out.joint = joint;
        out.neighbor = nbr;
        facet_panel_options o = panel_options(t, 10.0, FACET_PANEL_EDGE_SQUARE);
        facet_panel_result r;
        facet_error e;
        CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
        CHECK(r.narrowest_joint_faces[0] == 0 && r.narrowest_joint_faces[1] == 1);
        CHECK(r.narrowest_joint_vertex == 0 || r.narrowest_joint_vertex == 1);
        for (int c = 0; c < 8; ++c)
            if (nbr[c] < 0)
                CHECK(joint[c] == 0.0);
            else
                CHECK(joint[c] == r.narrowest_joint);
        CHECK(r.narrowest_repaired_joint == -1.0);
        if (!valley) {
            CHECK_NEAR(r.narrowest_joint, 10.0 * cos(0.5 * fold), 1e-9);
            CHECK(r.n_overlapping_joints == 0 && r.clearing_gap == 0.0);
        } else {
            /* overlapping: how deep, and the gap that clears it */
            CHECK(r.narrowest_joint < -1.0);
            CHECK(r.n_overlapping_joints == 1);
            CHECK_NEAR(r.clearing_gap, clear, 1e-9 * clear);
            /* just above it the top corners almost touch; just below they overlap */
            o.gap = clear * (1.0 + 1e-7);
            CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
            CHECK(r.n_overlapping_joints == 0 && r.narrowest_joint >= 0.0 &&
                  r.narrowest_joint < 1e-5);
            o.gap = clear * (1.0 - 1e-5);
            CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
            CHECK(r.n_overlapping_joints == 1 && r.narrowest_joint < 0.0);
            o.gap = 30.0;
            CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
            CHECK_NEAR(r.narrowest_joint, 30.0 * cos(0.5 * fold) - 2.0 * t * sin(0.5 * fold),
                       1e-9);
            CHECK(r.n_overlapping_joints == 0 && r.clearing_gap == 0.0);
        }
        /* mitred: the gap, both ways */
        o.edge = FACET_PANEL_EDGE_BISECTOR;
        o.gap = 10.0;
        CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
        CHECK_NEAR(r.narrowest_joint, 10.0, 1e-9);
        CHECK(r.n_overlapping_joints == 0);
    }
}

/* Panels that meet only at a node (facet_panel_output.node_clash): a bowl of
 * four planar quads, z = s (|x| + |y|) (translational, so its node is
 * torsion-free), 200 thick on top. Cut square, the diagonal panels' top
 * corners run into each other over the bowl's bottom until the gap clears
 * the edges' joints (2 t tan(fold/2), cos fold = 1 / (1 + 2 s^2)); mitred,
 * they never meet. */
static void node_clashes(void)
{
    const double L = 1000.0, t = 200.0, sl = tan(30.0 * PI / 180.0);
    double q[27];
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            double *p = q + 3 * (3 * j + i);
            p[0] = (i - 1) * L + 2.5e6, p[1] = (j - 1) * L + 1.2e6;
            p[2] = sl * L * (abs(i - 1) + abs(j - 1)) + 350.0;
        }
    int32_t qs[5] = {0, 4, 8, 12, 16};
    int32_t qf[16] = {0, 1, 4, 3, 1, 2, 5, 4, 3, 4, 7, 6, 4, 5, 8, 7};
    facet_mesh qm = {9, 4, q, qs, qf};
    double clash[9];
    facet_panel_output out;
    memset(&out, 0, sizeof out);
    double face_clash[4];
    out.node_clash = clash;
    out.clash = face_clash;
    facet_panel_options o = panel_options(t, 10.0, FACET_PANEL_EDGE_SQUARE);
    facet_panel_result r;
    facet_error e;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
    const double clear = 2.0 * t * tan(0.5 * acos(1.0 / (1.0 + 2.0 * sl * sl)));
    CHECK(r.n_overlapping_joints == 4);
    CHECK_NEAR(r.clearing_gap, clear, 1e-9 * clear);
    CHECK(r.n_node_clashes == 2); /* faces 0 and 3, 1 and 2 */
    CHECK(r.node_clash_vertex == 4 && r.deepest_node_clash > 1.0);
    CHECK((r.node_clash_faces[0] == 0 && r.node_clash_faces[1] == 3) ||
          (r.node_clash_faces[0] == 1 && r.node_clash_faces[1] == 2));
    for (int v = 0; v < 9; ++v)
        CHECK(v == 4 ? clash[v] == r.deepest_node_clash : clash[v] == 0.0);
    /* each panel's deepest overlap: its joints' and the node's */
    for (int f = 0; f < 4; ++f)
        CHECK(face_clash[f] >= r.deepest_node_clash && face_clash[f] >= -r.narrowest_joint);
    /* a wider gap parts them less deep, the clearing gap parts them */
    const double deep = r.deepest_node_clash;
    o.gap = 100.0;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
    CHECK(r.n_node_clashes == 2 && r.deepest_node_clash < deep);
    o.gap = clear * (1.0 + 1e-6);
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
    CHECK(r.n_overlapping_joints == 0 && r.n_node_clashes == 0 && r.node_clash_vertex == -1);
    CHECK(r.node_clash_faces[0] == -1 && r.deepest_node_clash == 0.0 && clash[4] == 0.0);
    for (int f = 0; f < 4; ++f)
        CHECK(face_clash[f] == 0.0);
    o.edge = FACET_PANEL_EDGE_BISECTOR;
    o.gap = 10.0;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
    CHECK(r.max_node_deviation < 1e-9 && r.n_node_clashes == 0);
    /* face 0 a dart (its outer corner moved in along the diagonal, on its plane:
     * concave there), tested by convex pieces: the same two pairs overlap, and
     * none at the clearing gap */
    q[0] = -0.3 * L + 2.5e6, q[1] = -0.3 * L + 1.2e6, q[2] = sl * 0.6 * L + 350.0;
    o.edge = FACET_PANEL_EDGE_SQUARE;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
    CHECK(r.n_node_clashes == 2 && r.node_clash_vertex == 4 && face_clash[0] > 1.0);
    o.gap = clear * (1.0 + 1e-6);
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
    CHECK(r.n_node_clashes == 0 && r.n_overlapping_joints == 0 && face_clash[0] == 0.0);
}

/* A T-junction at georeferenced coordinates: face 0, 2 x 1, has a straight
 * corner (vertex 3) in the middle of its far edge, along which faces 1 and 2
 * rise by 30 degrees (coplanar, as a planar mesh makes them). The corner was
 * an error ("the edges at vertex 3 are collinear"). */
static void straight_corner(void)
{
    const double ox = 2.5e6, oy = 1.2e6, tz = 0.5773502691896258; /* tan 30 */
    double q[24] = {0, 0, 0, 2, 0, 0, 2, 1, 0, 1, 1, 0, 0, 1, 0, 0, 2, tz, 1, 2, tz, 2, 2, tz};
    for (int v = 0; v < 8; ++v)
        q[3 * v] += ox, q[3 * v + 1] += oy;
    int32_t qs[4] = {0, 5, 9, 13}, qf[13] = {0, 1, 2, 3, 4, 3, 2, 7, 6, 4, 3, 6, 5};
    facet_mesh qm = {8, 3, q, qs, qf};
    double top[39], bottom[39];
    int32_t squared[13];
    facet_panel_output out;
    memset(&out, 0, sizeof out);
    out.top = top, out.bottom = bottom, out.squared = squared;
    facet_panel_options o = panel_options(0.02, 0.01, FACET_PANEL_EDGE_BISECTOR);
    facet_panel_result r;
    facet_error e;
    for (int edge = 0; edge < 2; ++edge) {
        o.edge = edge ? FACET_PANEL_EDGE_SQUARE : FACET_PANEL_EDGE_BISECTOR;
        CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
        CHECK(r.n_squared_edges == 0 && r.n_dropped_edges == 0);
        /* corners 2, 3, 4 of face 0 on one line in each outline, half the
         * gap in from the edge; corner 3 beside vertex 3 */
        for (int side = 0; side < 2; ++side) {
            const double *x = side ? top : bottom;
            CHECK_NEAR(line_distance(x + 9, x + 6, x + 12), 0.0, 1e-9);
            CHECK_NEAR(x[9] - ox, 1.0, 1e-9);
        }
        /* half the gap; mitred, half the slot across the 15-degree mitre */
        CHECK_NEAR(q[10] - bottom[10], edge ? 0.005 : 0.005 / cos(PI / 12), 1e-9);
    }
    /* face 1 left out: the edge is free left of vertex 3 and mitred right of
     * it; the mitre becomes a butt joint (square on face 0), or without
     * repair an error */
    qm.n_faces = 2;
    o.edge = FACET_PANEL_EDGE_BISECTOR;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
    CHECK(r.n_squared_edges == 1 && r.n_butt_edges == 1 && squared[2] == 1 && squared[5] == 2);
    for (int side = 0; side < 2; ++side) {
        const double *x = side ? top : bottom;
        CHECK_NEAR(line_distance(x + 9, x + 6, x + 12), 0.0, 1e-9);
        CHECK_NEAR(q[10] - x[10], 0.005, 1e-9);
    }
    /* vertex 3 (and 6 with it) 5 mm out: a corner turned 0.57 degrees. The mitre's top
     * line met the free edge's 0.55 along it (28 thicknesses); it is squared as at a
     * straight corner, the corner half the gap in from the vertex */
    q[10] += 0.005, q[19] += 0.005;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
    CHECK(r.n_squared_edges == 1 && r.n_butt_edges == 1 && squared[2] == 1);
    for (int side = 0; side < 2; ++side) {
        const double *x = side ? top : bottom;
        CHECK(fabs(x[9] - q[9]) < 0.006 && fabs(x[10] - q[10]) < 0.006);
    }
    q[10] -= 0.005, q[19] -= 0.005;
    o.repair_consumed = 0;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_ERROR_PANEL_GEOMETRY);
    CHECK(strstr(e.message, "face 0: the edges at vertex 3 are collinear and their joints are "
                            "cut at different angles") != NULL);
    /* face 2 (B, left of the corner) with a chamfer 7.6 mm long at vertex 4 (vertex 5
     * moved there): the gap consumes it and B's mitre to face 0 with it, a butt joint on
     * face 0. Face 0's mitre to face 1 (C, coplanar with B) right of the straight corner
     * becomes a butt joint too, C square: no joint square on both panels (which
     * overlapped on the fold, an error) */
    q[15] = ox - 0.005, q[16] = oy + 1.005, q[17] = 0.005 * tz;
    qm.n_faces = 3;
    o.repair_consumed = 1;
    CHECK_STATUS(facet_panels(&qm, &o, &out, &r, &e), FACET_OK);
    CHECK(r.n_squared_edges == 2 && r.n_butt_edges == 2 && r.n_overlapping_joints == 0);
    CHECK(squared[2] == 2 && squared[3] == 2 && squared[5] == 1 && squared[9] == 1);
    for (int side = 0; side < 2; ++side) {
        const double *x = side ? top : bottom;
        CHECK_NEAR(line_distance(x + 9, x + 6, x + 12), 0.0, 1e-9);
    }
}

int main(void)
{
    const double R = 5000.0, da = 0.2, h = 800.0, t = 40.0;
    cylinder(R, da, h);
    /* Georeferenced offset: coordinates in the millions. */
    for (int v = 0; v < (NU + 1) * (NV + 1); ++v)
        xyz[3 * v] += 2.5e6, xyz[3 * v + 1] += 1.2e6;
    facet_mesh m = {(NU + 1) * (NV + 1), NU * NV, xyz, start, fv};
    const int nc = 4 * NU * NV, nf = NU * NV, nv = (NU + 1) * (NV + 1);
    double top[3 * 4 * NU * NV], bottom[3 * 4 * NU * NV], plane[4 * NU * NV], frame[12 * NU * NV];
    double dih[4 * NU * NV], bev[4 * NU * NV], dev[(NU + 1) * (NV + 1)], pl[NU * NV];
    int32_t nbr[4 * NU * NV], rev[NU * NV], bad[NU * NV];
    facet_panel_output out = {plane, top, bottom, frame, rev,  nbr,
                              dih,   bev, dev,    pl,    bad, NULL, NULL, NULL, NULL, NULL};
    facet_panel_options o;
    facet_panel_options_default(&o);
    o.thickness = t;
    facet_panel_result r;
    facet_error e;
    CHECK_STATUS(facet_panels(&m, &o, &out, &r, &e), FACET_OK);
    CHECK(r.n_components == 1);
    CHECK(r.n_reversed == 0);
    /* Square, no gap, outer: bottom = the face, top = face + t n. */
    for (int c = 0; c < nc; ++c) {
        const double *p = xyz + 3 * fv[c];
        CHECK(dist3(bottom + 3 * c, p) < 1e-8);
        CHECK_NEAR(dist3(top + 3 * c, p), t, 1e-8);
        CHECK_NEAR(bev[c], 0.0, 1e-12);
    }
    /* Across the vertical edges the fold is da; the faces are wound so the
     * normal points into the cylinder here (i increasing, z up: e_u x e_z
     * points outward... whichever way, |pi - dihedral| = da). */
    int n_interior = 0;
    for (int c = 0; c < nc; ++c)
        if (nbr[c] >= 0) {
            ++n_interior;
            const double fold = fabs(PI - dih[c]);
            CHECK(fabs(fold - da) < 1e-9 || fabs(fold) < 1e-9);
        } else {
            CHECK(dih[c] == 0.0);
        }
    CHECK(n_interior == 2 * ((NU - 1) * NV + NU * (NV - 1)));
    /* Torsion-free: every node's edge planes share a line. */
    CHECK(r.max_node_deviation < 1e-9);
    /* Unfold frame: corner 0 at the origin, corner 1 on +x, z = 0. */
    for (int f = 0; f < nf; ++f) {
        const double *F = frame + 12 * f;
        for (int k = 0; k < 4; ++k) {
            const double *p = xyz + 3 * fv[4 * f + k];
            double q[3];
            for (int i = 0; i < 3; ++i)
                q[i] = F[3 * i] * p[0] + F[3 * i + 1] * p[1] + F[3 * i + 2] * p[2] + F[9 + i];
            CHECK(fabs(q[2]) < 1e-6);
            if (k == 0)
                CHECK(fabs(q[0]) < 1e-6 && fabs(q[1]) < 1e-6);
            if (k == 1)
                CHECK(fabs(q[0] - dist3(p, xyz + 3 * fv[4 * f])) < 1e-6 && fabs(q[1]) < 1e-6);
        }
    }

    /* Bisector edges with a gap: neighbours' side planes are parallel and
     * g apart; bevels are half the fold. */
    const double g = 10.0;
    o.edge = FACET_PANEL_EDGE_BISECTOR;
    o.gap = g;
    CHECK_STATUS(facet_panels(&m, &o, &out, &r, &e), FACET_OK);
    for (int c = 0; c < nc; ++c)
        if (nbr[c] >= 0 && fabs(PI - dih[c]) > 1e-6)
            CHECK_NEAR(fabs(bev[c]), da / 2, 1e-9);
    /* Face 0's edge 1 (corners 1 -> 2) borders face 1 at its edge 3
     * (corners 3 -> 0). Distance from face 1's side-face corners to face
     * 0's side plane through top[1], top[2], bottom[1]. */
    {
        const double *a = top + 3 * 1, *b = top + 3 * 2, *c = bottom + 3 * 1;
        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        double ln = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        const int other[4] = {4 + 3, 4 + 0, 4 + 3, 4 + 0};
        const double *pts[4] = {top, top, bottom, bottom};
        for (int k = 0; k < 4; ++k) {
            const double *p = pts[k] + 3 * other[k];
            double d = ((p[0] - a[0]) * n[0] + (p[1] - a[1]) * n[1] + (p[2] - a[2]) * n[2]) / ln;
            CHECK_NEAR(fabs(d), g, 1e-7);
        }
    }

    /* Flip: every face reversed, normals negated. */
    double n0[3] = {plane[0], plane[1], plane[2]};
    o.flip = 1;
    o.gap = 0;
    CHECK_STATUS(facet_panels(&m, &o, &out, &r, &e), FACET_OK);
    CHECK(r.n_reversed == nf);
    CHECK_NEAR(plane[0], -n0[0], 1e-12);
    CHECK_NEAR(plane[2], -n0[2], 1e-12);

    /* Inconsistent input winding is repaired: reverse face 5's loop. */
    int32_t saved[4];
    memcpy(saved, fv + 20, sizeof saved);
    fv[20] = saved[3], fv[21] = saved[2], fv[22] = saved[1], fv[23] = saved[0];
    o.flip = 0;
    CHECK_STATUS(facet_panels(&m, &o, &out, &r, &e), FACET_OK);
    CHECK(r.n_reversed == 1 && rev[5] == 1);
    CHECK_NEAR(plane[4 * 5 + 0] * plane[4 * 4 + 0] + plane[4 * 5 + 1] * plane[4 * 4 + 1], cos(da),
               1e-9);
    memcpy(fv + 20, saved, sizeof saved);

    /* Errors: bad thickness, a gap wider than the panel, a bent face. */
    o.thickness = 0;
    CHECK_STATUS(facet_panels(&m, &o, &out, &r, &e), FACET_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(e.message, "thickness") != NULL);
    o.thickness = t;
    o.gap = 2 * R;
    CHECK_STATUS(facet_panels(&m, &o, &out, &r, &e), FACET_ERROR_PANEL_GEOMETRY);
    CHECK(strstr(e.message, "gap") != NULL);
    o.gap = 0;
    xyz[3 * 6 + 0] += 5.0; /* move vertex 6: faces 0, 1, 4, 5 bend */
    for (int f = 0; f < nf; ++f)
        bad[f] = -1;
    CHECK_STATUS(facet_panels(&m, &o, &out, &r, &e), FACET_ERROR_NOT_PLANAR);
    CHECK(r.n_nonplanar == 4);
    CHECK(bad[0] == 0 && bad[1] == 1 && bad[2] == 4 && bad[3] == 5);
    CHECK(strstr(e.message, "4 faces are not planar") != NULL);
    o.planarity_tol_abs = 10.0; /* within the tolerance: accepted */
    CHECK_STATUS(facet_panels(&m, &o, &out, &r, &e), FACET_OK);
    xyz[3 * 6 + 0] -= 5.0;
    (void)nv;

    /* A Moebius strip cannot be oriented: the error names a face. */
    {
        enum { NS = 8 };
        double mx[3 * 2 * NS];
        int32_t ms[NS + 1], mf[4 * NS];
        for (int i = 0; i < NS; ++i) {
            const double a = 2 * PI * i / NS, tw = a / 2;
            for (int k = 0; k < 2; ++k) {
                const double rad = 10.0 + (k ? -1.0 : 1.0) * cos(tw);
                mx[3 * (2 * i + k) + 0] = rad * cos(a);
                mx[3 * (2 * i + k) + 1] = rad * sin(a);
                mx[3 * (2 * i + k) + 2] = (k ? -1.0 : 1.0) * sin(tw);
            }
        }
        for (int i = 0; i < NS; ++i) {
            ms[i] = 4 * i;
            const int j = (i + 1) % NS;
            mf[4 * i + 0] = 2 * i, mf[4 * i + 1] = 2 * i + 1;
            if (j == 0) /* the twist: top meets bottom */
                mf[4 * i + 2] = 0, mf[4 * i + 3] = 1;
            else
                mf[4 * i + 2] = 2 * j + 1, mf[4 * i + 3] = 2 * j;
        }
        ms[NS] = 4 * NS;
        facet_mesh mm = {2 * NS, NS, mx, ms, mf};
        facet_panel_options mo;
        facet_panel_options_default(&mo);
        facet_panel_output none;
        memset(&none, 0, sizeof none);
        CHECK_STATUS(facet_panels(&mm, &mo, &none, NULL, &e), FACET_ERROR_NOT_ORIENTABLE);
        CHECK(strstr(e.message, "cannot be oriented") != NULL);
        CHECK(e.face >= 0 && e.face < NS);
    }

    /* Cancel from the progress callback (called every 1024 faces). */
    {
        enum { G = 40 };
        static double gx[3 * (G + 1) * (G + 1)];
        static int32_t gs[G * G + 1], gf[4 * G * G];
        for (int j = 0; j <= G; ++j)
            for (int i = 0; i <= G; ++i) {
                double *q = gx + 3 * (j * (G + 1) + i);
                q[0] = i, q[1] = j, q[2] = 0.0;
            }
        for (int f = 0; f < G * G; ++f) {
            const int i = f % G, j = f / G, a = j * (G + 1) + i;
            gs[f] = 4 * f;
            gf[4 * f] = a, gf[4 * f + 1] = a + 1, gf[4 * f + 2] = a + G + 2, gf[4 * f + 3] = a + G + 1;
        }
        gs[G * G] = 4 * G * G;
        facet_mesh gm = {(G + 1) * (G + 1), G * G, gx, gs, gf};
        facet_panel_options go;
        facet_panel_options_default(&go);
        go.thickness = 0.1;
        go.progress = cancel_now;
        facet_panel_output none;
        memset(&none, 0, sizeof none);
        CHECK_STATUS(facet_panels(&gm, &go, &none, NULL, &e), FACET_ERROR_CANCELLED);
        go.progress = NULL;
        facet_panel_result gr;
        CHECK_STATUS(facet_panels(&gm, &go, &none, &gr, &e), FACET_OK);
        CHECK(gr.max_node_deviation < 1e-12); /* a flat grid: every node is torsion-free */
    }
    consumed_edge();
    straight_corner();
    squared_mitre();
    square_joint_overlap();
    joint_widths();
    sharp_valley_joints();
    node_clashes();
    return check_report("test_panel");
}
