#!/bin/sh
# What a user sees on a terminal (tools/ff.sh, so make run too): -help and a
# refused option end with the scene's own lines, without FreeFEM's trailer
# ("current line = N", " call F  at  line N", "exit(N)", " err code N ..."),
# and keep their exit codes (0, 2); an uncaught module error (exit 8) keeps the
# trailer (it says where). Into a file the output is FreeFEM's own, trailer
# included, with the same exit code. The terminal is a pseudo-terminal from
# script(1).
set -u
command -v script > /dev/null || { echo "script(1) missing (util-linux): cannot open a terminal"; exit 1; }
tmp="${WFF_TEST_TMP:-/tmp}/terminal_output"
rm -rf "$tmp"; mkdir -p "$tmp"
scene=freefem_scripts/ballistic_impact.edp
fail=0
trailer='current line = \|^ call .* at  line \|^exit([0-9]*)\|err code [0-9]'
# on_terminal NAME WANT-EXIT WANT-TRAILER(0|1) PATTERN ARGS...: run on a pseudo-terminal
on_terminal() {
    name=$1; want=$2; keep=$3; pattern=$4; shift 4
    script -qc "sh tools/ff.sh $* ; echo \"rc=\$?\"" /dev/null < /dev/null | tr -d '\r' > "$tmp/$name.log"
    rc=$(sed -n 's/^rc=//p' "$tmp/$name.log")
    [ "$rc" = "$want" ] || { echo "$name: exit $rc on a terminal, want $want"; fail=1; }
    grep -q -- "$pattern" "$tmp/$name.log" || { echo "$name: no '$pattern' on the terminal"; fail=1; }
    if [ "$keep" = 1 ]; then
        grep -q "$trailer" "$tmp/$name.log" || { echo "$name: the trailer is gone (an uncaught error keeps it)"; fail=1; }
    else
        grep "$trailer" "$tmp/$name.log" && { echo "$name: FreeFEM's trailer on the terminal"; fail=1; }
    fi
    echo "$name: exit $rc on a terminal, trailer $( [ "$keep" = 1 ] && echo kept || echo gone)"
}
on_terminal help 0 0 "-maxoutput" "$scene" -help
on_terminal bad_option 2 0 "^error: ballistic_impact: -velocity 'abc' is not a number" "$scene" -velocity abc
printf 'load "wovenff"\nreal x = wovenffGet(12345, "time");\n' > "$tmp/bug.edp"
on_terminal uncaught 8 1 "is not a live wovenff model handle" "$tmp/bug.edp"
# into a file: FreeFEM's own output, the trailer there, the same exit code
sh tools/ff.sh "$scene" -velocity abc > "$tmp/file.log" 2>&1
rc=$?
[ "$rc" -eq 2 ] || { echo "into a file: exit $rc, want 2"; fail=1; }
grep -q "err code 2" "$tmp/file.log" || { echo "into a file: FreeFEM's trailer missing"; fail=1; }
echo "into a file: exit $rc, FreeFEM's output as it is"
exit $fail
