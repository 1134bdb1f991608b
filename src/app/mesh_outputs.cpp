// SPDX-License-Identifier: GPL-3.0-or-later
// Writing every requested output of a global mesh run (see mesh_outputs.hpp).
#include "app/mesh_outputs.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <optional>

#include "core/error.hpp"
#include "core/timer.hpp"
#include "mesh/model_cleaning.hpp"
#include "mesh_files/fesom_writer.hpp"
#include "mesh_files/fort14_writer.hpp"
#include "mesh_files/geographic_mesh.hpp"
#include "mesh_files/msh_writer.hpp"
#include "mesh_files/schism_writer.hpp"
#include "mesh_files/sphere_quality.hpp"
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
  p.colour = o.png_color;
  return p;
}

// output.formats without repeats, in the order given.
std::vector<config::OutputFormat> requested_formats(const config::OutputOptions& o) {
  std::vector<config::OutputFormat> out;
  for (const config::OutputFormat f : o.formats)
    if (std::find(out.begin(), out.end(), f) == out.end()) out.push_back(f);
  return out;
}

}  // namespace

UgridOptions ugrid_options(const config::OutputOptions& options, const MeshOutputInfo& info) {
  UgridOptions o;
  o.elements = info.elements;
  o.source = info.source;
  o.history = fmt::format("written by aquatoria ({})", info.source);
  o.deflate = options.ugrid_deflate;
  return o;
}

ModelMeshNotes model_mesh_notes(const mesh::ModelMesh& model, double seconds) {
  ModelMeshNotes notes;
  notes.lines.push_back({LogLevel::kInfo, fmt::format("mesh cleaning: {} ({:.3f} s)", model.describe(), seconds)});
  const mesh::Mesh& c = model.mesh();
  notes.cleaning = model.json();
  if (!c.lattice.mercator()) {
    constexpr double kObtuseDeg = 120.0;
    const ObtuseTriangles o = obtuse_triangles(c, kObtuseDeg);
    notes.cleaning["angle_above_120_deg_triangles"] = o.count;
    if (o.count > 0) {
      notes.cleaning["angle_above_120_deg_from_lat_deg"] = std::round(o.from_lattice_lat_deg * 100.0) / 100.0;
      notes.lines.push_back(
          {LogLevel::kWarning,
           fmt::format("model formats: {} triangles have an angle above {:g}° on the sphere (up to {:.1f}°), "
                       "poleward of {:.1f}° {}latitude: the lon-lat lattice's squares narrow as cos φ there. "
                       "FESOM2's SSH solver needed 26-60 times the iterations on such meshes; use the Mercator "
                       "lattice (quadtree.lattice = \"mercator\", as in configs/global_mercator.toml)",
                       o.count, kObtuseDeg, o.max_angle_deg, o.from_lattice_lat_deg,
                       c.rotation.enabled ? "rotated " : "")});
    }
  }
  return notes;
}

std::optional<std::string> fesom_floodplain_warning(const mesh::Mesh& model) {
  if (model.floodplain_top_m <= 0.0) return std::nullopt;  // FESOM2 has no wetting and drying
  const auto above = std::count_if(model.depth_m.begin(), model.depth_m.end(), [](double e) { return e > 0.0; });
  if (above == 0) return std::nullopt;
  return fmt::format(
      "fesom: FESOM2 has no wetting and drying: aux3d.out writes the {} nodes of the floodplain "
      "(above the datum, up to {} m) at 0 m, and FESOM2 deepens them to its 5th level, water; "
      "mesh a surge domain for ADCIRC or SCHISM (fort14, schism), or set mask.min_depth_m >= 0",
      above, model.floodplain_top_m);
}

void check_mesh_output_options(const config::OutputOptions& o, ElementKinds elements) {
  std::string why;
  if (const std::string bad = config::output_name_problem(o.name); !bad.empty())
    why += fmt::format("\n  output.name = \"{}\": {}", o.name, bad);
  for (const config::KeyProblem& bad : config::output_problems(o, elements))
    why += fmt::format("\n  {}: {}", fmt::join(bad.keys, ", "), bad.text);
  if (!why.empty()) throw ConfigError("output options:" + why);
}

