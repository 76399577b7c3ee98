/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Generated test meshes: quad grids on doubly curved surfaces. */
#ifndef FACET_TEST_MESHES_H
#define FACET_TEST_MESHES_H

#include "facet.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

typedef struct {
    facet_mesh mesh;
    double *xyz;
    int32_t *face_start, *face_vertices;
} test_mesh;

/* Points t->mesh at t's own arrays, of nv vertices and nf faces. */
static inline void test_mesh_view(test_mesh *t, int32_t nv, int32_t nf)
{
    t->mesh.n_vertices = nv;
    t->mesh.n_faces = nf;
    t->mesh.xyz = t->xyz;
    t->mesh.face_start = t->face_start;
    t->mesh.face_vertices = t->face_vertices;
}

/* The faces of an nu x nv grid of quads over vertices numbered row by row. */
static inline void grid_quads(test_mesh *t, int nu, int nv)
{
    for (int f = 0; f <= nu * nv; ++f)
        t->face_start[f] = 4 * f;
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const int f = j * nu + i, v = j * (nu + 1) + i;
            t->face_vertices[4 * f] = v;
            t->face_vertices[4 * f + 1] = v + 1;
            t->face_vertices[4 * f + 2] = v + nu + 2;
            t->face_vertices[4 * f + 3] = v + nu + 1;
        }
}

/* An nu x nv quad grid over [0, nu] x [0, nv] (unit cells) with heights
 * z = amplitude * (bumps) plus a deterministic jitter, scaled by `scale` and
 * shifted by `offset` (georeferenced coordinates). */
static inline test_mesh test_grid(int nu, int nv, double amplitude, double scale, double offset)
{
    test_mesh t;
    const int np = (nu + 1) * (nv + 1), nf = nu * nv;
    t.xyz = malloc(sizeof(double) * 3 * (size_t)np);
    t.face_start = malloc(sizeof(int32_t) * (size_t)(nf + 1));
    t.face_vertices = malloc(sizeof(int32_t) * 4 * (size_t)nf);
    uint32_t seed = 12345u;
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
            const int v = j * (nu + 1) + i;
            seed = seed * 1664525u + 1013904223u;
            const double jitter = ((double)(seed >> 8) / 16777216.0 - 0.5) * 0.1 * amplitude;
            const double x = i, y = j;
            const double z = amplitude * (0.08 * (x - 0.5 * nu) * (y - 0.5 * nv) / (1.0 + 0.02 * (nu + nv)) +
                                          1.5 * sin(0.35 * x) * cos(0.27 * y)) + jitter;
            t.xyz[3 * v] = x * scale + offset;
            t.xyz[3 * v + 1] = y * scale + offset;
            t.xyz[3 * v + 2] = z * scale;
        }
    grid_quads(&t, nu, nv);
    test_mesh_view(&t, np, nf);
    return t;
}

/* An n x n grid of unit quads, flat but for a saddle of radius r in its
 * middle, z = amplitude (x - c)(y - c) / r exp(-d^2 / r^2): a facade plane
 * with a local feature. Its faces far from the saddle are planar to
 * rounding, those near its axes nearly so (docs/solver-notes.md, "Method
 * auto: L/G when L/L closes a panel"). */
static inline test_mesh test_saddle(int n, double r, double amplitude)
{
    test_mesh t;
    const int np = (n + 1) * (n + 1), nf = n * n;
    const double c = 0.5 * n;
    t.xyz = malloc(sizeof(double) * 3 * (size_t)np);
    t.face_start = malloc(sizeof(int32_t) * (size_t)(nf + 1));
    t.face_vertices = malloc(sizeof(int32_t) * 4 * (size_t)nf);
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const int v = j * (n + 1) + i;
            const double x = i, y = j, d2 = (x - c) * (x - c) + (y - c) * (y - c);
            t.xyz[3 * v] = x, t.xyz[3 * v + 1] = y;
            t.xyz[3 * v + 2] = amplitude * (x - c) * (y - c) / r * exp(-d2 / (r * r));
        }
    grid_quads(&t, n, n);
    test_mesh_view(&t, np, nf);
    return t;
}

/* An n x n quad grid on z = x y over [-1, 1]^2 (tools/bench/families.py's
 * hypar(n), the same vertices and faces): every quad is skew, every input
 * corner at least 60 degrees. */
static inline test_mesh test_hypar(int n)
{
    test_mesh g;
    const int cu = n + 1, nv = cu * cu, nf = n * n;
    g.xyz = malloc(sizeof(double) * 3 * (size_t)nv);
    g.face_start = malloc(sizeof(int32_t) * (size_t)(nf + 1));
    g.face_vertices = malloc(sizeof(int32_t) * 4 * (size_t)nf);
    const double step = 2.0 / n;
    for (int j = 0; j < cu; ++j)
        for (int i = 0; i < cu; ++i) {
            const double x = i == n ? 1.0 : -1.0 + i * step, y = j == n ? 1.0 : -1.0 + j * step;
            double *p = g.xyz + 3 * (size_t)(j * cu + i);
            p[0] = x, p[1] = y, p[2] = x * y;
        }
    for (int f = 0; f <= nf; ++f)
        g.face_start[f] = 4 * f;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            int32_t *q = g.face_vertices + 4 * (size_t)(j * n + i);
            q[0] = j * cu + i, q[1] = j * cu + i + 1, q[2] = (j + 1) * cu + i + 1, q[3] = (j + 1) * cu + i;
        }
    test_mesh_view(&g, nv, nf);
    return g;
}

static inline void test_mesh_free(test_mesh *t)
{
    free(t->xyz);
    free(t->face_start);
    free(t->face_vertices);
}

#endif
