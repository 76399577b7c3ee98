/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* One planarization configuration on one mesh, timed in C: the honest
 * measure of issue 3's iteration targets (no Python around the solve).
 *
 *   bench_iterations MESH [--method ll|lg] [--iterations N] [--threads T]
 *                    [--runs R] [--schedule paper|default] [--anderson M] [--angle-floor DEG]
 *                    [--check FILE]
 *
 * MESH is an OBJ file (v and f lines; e.g. Level 5 written by
 * tools/bench/families.py) or grid:NUxNV (the doubly curved quad grid of
 * test_meshes.h). --schedule paper is the paper's fixed schedule (L/L
 * r = 0.9, L/G r = 0.7, no hold; as tools/bench/run_bench.py's ll100 and
 * lg30), default is facet_planarize_options_default. --anderson overrides
 * the depth (paper: 0). The first solve (symbolic analysis, page faults) is
 * reported apart; then the median and range of R timed solves, the CPU
 * seconds per solve, ns per face per iteration, and the peak RSS per face.
 * --check FILE writes the last result (17 significant digits) to compare
 * two builds bit for bit. Run it with OPENBLAS_NUM_THREADS=1 (as make
 * bench runs bench_planarize): the library links OpenBLAS, whose worker
 * threads may spin for about 0.1 s after it loads; a two-thread "first"
 * solve of grid:100x100 then took 0.12 s instead of 0.02-0.025 s
 * (docs/benchmarks.md). */
#include "facet.h"
#include "bench_common.h"
#include "test_meshes.h"

#include <stdio.h>
#include <string.h>
#include <time.h>

/* A minimal OBJ reader: "v x y z" and "f a b c ..." (1-based, a/b/c forms). */
static int read_obj(const char *path, test_mesh *t)
{
    FILE *in = fopen(path, "r");
    if (!in)
        return 0;
    size_t nv = 0, nf = 0, nc = 0, cv = 1024, cf = 1024, cc = 4096;
    double *xyz = malloc(sizeof(double) * 3 * cv);
    int32_t *start = malloc(sizeof(int32_t) * (cf + 1)), *idx = malloc(sizeof(int32_t) * cc);
    char line[4096];
    start[0] = 0;
    while (fgets(line, sizeof line, in)) {
        if (line[0] == 'v' && line[1] == ' ') {
            if (nv == cv)
                xyz = realloc(xyz, sizeof(double) * 3 * (cv *= 2));
            if (sscanf(line + 2, "%lf %lf %lf", xyz + 3 * nv, xyz + 3 * nv + 1, xyz + 3 * nv + 2) != 3)
                return 0;
            ++nv;
        } else if (line[0] == 'f' && line[1] == ' ') {
            char *p = line + 2;
            for (;;) {
                char *end;
                const long k = strtol(p, &end, 10);
                if (end == p)
                    break;
                if (nc == cc)
                    idx = realloc(idx, sizeof(int32_t) * (cc *= 2));
                idx[nc++] = (int32_t)(k - 1);
                p = end;
                while (*p && *p != ' ' && *p != '\t' && *p != '\n')
                    ++p;
            }
            if (nf + 1 == cf)
                start = realloc(start, sizeof(int32_t) * ((cf *= 2) + 1));
            start[++nf] = (int32_t)nc;
        }
    }
    fclose(in);
    t->xyz = xyz;
    t->face_start = start;
    t->face_vertices = idx;
    t->mesh.n_vertices = (int32_t)nv;
    t->mesh.n_faces = (int32_t)nf;
    t->mesh.xyz = xyz;
    t->mesh.face_start = start;
    t->mesh.face_vertices = idx;
    return nv > 0 && nf > 0;
}

