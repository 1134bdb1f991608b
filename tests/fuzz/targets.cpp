// SPDX-License-Identifier: GPL-3.0-or-later
// Fuzz targets (targets.hpp). File readers get the bytes through a file in a private temporary
// folder (the readers take paths, as users give them); the folder also holds copies of the
// configs/*.izogrid files so that a regional config's relative contour_file can resolve.
#include "fuzz/targets.hpp"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <system_error>

#include "config/load.hpp"
#include "config/regional.hpp"
#include "core/error.hpp"
#include "grid_files/contact_netcdf.hpp"
#include "grid_files/nesting_netcdf.hpp"
#include "grid_files/xygrid_netcdf.hpp"
#include "grid_params/izogrid_file.hpp"
#include "raster/bathymetry.hpp"

#ifndef AQ_SOURCE_DIR
#define AQ_SOURCE_DIR "."
#endif

namespace aq::fuzz {
namespace {

namespace fs = std::filesystem;

// A private folder, removed when the process exits normally.
class Scratch {
 public:
  Scratch() {
    const fs::path shm("/dev/shm");
    std::error_code ec;
    const fs::path base = fs::is_directory(shm, ec) ? shm : fs::temp_directory_path();
    dir_ = base / ("aq_fuzz_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    for (const auto& e : fs::directory_iterator(fs::path(AQ_SOURCE_DIR) / "configs", ec))
      if (e.path().extension() == ".izogrid") fs::copy_file(e.path(), dir_ / e.path().filename(), ec);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;

  // Writes the bytes to `name` in the folder and returns its path.
  fs::path put(const std::string& name, const std::uint8_t* data, std::size_t size) const {
    const fs::path p = dir_ / name;
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return p;
  }

 private:
  fs::path dir_;
};

const Scratch& scratch() {
  static const Scratch s;
  return s;
}

// Runs `f`; the message of an error aquatoria reports to users, or "".
template <typename F>
std::string expect_clear_error(F&& f) {
  try {
    f();
  } catch (const aq::Error& e) {
    return e.what();
  }
  return {};
}

std::vector<std::string> lines(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> out;
  std::string cur;
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == '\n') {
      out.push_back(cur);
      cur.clear();
    } else {
      cur.push_back(static_cast<char>(data[i]));
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

std::string config_global(const std::uint8_t* data, std::size_t size) {
  const fs::path p = scratch().put("fuzz.toml", data, size);
  return expect_clear_error([&] { (void)config::load_global(p.string(), {}); });
}

std::string config_regional(const std::uint8_t* data, std::size_t size) {
  const fs::path p = scratch().put("fuzz_regional.toml", data, size);
  return expect_clear_error([&] { (void)config::load_regional(p.string(), {}); });
}

std::string izogrid(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  return expect_clear_error([&] { (void)curvilinear::parse_izogrid(text, "fuzz.izogrid"); });
}

// The regional overrides apply on top of the seed's Black Sea file (a complete, valid config).
std::string set(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return {};
  const std::vector<std::string> overrides = lines(data + 1, size - 1);
  if (data[0] % 2 == 0) {
    return expect_clear_error([&] { (void)config::load_global(std::nullopt, overrides); });
  }
  static const fs::path base = [] {
    const std::string text = "[regional]\nname = \"fuzz\"\ncontour_file = \"black_sea.izogrid\"\n";
    return scratch().put("fuzz_set_base.toml", reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
  }();
  return expect_clear_error([&] { (void)config::load_regional(base.string(), overrides); });
}

std::string roms_grid(const std::uint8_t* data, std::size_t size) {
  const fs::path p = scratch().put("fuzz_grd.nc", data, size);
  return expect_clear_error([&] { (void)io::read_roms_grid_fields(p); });
}

std::string nesting(const std::uint8_t* data, std::size_t size) {
  const fs::path p = scratch().put("fuzz_nesting.nc", data, size);
  return expect_clear_error([&] { (void)io::read_nesting(p); });
}

// A raster's header and first read, as `aquatoria mesh` opens input.path: GDAL picks the driver
// from the bytes (netCDF-3/4, GeoTIFF, ...); the header is checked (netCDF size, coordinate
// variables, geotransform, band type) before any value is trusted, and a declared size beyond the
// memory limit is refused before anything is allocated.
std::string raster_file(const std::uint8_t* data, std::size_t size) {
  const fs::path p = scratch().put("fuzz_raster", data, size);
  return expect_clear_error([&] {
    raster::OpenOptions o;
    o.path = p.string();
    o.max_memory_bytes = std::int64_t{256} << 20;
    (void)raster::plan_raster(o);
    const raster::Bathymetry b = raster::Bathymetry::open(o);
    (void)b.sample(0.0, 0.0);
  });
}

std::string xygrid(const std::uint8_t* data, std::size_t size) {
  const fs::path p = scratch().put("fuzz_xygrid.nc", data, size);
  return expect_clear_error([&] { (void)io::read_xygrid(p); });
}

}  // namespace

const std::vector<Target>& targets() {
  static const std::vector<Target> t{{"config_global", config_global},
                                     {"config_regional", config_regional},
                                     {"izogrid", izogrid},
                                     {"set", set},
                                     {"roms_grid", roms_grid},
                                     {"nesting", nesting},
                                     {"xygrid", xygrid},
                                     {"raster", raster_file}};
  return t;
}

const Target* find_target(std::string_view name) {
  for (const Target& t : targets())
    if (t.name == name) return &t;
  return nullptr;
}

}  // namespace aq::fuzz
