/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Benchmark of optimal liftings: factorization (facet_lifter_create), one
 * solve, and one vertex's fundamental lifting after that, on quad-grid plans
 * from 1k to 100k faces, straight (dimension nu + nv + 1) and with jittered
 * interior vertices (generic); medians of several runs.
 *
 *   bench_lift [--max-faces N] [--runs R] [--json FILE] */
#include "facet.h"
#include "bench_common.h"
#include "test_meshes.h"

#include <stdio.h>
#include <string.h>
#include <time.h>

int main(int argc, char **argv)
{
    long max_faces = 100000;
    int runs = 5;
    const char *json_path = NULL;
    for (int k = 1; k < argc; ++k) {
        if (!strcmp(argv[k], "--max-faces") && k + 1 < argc)
            max_faces = atol(argv[++k]);
        else if (!strcmp(argv[k], "--runs") && k + 1 < argc)
            runs = atoi(argv[++k]);
        else if (!strcmp(argv[k], "--json") && k + 1 < argc)
            json_path = argv[++k];
        else {
            fprintf(stderr, "usage: %s [--max-faces N] [--runs R] [--json FILE]\n", argv[0]);
            return 2;
        }
    }
    if (runs < 1 || runs > 101)
        runs = 5;
    FILE *json = json_path ? fopen(json_path, "w") : NULL;
    if (json)
        fprintf(json, "[\n");
    int first = 1;
    const int sides[][2] = {{40, 25}, {125, 80}, {400, 250}, {1250, 800}};
    printf("%-9s %8s %8s %6s %11s %11s %15s\n", "plan", "faces", "vertices", "dim", "factor s",
           "solve s", "fundamental ms");
    for (size_t m = 0; m < sizeof sides / sizeof sides[0]; ++m) {
        const long faces = (long)sides[m][0] * sides[m][1];
        if (faces > max_faces)
            break;
        for (int jitter = 0; jitter < 2; ++jitter) {
            test_mesh t = test_grid(sides[m][0], sides[m][1], 0.6, 1.0, 0.0);
            const int32_t n = t.mesh.n_vertices;
            const int nu = sides[m][0], nv = sides[m][1];
            uint32_t seed = 777u;
            if (jitter)
                for (int j = 1; j < nv; ++j)
                    for (int i = 1; i < nu; ++i) {
                        const int v = j * (nu + 1) + i;
                        seed = seed * 1664525u + 1013904223u;
                        t.xyz[3 * v] += ((double)(seed >> 8) / 16777216.0 - 0.5) * 0.3;
                        seed = seed * 1664525u + 1013904223u;
                        t.xyz[3 * v + 1] += ((double)(seed >> 8) / 16777216.0 - 0.5) * 0.3;
                    }
            double *targets = malloc(sizeof(double) * (size_t)n);
            double *z = malloc(sizeof(double) * (size_t)n);
            for (int32_t v = 0; v < n; ++v)
                targets[v] = t.xyz[3 * v + 2];
            double factor[101], solve[101], fundamental[101];
            int32_t dim = 0;
            for (int r = 0; r < runs; ++r) {
                facet_lifter *l = NULL;
                facet_error e;
                double t0 = now();
                if (facet_lifter_create(&t.mesh, NULL, NULL, &l, &e) < 0) {
                    fprintf(stderr, "create failed: %s\n", e.message);
                    return 1;
                }
                factor[r] = now() - t0;
                dim = facet_lifter_dimension(l);
                t0 = now();
                if (facet_lifter_solve(l, targets, z, NULL, &e) < 0) {
                    fprintf(stderr, "solve failed: %s\n", e.message);
                    return 1;
                }
                solve[r] = now() - t0;
                /* Median over 21 vertices spread over the plan, per run. */
                double each[21];
                for (int k = 0; k < 21; ++k) {
                    t0 = now();
                    facet_lifter_fundamental(l, (int32_t)((long)k * (n - 1) / 20), z, &e);
                    each[k] = now() - t0;
                }
                fundamental[r] = median(each, 21);
                facet_lifter_free(&l);
            }
            double mf = median(factor, runs), ms = median(solve, runs),
                   mu = median(fundamental, runs);
            printf("%-9s %8ld %8d %6d %11.4f %11.4f %15.3f\n", jitter ? "jittered" : "straight",
                   faces, (int)n, (int)dim, mf, ms, 1e3 * mu);
            fflush(stdout);
            if (json) {
                fprintf(json,
                        "%s  {\"plan\": \"%s\", \"faces\": %ld, \"vertices\": %d, \"dimension\": "
                        "%d, \"factor_seconds\": %.17g, \"solve_seconds\": %.17g, "
                        "\"fundamental_seconds\": %.17g, \"runs\": %d}",
                        first ? "" : ",\n", jitter ? "jittered" : "straight", faces, (int)n,
                        (int)dim, mf, ms, mu, runs);
                first = 0;
            }
            free(targets);
            free(z);
            test_mesh_free(&t);
        }
    }
    if (json) {
        fprintf(json, "\n]\n");
        fclose(json);
    }
    return 0;
}