namespace {

// The files of one mesh, planned on the calling thread before any is written (see
// write_mesh_outputs): the meshes they need built once, their writers bound to them, the lines
// logged meanwhile held back (output_jobs.hpp). It must outlive the jobs it plans: their writers
// refer to its meshes.
class OutputPlanner {
 public:
  OutputPlanner(const mesh::Mesh& m, const raster::Bathymetry& b, const config::OutputOptions& o, OutputSet& out,
                const MeshOutputInfo& i, Report* r)
      : mesh(m), bathy(b), options(o), outputs(out), info(i), report(r), name(o.name) {}
  OutputPlanner(const OutputPlanner&) = delete;
  OutputPlanner& operator=(const OutputPlanner&) = delete;

  std::vector<OutputJob> jobs;
  std::vector<LogLine> pending;  ///< lines held back for the next job

  // Shape quality on the sphere of the triangles as the geographic files hold them; its
  // per-triangle values also colour the preview (output.png_color). Computed by the first job:
  // a step on the extra thread, before the UGRID file, unless the preview's job (later, on this
  // thread) reads `shapes_`; then on this thread, beside the UGRID file.
  void plan_quality() {
    if (!has_triangles(info.elements) || mesh.triangles.empty()) return;
    const Timer geo_timer;
    const mesh::Mesh& g = geographic(ElementKinds::kTriangles);
    const double geo_s = geo_timer.wall_s();
    const PreviewColour colour = options.writes(config::OutputFormat::kPng) ? options.png_color : PreviewColour::kLevel;
    OutputJob quality;
    quality.format = "quality";
    quality.step = [&g, &shapes = shapes_, report = report, geo_s, colour] {
      const Timer timer;
      shapes = triangle_shapes(g);
      const SphereQuality q = summarize_quality(*shapes);
      // Only the preview reads the values afterwards, one array at most (20 bytes per triangle
      // while the files are written, 0.6 GB at 15"): the others go.
      if (colour != PreviewColour::kAngle) std::vector<float>().swap(shapes->min_angle_deg);
      if (colour != PreviewColour::kSize) std::vector<float>().swap(shapes->size_km);
      for (auto* v : {&shapes->max_angle_deg, &shapes->edge_ratio, &shapes->neighbour_area_ratio})
        std::vector<float>().swap(*v);
      if (report != nullptr) {
        Json j = q.json();
        j["mesh"] = "geographic (as written to ugrid, vtu, text; fort14, fesom, schism write it cleaned)";
        j["seconds"] = std::round(timer.wall_s() * 1000.0) / 1000.0;
        j["cpu_seconds"] = std::round(timer.cpu_s() * 1000.0) / 1000.0;
        j["geographic_mesh_seconds"] = std::round(geo_s * 1000.0) / 1000.0;
        (*report)["quality"] = j;
      }
      return std::vector<LogLine>{{LogLevel::kInfo, fmt::format("quality: {} ({:.3f} s, {:.3f} s CPU)", q.describe(),
                                                                timer.wall_s(), timer.cpu_s())}};
    };
    // Beside the files when the preview does not colour by it (on the 1' Mercator run its
    // 0.9 s overlapped the binary MSH file's), unless the UGRID file takes the extra thread: then
    // on this one, beside it (the 15" run: 12 s of UGRID against 3.5 s of quality and 3.7 s of MSH).
    quality.own_thread = colour == PreviewColour::kLevel && !options.writes(config::OutputFormat::kUgrid);
    quality.log_before = std::move(pending);
    pending.clear();
    jobs.push_back(std::move(quality));
  }

