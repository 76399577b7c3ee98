/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Fuzz target: facet_panels on valid meshes (grids are planar when not
 * bent), options sometimes zero, negative or not finite; run twice, same
 * bits. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

typedef struct panel_buffers {
    facet_panel_output o;
    facet_panel_result r;
} panel_buffers;

static void alloc_out(panel_buffers *p, int32_t nv, int32_t nf, int32_t nc, uint8_t mask)
{
    memset(p, 0, sizeof *p);
    if (mask & 1) p->o.plane = fz_calloc(4 * (size_t)nf, sizeof(double));
    if (mask & 2) p->o.top = fz_calloc(3 * (size_t)nc, sizeof(double));
    if (mask & 2) p->o.bottom = fz_calloc(3 * (size_t)nc, sizeof(double));
    if (mask & 4) p->o.frame = fz_calloc(12 * (size_t)nf, sizeof(double));
    if (mask & 8) p->o.reversed = fz_calloc((size_t)nf, sizeof(int32_t));
    if (mask & 8) p->o.neighbor = fz_calloc((size_t)nc, sizeof(int32_t));
    if (mask & 16) p->o.dihedral = fz_calloc((size_t)nc, sizeof(double));
    if (mask & 16) p->o.bevel = fz_calloc((size_t)nc, sizeof(double));
    if (mask & 16) p->o.joint = fz_calloc((size_t)nc, sizeof(double));
    if (mask & 32) p->o.node_deviation = fz_calloc((size_t)nv, sizeof(double));
    if (mask & 32) p->o.node_clash = fz_calloc((size_t)nv, sizeof(double));
    if (mask & 64) p->o.planarity = fz_calloc((size_t)nf, sizeof(double));
    if (mask & 64) p->o.nonplanar = fz_calloc((size_t)nf, sizeof(int32_t));
    if (mask & 64) p->o.clash = fz_calloc((size_t)nf, sizeof(double));
}

static void free_out(panel_buffers *p)
{
    free(p->o.plane); free(p->o.top); free(p->o.bottom); free(p->o.frame); free(p->o.reversed);
    free(p->o.neighbor); free(p->o.dihedral); free(p->o.bevel); free(p->o.node_deviation);
    free(p->o.planarity); free(p->o.nonplanar); free(p->o.joint);
    free(p->o.node_clash);
    free(p->o.clash);
}

typedef struct cancel_at {
    int64_t done;
} cancel_at;

