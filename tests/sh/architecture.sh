#!/bin/sh
# docs/architecture.md against the tree and the build (issue "The house,
# second round", item 4).
#  (a) every plugin/**/*.{c,h,cpp,hpp} file is named in the doc's `layers`
#      block and has a row `| \`plugin/PATH\` |` in its file table (a name in
#      the doc with no file is ignored: a planned file);
#  (b) who may call whom: a file may include and call only files of its own
#      layer or lower ones. Includes are what the compiler's dependency files
#      say (build/plugin/**/*.d, build/kernel/VARIANT/plugin/**/*.d; the test
#      binaries' .d under build/tests/ are not plugin files); calls are the
#      undefined symbols of each object (nm) mapped to the object that
#      defines them (build/plugin/**/*.o, build/kernel/baseline/plugin/**/*.o;
#      a call of NAME__VARIANT is one of the kernel file defining NAME). A layer named on a `public-only:`
#      line may include no plugin/ header outside its layer and call only
#      functions declared in include/wovenff/*.h. `allow: FROM -> TO` lines
#      are exceptions.
# Prints each violation as "from (layer) -> to (layer): symbols" and exits 1
# on any. Needs a build (make test builds first): no .d file is a failure.
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root" || exit 1
doc=docs/architecture.md
[ -f "$doc" ] || { echo "architecture: $doc is missing"; exit 1; }
tmp=${WFF_ARCH_TMP:-$(mktemp -d)}; [ -n "${WFF_ARCH_TMP:-}" ] || trap 'rm -rf "$tmp"' EXIT; mkdir -p "$tmp"

# The layers block: "layer N NAME: file ...", "public-only: NAME", "allow: A -> B".
awk '/^```layers[ \t]*$/ { inb = 1; next } inb && /^```/ { inb = 0 } inb' "$doc" > "$tmp/block"
[ -s "$tmp/block" ] || { echo "architecture: no \`\`\`layers block in $doc"; exit 1; }
awk '$1 == "layer" { n = $2; name = $3; sub(/:$/, "", name)
                     for (i = 4; i <= NF; i++) print "plugin/" $i, n, name }' \
    "$tmp/block" > "$tmp/layers"

fail=0
# (a) every plugin file named.
find plugin -type f \( -name '*.c' -o -name '*.h' -o -name '*.cpp' -o -name '*.hpp' \) | sort \
    > "$tmp/files"
[ -s "$tmp/files" ] || { echo "architecture: no plugin files found"; exit 1; }
missing=$(awk -v doc="$doc" 'FNR == NR { named[$1] = 1; next }
    FILENAME == doc { if ($0 !~ /^\| `plugin\//) next
                      split($0, cell, "|"); c = cell[2]   # the first cell: one or more `plugin/X`
                      while (match(c, /`plugin\/[^`]*`/)) { row[substr(c, RSTART + 1, RLENGTH - 2)] = 1
                                                           c = substr(c, RSTART + RLENGTH) }
                      next }
    { if (!($1 in named)) print "not in the layers block of " doc ": " $1
      if (!($1 in row))   print "no row | `" $1 "` | (its job) in " doc }' \
    "$tmp/layers" "$doc" "$tmp/files")
if [ -n "$missing" ]; then printf '%s\n' "$missing"; fail=1; fi

# (b) the build's dependency files and objects.
find build/plugin build/kernel -name '*.d' 2>/dev/null | sort > "$tmp/dfiles"
if [ ! -s "$tmp/dfiles" ]; then
    echo "architecture: no dependency files build/**/*.d: build first (make; make test does)"
    exit 1
fi
# source of a build file: build/plugin/X.{d,o} or build/kernel/V/plugin/X.{d,o} -> plugin/X.c|.cpp
srcof='function srcof(p,   s) { s = p; sub(/^build\/kernel\/[^\/]*\//, "", s); sub(/^build\//, "", s)
                                 sub(/\.[do]$/, "", s); return s }'
# includes: one "from to #include" line per plugin header a source includes
while read -r d; do
    awk "$srcof"'
        { gsub(/\\/, " "); for (i = 1; i <= NF; i++) { t = $i; sub(/:$/, "", t)
              if (t ~ /^plugin\/.*\.(h|hpp)$/) hdr[t] = 1 } }
        END { s = srcof(FILENAME); for (h in hdr) print s, h, "#include" }' "$d"
