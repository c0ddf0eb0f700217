#!/bin/sh
# Every scene checks its options through the option table the same way: an
# unknown option, a value that is not a number and an option without its value
# each stop the scene with exit 2, a line naming the option, and nothing
# written. (ballistic_impact and strip_tension: bad_input.sh; the explorer and
# the fit scene: their own tests; here the sensitivity and explicit_loop scenes.)
set -u
tmp="${WFF_TEST_TMP:-/tmp}/scene_options"
rm -rf "$tmp"
mkdir -p "$tmp"
fail=0
# expect SCENE PATTERN ARGS...
expect() {
    scene=$1; pattern=$2; shift 2
    out="$tmp/run"
    sh tools/ff.sh "freefem_scripts/$scene.edp" -out "$out" "$@" > "$tmp/log" 2>&1
    rc=$?
    [ $rc -eq 2 ] || { echo "$scene $*: exit $rc, want 2"; fail=1; }
    grep -qF -- "$pattern" "$tmp/log" || { echo "$scene $*: no '$pattern':"; head -3 "$tmp/log"; fail=1; }
    [ -e "$out" ] && { echo "$scene $*: wrote $out"; rm -rf "$out"; fail=1; }
    grep -m1 '^error' "$tmp/log" | cut -c1-140
}
expect sensitivity "error: sensitivity: unknown option '-bogus'" -bogus 1
expect sensitivity "error: sensitivity: -jobs 'abc' is not a number" -jobs abc
expect sensitivity "error: sensitivity: option -jobs needs a value" -plots 0 -jobs
expect explicit_loop "error: explicit_loop: unknown option '-bogus'" -bogus 1
expect explicit_loop "error: explicit_loop: -tend 'abc' is not a number" -tend abc
expect explicit_loop "error: explicit_loop: option -tend needs a value" -plots 0 -tend
exit $fail
