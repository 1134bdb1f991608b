// SPDX-License-Identifier: GPL-3.0-or-later
// Plain-text mesh writer (see text_writer.hpp for the format).
#include "mesh_files/text_writer.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <iterator>
#include <vector>

#include "io/depth.hpp"
#include "io/file_writer.hpp"

namespace aq::io {

WriteStats write_text(const mesh::Mesh& mesh, const std::filesystem::path& path, const TextOptions& options) {
  check_elements(mesh, options.elements);
  FileWriter f(path);
  auto& buf = f.buffer();
  const Lattice& l = mesh.lattice;
  f.print("# aquatoria mesh, plain text format 1\n");
  // The global lattice and its indices, also from a window lattice (a regional run).
  f.print("# lattice lon0_deg={} step0_deg={} levels={} nx={} ny={}", l.lon0_deg, l.step0_deg, l.levels, l.nx_global,
          l.ny_global);
  if (l.mercator()) f.print(" kind=mercator y0_deg={}", l.y0_deg);
  f.print("\n");
  if (mesh.rotation.enabled) {
    f.print("# rotation pole_lon_deg={} pole_lat_deg={}\n", mesh.rotation.pole_lon_deg, mesh.rotation.pole_lat_deg);
  } else {
    f.print("# rotation none\n");
  }
  if (mesh.floodplain_top_m > 0.0)  // only then: the files of other meshes keep their bytes
    f.print("# floodplain: the mesh reaches land up to {} m above the datum; depth_m is negative there (dry at rest)\n",
            mesh.floodplain_top_m);
  f.print(
      "# ids are 0-based; depth_m is positive down; lon/lat are geographic degrees; i j are the\n"
      "# integer lattice coordinates (rotated system with a rotated pole), -1 -1 for a node of a pole cap;\n"
      "# flags: 1 boundary, 2 midside (hanging) node, 4 centre node, 8 pole, 16 seam, 32 pole-cap node{}\n",
      mesh.has_moved_nodes() ? ", 64 open-boundary node moved onto the domain polygon (i j: its lattice vertex)" : "");

  const std::int64_t np = mesh.node_count();
  f.print("nodes {}\n# id lon_deg lat_deg depth_m flags i j\n", np);
  for (NodeId n = 0; n < np; ++n) {
    fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{} {} {} {} {} {} {}\n"), n, mesh.lon_deg[n], mesh.lat_deg[n],
                   depth_below_datum_m(mesh.depth_m[n]), mesh.node_flags[n],
                   mesh.node_i[n] < 0 ? mesh.node_i[n] : (mesh.node_i[n] + l.i_origin) % l.nx_global,
                   mesh.node_j[n] < 0 ? mesh.node_j[n] : mesh.node_j[n] + l.j_origin);
    f.maybe_flush();
  }
  std::int64_t elements = 0;
  if (has_triangles(options.elements)) {
    f.print("triangles {}\n# id level n1 n2 n3\n", mesh.triangle_count());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& v = mesh.triangles[t];
      fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{} {} {} {} {}\n"), t, mesh.triangle_level[t], v[0], v[1],
                     v[2]);
      f.maybe_flush();
    }
    elements += mesh.triangle_count();
  }
  if (has_squares(options.elements)) {
    f.print("squares {}\n# id level sw se ne nw mid_s mid_e mid_n mid_w\n", mesh.square_count());
    const std::array<NodeId, 4> none{-1, -1, -1, -1};
    for (std::size_t s = 0; s < mesh.squares.size(); ++s) {
      const auto& c = mesh.squares[s];
      const auto& m = mesh.square_midside.empty() ? none : mesh.square_midside[s];
      fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{} {} {} {} {} {} {} {} {} {}\n"), s, mesh.square_level[s],
                     c[0], c[1], c[2], c[3], m[0], m[1], m[2], m[3]);
      f.maybe_flush();
    }
    elements += mesh.square_count();
  }
  std::vector<std::int64_t> loop_edges(mesh.loops.size(), 0);
  for (const std::int32_t id : mesh.boundary_edge_loop)
    if (id >= 0 && static_cast<std::size_t>(id) < loop_edges.size()) ++loop_edges[static_cast<std::size_t>(id)];
  f.print("loops {}\n# id outer pole edges\n", mesh.loops.size());
  for (std::size_t k = 0; k < mesh.loops.size(); ++k) {
    f.print("{} {} {} {}\n", k, mesh.loops[k].outer ? 1 : 0, mesh.loops[k].pole ? 1 : 0, loop_edges[k]);
  }
  f.print("boundary_edges {}\n# loop a b\n", mesh.boundary_edges.size());
  for (std::size_t e = 0; e < mesh.boundary_edges.size(); ++e) {
    const int loop = mesh.boundary_edge_loop.empty() ? -1 : mesh.boundary_edge_loop[e];
    fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{} {} {}\n"), loop, mesh.boundary_edges[e][0],
                   mesh.boundary_edges[e][1]);
    f.maybe_flush();
  }

  WriteStats stats;
  stats.bytes = f.close();
  stats.nodes = np;
  stats.elements = elements;
  stats.boundary_edges = static_cast<std::int64_t>(mesh.boundary_edges.size());
  return stats;
}

}  // namespace aq::io
