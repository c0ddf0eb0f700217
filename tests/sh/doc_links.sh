#!/bin/sh
# The README's and docs/*.md's references resolve:
#  - every relative markdown link or image, [text](target), from the file's own folder;
#  - every `docs/NAME.md` named in the text (from the repository root), and the section it
#    names after it: `docs/NAME.md` "Title" must begin a heading of that file, `docs/NAME.md` §N
#    must be one of its "## §N" headings;
#  - every repository path in backquotes (plugin/, include/, tests/, bench/, tools/,
#    freefem_scripts/, meshes/, docs/) that names no pattern (no * < > { } | ..., no NAME or
#    other capitalised placeholder); a program built from PATH.c counts, and so does a file
#    docs/architecture.md marks (planned).
# A heading is a "#" line or a paragraph that starts in bold (**Title.**).
# Prints "file:line: what" for each reference that does not resolve and exits 1 on any.
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root" || exit 1
files="README.md $(ls docs/*.md)"
# shellcheck disable=SC2086
awk '
    function exists(p,   r) { r = (system("test -e \"" p "\"") == 0); return r }
    function headings(doc,   l, h) {
        if (doc in loaded) return
        loaded[doc] = 1
        while ((getline l < doc) > 0) {
            if (l ~ /^#+ /) { h = l; sub(/^#+ +/, "", h); head[doc, ++nh[doc]] = h }
            else if (l ~ /^\*\*[^*]+\*\*/) { h = substr(l, 3); sub(/\*\*.*/, "", h); head[doc, ++nh[doc]] = h } }
        close(doc) }
    function has_heading(doc, title,   i) {
        headings(doc)
        for (i = 1; i <= nh[doc]; i++) if (index(head[doc, i], title) == 1) return 1
        return 0 }
    function bad(what) { printf "%s:%d: %s\n", FILENAME, FNR, what; nbad++ }
    BEGIN { while ((getline l < "docs/architecture.md") > 0) if (l ~ /\(planned\)/)
                while (match(l, /`plugin\/[^`]+`/)) { planned[substr(l, RSTART + 1, RLENGTH - 2)] = 1
                                                     l = substr(l, RSTART + RLENGTH) }
            close("docs/architecture.md") }
    FNR == 1 { dir = FILENAME; if (sub(/\/[^\/]*$/, "", dir) == 0) dir = "."; fence = 0 }
    /^```/ { fence = !fence; next }
    fence { next }
    {
        line = $0
        # markdown links and images
        s = line
        while (match(s, /\]\([^)]+\)/)) {
            t = substr(s, RSTART + 2, RLENGTH - 3); s = substr(s, RSTART + RLENGTH)
            if (t ~ /^(https?|mailto):/ || t ~ /^#/) continue
            sub(/#.*/, "", t)
            if (!exists(dir "/" t)) bad("link (" t ") does not resolve from " dir "/")
        }
        # docs/NAME.md and the section named after it
        s = line
        while (match(s, /docs\/[A-Za-z0-9_]+\.md/)) {
            doc = substr(s, RSTART, RLENGTH); s = substr(s, RSTART + RLENGTH)
            if (!exists(doc)) { bad(doc " does not exist"); continue }
            rest = s; sub(/^`?,? */, "", rest)
            if (match(rest, /^"[^"]+"/)) {
                title = substr(rest, 2, RLENGTH - 2)
                if (!has_heading(doc, title)) bad(doc " has no heading \"" title "\"")
            } else if (match(rest, /^§[0-9]+/)) {
                sec = substr(rest, 1, RLENGTH)
                if (!has_heading(doc, sec " ")) bad(doc " has no section " sec)
            }
        }
        # repository paths in backquotes
        s = line
        while (match(s, /`[^`]+`/)) {
            t = substr(s, RSTART + 1, RLENGTH - 2); s = substr(s, RSTART + RLENGTH)
            if (t !~ /^(plugin|include|tests|bench|tools|freefem_scripts|meshes|docs)\/[^ ]*$/) continue
            if (t ~ /[*<>{}|]|\.\.\.|[A-Z][A-Z][A-Z]/) continue
            sub(/:[0-9]+$/, "", t); sub(/[,.;:]$/, "", t)
            if (!exists(t) && !exists(t ".c") && !(t in planned)) bad("`" t "` does not exist")
        }
    }
    END { if (nbad) { printf "%d references do not resolve\n", nbad; exit 1 }
          print "doc_links: every link, document, section and path named resolves" }
' $files
