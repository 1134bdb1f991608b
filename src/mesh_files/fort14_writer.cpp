// SPDX-License-Identifier: GPL-3.0-or-later
// ADCIRC fort.14 writer (see fort14_writer.hpp).
#include "mesh_files/fort14_writer.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <algorithm>
#include <iterator>

#include "core/error.hpp"
#include "core/types.hpp"
#include "io/file_writer.hpp"
#include "mesh_files/element_kinds.hpp"
#include "mesh_files/model_columns.hpp"

namespace aq::io {

WriteStats write_fort14(const mesh::Mesh& mesh, const std::filesystem::path& path, const Fort14Options& options) {
  check_elements(mesh, ElementKinds::kTriangles);
  if (mesh.triangles.empty()) {
    throw InternalError(fmt::format("fort.14 writer: the mesh has no triangles ({})", path.string()));
  }
  std::string title = options.title.substr(0, std::min<std::size_t>(80, options.title.find('\n')));
  if (title.empty()) title = "aquatoria";

  FileWriter f(path);
  auto& buf = f.buffer();
  const std::int64_t np = mesh.node_count(), ne = mesh.triangle_count();
  f.print("{}\n{} {}\n", title, ne, np);
  for (NodeId n = 0; n < np; ++n) {
    fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{} {} {} {}\n"), n + 1, model_lon_deg(mesh.lon_deg[n]),
                   mesh.lat_deg[n], fort14_depth_m(mesh.depth_m[n]));
    f.maybe_flush();
  }
  for (std::int64_t e = 0; e < ne; ++e) {
    const auto& t = mesh.triangles[static_cast<std::size_t>(e)];
    fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{} 3 {} {} {}\n"), e + 1, t[0] + 1, t[1] + 1, t[2] + 1);
    f.maybe_flush();
  }

  const Fort14Boundaries b = fort14_boundaries(mesh, options);
  std::int64_t neta = 0, nvel = 0, edges = 0;
  for (const auto& o : b.open) neta += static_cast<std::int64_t>(o.nodes.size());
  for (const auto& l : b.land) {
    nvel += static_cast<std::int64_t>(l.nodes.size());
    edges += static_cast<std::int64_t>(l.nodes.size()) - 1;
  }
  f.print("{} ! NOPE = number of open boundaries\n{} ! NETA = total number of open boundary nodes\n", b.open.size(),
          neta);
  for (const auto& o : b.open) {
    f.print("{} {} ! {}\n", o.nodes.size(), o.flag, o.comment);
    for (const NodeId n : o.nodes) {
      fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{}\n"), n + 1);
      f.maybe_flush();
    }
  }
  f.print("{} ! {} = number of land boundaries\n{} ! NVEL = total number of land boundary nodes\n", b.land.size(),
          options.land_count_name, nvel);
  for (const auto& l : b.land) {
    f.print("{} {} ! {}\n", l.nodes.size(), l.flag, l.comment);
    for (const NodeId n : l.nodes) {
      fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{}\n"), n + 1);
      f.maybe_flush();
    }
  }
  WriteStats stats;
  stats.bytes = f.close();
  stats.nodes = np;
  stats.elements = ne;
  stats.boundary_edges = edges;
  return stats;
}

Fort14Boundaries fort14_boundaries(const mesh::Mesh& mesh, const Fort14Options& options) {
  Fort14Boundaries b;
  if (mesh.typed) {
    for (const auto& sg : mesh.segments) {
      Fort14Boundary l;
      l.type = sg.type;
      l.closed = sg.closed;
      l.nodes = sg.nodes;
      if (sg.closed) l.nodes.push_back(sg.nodes.front());
      const bool river = sg.type == mesh::BoundaryType::kRiver;
      if (sg.type == mesh::BoundaryType::kOpen || (options.rivers_open && river)) {
        l.comment = river ? fmt::format("open boundary {} (river inflow)", b.open.size() + 1)
                          : fmt::format("open boundary {}", b.open.size() + 1);
        b.open.push_back(std::move(l));
        continue;
      }
      const bool island = sg.type == mesh::BoundaryType::kIsland;
      l.flag = river ? options.river_type : island ? options.island_type : options.mainland_type;
      l.comment = fmt::format("land boundary {} ({})", b.land.size() + 1,
                              river       ? "river inflow: specified normal flux"
                              : island    ? "island"
                              : sg.closed ? "mainland, closed"
                                          : "mainland");
      b.land.push_back(std::move(l));
    }
    return b;
  }
  for (const auto& loop : mesh.loops) {
    if (loop.nodes.empty()) continue;
    Fort14Boundary l;
    l.type = loop.outer ? mesh::BoundaryType::kMainland : mesh::BoundaryType::kIsland;
    l.flag = loop.outer ? 0 : 1;
    l.closed = true;
    l.nodes = loop.nodes;
    l.nodes.push_back(loop.nodes.front());
    l.comment = fmt::format("boundary {} ({})", b.land.size() + 1, loop.outer ? "mainland" : "island");
    b.land.push_back(std::move(l));
  }
  return b;
}

}  // namespace aq::io
