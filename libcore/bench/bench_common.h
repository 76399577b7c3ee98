/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Helpers shared by the benchmark drivers: wall and process CPU clocks, the
 * peak resident set, and the median of a sample (sorted in place). */
#ifndef FACET_BENCH_COMMON_H
#define FACET_BENCH_COMMON_H

#include <stdlib.h>
#include <sys/resource.h>
#include <time.h>

/* The process's peak resident set so far, in KiB. */
static inline long peak_rss_kb(void)
{
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss;
}

static inline double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Process CPU time: on a machine shared with other work, CPU seconds on one
 * thread is the figure that does not depend on the load. */
static inline double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static inline int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median of v[0..n), which is left sorted. */
static inline double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, compare_double);
    return v[n / 2];
}

#endif