static int progress(void *user, int64_t done, int64_t total)
{
    (void)total;
    const cancel_at *c = user;
    return c->done >= 0 && done >= c->done;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_bytes b = {data, size};
    static fz_mesh m;
    fz_mesh_decode(&b, &m);
    facet_error e;
    fz_error_init(&e);
    if (facet_mesh_validate(&m.mesh, NULL, &e) < 0) return 0; /* facet_panels needs a valid mesh */
    int32_t nv = m.mesh.n_vertices, nf = m.mesh.n_faces, nc = fz_corners(&m.mesh);
    facet_panel_options opt;
    facet_panel_options_default(&opt);
    opt.thickness = fz_u8(&b) < 16 ? fz_special(&b) : fz_range(&b, 0.0, 0.5, 0);
    uint8_t pick = fz_u8(&b); /* left to right, spelled out (see fuzz_common.h) */
    opt.offset = (facet_panel_offset)(pick % (fz_u8(&b) < 8 ? 5 : 3));
    opt.gap = fz_u8(&b) < 16 ? fz_special(&b) : (fz_u8(&b) < 128 ? 0.0 : fz_range(&b, 0.0, 0.2, 0));
    pick = fz_u8(&b);
    opt.edge = (facet_panel_edge)(pick % (fz_u8(&b) < 8 ? 4 : 2));
    opt.flip = fz_u8(&b) & 1;
    if (fz_u8(&b) < 32) opt.planarity_tol_abs = fz_special(&b);
    if (fz_u8(&b) < 64) opt.planarity_tol_rel = fz_u8(&b) < 32 ? fz_special(&b) : fz_range(&b, 0.0, 0.2, 0);
    cancel_at cancel = {-1};
    if (fz_u8(&b) < 32) {
        cancel.done = fz_below(&b, nf + 1);
        opt.progress = progress;
        opt.progress_user = &cancel;
    }
    uint8_t mask = fz_u8(&b) < 128 ? 0x7f : fz_u8(&b);
    panel_buffers p[2];
    facet_status s[2];
    for (int k = 0; k < 2; k++) {
        alloc_out(&p[k], nv, nf, nc, mask);
        fz_error_init(&e);
        s[k] = facet_panels(&m.mesh, &opt, &p[k].o, &p[k].r, &e);
        fz_check_status("facet_panels", s[k], &e);
    }
    if (s[0] != s[1]) FZ_FAIL("facet_panels: status %d then %d", (int)s[0], (int)s[1]);
    if (s[0] >= 0) {
        const facet_panel_output *o = &p[0].o;
        fz_check_finite("facet_panels", "plane", o->plane, o->plane ? 4 * (int64_t)nf : 0);
        fz_check_finite("facet_panels", "top", o->top, o->top ? 3 * (int64_t)nc : 0);
        fz_check_finite("facet_panels", "bottom", o->bottom, o->bottom ? 3 * (int64_t)nc : 0);
        fz_check_finite("facet_panels", "frame", o->frame, o->frame ? 12 * (int64_t)nf : 0);
        fz_check_finite("facet_panels", "dihedral", o->dihedral, o->dihedral ? nc : 0);
        fz_check_finite("facet_panels", "bevel", o->bevel, o->bevel ? nc : 0);
        fz_check_finite("facet_panels", "joint", o->joint, o->joint ? nc : 0);
        fz_check_finite("facet_panels", "node_clash", o->node_clash, o->node_clash ? nv : 0);
        fz_check_finite("facet_panels", "clash", o->clash, o->clash ? nf : 0);
        if (o->clash) {
            int any = 0;
            for (int32_t f = 0; f < nf; f++)
                any |= o->clash[f] > 0.0;
            if (any != (p[0].r.n_node_clashes > 0 || p[0].r.n_overlapping_joints > 0))
                FZ_FAIL("facet_panels: clash per face %d, %lld node clashes, %lld joints",
                        any, (long long)p[0].r.n_node_clashes, (long long)p[0].r.n_overlapping_joints);
        }
        fz_check_finite("facet_panels", "node_deviation", o->node_deviation, o->node_deviation ? nv : 0);
        fz_check_finite("facet_panels", "planarity", o->planarity, o->planarity ? nf : 0);
        if (o->neighbor)
            for (int32_t c = 0; c < nc; c++)
                if (o->neighbor[c] < -1 || o->neighbor[c] >= nf) FZ_FAIL("facet_panels: neighbor[%d] = %d", (int)c, (int)o->neighbor[c]);
        if (o->nonplanar)
            for (int64_t k = 0; k < p[0].r.n_nonplanar; k++)
                if (o->nonplanar[k] < 0 || o->nonplanar[k] >= nf) FZ_FAIL("facet_panels: nonplanar[%d] out of range", (int)k);
        double rv[5] = {p[0].r.max_node_deviation, p[0].r.max_planarity, p[0].r.narrowest_joint,
                        p[0].r.clearing_gap, p[0].r.deepest_node_clash};
        fz_check_finite("facet_panels", "result", rv, 5);
        const facet_panel_result *r = &p[0].r;
        if (r->n_overlapping_joints < 0 || !(r->clearing_gap >= 0.0) ||
            (r->n_overlapping_joints > 0) != (r->clearing_gap > 0.0) ||
            (r->n_overlapping_joints > 0 && !(r->narrowest_joint < 0.0)))
            FZ_FAIL("facet_panels: %lld overlapping joints, clearing gap %g, narrowest %g",
                    (long long)r->n_overlapping_joints, r->clearing_gap, r->narrowest_joint);
        if ((r->n_node_clashes > 0) != (r->deepest_node_clash > 0.0) ||
            (r->n_node_clashes > 0) != (r->node_clash_vertex >= 0) || r->node_clash_vertex >= nv)
            FZ_FAIL("facet_panels: %lld node clashes, deepest %g at vertex %lld",
                    (long long)r->n_node_clashes, r->deepest_node_clash,
                    (long long)r->node_clash_vertex);
        for (int k = 0; k < 2; k++)
            if (r->node_clash_faces[k] < -1 || r->node_clash_faces[k] >= nf)
                FZ_FAIL("facet_panels: node_clash_faces[%d] = %d", k, (int)r->node_clash_faces[k]);
        for (int k = 0; k < 2; k++)
            if (r->narrowest_joint_faces[k] < -1 || r->narrowest_joint_faces[k] >= nf)
                FZ_FAIL("facet_panels: narrowest_joint_faces[%d] = %d", k, (int)r->narrowest_joint_faces[k]);
        if (p[0].r.n_nonplanar != 0) FZ_FAIL("facet_panels: ok with %lld non-planar faces", (long long)p[0].r.n_nonplanar);
    }
    if (s[0] >= 0) {
        const facet_panel_output *a = &p[0].o, *c = &p[1].o;
        fz_check_same("facet_panels", "plane", a->plane, c->plane, 4 * (size_t)nf * sizeof(double));
        fz_check_same("facet_panels", "top", a->top, c->top, 3 * (size_t)nc * sizeof(double));
        fz_check_same("facet_panels", "bottom", a->bottom, c->bottom, 3 * (size_t)nc * sizeof(double));
        fz_check_same("facet_panels", "frame", a->frame, c->frame, 12 * (size_t)nf * sizeof(double));
        fz_check_same("facet_panels", "dihedral", a->dihedral, c->dihedral, (size_t)nc * sizeof(double));
        fz_check_same("facet_panels", "joint", a->joint, c->joint, (size_t)nc * sizeof(double));
        fz_check_same("facet_panels", "node_clash", a->node_clash, c->node_clash, (size_t)nv * sizeof(double));
        fz_check_same("facet_panels", "clash", a->clash, c->clash, (size_t)nf * sizeof(double));
        fz_check_same("facet_panels", "node_deviation", a->node_deviation, c->node_deviation, (size_t)nv * sizeof(double));
    }
    free_out(&p[0]);
    free_out(&p[1]);
    return 0;
}