  void plan_format(const config::OutputFormat kind) {
    using F = config::OutputFormat;
    const std::string format(name_of(kind));
    if (kind == F::kMsh) {
      MshOptions o;
      o.binary = options.msh_binary;
      o.elements = info.elements;
      plan(
          format, name + ".msh", [&mesh = mesh, o](const auto& p) { return write_msh(mesh, p, o); },
          [](const WriteStats& s) {
            return Facts{{"nodes", s.nodes}, {"elements", s.elements}, {"seam duplicates", s.seam_duplicates}};
          });
    } else if (kind == F::kUgrid) {
      const UgridOptions o = ugrid_options(options, info);
      // The only writer that uses netCDF/HDF5 (neither is thread-safe): it may run beside the
      // others when nothing else can call netCDF meanwhile (see the header).
      plan(
          format, name + ".nc", [&g = geographic(info.elements), o](const auto& p) { return write_ugrid(g, p, o); },
          [](const WriteStats& s) {
            return Facts{{"nodes", s.nodes}, {"faces", s.elements}};
          },
          true);
    } else if (kind == F::kVtu) {
      VtuOptions o;
      o.coordinates = options.vtu_coordinates;
      o.elements = info.elements;
      plan(
          format, name + ".vtu", [&g = geographic(info.elements), o](const auto& p) { return write_vtu(g, p, o); },
          [](const WriteStats& s) {
            return Facts{{"points", s.nodes},
                         {"cells", s.elements},
                         {"merged pole nodes", s.merged_pole_nodes},
                         {"dropped degenerate cells", s.dropped_elements}};
          });
    } else if (kind == F::kFort14) {
      Fort14Options o;
      o.title = fmt::format("aquatoria mesh {} ({})", name, info.source);
      plan(
          format, name + ".14", [&g = model_mesh(), o](const auto& p) { return write_fort14(g, p, o); },
          [](const WriteStats& s) {
            return Facts{{"nodes", s.nodes}, {"triangles", s.elements}, {"land boundary edges", s.boundary_edges}};
          });
    } else if (kind == F::kText) {
      TextOptions o;
      o.elements = info.elements;
      plan(
          format, name + ".txt", [&g = geographic(info.elements), o](const auto& p) { return write_text(g, p, o); },
          [](const WriteStats& s) {
            return Facts{{"nodes", s.nodes}, {"elements", s.elements}};
          });
    } else if (kind == F::kFesom) {
      plan_fesom(format);
    } else if (kind == F::kSchism) {
      plan_schism(format);
    } else if (kind == F::kPng) {
      plan_png(format);
    } else if (kind == F::kTif) {
      plan(format, name + ".tif", info.global_run_file, [](const WriteStats& s) {
        return Facts{{"pixels", s.nodes}, {"filled pixels", s.elements}};
      });
    }
  }

  // As if written one after another: the files before it are written and logged, then this
  // error (a geographic mesh that cannot be built, a streamed raster that cannot be read).
  void plan_failure(const config::OutputFormat kind, std::exception_ptr e) {
    OutputJob failing;
    failing.format = std::string(name_of(kind));
    failing.writer = [e](const std::filesystem::path&) -> WriteStats { std::rethrow_exception(e); };
    failing.log_before = std::move(pending);
    pending.clear();
    jobs.push_back(std::move(failing));
  }

 private:
  const mesh::Mesh& mesh;
  const raster::Bathymetry& bathy;
  const config::OutputOptions& options;
  OutputSet& outputs;
  const MeshOutputInfo& info;
  Report* report;
  const std::string& name;

  // Writers in geographic coordinates get the mesh without the degenerate pole row (made once,
  // when the first of them needs it; fort.14 always writes triangles).
  const ElevationSampler elevation_ = [this](const std::vector<double>& lon, const std::vector<double>& lat,
                                             std::vector<double>& out) {
    out.resize(lon.size());
    bathy.sample_points(lon.data(), lat.data(), static_cast<std::int64_t>(lon.size()), out.data());
  };
  std::optional<GeographicMesh> geo_, geo_triangles_;
  // The model formats (fort14, fesom, schism) write the geographic triangles cleaned for the
  // models (mesh/model_cleaning.hpp: no triangle with fewer than two neighbours, no pinch
  // vertex); the lattice mesh and the other files keep every triangle (README "Meshes for the
  // models"). Made once, when the first of them needs it.
  std::optional<mesh::ModelMesh> model_;
  std::optional<TriangleShapes> shapes_;

  void hold(LogLevel level, std::string text) { pending.push_back({level, std::move(text)}); }

  const mesh::Mesh& geographic(ElementKinds kinds) {
    std::optional<GeographicMesh>& g = kinds == info.elements ? geo_ : geo_triangles_;
    if (!g) {
      g.emplace(mesh, kinds, elevation_);
      for (const auto& line : g->describe()) hold(LogLevel::kInfo, fmt::format("geographic mesh: {}", line));
      // "geographic_mesh": the mesh of UGRID/text/VTU; with mesh.elements = "both" fort.14 writes
      // the triangles with the pole cap, reported as "geographic_mesh_fort14".
      if (report != nullptr)
        (*report)[kinds == info.elements ? "geographic_mesh" : "geographic_mesh_fort14"] = g->json();
    }
    return g->mesh();
  }

  const mesh::Mesh& model_mesh() {
    if (model_) return model_->mesh();
    const mesh::Mesh& g = geographic(ElementKinds::kTriangles);
    const Timer timer;
    model_.emplace(g);
    ModelMeshNotes notes = model_mesh_notes(*model_, timer.wall_s());
    for (auto& line : notes.lines) hold(line.level, std::move(line.text));
    if (report != nullptr) (*report)["cleaning"] = std::move(notes.cleaning);
    return model_->mesh();
  }

