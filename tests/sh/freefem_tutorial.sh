#!/bin/sh
# The FreeFEM tutorial (docs/freefem_tutorial.md) runs as written: each
# numbered section ("## N. ...") is one script made of its ```freefem blocks in
# order (the doc says so); each is run with tools/ff.sh from the repository
# root and must exit 0 (its asserts: the physics it shows). The doc's output
# folder results/tutorial is replaced by the test folder. The tutorial must
# have its four sections, each with code; every function the issue names for
# the tutorial must appear in it.
# Run from the repository root (tests/run.sh does).
set -u
doc=docs/freefem_tutorial.md
out="${WFF_TEST_TMP:-/tmp}/freefem_tutorial"
rm -rf "$out"
mkdir -p "$out"
[ -f "$doc" ] || { echo "missing $doc"; exit 1; }

# split: section k's code into $out/section_k.edp, its title into $out/section_k.title
awk -v dir="$out" '
    /^## [0-9]+\./ { k++; title = $0; sub(/^## /, "", title); print title > (dir "/section_" k ".title"); next }
    /^```freefem[ \t]*$/ { if (k == 0) { print "code before the first section" > "/dev/stderr"; exit 1 }
                           code = 1; blocks[k]++; next }
    /^```[ \t]*$/ { if (code) { code = 0; print "" >> (dir "/section_" k ".edp") }; next }
    code { gsub(/results\/tutorial/, dir); print >> (dir "/section_" k ".edp") }
    END { if (code) { print "unterminated code block" > "/dev/stderr"; exit 1 }
          for (i = 1; i <= k; i++) if (!blocks[i]) { print "section " i " has no freefem block" > "/dev/stderr"; exit 1 } }
' "$doc" || exit 1

fail=0
n=$(ls "$out"/section_*.title 2>/dev/null | wc -l)
[ "$n" -ge 4 ] || { echo "$doc: $n numbered sections, want 4 (points, struck ply, own loop, adapted mesh)"; fail=1; }

for name in wovenffMaterial wovenffPoints 'wovenffModel(Th' wovenffFix wovenffGetVector \
            wovenffSetVector wovenffElementField wovenffForces wovenffMass wovenffStableStep \
            wovenffProjectile wovenffImpactPoint wovenffProjectileShape wovenffRemesh square \
            adaptmesh; do
    grep -q "$name" "$out"/section_*.edp || { echo "$doc: no code uses $name"; fail=1; }
done

k=1
while [ -f "$out/section_$k.edp" ]; do
    title=$(cat "$out/section_$k.title")
    start=$(date +%s.%N)
    if sh tools/ff.sh "$out/section_$k.edp" > "$out/section_$k.log" 2>&1; then
        secs=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
        echo "ok   section $title (${secs} s)"
    else
        rc=$?
        echo "FAIL section $title: exit $rc; its script is $out/section_$k.edp, output:"
        tail -20 "$out/section_$k.log" | sed 's/^/    /'
        fail=1
    fi
    k=$((k + 1))
done
exit $fail
