// SPDX-License-Identifier: GPL-3.0-or-later
// The global run as a file (issue 9): the filled set Ω_L, the pixel classes and the quadtree level
// of every lattice pixel as one compact GeoTIFF (raster/byte_geotiff.hpp), written by
// `aquatoria mesh` (output.formats "tif", <name>.tif) and read back by `aquatoria blocks` and
// `aquatoria regional` instead of re-running the mask stage when its inputs match.
//
// Layout: nx × ny byte pixels, north-up (file row r = lattice row ny − 1 − r), georeferenced in
// EPSG:4326 with the western edge at quadtree.lon0_deg and pixels of Δ_L degrees. With a pole
// rotation the coordinates are those of the rotated frame (metadata AQ_FRAME says so).
//   band 1 "classes"  bit flags: 1 = in Ω_L (the K-fill), 2 = wet pixel, 4 = coastal pixel
//                     (mask/pixel_classes.hpp); 0 = dry or not reached by the fill
//   band 2 "level"    quadtree level 0..L of the leaf holding the pixel; 255 (no-data) outside Ω_L
// Metadata: AQ_FORMAT, AQ_FRAME, AQ_LATTICE, AQ_QUADTREE (the keys that shape band 2), one
// AQ_INPUT_<key> item per input of the mask stage and AQ_INPUTS_FNV1A64, the checksum of them all.
//
// The inputs of the mask stage (mask_inputs): the raster (absolute path, size in bytes and
// modification time of the file; input.variable, band, positive_down, interpolation), the lattice
// (quadtree.step_deg, levels, lon0_deg), rotation.* and every mask.* key except passages (a
// report only). The other files GDAL reads for the raster (a VRT's tiles, sidecars) count by size
// and modification time (input.source_files). A source that is not a plain file (a GDAL subdataset
// string, /vsicurl/...) is never reused.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "config/options.hpp"
#include "core/lattice.hpp"
#include "mask/wet_area.hpp"

namespace aq::mask {

/// The mask stage's inputs as (key, value) items in a fixed order (see the file comment).
std::vector<std::pair<std::string, std::string>> mask_inputs(const config::GlobalConfig& c);

/// 16 hex digits: FNV-1a 64 of the items as "key=value\n" lines.
std::string mask_inputs_checksum(const std::vector<std::pair<std::string, std::string>>& items);

/// Fills the quadtree level of lattice rows [j0, j0 + rows) (south-up): out[(j − j0)·nx + i],
/// 255 where no leaf is. Supplied by the caller (the quadtree stage sits above this one).
using LevelRows = std::function<void(std::int64_t j0, std::int64_t rows, std::uint8_t* out)>;

/// Writes the file (OutputError naming it on failure). `c` gives the inputs and the quadtree keys.
void write_global_run_file(const std::filesystem::path& path, const WetArea& area, const Lattice& lattice,
                           const config::GlobalConfig& c, const LevelRows& levels);

/// What reading a global run file gave.
struct GlobalRunFile {
  bool reused = false;  ///< the inputs matched: `area` holds filled, wet and coastal
  std::string differs;  ///< when not reused: the first differing input, "key: file value -> this run's value"
  WetArea area;         ///< wet_vertices, statistics and passages are not stored (empty)
};

/// Reads `path` when its inputs equal mask_inputs(c) and its lattice is `lattice`; otherwise
/// returns reused = false and what differs. Throws InputError naming the file when it is not a
/// readable global run file.
GlobalRunFile read_global_run_file(const std::filesystem::path& path, const config::GlobalConfig& c,
                                   const Lattice& lattice);

}  // namespace aq::mask
