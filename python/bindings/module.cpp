// SPDX-License-Identifier: GPL-3.0-or-later
// The compiled part of the Python package `aquatoria` (module aquatoria._core, pybind11): the
// global pipeline of aq_app run on the caller's configuration, its results handed to numpy as
// views of the C++ arrays (no copy) where the layout allows, and aq::Error mapped to Python
// exceptions carrying the command line's messages. The Python layer (python/aquatoria/*.py)
// turns dicts into --set overrides, builds xarray datasets and documents the public API.
//
// Threads: every call that runs C++ work releases the GIL and then takes one process-wide lock,
// so calls from several Python threads run one after another (GDAL's netCDF driver and the
// netCDF/HDF5 writers are not thread-safe), each with its own OpenMP team (threads = n sets the
// team size for that call only; default: OMP_NUM_THREADS, as for the command line).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>
#include <netcdf.h>

#include <cstdio>
#include <functional>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/global_run.hpp"
#include "app/mesh_outputs.hpp"
#include "app/mesh_run.hpp"
#include "config/load.hpp"
#include "core/cancel.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/output_files.hpp"
#include "core/report.hpp"
#include "core/timer.hpp"
#include "io/memory_dataset.hpp"
#include "mesh/model_cleaning.hpp"
#include "mesh_arrays.hpp"
#include "mesh_files/element_kinds.hpp"
#include "mesh_files/geographic_mesh.hpp"
#include "mesh_files/ugrid_writer.hpp"
#include "python_common.hpp"
#include "quadtree/leaf_levels.hpp"
#include "raster/memory_raster.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

#ifndef AQ_VERSION
#define AQ_VERSION "dev"
#endif

namespace py = pybind11;

namespace aq::python {

namespace {

// The configuration of a run from Python, loaded as `aquatoria mesh` loads it, and the header of
// its report: the `command` ("mesh" or "mask"), the interface, the source and the echo.
config::Loaded<config::GlobalConfig> load(const std::optional<std::string>& path,
                                          const std::vector<std::string>& overrides, const char* command,
                                          Report& report) {
  const config::GlobalUse use = std::string(command) == "mask" ? config::GlobalUse::kMask : config::GlobalUse::kMesh;
  config::Loaded<config::GlobalConfig> loaded = config::load_global(path, overrides, use);
  report["command"] = command;
  report["interface"] = "python";
  report["config_source"] = loaded.source;
  report["config"] = loaded.echo;
  return loaded;
}

// Unpacks rows of a bitmap into one byte per pixel (value `one` where set, added to out).
void add_bitmap(const Bitmap& b, std::uint8_t one, std::uint8_t* out) {
  const std::int64_t nx = b.nx(), ny = b.ny();
#pragma omp parallel for schedule(static) default(none) shared(b, out) firstprivate(nx, ny, one)
  for (std::int64_t j = 0; j < ny; ++j) {
    const std::uint64_t* row = b.row(j);
    std::uint8_t* o = out + j * nx;
    for (std::int64_t i = 0; i < nx; ++i)
      if ((row[i >> 6] >> (i & 63)) & 1ULL) o[i] = static_cast<std::uint8_t>(o[i] + one);
  }
}

// A (ny, nx) array of one byte per lattice pixel, zeroed, then filled by `fill` with the GIL
// released.
py::array_t<std::uint8_t> pixel_array(std::int64_t nx, std::int64_t ny,
                                      const std::function<void(std::uint8_t*)>& fill) {
  py::array_t<std::uint8_t> out({static_cast<py::ssize_t>(ny), static_cast<py::ssize_t>(nx)});
  std::uint8_t* o = out.mutable_data();
  {
    py::gil_scoped_release release;
    std::fill(o, o + nx * ny, std::uint8_t{0});
    fill(o);
  }
  return out;
}

}  // namespace

/// One global mesh run: the configuration, the pipeline's result (the lattice mesh), and made when
/// first asked for: the geographic mesh the UGRID, VTU and text files hold, the geographic
/// triangles cleaned for the models (what fort14, fesom and schism write), and the report.
class MeshRun {
 public:
  MeshRun(const std::optional<std::string>& config_path, const std::vector<std::string>& overrides, bool verbose,
          int threads)
      : lines_(std::make_shared<LogLines>()), log_(make_logger(lines_, verbose)) {
    WorkScope work(threads);
    loaded_ = load(config_path, overrides, "mesh", report_);
    const config::GlobalConfig& c = loaded_.options;
    const app::GlobalSetup setup = app::prepare_global_run(c);
    app::log_memory_estimate(setup, log_);
    run_ = app::run_global_pipeline(c, setup, log_, &report_);
    report_["mesh_counts"] = app::mesh_counts_json(run_.mesh);
    report_["memory"] = app::memory_json(setup);
    kinds_ = c.mesh.elements;
  }

