/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Edge collapse: new topology, validity, manifoldness, what is reported. */
#include "check.h"
#include "facet.h"
#include "test_meshes.h"

#include <string.h>

typedef struct {
    double *xyz;
    int32_t *start, *fv, *map, *collapsed, *removed;
    facet_cleanup_result r;
} out_t;

static facet_status run(const facet_mesh *m, double min_edge, int relative, out_t *o,
                        facet_error *e)
{
    const size_t nc = (size_t)m->face_start[m->n_faces];
    o->xyz = malloc(sizeof(double) * 3 * (size_t)m->n_vertices);
    o->start = malloc(sizeof(int32_t) * ((size_t)m->n_faces + 1));
    o->fv = malloc(sizeof(int32_t) * nc);
    o->map = malloc(sizeof(int32_t) * (size_t)m->n_vertices);
    o->collapsed = malloc(sizeof(int32_t) * 2 * (size_t)m->n_vertices);
    o->removed = malloc(sizeof(int32_t) * (size_t)m->n_faces);
    memset(&o->r, 0, sizeof o->r);
    facet_cleanup_options opt = {min_edge, relative};
    return facet_cleanup(m, &opt, o->xyz, o->start, o->fv, o->map, o->collapsed, o->removed,
                         &o->r, e);
}

static void out_free(out_t *o)
{
    free(o->xyz), free(o->start), free(o->fv), free(o->map), free(o->collapsed), free(o->removed);
}

int main(void)
{
    facet_error e;
    /* a 6 x 4 grid whose column x = 3 is squeezed against x = 2 (edges of
     * 0.01): collapsing the 5 short horizontal edges merges the two columns;
     * the 4 quads between them disappear (a quad losing two corners keeps 2) */
    {
        test_mesh g = test_grid(6, 4, 0.0, 1.0, 0.0);
        for (int v = 0; v < g.mesh.n_vertices; ++v)
            if (v % 7 == 3)
                g.xyz[3 * v] = 2.01;
        out_t o;
        CHECK_STATUS(run(&g.mesh, 0.1, 0, &o, &e), FACET_OK);
        CHECK(o.r.n_collapsed == 5);
        CHECK(o.r.n_removed_faces == 4);
        CHECK(o.r.n_faces == 20);
        CHECK(o.r.n_vertices == 35 - 5);
        CHECK(o.r.n_corners == 80);
        CHECK(o.r.n_skipped == 0);
        CHECK_NEAR(o.r.threshold, 0.1, 0);
        facet_mesh out = {o.r.n_vertices, o.r.n_faces, o.xyz, o.start, o.fv};
        facet_mesh_report rep;
        CHECK_STATUS(facet_mesh_validate(&out, &rep, &e), FACET_OK);
        CHECK(rep.n_non_manifold_edges == 0);
        CHECK(rep.n_boundary_edges == 2 * (5 + 4)); /* 5 x 4 grid outline */
        /* merged vertices at the midpoint of the boundary edge... both ends on the
         * boundary: midpoint x = 2.005 */
        CHECK_NEAR(o.xyz[3 * o.map[3]], 2.005, 1e-15);
        CHECK(o.map[2] == o.map[3]);
        for (int k = 0; k < o.r.n_removed_faces; ++k)
            CHECK(o.removed[k] % 6 == 2);
        /* relative threshold: 0.1 of the mean edge (about 0.99) is the same cut */
        out_t o2;
        CHECK_STATUS(run(&g.mesh, 0.1, 1, &o2, &e), FACET_OK);
        CHECK(o2.r.n_collapsed == 5);
        CHECK_NEAR(o2.r.threshold, 0.1, 1e-15); /* mean edge 58 / 58 = 1 */
        out_free(&o2);
        out_free(&o);
        test_mesh_free(&g);
    }
    /* one short inner edge in a grid: its two quads become triangles; the
     * inner vertices merge at the midpoint */
    {
        test_mesh g = test_grid(4, 4, 0.0, 1.0, 0.0);
        /* vertices 12 (2,2) and 13 (3,2)... move 13 next to 12 */
        g.xyz[3 * 13] = 2.02;
        out_t o;
        CHECK_STATUS(run(&g.mesh, 0.05, 0, &o, &e), FACET_OK);
        CHECK(o.r.n_collapsed == 1);
        CHECK(o.r.n_removed_faces == 0);
        CHECK(o.r.n_faces == 16);
        CHECK(o.r.n_corners == 62);
        CHECK(o.collapsed[0] == 12 && o.collapsed[1] == 13);
        CHECK_NEAR(o.xyz[3 * o.map[12]], 2.01, 1e-15);
        facet_mesh out = {o.r.n_vertices, o.r.n_faces, o.xyz, o.start, o.fv};
        facet_mesh_report rep;
        CHECK_STATUS(facet_mesh_validate(&out, &rep, &e), FACET_OK);
        CHECK(rep.n_non_manifold_edges == 0);
        out_free(&o);
        test_mesh_free(&g);
    }
    /* an inner edge between two boundary vertices would pinch the mesh: two
     * quads side by side whose shared edge 1-4 is short; collapsing it would
     * leave two triangles meeting at one vertex. Skipped and reported. */
    {
        const double xyz[] = {0, 0, 0, 1, 0.49, 0, 2, 0, 0, 0, 1, 0, 1, 0.51, 0, 2, 1, 0};
        const int32_t start[] = {0, 4, 8};
        const int32_t fv[] = {0, 1, 4, 3, 1, 2, 5, 4};
        facet_mesh m = {6, 2, xyz, start, fv};
        out_t o;
        CHECK_STATUS(run(&m, 0.05, 0, &o, &e), FACET_WARNING_COLLAPSE_SKIPPED);
        CHECK(strstr(e.message, "1 edges shorter") != NULL);
        CHECK(o.r.n_collapsed == 0 && o.r.n_skipped == 1);
        CHECK(o.r.n_faces == 2 && o.r.n_vertices == 6);
        CHECK(memcmp(o.fv, fv, sizeof fv) == 0);
        out_free(&o);
    }
    /* everything too short: nothing left */
    {
        test_mesh g = test_grid(2, 2, 0.0, 1.0, 0.0);
        out_t o;
        CHECK_STATUS(run(&g.mesh, 10.0, 0, &o, &e), FACET_ERROR_NOTHING_LEFT);
        CHECK(strstr(e.message, "min_edge") != NULL);
        out_free(&o);
        CHECK_STATUS(run(&g.mesh, -1.0, 0, &o, &e), FACET_ERROR_INVALID_ARGUMENT);
        out_free(&o);
        CHECK_STATUS(run(&g.mesh, NAN, 0, &o, &e), FACET_ERROR_INVALID_ARGUMENT);
        out_free(&o);
        test_mesh_free(&g);
    }
    return check_report("test_cleanup");
}
