#!/bin/sh
# The portable build: wovenff.so and every object of the C core hold no
# instruction beyond x86-64-v2 outside the kernel variants chosen at run time
# (include/wovenff/kernel.h): a function of the avx2 variant may use up to
# x86-64-v3 (AVX2, FMA, BMI), one of the avx512 variant anything; every other
# function, none of AVX (VEX or EVEX encodings, %ymm, %zmm, mask registers),
# BMI1/2, LZCNT, MOVBE or ADX. libmvec's vector functions likewise: the SSE4
# ones (_ZGVb) anywhere, the AVX2 ones (_ZGVc, _ZGVd) only from avx2 and
# avx512 code, the AVX-512 ones (_ZGVe) only from avx512 code. And the
# variants are what they claim: AVX-512 code in the avx512 variant, AVX2 code
# in the avx2 one, the entry points of all three in the library.
# Which variant a function belongs to: its object (build/kernel/VARIANT.o, the
# variant's kernels linked together), and in the library the address range
# the link map (build/wovenff.map, written beside it) gives that object's
# code. Static functions keep their names in every variant (king_evaluate is
# in all three), so a name alone does not say.
# Run from the repository root after make (make test does). With an argument:
# that library alone (e.g. an older build, to see what it holds).
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root" || exit 1
lib=${1:-build/wovenff.so}
[ -f "$lib" ] || { echo "portable_build: $lib missing (run make first)"; exit 1; }
map=${lib%.so}.map
[ -f "$map" ] || { echo "portable_build: the link map $map missing (the Makefile writes it)"; exit 1; }
objects=""
if [ $# -eq 0 ]; then
    # the objects the library is linked from, as the Makefile lists them (the core's
    # and the three kernel variants; build/kernel/VARIANT/ holds their parts before
    # the renaming, never linked; an object a past build left is not scanned)
    objects=$(make -s --no-print-directory print-core-objects)
    [ -n "$objects" ] || { echo "portable_build: no objects under build/"; exit 1; }
fi
fail=0

# The kernel variants' code in the library: "START END VARIANT" (decimal) for
# every text section the link map places from build/kernel/VARIANT.o.
ranges=$(mktemp)
awk 'function hex(s,  i, n) { n = 0; s = tolower(s); sub(/^0x/, "", s)
         for (i = 1; i <= length(s); i++) n = n * 16 + index("0123456789abcdef", substr(s, i, 1)) - 1
         return n }
     /^ \.text/ { if (NF == 1) { getline; $0 = "x " $0 } }
     /^ \.text|^x / && $4 ~ /kernel\/(baseline|avx2|avx512)\.o$/ {
         v = $4; sub(/.*kernel\//, "", v); sub(/\.o$/, "", v)
         printf "%.0f %.0f %s\n", hex($2), hex($2) + hex($3), v }' "$map" >"$ranges"

# Disassembly of one file → "FILE FUNCTION VARIANT LEVEL-NEEDED INSTRUCTION"
# for every instruction beyond x86-64-v2, where VARIANT is baseline, avx2,
# avx512 or "-" (no variant) and LEVEL-NEEDED is v3 or v4, then a summary line
# "= FILE functions N avx2 N avx512 N zmm N ymm N".
scan() {
    fixed=-
    case "$1" in */kernel/baseline.o) fixed=baseline ;; */kernel/avx2.o) fixed=avx2 ;;
                 */kernel/avx512.o) fixed=avx512 ;; esac
    objdump -d --no-show-raw-insn "$1" | awk -v file="$1" -v fixed="$fixed" -v lib="$lib" \
        -v ranges="$ranges" '
    function hex(s,  i, n) { n = 0; s = tolower(s)
        for (i = 1; i <= length(s); i++) n = n * 16 + index("0123456789abcdef", substr(s, i, 1)) - 1
        return n }
    BEGIN { if (file == lib) while ((getline line < ranges) > 0) { split(line, r, " ")
                nr++; lo[nr] = r[1]; hi[nr] = r[2]; rv[nr] = r[3] } }
    /^[0-9a-f]+ <.*>:$/ {
        fn = substr($2, 2, length($2) - 3); funcs++
        variant = fixed
        if (file == lib) { a = hex($1); variant = "-"
            for (i = 1; i <= nr; i++) if (a >= lo[i] && a < hi[i]) { variant = rv[i]; break } }
        if (variant == "avx2") n2++; else if (variant == "avx512") n5++
        next
    }
    fn ~ /@plt$/ { next } # a PLT stub: a jump to the function it names
    /^ *[0-9a-f]+:\t/ {
        n = split($0, part, "\t"); ins = part[n]
        split(ins, word, " "); m = word[1]
        if (m ~ /^(rep|repz|repnz|lock|notrack|bnd|data16|addr32|cs|ds)$/) m = word[2]
        level = ""
        # AVX-512 (EVEX): zmm, mask registers, xmm/ymm 16-31, masking, EVEX-only names
        if (ins ~ /%zmm|%k[0-7]|%[xy]mm(1[6-9]|2[0-9]|3[01])\>|\{sae\}|-sae\}/ ||
            m ~ /^k(mov|and|or|xor|not|shift|test|add|unpck|ortest)/ ||
            m ~ /^(vpternlog|vperm[it]2|vrcp14|vrsqrt14|vrndscale|vscalef|vgetexp|vgetmant|vfixupimm|vrange|vreduce|vfpclass|valign|vdbpsadbw)/ ||
            m ~ /^vcvt[a-z0-9]*(qq|uqq|udq|usi)[a-z]*$/ || m ~ /^vcvtu/ ||
            m ~ /^vpmov(u?s)?(qd|qw|qb|dw|db|wb)$/ || m ~ /^vpmov(m2[bwdq]|[bwdq]2m)$/ ||
            m ~ /^v(p)?(compress|expand|blendm)/ || m ~ /^vpro[lr]/ ||
            m ~ /^vp(abs|maxs|mins|maxu|minu|sra)q$/ || m ~ /^vpmullq$/ ||
            m ~ /^v(extract|insert|broadcast)[if](32x[48]|64x[24])$/ || m ~ /^vshuf[if](32x4|64x2)$/)
            level = "v4"
        # AVX, AVX2, FMA, F16C (VEX), BMI1/2, LZCNT, MOVBE, ADX
        else if (m ~ /^v/ || ins ~ /%ymm/ ||
                 m ~ /^(andn|bextr|blsi|blsmsk|blsr|bzhi|mulx|pdep|pext|rorx|sarx|shlx|shrx|lzcnt|movbe|adcx|adox)$/)
            level = "v3"
        if (ins ~ /%zmm/) zmm[fn] = 1
        if (ins ~ /%ymm/) ymm[fn] = 1
        # libmvec: the vector width a call needs
        if (ins ~ /<_ZGVe/) level = "v4"
        else if (ins ~ /<_ZGV[cd]/ && level == "") level = "v3"
        if (level != "") print file, fn, variant, level, ins
    }
    END {
        for (f in zmm) nz++
        for (f in ymm) ny++
        printf "= %s functions %d avx2 %d avx512 %d zmm %d ymm %d\n", file, funcs, n2, n5, nz, ny
    }'
}

