// SPDX-License-Identifier: GPL-3.0-or-later
// The parsers fuzzed by scripts/fuzz.sh (libFuzzer, tests/fuzz/fuzz_main.cpp) and replayed by the
// regression test (tests/fuzz/fuzz_regressions_test.cpp) on every kept input in
// tests/fuzz_regressions/<target>/. Each target feeds the bytes to one reader exactly as a user's
// file or argument would reach it; a clear aq::Error is the expected answer to bad input, so it is
// swallowed. Anything else (another exception, a crash, a sanitizer report, a hang) is a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace aq::fuzz {

/// One fuzz target: its name (the scripts/fuzz.sh argument and the folder of its kept inputs)
/// and the function that runs one input. `run` returns the message of the aq::Error the input
/// ended in, or "" when it was accepted; any other exception propagates.
struct Target {
  std::string_view name;
  std::string (*run)(const std::uint8_t* data, std::size_t size);
};

/// Every target, in the order scripts/fuzz.sh lists them:
///   config_global    the global TOML config (config::load_global of a file)
///   config_regional  the regional TOML config (config::load_regional of a file)
///   izogrid          the seed's .izogrid text (curvilinear::parse_izogrid)
///   set              --set overrides, one per line (config::load_global / load_regional; the
///                    first byte chooses which)
///   roms_grid        a parent ROMS grid _grd.nc (io::read_roms_grid_fields)
///   nesting          a nesting/contact-point file _nesting.nc (io::read_nesting)
///   xygrid           an xygrid netCDF for `aquatoria check` (io::read_xygrid)
///   raster           a bathymetry raster's header and first read (raster::plan_raster and
///                    Bathymetry::open with a 256 MB limit): netCDF-3/4, GeoTIFF, any GDAL format
const std::vector<Target>& targets();

/// The target called `name`, or nullptr.
const Target* find_target(std::string_view name);

}  // namespace aq::fuzz
