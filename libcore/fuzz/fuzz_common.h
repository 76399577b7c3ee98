/* SPDX-License-Identifier: LGPL-2.1-or-later */
/*
 * fuzz_common.h -- shared by the libFuzzer targets of libfacet.
 *
 * The fuzz bytes are decoded into a mesh (random topology and coordinates,
 * or a grid of quads bent and corrupted by the bytes, so that most inputs
 * reach the solvers while some exercise validation), options and queries.
 * The oracle, checked by every target:
 *  - no crash and no sanitizer report;
 *  - the status is one of FACET_STATUS_LIST, and an error fills the error
 *    record (same status, a non-empty NUL-terminated message);
 *  - when the status is >= 0 every floating-point output is finite;
 *  - running the same call again (with another thread count where the call
 *    takes one) gives the same status and the same bits.
 * A broken oracle prints what broke and calls abort(), which libFuzzer and
 * the replay driver (replay_main.c) report as a finding.
 */
#ifndef FACET_FUZZ_COMMON_H
#define FACET_FUZZ_COMMON_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "facet.h"

/* ---------------------------------------------------------------- bytes */

typedef struct fz_bytes {
    const uint8_t *p;
    size_t n;
} fz_bytes;

static inline uint8_t fz_u8(fz_bytes *b)
{
    if (b->n == 0) return 0;
    b->n--;
    return *b->p++;
}

static inline uint16_t fz_u16(fz_bytes *b)
{
    uint16_t lo = fz_u8(b);
    return (uint16_t)(lo | (uint16_t)fz_u8(b) << 8);
}

static inline uint32_t fz_u32(fz_bytes *b)
{
    uint32_t lo = fz_u16(b);
    return lo | (uint32_t)fz_u16(b) << 16;
}

/* An int in [0, n) (0 when n <= 0). */
static inline int32_t fz_below(fz_bytes *b, int32_t n)
{
    if (n <= 0) return 0;
    return (int32_t)(n <= 256 ? fz_u8(b) % (uint32_t)n : fz_u32(b) % (uint32_t)n);
}

/* A double: mostly ordinary, sometimes special (NaN, Inf, huge, tiny,
 * denormal, -0), sometimes raw bits. */
static inline double fz_special(fz_bytes *b)
{
    static const double specials[] = {0.0, -0.0, 1.0, -1.0, 1e-300, 4.9e-324, 1e300, -1e300,
                                      1.7976931348623157e308, 2.2250738585072014e-308,
                                      1e-6, 1e7, 6.5e6, 1e-12, 1e12};
    uint8_t k = fz_u8(b);
    if (k < 3) return (double)NAN;
    if (k < 5) return (double)INFINITY;
    if (k < 7) return -(double)INFINITY;
    if (k < 40) return specials[k % (sizeof specials / sizeof specials[0])];
    if (k < 60) {
        uint64_t lo = fz_u32(b), hi = fz_u32(b);
        uint64_t bits = lo | hi << 32;
        double d;
        memcpy(&d, &bits, sizeof d);
        return d;
    }
    return ((double)fz_u16(b) - 32768.0) / 256.0;
}

/* A double in [lo, hi], or with probability ~special/256 a special value. */
static inline double fz_range(fz_bytes *b, double lo, double hi, uint8_t special)
{
    if (fz_u8(b) < special) return fz_special(b);
    return lo + (hi - lo) * (double)fz_u16(b) / 65535.0;
}

/* ----------------------------------------------------------------- mesh */

enum { FZ_MAX_VERTICES = 400, FZ_MAX_FACES = 400, FZ_MAX_CORNERS = 2000 };

typedef struct fz_mesh {
    facet_mesh mesh;
    double xyz[3 * FZ_MAX_VERTICES];
    int32_t face_start[FZ_MAX_FACES + 1];
    int32_t face_vertices[FZ_MAX_CORNERS];
} fz_mesh;

static inline void fz_finish(fz_mesh *m, int32_t nv, int32_t nf)
{
    m->mesh.n_vertices = nv;
    m->mesh.n_faces = nf;
    m->mesh.xyz = m->xyz;
    m->mesh.face_start = m->face_start;
    m->mesh.face_vertices = m->face_vertices;
}

