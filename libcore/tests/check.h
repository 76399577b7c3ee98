/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Minimal assertion helpers for libfacet's tests: each failed check prints
 * where and why, and the test's exit status counts failures. */
#ifndef FACET_CHECK_H
#define FACET_CHECK_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static int check_failures = 0;
static int check_count = 0;

/* Whether every one of the n doubles at x is finite. */
static inline int all_finite(const double *x, size_t n)
{
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(x[i]))
            return 0;
    return 1;
}

#define CHECK(cond)                                                              \
    do {                                                                         \
        ++check_count;                                                           \
        if (!(cond)) {                                                           \
            ++check_failures;                                                    \
            fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
        }                                                                        \
    } while (0)

#define CHECK_NEAR(a, b, tol)                                                        \
    do {                                                                             \
        ++check_count;                                                               \
        double check_a_ = (a), check_b_ = (b);                                       \
        if (!(fabs(check_a_ - check_b_) <= (tol))) {                                 \
            ++check_failures;                                                        \
            fprintf(stderr, "%s:%d: %s = %.17g, %s = %.17g, differ by more than %g\n", \
                    __FILE__, __LINE__, #a, check_a_, #b, check_b_, (double)(tol));  \
        }                                                                            \
    } while (0)

#define CHECK_STATUS(expr, expected)                                                     \
    do {                                                                                 \
        ++check_count;                                                                   \
        int check_s_ = (int)(expr);                                                      \
        if (check_s_ != (int)(expected)) {                                               \
            ++check_failures;                                                            \
            fprintf(stderr, "%s:%d: %s returned %d, expected %s (%d)\n", __FILE__, __LINE__, \
                    #expr, check_s_, #expected, (int)(expected));                        \
        }                                                                                \
    } while (0)

static inline int check_report(const char *name)
{
    printf("%s: %d checks, %d failed\n", name, check_count, check_failures);
    return check_failures ? EXIT_FAILURE : EXIT_SUCCESS;
}

#endif
