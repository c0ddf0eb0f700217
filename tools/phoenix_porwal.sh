#!/bin/sh
# Phoenix-Porwal membrane estimate of a fabric's ballistic limit beside Smith's
# yarn relation (docs/penetration.md "The Phoenix-Porwal estimate"):
#
#   V50 = sqrt(2) (1 + Gamma) c (eps_max / K_max)^(3/4)
#
#   c        sqrt(S / rho_A), S the yarn stiffness per width of one family, rho_A
#            the areal density (both families): the membrane's tensile wave speed
#   eps_max  the yarn failure strain
#   Gamma    m_m / M_p, the mass of the fabric under the projectile's face
#            (N rho_A pi r_p^2 for a pack of N plies) over the projectile's
#   K_max    the strain concentration at the projectile's edge when the strain
#            there peaks, over the strain Smith's yarn relation gives for the
#            speed then; a function of Gamma (and eps_max)
#
# Gamma and the formula are as a secondary source quotes Phoenix & Porwal (2003);
# K_max is not given there. The K_max printed is our reconstruction from the
# two relations that source quotes (the cone moves with the projectile, reactive
# force pi rho_A V d(R^2)/dt; the strain in the cone ~ eps_c R / r) with the
# cone-front strain eps_c taken as Smith's for the speed V(t): with x = R / r_p,
# V = V0 / (1 + Gamma) exp(-Gamma (x^2 - 1)) and edge strain x (V / (sqrt 2 c))^(4/3),
# largest at x*^2 = 3 / (8 Gamma):  K_max = x* exp(-4 Gamma (x*^2 - 1) / 3)
# (1 when x* <= 1). With a clamp of radius R_o the cone reaches it at x_o = R_o / r_p;
# when x_o < x* the strain has not peaked by then, and the speed above which the
# fabric fails before the cone reaches the clamp is printed too.
#
# Usage: tools/phoenix_porwal.sh [-material FILE] [-mass KG] [-radius M] [-opening M]
#                                [-strain EPS] [-kmax K] [-plies N]
# Defaults: the paper's scene (freefem_scripts/ballistic_impact.edp): Kevlar S706,
# 0.104 kg, nose radius 6.35 mm, opening radius 0.127 m; eps_max from the material's
# fail_strain_1 key, else 0.0355 (yarns taken out of woven Kevlar, issue 13 item 4);
# K_max: the reconstruction, or the value given; 1 ply (N plies: Gamma x N, c and
# eps_max unchanged: the pack moves as one membrane).
# The C core has the same estimate (include/wovenff/membrane_limit.h, FreeFEM's
# wovenffV50Estimate), with c from the cell's own stress at 1 % stretch.
# S from the material: linear_yarns S_1; king_plain k_1 p0_1 / (2 p0_2) (the truss
# stiffness over the yarn spacing, as freefem_scripts/materials/kevlar_linear.txt).
root=$(cd "$(dirname "$0")/.." && pwd)
material=$root/freefem_scripts/materials/kevlar_s706.txt shown=freefem_scripts/materials/kevlar_s706.txt
mass=0.104 radius=6.35e-3 opening=0.127 strain="" kmax="" plies=1
while [ $# -gt 0 ]; do
    case $1 in
        -material) material=$2 shown=$2 ;;
        -mass) mass=$2 ;;
        -radius) radius=$2 ;;
        -opening) opening=$2 ;;
        -strain) strain=$2 ;;
        -kmax) kmax=$2 ;;
        -plies) plies=$2 ;;
        *) echo "phoenix_porwal.sh: unknown option $1 (see the header for the options)" >&2; exit 2 ;;
    esac
    [ $# -ge 2 ] || { echo "phoenix_porwal.sh: $1 needs a value" >&2; exit 2; }
    shift 2
done
[ -r "$material" ] || { echo "phoenix_porwal.sh: cannot read material file $material" >&2; exit 2; }
awk -v mass="$mass" -v radius="$radius" -v opening="$opening" -v strain="$strain" \
    -v kmax="$kmax" -v plies="$plies" -v file="$shown" '
function smith_v(e, c) { return c * sqrt(2 * e * sqrt(e * (1 + e)) - e * e) }
function pp(g, k) { return sqrt(2) * (1 + g) * c * (eps / k) ^ 0.75 }
function kx(x) { return x * exp(-4 * gam * (x * x - 1) / 3) }  # edge strain / Smith strain of V0/(1+Gamma)
{ sub(/#.*/, ""); if (split($0, kv, "=") == 2) { k = kv[1]; v = kv[2]; gsub(/[ \t]/, "", k);
  gsub(/[ \t]/, "", v); val[k] = v } }
END {
    cell = val["cell"]
    if (cell == "linear_yarns") { S = val["S_1"]; how = "S_1" }
    else if (cell == "king_plain") { S = val["k_1"] * val["p0_1"] / (2 * val["p0_2"]);
        how = "k_1 p0_1 / (2 p0_2)" }
    else { printf "phoenix_porwal.sh: %s: cell %s: no stiffness per width known here " \
           "(linear_yarns or king_plain)\n", file, cell > "/dev/stderr"; exit 2 }
    rhoA = val["rho_A"]
    if (!(S > 0) || !(rhoA > 0) || !(mass > 0) || !(radius > 0) || !(opening > radius) ||
        (kmax != "" && !(kmax >= 1)) || plies !~ /^[0-9]+$/ || !(plies + 0 >= 1)) {
        print "phoenix_porwal.sh: need S > 0, rho_A > 0, -mass > 0, -radius > 0, " \
              "-opening > -radius, -kmax >= 1, -plies a whole number >= 1" > "/dev/stderr"; exit 2 }
    if (strain != "") { eps = strain; src = "given" }
    else if ("fail_strain_1" in val) { eps = val["fail_strain_1"]; src = "fail_strain_1 of the material" }
    else { eps = 0.0355; src = "no fail_strain_1 in the material: the woven-yarn value" }
    c = sqrt(S / rhoA); pi = atan2(0, -1)
    gam = plies * rhoA * pi * radius ^ 2 / mass    # Gamma = m_m / M_p
    xs = sqrt(3 / (8 * gam)); if (xs < 1) xs = 1   # cone radius / r_p at the peak
    xo = opening / radius                          # ... when the cone reaches the clamp
    if (kmax == "") { k = kx(xs); how_k = "our reconstruction, see the header" }
    else { k = kmax; how_k = "given" }
    printf "material      %s (cell %s)\n", file, cell
    printf "c             %.6g m/s = sqrt(S / rho_A), S = %s = %.6g N/m, rho_A = %g kg/m^2\n", c, how, S, rhoA
    printf "eps_max       %g (%s)\n", eps, src
    printf "projectile    %g kg, radius %g m; clamp opening radius %g m\n", mass, radius, opening
    printf "Smith, yarn   V(eps_max) = %.5g m/s (exact); sqrt(2) c eps_max^(3/4) = %.5g m/s (small strain)\n",
           smith_v(eps, c), sqrt(2) * c * eps ^ 0.75
    if (plies == 1) printf "Gamma         %.4g = rho_A pi r_p^2 / M_p\n", gam
    else printf "Gamma         %.4g = %d rho_A pi r_p^2 / M_p (%d plies)\n", gam, plies, plies
    printf "peak strain   at cone radius %.4g r_p = %.4g m (the clamp: %.4g r_p)\n", xs, xs * radius, xo
    printf "K_max         %.4g (%s)\n", k, how_k
    printf "V50           %.5g m/s = sqrt(2) (1 + Gamma) c (eps_max / K_max)^(3/4)\n", pp(gam, k)
    if (kmax == "" && xo < xs)
        printf "clamped       the cone reaches the clamp before the peak: K there %.4g, failure " \
               "before the cone reaches it above %.5g m/s\n", kx(xo), pp(gam, kx(xo))
}' "$material"
