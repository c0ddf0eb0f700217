#!/bin/sh
# docs/csv_columns.md's table of every CSV column is what tools/csv_columns.sh
# prints now (the scenes' headers, the cells' own names and units): a column
# added, renamed or left without a unit fails here (the tool names it).
set -u
cd "$(dirname "$0")/../.." || exit 1
doc=docs/csv_columns.md
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
sh tools/csv_columns.sh > "$tmp/now.md" || { echo "tools/csv_columns.sh failed"; exit 1; }
sed -n '/^<!-- columns begin/,/^<!-- columns end -->$/p' "$doc" | sed '1d;$d' > "$tmp/doc.md"
[ -s "$tmp/doc.md" ] || { echo "$doc has no table between its markers"; exit 1; }
if ! cmp -s "$tmp/now.md" "$tmp/doc.md"; then
    echo "$doc differs from what tools/csv_columns.sh prints now (regenerate it: docs/csv_columns.md says how):"
    diff "$tmp/doc.md" "$tmp/now.md" | head -20
    exit 1
fi
# the explorer's columns a newcomer asked about are there, with units
for col in dA1_static dA2_static K_amp time gamma E_yarn_stretch; do
    grep -q "^| unit_cell_explorer (king_plain) | .* | \`$col\` | [^|]*[^ |][^|]* |" "$doc" \
        || { echo "$doc: the explorer's column $col is missing or has no unit"; exit 1; }
done
echo "$(grep "^| [a-z]" "$tmp/now.md" | grep -vc "^| scene |") columns (scene by scene) in $doc, as the tool prints them now"
