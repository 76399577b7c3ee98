/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Benchmark of closest-point queries: build time and queries per second on
 * triangulated doubly curved grids (10k to 1M triangles), query points near
 * the surface (the quality report's and the solver's use), 1 and 2 threads;
 * the median of several runs.
 *
 *   bench_surface [--runs R] [--json FILE] */
#include "facet.h"
#include "bench_common.h"
#include "test_meshes.h"

#include <stdio.h>
#include <string.h>
#include <time.h>

int main(int argc, char **argv)
{
    int runs = 5;
    const char *json_path = NULL;
    for (int k = 1; k < argc; ++k) {
        if (!strcmp(argv[k], "--runs") && k + 1 < argc)
            runs = atoi(argv[++k]);
        else if (!strcmp(argv[k], "--json") && k + 1 < argc)
            json_path = argv[++k];
        else {
            fprintf(stderr, "usage: %s [--runs R] [--json FILE]\n", argv[0]);
            return 2;
        }
    }
    if (runs < 1 || runs > 101)
        runs = 5;
    FILE *json = json_path ? fopen(json_path, "w") : NULL;
    if (json)
        fprintf(json, "[\n");
    /* quads split in two: 2 * nu * nv triangles */
    const int sides[][2] = {{100, 50}, {250, 200}, {1000, 500}};
    printf("%-10s %-9s %-8s %10s %14s %16s\n", "triangles", "queries", "threads", "build_s",
           "queries_per_s", "queries_per_cpu_s");
    int first = 1;
    for (size_t s = 0; s < sizeof sides / sizeof sides[0]; ++s) {
        test_mesh g = test_grid(sides[s][0], sides[s][1], 1.0, 1.0, 0.0);
        const int nt = 2 * g.mesh.n_faces;
        double times[101];
        facet_surface *surf = NULL;
        facet_error e;
        for (int r = 0; r < runs; ++r) {
            facet_surface_free(&surf);
            const double t0 = now();
            if (facet_surface_create_from_mesh(&g.mesh, &surf, &e) != FACET_OK) {
                fprintf(stderr, "bench_surface: %s\n", e.message);
                return 1;
            }
            times[r] = now() - t0;
        }
        const double build = median(times, runs);
        /* queries: every vertex moved off the surface by up to 0.2 cells */
        const int nq = g.mesh.n_vertices;
        double *q = malloc(sizeof(double) * 3 * (size_t)nq), *d = malloc(sizeof(double) * (size_t)nq);
        uint32_t seed = 7u;
        for (int i = 0; i < 3 * nq; ++i) {
            seed = seed * 1664525u + 1013904223u;
            q[i] = g.xyz[i] + 0.4 * ((double)(seed >> 8) / 16777216.0 - 0.5);
        }
        for (int threads = 1; threads <= 2; ++threads) {
            double cpu[101];
            for (int r = 0; r < runs; ++r) {
                const double t0 = now(), c0 = cpu_now();
                facet_surface_closest(surf, nq, q, threads, NULL, d, NULL, NULL, &e);
                times[r] = now() - t0;
                cpu[r] = cpu_now() - c0;
            }
            const double t = median(times, runs), c = median(cpu, runs);
            printf("%-10d %-9d %-8d %10.4f %14.0f %16.0f\n", nt, nq, threads, build, nq / t,
                   nq / c);
            if (json) {
                fprintf(json,
                        "%s  {\"triangles\": %d, \"queries\": %d, \"threads\": %d, "
                        "\"build_seconds\": %.17g, \"query_seconds\": %.17g, "
                        "\"queries_per_second\": %.17g, \"cpu_seconds\": %.17g}",
                        first ? "" : ",\n", nt, nq, threads, build, t, nq / t, c);
                first = 0;
            }
        }
        free(q);
        free(d);
        facet_surface_free(&surf);
        test_mesh_free(&g);
    }
    if (json) {
        fprintf(json, "\n]\n");
        fclose(json);
    }
    return 0;
}