  /// The mesh in geographic coordinates with the configuration's elements, as the UGRID, VTU and
  /// text files hold it. Call under a WorkScope.
  const mesh::Mesh& geographic() {
    if (!geo_) {
      geo_.emplace(run_.mesh, kinds_, elevation_sampler());
      geo_columns_.emplace(geo_->mesh());
    }
    return geo_->mesh();
  }

  /// The geographic triangles cleaned for the models (mesh_outputs.cpp's order of making them:
  /// the geographic mesh of triangles, then the cleaning; its log lines and report section are the
  /// command's). Call under a WorkScope.
  const mesh::ModelMesh& model() {
    if (!model_) {
      const mesh::Mesh& g = geographic_triangles();
      const Timer timer;
      model_.emplace(g);
      io::ModelMeshNotes notes = io::model_mesh_notes(*model_, timer.wall_s());
      for (const auto& line : notes.lines) log_.log(line.level, line.text);
      cleaning_ = std::move(notes.cleaning);
    }
    return *model_;
  }
  /// What the "fesom" format logs of the model mesh (the floodplain a FESOM2 mesh cannot keep dry),
  /// once per run.
  void fesom_notes() {
    if (fesom_noted_) return;
    fesom_noted_ = true;
    if (const auto w = io::fesom_floodplain_warning(model().mesh())) log_.log(LogLevel::kWarning, *w);
  }
  /// The mesh model() cleaned: the geographic mesh when the elements are triangles.
  const mesh::Mesh& geographic_triangles() {
    if (kinds_ == io::ElementKinds::kTriangles) return geographic();
    if (!geo_triangles_) geo_triangles_.emplace(run_.mesh, io::ElementKinds::kTriangles, elevation_sampler());
    return geo_triangles_->mesh();
  }

  /// The UGRID dataset write(..., ["ugrid"]) would put into its file, in memory. Call under a WorkScope.
  std::shared_ptr<io::MemoryDataset> ugrid() {
    const mesh::Mesh& g = geographic();
    io::MeshOutputInfo info;
    info.elements = kinds_;
    info.source = app::global_mesh_source(*run_.bathy);
    auto ds = std::make_shared<io::MemoryDataset>();
    io::ugrid_dataset(g, io::ugrid_options(loaded_.options.output, info), *ds);
    return ds;
  }

  py::object report() const {
    Json r = report_.root();
    if (geo_) r["geographic_mesh"] = geo_->json();
    if (model_) r["cleaning"] = cleaning_;
    return json_to_python(r);
  }

