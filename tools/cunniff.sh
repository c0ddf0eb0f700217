#!/bin/sh
# cunniff.sh — Cunniff's dimensionless form of a pack's ballistic limit.
#
# Cunniff (1999, "Dimensionless parameters for optimization of textile-based body
# armor systems", 18th Int. Symp. on Ballistics) scales the limit V50 of a fabric
# pack by the cube root of the fibre's
#     U* = sigma eps / (2 rho) * sqrt(E / rho)      (m^3/s^3)
# (sigma the fibre strength, eps its failure strain, E its modulus, rho its
# density: the specific toughness times the strain wave speed) and the pack's
# areal density A_D (kg/m^2) by the projectile's mass over its presented area:
#     x = A_D A_p / m_p,  y = V50 / U*^(1/3),  A_p = pi r^2.
#
# Usage   sh tools/cunniff.sh [options] [FILE]    (FILE or stdin: rows plies,V50,BFD)
#   -material F  material file (freefem_scripts/materials/kevlar_s706.txt): the fibre's
#                E, strength and failure strain from its comment "fibre E = .. GPa,
#                strength .. GPa, failure strain .. %", the ply's areal density rho_A
#   -E Pa -sigma Pa -strain - -rho kg/m^3   the fibre data, replacing the file's
#                (rho: 1440, KM2's density, DuPont's Kevlar technical guide)
#   -radius m    projectile radius (0.00635: the ballistic scene's 12.7 mm nose)
#   -mass kg     projectile mass (0.104, the scene's)
#   -ustar       print U* (m^3/s^3) and U*^(1/3) (m/s) only
# Rows: plies, V50 (m/s), back-face deformation (m; may be empty); '#' lines and a
# header row starting "plies" are skipped. Output CSV:
#   plies,areal_density,v50,bfd,v50_over_ustar13,ad_ap_over_mp
# Exit 0; 2 bad input (naming the option, the file or the row).
set -u
material=freefem_scripts/materials/kevlar_s706.txt
E=""; sigma=""; strain=""; rho=1440; radius=0.00635; mass=0.104; only=0; input=""
die() { echo "error: cunniff.sh: $*" >&2; exit 2; }
isnum() { printf '%s\n' "$1" | grep -Eq '^[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?$'; }
while [ $# -gt 0 ]; do
    case "$1" in
        -material|-E|-sigma|-strain|-rho|-radius|-mass)
            [ $# -ge 2 ] || die "option $1 needs a value"
            opt=$1; val=$2; shift 2
            if [ "$opt" != -material ]; then
                isnum "$val" || die "$opt '$val' is not a number"
                awk -v v="$val" 'BEGIN { exit !(v > 0) }' || die "$opt $val must be > 0"
            fi
            case "$opt" in
                -material) material=$val ;; -E) E=$val ;; -sigma) sigma=$val ;; -strain) strain=$val ;;
                -rho) rho=$val ;; -radius) radius=$val ;; -mass) mass=$val ;;
            esac ;;
        -ustar) only=1; shift ;;
        -*) die "unknown option '$1' (options: -material -E -sigma -strain -rho -radius -mass -ustar)" ;;
        *) [ -z "$input" ] || die "one input file only ('$input', '$1')"; input=$1; shift ;;
    esac
done
[ -r "$material" ] || die "-material $material: cannot be read"
# the fibre data from the material's comment, unless given
line=$(grep -m1 -i 'fibre E = ' "$material" || true)
[ -n "$E" ] || E=$(printf '%s\n' "$line" | sed -n 's/.*fibre E = \([0-9.eE+-]*\) GPa.*/\1e9/p')
[ -n "$sigma" ] || sigma=$(printf '%s\n' "$line" | sed -n 's/.*strength \([0-9.eE+-]*\) GPa.*/\1e9/p')
if [ -z "$strain" ]; then
    pct=$(grep -m1 -i -A1 'fibre E = ' "$material" | tr '\n' ' ' | sed -n 's/.*failure strain \([0-9.eE+-]*\) %.*/\1/p')
    [ -n "$pct" ] && strain=$(awk -v p="$pct" 'BEGIN { printf "%.10g", p / 100 }')
fi
[ -n "$E" ] && [ -n "$sigma" ] && [ -n "$strain" ] \
    || die "-material $material: no fibre data (a comment 'fibre E = .. GPa, strength .. GPa, failure strain .. %'); give -E -sigma -strain"
rhoA=$(sed -n 's/^rho_A *= *\([0-9.eE+-]*\).*/\1/p' "$material" | head -1)
[ -n "$rhoA" ] || die "-material $material: no rho_A key (the ply's areal density)"
ustar=$(awk -v s="$sigma" -v e="$strain" -v r="$rho" -v E="$E" 'BEGIN { printf "%.10g", s * e / (2 * r) * sqrt(E / r) }')
cube=$(awk -v u="$ustar" 'BEGIN { printf "%.10g", u ^ (1 / 3) }')
if [ "$only" = 1 ]; then
    echo "E $E Pa, sigma $sigma Pa, strain $strain, rho $rho kg/m^3: U* $ustar m^3/s^3, U*^(1/3) $cube m/s"
    exit 0
fi
if [ -n "$input" ]; then [ -r "$input" ] || die "input $input: cannot be read"; else input=-; fi
echo "plies,areal_density,v50,bfd,v50_over_ustar13,ad_ap_over_mp"
awk -F, -v rhoA="$rhoA" -v cube="$cube" -v r="$radius" -v m="$mass" -v name="$input" '
    function num(s) { return s ~ /^[ ]*[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?[ ]*$/ }
    /^[ ]*#/ || /^[ ]*$/ || /^[ ]*plies/ { next }
    {
        if (!num($1) || $1 < 1 || $1 != int($1) || !num($2) || ($3 != "" && !num($3))) {
            printf "error: cunniff.sh: %s row %d \"%s\": want plies,V50,BFD (numbers; BFD may be empty)\n", name, NR, $0 > "/dev/stderr"
            bad = 1; exit 2
        }
        AD = $1 * rhoA; Ap = 3.14159265358979 * r * r
        printf "%d,%.6g,%.6g,%s,%.6g,%.6g\n", $1, AD, $2, ($3 == "" ? "" : sprintf("%.6g", $3)), $2 / cube, AD * Ap / m
    }
    END { exit bad ? 2 : 0 }' "$input"
