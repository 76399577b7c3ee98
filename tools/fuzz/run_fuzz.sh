#!/bin/sh
# SPDX-License-Identifier: LGPL-2.1-or-later
# Run every libFuzzer target of Facet for a set time (make fuzz).
#
#   sh tools/fuzz/run_fuzz.sh BUILD_DIR SECONDS_PER_TARGET [TARGET...]
#
# BUILD_DIR holds the clang build (cmake -DFACET_FUZZ=ON, see the Makefile's
# fuzz-build). Targets: mesh planarize lift panel cleanup surface python
# (default: all). Each runs SECONDS_PER_TARGET seconds from its working corpus
# BUILD_DIR/corpus/<target> (kept between runs), seeded from
# libcore/fuzz/corpus/<target> and libcore/fuzz/regressions/<target>.
# A finding (crash, sanitizer report, broken oracle, timeout, out of memory)
# is written to BUILD_DIR/findings/<target>-*; the run goes on with the next
# target and the script exits 1 at the end when there was any.
# Summary (executions, exec/s, findings) in BUILD_DIR/fuzz-summary.txt.
set -u
build=${1:?build dir}
seconds=${2:?seconds per target}
shift 2
targets=${*:-mesh planarize lift panel cleanup surface python}
root=$(cd "$(dirname "$0")/../.." && pwd)
findings=$build/findings
summary=$build/fuzz-summary.txt
mkdir -p "$findings" "$build/logs"
: > "$summary"
found=0
for t in $targets; do
    bin=$build/fuzz/fuzz_$t
    if [ ! -x "$bin" ]; then
        echo "run_fuzz: no $bin (build it with make fuzz-build)" >&2
        exit 2
    fi
    corpus=$build/corpus/$t
    mkdir -p "$corpus"
    seeds=""
    for d in "$root/libcore/fuzz/corpus/$t" "$root/libcore/fuzz/regressions/$t"; do
        [ -d "$d" ] && seeds="$seeds $d"
    done
    dict=""
    [ -f "$root/libcore/fuzz/$t.dict" ] && dict="-dict=$root/libcore/fuzz/$t.dict"
    before=$(ls "$findings" | grep -c "^$t-" || true)
    log=$build/logs/$t.log
    echo "run_fuzz: $t for ${seconds}s (log $log)"
    # Python keeps its interpreter's memory at exit: no leak report there.
    leaks=1
    [ "$t" = python ] && leaks=0
    # A finding stops libFuzzer: start it again (from the grown corpus) until
    # the target's time is used, at most 20 times.
    end=$(($(date +%s) + seconds))
    : > "$log"
    rc=0
    restarts=0
    while left=$((end - $(date +%s))); [ "$left" -gt 0 ] && [ "$restarts" -lt 20 ]; do
        # shellcheck disable=SC2086
        ASAN_OPTIONS="detect_leaks=$leaks:abort_on_error=1:symbolize=1" \
        UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
        OMP_NUM_THREADS=2 \
            "$bin" -max_total_time="$left" -timeout=60 -rss_limit_mb=2560 -max_len=40000 \
            -print_final_stats=1 -artifact_prefix="$findings/$t-" $dict "$corpus" $seeds >> "$log" 2>&1
        r=$?
        [ "$r" -ne 0 ] && rc=$r
        restarts=$((restarts + 1))
    done
    after=$(ls "$findings" | grep -c "^$t-" || true)
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | awk '{s += $1} END {print s + 0}')
    cov=$(grep -o 'cov: [0-9]* ft: [0-9]*' "$log" | tail -n 1)
    line="$t: rc=$rc runs=$runs seconds=$seconds exec/s=$((runs / seconds)) starts=$restarts ${cov:-} findings=$((after - before))"
    echo "run_fuzz: $line"
    echo "$line" >> "$summary"
    if [ "$rc" -ne 0 ] || [ "$after" -gt "$before" ]; then
        found=1
        grep -E "FUZZ ORACLE|ERROR:|runtime error|Error|Traceback|FINDING" "$log" | head -n 12 >&2
    fi
done
if [ "$found" -ne 0 ]; then
    echo "run_fuzz: FINDINGS in $findings (replay one: $build/fuzz/fuzz_<target> FILE)" >&2
    exit 1
fi
echo "run_fuzz: no finding"
