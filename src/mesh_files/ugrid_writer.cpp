// SPDX-License-Identifier: GPL-3.0-or-later
// UGRID-1.0 netCDF writer (see ugrid_writer.hpp for the file layout): the dataset is described
// once, through io::DatasetSink, into a netCDF file or into memory.
#include "mesh_files/ugrid_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_set>
#include <vector>

#include "core/cancel.hpp"
#include "core/error.hpp"
#include "core/rotation.hpp"
#include "core/types.hpp"
#include "io/depth.hpp"
#include "io/netcdf_dataset.hpp"
#include "mesh_files/geographic_mesh.hpp"

namespace aq::io {

namespace {

// Rows per put (one block of a netCDF write). HDF5 places the chunks in the file as its chunk cache
// flushes them, so this also fixes the file's bytes: another value writes the same data in another
// layout.
constexpr std::int64_t kChunk = std::int64_t{1} << 20;
constexpr char kWgs84Wkt[] =
    "GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563]],PRIMEM[\"Greenwich\",0],"
    "UNIT[\"degree\",0.0174532925199433],AUTHORITY[\"EPSG\",\"4326\"]]";

// The faces of one topology: triangles, or square polygons with their hanging nodes.
class FaceSet {
 public:
  FaceSet(const mesh::Mesh& mesh, bool squares) : m_(mesh), squares_(squares) {
    max_nodes_ = 3;
    if (squares_) {
      max_nodes_ = 4;
      std::array<NodeId, kMaxSquarePolygon> p{};
      for (ElementId s = 0; s < m_.square_count(); ++s) max_nodes_ = std::max(max_nodes_, square_polygon(m_, s, p));
    }
  }
  [[nodiscard]] std::int64_t count() const { return squares_ ? m_.square_count() : m_.triangle_count(); }
  [[nodiscard]] int max_nodes() const { return max_nodes_; }
  int nodes(std::int64_t f, std::array<NodeId, kMaxSquarePolygon>& out) const {
    if (squares_) return square_polygon(m_, f, out);
    const auto& t = m_.triangles[static_cast<std::size_t>(f)];
    out[0] = t[0];
    out[1] = t[1];
    out[2] = t[2];
    return 3;
  }
  [[nodiscard]] int level(std::int64_t f) const {
    return squares_ ? m_.square_level[static_cast<std::size_t>(f)] : m_.triangle_level[static_cast<std::size_t>(f)];
  }

 private:
  const mesh::Mesh& m_;
  bool squares_;
  int max_nodes_ = 3;
};

// std::remainder(x, 360) (the representative of x in [-180, 180]): x itself when |x| <= 180
// (IEEE remainder rounds x / 360 = ±0.5 to the even 0), which is nearly every corner of a face
// around its centre; the library call only for the faces across the antimeridian.
double near_zero_remainder(double x) { return std::abs(x) <= 180.0 ? x : std::remainder(x, 360.0); }

std::uint64_t edge_key(NodeId a, NodeId b) {
  return (static_cast<std::uint64_t>(a) << 32) ^ static_cast<std::uint64_t>(b);
}

// Every unique edge once, in face order: a half-edge a -> b of a face is taken when a < b (each
// interior edge has exactly one such half-edge) or when it is a boundary edge. Checked against
// the half-edge count: 2 E - B must equal the number of half-edges of the faces. The edges are
// counted here and made again, chunk by chunk, while they are written (for_each_chunk): the
// whole list would be 16 bytes per edge, 0.7 GB for the 29 million triangles at 15".
class UniqueEdges {
 public:
  UniqueEdges(const mesh::Mesh& mesh, const FaceSet& faces)
      : mesh_(mesh), faces_(faces), next_(static_cast<std::size_t>(mesh.node_count()), kNone) {
    // The end of the boundary edge that starts at each node (nearly every boundary node starts
    // one); a node that starts several (a pinch), or any node of a mesh too large for 32-bit
    // numbers, is marked kSeveral and its edges go to the hash set.
    const bool small = mesh.node_count() < kSeveral;
    for (const auto& e : mesh.boundary_edges) {
      std::int32_t& x = next_[static_cast<std::size_t>(e[0])];
      if (small && x == kNone) {
        x = static_cast<std::int32_t>(e[1]);
        continue;
      }
      if (x != kSeveral) {
        if (x != kNone) several_.insert(edge_key(e[0], x));
        x = kSeveral;
      }
      several_.insert(edge_key(e[0], e[1]));
    }
    std::int64_t half_edges = 0;
    visit([&](int k) { half_edges += k; }, [&](NodeId, NodeId) { ++count_; });
    const auto b = static_cast<std::int64_t>(mesh.boundary_edges.size());
    if (2 * count_ - b != half_edges) {
      throw InternalError(
          fmt::format("UGRID writer: the mesh's {} boundary edges do not match its faces ({} half-edges, {} edges)", b,
                      half_edges, count_));
    }
  }
  [[nodiscard]] std::int64_t count() const { return count_; }
  /// Calls fn(first edge, rows, node pairs a0 b0 a1 b1 ...) for chunks of `chunk` edges in order
  /// (the last one shorter).
  template <typename Fn>
  void for_each_chunk(std::int64_t chunk, Fn&& fn) const {
    std::vector<long long> idx;
    idx.reserve(static_cast<std::size_t>(2 * std::min(chunk, count_)));
    std::int64_t first = 0;
    visit([](int) {},
          [&](NodeId u, NodeId v) {
            idx.push_back(u);
            idx.push_back(v);
            if (static_cast<std::int64_t>(idx.size()) == 2 * chunk) {
              fn(first, chunk, idx.data());
              first += chunk;
              idx.clear();
            }
          });
    if (!idx.empty()) fn(first, static_cast<std::int64_t>(idx.size()) / 2, idx.data());
  }

