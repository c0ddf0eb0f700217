#!/bin/sh
# The ply contact's solve under valgrind's memcheck: the clamped 8-ply impact of
# test_ply_contact (4) to 0.03 ms, ~300 steps through every part of the column
# solve (a column's normal LCP, its pairs' friction, the nose contacts), reads no
# uninitialised memory. The column friction's first version did (a pair with no
# normal impulse read from the stack: garbage friction impulses, 0.29 J put in on
# 40 plies, docs/model.md §23), which no check of the numbers caught: the stack
# held zeros in the tests. One thread (libgomp's team start is not memcheck's
# business). Skipped, and said, where valgrind is not installed.
# test-runner: first (~21 s: one of the longest tests; tests/run.sh starts the longest first)
set -u
command -v valgrind > /dev/null 2>&1 || { echo "memcheck_ply_contact: no valgrind on this machine: skipped"; exit 0; }
log="${WFF_TEST_TMP:-/tmp}/memcheck_ply_contact.log"
OMP_NUM_THREADS=1 valgrind --error-exitcode=3 --track-origins=yes build/tests/test_ply_contact memcheck > "$log" 2>&1
rc=$?
grep -E '8 plies|ERROR SUMMARY|checks' "$log" | cut -c1-200
if [ $rc -ne 0 ]; then
    echo "memcheck_ply_contact: exit $rc (3: memcheck found errors)"
    grep -m1 -A8 -E 'uninitialised|Invalid' "$log"
    exit 1
fi
exit 0
