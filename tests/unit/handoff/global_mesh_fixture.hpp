// SPDX-License-Identifier: GPL-3.0-or-later
// A real small global mesh for the hand-off tests: ETOPO60 (1°), Δ0 = 4°, L = 3, K = 2, h = 0,
// optionally with the seed's rotated pole, on the lon-lat or the Mercator lattice (rows to
// ±86.5°, as configs/global_mercator.toml; it needs the rotation, which puts the caps beyond the
// rows on Greenland and East Antarctica); built once per process and configuration.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <utility>

#include "config/options.hpp"
#include "core/lattice.hpp"
#include "core/log.hpp"
#include "core/rotation.hpp"
#include "mask/wet_area.hpp"
#include "mesh/build_mesh.hpp"
#include "quadtree/build_leaves.hpp"
#include "raster/bathymetry.hpp"

namespace aq::testing {

struct GlobalMeshFixture {
  config::GlobalConfig config;
  Lattice lattice;
  PoleRotation rotation;
  std::unique_ptr<raster::Bathymetry> bathy;
  mask::WetArea area;
  mesh::Mesh mesh;
};

inline const GlobalMeshFixture& etopo60_mesh(bool rotated, LatticeKind kind = LatticeKind::kLonLat) {
  static std::map<std::pair<bool, LatticeKind>, std::unique_ptr<GlobalMeshFixture>> cache;
  auto& slot = cache[{rotated, kind}];
  if (slot) return *slot;
  auto f = std::make_unique<GlobalMeshFixture>();
  config::GlobalConfig& c = f->config;
  c.input.path = std::string(AQ_ETOPO_DIR) + "/etopo60.cdf";
  c.quadtree.step_deg = 4.0;
  c.quadtree.levels = 3;
  c.mask.passages = false;
  c.rotation.enabled = rotated;
  c.quadtree.lattice = kind;
  f->lattice = kind == LatticeKind::kMercator
                   ? Lattice::make_mercator(c.quadtree.step_deg, c.quadtree.levels, c.quadtree.lon0_deg,
                                            c.quadtree.mercator_lat_max_deg)
                   : Lattice::make(c.quadtree.step_deg, c.quadtree.levels, c.quadtree.lon0_deg);
  f->rotation = rotated ? PoleRotation(c.rotation.pole_lon_deg, c.rotation.pole_lat_deg) : PoleRotation();
  raster::OpenOptions ro;
  ro.path = c.input.path;
  f->bathy = std::make_unique<raster::Bathymetry>(raster::Bathymetry::open(ro));
  f->area = mask::compute_wet_area(*f->bathy, f->lattice, f->rotation, c.mask, Logger::null(), nullptr);
  const auto leaves = quadtree::build_leaves(f->area.filled, f->lattice, c.quadtree, f->rotation, f->bathy.get(),
                                             Logger::null(), nullptr);
  f->mesh = mesh::build_mesh(leaves, f->lattice, f->rotation, *f->bathy, c.mesh, Logger::null(), nullptr);
  slot = std::move(f);
  return *slot;
}

}  // namespace aq::testing
