// SPDX-License-Identifier: GPL-3.0-or-later
// Slopes of the C2 interpolating cubic spline on a uniform grid (reference splines.md §3.1,
// sweep solvers §7): d[k-1] + 4 d[k] + d[k+1] = 3 (f[k+1] - f[k-1]) / h, with periodic ends
// (cyclic sweep) or natural ends (zero second derivative: 2 d0 + d1 = 3 (f1 - f0) / h).
#pragma once

#include <cstdint>

namespace aq::raster {

/// Writes the spline slopes of f[0..n) into d. `work` must hold
/// 2n doubles. n >= 3 for periodic, n >= 2 for natural ends.
void spline_slopes(const double* f, double* d, std::int64_t n, double h, bool periodic, double* work);

}  // namespace aq::raster
