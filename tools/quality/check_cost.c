/* The quality check's instructions against the whole solve: build after `make build` with
 *   gcc -O2 -g -std=c11 -D_DEFAULT_SOURCE -Ilibcore/include tools/quality/check_cost.c \
 *       build/libcore/libfacet.a -o build/check_cost -fopenmp -lcholmod -lm
 * and run `OMP_NUM_THREADS=1 valgrind --tool=callgrind build/check_cost 60` (n x n test grid, L/L;
 * a second argument starting with g: L/G); callgrind_annotate shows facet_pl_new_narrow. */
#include "../../libcore/tests/test_meshes.h" /* from tools/quality */
#include <stdio.h>
#include <stdlib.h>
int main(int argc, char **argv)
{
    const int n = argc > 1 ? atoi(argv[1]) : 60;
    facet_error e;
    test_mesh t = test_grid(n, n, 0.6, 1.0, 0.0);
    facet_planarizer *p = NULL;
    facet_planarizer_create(&t.mesh, &p, &e);
    double *out = malloc(sizeof(double) * 3 * (size_t)t.mesh.n_vertices);
    facet_planarize_options o;
    facet_planarize_options_default(argc > 2 && argv[2][0] == 'g' ? FACET_METHOD_LOCAL_GLOBAL : FACET_METHOD_LOCAL_LOCAL, &o);
    o.threads = 1;
    facet_planarize_result r;
    int s = facet_planarizer_solve(p, t.xyz, &o, out, &r, &e);
    printf("n %d status %d it %d quality %d resolves %d\n", n, s, (int)r.iterations, (int)r.quality, (int)r.quality_resolves);
    return 0;
}