 private:
  // face(k) once per face with its node count k; edge(u, v) for every unique edge in order.
  template <typename Face, typename Edge>
  void visit(Face&& face, Edge&& edge) const {
    std::array<NodeId, kMaxSquarePolygon> p{};
    for (std::int64_t f = 0; f < faces_.count(); ++f) {
      const int k = faces_.nodes(f, p);
      face(k);
      for (int a = 0; a < k; ++a) {
        const NodeId u = p[a], v = p[(a + 1) % k];
        if (u < v || boundary(u, v)) edge(u, v);
      }
    }
  }

  [[nodiscard]] bool boundary(NodeId u, NodeId v) const {
    const std::int32_t x = next_[static_cast<std::size_t>(u)];
    if (x == kNone) return false;
    if (x != kSeveral) return x == v;
    return several_.count(edge_key(u, v)) > 0;
  }

  static constexpr std::int32_t kNone = -1;
  static constexpr std::int32_t kSeveral = std::numeric_limits<std::int32_t>::max();
  const mesh::Mesh& mesh_;
  const FaceSet& faces_;
  std::vector<std::int32_t> next_;             ///< by node: kNone, the boundary edge's end, or kSeveral
  std::unordered_set<std::uint64_t> several_;  ///< boundary edges of the kSeveral nodes
  std::int64_t count_ = 0;
};

struct TopologyNames {
  bool squares;  // the second topology of mesh.elements = "both": the quadtree squares
  std::string mesh, face_dim, edge_dim, max_dim, faces, edges, face_x, face_y, level;
};

// The main topology "mesh" (triangles, or the squares when they are the only elements) or the
// squares beside the triangles, "mesh_squares".
TopologyNames topology_names(bool second_squares) {
  const std::string mesh = second_squares ? "mesh_squares" : "mesh";
  const std::string cap = second_squares ? "Mesh_squares" : "Mesh";
  return {second_squares,
          mesh,
          "n" + cap + "_face",
          "n" + cap + "_edge",
          "nMax" + cap + "_face_nodes",
          mesh + "_face_nodes",
          mesh + "_edge_nodes",
          mesh + "_face_x",
          mesh + "_face_y",
          second_squares ? "level_squares" : "level"};
}

struct TopologyVars {
  int faces = -1, edges = -1, face_x = -1, face_y = -1, face_x_bnds = -1, face_y_bnds = -1, level = -1;
};

// Defines one topology's variables (the nodes and boundary are shared, defined by the caller).
TopologyVars define_topology(DatasetSink& nc, const TopologyNames& n, const FaceSet& faces, std::int64_t edge_count,
                             int two, DataType index_type, bool with_boundary, const std::string& node_coordinates) {
  TopologyVars v;
  const int face_dim = nc.dim(n.face_dim, faces.count());
  const int edge_dim = nc.dim(n.edge_dim, edge_count);
  const int max_dim = nc.dim(n.max_dim, faces.max_nodes());

  const int topo = nc.var(n.mesh, DataType::kInt, {});
  nc.text(topo, "cf_role", "mesh_topology");
  nc.text(topo, "long_name",
          n.squares ? "Topology of the quadtree squares (polygons with hanging nodes)" : "Topology of the ocean mesh");
  nc.number(topo, "topology_dimension", DataType::kInt, 2);
  nc.text(topo, "node_coordinates", node_coordinates);
  nc.text(topo, "face_node_connectivity", n.faces);
  nc.text(topo, "face_dimension", n.face_dim);
  nc.text(topo, "edge_node_connectivity", n.edges);
  nc.text(topo, "edge_dimension", n.edge_dim);
  if (with_boundary) nc.text(topo, "boundary_node_connectivity", "mesh_boundary_nodes");
  nc.text(topo, "face_coordinates", n.face_x + " " + n.face_y);

  v.faces = nc.var(n.faces, index_type, {face_dim, max_dim});
  nc.text(v.faces, "cf_role", "face_node_connectivity");
  nc.text(v.faces, "long_name", "Nodes of each face, anticlockwise");
  nc.number(v.faces, "start_index", DataType::kInt, 0);
  if (faces.max_nodes() > 3) nc.number(v.faces, "_FillValue", index_type, -1);

  v.edges = nc.var(n.edges, index_type, {edge_dim, two});
  nc.text(v.edges, "cf_role", "edge_node_connectivity");
  nc.text(v.edges, "long_name", "Nodes of each edge (every edge once)");
  nc.number(v.edges, "start_index", DataType::kInt, 0);

  v.face_x = nc.var(n.face_x, DataType::kDouble, {face_dim});
  nc.text(v.face_x, "standard_name", "longitude");
  nc.text(v.face_x, "long_name", "Longitude of the face centre");
  nc.text(v.face_x, "units", "degrees_east");
  nc.text(v.face_x, "bounds", n.face_x + "_bnds");
  v.face_y = nc.var(n.face_y, DataType::kDouble, {face_dim});
  nc.text(v.face_y, "standard_name", "latitude");
  nc.text(v.face_y, "long_name", "Latitude of the face centre");
  nc.text(v.face_y, "units", "degrees_north");
  nc.text(v.face_y, "bounds", n.face_y + "_bnds");
  v.face_x_bnds = nc.var(n.face_x + "_bnds", DataType::kDouble, {face_dim, max_dim});
  nc.text(v.face_x_bnds, "long_name", "Longitudes of the face corners, continuous around the face centre");
  nc.text(v.face_x_bnds, "units", "degrees_east");
  v.face_y_bnds = nc.var(n.face_y + "_bnds", DataType::kDouble, {face_dim, max_dim});
  nc.text(v.face_y_bnds, "long_name", "Latitudes of the face corners");
  nc.text(v.face_y_bnds, "units", "degrees_north");

  v.level = nc.var(n.level, DataType::kShort, {face_dim});
  nc.text(v.level, "long_name", "Quadtree level of the face (0 = coarsest)");
  nc.text(v.level, "units", "1");
  nc.text(v.level, "mesh", n.mesh);
  nc.text(v.level, "location", "face");
  nc.text(v.level, "coordinates", n.face_x + " " + n.face_y);
  nc.text(v.level, "grid_mapping", "crs");
  return v;
}

// Face centre (lon, lat) of face f with nodes p[0..k).
std::array<double, 2> face_centre(const mesh::Mesh& mesh, const PoleRotation& rotation,
                                  const std::array<NodeId, kMaxSquarePolygon>& p, int k) {
  const std::int64_t nx = mesh.lattice.nx;
  std::int64_t max_i = 0, min_i = 0;
  bool moved = false;
  for (int a = 0; a < k; ++a) {
    max_i = std::max(max_i, mesh.node_i[p[a]]);
    min_i = std::min(min_i, mesh.node_i[p[a]]);
    moved = moved || (mesh.node_flags[p[a]] & mesh::kNodeMoved) != 0;
  }
  double lon = 0.0, lat = 0.0;
  if (min_i < 0 || moved) {
    // A face of a pole cap (io/geographic_mesh.hpp) or with a node moved onto a domain
    // polygon (mesh/open_snap.hpp): the centre of its nodes on the sphere.
    std::array<double, 3> c{0.0, 0.0, 0.0};
    for (int a = 0; a < k; ++a) {
      const auto u = unit_vector_deg(mesh.lon_deg[p[a]], mesh.lat_deg[p[a]]);
      for (int d = 0; d < 3; ++d) c[d] += u[d];
    }
    lon = wrap_lon_deg(std::atan2(c[1], c[0]) * kRadToDeg, mesh.lattice.lon0_deg);
    lat = std::atan2(c[2], std::hypot(c[0], c[1])) * kRadToDeg;
  } else {
    double si = 0.0, sj = 0.0;
    for (int a = 0; a < k; ++a) {
      const std::int64_t i = mesh.node_i[p[a]];
      // Global columns (a window lattice's origin added as an integer: the same bits as on the global lattice).
      si += static_cast<double>((i == 0 && max_i > nx / 2 && mesh.lattice.periodic() ? nx : i) + mesh.lattice.i_origin);
      sj += static_cast<double>(mesh.node_j[p[a]]);
    }
    const double rlon = mesh.lattice.lon0_deg + si / k * mesh.lattice.pixel_deg();
    const double rlat = mesh.lattice.lat_of_row(sj / k);
    lon = rlon;
    lat = rlat;
    if (mesh.rotation.enabled) {
      rotation.to_geographic(rlon, rlat, lon, lat);
      lon = wrap_lon_deg(lon, mesh.lattice.lon0_deg);  // the nodes' convention: [λ0, λ0 + 360)
    }
  }
  return {lon, lat};
}

// The faces' variables, slab by slab (kChunk faces): a slab's arrays made together on the team,
// then written one variable at a time in the netCDF calls' fixed order, from a few buffers reused
// by every slab (about 80 MB at 15", against 105 MB per slab for arrays of their own).
// Node numbers go out in the variable's own type (int when they fit: index_type DataType::kInt).
template <typename Index>
void write_faces(DatasetSink& nc, const mesh::Mesh& mesh, const FaceSet& faces, const TopologyVars& v) {
  const int w = faces.max_nodes();
  const PoleRotation rotation =
      mesh.rotation.enabled ? PoleRotation(mesh.rotation.pole_lon_deg, mesh.rotation.pole_lat_deg) : PoleRotation();
  std::vector<Index> idx;
  std::vector<double> cx, cy, corners;
  std::vector<short> lev;
  // On the team: at 15" these loops were a tenth of the work of the UGRID file's own thread (the
  // longest of the writers); each face's values as before.
  for (std::int64_t f0 = 0; f0 < faces.count(); f0 += kChunk) {
    throw_if_cancelled();  // between blocks (core/cancel.hpp)
    const std::int64_t rows = std::min(kChunk, faces.count() - f0);
    const auto ur = static_cast<std::size_t>(rows), uw = static_cast<std::size_t>(w);
    idx.assign(ur * uw, Index{-1});
    cx.resize(ur);
    cy.resize(ur);
    corners.resize(2 * ur * uw);  // the corners' longitudes (around the centre), then latitudes
#pragma omp parallel default(none) shared(faces, mesh, rotation, idx, cx, cy, corners, f0, rows, uw, w) if (rows > 4096)
    {
      std::array<NodeId, kMaxSquarePolygon> p{};
#pragma omp for schedule(static)
      for (std::int64_t r = 0; r < rows; ++r) {
        const auto ur_ = static_cast<std::size_t>(r);
        const int k = faces.nodes(f0 + r, p);
        for (int a = 0; a < k; ++a) idx[ur_ * uw + static_cast<std::size_t>(a)] = static_cast<Index>(p[a]);
        const auto c = face_centre(mesh, rotation, p, k);
        cx[ur_] = c[0];
        cy[ur_] = c[1];
        const std::size_t lat_at = static_cast<std::size_t>(rows) * uw;
        for (int a = 0; a < w; ++a) {
          const auto n = static_cast<std::size_t>(p[std::min(a, k - 1)]);
          corners[ur_ * uw + static_cast<std::size_t>(a)] = c[0] + near_zero_remainder(mesh.lon_deg[n] - c[0]);
          corners[lat_at + ur_ * uw + static_cast<std::size_t>(a)] = mesh.lat_deg[n];
        }
      }
    }
    nc.put(v.faces, f0, rows, idx.data());
    nc.put(v.face_x, f0, rows, cx.data());
    nc.put(v.face_y, f0, rows, cy.data());
    nc.put(v.face_x_bnds, f0, rows, corners.data());
    nc.put(v.face_y_bnds, f0, rows, corners.data() + ur * uw);
    lev.resize(ur);
    for (std::size_t r = 0; r < ur; ++r) lev[r] = static_cast<short>(faces.level(f0 + static_cast<std::int64_t>(r)));
    nc.put(v.level, f0, rows, lev.data());
  }
}

void write_topology(DatasetSink& nc, const mesh::Mesh& mesh, const FaceSet& faces, const TopologyVars& v,
                    const UniqueEdges& edges, DataType index_type) {
  if (index_type == DataType::kInt)
    write_faces<int>(nc, mesh, faces, v);
  else
    write_faces<long long>(nc, mesh, faces, v);
  edges.for_each_chunk(kChunk, [&](std::int64_t e0, std::int64_t rows, const long long* pairs) {
    throw_if_cancelled();
    nc.put(v.edges, e0, rows, pairs);
  });
}

}  // namespace

UgridCounts ugrid_dataset(const mesh::Mesh& mesh, const UgridOptions& options, DatasetSink& nc) {
  check_elements(mesh, options.elements);
  const std::int64_t n = mesh.node_count();
  const bool tri = has_triangles(options.elements), sq = has_squares(options.elements);
  std::vector<FaceSet> sets;
  if (tri) sets.emplace_back(mesh, false);
  if (sq) sets.emplace_back(mesh, true);
  for (const auto& s : sets) {
    if (n == 0 || s.count() == 0)
      throw InternalError(fmt::format("UGRID writer: the mesh is empty ({})", options.what));
  }
  std::vector<UniqueEdges> edges;
  edges.reserve(sets.size());  // they refer to sets[k]: no reallocation of either
  std::int64_t largest = n;
  for (const auto& s : sets) {
    edges.emplace_back(mesh, s);
    largest = std::max({largest, s.count(), edges.back().count()});
  }
  const bool big = largest > std::numeric_limits<std::int32_t>::max();
  const DataType index_type = big ? DataType::kInt64 : DataType::kInt;
  const auto nb = static_cast<std::int64_t>(mesh.boundary_edges.size());
  const bool rotated = mesh.rotation.enabled;

  nc.start(big);
  const int g = DatasetSink::kGlobal;
  nc.text(g, "Conventions", "CF-1.8 UGRID-1.0");
  nc.text(g, "title", options.title);
  nc.text(g, "institution", "aquatoria");
  nc.text(g, "source", options.source);
  nc.text(g, "history", options.history);
  nc.text(g, "comment",
          "Faces use geographic node coordinates; faces across the antimeridian list nodes on both sides of "
          "+-180 deg: draw them with the *_face_x_bnds corners (continuous around each face centre) or in 3-D. "
          "Depth is positive down. Pole-row nodes are distinct nodes at the same point.");
  nc.text(g, "aquatoria_elements", name_of(options.elements));
  nc.number(g, "aquatoria_lattice_lon0_deg", DataType::kDouble, mesh.lattice.lon0_deg);
  nc.number(g, "aquatoria_lattice_step0_deg", DataType::kDouble, mesh.lattice.step0_deg);
  nc.number(g, "aquatoria_lattice_levels", DataType::kInt, mesh.lattice.levels);
  if (mesh.lattice.mercator()) {  // the lon-lat lattice's files stay as they were
    nc.text(g, "aquatoria_lattice_kind", "mercator");
    nc.number(g, "aquatoria_lattice_y0_deg", DataType::kDouble, mesh.lattice.y0_deg);
  }

  const int node_dim = nc.dim("nMesh_node", n);
  const int two = nc.dim("Two", 2);
  const int bnd_dim = nb > 0 ? nc.dim("nMesh_boundary", nb) : -1;

  const std::string grid_mapping = rotated ? "rotated_pole" : "crs";
  const std::string node_coords = "mesh_node_x mesh_node_y";
  const std::string all_node_coords = rotated ? node_coords + " mesh_node_rlon mesh_node_rlat" : node_coords;

  std::vector<TopologyVars> tv;
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const bool squares = sq && (!tri || k == 1);
    tv.push_back(define_topology(nc, topology_names(squares && tri), sets[k], edges[k].count(), two, index_type, nb > 0,
                                 node_coords));
  }

