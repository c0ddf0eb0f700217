#!/bin/sh
# The module's errors reach the script user: tests/edp_fail/bad_material.edp
# must stop with exit code 8 (ExecError) and a message naming the key and the
# file, for a non-numeric value, a missing key, an unknown key and a missing
# file; and for an F or dA of the wrong size and a degenerate point. The same
# script with good input exits 0 (so the failures come from what is varied).
# Run from the repository root (tests/run.sh does).
set -u
tmp="${WFF_TEST_TMP:-}"
if [ -z "$tmp" ]; then tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT; fi
dir="$tmp/material_error_message"
mkdir -p "$dir"
good=freefem_scripts/materials/kevlar_s706.txt
script=tests/edp_fail/bad_material.edp
fail=0

# expect NAME STATUS PATTERN... -- ARGS: run the script with ARGS, want exit
# STATUS and every PATTERN (fixed string) in its output
expect() {
    name=$1; want=$2; shift 2
    patterns=""
    while [ "$1" != "--" ]; do patterns="$patterns$1
"; shift; done
    shift
    sh tools/ff.sh "$script" "$@" > "$dir/$name.log" 2>&1
    rc=$?
    ok=1
    [ "$rc" -eq "$want" ] || { echo "$name: exit $rc, want $want"; ok=0; }
    printf '%s' "$patterns" | while IFS= read -r p; do
        grep -qF -- "$p" "$dir/$name.log" || { echo "$name: output lacks '$p'"; exit 1; }
    done || ok=0
    if [ $ok -eq 0 ]; then sed 's/^/    /' "$dir/$name.log"; fail=1; fi
}

sed 's/^k_1 .*/k_1 = abc/' "$good" > "$dir/not_a_number.txt"
grep -v '^K_I ' "$good" > "$dir/missing_key.txt"
{ cat "$good"; echo "k_3 = 1.0e7   # no such key"; } > "$dir/unknown_key.txt"

expect good 0 "wovenffPoint succeeded" -- -material "$good"
expect not_a_number 8 "wovenffPoint:" "$dir/not_a_number.txt" "k_1" "'abc' is not a number" \
    -- -material "$dir/not_a_number.txt"
expect missing_key 8 "$dir/missing_key.txt" "missing key 'K_I'" -- -material "$dir/missing_key.txt"
expect unknown_key 8 "$dir/unknown_key.txt" "unknown key 'k_3'" -- -material "$dir/unknown_key.txt"
expect no_file 8 "$dir/no_such_file.txt" "cannot open material file" \
    -- -material "$dir/no_such_file.txt"
expect F_size 8 "F must have 6 entries" "got 5" -- -sizeF 5
expect dA_size 8 "dA must have 2 entries" "got 3" -- -sizedA 3
expect degenerate 8 "degenerate point" -- -scaleF 0
# the line number of the bad value is named too
line=$(grep -n '^k_1 ' "$dir/not_a_number.txt" | cut -d: -f1)
grep -qF "not_a_number.txt:$line:" "$dir/not_a_number.log" || {
    echo "not_a_number: output lacks the line number $line"; fail=1; }
exit $fail
