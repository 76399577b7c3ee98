#!/bin/sh
# SPDX-License-Identifier: LGPL-2.1-or-later
# Runs every C test executable in DIR under valgrind memcheck, first with the
# OpenMP default thread count and then with 1 thread. Fails on any memcheck
# error or definite leak ("possibly lost" blocks are libgomp's thread pool,
# alive until exit, and are not errors). Usage: check-memory.sh DIR
set -u
dir=${1:?usage: check-memory.sh build/libcore/tests}
here=$(cd "$(dirname "$0")" && pwd)
command -v valgrind >/dev/null || { echo "check-memory: valgrind is not installed" >&2; exit 2; }
# passive: spinning OpenMP workers make valgrind's serialised threads crawl
export OMP_WAIT_POLICY=passive
failed=0
count=0
for t in "$dir"/test_*; do
    [ -f "$t" ] && [ -x "$t" ] || continue
    for threads in default 1; do
        count=$((count + 1))
        if [ "$threads" = 1 ]; then export OMP_NUM_THREADS=1; else unset OMP_NUM_THREADS; fi
        log=$(mktemp)
        if valgrind --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite \
                --show-leak-kinds=definite --track-origins=yes --quiet \
                --suppressions="$here/valgrind.supp" "$t" >"$log" 2>&1; then
            echo "ok    $(basename "$t") ($threads threads)"
        else
            echo "FAIL  $(basename "$t") ($threads threads)"
            cat "$log"
            failed=$((failed + 1))
        fi
        rm -f "$log"
    done
done
echo "check-memory: $count runs, $failed failed"
[ "$failed" -eq 0 ]
