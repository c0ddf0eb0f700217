#!/bin/sh
# tools/wrinkle.awk (the wrinkle study's measure, docs/wrinkling.md) on made
# grids: a cone u_z = 2 mm (1 - r/R) over the quarter, 2 mm grid, with and
# without a circumferential wave of amplitude A = 50 um and wavelength 12 mm
# (along the arc) in the annulus 0.7 R .. R. With the wave: the ring's
# wavelength within 10 % of 12 mm and its RMS within [0.6, 1.1] x A/sqrt(2)
# (the bilinear sampling and the detrending take a little); without: the
# undulation RMS below A/20 (the cone's curvature only). And a file that is not
# a grid is refused (exit 2).
set -u
tmp="${WFF_TEST_TMP:-/tmp}/wrinkle_measure"
rm -rf "$tmp"; mkdir -p "$tmp"
fail=0
R=0.127
grid() { # FILE AMPLITUDE
    awk -v A="$2" -v R=$R 'BEGIN { print "x,y,uz"; pi = 3.14159265358979
        for (j = 0; j <= 100; j++) for (i = 0; i <= 100; i++) { x = 0.002 * i; y = 0.002 * j; r = sqrt(x * x + y * y)
            u = r < R ? 0.002 * (1 - r / R) : 0
            if (r > 0.7 * R && r < R) u += A * sin(2 * pi * r * atan2(y, x) / 0.012)
            printf "%.6g,%.6g,%.9g\n", x, y, u } }' > "$1"
}
field() { # LINE WORD: the number after WORD (its first occurrence, or the second with WORD2)
    echo "$1" | awk -v w="$2" -v nth="${3:-1}" '{ for (i = 1; i < NF; i++) if ($i == w && ++n == nth) { print $(i + 1); exit } }'
}
grid "$tmp/wave.csv" 50e-6
grid "$tmp/cone.csv" 0
wave=$(awk -v R=$R -f tools/wrinkle.awk "$tmp/wave.csv") || { echo "wrinkle.awk failed on the made grid"; fail=1; }
cone=$(awk -v R=$R -f tools/wrinkle.awk "$tmp/cone.csv") || { echo "wrinkle.awk failed on the cone"; fail=1; }
echo "wave: $wave"
echo "cone: $cone"
wl=$(field "$wave" wavelength); ring=$(field "$wave" rms 2); flat=$(field "$cone" rms 1)
awk -v wl="$wl" 'BEGIN { exit !(wl > 0.9 * 0.012 && wl < 1.1 * 0.012) }' || { echo "the ring's wavelength $wl m, made 0.012 m"; fail=1; }
awk -v r="$ring" 'BEGIN { a = 50e-6 / sqrt(2); exit !(r > 0.6 * a && r < 1.1 * a) }' || { echo "the ring's RMS $r m, made 50e-6/sqrt(2)"; fail=1; }
awk -v r="$flat" 'BEGIN { exit !(r < 50e-6 / 20) }' || { echo "the cone alone: undulation RMS $flat m, want < 2.5e-6 m"; fail=1; }
printf 'x,y,uz\n0,0,1\n' > "$tmp/tiny.csv"
awk -v R=$R -f tools/wrinkle.awk "$tmp/tiny.csv" > "$tmp/tiny.log" 2>&1
rc=$?
[ $rc -eq 2 ] && grep -q "not a grid" "$tmp/tiny.log" || { echo "a 1-point file: exit $rc, want 2 with 'not a grid'"; fail=1; }
exit $fail