  /// Writes the files of `formats` (empty: the configuration's) as <dir>/<name>.* and the report.
  std::vector<std::string> write(const std::string& dir, const std::string& name,
                                 const std::optional<std::vector<std::string>>& formats, int threads) {
    WorkScope work(threads);
    config::GlobalConfig c = loaded_.options;
    c.output.dir = dir;
    c.output.name = name;
    if (formats) c.output.formats = config::parse_names<config::OutputFormat>(*formats, "output.formats");
    io::check_mesh_output_options(c.output, kinds_);
    Report report = report_;
    report["config"]["output"]["name"] = c.output.name;
    report["config"]["output"]["dir"] = c.output.dir;
    report["config"]["output"]["formats"] = Json::array();
    for (const config::OutputFormat f : c.output.formats)
      report["config"]["output"]["formats"].push_back(std::string(name_of(f)));
    OutputSet out(c.output.dir);
    StageScope stage("write", &report, log_);
    const auto files = app::write_global_mesh_files(c, run_, out, log_, report);
    stage.done(fmt::format("{} files in {}", files.size(), c.output.dir));
    report.finish();
    const std::string report_name = app::write_global_report(c, report, out);
    throw_if_cancelled();  // the last moment: after the commit the files are there
    out.commit();
    std::vector<std::string> paths;
    for (const auto& f : files) paths.push_back(f.path.string());
    paths.push_back((std::filesystem::path(c.output.dir) / report_name).string());
    return paths;
  }

  std::vector<std::pair<int, std::string>> take_log() { return lines_->take(); }

  const app::GlobalRun& run() const { return run_; }
  const config::GlobalConfig& options() const { return loaded_.options; }
  io::ElementKinds kinds() const { return kinds_; }
  const NodeColumns& geographic_columns() const { return *geo_columns_; }
  const NodeColumns& lattice_columns() {
    if (!lattice_columns_) lattice_columns_.emplace(run_.mesh);
    return *lattice_columns_;
  }

 private:
  io::ElevationSampler elevation_sampler() const {
    const raster::Bathymetry& bathy = *run_.bathy;
    return [&bathy](const std::vector<double>& lon, const std::vector<double>& lat, std::vector<double>& out) {
      out.resize(lon.size());
      bathy.sample_points(lon.data(), lat.data(), static_cast<std::int64_t>(lon.size()), out.data());
    };
  }

  std::shared_ptr<LogLines> lines_;
  Logger log_;
  bool fesom_noted_ = false;
  config::Loaded<config::GlobalConfig> loaded_;
  Report report_;
  app::GlobalRun run_;
  io::ElementKinds kinds_ = io::ElementKinds::kTriangles;
  std::optional<io::GeographicMesh> geo_, geo_triangles_;
  std::optional<NodeColumns> geo_columns_, lattice_columns_;
  std::optional<mesh::ModelMesh> model_;
  Json cleaning_;
};

/// The mask stage and the quadtree levels of a run, without a mesh.
class MaskRun {
 public:
  MaskRun(const std::optional<std::string>& config_path, const std::vector<std::string>& overrides, bool verbose,
          int threads)
      : lines_(std::make_shared<LogLines>()), log_(make_logger(lines_, verbose)) {
    WorkScope work(threads);
    loaded_ = load(config_path, overrides, "mask", report_);
    const config::GlobalConfig& c = loaded_.options;
    const app::GlobalSetup setup = app::prepare_global_run(c);
    run_ = app::run_global_leaves(c, setup, log_, &report_);
  }

  const app::GlobalRun& run() const { return run_; }
  py::object report() const { return json_to_python(report_.root()); }
  std::vector<std::pair<int, std::string>> take_log() { return lines_->take(); }