int main(int argc, char **argv)
{
    const char *mesh_name = NULL, *check = NULL;
    int method = FACET_METHOD_LOCAL_LOCAL, iterations = 100, threads = 1, runs = 9, anderson = -1;
    double angle_floor = -1.0;
    int paper = 1;
    for (int k = 1; k < argc; ++k) {
        if (!strcmp(argv[k], "--method") && k + 1 < argc) {
            ++k;
            method = !strcmp(argv[k], "lg") ? FACET_METHOD_LOCAL_GLOBAL : FACET_METHOD_LOCAL_LOCAL;
        } else if (!strcmp(argv[k], "--iterations") && k + 1 < argc) {
            iterations = atoi(argv[++k]);
        } else if (!strcmp(argv[k], "--threads") && k + 1 < argc) {
            threads = atoi(argv[++k]);
        } else if (!strcmp(argv[k], "--runs") && k + 1 < argc) {
            runs = atoi(argv[++k]);
        } else if (!strcmp(argv[k], "--anderson") && k + 1 < argc) {
            anderson = atoi(argv[++k]);
        } else if (!strcmp(argv[k], "--angle-floor") && k + 1 < argc) {
            angle_floor = atof(argv[++k]);
        } else if (!strcmp(argv[k], "--schedule") && k + 1 < argc) {
            paper = !strcmp(argv[++k], "paper");
        } else if (!strcmp(argv[k], "--check") && k + 1 < argc) {
            check = argv[++k];
        } else if (argv[k][0] != '-' && !mesh_name) {
            mesh_name = argv[k];
        } else {
            fprintf(stderr,
                    "usage: %s MESH [--method ll|lg] [--iterations N] [--threads T] [--runs R] "
                    "[--schedule paper|default] [--anderson M] [--angle-floor DEG] [--check FILE]\n",
                    argv[0]);
            return 2;
        }
    }
    if (!mesh_name || runs < 1 || runs > 101 || iterations < 0) {
        fprintf(stderr, "bench_iterations: give a mesh (OBJ file or grid:NUxNV), runs 1-101\n");
        return 2;
    }
    test_mesh t;
    int nu = 0, nv = 0;
    if (sscanf(mesh_name, "grid:%dx%d", &nu, &nv) == 2 && nu > 0 && nv > 0) {
        t = test_grid(nu, nv, 0.6, 1.0, 0.0);
    } else if (!read_obj(mesh_name, &t)) {
        fprintf(stderr, "bench_iterations: cannot read mesh %s\n", mesh_name);
        return 2;
    }
    const long rss_mesh = peak_rss_kb();
    double *out = malloc(sizeof(double) * 3 * (size_t)t.mesh.n_vertices);
    facet_planarizer *s = NULL;
    facet_error e;
    if (facet_planarizer_create(&t.mesh, &s, &e) != FACET_OK) {
        fprintf(stderr, "create: %s\n", e.message);
        return 1;
    }
    facet_planarize_options o;
    facet_planarize_options_default((facet_method)method, &o);
    o.iterations = iterations;
    o.threads = threads;
    if (paper) {
        o.ratio = method == FACET_METHOD_LOCAL_GLOBAL ? 0.7 : 0.9;
        o.hold_tol = 0.0;
        o.anderson = 0;
    }
    if (anderson >= 0)
        o.anderson = anderson;
    if (angle_floor >= 0.0)
        o.angle_floor = angle_floor;
    facet_planarize_result r;
    double t0 = now();
    facet_status status = facet_planarizer_solve(s, t.xyz, &o, out, &r, &e);
    const double first = now() - t0;
    if (status < 0) {
        fprintf(stderr, "solve: %s\n", e.message);
        return 1;
    }
    double times[101], cpu[101];
    for (int k = 0; k < runs; ++k) {
        const double c0 = cpu_now();
        t0 = now();
        facet_planarizer_solve(s, t.xyz, &o, out, &r, &e);
        times[k] = now() - t0;
        cpu[k] = cpu_now() - c0;
    }
    qsort(times, (size_t)runs, sizeof(double), compare_double);
    qsort(cpu, (size_t)runs, sizeof(double), compare_double);
    const double median = times[runs / 2];
    const int32_t nf = t.mesh.n_faces;
    const double per = r.iterations > 0 ? 1e9 * median / ((double)nf * r.iterations) : 0.0;
    printf("%s %s faces=%d threads=%d schedule=%s anderson=%d iterations=%d first=%.4f s "
           "median=%.4f s (min %.4f max %.4f, %d runs) cpu=%.4f s ns/face/iter=%.1f "
           "max_rel=%.3g peak_rss_growth=%.0f B/face\n",
           mesh_name, method == FACET_METHOD_LOCAL_GLOBAL ? "lg" : "ll", (int)nf, threads,
           paper ? "paper" : "default", (int)o.anderson, (int)r.iterations, first, median, times[0],
           times[runs - 1], runs, cpu[runs / 2], per, r.planarity_max_rel,
           1024.0 * (double)(peak_rss_kb() - rss_mesh) / (double)nf);
    if (check) {
        FILE *f = fopen(check, "w");
        if (!f)
            return 1;
        for (int32_t v = 0; v < t.mesh.n_vertices; ++v)
            fprintf(f, "%.17g %.17g %.17g\n", out[3 * v], out[3 * v + 1], out[3 * v + 2]);
        fclose(f);
    }
    facet_planarizer_free(&s);
    free(out);
    test_mesh_free(&t);
    return 0;
}