out=$(mktemp); trap 'rm -f "$out" "$ranges"' EXIT
for f in "$lib" $objects; do scan "$f"; done >"$out"

# what each function may use: avx512 anything, avx2 up to v3, the rest v2
bad=$(awk '!/^=/ && $3 != "avx512" && !($3 == "avx2" && $4 == "v3")' "$out")
if [ -n "$bad" ]; then
    echo "instructions beyond x86-64-v2 outside the kernel variants (file function variant level instruction):"
    printf '%s\n' "$bad" | head -40
    echo "($(printf '%s\n' "$bad" | wc -l) in all)"
    fail=1
fi
summary=$(grep "^= $lib " "$out")
echo "$summary"
set -- $summary
funcs=$4 avx2=$6 avx512=$8
beyond=$(awk -v lib="$lib" '$1 == lib && !/^=/' "$out" | wc -l)
outside=$(printf '%s\n' "$bad" | awk -v lib="$lib" '$1 == lib' | wc -l)
echo "portable_build: $lib: $funcs functions, $avx2 of them avx2 and $avx512 avx512 variants;" \
     "$beyond instructions beyond x86-64-v2, $outside of them outside the variants"

# the variants are what they claim
zmm512=$(awk -v lib="$lib" '$1 == lib && $3 == "avx512" && /%zmm/' "$out" | wc -l)
ymm2=$(awk -v lib="$lib" '$1 == lib && $3 == "avx2" && /%ymm/' "$out" | wc -l)
mvec512=$(awk -v lib="$lib" '$1 == lib && $3 == "avx512" && /<_ZGVe/' "$out" | wc -l)
echo "portable_build: $zmm512 zmm instructions and $mvec512 calls to libmvec's AVX-512 functions" \
     "in the avx512 variant, $ymm2 ymm instructions in the avx2 variant"
[ "$zmm512" -gt 0 ] && [ "$mvec512" -gt 0 ] || { echo "the avx512 variant holds no AVX-512 code"; fail=1; }
[ "$ymm2" -gt 0 ] || { echo "the avx2 variant holds no AVX2 code"; fail=1; }
for entry in wff_elements_forces wff_elements_stable_step; do
    for v in baseline avx2 avx512; do
        nm --defined-only "$lib" | grep -q " T ${entry}__$v\$" ||
            { echo "$lib: entry point ${entry}__$v missing"; fail=1; }
    done
    nm --defined-only "$lib" | grep -q " T $entry\$" || { echo "$lib: dispatcher $entry missing"; fail=1; }
done
[ $fail -eq 0 ] && echo "portable_build: ok"
exit $fail
