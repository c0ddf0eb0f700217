#!/bin/sh
# wovenff test runner: every C test binary, every .edp test and every shell
# test counts as one test; it passes when it exits 0. Output of a failing test
# is shown. The last line is "N passed, N failed".
# Run from the repository root (make test does).
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root" || exit 1
passed=0; failed=0; failed_names=""
log=$(mktemp); trap 'rm -f "$log"' EXIT
WFF_TEST_TMP=$(mktemp -d); export WFF_TEST_TMP
run_one() { # name, command...
    name=$1; shift
    start=$(date +%s.%N)
    if "$@" >"$log" 2>&1; then
        passed=$((passed + 1)); status=PASS
    else
        failed=$((failed + 1)); status=FAIL; failed_names="$failed_names $name"
    fi
    secs=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
    printf '%s %-40s %6ss\n' "$status" "$name" "$secs"
    if [ "$status" = FAIL ]; then sed 's/^/    | /' "$log" | tail -40; fi
}
for t in build/tests/test_*; do
    [ -x "$t" ] && run_one "c/$(basename "$t")" "$t"
done
for t in tests/edp/*.edp; do
    [ -f "$t" ] && run_one "edp/$(basename "$t")" sh tools/ff.sh "$t"
done
for t in tests/sh/*.sh; do
    [ -f "$t" ] && run_one "sh/$(basename "$t")" sh "$t"
done
rm -rf "$WFF_TEST_TMP"
[ -n "$failed_names" ] && echo "failed:$failed_names"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
