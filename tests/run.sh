#!/bin/sh
# wovenff test runner: every C test binary, every .edp test and every shell
# test counts as one test; it passes when it exits 0. Each test's output goes to
# a log of its own, shown (its last 40 lines) when it fails. A line per test as
# it ends (PASS/FAIL, name, wall seconds); the last line is "N passed, N failed".
# Run from the repository root (make test does).
#
# Tests at a time: WFF_TEST_JOBS (default: the cores this process may use).
# Nearly every test is one single-threaded process at a time (a coarse scene takes a
# team of threads only from 16384 triangles: docs/limits.md "Threads"), so on a
# 2-core machine two tests at once take about half the wall time. Each test keeps
# its files in a folder of its own under $WFF_TEST_TMP. A shell test whose header
# holds the line "# test-runner: alone (why)" runs with no other test beside it
# (its own MPI ranks want the cores); these run first. A shell test with
# "# test-runner: first (~N s: why)" is started before the others, the longest (N)
# first (a long test started last would leave the other cores idle at the end).
# WFF_TEST_JOBS=1: one test at a time, in the order of the listing.
# Arguments: only the tests whose names (as printed: c/test_cells, sh/restart.sh, ...)
# match one of them (shell patterns: 'sh/*scene*'); none: every test.
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root" || exit 1
jobs=${WFF_TEST_JOBS:-$(nproc 2>/dev/null || echo 1)}
case "$jobs" in ''|*[!0-9]*|0) echo "tests/run.sh: WFF_TEST_JOBS '$jobs' is not a count >= 1"; exit 2 ;; esac
state=$(mktemp -d) || exit 1
WFF_TEST_TMP=$(mktemp -d) || exit 1; export WFF_TEST_TMP
workers=""
# (a worker's tests ignore Ctrl-C, as every command sh starts with &: an interrupted run
# ends each worker and what it started, by process id, children first)
kill_tree() {
    for child in $(ps -o pid= --ppid "$1" 2>/dev/null); do kill_tree "$child"; done
    kill "$1" 2>/dev/null
}
cleanup() {
    for w in $workers; do kill_tree "$w"; done
    rm -rf "$state" "$WFF_TEST_TMP"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# the tests, one a line: NAME<tab>COMMAND (words split at blanks)
tab=$(printf '\t')
marked() { grep -q "^# test-runner: $1" "$2"; }
chosen() { # NAME PATTERN...: one of the patterns matches NAME (no pattern: every NAME does)
    name=$1; shift
    [ $# -eq 0 ] && return 0
    for p in "$@"; do
        # shellcheck disable=SC2254 # (a pattern)
        case "$name" in $p) return 0 ;; esac
    done
    return 1
}
{
    for t in tests/sh/*.sh; do
        [ -f "$t" ] && marked alone "$t" && printf 'sh/%s\tsh %s\n' "$(basename "$t")" "$t"
    done
} > "$state/alone"
{
    for t in tests/sh/*.sh; do   # (the longest first: "first (~N s" in the line)
        [ -f "$t" ] && ! marked alone "$t" && marked first "$t" &&
            printf '%s\tsh/%s\tsh %s\n' "$(sed -n 's/^# test-runner: first (~\([0-9]*\) s.*/\1/p' "$t")" \
                "$(basename "$t")" "$t"
    done | sort -t "$tab" -k1,1rn | cut -f2-
    for t in tests/sh/*.sh; do
        [ -f "$t" ] && ! marked alone "$t" && ! marked first "$t" && printf 'sh/%s\tsh %s\n' "$(basename "$t")" "$t"
    done
    for t in build/tests/test_*; do
        [ -f "$t" ] && [ -x "$t" ] && printf 'c/%s\t%s\n' "$(basename "$t")" "$t"
    done
    for t in tests/edp/*.edp; do
        [ -f "$t" ] && printf 'edp/%s\tsh tools/ff.sh %s\n' "$(basename "$t")" "$t"
    done
} > "$state/pool"
for list in alone pool; do   # the arguments' tests only
    while IFS= read -r line; do
        chosen "${line%%"$tab"*}" "$@" && printf '%s\n' "$line"
    done < "$state/$list" > "$state/chosen"
    mv "$state/chosen" "$state/$list"
done
if [ "$jobs" -eq 1 ]; then   # the listing's order: C tests, .edp tests, shell tests
    grep -h "^c/" "$state/pool" > "$state/serial"
    grep -h "^edp/" "$state/pool" >> "$state/serial"
    grep -v -h -e "^c/" -e "^edp/" "$state/pool" "$state/alone" | sort -t "$tab" -k1,1 >> "$state/serial"
    : > "$state/alone"; mv "$state/serial" "$state/pool"
fi

# run_one LIST N: the test on line N of LIST; its verdict to $state/results, its line
# (and a failure's output) printed at once, one test's report at a time
run_one() {
    line=$(sed -n "$2p" "$1")
    name=${line%%"$tab"*} cmd=${line#*"$tab"}
    log="$state/log.${1##*/}.$2"
    start=$(date +%s.%N)
    # shellcheck disable=SC2086 # (cmd: the words of the command)
    if $cmd > "$log" 2>&1 < /dev/null; then status=PASS; else status=FAIL; fi
    secs=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
    until mkdir "$state/print.lock" 2>/dev/null; do sleep 0.05; done
    printf '%s %-40s %6ss\n' "$status" "$name" "$secs"
    if [ "$status" = FAIL ]; then sed 's/^/    | /' "$log" | tail -40; fi
    printf '%s %s\n' "$status" "$name" >> "$state/results"
    rmdir "$state/print.lock"
}
# worker LIST: takes the next test of LIST no other worker has taken (mkdir is atomic)
worker() {
    n=$(wc -l < "$1") i=0
    while [ "$i" -lt "$n" ]; do
        i=$((i + 1))
        mkdir "$state/taken.${1##*/}.$i" 2>/dev/null && run_one "$1" "$i"
    done
    return 0
}
: > "$state/results"
worker "$state/alone"
k=0
while [ "$k" -lt "$jobs" ]; do
    k=$((k + 1))
    worker "$state/pool" &
    workers="$workers $!"
done
wait
workers=""
passed=$(grep -c '^PASS ' "$state/results")
failed=$(grep -c '^FAIL ' "$state/results")
failed_names=$(sed -n 's/^FAIL / /p' "$state/results" | tr -d '\n')
[ -n "$failed_names" ] && echo "failed:$failed_names"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