 private:
  std::shared_ptr<LogLines> lines_;
  Logger log_;
  config::Loaded<config::GlobalConfig> loaded_;
  Report report_;
  app::GlobalRun run_;
};

namespace {

int default_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

py::array lattice_edges_lon(const Lattice& lat) {
  py::array_t<double> a(static_cast<py::ssize_t>(lat.nx + 1));
  auto r = a.mutable_unchecked<1>();
  for (std::int64_t i = 0; i <= lat.nx; ++i) r(i) = lat.lon_of(i);
  return a;
}

py::array lattice_edges_lat(const Lattice& lat) {
  py::array_t<double> a(static_cast<py::ssize_t>(lat.ny + 1));
  auto r = a.mutable_unchecked<1>();
  for (std::int64_t j = 0; j <= lat.ny; ++j) r(j) = lat.lat_of(j);
  return a;
}

py::array lattice_centres_lon(const Lattice& lat) {
  py::array_t<double> a(static_cast<py::ssize_t>(lat.nx));
  auto r = a.mutable_unchecked<1>();
  for (std::int64_t i = 0; i < lat.nx; ++i) r(i) = lat.lon0_deg + (static_cast<double>(i) + 0.5) * lat.pixel_deg();
  return a;
}

py::array lattice_centres_lat(const Lattice& lat) {
  py::array_t<double> a(static_cast<py::ssize_t>(lat.ny));
  auto r = a.mutable_unchecked<1>();
  for (std::int64_t j = 0; j < lat.ny; ++j) r(j) = lat.lat_of_row(static_cast<double>(j) + 0.5);
  return a;
}

py::dict lattice_dict(const Lattice& lat, const config::GlobalConfig& c) {
  py::dict d;
  d["kind"] = lat.kind_name();
  d["nx"] = lat.nx;
  d["ny"] = lat.ny;
  d["pixel_deg"] = lat.pixel_deg();
  d["step0_deg"] = lat.step0_deg;
  d["levels"] = lat.levels;
  d["lon0_deg"] = lat.lon0_deg;
  d["rotated"] = c.rotation.enabled;
  d["pole_lon_deg"] = c.rotation.pole_lon_deg;
  d["pole_lat_deg"] = c.rotation.pole_lat_deg;
  return d;
}

}  // namespace

}  // namespace aq::python

namespace aq::python {
void bind_regional(py::module_& m);
}