  const int crs = nc.var("crs", DataType::kInt, {});
  nc.text(crs, "grid_mapping_name", "latitude_longitude");
  nc.number(crs, "semi_major_axis", DataType::kDouble, 6378137.0);
  nc.number(crs, "inverse_flattening", DataType::kDouble, 298.257223563);
  nc.number(crs, "longitude_of_prime_meridian", DataType::kDouble, 0.0);
  nc.text(crs, "crs_wkt", kWgs84Wkt);
  nc.text(crs, "epsg_code", "EPSG:4326");
  if (rotated) {
    const int rp = nc.var("rotated_pole", DataType::kInt, {});
    nc.text(rp, "grid_mapping_name", "rotated_latitude_longitude");
    nc.number(rp, "grid_north_pole_latitude", DataType::kDouble, mesh.rotation.pole_lat_deg);
    nc.number(rp, "grid_north_pole_longitude", DataType::kDouble, mesh.rotation.pole_lon_deg);
    nc.number(rp, "north_pole_grid_longitude", DataType::kDouble, 180.0);
  }

  auto coord = [&](const char* name, const char* standard, const char* long_name, const char* units) {
    const int v = nc.var(name, DataType::kDouble, {node_dim});
    nc.text(v, "standard_name", standard);
    nc.text(v, "long_name", long_name);
    nc.text(v, "units", units);
    return v;
  };
  const int node_x = coord("mesh_node_x", "longitude", "Longitude of the mesh nodes", "degrees_east");
  const int node_y = coord("mesh_node_y", "latitude", "Latitude of the mesh nodes", "degrees_north");
  int node_rlon = -1, node_rlat = -1;
  if (rotated) {
    node_rlon = coord("mesh_node_rlon", "grid_longitude", "Rotated longitude of the mesh nodes", "degrees");
    node_rlat = coord("mesh_node_rlat", "grid_latitude", "Rotated latitude of the mesh nodes", "degrees");
  }

