/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* The cost of a parallel region (fork and join) against a barrier inside one
 * region, on 2 threads, with almost no work: what "one parallel region per
 * iteration, the passes separated by omp barrier" could save per pass
 * (docs/benchmarks.md, "1M faces: scheduling (branch dyn8)").
 *
 *   gcc -O2 -fopenmp tools/bench/omp_forkjoin.c -o /tmp/omp_forkjoin && /tmp/omp_forkjoin */
#include <omp.h>
#include <stdio.h>
int main(void)
{
    enum { N = 20000 };
    static volatile double sink[2];
    double t0 = omp_get_wtime();
    for (int i = 0; i < N; ++i) {
#pragma omp parallel for schedule(static) num_threads(2)
        for (int k = 0; k < 2; ++k)
            sink[k] += 1.0;
    }
    double t1 = omp_get_wtime();
#pragma omp parallel num_threads(2)
    for (int i = 0; i < N; ++i) {
#pragma omp for schedule(static)
        for (int k = 0; k < 2; ++k)
            sink[k] += 1.0;
    }
    double t2 = omp_get_wtime();
    printf("parallel for (fork+join): %.2f us; omp for in one region (barrier): %.2f us\n",
           (t1 - t0) / N * 1e6, (t2 - t1) / N * 1e6);
    return 0;
}
