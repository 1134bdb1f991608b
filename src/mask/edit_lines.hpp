// SPDX-License-Identifier: GPL-3.0-or-later
// Lines that edit the bathymetry before the fill (README "Passages, channels and rivers"), read
// from any GDAL/OGR vector layer of lines in lon/lat (GeoJSON, GeoPackage, Shapefile, KML, ...):
//   mask.transects  user passages (carved open, like mask.passages_open) and land blockages
//                   (kept dry): attribute `kind` = "passage" (default) or "blockage";
//                   optional `name`, `depth_m` (a passage's depth, m, positive down), `height_m`
//                   (a blockage's top, m above the datum);
//   mask.channels   channels and rivers burned in as water: optional `name`, `width_m` (m),
//                   `depth_m` (m, positive down); missing ones take mask.channel_width_m /
//                   mask.channel_depth_m.
// Each LineString is one line; a MultiLineString gives one line per part (same attributes).
// Attribute names are matched without case; a number may be stored as a number or as text.
#pragma once

#include <array>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "core/enum_names.hpp"

namespace aq::mask {

enum class LineKind : unsigned char {
  kPassage,   ///< carved open along the line, depth stated or from the raster's deepest path
  kChannel,   ///< carved open, width and depth stated or from the keys (a river, a dredged channel)
  kBlockage,  ///< kept dry along the line (a causeway, a dam, a canal the raster shows as water)
};

/// The `kind` names (a transects file states "passage" or "blockage"; mask.channels lines are
/// channels), printed in the log and the run report.
inline constexpr std::array<EnumName<LineKind>, 3> kLineKindNames{{
    {LineKind::kPassage, "passage", "carved open along the line"},
    {LineKind::kChannel, "channel", "a channel or river burned in as water"},
    {LineKind::kBlockage, "blockage", "kept dry along the line"},
}};
constexpr std::span<const EnumName<LineKind>> enum_names(LineKind) { return kLineKindNames; }

struct EditLine {
  std::string name;   ///< the `name` attribute, or "<key> feature N"
  std::string where;  ///< "mask.channels = \"file\", layer L, feature N (part P)": for messages
  LineKind kind = LineKind::kPassage;
  std::vector<double> lon_deg, lat_deg;                        ///< >= 2 vertices, geographic degrees
  double depth_m = std::numeric_limits<double>::quiet_NaN();   ///< stated depth (m, positive down), NaN = none
  double width_m = std::numeric_limits<double>::quiet_NaN();   ///< stated width (m), NaN = none
  double height_m = std::numeric_limits<double>::quiet_NaN();  ///< stated blockage height (m), NaN = none
};

/// Reads every line feature of `layer` ("" = the first layer) of the vector file `path`, for the
/// configuration key `key` ("mask.transects" or "mask.channels"); `channels` selects the
/// channel form (kind kChannel, no `kind` attribute). Throws InputError naming the key, the file,
/// the layer and the feature: the file cannot be opened as a vector file, no such layer, the
/// layer is not in geographic coordinates, a feature that is not a line (or has fewer than two
/// vertices, or a vertex that is not a lon/lat point), an attribute that is not a number or is
/// out of range (depth_m, width_m > 0; height_m finite), a `kind` that is not passage/blockage,
/// or no line at all.
std::vector<EditLine> read_edit_lines(const std::string& path, const std::string& layer, const std::string& key,
                                      bool channels);

}  // namespace aq::mask
