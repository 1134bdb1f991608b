// SPDX-License-Identifier: GPL-3.0-or-later
// Periodic (cyclic) spline systems and Hermite bases for the izogrid contour (seed 000 Sec. 2.2
// and Appendix 2, eqs. (55)–(73), (85)–(87); digest izogrid.md §4.3–4.4 with the corrected
// signs of (72)/(73); sweep solvers of seed 001 Ch. I §10, digest splines.md §7).
//
// Unknowns at knot k of a periodic sequence of n knots (indices taken mod n): the cubic slope
// d_k = f'(s_k), or the quintic pair (d_k, δ''_k = f''(s_k)). The data are the differences
// Δf_{k+1/2} = f_{k+1} − f_k of the *unfolded* (not closed) contour and the knot spacings
// h_k = s_{k+1} − s_k (segment k joins knot k to knot k+1; segment n−1 closes the loop).
//
//     knot:    0        1        2            n−1        0 (again)
//              |--h_0---|--h_1---|--- ... ---|--h_{n-1}--|
//     Δf:        Δf_0     Δf_1                 Δf_{n-1}
#pragma once

#include <array>
#include <span>

namespace aq::curvilinear {

/// Solves the cyclic tridiagonal system a_i z_{i−1} + b_i z_i + c_i z_{i+1} = g_i, i = 0..n−1,
/// indices mod n (seed 001 (101)–(102): sweep with a bordering column for the corner terms).
/// n ≥ 3; `g` is overwritten with z. Throws NumericalError if a pivot vanishes or the result is
/// not finite (singular or badly conditioned system).
void solve_cyclic_tridiagonal(std::span<const double> a, std::span<const double> b, std::span<const double> c,
                              std::span<double> g);

/// A 2×2 block, row-major: {m00, m01, m10, m11}.
using Block2 = std::array<double, 4>;
using Vec2d = std::array<double, 2>;

/// Cyclic block-tridiagonal solve with 2×2 blocks ("matrix sweep", seed 000 after (73)):
/// A_i z_{i−1} + B_i z_i + C_i z_{i+1} = g_i, indices mod n, n ≥ 3. `g` is overwritten with z.
/// Throws NumericalError for a singular pivot block or a non-finite result.
void solve_cyclic_block_tridiagonal(std::span<const Block2> a, std::span<const Block2> b, std::span<const Block2> c,
                                    std::span<Vec2d> g);

/// Slopes of the periodic C² cubic spline, eq. (62) (eq. (85) when all h = 1):
/// d_{k−1}/A + 2(1/A + 1/B) d_k + d_{k+1}/B = 3(Δf_{k−1/2}/A² + Δf_{k+1/2}/B²),
/// A = h_{k−1}, B = h_k. Inputs and output have n ≥ 3 entries; h > 0.
void periodic_cubic_slopes(std::span<const double> h, std::span<const double> df, std::span<double> d);

/// Slopes and second derivatives of the periodic C⁴ quintic spline, eqs. (70) and (72)
/// corrected (digest §4.4: −1/10 on δ''_k, B⁴ under Δf_{k+1/2}); (86)–(87) when all h = 1.
void periodic_quintic_derivatives(std::span<const double> h, std::span<const double> df, std::span<double> d,
                                  std::span<double> dd);

/// Hermite basis functions of a segment in p = (s − s_L)/Δ ∈ [0, 1], as polynomial coefficients
/// c[0] + c[1] p + ... + c[5] p⁵. Cubic (55)–(57): f = f_L hL + f_R hR + Δ(d_L gL + d_R gR).
/// Quintic (64)–(66): adds Δ²(δ''_L DL + δ''_R DR).
struct HermiteBasis {
  std::array<double, 6> fl{}, fr{}, dl{}, dr{}, ddl{}, ddr{};
};
/// The cubic (degree 3) or quintic (degree 5) basis; other degrees are an InternalError.
const HermiteBasis& hermite_basis(int degree);

/// Value (order 0) or derivative of order 1..5 with respect to p of a polynomial in p.
double poly_derivative(const std::array<double, 6>& c, double p, int order);

}  // namespace aq::curvilinear
