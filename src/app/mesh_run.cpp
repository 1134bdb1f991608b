// SPDX-License-Identifier: GPL-3.0-or-later
// The files of a global mesh run (see mesh_run.hpp).
#include "app/mesh_run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "app/mesh_outputs.hpp"
#include "core/error.hpp"
#include "io/file_writer.hpp"
#include "mask/global_run_file.hpp"
#include "quadtree/leaf_levels.hpp"

#ifndef AQ_VERSION
#define AQ_VERSION "dev"
#endif

namespace aq::app {

std::string global_mesh_source(const raster::Bathymetry& bathy) {
  return fmt::format("aquatoria {} from {}", AQ_VERSION, bathy.info().path);
}

std::vector<io::WrittenFile> write_global_mesh_files(const config::GlobalConfig& c, const GlobalRun& run,
                                                     OutputSet& out, const Logger& log, Report& report) {
  const raster::Bathymetry& bathy = *run.bathy;
  const Lattice& lat = run.setup.lattice;
  io::MeshOutputInfo oinfo;
  oinfo.elements = c.mesh.elements;
  oinfo.source = global_mesh_source(bathy);
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
  if (run.size_field.has_grid()) {  // the field's range, and its value per triangle for "target"
    const size::SizeField& field = run.size_field;
    const mesh::Mesh& m = run.mesh;
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (const quadtree::Leaf& f : run.leaves) {
      const double v = field.grid_min_over_square(f.level, f.a, f.b);
      if (std::isfinite(v)) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    }
    if (hi > 0.0) oinfo.size_scale_km = {std::max(lo, 1e-3), hi};
    if (c.output.png_color == config::PreviewColour::kTarget) {
      oinfo.target_km.resize(m.triangles.size());
      for (std::size_t t = 0; t < m.triangles.size(); ++t) {
        // The centroid's pixel from the lattice coordinates (I unwrapped against the first node).
        std::int64_t si = 0, sj = 0;
        const std::int64_t i0 = m.node_i[static_cast<std::size_t>(m.triangles[t][0])];
        for (const NodeId n : m.triangles[t]) {
          std::int64_t i = m.node_i[static_cast<std::size_t>(n)];
          if (i - i0 > lat.nx / 2) i -= lat.nx;
          if (i0 - i > lat.nx / 2) i += lat.nx;
          si += i;
          sj += m.node_j[static_cast<std::size_t>(n)];
        }
        oinfo.target_km[t] = static_cast<float>(field.at_pixel(si / 3, std::min(sj / 3, lat.ny - 1)));
      }
    }
  }
  auto files = io::write_mesh_outputs(run.mesh, bathy, c.output, out, log, oinfo, &report);
  Json outputs = Json::array();
  for (const auto& f : files) {
    outputs.push_back(Json{{"file", f.name},
                           {"format", f.format},
                           {"bytes", f.stats.bytes},
                           {kChecksumKey, f.checksum},
                           {"seconds", std::round(f.seconds * 1000.0) / 1000.0}});
  }
  report["outputs"] = outputs;
  return files;
}

std::string write_global_report(const config::GlobalConfig& c, const Report& report, OutputSet& out) {
  const std::string report_name = c.output.name + "_report.json";
  // Through FileWriter: a full disk is an error naming the file and errno, not a short report.
  io::FileWriter rf(out.temp_path(report_name));
  rf.text(report.dump());
  rf.text("\n");
  rf.close();
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
