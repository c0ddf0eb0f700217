# wrinkle.awk — the out-of-plane undulation (wrinkles) near the clamp edge in a
# contour grid the ballistic scene writes (contour_<k>.csv: x,y,uz in m on a
# regular grid, x varying fastest; docs/wrinkling.md).
#   awk -v R=0.127 [-v band=0.7] [-v out=residual.csv] -f tools/wrinkle.awk contour_3.csv
# R: the clamp edge's radius (m); the annulus band*R .. 0.97 R (less the
# trend's half width) is measured. The trend at a grid point is the mean of the
# 5 x 5 points around it (4 grid steps across); the undulation is uz less its
# trend. Printed: its RMS and largest size over the annulus (m), and along the
# ring r = 0.9 R (bilinear samples at 901 angles over the quarter, detrended by
# a moving mean over +-3 deg) its RMS (m), the sign changes of the detrended
# values and the wavelength they give (2 x arc / changes, m). out: the
# undulation over the annulus as x,y,undulation (m), for a picture.
BEGIN { FS = ","; if (band == "") band = 0.7
        if (!(R > 0)) { print "wrinkle.awk: give the clamp edge's radius: -v R=0.127 (m)" > "/dev/stderr"; exit 2 } }
NR == 1 { next }
{ x = $1 + 0; y = $2 + 0
  if (!(x in xi)) { xi[x] = nx++; xs[nx - 1] = x }
  if (!(y in yi)) { yi[y] = ny++; ys[ny - 1] = y }
  z[xi[x], yi[y]] = $3 + 0 }
END {
  if (nx < 6 || ny < 6) { print "wrinkle.awk: " FILENAME ": not a grid of at least 6 x 6 points" > "/dev/stderr"; exit 2 }
  pi = 3.14159265358979; h = xs[1] - xs[0]; w = 2
  if (out != "") print "x,y,undulation" > out
  n = 0; s2 = 0; largest = 0
  for (j = w; j < ny - w; j++) for (i = w; i < nx - w; i++) {
    r = sqrt(xs[i] ^ 2 + ys[j] ^ 2)
    if (r < band * R || r > 0.97 * R - 1.5 * w * h) continue
    m = 0
    for (a = -w; a <= w; a++) for (b = -w; b <= w; b++) m += z[i + a, j + b]
    d = z[i, j] - m / (2 * w + 1) ^ 2
    s2 += d * d; n++
    if (d > largest) largest = d
    if (-d > largest) largest = -d
    if (out != "") printf "%.6g,%.6g,%.6g\n", xs[i], ys[j], d > out
  }
  r0 = 0.9 * R; K = 900; W = int(K / 30)
  for (k = 0; k <= K; k++) {
    t = (pi / 2) * k / K; px = (r0 * cos(t) - xs[0]) / h; py = (r0 * sin(t) - ys[0]) / h
    i = int(px); j = int(py); fx = px - i; fy = py - j
    if (i >= nx - 1) { i = nx - 2; fx = 1 }
    if (j >= ny - 1) { j = ny - 2; fy = 1 }
    u[k] = (1 - fx) * (1 - fy) * z[i, j] + fx * (1 - fy) * z[i + 1, j] + (1 - fx) * fy * z[i, j + 1] + fx * fy * z[i + 1, j + 1]
  }
  changes = 0; last = 0; rr = 0; cnt = 0
  for (k = W; k <= K - W; k++) {
    m = 0
    for (a = -W; a <= W; a++) m += u[k + a]
    d = u[k] - m / (2 * W + 1); rr += d * d; cnt++
    sg = d > 1e-12 * R ? 1 : (d < -1e-12 * R ? -1 : 0)
    if (sg != 0 && last != 0 && sg != last) changes++
    if (sg != 0) last = sg
  }
  arc = r0 * (pi / 2) * (K - 2 * W) / K
  wavelength = changes > 0 ? 2 * arc / changes : 0
  printf "annulus %.3g-%.3g m: undulation rms %.3e m, largest %.3e m (%d points); ring r = %.4g m: rms %.3e m, %d sign changes, wavelength %.4g m\n", band * R, 0.97 * R, sqrt(s2 / n), largest, n, r0, sqrt(rr / cnt), changes, wavelength
}
