// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the control-function formulas (seed 004's w(x, y)).
#include "grid_params/control_function.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace aq::curvilinear::unit_grid_params_control_function_test {
namespace {

TEST(ControlFunction, EvaluatesThePapersFormulas) {
  const ControlFunction w = ControlFunction::parse("1 + 10*x*(1-x) + y^3");
  EXPECT_DOUBLE_EQ(w(0.5, 2.0), 1.0 + 2.5 + 8.0);
  const ControlFunction v = ControlFunction::parse("sqrt(1 + 0.5*abs(cos(2*pi*x))) - -2^2^0.5 / 4");
  EXPECT_NEAR(v(0.0, 0.0), std::sqrt(1.5) + std::pow(2.0, std::sqrt(2.0)) / 4.0, 1e-15);
  EXPECT_TRUE(ControlFunction().is_unity());
  EXPECT_TRUE(ControlFunction::parse(" 1 ").is_unity());
  EXPECT_FALSE(w.is_unity());
}

TEST(ControlFunction, BadFormulasNameTheKeyAndPosition) {
  for (const char* bad : {"1 +", "2*(x", "foo(x)", "x y", "sin x", ""}) {
    try {
      (void)ControlFunction::parse(bad, "regional.weight");
      ADD_FAILURE() << bad;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("regional.weight"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("character"), std::string::npos) << e.what();
    }
  }
}

TEST(ControlFunction, SampledFieldIsBilinearAndClamped) {
  const ControlFunction w = ControlFunction::sampled(0.0, 0.0, 1.0, 2.0, 2, 2, {1.0, 3.0, 5.0, 7.0});
  EXPECT_DOUBLE_EQ(w(0.5, 1.0), 4.0);
  EXPECT_DOUBLE_EQ(w(-5.0, -5.0), 1.0);
  EXPECT_DOUBLE_EQ(w(9.0, 9.0), 7.0);
}

}  // namespace
}  // namespace aq::curvilinear::unit_grid_params_control_function_test