/* Random topology: any degree, any index (in range mostly). */
static inline void fz_random_mesh(fz_bytes *b, fz_mesh *m)
{
    int32_t nv = fz_below(b, 40);
    int32_t nf = fz_below(b, 30);
    double scale = fz_range(b, 0.0, 10.0, 10);
    int32_t c = 0;
    for (int32_t v = 0; v < 3 * nv; v++) m->xyz[v] = scale * fz_range(b, -1.0, 1.0, 12);
    m->face_start[0] = 0;
    for (int32_t f = 0; f < nf; f++) {
        uint8_t d = fz_u8(b);
        int32_t degree = d < 200 ? 3 + d % 4 : d % 9;
        for (int32_t k = 0; k < degree && c < FZ_MAX_CORNERS; k++) {
            uint8_t how = fz_u8(b);
            int32_t index;
            if (how < 245) index = nv > 0 ? (int32_t)(how % (uint32_t)nv) : 0;
            else if (how < 248) index = -1;
            else if (how < 251) index = nv;
            else if (how < 253) index = INT32_MAX;
            else index = INT32_MIN;
            m->face_vertices[c++] = index;
        }
        m->face_start[f + 1] = c;
    }
    fz_finish(m, nv, nf);
}

/* A rows x cols grid of quads (some split into triangles, some removed,
 * some pairs merged into pentagon-like strips), bent out of plane, placed
 * at a scale from 1e-6 to 1e7 and an offset up to georeferenced
 * coordinates; then a few corruptions. */
static inline void fz_grid_mesh(fz_bytes *b, fz_mesh *m)
{
    int32_t rows = 1 + fz_below(b, 8), cols = 1 + fz_below(b, 8);
    int32_t nv = (rows + 1) * (cols + 1);
    static const double scales[] = {1e-6, 1e-3, 1.0, 1.0, 1.0, 1e3, 1e7};
    static const double offsets[] = {0.0, 0.0, 0.0, 1e3, 6.5e6, -2.5e6};
    double scale = scales[fz_below(b, 7)];
    double offset = offsets[fz_below(b, 6)];
    double bend = fz_range(b, 0.0, 0.5, 0);
    double noise = fz_u8(b) < 128 ? 0.0 : fz_range(b, 0.0, 0.3, 0);
    for (int32_t i = 0; i <= rows; i++)
        for (int32_t j = 0; j <= cols; j++) {
            int32_t v = i * (cols + 1) + j;
            double x = j, y = i;
            double z = bend * ((x - 0.5 * cols) * (x - 0.5 * cols) - (y - 0.5 * rows) * (y - 0.5 * rows)) / 4.0;
            x += noise * fz_range(b, -1.0, 1.0, 0);
            y += noise * fz_range(b, -1.0, 1.0, 0);
            z += noise * fz_range(b, -1.0, 1.0, 0);
            m->xyz[3 * v] = offset + scale * x;
            m->xyz[3 * v + 1] = offset + scale * y;
            m->xyz[3 * v + 2] = scale * z;
        }
    int32_t nf = 0, c = 0;
    m->face_start[0] = 0;
    for (int32_t i = 0; i < rows; i++)
        for (int32_t j = 0; j < cols; j++) {
            int32_t a = i * (cols + 1) + j, q[4] = {a, a + 1, a + cols + 2, a + cols + 1};
            uint8_t kind = fz_u8(b);
            if (kind < 20) continue;                 /* a hole */
            if (kind < 60) {                         /* two triangles */
                int32_t t[6] = {q[0], q[1], q[2], q[0], q[2], q[3]};
                for (int k = 0; k < 6; k++) m->face_vertices[c++] = t[k];
                m->face_start[++nf] = c - 3;
                m->face_start[++nf] = c;
                continue;
            }
            for (int k = 0; k < 4; k++) m->face_vertices[c++] = q[(kind & 1) ? 3 - k : k];
            m->face_start[++nf] = c;
        }
    fz_finish(m, nv, nf);
    /* corruptions */
    int32_t n_corrupt = fz_u8(b) < 200 ? 0 : 1 + fz_below(b, 3);
    for (int32_t k = 0; k < n_corrupt; k++) {
        uint8_t what = fz_u8(b) % 8;
        if (c == 0 || nv == 0) break;
        switch (what) {
        /* value first, then index: the order clang gave these statements when
         * the regressions were recorded, spelled out so that every compiler
         * decodes the same (C leaves it unspecified; gcc does the index first) */
        case 0: { int32_t value = fz_below(b, nv + 3) - 1; m->face_vertices[fz_below(b, c)] = value; break; }
        case 1: { double value = fz_special(b); m->xyz[fz_below(b, 3 * nv)] = value; break; }
        case 2: if (nf > 0) { int32_t value = fz_below(b, c + 2); m->face_start[1 + fz_below(b, nf)] = value; } break;
        case 3: { int32_t value = m->face_vertices[fz_below(b, c)]; m->face_vertices[fz_below(b, c)] = value; break; }
        case 4: { /* a vertex moved onto another: zero-length edge */
            int32_t u = fz_below(b, nv), w = fz_below(b, nv);
            memcpy(m->xyz + 3 * u, m->xyz + 3 * w, 3 * sizeof(double));
            break;
        }
        case 5: m->mesh.n_vertices = fz_below(b, nv + 1); break;
        case 6: m->mesh.n_faces = fz_below(b, nf + 1); break;
        default: m->face_start[0] = fz_below(b, 3); break;
        }
    }
}