  // Per lattice-mesh triangle (what the preview draws): the value of the geographic triangle it
  // became, NaN where the pole cap replaced it.
  [[nodiscard]] std::vector<float> lattice_values(const std::vector<float>& geo_values) const {
    const auto& src = (info.elements == ElementKinds::kTriangles ? geo_ : geo_triangles_)->source_triangle();
    if (src.empty()) return geo_values;
    std::vector<float> v(mesh.triangles.size(), std::numeric_limits<float>::quiet_NaN());
    for (std::size_t k = 0; k < src.size(); ++k)
      if (src[k] >= 0) v[static_cast<std::size_t>(src[k])] = geo_values[k];
    return v;
  }

  // Plans one file; the writer and the facts run later, so they capture what they use by value
  // or refer to what outlives the jobs (the caller's arguments, the geographic meshes).
  void plan(const std::string& format, const std::string& file,
            std::function<WriteStats(const std::filesystem::path&)> writer,
            std::function<Facts(const WriteStats&)> facts, bool own_thread = false) {
    OutputJob job;
    job.format = format;
    job.name = file;
    job.temp_path = outputs.temp_path(file);
    job.final_path = outputs.final_path(file);
    job.writer = std::move(writer);
    job.facts = std::move(facts);
    job.own_thread = own_thread;
    job.log_before = std::move(pending);
    pending.clear();
    jobs.push_back(std::move(job));
  }

  void plan_fesom(const std::string& format) {
    const std::vector<double>& levels = options.fesom_levels.empty() ? default_fesom_levels_m() : options.fesom_levels;
    const mesh::Mesh& g = model_mesh();
    plan(
        format, name + "_nod2d.out", [&g](const auto& p) { return write_fesom_nod2d(g, p); },
        [](const WriteStats& s) {
          return Facts{{"nodes", s.nodes}, {"boundary nodes", s.boundary_edges}};
        });
    plan(
        format, name + "_elem2d.out", [&g](const auto& p) { return write_fesom_elem2d(g, p); },
        [](const WriteStats& s) {
          return Facts{{"triangles", s.elements}};
        });
    plan(
        format, name + "_aux3d.out", [&g, &levels](const auto& p) { return write_fesom_aux3d(g, p, levels); },
        [&levels](const WriteStats& s) {
          return Facts{{"nodes", s.nodes}, {"levels", static_cast<std::int64_t>(levels.size())}};
        });
    bool open = false;
    for (const auto& sg : g.segments) open = open || sg.type == mesh::BoundaryType::kOpen;
    if (open) {
      plan(
          format, name + "_obn.out", [&g](const auto& p) { return write_fesom_open_boundary(g, p); },
          [](const WriteStats& s) {
            return Facts{{"open-boundary nodes", s.nodes}};
          });
    }
    if (const auto w = fesom_floodplain_warning(g)) hold(LogLevel::kWarning, *w);
    const FesomRotation r = fesom_rotation(mesh.rotation);
    hold(LogLevel::kInfo,
         fmt::format("FESOM namelist.config &geometry: {} ({})", r.namelist(),
                     mesh.rotation.enabled ? "FESOM's model frame = the mesh's rotated frame"
                                           : "the mesh is not rotated: FESOM's standard frame, its pole on "
                                             "Greenland; force_rotation = .false. with 0, 0, 0 also works"));
    if (report != nullptr) {
      (*report)["fesom"] = Json{{"force_rotation", r.force_rotation},
                                {"alphaEuler", r.alpha_deg},
                                {"betaEuler", r.beta_deg},
                                {"gammaEuler", r.gamma_deg},
                                {"levels_m", levels}};
    }
  }

  void plan_schism(const std::string& format) {
    SchismOptions o;
    o.title = fmt::format("aquatoria mesh {} ({}), lon/lat: SCHISM ics = 2", name, info.source);
    const mesh::Mesh& g = model_mesh();
    const SchismTimeStep dt = schism_time_step(g);
    hold(LogLevel::kInfo, dt.describe());
    if (report != nullptr) {
      (*report)["schism"] = Json{{"wet_nodes", dt.wet_nodes},
                                 {"dt_advection_off_min_s", std::ceil(dt.dt_half_s)},
                                 {"dt_advection_on_min_s", std::ceil(dt.dt_p95_s)},
                                 {"dt_all_nodes_s", std::ceil(dt.dt_all_s)},
                                 {"dt_max_s", SchismTimeStep::kMaxDtS}};
    }
    for (const char* ext : {".gr3", ".ll"}) {
      plan(
          format, name + ext, [&g, o](const auto& p) { return write_schism_hgrid(g, p, o); },
          [](const WriteStats& s) {
            return Facts{{"nodes", s.nodes}, {"triangles", s.elements}, {"land boundary edges", s.boundary_edges}};
          });
    }
    bool open = false;
    for (const auto& sg : g.segments)
      open = open || sg.type == mesh::BoundaryType::kOpen || sg.type == mesh::BoundaryType::kRiver;
    if (open) {
      plan(
          format, name + "_bctides.in",
          [&g, title = o.title](const auto& p) { return write_schism_bctides(g, p, title); },
          [](const WriteStats& s) {
            return Facts{{"open boundaries", s.boundary_edges}, {"open nodes", s.nodes}};
          });
    }
  }

