#!/bin/sh
# tools/cunniff.sh against a hand computation. KM2 fibre (kevlar_s706.txt's
# comment): sigma eps / (2 rho) = 3.88e9 * 0.0452 / (2 * 1440) = 60894.44 m^2/s^2,
# sqrt(E / rho) = sqrt(84.62e9 / 1440) = 7665.761 m/s, U* = 4.668022e8 m^3/s^3,
# U*^(1/3) = 775.7307 m/s. Two plies of rho_A 0.181 kg/m^2, a 12.7 mm nose
# (A_p = pi 0.00635^2 = 1.266769e-4 m^2), 0.104 kg: A_D A_p / m_p = 4.409330e-4;
# V50 80 m/s: 80 / 775.7307 = 0.1031286. Bad input exits 2 naming what.
set -u
fail=0
close() { awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= 1e-5 * (b < 0 ? -b : b)) }'; }
u=$(sh tools/cunniff.sh -ustar) || { echo "-ustar failed"; fail=1; }
echo "$u"
ustar=$(echo "$u" | sed -n 's/.*U\* \([0-9.e+]*\) m^3.*/\1/p')
cube=$(echo "$u" | sed -n 's/.*U\*^(1\/3) \([0-9.e+]*\) m\/s.*/\1/p')
close "$ustar" 4.668022e8 || { echo "U* $ustar, by hand 4.668022e8"; fail=1; }
close "$cube" 775.7307 || { echo "U*^(1/3) $cube, by hand 775.7307"; fail=1; }
row=$(printf 'plies,v50,bfd\n2,80,0.025\n' | sh tools/cunniff.sh | sed -n 2p)
echo "$row"
IFS=, read -r n ad v b y x <<EOT
$row
EOT
close "$ad" 0.362 && close "$y" 0.1031286 && close "$x" 4.409330e-4 && [ "$n" = 2 ] && close "$b" 0.025 \
    || { echo "row '$row', by hand 2,0.362,80,0.025,0.1031286,4.409330e-4"; fail=1; }
# the fibre data given: U* scales as sigma (x2 -> x2)
u2=$(sh tools/cunniff.sh -ustar -sigma 7.76e9 | sed -n 's/.*U\* \([0-9.e+]*\) m^3.*/\1/p')
close "$u2" 9.336045e8 || { echo "-sigma 7.76e9: U* $u2, by hand 9.336045e8"; fail=1; }
bad() {
    want=$1; shift
    out=$(sh tools/cunniff.sh "$@" < "$input" 2>&1 >/dev/null); rc=$?
    if [ $rc -ne 2 ] || ! echo "$out" | grep -q -- "$want"; then echo "'$*': exit $rc, '$out', wanted 2 and '$want'"; fail=1
    else echo "$out"; fi
}
input="${WFF_TEST_TMP:-/tmp}/cunniff_rows.csv"
printf '1,abc,0.01\n' > "$input"
bad 'row 1' 
printf '1,50,\n' > "$input"
bad "-rho" -rho -1
bad "-material" -material no_such_material.txt
bad "unknown option" -speed 3
exit $fail
