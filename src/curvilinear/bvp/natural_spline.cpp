// SPDX-License-Identifier: GPL-3.0-or-later
// Natural cubic spline on integer knots; see natural_spline.hpp.
#include "curvilinear/bvp/natural_spline.hpp"

#include <algorithm>
#include <cmath>

namespace aq::curvilinear {

NaturalSpline::NaturalSpline(std::vector<double> f) : f_(std::move(f)), m_(f_.size(), 0.0) {
  const std::size_t n = f_.size();
  if (n < 3) return;
  // Interior unknowns M_1..M_{n−2}: tridiag(1, 4, 1), forward elimination then back substitution.
  std::vector<double> c(n, 0.0), d(n, 0.0);
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const double rhs = 6.0 * (f_[k + 1] - 2.0 * f_[k] + f_[k - 1]);
    const double piv = 4.0 - (k > 1 ? c[k - 1] : 0.0);
    c[k] = 1.0 / piv;
    d[k] = (rhs - (k > 1 ? d[k - 1] : 0.0)) / piv;
  }
  for (std::size_t k = n - 2; k >= 1; --k) {
    m_[k] = d[k] - c[k] * m_[k + 1];
    if (k == 1) break;
  }
}

double NaturalSpline::operator()(double t) const {
  const double last = static_cast<double>(f_.size() - 1);
  t = std::clamp(t, 0.0, last);
  const auto k = std::min(static_cast<std::size_t>(t), f_.size() - 2);
  const double u = t - static_cast<double>(k), v = 1.0 - u;
  return v * f_[k] + u * f_[k + 1] + ((v * v * v - v) * m_[k] + (u * u * u - u) * m_[k + 1]) / 6.0;
}

double NaturalSpline::derivative(double t) const {
  const double last = static_cast<double>(f_.size() - 1);
  t = std::clamp(t, 0.0, last);
  const auto k = std::min(static_cast<std::size_t>(t), f_.size() - 2);
  const double u = t - static_cast<double>(k), v = 1.0 - u;
  return f_[k + 1] - f_[k] + (-(3 * v * v - 1) * m_[k] + (3 * u * u - 1) * m_[k + 1]) / 6.0;
}

}  // namespace aq::curvilinear
