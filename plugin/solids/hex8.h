/* hex8.h — the backing block's element: an 8-node hexahedron integrated at
 * its centre (one point, the usual explicit solid: the pressure is the
 * element's mean, so the nearly incompressible plastic flow of clay does not
 * lock), at finite strain, with a stiffness hourglass control (Flanagan &
 * Belytschko 1981, Int. J. Numer. Meth. Eng. 17: the γ vectors orthogonal to
 * every linear field) and dashpots beside its springs (without them a crater's
 * bottom node rings on the springs for milliseconds: docs/backing.md).
 *
 * Kinematics (total Lagrangian): F at the centre from the reference
 * gradients B0 (∂N_a/∂X there); C = FᵀF = Q diag(λ) Qᵀ; the Hencky strain in
 * the material frame ε = ½ ln C (solid_laws.h's strain); the law's stress τ̄
 * in that frame; the second Piola–Kirchhoff stress S = U⁻¹ τ̄ U⁻¹ and the
 * nodal forces f_a = −V0 F S B0_a. For an isotropic stored energy W(ε), τ̄ is
 * coaxial with U and S = 2 ∂W/∂C exactly: the forces are −∂(V0 W)/∂x
 * (tests/c/test_hex8.c, by finite differences). The Kirchhoff stress is
 * τ = R τ̄ Rᵀ (R = F U⁻¹), the Cauchy stress τ/J.
 *
 * Hourglass: q_α = Σ_a γ_αa u_a (α = 1..4), energy ½ k Σ_α |q_α|², force
 * −k Σ_α γ_αa q_α; γ_αa = h_αa − (Σ_b h_αb X_b)·B0_a with h_α the products
 * ξη, ηζ, ξζ, ξηζ at the nodes. k = κ G V0 Σ_a |B0_a|² / 8 (κ ~ 0.05).
 *
 * Pure: no allocation, no global state. Nodes in the order of the natural
 * coordinates (−1,−1,−1), (1,−1,−1), (1,1,−1), (−1,1,−1), then the same at
 * ζ = +1. Lengths m, stresses Pa, energies J. */
#ifndef WFF_HEX8_H
#define WFF_HEX8_H

#define WFF_HEX_NODES 8

/* What an element keeps of its reference shape. */
typedef struct wff_hex8_ref {
    double gradient[WFF_HEX_NODES][3]; /* B0_a = ∂N_a/∂X at the centre, 1/m */
    double gamma[4][WFF_HEX_NODES];    /* hourglass vectors γ_αa */
    double volume;                     /* V0, m³ (the one-point volume, 8 det J0) */
} wff_hex8_ref;

/* The reference shape from the nodes' reference positions X; -1 if the
 * element is inverted or flat (det J0 <= 0). */
int wff_hex8_reference(const double X[WFF_HEX_NODES][3], wff_hex8_ref *r);

/* F = I + Σ_a u_a ⊗ B0_a (row-major 3×3) from the nodal displacements u. */
void wff_hex8_gradient(const wff_hex8_ref *r, const double u[WFF_HEX_NODES][3], double F[9]);

/* The material Hencky strain ε = ½ ln(FᵀF) (6 entries, solid_laws.h's order)
 * and U⁻¹ (row-major 3×3); returns J = det F (<= 0: inverted, the rest
 * unset). */
double wff_hencky(const double F[9], double strain[6], double U_inv[9]);

/* Nodal internal forces f_a = −V0 F U⁻¹ τ̄ U⁻¹ B0_a (written, not added)
 * from the material-frame stress τ̄ (6 entries). */
void wff_hex8_forces(const wff_hex8_ref *r, const double F[9], const double U_inv[9],
                     const double stress[6], double f[WFF_HEX_NODES][3]);

/* Hourglass stiffness k for κ and the shear modulus G (Pa), N/m. */
double wff_hex8_hourglass_stiffness(const wff_hex8_ref *r, double kappa, double shear);