PYBIND11_MODULE(_core, m) {
  using aq::python::MaskRun;
  using aq::python::MeshRun;
  m.doc() = "aquatoria's compiled core (use the package `aquatoria`, not this module)";
  // netCDF (and HDF5 under it) initialised on the importing thread, as when the work ran there:
  // HDF5's automatic error printing is switched off per thread by netCDF's first initialisation,
  // and the work now runs on worker threads (_interrupt.py), so the user's own netCDF reads on
  // the main thread (netCDF4, xarray) would otherwise print HDF5-DIAG stacks for every probe.
  nc_initialize();
  m.attr("__version__") = AQ_VERSION;

  static py::exception<aq::Error> error(m, "Error", PyExc_RuntimeError);
  static py::exception<aq::ConfigError> config_error(m, "ConfigError", error.ptr());
  static py::exception<aq::InputError> input_error(m, "InputError", error.ptr());
  static py::exception<aq::OutputError> output_error(m, "OutputError", error.ptr());
  static py::exception<aq::NumericalError> numerical_error(m, "NumericalError", error.ptr());
  static py::exception<aq::InternalError> internal_error(m, "InternalError", error.ptr());
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const aq::Cancelled& e) {
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    } catch (const aq::ConfigError& e) {
      config_error(e.what());
    } catch (const aq::InputError& e) {
      input_error(e.what());
    } catch (const aq::OutputError& e) {
      output_error(e.what());
    } catch (const aq::NumericalError& e) {
      numerical_error(e.what());
    } catch (const aq::InternalError& e) {
      internal_error(e.what());
    } catch (const aq::Error& e) {
      error(e.what());
    }
  });

  m.def("default_threads", &aq::python::default_threads, "OpenMP threads a call uses by default");

  // Ctrl-C (python/aquatoria/_interrupt.py): a call made through call_with_token stops, with
  // KeyboardInterrupt, at the pipeline's next look at its token (core/cancel.hpp) after
  // token.request().
  py::class_<aq::CancelToken>(m, "CancelToken")
      .def(py::init<>())
      .def("request", &aq::CancelToken::request, "Asks the call made with this token to stop")
      .def_property_readonly("requested", &aq::CancelToken::requested);
  m.def(
      "call_with_token",
      [](const aq::CancelToken& token, const py::function& fn, const py::args& args, const py::kwargs& kwargs) {
        const aq::CancelToken*& slot = aq::python::call_token();
        const aq::CancelToken* before = slot;
        slot = &token;
        struct Restore {
          const aq::CancelToken*& slot;
          const aq::CancelToken* before;
          ~Restore() { slot = before; }
        } restore{slot, before};
        return fn(*args, **kwargs);
      },
      py::arg("token"), py::arg("fn"), "fn(*args, **kwargs) with `token` as the stop request of its C++ work");

  py::class_<MeshRun>(m, "MeshRun")
      .def(py::init<const std::optional<std::string>&, const std::vector<std::string>&, bool, int>(), py::arg("config"),
           py::arg("overrides"), py::arg("verbose"), py::arg("threads"))
      .def(
          "geographic_mesh",
          [](py::object self, int threads) {
            MeshRun& r = self.cast<MeshRun&>();
            const aq::mesh::Mesh* g = nullptr;
            {
              aq::python::WorkScope work(threads);
              g = &r.geographic();
            }
            return aq::python::mesh_dict(*g, r.geographic_columns(), self);
          },
          py::arg("threads"))
      .def("lattice_mesh",
           [](py::object self) {
             MeshRun& r = self.cast<MeshRun&>();
             return aq::python::mesh_dict(r.run().mesh, r.lattice_columns(), self);
           })
      .def(
          "model_mesh",
          [](py::object self, const std::string& format, int threads) {
            MeshRun& r = self.cast<MeshRun&>();
            const auto f = aq::python::parse_model_format(format);
            if (!aq::io::has_triangles(r.kinds()))
              throw aq::ConfigError(fmt::format(
                  "model_mesh(\"{}\"): the model formats are triangle meshes, but mesh.elements = \"squares\" (use "
                  "\"triangles\" or \"both\")",
                  format));
            const aq::mesh::ModelMesh* model = nullptr;
            const aq::mesh::Mesh* geo = nullptr;
            {
              aq::python::WorkScope work(threads);
              model = &r.model();
              geo = &r.geographic_triangles();
            }
            if (f == aq::python::ModelFormat::kFesom) r.fesom_notes();
            return aq::python::model_dict(*model, *geo, f, r.options().output.fesom_levels, self);
          },
          py::arg("format"), py::arg("threads"))
      .def(
          "ugrid_dataset",
          [](MeshRun& r, int threads) {
            std::shared_ptr<aq::io::MemoryDataset> ds;
            {
              aq::python::WorkScope work(threads);
              ds = r.ugrid();
            }
            return aq::python::dataset_dict(std::move(ds));
          },
          py::arg("threads"))
      .def_property_readonly(
          "lattice", [](const MeshRun& r) { return aq::python::lattice_dict(r.run().setup.lattice, r.options()); })
      .def("report", &MeshRun::report)
      .def("take_log", &MeshRun::take_log)
      .def("write", &MeshRun::write, py::arg("dir"), py::arg("name"), py::arg("formats"), py::arg("threads"));

  py::class_<MaskRun>(m, "MaskRun")
      .def(py::init<const std::optional<std::string>&, const std::vector<std::string>&, bool, int>(), py::arg("config"),
           py::arg("overrides"), py::arg("verbose"), py::arg("threads"))
      .def("classes",
           [](const MaskRun& r) {
             const auto& a = r.run().area;
             return aq::python::pixel_array(a.wet.nx(), a.wet.ny(), [&a](std::uint8_t* o) {
               aq::python::add_bitmap(a.coastal, 1, o);
               aq::python::add_bitmap(a.wet, 2, o);
             });
           })
      .def("filled",
           [](const MaskRun& r) {
             const auto& a = r.run().area;
             return aq::python::pixel_array(a.filled.nx(), a.filled.ny(),
                                            [&a](std::uint8_t* o) { aq::python::add_bitmap(a.filled, 1, o); })
                 .attr("view")("bool");
           })
      .def("floodplain",
           [](const MaskRun& r) {
             // mask.min_depth_m < 0: the filled pixels not wet at the datum (WetArea::sea is the rest)
             const auto& a = r.run().area;
             const auto nx = a.filled.nx(), ny = a.filled.ny();
             return aq::python::pixel_array(nx, ny,
                                            [&a, nx, ny](std::uint8_t* o) {
                                              if (a.sea.nx() != nx || a.sea.ny() != ny) return;
                                              aq::python::add_bitmap(a.filled, 1, o);
                                              aq::python::add_bitmap(a.sea, 1,
                                                                     o);  // sea ⊂ filled: 2 = sea, 1 = floodplain
                                              for (std::int64_t k = 0; k < nx * ny; ++k) o[k] = o[k] == 1 ? 1 : 0;
                                            })
                 .attr("view")("bool");
           })
      .def("levels",
           [](const MaskRun& r) {
             const auto& lat = r.run().setup.lattice;
             return aq::python::pixel_array(lat.nx, lat.ny, [&r, &lat](std::uint8_t* o) {
               const aq::quadtree::LeafLevels levels(r.run().leaves, lat);
               levels.fill(0, lat.ny, o);
             });
           })
      .def_property_readonly("lon_edges",
                             [](const MaskRun& r) { return aq::python::lattice_edges_lon(r.run().setup.lattice); })
      .def_property_readonly("lat_edges",
                             [](const MaskRun& r) { return aq::python::lattice_edges_lat(r.run().setup.lattice); })
      .def_property_readonly("lon",
                             [](const MaskRun& r) { return aq::python::lattice_centres_lon(r.run().setup.lattice); })
      .def_property_readonly("lat",
                             [](const MaskRun& r) { return aq::python::lattice_centres_lat(r.run().setup.lattice); })
      .def("report", &MaskRun::report)
      .def("take_log", &MaskRun::take_log);

  aq::python::bind_regional(m);

  py::class_<aq::raster::MemoryRaster>(m, "MemoryRaster")
      .def(py::init([](py::array values, py::array_t<double, py::array::c_style | py::array::forcecast> lon,
                       py::array_t<double, py::array::c_style | py::array::forcecast> lat) {
             if (values.ndim() != 2)
               throw aq::InputError(fmt::format(
                   "in-memory raster: the values have {} dimension(s); 2 (lat, lon) are needed", values.ndim()));
             if (lon.ndim() != 1 || lat.ndim() != 1) throw aq::InputError("in-memory raster: lon and lat must be 1-D");
             const auto ny = values.shape(0), nx = values.shape(1);
             if (lon.shape(0) != nx || lat.shape(0) != ny)
               throw aq::InputError(
                   fmt::format("in-memory raster: values are {} x {} (lat, lon) but lon has {} and lat {} values", ny,
                               nx, lon.shape(0), lat.shape(0)));
             aq::raster::MemoryType type;
             py::array a;
             const char kind = values.dtype().kind();
             const auto size = values.dtype().itemsize();
             if (kind == 'i' && size == 2)
               type = aq::raster::MemoryType::kInt16;
             else if (kind == 'i' && size == 4)
               type = aq::raster::MemoryType::kInt32;
             else if (kind == 'f' && size == 4)
               type = aq::raster::MemoryType::kFloat32;
             else
               type = aq::raster::MemoryType::kFloat64;
             if (type == aq::raster::MemoryType::kFloat64)
               a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(values);
             else
               a = py::array::ensure(values, py::array::c_style);
             if (!a) throw aq::InputError("in-memory raster: the values cannot be read as numbers");
             py::gil_scoped_release release;
             return std::make_unique<aq::raster::MemoryRaster>(a.data(), type, nx, ny, nx, lon.data(), lat.data());
           }),
           py::arg("values"), py::arg("lon"), py::arg("lat"))
      .def_property_readonly("path", &aq::raster::MemoryRaster::path);
}
