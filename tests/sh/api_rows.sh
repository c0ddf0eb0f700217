#!/bin/sh
# Every wovenff* function the FreeFEM binding registers (the Global.Add calls of
# plugin/ff/*.cpp) has exactly one row in docs/freefem_api.md: a table row whose
# first cell names it followed by "(" (overloads share their row, a row may name
# several functions); and every function such a row names is registered (no row
# for a function that is gone).
set -u
cd "$(dirname "$0")/../.." || exit 1
doc=docs/freefem_api.md
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
grep -ho 'Global\.Add("wovenff[A-Za-z0-9_]*"' plugin/ff/*.cpp | sed 's/^Global\.Add("//; s/"$//' |
    LC_ALL=C sort -u > "$tmp/registered"
# the first cell of every table row (a "\|" inside a cell is not a separator)
awk '/^\|/ { line = $0; gsub(/\\\|/, "", line); n = split(line, cell, "|"); if (n >= 3) print cell[2] }' "$doc" |
    grep -v '^ *-*$' > "$tmp/cells"
# each cell's functions, once per cell
: > "$tmp/named"
while IFS= read -r cell; do
    printf '%s\n' "$cell" | grep -o 'wovenff[A-Za-z0-9_]*(' | sed 's/($//' | LC_ALL=C sort -u >> "$tmp/named"
done < "$tmp/cells"
fail=0
n=0
while read -r f; do
    n=$((n + 1))
    rows=$(grep -cx "$f" "$tmp/named")
    [ "$rows" -eq 1 ] || { echo "$f: $rows rows in $doc, want 1"; fail=1; }
done < "$tmp/registered"
LC_ALL=C sort -u "$tmp/named" | while read -r f; do
    grep -qx "$f" "$tmp/registered" || { echo "$f: a row in $doc, but the binding registers no such function"; exit 1; }
done || fail=1
[ "$n" -gt 50 ] || { echo "only $n functions found registered: the grep of plugin/ff/*.cpp is broken"; fail=1; }
[ $fail -eq 0 ] && echo "$n functions registered, each with exactly one row in $doc"
exit $fail
