// SPDX-License-Identifier: GPL-3.0-or-later
// Control function w(x, y): a tiny formula compiler (recursive descent to postfix) and a sampled
// lattice field; see control_function.hpp.
#include "grid_params/control_function.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include "core/error.hpp"

namespace aq::curvilinear {

namespace {

using Fun = double (*)(double);
struct FunEntry {
  const char* name;
  Fun f;
};
const std::array<FunEntry, 10> kFunctions = {{{"sin", [](double v) { return std::sin(v); }},
                                              {"cos", [](double v) { return std::cos(v); }},
                                              {"tan", [](double v) { return std::tan(v); }},
                                              {"exp", [](double v) { return std::exp(v); }},
                                              {"log", [](double v) { return std::log(v); }},
                                              {"sqrt", [](double v) { return std::sqrt(v); }},
                                              {"abs", [](double v) { return std::fabs(v); }},
                                              {"sinh", [](double v) { return std::sinh(v); }},
                                              {"cosh", [](double v) { return std::cosh(v); }},
                                              {"tanh", [](double v) { return std::tanh(v); }}}};

}  // namespace

// Recursive descent: expr = term {(+|−) term}; term = unary {(*|/) unary}; unary = −unary | power;
// power = atom [^ unary]; atom = number | x | y | pi | fun(expr) | (expr).
class FormulaParser {
 public:
  FormulaParser(std::string_view s, const std::string& key) : s_(s), key_(key) {}

  template <class Instr, class Op>
  void parse(std::vector<Instr>& out) {
    expr<Instr, Op>(out);
    skip();
    if (pos_ != s_.size()) fail("unexpected text");
  }

 private:
  std::string_view s_;
  const std::string& key_;
  std::size_t pos_ = 0;