/* Adds the hourglass forces −k Σ_α γ_αa q_α to f; returns the hourglass
 * energy ½ k Σ_α |q_α|², J. */
double wff_hex8_hourglass(const wff_hex8_ref *r, const double u[WFF_HEX_NODES][3], double k,
                          double f[WFF_HEX_NODES][3]);

/* Viscous hourglass damping beside the springs: each hourglass mode α of the
 * element a dashpot on its rate q̇_α = Σ_a γ_αa v_a (v the nodal velocities,
 * m/s), force −c_α γ_αa q̇_α. The coefficients, once per element:
 * c_α = 2 ζ √(k m_node) / |γ_α| (N s/m), the fraction ζ of the critical
 * damping of that mode's oscillator (the spring k on the element's lumped
 * node masses m_node, kg, alone), so that ζ = 1 stops an hourglass mode's
 * ringing within its period (all 0 for k, ζ or m_node 0). */
void wff_hex8_hourglass_dashpots(const wff_hex8_ref *r, double k, double node_mass, double ratio,
                                 double c[4]);

/* The dashpots' forces at the velocities v, added to f; returns the power
 * they dissipate, Σ_α c_α |q̇_α|² >= 0, W. Like the springs they act on no
 * linear velocity field (γ_α is orthogonal to them): a rigid motion or a
 * uniform strain rate meets no force. */
double wff_hex8_hourglass_damping(const wff_hex8_ref *r, const double v[WFF_HEX_NODES][3],
                                  const double c[4], double f[WFF_HEX_NODES][3]);

/* Bulk viscosity (the explicit codes' artificial viscosity, von Neumann &
 * Richtmyer's quadratic term with a linear one; the factors Abaqus/Explicit
 * uses by default are 0.06 and 1.2): a pressure
 *   q = ρ L (b1 c (−ε̇_v) + b2² L ε̇_v²)   (the quadratic term in compression only)
 * from the volume rate ε̇_v = tr D = Σ_a v_a·b_a at the nodal velocities v
 * (b_a = F⁻ᵀ B0_a), L = (J V0)^(1/3), ρ (kg/m³, the reference's) and the
 * dilatational wave speed c (m/s). Adds its nodal forces J V0 q b_a to f and
 * returns the power it dissipates, q (−ε̇_v) J V0 >= 0, W. It damps the
 * ringing of a compressed element and spreads an impact's front over a few
 * elements; it acts only on a changing volume. */
double wff_hex8_bulk_viscosity(const wff_hex8_ref *r, const double F[9], double J,
                               const double v[WFF_HEX_NODES][3], double density,
                               double wave_speed, double linear, double quadratic,
                               double f[WFF_HEX_NODES][3]);

/* The hourglass springs' highest frequency on the element's node masses
 * alone, √(k max_α |γ_α|² / m_node), rad/s (0 without mass). */
double wff_hex8_hourglass_frequency(const wff_hex8_ref *r, double k, double node_mass);

/* The stable step of the element, s: 2/ω with ω² bounded by the sum of
 * Flanagan & Belytschko's bound for the centre point, 8 c² Σ_a |b_a|²
 * (b_a = F⁻ᵀ B0_a, the current gradients; c the dilatational wave speed, m/s),
 * and the hourglass springs' k max_α |γ_α|² / m_node (m_node the element's
 * lumped share of a node's mass, kg): the largest eigenvalue of a sum is at
 * most the sum of the largest ones. */
double wff_hex8_stable_step(const wff_hex8_ref *r, const double F[9], double wave_speed,
                            double k, double node_mass);

