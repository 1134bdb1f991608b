// The files of a global mesh run (see mesh_run.hpp).
#include "app/mesh_run.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "app/mesh_outputs.hpp"
#include "core/error.hpp"
#include "mask/global_run_file.hpp"
#include "quadtree/leaf_levels.hpp"

#ifndef AQ_VERSION
#define AQ_VERSION "dev"
#endif

namespace aq::app {

std::vector<io::WrittenFile> write_global_mesh_files(const config::GlobalConfig& c, const GlobalRun& run,
                                                     OutputSet& out, const Logger& log, Report& report) {
  const raster::Bathymetry& bathy = *run.bathy;
  const Lattice& lat = run.setup.lattice;
  io::MeshOutputInfo oinfo;
  oinfo.elements = io::parse_element_kinds(c.mesh.elements);
  oinfo.source = fmt::format("aquatoria {} from {}", AQ_VERSION, bathy.info().path);
  oinfo.global_run_file = [&](const std::filesystem::path& p) {
    const quadtree::LeafLevels levels(run.leaves, lat);
    mask::write_global_run_file(p, run.area, lat, c,
                                [&](std::int64_t j0, std::int64_t rows, std::uint8_t* o) { levels.fill(j0, rows, o); });
    io::WriteStats s;
    s.bytes = static_cast<std::int64_t>(std::filesystem::file_size(p));
    s.nodes = lat.nx * lat.ny;
    s.elements = run.area.filled_pixels;
    return s;
  };
  auto files = io::write_mesh_outputs(run.mesh, bathy, c.output, out, log, oinfo, &report);
  Json outputs = Json::array();
  for (const auto& f : files) {
    outputs.push_back(Json{{"file", f.name},
                           {"format", f.format},
                           {"bytes", f.stats.bytes},
                           {kChecksumKey, file_checksum(out.pending_path(f.name))},
                           {"seconds", std::round(f.seconds * 1000.0) / 1000.0}});
  }
  report["outputs"] = outputs;
  return files;
}

std::string write_global_report(const config::GlobalConfig& c, const Report& report, OutputSet& out) {
  const std::string report_name = c.output.name + "_report.json";
  std::ofstream rf(out.temp_path(report_name));
  rf << report.dump() << '\n';
  if (!rf) throw OutputError(fmt::format("{}: cannot write the report", out.final_path(report_name).string()));
  return report_name;
}

Json mesh_counts_json(const mesh::Mesh& m) {
  return Json{{"nodes", m.node_count()},
              {"triangles", m.triangle_count()},
              {"squares", m.square_count()},
              {"boundary_loops", m.loops.size()},
              {"pinch_nodes", m.pinch_nodes.size()}};
}

}  // namespace aq::app
