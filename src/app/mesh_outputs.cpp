// Writing every requested output of a global mesh run (see mesh_outputs.hpp).
#include "app/mesh_outputs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <optional>

#include "core/error.hpp"
#include "core/timer.hpp"
#include "mesh_files/fort14_writer.hpp"
#include "mesh_files/geographic_mesh.hpp"
#include "mesh_files/msh_writer.hpp"
#include "mesh_files/text_writer.hpp"
#include "mesh_files/ugrid_writer.hpp"
#include "mesh_files/vtu_writer.hpp"
#include "pictures/preview_png.hpp"

namespace aq::io {

namespace {

PreviewOptions preview_options(const config::OutputOptions& o, ElementKinds elements) {
  PreviewOptions p;
  p.width_px = o.png_width;
  p.elements = elements;
  p.zoom = o.png_zoom;
  p.title = fmt::format("aquatoria mesh '{}'", o.name);
  return p;
}

std::vector<std::string> requested_formats(const config::OutputOptions& o) {
  std::vector<std::string> out;
  for (const auto& f : o.formats)
    if (std::find(out.begin(), out.end(), f) == out.end()) out.push_back(f);
  return out;
}

std::string facts_text(const std::vector<std::pair<std::string, std::int64_t>>& facts) {
  std::string s;
  for (const auto& [k, v] : facts) s += fmt::format(", {} {}", v, k);
  return s;
}

}  // namespace

const std::vector<std::string>& known_output_formats() {
  static const std::vector<std::string> formats{"msh", "ugrid", "vtu", "fort14", "text", "png"};
  return formats;
}

void check_mesh_output_options(const config::OutputOptions& o, ElementKinds elements) {
  const auto& known = known_output_formats();
  for (const auto& f : o.formats) {
    if (std::find(known.begin(), known.end(), f) == known.end()) {
      throw ConfigError(fmt::format("output.formats: unknown format \"{}\" (known: {})", f, fmt::join(known, ", ")));
    }
    if (f == "fort14" && !has_triangles(elements)) {
      throw ConfigError(
          "output.formats: \"fort14\" needs triangles but mesh.elements = \"squares\" (ADCIRC meshes are "
          "triangular; use mesh.elements = \"both\" or drop fort14)");
    }
  }
  if (o.name.empty() || o.name.find('/') != std::string::npos || o.name == "." || o.name == "..") {
    throw ConfigError(fmt::format("output.name = \"{}\": must be a plain file name (no '/')", o.name));
  }
  parse_vtu_coordinates(o.vtu_coordinates);
  check_preview_options(preview_options(o, elements));
}

std::vector<WrittenFile> write_mesh_outputs(const mesh::Mesh& mesh, const raster::Bathymetry& bathy,
                                            const config::OutputOptions& options, OutputSet& outputs, const Logger& log,
                                            const MeshOutputInfo& info, Report* report) {
  check_mesh_output_options(options, info.elements);
  check_elements(mesh, info.elements);
  std::vector<WrittenFile> written;

  // Writers in geographic coordinates get the mesh without the degenerate pole row (made once,
  // when the first of them needs it; fort.14 always writes triangles).
  const ElevationSampler elevation = [&](const std::vector<double>& lon, const std::vector<double>& lat,
                                         std::vector<double>& out) {
    out.resize(lon.size());
    bathy.sample_points(lon.data(), lat.data(), static_cast<std::int64_t>(lon.size()), out.data());
  };
  std::optional<GeographicMesh> geo, geo_triangles;
  auto geographic = [&](ElementKinds kinds) -> const mesh::Mesh& {
    std::optional<GeographicMesh>& g = kinds == info.elements ? geo : geo_triangles;
    if (!g) {
      g.emplace(mesh, kinds, elevation);
      for (const auto& line : g->describe()) log.info("geographic mesh: {}", line);
      // "geographic_mesh": the mesh of UGRID/text/VTU; with mesh.elements = "both" fort.14 writes
      // the triangles with the pole cap, reported as "geographic_mesh_fort14".
      if (report != nullptr)
        (*report)[kinds == info.elements ? "geographic_mesh" : "geographic_mesh_fort14"] = g->json();
    }
    return g->mesh();
  };

  auto write = [&](const std::string& format, const std::string& file,
                   const std::function<WriteStats(const std::filesystem::path&)>& writer,
                   const std::function<std::vector<std::pair<std::string, std::int64_t>>(const WriteStats&)>& facts) {
    const std::filesystem::path tmp = outputs.temp_path(file);
    const Timer timer;
    WrittenFile w;
    w.stats = writer(tmp);
    w.seconds = timer.wall_s();
    w.name = file;
    w.format = format;
    w.path = outputs.final_path(file);
    w.bytes = w.stats.bytes;
    w.facts = facts(w.stats);
    log.info("output: {} ({}, {} bytes, {:.3f} s{})", file, format, w.bytes, w.seconds, facts_text(w.facts));
    written.push_back(std::move(w));
  };
  using Facts = std::vector<std::pair<std::string, std::int64_t>>;
  const std::string& name = options.name;

  for (const auto& format : requested_formats(options)) {
    if (format == "msh") {
      MshOptions o;
      o.binary = options.msh_binary;
      o.elements = info.elements;
      write(
          format, name + ".msh", [&](const auto& p) { return write_msh(mesh, p, o); },
          [](const WriteStats& s) {
            return Facts{{"nodes", s.nodes}, {"elements", s.elements}, {"seam duplicates", s.seam_duplicates}};
          });
    } else if (format == "ugrid") {
      UgridOptions o;
      o.elements = info.elements;
      o.source = info.source;
      o.history = fmt::format("written by aquatoria ({})", info.source);
      write(
          format, name + ".nc", [&](const auto& p) { return write_ugrid(geographic(info.elements), p, o); },
          [](const WriteStats& s) {
            return Facts{{"nodes", s.nodes}, {"faces", s.elements}};
          });
    } else if (format == "vtu") {
      VtuOptions o;
      o.coordinates = parse_vtu_coordinates(options.vtu_coordinates);
      o.elements = info.elements;
      write(
          format, name + ".vtu", [&](const auto& p) { return write_vtu(geographic(info.elements), p, o); },
          [](const WriteStats& s) {
            return Facts{{"points", s.nodes},
                         {"cells", s.elements},
                         {"merged pole nodes", s.merged_pole_nodes},
                         {"dropped degenerate cells", s.dropped_elements}};
          });
    } else if (format == "fort14") {
      Fort14Options o;
      o.title = fmt::format("aquatoria mesh {} ({})", name, info.source);
      write(
          format, name + ".14", [&](const auto& p) { return write_fort14(geographic(ElementKinds::kTriangles), p, o); },
          [](const WriteStats& s) {
            return Facts{{"nodes", s.nodes}, {"triangles", s.elements}, {"land boundary edges", s.boundary_edges}};
          });
    } else if (format == "text") {
      TextOptions o;
      o.elements = info.elements;
      write(
          format, name + ".txt", [&](const auto& p) { return write_text(geographic(info.elements), p, o); },
          [](const WriteStats& s) {
            return Facts{{"nodes", s.nodes}, {"elements", s.elements}};
          });
    } else if (format == "png") {
      const PreviewOptions o = preview_options(options, info.elements);
      write(
          format, name + ".png", [&](const auto& p) { return write_preview_png(mesh, bathy, p, o); },
          [](const WriteStats& s) {
            return Facts{{"elements drawn", s.elements}};
          });
      if (!options.png_zoom.empty()) {
        write(
            "png_zoom", name + "_zoom.png", [&](const auto& p) { return write_preview_zoom_png(mesh, bathy, p, o); },
            [](const WriteStats&) { return Facts{}; });
      }
    }
  }
  return written;
}

std::vector<WrittenFile> write_mesh_outputs(const mesh::Mesh& mesh, const raster::Bathymetry& bathy,
                                            const config::OutputOptions& options, OutputSet& outputs,
                                            const Logger& log) {
  MeshOutputInfo info;
  info.elements = default_element_kinds(mesh);
  return write_mesh_outputs(mesh, bathy, options, outputs, log, info);
}

}  // namespace aq::io