done < "$tmp/dfiles" > "$tmp/inc.raw"
# .c or .cpp: whichever exists
awk 'FNR == NR { have[$1] = 1; next }
     { s = $1; if ((s ".c") in have) s = s ".c"; else if ((s ".cpp") in have) s = s ".cpp"
       if (s != $2) print s, $2, $3 }' "$tmp/files" "$tmp/inc.raw" | sort -u > "$tmp/edges"

# calls: nm's undefined symbols mapped to their defining object
objs=$(find build/plugin build/kernel/baseline/plugin -name '*.o' 2>/dev/null | sort)
if [ -z "$objs" ]; then echo "architecture: no objects under build/plugin: build first"; exit 1; fi
# shellcheck disable=SC2086
nm -P -A -g $objs 2>/dev/null > "$tmp/nm" || { echo "architecture: nm failed"; exit 1; }
awk "$srcof"'
    FNR == NR { have[$1] = 1; next }
    function file(o,   s) { s = srcof(o); return ((s ".c") in have) ? s ".c" : s ".cpp" }
    { o = $1; sub(/:$/, "", o); sym = $2; type = $3
      if (type == "U" || type == "w" || type == "v") { und[++nu] = file(o) " " sym; next }
      f = file(o); kernel = (o ~ /^build\/kernel\//)
      # a kernel entry is defined in kernel_dispatch.c and in membrane_forces.c: the core object wins
      if (!(sym in def) || (defk[sym] && !kernel)) { def[sym] = f; defk[sym] = kernel }
      if (kernel) kdef[sym] = f }
    END { for (i = 1; i <= nu; i++) { split(und[i], a, " "); s = a[2]; d = ""
              if (s in def) d = def[s]
              else { t = s; if (sub(/__(baseline|avx2|avx512)$/, "", t) && (t in kdef)) d = kdef[t] }
              if (d != "" && d != a[1]) print a[1], d, a[2] } }' \
    "$tmp/files" "$tmp/nm" | sort -u >> "$tmp/edges"

# the public API: every identifier in include/wovenff/*.h
cat include/wovenff/*.h | tr -c 'A-Za-z0-9_' '\n' | grep -E '^[A-Za-z_]' | sort -u > "$tmp/public"

awk -v block="$tmp/block" -v pub="$tmp/public" -v layersf="$tmp/layers" '
    BEGIN { while ((getline l < layersf) > 0) { split(l, a, " "); layer[a[1]] = a[2]; lname[a[1]] = a[3] }
            while ((getline l < block) > 0) {
                if (l ~ /^public-only:/) { sub(/^public-only:[ \t]*/, "", l); np = split(l, p, /[ \t]+/)
                                           for (i = 1; i <= np; i++) publiconly[p[i]] = 1 }
                if (l ~ /^allow:/) { sub(/^allow:[ \t]*/, "", l); sub(/[ \t]*#.*/, "", l)
                                     split(l, p, /[ \t]*->[ \t]*/); allow["plugin/" p[1] " plugin/" p[2]] = 1 } }
            while ((getline l < pub) > 0) public[l] = 1 }
    { from = $1; to = $2; what = $3
      if (!(from in layer) || !(to in layer) || ((from " " to) in allow)) next
      bad = ""
      if (layer[to] > layer[from]) bad = "up"
      else if ((lname[from] in publiconly) && lname[to] != lname[from]) {
          if (what == "#include") bad = "not the public API"
          else { s = what; sub(/__(baseline|avx2|avx512)$/, "", s); if (!(s in public)) bad = "not the public API" } }
      if (bad == "") next
      k = from " (" lname[from] ") -> " to " (" lname[to] ")" (bad == "up" ? "" : ", " bad)
      if (!(k in seen)) { seen[k] = 1; order[++n] = k }
      msg[k] = msg[k] " " what }
    END { for (i = 1; i <= n; i++) print order[i] ":" msg[order[i]]; exit n > 0 }' \
    "$tmp/edges" > "$tmp/violations"
vrc=$?
if [ "$vrc" -ne 0 ]; then
    echo "who may call whom (docs/architecture.md, \"Who may call whom\"): $(wc -l < "$tmp/violations") violations"
    sed 's/^/  /' "$tmp/violations"
    fail=1
fi
[ "$fail" -eq 0 ] && echo "architecture: $(wc -l < "$tmp/files") plugin files named, $(wc -l < "$tmp/edges") file -> file dependencies within the layers"
exit "$fail"