  [[noreturn]] void fail(const char* what) const {
    throw ConfigError(fmt::format("{} = \"{}\": {} at character {}", key_, s_, what, pos_ + 1));
  }
  void skip() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool eat(char c) {
    skip();
    if (pos_ < s_.size() && s_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  template <class Instr, class Op>
  void expr(std::vector<Instr>& out) {
    term<Instr, Op>(out);
    for (;;) {
      if (eat('+')) {
        term<Instr, Op>(out);
        out.push_back({Op::kAdd, 0, 0.0});
      } else if (eat('-')) {
        term<Instr, Op>(out);
        out.push_back({Op::kSub, 0, 0.0});
      } else {
        return;
      }
    }
  }
  template <class Instr, class Op>
  void term(std::vector<Instr>& out) {
    unary<Instr, Op>(out);
    for (;;) {
      if (eat('*')) {
        unary<Instr, Op>(out);
        out.push_back({Op::kMul, 0, 0.0});
      } else if (eat('/')) {
        unary<Instr, Op>(out);
        out.push_back({Op::kDiv, 0, 0.0});
      } else {
        return;
      }
    }
  }
  template <class Instr, class Op>
  void unary(std::vector<Instr>& out) {
    if (eat('-')) {
      unary<Instr, Op>(out);
      out.push_back({Op::kNeg, 0, 0.0});
      return;
    }
    if (eat('+')) return unary<Instr, Op>(out);
    atom<Instr, Op>(out);
    if (eat('^')) {
      unary<Instr, Op>(out);
      out.push_back({Op::kPow, 0, 0.0});
    }
  }
  template <class Instr, class Op>
  void atom(std::vector<Instr>& out) {
    skip();
    if (pos_ >= s_.size()) fail("expected a number, x, y, a function or '('");
    const char c = s_[pos_];
    if (eat('(')) {
      expr<Instr, Op>(out);
      if (!eat(')')) fail("expected ')'");
      return;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      const std::string rest(s_.substr(pos_));
      char* end = nullptr;
      const double v = std::strtod(rest.c_str(), &end);
      if (end == rest.c_str()) fail("bad number");
      pos_ += static_cast<std::size_t>(end - rest.c_str());
      out.push_back({Op::kNum, 0, v});
      return;
    }
    if (!std::isalpha(static_cast<unsigned char>(c))) fail("unexpected character");
    std::size_t e = pos_;
    while (e < s_.size() && std::isalnum(static_cast<unsigned char>(s_[e]))) ++e;
    const std::string_view name = s_.substr(pos_, e - pos_);
    pos_ = e;
    if (name == "x") return out.push_back({Op::kX, 0, 0.0});
    if (name == "y") return out.push_back({Op::kY, 0, 0.0});
    if (name == "pi") return out.push_back({Op::kNum, 0, std::numbers::pi});
    for (std::size_t k = 0; k < kFunctions.size(); ++k) {
      if (name == kFunctions[k].name) {
        if (!eat('(')) fail("expected '(' after a function name");
        expr<Instr, Op>(out);
        if (!eat(')')) fail("expected ')'");
        out.push_back({Op::kFun, static_cast<int>(k), 0.0});
        return;
      }
    }
    fail("unknown name (use x, y, pi, sin, cos, tan, exp, log, sqrt, abs, sinh, cosh, tanh)");
  }
};

ControlFunction ControlFunction::parse(std::string_view formula, const std::string& key) {
  ControlFunction w;
  w.text_ = std::string(formula);
  FormulaParser(formula, key).parse<Instr, Op>(w.program_);
  // Stack depth check: every operand pushes, every binary op pops one.
  int depth = 0, max_depth = 0;
  for (const Instr& in : w.program_) {
    if (in.op == Op::kNum || in.op == Op::kX || in.op == Op::kY) ++depth;
    if (in.op == Op::kAdd || in.op == Op::kSub || in.op == Op::kMul || in.op == Op::kDiv || in.op == Op::kPow) --depth;
    max_depth = std::max(max_depth, depth);
  }
  if (max_depth > 32) throw ConfigError(fmt::format("{} = \"{}\": nested too deeply", key, formula));
  w.unity_ = w.program_.size() == 1 && w.program_[0].op == Op::kNum && w.program_[0].value == 1.0;
  return w;
}

ControlFunction ControlFunction::sampled(double x0, double y0, double dx, double dy, int nx, int ny,
                                         std::vector<double> values) {
  if (nx < 2 || ny < 2 || !(dx > 0.0) || !(dy > 0.0) || values.size() != static_cast<std::size_t>(nx) * ny)
    throw InternalError("ControlFunction::sampled: bad lattice");
  ControlFunction w;
  w.unity_ = false;
  w.text_ = "sampled";
  w.values_ = std::move(values);
  w.x0_ = x0;
  w.y0_ = y0;
  w.dx_ = dx;
  w.dy_ = dy;
  w.nx_ = nx;
  w.ny_ = ny;
  return w;
}

double ControlFunction::operator()(double x, double y) const {
  if (unity_) return 1.0;
  if (nx_ > 0) {
    const double u = std::clamp((x - x0_) / dx_, 0.0, nx_ - 1.0);
    const double v = std::clamp((y - y0_) / dy_, 0.0, ny_ - 1.0);
    const int i = std::min(static_cast<int>(u), nx_ - 2);
    const int j = std::min(static_cast<int>(v), ny_ - 2);
    const double fu = u - i, fv = v - j;
    const auto at = [&](int a, int b) { return values_[static_cast<std::size_t>(b) * nx_ + a]; };
    return (1 - fv) * ((1 - fu) * at(i, j) + fu * at(i + 1, j)) +
           fv * ((1 - fu) * at(i, j + 1) + fu * at(i + 1, j + 1));
  }
  std::array<double, 34> st{};
  int n = 0;
  for (const Instr& in : program_) {
    switch (in.op) {
      case Op::kNum:
        st[n++] = in.value;
        break;
      case Op::kX:
        st[n++] = x;
        break;
      case Op::kY:
        st[n++] = y;
        break;
      case Op::kAdd:
        --n, st[n - 1] += st[n];
        break;
      case Op::kSub:
        --n, st[n - 1] -= st[n];
        break;
      case Op::kMul:
        --n, st[n - 1] *= st[n];
        break;
      case Op::kDiv:
        --n, st[n - 1] /= st[n];
        break;
      case Op::kPow:
        --n, st[n - 1] = std::pow(st[n - 1], st[n]);
        break;
      case Op::kNeg:
        st[n - 1] = -st[n - 1];
        break;
      case Op::kFun:
        st[n - 1] = kFunctions[static_cast<std::size_t>(in.fun)].f(st[n - 1]);
        break;
    }
  }
  return st[0];
}

}  // namespace aq::curvilinear