  const int depth = nc.var("depth", DataType::kDouble, {node_dim});
  nc.text(depth, "standard_name", "sea_floor_depth_below_geoid");
  // Positive down by its standard name. No `positive` attribute: CF gives it to vertical
  // coordinates only, and CDO then takes `depth` for one and skips it as data.
  nc.text(depth, "long_name", "Sea floor depth at the nodes (positive down)");
  nc.text(depth, "units", "m");
  nc.text(depth, "mesh", "mesh");
  nc.text(depth, "location", "node");
  nc.text(depth, "coordinates", all_node_coords);
  nc.text(depth, "grid_mapping", grid_mapping);
  // A node without data (a pole-cap node over a raster's no-data) holds NaN: declared then, and
  // only then, so files of meshes without one keep their bytes.
  if (std::any_of(mesh.depth_m.begin(), mesh.depth_m.end(), [](double d) { return std::isnan(d); }))
    nc.number(depth, "_FillValue", DataType::kDouble, std::numeric_limits<double>::quiet_NaN());
  // A floodplain mesh (mask.min_depth_m < 0) says what its negative depths are (only then: the
  // files of other meshes keep their bytes).
  if (mesh.floodplain_top_m > 0.0)
    nc.text(depth, "comment",
            fmt::format("Positive down from the datum; negative above it: the floodplain, land up to {} m above the "
                        "datum that is connected to the ocean (dry at rest; a model with wetting and drying floods it)",
                        mesh.floodplain_top_m));

