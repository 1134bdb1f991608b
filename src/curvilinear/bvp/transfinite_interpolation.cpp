// SPDX-License-Identifier: GPL-3.0-or-later
// Classic transfinite interpolation; see transfinite_interpolation.hpp.
#include "curvilinear/bvp/transfinite_interpolation.hpp"

#include <fmt/format.h>

#include "core/error.hpp"

namespace aq::curvilinear {

SurfaceGrid transfinite_interpolation(const std::vector<Vec3>& south, const std::vector<Vec3>& east,
                                      const std::vector<Vec3>& north, const std::vector<Vec3>& west) {
  const int nx = static_cast<int>(south.size());
  const int ny = static_cast<int>(west.size());
  if (nx < 2 || ny < 2 || north.size() != south.size() || east.size() != west.size())
    throw InternalError(fmt::format("transfinite_interpolation: sides of {}, {}, {}, {} points", south.size(),
                                    east.size(), north.size(), west.size()));
  SurfaceGrid g(nx, ny);
  const Vec3 sw = south.front(), se = south.back(), ne = north.back(), nw = north.front();
  for (int j = 0; j < ny; ++j) {
    const double v = static_cast<double>(j) / (ny - 1);
    for (int i = 0; i < nx; ++i) {
      const double u = static_cast<double>(i) / (nx - 1);
      const auto ii = static_cast<std::size_t>(i), jj = static_cast<std::size_t>(j);
      g(i, j) = (1 - v) * south[ii] + v * north[ii] + (1 - u) * west[jj] + u * east[jj] -
                ((1 - u) * (1 - v) * sw + u * (1 - v) * se + u * v * ne + (1 - u) * v * nw);
    }
  }
  for (int i = 0; i < nx; ++i) {
    g(i, 0) = south[static_cast<std::size_t>(i)];
    g(i, ny - 1) = north[static_cast<std::size_t>(i)];
  }
  for (int j = 1; j < ny - 1; ++j) {
    g(0, j) = west[static_cast<std::size_t>(j)];
    g(nx - 1, j) = east[static_cast<std::size_t>(j)];
  }
  return g;
}

}  // namespace aq::curvilinear