/* ---- the fully integrated element: 2×2×2 Gauss points with F-bar ----
 * The one-point element's hourglass modes carry a share of a crater's flow
 * that grows as the block is refined (docs/backing.md "Element"); this is
 * its reference beside it, with no hourglass mode and no control: the
 * deviatoric strain at the eight Gauss points ξ = ±1/√3, the volumetric at
 * the centre (F-bar, de Souza Neto, Perić, Dutko & Owen 1996, Int. J. Solids
 * Struct. 33: F̄_g = (J_0/J_g)^(1/3) F_g, J_0 = det F at the centre), so the
 * nearly incompressible plastic flow does not lock either. Stored energy
 * Σ_g V_g W(ε̄_g) with ε̄_g = ½ ln(F̄_gᵀF̄_g); its forces (the derivative
 * through J_0 and J_g included) are wff_hex8_fbar_forces'. Eight law states
 * an element. Costs ~8× the one-point element. */
#define WFF_HEX_POINTS 8

typedef struct wff_hex8_full {
    double gradient[WFF_HEX_POINTS][WFF_HEX_NODES][3]; /* B_ga = ∂N_a/∂X at point g, 1/m */
    double volume[WFF_HEX_POINTS];                     /* V_g = det J0(ξ_g) (weight 1), m³ */
} wff_hex8_full;

/* The points' reference gradients and volumes; -1 if any point is inverted
 * or flat. */
int wff_hex8_full_reference(const double X[WFF_HEX_NODES][3], wff_hex8_full *r);

/* The current gradients b_a = F⁻ᵀ B_a of reference gradients B (1/m) at the
 * deformation F; returns J = det F (<= 0: inverted, b unset). Once an
 * element a step for its centre (F-bar's F_0⁻ᵀ B0_a, the same at its eight
 * points). */
double wff_hex8_current_gradients(const double F[9], const double B[WFF_HEX_NODES][3],
                                  double b[WFF_HEX_NODES][3]);

/* A Gauss point's deformation: F_g, F̄_g = s F_g with s = (J_0/J_g)^(1/3),
 * J_g. */
typedef struct wff_hex8_fbar_point {
    double F[9], F_bar[9], J, scale;
} wff_hex8_fbar_point;

/* Point g's deformation from the nodal displacements u and the centre's
 * J_0 = det F_0 (> 0): 0, or -1 if the point is inverted (J_g <= 0). */
int wff_hex8_fbar(const wff_hex8_full *r, int g, const double u[WFF_HEX_NODES][3],
                  double J_centre, wff_hex8_fbar_point *p);

/* Adds point g's nodal forces −V_g ∂W(F̄_g)/∂u_a to f from the law's
 * material-frame stress τ̄ at ε̄_g (6 entries) and U⁻¹ of F̄_g (wff_hencky of
 * F̄_g): −V_g [s F̄ S̄ B_ga + ⅓ tr τ̄ (b0_a − F_g⁻ᵀ B_ga)], S̄ = U⁻¹ τ̄ U⁻¹,
 * b0_a = F_0⁻ᵀ B0_a the centre's current gradients
 * (wff_hex8_current_gradients of the one-point reference's). */
void wff_hex8_fbar_forces(const wff_hex8_full *r, int g, const double b_centre[WFF_HEX_NODES][3],
                          const wff_hex8_fbar_point *p, const double U_inv[9],
                          const double stress[6], double f[WFF_HEX_NODES][3]);

/* The fully integrated element's stable step, s: 2/ω with ω² bounded by
 * [K V Σ_a |b0_a|² + 2 G Σ_g V_g Σ_a |b_ga|²] / m_node, V = Σ_g V_g (the F-bar energy's
 * volumetric term at the centre and deviatoric terms at the points, each
 * strain's square bounded by Σ_a |b_a|² Σ_a |u_a|²; b = F⁻ᵀ B at the
 * current shape), K = ρ c² − 4G/3 from the dilatational wave speed c (m/s),
 * the density ρ (kg/m³) and the shear modulus G (Pa); m_node = ρ V0 / 8. */
double wff_hex8_full_stable_step(const wff_hex8_ref *centre, const wff_hex8_full *r,
                                 const double u[WFF_HEX_NODES][3], double density,
                                 double wave_speed, double shear);

#endif