  const int flags = nc.var("node_flags", DataType::kByte, {node_dim});
  nc.text(flags, "long_name", "Node flags");
  // The moved-node flag only where there is one (the files of other runs keep their bytes).
  const bool moved = mesh.has_moved_nodes();
  std::vector<double> masks{1, 2, 4, 8, 16, 32, 64};
  if (!moved) masks.pop_back();
  nc.numbers(flags, "flag_masks", DataType::kByte, masks);
  nc.text(flags, "flag_meanings",
          std::string("boundary midside_hanging_node centre_node pole seam pole_cap_node") +
              (moved ? " open_boundary_node_moved_onto_polygon" : ""));
  nc.text(flags, "mesh", "mesh");
  nc.text(flags, "location", "node");
  nc.text(flags, "coordinates", all_node_coords);

  int bnd = -1, bnd_loop = -1;
  if (nb > 0) {
    bnd = nc.var("mesh_boundary_nodes", index_type, {bnd_dim, two});
    nc.text(bnd, "cf_role", "boundary_node_connectivity");
    nc.text(bnd, "long_name", "Boundary (coast) edges a -> b with the wet area on the left");
    nc.number(bnd, "start_index", DataType::kInt, 0);
    bnd_loop = nc.var("mesh_boundary_loop", DataType::kInt, {bnd_dim});
    nc.text(bnd_loop, "long_name", "Boundary loop of each boundary edge (0-based)");
    int outer = -1;
    for (std::size_t l = 0; l < mesh.loops.size(); ++l)
      if (mesh.loops[l].outer) outer = static_cast<int>(l);
    nc.number(bnd_loop, "outer_loop", DataType::kInt, outer);
  }
  int bnd_type = -1;  // regional meshes: the type of each boundary edge (README "Regional FE meshes")
  const bool typed = nb > 0 && mesh.typed && mesh.boundary_edge_type.size() == static_cast<std::size_t>(nb);
  if (typed) {
    bnd_type = nc.var("mesh_boundary_type", DataType::kByte, {bnd_dim});
    nc.text(bnd_type, "long_name", "Type of each boundary edge");
    // The river flag only in a mesh that has river inflows (earlier files keep their bytes).
    const bool rivers = std::find(mesh.boundary_edge_type.begin(), mesh.boundary_edge_type.end(),
                                  mesh::BoundaryType::kRiver) != mesh.boundary_edge_type.end();
    nc.numbers(bnd_type, "flag_values", DataType::kByte,
               rivers ? std::vector<double>{0, 1, 2, 3} : std::vector<double>{0, 1, 2});
    nc.text(bnd_type, "flag_meanings", rivers ? "mainland island open river" : "mainland island open");
  }
  nc.end_definitions();