  void plan_png(const std::string& format) {
    // The colours by angle or size come from the quality step, which runs before this job.
    auto o = std::make_shared<PreviewOptions>(preview_options(options, info.elements));
    auto colour = [o, this] {
      if (o->colour == PreviewColour::kAngle && shapes_) o->triangle_values = lattice_values(shapes_->min_angle_deg);
      if (o->colour == PreviewColour::kSize && shapes_) o->triangle_values = lattice_values(shapes_->size_km);
    };
    if (o->colour == PreviewColour::kTarget) o->triangle_values = info.target_km;
    if (o->colour == PreviewColour::kElevation) {  // the mean node elevation (m) of each lattice-mesh triangle
      o->triangle_values.resize(mesh.triangles.size());
      for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
        double sum = 0.0;
        for (const NodeId n : mesh.triangles[k]) sum += mesh.depth_m[static_cast<std::size_t>(n)];
        o->triangle_values[k] = static_cast<float>(sum / 3.0);
      }
    }
    if (o->colour == PreviewColour::kSize || o->colour == PreviewColour::kTarget)
      o->value_range_km = info.size_scale_km;
    plan(
        format, name + ".png",
        [&mesh = mesh, &bathy = bathy, o, colour](const auto& p) {
          colour();
          return write_preview_png(mesh, bathy, p, *o);
        },
        [](const WriteStats& s) {
          return Facts{{"elements drawn", s.elements}};
        });
    if (!options.png_zoom.empty()) {
      plan(
          "png_zoom", name + "_zoom.png",
          [&mesh = mesh, &bathy = bathy, o](const auto& p) { return write_preview_zoom_png(mesh, bathy, p, *o); },
          [](const WriteStats&) { return Facts{}; });
    }
  }
};

}  // namespace

std::vector<WrittenFile> write_mesh_outputs(const mesh::Mesh& mesh, const raster::Bathymetry& bathy,
                                            const config::OutputOptions& options, OutputSet& outputs, const Logger& log,
                                            const MeshOutputInfo& info, Report* report) {
  check_mesh_output_options(options, info.elements);
  check_elements(mesh, info.elements);
  const auto formats = requested_formats(options);
  if (options.writes(config::OutputFormat::kTif) && !info.global_run_file)
    throw ConfigError("output.formats: \"tif\" (the global run file) is written by `aquatoria mesh` only");

  // Every file is planned first, on this thread: its temporary path reserved, the meshes it
  // needs built, its writer bound to them; the lines logged meanwhile are held back and go out
  // in order with the files' lines (output_jobs.hpp).
  OutputPlanner planner(mesh, bathy, options, outputs, info, report);
  planner.plan_quality();
  for (const auto& format : formats) {
    try {
      planner.plan_format(format);
    } catch (...) {
      planner.plan_failure(format, std::current_exception());
      break;
    }
  }
  // A streamed raster is read through GDAL (its netCDF driver for GEBCO / SRTM15+ files) while
  // the preview samples it: then nothing may write netCDF meanwhile. Without a preview nothing
  // reads the raster while the files are written (the geographic meshes were built above).
  const bool concurrent = info.concurrent && !(bathy.info().streamed && options.writes(config::OutputFormat::kPng));
  return write_output_jobs(std::move(planner.jobs), planner.pending, concurrent, log);
}

std::vector<WrittenFile> write_mesh_outputs(const mesh::Mesh& mesh, const raster::Bathymetry& bathy,
                                            const config::OutputOptions& options, OutputSet& outputs,
                                            const Logger& log) {
  MeshOutputInfo info;
  info.elements = default_element_kinds(mesh);
  return write_mesh_outputs(mesh, bathy, options, outputs, log, info);
}

}  // namespace aq::io
