// SPDX-License-Identifier: GPL-3.0-or-later
// `aquatoria info FILE [--at LON,LAT ...]`: what the raster is, as found and as normalised, and
// sampled elevations at given points.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "core/error.hpp"
#include "raster/bathymetry.hpp"

namespace aq::app {

namespace {

struct InfoArgs {
  std::string path;
  std::vector<std::string> at;
  std::string variable;
  int band = 1;
  bool positive_down = false;
  std::string interpolation = "bilinear";
  double max_memory_gb = 0.0;
};

int run_info(const InfoArgs& a, const Logger& log) {
  raster::OpenOptions o;
  o.path = a.path;
  o.variable = a.variable;
  o.band = a.band;
  o.positive_down = a.positive_down;
  if (!(a.max_memory_gb >= 0.0) || !std::isfinite(a.max_memory_gb))
    throw ConfigError(fmt::format("--max-memory-gb = {}: must be a finite number >= 0", a.max_memory_gb));
  // A tiny limit is a limit (at least 1 byte), not 0 = "80% of RAM".
  o.max_memory_bytes = a.max_memory_gb > 0.0
                           ? std::max<std::int64_t>(1, static_cast<std::int64_t>(std::min(a.max_memory_gb, 1e9) * 1e9))
                           : 0;
  if (const auto interpolation = parse_name<raster::Interpolation>(a.interpolation))
    o.interpolation = *interpolation;
  else
    throw ConfigError("--interpolation: " + unknown_name_message<raster::Interpolation>(a.interpolation));
  // Parse points first so a typo is reported before the raster is read.
  std::vector<std::pair<double, double>> pts;
  for (const auto& s : a.at) {
    double lon = 0.0, lat = 0.0;
    char tail = 0;
    // sscanf reads "nan" and "inf" as numbers: a point must be finite.
    if (std::sscanf(s.c_str(), "%lf,%lf%c", &lon, &lat, &tail) != 2 || !std::isfinite(lon) ||
        !(lat >= -90.0 && lat <= 90.0)) {
      throw ConfigError(fmt::format("--at {}: expected LON,LAT in degrees, finite, with -90 <= LAT <= 90", s));
    }
    pts.emplace_back(lon, lat);
  }
  // A raster too big to hold (15" GEBCO/ETOPO 2022) is streamed: one banded pass gives its
  // statistics, and the --at samples read single values.
  o.allow_streaming = o.interpolation == raster::Interpolation::kBilinear;
  const auto b = raster::Bathymetry::open(o, log);
  b.ensure_statistics(log.progress("statistics"));
  const auto& i = b.info();
  const double lon_last = i.lon_first_found + static_cast<double>(i.ncols - 1) * i.dlon;
  std::printf("file:          %s\n", i.path.c_str());
  std::printf("driver:        %s\n", i.driver.c_str());
  std::printf("variable:      %s (band %d, %s, units '%s')\n", i.variable.c_str(), a.band, i.data_type.c_str(),
              i.units.c_str());
  std::printf("size:          %lld x %lld (columns x rows as stored)\n", static_cast<long long>(i.width),
              static_cast<long long>(i.height));
  std::printf("resolution:    %.10g x %.10g deg (%.4g' x %.4g')\n", i.dlon, i.dlat, i.dlon * 60.0, i.dlat * 60.0);
  std::printf("registration:  %s%s\n", i.registration.c_str(),
              i.duplicate_column ? " (duplicated 360-degree column dropped)" : "");
  std::printf("longitude:     first sample %.10g as found, %.10g normalised; %s\n", i.lon_first_found, i.lon_first,
              i.global_lon ? "global (wraps)" : fmt::format("regional, to {:.10g}", lon_last).c_str());
  std::printf("latitude:      %.10g .. %.10g; rows stored %s\n", i.lat_first,
              i.lat_first + static_cast<double>(i.nrows - 1) * i.dlat, i.north_up ? "north-up" : "south-up");
  std::printf("crs:           %s\n", i.crs_name.c_str());
  std::printf("no-data:       %s\n", i.has_nodata ? fmt::format("{:g}", i.nodata).c_str() : "none");
  if (i.scale != 1.0 || i.offset != 0.0) std::printf("scale/offset:  %g / %g\n", i.scale, i.offset);
  std::printf("elevation:     min %.1f m, max %.1f m, mean %.1f m (%lld valid values)\n", i.min_m, i.max_m, i.mean_m,
              static_cast<long long>(i.valid_count));
  if (const std::string note = raster::implausible_note(i); !note.empty())
    std::printf("implausible:   %s\n", note.c_str());
  std::printf("memory:        %.1f MB held (float32%s)\n", static_cast<double>(i.memory_bytes) / 1048576.0,
              i.streamed ? fmt::format(", streamed in bands of {} rows", i.band_rows).c_str() : "");
  for (const auto& [lon, lat] : pts) {
    const double z = b.sample(lon, lat);
    std::printf("at %.6g,%.6g: %s\n", lon, lat,
                std::isnan(z) ? "no data" : fmt::format("{:.2f} m ({})", z, z <= 0 ? "sea" : "land").c_str());
  }
  return 0;
}

}  // namespace

void add_info_command(CLI::App& app, Context& ctx) {
  auto args = std::make_shared<InfoArgs>();
  CLI::App* cmd = app.add_subcommand("info", "Describe a bathymetry raster and sample it at points");
  cmd->add_option("file", args->path, "Raster file (any GDAL format in lon/lat)")->required();
  cmd->add_option("--at", args->at, "Sample at LON,LAT (repeatable)")->allow_extra_args(false);
  cmd->add_option("--variable", args->variable, "netCDF variable / subdataset name");
  cmd->add_option("--band", args->band, "1-based band number");
  cmd->add_flag("--positive-down", args->positive_down, "The file stores depth as positive numbers");
  cmd->add_option(
      "--interpolation", args->interpolation,
      fmt::format("Sampling of the --at points: {} (default bilinear)", name_help<raster::Interpolation>()));
  cmd->add_option("--max-memory-gb", args->max_memory_gb,
                  "Hold the raster only below this size as float32 (GB; 0 = 80% of RAM); above it, or above 1 GiB, "
                  "it is streamed in bands of rows");
  cmd->callback([&ctx, args] { ctx.run = [&ctx, args] { return run_info(*args, ctx.log); }; });
}

}  // namespace aq::app
