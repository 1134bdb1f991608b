// ADCIRC fort.14 writer (see fort14_writer.hpp).
#include "mesh_files/fort14_writer.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <algorithm>
#include <iterator>

#include "core/error.hpp"
#include "core/types.hpp"
#include "io/depth.hpp"
#include "io/file_writer.hpp"
#include "mesh_files/element_kinds.hpp"

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
    fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{} {} {} {}\n"), n + 1, wrap_lon_deg(mesh.lon_deg[n], -180.0),
                   mesh.lat_deg[n], depth_below_datum_m(mesh.depth_m[n]));
    f.maybe_flush();
  }
  for (std::int64_t e = 0; e < ne; ++e) {
    const auto& t = mesh.triangles[static_cast<std::size_t>(e)];
    fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{} 3 {} {} {}\n"), e + 1, t[0] + 1, t[1] + 1, t[2] + 1);
    f.maybe_flush();
  }

  const auto finish = [&](std::int64_t boundary_edges) {
    WriteStats stats;
    stats.bytes = f.close();
    stats.nodes = np;
    stats.elements = ne;
    stats.boundary_edges = boundary_edges;
    return stats;
  };
  if (mesh.typed) {
    std::int64_t nope = 0, neta = 0, nbou = 0, nvel = 0, edges = 0;
    const auto in_open_list = [&options](const mesh::BoundarySegment& sg) {
      return sg.type == mesh::BoundaryType::kOpen || (options.rivers_open && sg.type == mesh::BoundaryType::kRiver);
    };
    for (const auto& sg : mesh.segments) {
      if (in_open_list(sg)) {
        ++nope;
        neta += static_cast<std::int64_t>(sg.nodes.size());
      } else {
        ++nbou;
        nvel += static_cast<std::int64_t>(sg.nodes.size()) + (sg.closed ? 1 : 0);
        edges += static_cast<std::int64_t>(sg.nodes.size()) - (sg.closed ? 0 : 1);
      }
    }
    f.print("{} ! NOPE = number of open boundaries\n{} ! NETA = total number of open boundary nodes\n", nope, neta);
    std::int64_t k = 0;
    for (const auto& sg : mesh.segments) {
      if (!in_open_list(sg)) continue;
      if (sg.type == mesh::BoundaryType::kRiver)
        f.print("{} 0 ! open boundary {} (river inflow)\n", sg.nodes.size(), ++k);
      else
        f.print("{} 0 ! open boundary {}\n", sg.nodes.size(), ++k);
      for (const NodeId n : sg.nodes) {
        fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{}\n"), n + 1);
        f.maybe_flush();
      }
    }
    f.print("{} ! {} = number of land boundaries\n{} ! NVEL = total number of land boundary nodes\n", nbou,
            options.land_count_name, nvel);
    k = 0;
    for (const auto& sg : mesh.segments) {
      if (in_open_list(sg)) continue;
      const bool island = sg.type == mesh::BoundaryType::kIsland, river = sg.type == mesh::BoundaryType::kRiver;
      f.print("{} {} ! land boundary {} ({})\n", sg.nodes.size() + (sg.closed ? 1 : 0),
              river    ? options.river_type
              : island ? options.island_type
                       : options.mainland_type,
              ++k,
              river       ? "river inflow: specified normal flux"
              : island    ? "island"
              : sg.closed ? "mainland, closed"
                          : "mainland");
      for (const NodeId n : sg.nodes) {
        fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{}\n"), n + 1);
        f.maybe_flush();
      }
      if (sg.closed) f.print("{}\n", sg.nodes.front() + 1);
    }
    return finish(edges);
  }

  std::int64_t nvel = 0, edges = 0;
  for (const auto& loop : mesh.loops) {
    if (loop.nodes.empty()) continue;
    nvel += static_cast<std::int64_t>(loop.nodes.size()) + 1;
    edges += static_cast<std::int64_t>(loop.nodes.size());
  }
  const auto nbou = std::count_if(mesh.loops.begin(), mesh.loops.end(), [](const auto& l) { return !l.nodes.empty(); });
  f.print("0 ! NOPE = number of open boundaries\n0 ! NETA = total number of open boundary nodes\n");
  f.print("{} ! {} = number of land boundaries\n{} ! NVEL = total number of land boundary nodes\n", nbou,
          options.land_count_name, nvel);
  std::int64_t k = 0;
  for (const auto& loop : mesh.loops) {
    if (loop.nodes.empty()) continue;
    const int ibtype = loop.outer ? 0 : 1;
    f.print("{} {} ! boundary {} ({})\n", loop.nodes.size() + 1, ibtype, ++k, loop.outer ? "mainland" : "island");
    for (const NodeId n : loop.nodes) {
      fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{}\n"), n + 1);
      f.maybe_flush();
    }
    f.print("{}\n", loop.nodes.front() + 1);
  }
  return finish(edges);
}

}  // namespace aq::io
