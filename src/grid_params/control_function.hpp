// SPDX-License-Identifier: GPL-3.0-or-later
// The control function w(x, y) ≥ 1 of seed 004's adaptive grids (digest orthogonal_bvp_and_elliptic.md
// B.2, B.4, B.5): large w gives small cells. Either a formula in the plane coordinates x, y (e.g. the
// paper's Fig. 1 "1 + 10*x*(1-x) + y^3") or a field sampled on a regular lattice (the app samples
// w = 1 + a·|∇h|/max|∇h| from the bathymetry), bilinear between lattice points.
//
// Formula grammar: numbers, x, y, pi, + − * / ^ (right-associative), unary −, parentheses and the
// functions sin cos tan exp log sqrt abs sinh cosh tanh. Compiled once to postfix; evaluation is
// thread-safe and allocation-free.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace aq::curvilinear {

class ControlFunction {
 public:
  /// w ≡ 1.
  ControlFunction() = default;
  /// Parses `formula`; throws ConfigError naming `key` and the position of the first bad token.
  static ControlFunction parse(std::string_view formula, const std::string& key = "weight");
  /// Bilinear interpolation of `values` (nx × ny, row-major, j·nx + i) on the lattice
  /// x0 + i·dx, y0 + j·dy; clamped to the lattice outside it. nx, ny ≥ 2, dx, dy > 0.
  static ControlFunction sampled(double x0, double y0, double dx, double dy, int nx, int ny,
                                 std::vector<double> values);

  /// w at a plane point (no clamping to ≥ 1: the caller's formula is trusted, see is_positive_on()).
  [[nodiscard]] double operator()(double x, double y) const;
  /// true for w ≡ 1 (the default or the formula "1").
  [[nodiscard]] bool is_unity() const { return unity_; }
  /// The formula text (or "sampled" / "1").
  [[nodiscard]] const std::string& text() const { return text_; }

 private:
  enum class Op : unsigned char { kNum, kX, kY, kAdd, kSub, kMul, kDiv, kPow, kNeg, kFun };
  struct Instr {
    Op op;
    int fun;       // index into the function table for kFun
    double value;  // kNum
  };
  std::vector<Instr> program_;
  bool unity_ = true;
  std::string text_ = "1";
  // Sampled field.
  std::vector<double> values_;
  double x0_ = 0, y0_ = 0, dx_ = 1, dy_ = 1;
  int nx_ = 0, ny_ = 0;
};

}  // namespace aq::curvilinear
