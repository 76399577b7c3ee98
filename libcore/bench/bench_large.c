/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* One to-tolerance planarization of a large mesh with the given options, in
 * C: iterations, stop reason, planarity, wall and CPU time, peak memory per
 * face and the vertex displacement (issue 3's large-mesh target).
 *
 *   bench_large MESH [--method auto|ll|lg] [--threads T] [--runs R]
 *               [--set NAME=VALUE ...]
 *
 * MESH is a binary file written by tools/bench/dump_mesh.py (int64 n_vertices,
 * n_faces, n_corners; float64 xyz; int32 face_start; int32 face_vertices)
 * or grid:NUxNV (test_meshes.h). The options start from
 * facet_planarize_options_default(method); --set changes one of mu0, ratio,
 * mu_min, tol_rel, tol_abs, hold_tol, hold_max, anderson, max_iter,
 * iterations. Peak memory is the growth of the peak resident set over what
 * the mesh and the output array took, per face: the solver's own memory. */
#include "facet.h"
#include "bench_common.h"
#include "test_meshes.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static int read_bin(const char *path, test_mesh *t)
{
    FILE *in = fopen(path, "rb");
    int64_t head[3];
    if (!in || fread(head, sizeof head, 1, in) != 1 || head[0] <= 0 || head[1] <= 0 ||
        head[2] <= 0 || head[0] > INT32_MAX || head[1] >= INT32_MAX || head[2] > INT32_MAX) {
        if (in)
            fclose(in);
        return 0;
    }
    const size_t nv = (size_t)head[0], nf = (size_t)head[1], nc = (size_t)head[2];
    t->xyz = malloc(sizeof(double) * 3 * nv);
    t->face_start = malloc(sizeof(int32_t) * (nf + 1));
    t->face_vertices = malloc(sizeof(int32_t) * nc);
    const int ok = t->xyz && t->face_start && t->face_vertices &&
                   fread(t->xyz, sizeof(double), 3 * nv, in) == 3 * nv &&
                   fread(t->face_start, sizeof(int32_t), nf + 1, in) == nf + 1 &&
                   fread(t->face_vertices, sizeof(int32_t), nc, in) == nc;
    fclose(in);
    t->mesh.n_vertices = (int32_t)nv;
    t->mesh.n_faces = (int32_t)nf;
    t->mesh.xyz = t->xyz;
    t->mesh.face_start = t->face_start;
    t->mesh.face_vertices = t->face_vertices;
    return ok;
}

static int set_option(facet_planarize_options *o, const char *text)
{
    char name[64];
    double value;
    if (sscanf(text, "%63[a-z_0-9]=%lf", name, &value) != 2)
        return 0;
    if (!strcmp(name, "mu0"))
        o->mu0 = value;
    else if (!strcmp(name, "ratio"))
        o->ratio = value;
    else if (!strcmp(name, "mu_min"))
        o->mu_min = value;
    else if (!strcmp(name, "tol_rel"))
        o->tol_rel = value;
    else if (!strcmp(name, "tol_abs"))
        o->tol_abs = value;
    else if (!strcmp(name, "hold_tol"))
        o->hold_tol = value;
    else if (!strcmp(name, "hold_max"))
        o->hold_max = (int32_t)value;
    else if (!strcmp(name, "anderson"))
        o->anderson = (int32_t)value;
    else if (!strcmp(name, "max_iter"))
        o->max_iter = (int32_t)value;
    else if (!strcmp(name, "iterations"))
        o->iterations = (int32_t)value;
    else if (!strcmp(name, "quality_angle"))
        o->quality_angle = value;
    else
        return 0;
    return 1;
}

static const char *reason_name(facet_stop_reason r)
{
    static const char *names[] = {"none", "tolerance", "max_iter", "iterations",
                                  "stagnation", "cancelled", "time"};
    return (unsigned)r < sizeof names / sizeof names[0] ? names[r] : "?";
}

int main(int argc, char **argv)
{
    const char *mesh_name = NULL, *method_name = "auto";
    int threads = 2, runs = 1;
    const char *sets[32];
    int n_sets = 0;
    for (int k = 1; k < argc; ++k) {
        if (!strcmp(argv[k], "--method") && k + 1 < argc)
            method_name = argv[++k];
        else if (!strcmp(argv[k], "--threads") && k + 1 < argc)
            threads = atoi(argv[++k]);
        else if (!strcmp(argv[k], "--runs") && k + 1 < argc)
            runs = atoi(argv[++k]);
        else if (!strcmp(argv[k], "--set") && k + 1 < argc && n_sets < 32)
            sets[n_sets++] = argv[++k];
        else if (argv[k][0] != '-' && !mesh_name)
            mesh_name = argv[k];
        else {
            fprintf(stderr, "usage: %s MESH [--method auto|ll|lg] [--threads T] [--runs R] "
                            "[--set NAME=VALUE ...]\n", argv[0]);
            return 2;
        }
    }
    facet_method method = !strcmp(method_name, "ll")   ? FACET_METHOD_LOCAL_LOCAL
                          : !strcmp(method_name, "lg") ? FACET_METHOD_LOCAL_GLOBAL
                                                       : FACET_METHOD_AUTO;
    if (!mesh_name || runs < 1 || runs > 101) {
        fprintf(stderr, "bench_large: give a mesh (binary file or grid:NUxNV), runs 1-101\n");
        return 2;
    }
    test_mesh t;
    int nu = 0, nvv = 0;
    if (sscanf(mesh_name, "grid:%dx%d", &nu, &nvv) == 2 && nu > 0 && nvv > 0) {
        t = test_grid(nu, nvv, 0.6, 1.0, 0.0);
    } else if (!read_bin(mesh_name, &t)) {
        fprintf(stderr, "bench_large: cannot read mesh %s\n", mesh_name);
        return 2;
    }
    const int32_t nv = t.mesh.n_vertices, nf = t.mesh.n_faces;
    double *out = malloc(sizeof(double) * 3 * (size_t)nv);
    for (size_t k = 0; k < 3 * (size_t)nv; ++k) /* touch it: not the solver's memory */
        out[k] = 0.0;
    const long rss_mesh = peak_rss_kb();
    facet_planarize_options o;
    facet_planarize_options_default(method, &o);
    o.threads = threads;
    for (int k = 0; k < n_sets; ++k)
        if (!set_option(&o, sets[k])) {
            fprintf(stderr, "bench_large: bad --set %s\n", sets[k]);
            return 2;
        }
    facet_planarizer *s = NULL;
    facet_error e;
    if (facet_planarizer_create(&t.mesh, &s, &e) != FACET_OK) {
        fprintf(stderr, "create: %s\n", e.message);
        return 1;
    }
    double times[101], cpu[101];
    facet_planarize_result r;
    facet_status status = FACET_OK;
    for (int k = 0; k < runs; ++k) {
        const double c0 = cpu_now(), t0 = now();
        status = facet_planarizer_solve(s, t.xyz, &o, out, &r, &e);
        times[k] = now() - t0;
        cpu[k] = cpu_now() - c0;
        if (status < 0) {
            fprintf(stderr, "solve: %s\n", e.message);
            return 1;
        }
    }
    const long rss_peak = peak_rss_kb();
    double fastest = times[0]; /* (before median() sorts the times) */
    for (int k = 1; k < runs; ++k)
        fastest = times[k] < fastest ? times[k] : fastest;
    const double wall = median(times, runs), cpu_median = median(cpu, runs);
    /* displacement in mean edge lengths of the input */
    double edge = 0.0;
    for (int32_t f = 0; f < nf; ++f)
        for (int32_t k = t.face_start[f]; k < t.face_start[f + 1]; ++k) {
            const int32_t a = t.face_vertices[k];
            const int32_t b = t.face_vertices[k + 1 < t.face_start[f + 1] ? k + 1 : t.face_start[f]];
            double d2 = 0.0;
            for (int c = 0; c < 3; ++c)
                d2 += (t.xyz[3 * (size_t)a + c] - t.xyz[3 * (size_t)b + c]) *
                      (t.xyz[3 * (size_t)a + c] - t.xyz[3 * (size_t)b + c]);
            edge += sqrt(d2);
        }
    edge /= (double)t.face_start[nf];
    double sum2 = 0.0, dmax = 0.0;
    for (int32_t v = 0; v < nv; ++v) {
        double d2 = 0.0;
        for (int c = 0; c < 3; ++c)
            d2 += (out[3 * (size_t)v + c] - t.xyz[3 * (size_t)v + c]) *
                  (out[3 * (size_t)v + c] - t.xyz[3 * (size_t)v + c]);
        sum2 += d2;
        dmax = d2 > dmax ? d2 : dmax;
    }
    /* distance from the input surface and the smallest corner angle */
    double srf_rms = -1.0, srf_max = -1.0, angle_min = -1.0;
    int below5 = 0;
    facet_surface *surface = NULL;
    double *distance = malloc(sizeof(double) * (size_t)(nv > nf ? nv : nf));
    if (distance && facet_surface_create_from_mesh(&t.mesh, &surface, &e) >= 0 &&
        facet_surface_closest(surface, nv, out, threads, NULL, distance, NULL, NULL, &e) >= 0) {
        double d2 = 0.0, dm = 0.0;
        for (int32_t v = 0; v < nv; ++v)
            d2 += distance[v] * distance[v], dm = distance[v] > dm ? distance[v] : dm;
        srf_rms = sqrt(d2 / nv) / edge, srf_max = dm / edge;
    }
    facet_surface_free(&surface);
    facet_mesh result_mesh = t.mesh;
    result_mesh.xyz = out;
    if (distance && facet_face_shape(&result_mesh, NULL, threads, distance, NULL, NULL, &e) >= 0) {
        angle_min = 1e9;
        for (int32_t f = 0; f < nf; ++f) {
            angle_min = distance[f] < angle_min ? distance[f] : angle_min;
            below5 += distance[f] < 5.0 * M_PI / 180.0;
        }
        angle_min *= 180.0 / M_PI;
    }
    free(distance);
    printf("%s method=%s faces=%d threads=%d iterations=%d reason=%s max_rel=%.3g "
           "wall=%.3f s (median of %d; min %.3f) cpu=%.3f s ns/face/iter=%.1f "
           "peak=%.0f B/face disp_rms=%.4g disp_max=%.4g surface_rms=%.4g surface_max=%.4g edges "
           "min_angle=%.2f deg below_5=%d aa=%d/%d status=%d\n",
           mesh_name, method_name, (int)nf, threads, (int)r.iterations, reason_name(r.stop_reason),
           r.planarity_max_rel, wall, runs, fastest, cpu_median,
           r.iterations > 0 ? 1e9 * wall / ((double)nf * r.iterations) : 0.0,
           1024.0 * (double)(rss_peak - rss_mesh) / (double)nf, sqrt(sum2 / nv) / edge,
           sqrt(dmax) / edge, srf_rms, srf_max, angle_min, below5, (int)r.anderson_accepted, (int)r.anderson_rejected, (int)status);
    facet_planarizer_free(&s);
    free(out);
    test_mesh_free(&t);
    return 0;
}
