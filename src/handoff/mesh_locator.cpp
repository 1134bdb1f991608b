// SPDX-License-Identifier: GPL-3.0-or-later
// Point location in a global mesh (see mesh_locator.hpp).
#include "handoff/mesh_locator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "quadtree/bits.hpp"

namespace aq::handoff {

namespace {

constexpr double kEdgeTolerancePx = 1e-9;  // a point this close to a pixel edge is tried on both sides
constexpr double kInsideTolerance = 1e-9;  // smallest barycentric weight accepted as inside

PoleRotation rotation_of(const mesh::Mesh& m) {
  return m.rotation.enabled ? PoleRotation(m.rotation.pole_lon_deg, m.rotation.pole_lat_deg) : PoleRotation();
}

}  // namespace

MeshLocator::MeshLocator(const mesh::Mesh& mesh) : mesh_(mesh), rotation_(rotation_of(mesh)) {
  const Lattice& lat = mesh.lattice;
  if (mesh.triangles.empty())
    throw InternalError("MeshLocator: the mesh has no triangles (mesh.elements = \"squares\")");
  root_shift_ = lat.levels;
  n0x_ = lat.nx >> root_shift_;
  const std::int64_t roots = n0x_ * (lat.ny >> root_shift_);
  const auto ns = static_cast<std::size_t>(mesh.square_count());
  root_start_.assign(static_cast<std::size_t>(roots) + 1, 0);
  morton_.resize(ns);
  std::int64_t prev_root = -1;
  for (std::size_t k = 0; k < ns; ++k) {
    const NodeId sw = mesh.squares[k][0];
    const std::int64_t I = mesh.node_i[static_cast<std::size_t>(sw)], J = mesh.node_j[static_cast<std::size_t>(sw)];
    const std::int64_t root = (J >> root_shift_) * n0x_ + (I >> root_shift_);
    const std::int64_t mask = (std::int64_t{1} << root_shift_) - 1;
    morton_[k] = quadtree::bits::morton(static_cast<std::uint64_t>(I & mask), static_cast<std::uint64_t>(J & mask));
    if (root < prev_root || root >= roots || (root == prev_root && morton_[k] <= morton_[k - 1])) {
      throw InternalError(
          fmt::format("MeshLocator: square {} is out of the leaf order (level-0 row-major, Morton)", k));
    }
    prev_root = root;
    ++root_start_[static_cast<std::size_t>(root) + 1];
  }
  for (std::size_t r = 1; r < root_start_.size(); ++r) root_start_[r] += root_start_[r - 1];
  first_triangle_.assign(ns + 1, 0);
  ElementId prev = -1;
  for (const ElementId s : mesh.triangle_square) {
    if (s < prev || s >= static_cast<ElementId>(ns)) throw InternalError("MeshLocator: triangles not in square order");
    prev = s;
    ++first_triangle_[static_cast<std::size_t>(s) + 1];
  }
  for (std::size_t k = 1; k < first_triangle_.size(); ++k) first_triangle_[k] += first_triangle_[k - 1];
}

ElementId MeshLocator::find_square(std::int64_t i, std::int64_t j) const {
  const Lattice& lat = mesh_.lattice;
  if (j < 0 || j >= lat.ny) return -1;
  i = wrap_index(i, lat.nx);
  const std::int64_t root = (j >> root_shift_) * n0x_ + (i >> root_shift_);
  const std::int64_t mask = (std::int64_t{1} << root_shift_) - 1;
  const std::uint64_t key =
      quadtree::bits::morton(static_cast<std::uint64_t>(i & mask), static_cast<std::uint64_t>(j & mask));
  const auto begin = morton_.begin() + root_start_[static_cast<std::size_t>(root)];
  const auto end = morton_.begin() + root_start_[static_cast<std::size_t>(root) + 1];
  auto it = std::upper_bound(begin, end, key);
  if (it == begin) return -1;
  const auto k = static_cast<std::size_t>(std::distance(morton_.begin(), it) - 1);
  const NodeId sw = mesh_.squares[k][0];
  const std::int64_t I0 = mesh_.node_i[static_cast<std::size_t>(sw)], J0 = mesh_.node_j[static_cast<std::size_t>(sw)];
  const std::int64_t size = lat.pixels_per_square(mesh_.square_level[k]);
  return (i >= I0 && i < I0 + size && j >= J0 && j < J0 + size) ? static_cast<ElementId>(k) : -1;
}

MeshLocation MeshLocator::locate_geographic(double lon_deg, double lat_deg) const {
  double rlon = lon_deg, rlat = lat_deg;
  if (!rotation_.identity()) rotation_.to_rotated(lon_deg, lat_deg, rlon, rlat);
  return locate_lattice(rlon, rlat);
}

MeshLocation MeshLocator::locate_lattice(double rlon_deg, double rlat_deg) const {
  const Lattice& lat = mesh_.lattice;
  const double d = lat.pixel_deg();
  const auto nx = static_cast<double>(lat.nx);
  double x = (wrap_lon_deg(rlon_deg, lat.lon0_deg) - lat.lon0_deg) / d;
  if (x >= nx) x -= nx;
  const double y = lat.row_of_lat(rlat_deg);  // the lattice plane: linear in the Mercator ordinate there
  MeshLocation best;
  if (!std::isfinite(x) || !std::isfinite(y)) return best;
  double best_min = -1e300;
  const auto candidates = [](double v, std::int64_t out[3]) {
    const double f = std::floor(v);
    const auto c = static_cast<std::int64_t>(f);
    int n = 0;
    out[n++] = c;
    if (v - f < kEdgeTolerancePx) out[n++] = c - 1;
    if (v - f > 1.0 - kEdgeTolerancePx) out[n++] = c + 1;
    return n;
  };
  std::int64_t ci[3], cj[3];
  const int ni = candidates(x, ci), nj = candidates(y, cj);
  for (int b = 0; b < nj; ++b) {
    for (int a = 0; a < ni; ++a) {
      const ElementId k = find_square(ci[a], cj[b]);
      if (k < 0) continue;
      const auto ks = static_cast<std::size_t>(k);
      const NodeId sw = mesh_.squares[ks][0];
      const std::int64_t I0 = mesh_.node_i[static_cast<std::size_t>(sw)],
                         J0 = mesh_.node_j[static_cast<std::size_t>(sw)];
      const std::int64_t size = lat.pixels_per_square(mesh_.square_level[ks]);
      double xs = x;
      if (xs < static_cast<double>(I0) - 0.5 * nx) xs += nx;
      if (xs > static_cast<double>(I0 + size) + 0.5 * nx) xs -= nx;
      const double px = xs - static_cast<double>(I0), py = y - static_cast<double>(J0);
      for (std::int64_t t = first_triangle_[ks]; t < first_triangle_[ks + 1]; ++t) {
        const auto& tri = mesh_.triangles[static_cast<std::size_t>(t)];
        double X[3], Y[3];
        for (int q = 0; q < 3; ++q) {
          X[q] = static_cast<double>(mesh_.unwrapped_i(tri, tri[static_cast<std::size_t>(q)]) - I0);
          Y[q] = static_cast<double>(mesh_.node_j[static_cast<std::size_t>(tri[static_cast<std::size_t>(q)])] - J0);
        }
        const double det = (Y[1] - Y[2]) * (X[0] - X[2]) + (X[2] - X[1]) * (Y[0] - Y[2]);
        const double w0 = ((Y[1] - Y[2]) * (px - X[2]) + (X[2] - X[1]) * (py - Y[2])) / det;
        const double w1 = ((Y[2] - Y[0]) * (px - X[2]) + (X[0] - X[2]) * (py - Y[2])) / det;
        const double w2 = 1.0 - w0 - w1;
        const double m = std::min({w0, w1, w2});
        if (m > best_min) {
          best_min = m;
          best.triangle = t;
          best.nodes = tri;
          best.weights = {w0, w1, w2};
          best.square = k;
          best.level = mesh_.square_level[ks];
          best.lattice_lon_deg = lat.lon0_deg + (static_cast<double>(I0) + px) * d;
          best.lattice_row = static_cast<double>(J0) + py;
          best.lattice_lat_deg = lat.lat_of_row(best.lattice_row);
        }
      }
    }
  }
  if (best_min < -kInsideTolerance) return MeshLocation{};
  // A point on an element edge gets weights like -1e-11 from the rounding of its pixel
  // coordinates: clamp them to 0 and renormalise (moves the point by < 1e-9 pixel).
  double sum = 0.0;
  for (double& w : best.weights) sum += (w = std::max(w, 0.0));
  for (double& w : best.weights) w /= sum;
  return best;
}

}  // namespace aq::handoff