static inline void fz_mesh_decode(fz_bytes *b, fz_mesh *m)
{
    if (fz_u8(b) < 64) fz_random_mesh(b, m);
    else fz_grid_mesh(b, m);
}

/* Corners of a mesh that passed validation. */
static inline int32_t fz_corners(const facet_mesh *mesh)
{
    return mesh->face_start[mesh->n_faces];
}

/* --------------------------------------------------------------- oracle */

#define FZ_FAIL(...)                                                  \
    do {                                                              \
        fprintf(stderr, "FUZZ ORACLE: %s:%d: ", __FILE__, __LINE__);  \
        fprintf(stderr, __VA_ARGS__);                                 \
        fputc('\n', stderr);                                          \
        abort();                                                      \
    } while (0)

static inline int fz_known_status(facet_status s)
{
    switch ((int)s) {
#define FZ_CASE(name, value, text) case value:
        FACET_STATUS_LIST(FZ_CASE)
#undef FZ_CASE
        return 1;
    default:
        return 0;
    }
}

/* The status is listed; an error filled the record. */
static inline void fz_check_status(const char *call, facet_status s, const facet_error *e)
{
    if (!fz_known_status(s)) FZ_FAIL("%s returned unlisted status %d", call, (int)s);
    if (s < 0) {
        if (memchr(e->message, 0, sizeof e->message) == NULL)
            FZ_FAIL("%s: error message not NUL-terminated", call);
        if (e->message[0] == 0) FZ_FAIL("%s: status %d with an empty message", call, (int)s);
        if (e->status != s) FZ_FAIL("%s: status %d but error.status %d", call, (int)s, (int)e->status);
    }
}

static inline void fz_check_finite(const char *call, const char *what, const double *x, int64_t n)
{
    if (x == NULL) return;
    for (int64_t i = 0; i < n; i++)
        if (!isfinite(x[i])) FZ_FAIL("%s returned ok but %s[%lld] = %g", call, what, (long long)i, x[i]);
}

static inline void fz_check_same(const char *call, const char *what, const void *a, const void *b,
                                 size_t bytes)
{
    if ((a == NULL) != (b == NULL)) FZ_FAIL("%s: %s allocated once only", call, what);
    if (a != NULL && memcmp(a, b, bytes) != 0) FZ_FAIL("%s: %s differs between two runs", call, what);
}

static inline void fz_error_init(facet_error *e)
{
    memset(e, 0, sizeof *e);
    e->status = FACET_OK;
}

/* Zeroed buffers of n elements, never NULL (n may be 0). */
static inline void *fz_calloc(size_t n, size_t size)
{
    void *p = calloc(n ? n : 1, size);
    if (p == NULL) abort();
    return p;
}

#endif
