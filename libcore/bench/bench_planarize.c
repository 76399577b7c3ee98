/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Benchmark of the planarization iterations: ns per face per iteration for
 * local/local and local/global on generated doubly curved quad grids from 1k
 * to 1M faces, with 1 and 2 threads; the median of several runs.
 *
 *   bench_planarize [--max-faces N] [--runs R] [--json FILE] */
#include "facet.h"
#include "bench_common.h"
#include "test_meshes.h"

#include <stdio.h>
#include <string.h>
#include <time.h>

int main(int argc, char **argv)
{
    long max_faces = 1000000;
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
    printf("%-6s %9s %8s %6s %12s %14s\n", "method", "faces", "threads", "iters", "median s",
           "ns/face/iter");
    for (size_t m = 0; m < sizeof sides / sizeof sides[0]; ++m) {
        const long faces = (long)sides[m][0] * sides[m][1];
        if (faces > max_faces)
            break;
        test_mesh t = test_grid(sides[m][0], sides[m][1], 0.6, 1.0, 0.0);
        double *out = malloc(sizeof(double) * 3 * (size_t)t.mesh.n_vertices);
        for (int method = 0; method < 2; ++method) {
            /* L/G is a sparse factorization per iteration: keep it to <= 100k faces */
            if (method == FACET_METHOD_LOCAL_GLOBAL && faces > 100000)
                continue;
            facet_planarizer *s = NULL;
            facet_error e;
            if (facet_planarizer_create(&t.mesh, &s, &e) != FACET_OK) {
                fprintf(stderr, "create: %s\n", e.message);
                return 1;
            }
            const int iters = method == FACET_METHOD_LOCAL_LOCAL
                                  ? (faces >= 1000000 ? 10 : faces >= 100000 ? 20 : 100)
                                  : (faces >= 100000 ? 5 : 20);
            for (int threads = 1; threads <= 2; ++threads) {
                facet_planarize_options o;
                facet_planarize_options_default((facet_method)method, &o);
                o.iterations = iters;
                o.threads = threads;
                double times[101];
                facet_planarize_result r;
                facet_planarizer_solve(s, t.xyz, &o, out, &r, &e); /* warm-up, analysis */
                for (int k = 0; k < runs; ++k) {
                    const double t0 = now();
                    facet_planarizer_solve(s, t.xyz, &o, out, &r, &e);
                    times[k] = now() - t0;
                }
                qsort(times, (size_t)runs, sizeof(double), compare_double);
                const double median = times[runs / 2];
                const double ns = 1e9 * median / ((double)faces * iters);
                const char *name = method == FACET_METHOD_LOCAL_LOCAL ? "ll" : "lg";
                printf("%-6s %9ld %8d %6d %12.4f %14.1f\n", name, faces, threads, iters, median, ns);
                fflush(stdout);
                if (json) {
                    fprintf(json,
                            "%s  {\"method\": \"%s\", \"faces\": %ld, \"threads\": %d, "
                            "\"iterations\": %d, \"median_seconds\": %.17g, "
                            "\"ns_per_face_iteration\": %.17g}",
                            first ? "" : ",\n", name, faces, threads, iters, median, ns);
                    first = 0;
                }
            }
            facet_planarizer_free(&s);
        }
        free(out);
        test_mesh_free(&t);
    }
    if (json) {
        fprintf(json, "\n]\n");
        fclose(json);
    }
    return 0;
}
