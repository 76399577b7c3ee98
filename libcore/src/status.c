/* SPDX-License-Identifier: LGPL-2.1-or-later */
#include "internal.h"

#include <stdio.h>
#include <string.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

const char *facet_status_string(facet_status status)
{
    switch (status) {
#define FACET_STATUS_CASE(name, value, text) \
    case name:                                \
        return text;
        FACET_STATUS_LIST(FACET_STATUS_CASE)
#undef FACET_STATUS_CASE
    }
    return "unknown status";
}

const char *facet_version(void)
{
#define FACET_STR2(x) #x
#define FACET_STR(x) FACET_STR2(x)
    return FACET_STR(FACET_VERSION_MAJOR) "." FACET_STR(FACET_VERSION_MINOR) "." FACET_STR(
        FACET_VERSION_PATCH);
}

facet_status facet_fail(facet_error *error, facet_status status, int64_t face, int64_t vertex,
                        const char *format, ...)
{
    if (error) {
        va_list args;
        error->status = status;
        error->face = face;
        error->vertex = vertex;
        va_start(args, format);
        vsnprintf(error->message, sizeof error->message, format, args);
        va_end(args);
    }
    return status;
}

void facet_error_clear(facet_error *error)
{
    if (error) {
        error->status = FACET_OK;
        error->face = -1;
        error->vertex = -1;
        error->message[0] = '\0';
    }
}

int facet_thread_count(int requested)
{
#ifdef _OPENMP
    if (requested <= 0)
        return omp_get_max_threads();
    /* A request far beyond the machine (threads = 1000000) would make libgomp
     * abort when thread creation fails: clamp it. Results do not depend on
     * the thread count, so this changes only the time. */
    int limit = 4 * omp_get_num_procs();
    if (limit < 64)
        limit = 64;
    if (limit < omp_get_max_threads())
        limit = omp_get_max_threads();
    if (limit > omp_get_thread_limit())
        limit = omp_get_thread_limit();
    return requested < limit ? requested : limit;
#else
    (void)requested;
    return 1;
#endif
}

double facet_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
