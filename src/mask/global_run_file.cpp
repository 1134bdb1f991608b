// SPDX-License-Identifier: GPL-3.0-or-later
// The global run as a GeoTIFF (see global_run_file.hpp).
#include "mask/global_run_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <system_error>

#include "core/error.hpp"
#include "core/output_files.hpp"
#include "raster/bathymetry.hpp"
#include "raster/byte_geotiff.hpp"

namespace aq::mask {

namespace {

namespace fs = std::filesystem;

constexpr char kFormat[] = "aquatoria global run 1";
constexpr std::uint8_t kFilledBit = 1, kWetBit = 2, kCoastalBit = 4;
constexpr std::uint8_t kNoLevel = 255;
constexpr char kNotAFile[] = "n/a (not a plain file)";

std::string number(double v) { return fmt::format("{:.17g}", v); }

std::string lattice_text(const Lattice& l) {
  return fmt::format("kind={} nx={} ny={} step0_deg={} levels={} lon0_deg={} y0_deg={}", l.kind_name(), l.nx, l.ny,
                     number(l.step0_deg), l.levels, number(l.lon0_deg), number(l.y0_deg));
}

}  // namespace

std::vector<std::pair<std::string, std::string>> mask_inputs(const config::GlobalConfig& c) {
  const std::vector<std::string> rasters = c.input.sources();
  const fs::path raster = fs::absolute(rasters.front()).lexically_normal();
  // A GDAL source that is not a plain file (a subdataset string, /vsicurl/...) has no size or
  // time to compare: recorded as kNotAFile, and such a file is never reused.
  std::error_code ec;
  std::string size = kNotAFile, mtime = kNotAFile;
  if (fs::is_regular_file(raster, ec)) {
    const auto bytes = fs::file_size(raster, ec);
    const auto time = fs::last_write_time(raster, ec);
    if (!ec) {
      size = std::to_string(bytes);
      mtime = std::to_string(time.time_since_epoch().count());
    }
  }
  // The other files GDAL reads for it (a VRT's tiles, sidecars), each by size and time, so that
  // changing a tile changes the inputs; none for a single file (its checksum is as before).
  std::string sources;
  if (size != kNotAFile) {
    for (const std::string& f : raster::raster_files(raster.string())) {
      const fs::path p = fs::absolute(f).lexically_normal();
      if (p == raster) continue;
      std::string entry = p.string() + " " + kNotAFile;
      if (fs::is_regular_file(p, ec)) {
        const auto bytes = fs::file_size(p, ec);
        const auto time = fs::last_write_time(p, ec);
        if (!ec) entry = fmt::format("{} {} bytes, mtime {}", p.string(), bytes, time.time_since_epoch().count());
      }
      sources += (sources.empty() ? "" : "; ") + entry;
    }
  }
  std::string seeds;
  for (const auto& s : c.mask.seeds)
    seeds += fmt::format("{}[{}, {}]", seeds.empty() ? "" : ", ", number(s[0]), number(s[1]));
  std::vector<std::pair<std::string, std::string>> items = {
      {"input.path", raster.string()},
      {"input.file_bytes", size},
      {"input.file_mtime", mtime},
      {"input.variable", c.input.variable},
      {"input.band", std::to_string(c.input.band)},
      {"input.positive_down", c.input.positive_down ? "true" : "false"},
      {"input.interpolation", std::string(name_of(c.input.interpolation))},
      {"quadtree.step_deg", number(c.quadtree.step_deg)},
      {"quadtree.levels", std::to_string(c.quadtree.levels)},
      {"quadtree.lon0_deg", number(c.quadtree.lon0_deg)},
      {"quadtree.lattice", std::string(name_of(c.quadtree.lattice))},
      {"quadtree.mercator_lat_max_deg", number(c.quadtree.mercator_lat_max_deg)},
      {"rotation", c.rotation.enabled
                       ? fmt::format("pole {} {}", number(c.rotation.pole_lon_deg), number(c.rotation.pole_lat_deg))
                       : std::string("none")},
      {"mask.min_depth_m", number(c.mask.min_depth_m)},
      {"mask.cursor", std::to_string(c.mask.cursor)},
      {"mask.seeds", "[" + seeds + "]"},
      {"mask.seed_radius_deg", number(c.mask.seed_radius_deg)},
      {"mask.sampling", std::string(name_of(c.mask.sampling))},
      {"mask.remove_pinches", c.mask.remove_pinches ? "true" : "false"},
  };
  if (!sources.empty()) items.insert(items.begin() + 3, {"input.source_files", sources});
  // Several sources (input.paths): the first is input.path above; the others by path, size and time.
  for (std::size_t k = 1; k < rasters.size(); ++k) {
    const fs::path p = fs::absolute(rasters[k]).lexically_normal();
    std::string entry = p.string() + " " + kNotAFile;
    if (fs::is_regular_file(p, ec)) {
      const auto bytes = fs::file_size(p, ec);
      const auto time = fs::last_write_time(p, ec);
      if (!ec) entry = fmt::format("{} {} bytes, mtime {}", p.string(), bytes, time.time_since_epoch().count());
    }
    for (const std::string& f : raster::raster_files(p.string()))
      if (fs::absolute(f).lexically_normal() != p) entry += "; " + fs::absolute(f).lexically_normal().string();
    items.push_back({fmt::format("input.paths[{}]", k), entry});
  }
  if (rasters.size() > 1) items.push_back({"input.blend_km", number(c.input.blend_km)});
  // Listed only when not the default (12000 m), so files written before the key existed still match.
  if (c.input.max_abs_elevation_m != config::InputOptions{}.max_abs_elevation_m)
    items.insert(items.begin() + 7, {"input.max_abs_elevation_m", number(c.input.max_abs_elevation_m)});
  // The carving (mask/carving.hpp), listed only when asked, so files written before it still match:
  // the names, the line files by path, size and time, and the defaults they take.
  const config::MaskOptions& m = c.mask;
  if (!m.passages_open.empty()) {
    std::string names;
    for (const std::string& n : m.passages_open) names += (names.empty() ? "" : ", ") + n;
    items.push_back({"mask.passages_open", "[" + names + "]"});
  }
  const auto line_file = [&](const char* key, const std::string& path, const std::string& layer) {
    if (path.empty()) return;
    const fs::path f = fs::absolute(path).lexically_normal();
    std::string entry = f.string() + " " + kNotAFile;
    if (fs::is_regular_file(f, ec)) {
      const auto bytes = fs::file_size(f, ec);
      const auto time = fs::last_write_time(f, ec);
      if (!ec) entry = fmt::format("{} {} bytes, mtime {}", f.string(), bytes, time.time_since_epoch().count());
    }
    items.push_back({key, entry + (layer.empty() ? std::string() : ", layer " + layer)});
  };
  line_file("mask.transects", m.transects, m.transects_layer);
  line_file("mask.channels", m.channels, m.channels_layer);
  if (!m.transects.empty() || !m.channels.empty())
    items.push_back({"mask.channel_defaults",
                     fmt::format("width {} m, depth {} m", number(m.channel_width_m), number(m.channel_depth_m))});
  return items;
}

std::string mask_inputs_checksum(const std::vector<std::pair<std::string, std::string>>& items) {
  std::uint64_t h = kFnvOffset;
  for (const auto& [k, v] : items) {
    const std::string line = k + "=" + v + "\n";
    h = fnv1a(line.data(), line.size(), h);
  }
  return fmt::format("{:016x}", h);
}

void write_global_run_file(const fs::path& path, const WetArea& area, const Lattice& lattice,
                           const config::GlobalConfig& c, const LevelRows& levels) {
  const std::int64_t nx = lattice.nx, ny = lattice.ny;
  const auto inputs = mask_inputs(c);
  raster::ByteGeoTiffLayout layout;
  layout.width = nx;
  layout.height = ny;
  layout.west_deg = lattice.lon0_deg;
  layout.north_deg = lattice.mercator() ? lattice.plane_y_of(lattice.ny) : 90.0;
  layout.pixel_deg = lattice.pixel_deg();
  layout.mercator = lattice.mercator();
  layout.band_names = {"classes: 1 = in the K-fill (Omega_L), 2 = wet pixel, 4 = coastal pixel",
                       "level: quadtree level of the leaf holding the pixel (255 = outside Omega_L)"};
  layout.no_data = -1;  // band 1 has no no-data; band 2's 255 is documented in its name and AQ_LEVEL_NODATA
  layout.metadata = {
      {"AQ_FORMAT", kFormat},
      {"AQ_FRAME", c.rotation.enabled
                       ? fmt::format("rotated: longitude/latitude of the rotated frame whose North pole is at lon {} "
                                     "lat {} (not EPSG:4326 geographic coordinates)",
                                     number(c.rotation.pole_lon_deg), number(c.rotation.pole_lat_deg))
                       : std::string("geographic")},
      {"AQ_LATTICE", lattice_text(lattice)},
      {"AQ_LEVEL_NODATA", std::to_string(kNoLevel)},
      {"AQ_QUADTREE", fmt::format("coast_band={} balance={} depth_rules={} box_rules={}", c.quadtree.coast_band,
                                  c.quadtree.balance, c.quadtree.depth_rules.size(), c.quadtree.box_rules.size())},
      {"AQ_INPUTS_FNV1A64", mask_inputs_checksum(inputs)},
  };
  for (const auto& [k, v] : inputs) layout.metadata.emplace_back("AQ_INPUT_" + k, v);

  std::vector<std::uint8_t> lev;
  write_byte_geotiff(path, layout, [&](std::int64_t r0, std::int64_t rows, std::vector<std::vector<std::uint8_t>>& b) {
    // File rows r0 .. r0+rows-1 are lattice rows ny-1-r0 down to ny-r0-rows.
    const std::int64_t j_low = ny - r0 - rows;
    lev.assign(static_cast<std::size_t>(rows * nx), kNoLevel);
    levels(j_low, rows, lev.data());
    std::uint8_t* flags = b[0].data();
    std::uint8_t* level = b[1].data();
    const std::uint8_t* lv = lev.data();
    const Bitmap* f = &area.filled;
    const Bitmap* w = &area.wet;
    const Bitmap* co = &area.coastal;
#pragma omp parallel for default(none) shared(flags, level, lv, f, w, co, rows, nx, ny, r0, j_low) schedule(static)
    for (std::int64_t r = 0; r < rows; ++r) {
      const std::int64_t j = ny - 1 - (r0 + r);
      std::uint8_t* out = flags + r * nx;
      for (std::int64_t i = 0; i < nx; ++i) {
        out[i] = static_cast<std::uint8_t>((f->get(i, j) ? kFilledBit : 0) | (w->get(i, j) ? kWetBit : 0) |
                                           (co->get(i, j) ? kCoastalBit : 0));
      }
      std::copy_n(lv + (j - j_low) * nx, nx, level + r * nx);
    }
  });
}

GlobalRunFile read_global_run_file(const fs::path& path, const config::GlobalConfig& c, const Lattice& lattice) {
  const raster::ByteGeoTiff tif(path);
  const auto& layout = tif.layout();
  if (tif.metadata("AQ_FORMAT") != kFormat || layout.band_names.size() != 2)
    throw InputError(fmt::format("{}: not a global run file of aquatoria (AQ_FORMAT \"{}\", expected \"{}\")",
                                 path.string(), tif.metadata("AQ_FORMAT"), kFormat));
  GlobalRunFile out;
  const auto inputs = mask_inputs(c);
  if (inputs[1].second == kNotAFile) {
    out.differs =
        fmt::format("input.path = \"{}\" is not a plain file, so its changes cannot be detected", c.input.path);
    return out;
  }
  if (tif.metadata("AQ_INPUTS_FNV1A64") != mask_inputs_checksum(inputs)) {
    for (const auto& [k, v] : inputs) {
      const std::string stored = tif.metadata("AQ_INPUT_" + k);
      if (stored != v) {
        out.differs = fmt::format("{}: {} -> {}", k, stored.empty() ? "(absent)" : stored, v);
        break;
      }
    }
    if (out.differs.empty()) out.differs = "AQ_INPUTS_FNV1A64 (the items match but the checksum does not)";
    return out;
  }
  if (tif.metadata("AQ_LATTICE") != lattice_text(lattice) || layout.width != lattice.nx ||
      layout.height != lattice.ny) {
    out.differs = fmt::format("lattice: {} -> {}", tif.metadata("AQ_LATTICE"), lattice_text(lattice));
    return out;
  }
  const std::int64_t nx = lattice.nx, ny = lattice.ny;
  WetArea& a = out.area;
  a.filled = Bitmap(nx, ny);
  a.wet = Bitmap(nx, ny);
  a.coastal = Bitmap(nx, ny);
  // Rows per read: several 512-row tile rows (decoded in parallel) within about 64 MB.
  const std::int64_t chunk = std::clamp<std::int64_t>((std::int64_t{1} << 26) / nx / 512 * 512, 512, 2048);
  std::vector<std::uint8_t> buf;
  for (std::int64_t r0 = 0; r0 < ny; r0 += chunk) {
    const std::int64_t rows = std::min(chunk, ny - r0);
    buf.resize(static_cast<std::size_t>(rows * nx));
    tif.read_rows(1, r0, rows, buf.data());
    const std::uint8_t* in = buf.data();
    WetArea* pa = &a;
#pragma omp parallel for default(none) shared(in, pa, rows, nx, ny, r0) schedule(static)
    for (std::int64_t r = 0; r < rows; ++r) {
      const std::int64_t j = ny - 1 - (r0 + r);
      const std::uint8_t* row = in + r * nx;
      for (std::int64_t i = 0; i < nx; ++i) {
        if ((row[i] & kFilledBit) != 0) pa->filled.set(i, j);
        if ((row[i] & kWetBit) != 0) pa->wet.set(i, j);
        if ((row[i] & kCoastalBit) != 0) pa->coastal.set(i, j);
      }
    }
  }
  a.filled_pixels = a.filled.count();
  a.classes.wet = a.wet.count();
  a.classes.coastal = a.coastal.count();
  out.reused = true;
  return out;
}

}  // namespace aq::mask
