// SPDX-License-Identifier: GPL-3.0-or-later
// Natural cubic spline through values f_0..f_N at the integer knots t = 0..N (s'' = 0 at both
// ends), the index-parametrised spline of seed 003 Sec. 4.2 (digest orthogonal_bvp_and_elliptic.md
// A.7). Second derivatives from the tridiagonal system M_{k−1} + 4 M_k + M_{k+1} =
// 6 (f_{k+1} − 2 f_k + f_{k−1}) by the Thomas algorithm.
#pragma once

#include <vector>

namespace aq::curvilinear {

class NaturalSpline {
 public:
  /// Needs ≥ 2 values (2 values give the straight line).
  explicit NaturalSpline(std::vector<double> f);
  /// Value at t in [0, N] (clamped), or its derivative.
  [[nodiscard]] double operator()(double t) const;
  [[nodiscard]] double derivative(double t) const;

 private:
  std::vector<double> f_, m_;
};

}  // namespace aq::curvilinear
