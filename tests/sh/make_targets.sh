#!/bin/sh
# What the README's two commands do on a fresh machine (make -n -B: every
# command make would run, none run): `make run` checks the Debian packages
# first (make deps: installs the missing ones), then builds the FreeFEM module
# and nothing else (no C test binary: the scene starts after the module's
# build), then starts the scene; `make test` checks the packages first too and
# builds everything, the C tests included, before it runs them.
set -u
cd "$(dirname "$0")/../.." || exit 1
fail=0
run=$(make -n -B run 2>&1) || { echo "make -n -B run failed:"; printf '%s\n' "$run" | tail -5; exit 1; }
line_of() { printf '%s\n' "$1" | grep -n -m1 -- "$2" | cut -d: -f1; }
deps=$(line_of "$run" "dpkg-query"); module=$(line_of "$run" "\-o build/wovenff.so"); scene=$(line_of "$run" "sh tools/ff.sh freefem_scripts/ballistic_impact.edp")
[ -n "$deps" ] && [ -n "$module" ] && [ -n "$scene" ] && [ "$deps" -lt "$module" ] && [ "$module" -lt "$scene" ] \
    || { echo "make run: want the package check (line $deps), then the module's link (line $module), then the scene (line $scene)"; fail=1; }
tests=$(printf '%s\n' "$run" | grep -c "build/tests/")
[ "$tests" -eq 0 ] || { echo "make run builds $tests test files"; printf '%s\n' "$run" | grep -m3 "build/tests/"; fail=1; }
compiles=$(printf '%s\n' "$run" | grep -c -- " -c ")
test_out=$(make -n -B test 2>&1) || { echo "make -n -B test failed"; exit 1; }
deps=$(line_of "$test_out" "dpkg-query"); first_test=$(line_of "$test_out" "build/tests/test_"); runner=$(line_of "$test_out" "sh tests/run.sh")
[ -n "$deps" ] && [ -n "$first_test" ] && [ -n "$runner" ] && [ "$deps" -lt "$first_test" ] && [ "$first_test" -lt "$runner" ] \
    || { echo "make test: want the package check (line $deps), the C tests built (line $first_test), then the runner (line $runner)"; fail=1; }
binaries=$(printf '%s\n' "$test_out" | grep -c -- "-o build/tests/test_")
expected=$(ls tests/c/test_*.c | wc -l)
[ "$binaries" -eq "$expected" ] || { echo "make test links $binaries test binaries, want $expected"; fail=1; }
[ $fail -eq 0 ] && echo "make run: packages checked, $compiles compilations for the module, no test binary, then the scene; make test: packages checked, $binaries test binaries built, then the runner"
exit $fail