  nc.put(node_x, 0, n, mesh.lon_deg.data());
  nc.put(node_y, 0, n, mesh.lat_deg.data());
  if (rotated) {
    nc.put(node_rlon, 0, n, mesh.rlon_deg.data());
    nc.put(node_rlat, 0, n, mesh.rlat_deg.data());
  }
  {
    std::vector<double> d(static_cast<std::size_t>(n));
    for (std::size_t a = 0; a < d.size(); ++a) d[a] = depth_below_datum_m(mesh.depth_m[a]);
    nc.put(depth, 0, n, d.data());
    std::vector<signed char> fl(static_cast<std::size_t>(n));
    for (std::size_t a = 0; a < fl.size(); ++a) fl[a] = static_cast<signed char>(mesh.node_flags[a]);
    nc.put(flags, 0, n, fl.data());
  }
  if (nb > 0) {
    std::vector<long long> be(static_cast<std::size_t>(2 * nb));
    std::vector<int> loop(static_cast<std::size_t>(nb), -1);
    for (std::size_t e = 0; e < static_cast<std::size_t>(nb); ++e) {
      be[2 * e] = mesh.boundary_edges[e][0];
      be[2 * e + 1] = mesh.boundary_edges[e][1];
      if (!mesh.boundary_edge_loop.empty()) loop[e] = mesh.boundary_edge_loop[e];
    }
    nc.put(bnd, 0, nb, be.data());
    nc.put(bnd_loop, 0, nb, loop.data());
  }
  if (typed) {
    std::vector<signed char> ty(static_cast<std::size_t>(nb));
    for (std::size_t e = 0; e < ty.size(); ++e) ty[e] = static_cast<signed char>(mesh.boundary_edge_type[e]);
    nc.put(bnd_type, 0, nb, ty.data());
  }
  UgridCounts counts;
  for (std::size_t k = 0; k < sets.size(); ++k) {
    write_topology(nc, mesh, sets[k], tv[k], edges[k], index_type);
    counts.faces += sets[k].count();
  }
  counts.nodes = n;
  counts.boundary_edges = nb;
  return counts;
}

WriteStats write_ugrid(const mesh::Mesh& mesh, const std::filesystem::path& path, const UgridOptions& options) {
  NetcdfDataset nc(path, options.deflate);
  UgridOptions o = options;
  o.what = path.string();
  const UgridCounts counts = ugrid_dataset(mesh, o, nc);
  nc.close();
  WriteStats stats;
  stats.bytes = static_cast<std::int64_t>(std::filesystem::file_size(path));
  stats.nodes = counts.nodes;
  stats.elements = counts.faces;
  stats.boundary_edges = counts.boundary_edges;
  return stats;
}

}  // namespace aq::io
