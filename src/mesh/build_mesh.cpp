// SPDX-License-Identifier: GPL-3.0-or-later
// The mesh stage: nodes, squares, template triangles, boundary (see build_mesh.hpp).
#include "mesh/build_mesh.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>

#include "core/cancel.hpp"
#include "core/error.hpp"
#include "core/timer.hpp"
#include "core/types.hpp"
#include "quadtree/nodes.hpp"
#include "quadtree/parallel.hpp"
#include "raster/bathymetry.hpp"

namespace aq::mesh {

static_assert(static_cast<int>(kNodeBoundary) == quadtree::kBoundaryNode);
static_assert(static_cast<int>(kNodeMidside) == quadtree::kMidsideNode);
static_assert(static_cast<int>(kNodeCentre) == quadtree::kCentreNode);
static_assert(static_cast<int>(kNodePole) == quadtree::kPoleNode);
static_assert(static_cast<int>(kNodeSeam) == quadtree::kSeamNode);

namespace {

double round3(double x) { return std::round(x * 1000.0) / 1000.0; }

}  // namespace

void emit_triangles(const std::vector<quadtree::Leaf>& leaves, const std::vector<std::uint8_t>& codes,
                    const std::vector<NodeId>& centres, Diagonal diagonal, Mesh& mesh) {
  const auto n = static_cast<std::int64_t>(mesh.squares.size());
  if (static_cast<std::int64_t>(leaves.size()) != n || static_cast<std::int64_t>(codes.size()) != n ||
      static_cast<std::int64_t>(centres.size()) != n || static_cast<std::int64_t>(mesh.square_midside.size()) != n) {
    throw InternalError("emit_triangles: leaves, codes, centres and squares differ in size");
  }
  const int blocks = quadtree::block_count(n, 8);
  std::vector<std::int64_t> offset(static_cast<std::size_t>(blocks), 0);
  quadtree::for_each_block(n, blocks, [&](int t, std::int64_t begin, std::int64_t end) {
    std::int64_t c = 0;
    for (std::int64_t k = begin; k < end; ++k) c += triangle_count(codes[static_cast<std::size_t>(k)]);
    offset[static_cast<std::size_t>(t)] = c;
  });
  const auto base = static_cast<std::int64_t>(mesh.triangles.size());
  const std::int64_t total = quadtree::exclusive_scan_in_place(offset);
  mesh.triangles.resize(static_cast<std::size_t>(base + total));
  mesh.triangle_level.resize(static_cast<std::size_t>(base + total));
  mesh.triangle_square.resize(static_cast<std::size_t>(base + total));
  std::array<NodeId, 3>* tri = mesh.triangles.data();
  std::uint8_t* level = mesh.triangle_level.data();
  ElementId* square = mesh.triangle_square.data();
  quadtree::for_each_block(n, blocks, [&](int t, std::int64_t begin, std::int64_t end) {
    std::int64_t pos = base + offset[static_cast<std::size_t>(t)];
    for (std::int64_t k = begin; k < end; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      const unsigned code = codes[kk];
      const quadtree::Leaf& f = leaves[kk];
      const std::array<NodeId, 4>& c = mesh.squares[kk];
      const std::array<NodeId, 4>& m = mesh.square_midside[kk];
      const std::array<NodeId, 9> v{c[0], c[1], c[2], c[3], m[0], m[1], m[2], m[3], centres[kk]};
      if (code != 0 && v[kCentre] < 0) {
        throw InternalError(fmt::format("emit_triangles: square {} has midside code {} but no centre node", k, code));
      }
      const Template& tp = template_for(code, uses_nw_diagonal(diagonal, f.a, f.b));
      for (unsigned q = 0; q < tp.count; ++q, ++pos) {
        const auto p = static_cast<std::size_t>(pos);
        tri[p] = {v[tp.tri[q][0]], v[tp.tri[q][1]], v[tp.tri[q][2]]};
        level[p] = static_cast<std::uint8_t>(f.level);
        square[p] = k;
      }
    }
  });
}

bool mesh_needs_centres(const config::MeshOptions& options) { return config::has_triangles(options.elements); }

Mesh build_mesh(const std::vector<quadtree::Leaf>& leaves, const Lattice& lat, const PoleRotation& rotation,
                const raster::Bathymetry& bathy, const config::MeshOptions& options, const Logger& log,
                Report* report) {
  StageScope stage("mesh", report, log);
  const bool triangles = mesh_needs_centres(options);

  Timer t_nodes;
  quadtree::QuadNodes qn = quadtree::build_nodes(leaves, lat, quadtree::NodeOptions{triangles});
  const double nodes_s = t_nodes.wall_s();
  throw_if_cancelled();  // between the steps (core/cancel.hpp)
  return build_mesh(leaves, std::move(qn), nodes_s, lat, rotation, bathy, options, log, report, stage);
}

Mesh build_mesh(const std::vector<quadtree::Leaf>& leaves, quadtree::QuadNodes qn, double nodes_s, const Lattice& lat,
                const PoleRotation& rotation, const raster::Bathymetry& bathy, const config::MeshOptions& options,
                const Logger& log, Report* report, StageScope& stage) {
  const Diagonal diagonal = options.diagonal;
  const bool triangles = config::has_triangles(options.elements);

  Mesh mesh;
  mesh.lattice = lat;
  mesh.rotation.enabled = !rotation.identity();
  if (mesh.rotation.enabled) {
    rotation.to_geographic(0.0, 90.0, mesh.rotation.pole_lon_deg, mesh.rotation.pole_lat_deg);
  }

  // Nodes: coordinates, depths, flags.
  Timer t_coords;
  const std::int64_t n = qn.node_count();
  mesh.node_i = std::move(qn.node_i);
  mesh.node_j = std::move(qn.node_j);
  mesh.node_flags = std::move(qn.node_flags);
  mesh.lon_deg.resize(static_cast<std::size_t>(n));
  mesh.lat_deg.resize(static_cast<std::size_t>(n));
  mesh.rlon_deg.resize(static_cast<std::size_t>(n));
  mesh.rlat_deg.resize(static_cast<std::size_t>(n));
  mesh.depth_m.resize(static_cast<std::size_t>(n));
  const bool rotated = mesh.rotation.enabled;
  // Rotated: the sines and cosines of every lattice column and row once (nodes sit on lattice
  // vertices), then the rotation; the same bits as to_geographic in degrees, which takes them
  // from the same angles.
  std::vector<double> cos_i, sin_i, cos_j, sin_j;
  if (rotated) {
    for (std::int64_t i = 0; i <= lat.nx; ++i) {
      cos_i.push_back(std::cos(lat.lon_of(i) * kDegToRad));
      sin_i.push_back(std::sin(lat.lon_of(i) * kDegToRad));
    }
    for (std::int64_t j = 0; j <= lat.ny; ++j) {
      cos_j.push_back(std::cos(lat.lat_of(j) * kDegToRad));
      sin_j.push_back(std::sin(lat.lat_of(j) * kDegToRad));
    }
  }
#pragma omp parallel for default(none) if (quadtree::parallel_worth(n * (rotated ? 32 : 2))) \
    shared(mesh, lat, rotation, n, rotated, cos_i, sin_i, cos_j, sin_j) schedule(static)
  for (std::int64_t k = 0; k < n; ++k) {
    const auto p = static_cast<std::size_t>(k);
    const double rlon = lat.lon_of(mesh.node_i[p]);
    const double rlat = lat.lat_of(mesh.node_j[p]);
    mesh.rlon_deg[p] = rlon;
    mesh.rlat_deg[p] = rlat;
    if (rotated) {
      double lon = 0.0, la = 0.0;
      const auto i = static_cast<std::size_t>(mesh.node_i[p]), j = static_cast<std::size_t>(mesh.node_j[p]);
      rotation.to_geographic(cos_i[i], sin_i[i], cos_j[j], sin_j[j], lon, la);
      mesh.lon_deg[p] = wrap_lon_deg(lon, lat.lon0_deg);
      mesh.lat_deg[p] = la;
    } else {
      mesh.lon_deg[p] = rlon;
      mesh.lat_deg[p] = rlat;
    }
  }
  const double coords_s = t_coords.wall_s();
  throw_if_cancelled();
  Timer t_depth;
  bathy.sample_points(mesh.lon_deg.data(), mesh.lat_deg.data(), n, mesh.depth_m.data(), log.progress("depths"));
  const double depth_s = t_depth.wall_s();
  throw_if_cancelled();

  // Squares and triangles.
  Timer t_tri;
  mesh.squares = std::move(qn.corners);
  mesh.square_midside = std::move(qn.midside);
  mesh.square_level.resize(leaves.size());
  for (std::size_t k = 0; k < leaves.size(); ++k) mesh.square_level[k] = static_cast<std::uint8_t>(leaves[k].level);
  if (triangles) emit_triangles(leaves, qn.midside_code, qn.centre, diagonal, mesh);
  const double tri_s = t_tri.wall_s();

  // Boundary.
  mesh.boundary_edges = std::move(qn.boundary_edges);
  mesh.boundary_edge_loop = std::move(qn.boundary_edge_loop);
  mesh.loops.resize(qn.loops.size());
  std::int64_t pole_loops = 0;
  for (std::size_t l = 0; l < qn.loops.size(); ++l) {
    const quadtree::LoopInfo& info = qn.loops[l];
    BoundaryLoop& loop = mesh.loops[l];
    loop.outer = info.outer;
    loop.pole = info.pole;
    pole_loops += info.pole;
    loop.nodes.resize(static_cast<std::size_t>(info.edge_count));
    for (std::int64_t e = 0; e < info.edge_count; ++e) {
      loop.nodes[static_cast<std::size_t>(e)] = mesh.boundary_edges[static_cast<std::size_t>(info.first_edge + e)][0];
    }
  }
  mesh.pinch_nodes = std::move(qn.pinch_nodes);

  // Counts for the report and the stage line.
  std::vector<std::int64_t> squares_per_level(static_cast<std::size_t>(lat.levels) + 1, 0);
  std::vector<std::int64_t> triangles_per_level(squares_per_level.size(), 0);
  std::vector<std::int64_t> codes(16, 0);
  for (std::size_t k = 0; k < leaves.size(); ++k) {
    ++squares_per_level[static_cast<std::size_t>(leaves[k].level)];
    ++codes[qn.midside_code[k]];
    if (triangles) {
      triangles_per_level[static_cast<std::size_t>(leaves[k].level)] += triangle_count(qn.midside_code[k]);
    }
  }
  std::int64_t midside = 0, centres = 0, boundary_nodes = 0;
  for (const std::uint8_t f : mesh.node_flags) {
    midside += (f & kNodeMidside) != 0;
    centres += (f & kNodeCentre) != 0;
    boundary_nodes += (f & kNodeBoundary) != 0;
  }
  if (pole_loops > 0) {
    log.warn(
        "mesh: the filled set reaches the lattice edge at φ = ±90°: {} pole loop(s) whose nodes are one "
        "physical point each; consider rotation.enabled = true to put the poles on land",
        pole_loops);
  }
  if (!mesh.pinch_nodes.empty()) {
    log.info(
        "mesh: {} pinch vertices (the wet area touches itself at a single corner); the model formats (fort14, "
        "fesom, schism) are written without them, and mask.remove_pinches = true removes them from the mesh",
        mesh.pinch_nodes.size());
  }
  if (report != nullptr) {
    Json& j = (*report)["mesh"];
    j["elements"] = std::string(name_of(options.elements));
    j["diagonal"] = std::string(name_of(options.diagonal));
    j["nodes"] = n;
    j["corner_nodes"] = n - centres;
    j["centre_nodes"] = centres;
    j["midside_nodes"] = midside;
    j["boundary_nodes"] = boundary_nodes;
    j["squares"] = mesh.square_count();
    j["squares_per_level"] = squares_per_level;
    j["triangles"] = mesh.triangle_count();
    j["triangles_per_level"] = triangles_per_level;
    j["squares_per_template_code"] = codes;
    j["boundary_edges"] = mesh.boundary_edges.size();
    j["boundary_loops"] = mesh.loops.size();
    j["pole_loops"] = pole_loops;
    Json pinches = Json::array();
    for (std::size_t k = 0; k < mesh.pinch_nodes.size() && k < 100; ++k) {
      const auto p = static_cast<std::size_t>(mesh.pinch_nodes[k]);
      pinches.push_back(
          Json{{"node", mesh.pinch_nodes[k]}, {"lon_deg", mesh.lon_deg[p]}, {"lat_deg", mesh.lat_deg[p]}});
    }
    j["pinch_nodes"] = mesh.pinch_nodes.size();
    j["pinch_positions"] = pinches;
    if (mesh.rotation.enabled) {
      j["rotation"] = Json{{"pole_lon_deg", mesh.rotation.pole_lon_deg}, {"pole_lat_deg", mesh.rotation.pole_lat_deg}};
    }
    j["timings_s"] = Json{{"nodes", round3(nodes_s)},
                          {"coordinates", round3(coords_s)},
                          {"depths", round3(depth_s)},
                          {"squares_triangles", round3(tri_s)}};
  }
  stage.done(fmt::format("{} nodes, {} squares, {} triangles, {} boundary loops, {} pinches", n, mesh.square_count(),
                         mesh.triangle_count(), mesh.loops.size(), mesh.pinch_nodes.size()));
  return mesh;
}

}  // namespace aq::mesh
