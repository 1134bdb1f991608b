// SPDX-License-Identifier: GPL-3.0-or-later
// Reading lines of transects and channels through GDAL/OGR (see edit_lines.hpp).
#include "mask/edit_lines.hpp"

#include <fmt/format.h>
#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>

#include "core/error.hpp"

namespace aq::mask {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The index of the field called `name` (without case), or -1.
int field_index(OGRFeatureDefnH defn, const char* name) {
  const int n = OGR_FD_GetFieldCount(defn);
  for (int k = 0; k < n; ++k)
    if (lower(OGR_Fld_GetNameRef(OGR_FD_GetFieldDefn(defn, k))) == name) return k;
  return -1;
}

// The number in field `k` of `f`, NaN when the field is missing or null; throws naming `where`
// when it is text that is not a number.
double number_field(OGRFeatureH f, int k, const std::string& where, const char* name) {
  if (k < 0 || OGR_F_IsFieldSetAndNotNull(f, k) == 0) return std::numeric_limits<double>::quiet_NaN();
  const OGRFieldType t = OGR_Fld_GetType(OGR_F_GetFieldDefnRef(f, k));
  if (t == OFTReal || t == OFTInteger || t == OFTInteger64) return OGR_F_GetFieldAsDouble(f, k);
  const std::string text = OGR_F_GetFieldAsString(f, k);
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  while (end != nullptr && *end != '\0' && std::isspace(static_cast<unsigned char>(*end)) != 0) ++end;
  if (text.empty() || end == nullptr || *end != '\0')
    throw InputError(fmt::format("{}: attribute {} = \"{}\" is not a number", where, name, text));
  return v;
}

void add_parts(OGRGeometryH g, std::vector<std::vector<std::array<double, 2>>>& parts, bool& other) {
  if (g == nullptr) return;
  const OGRwkbGeometryType t = wkbFlatten(OGR_G_GetGeometryType(g));
  if (t == wkbLineString) {
    std::vector<std::array<double, 2>> pts;
    for (int k = 0; k < OGR_G_GetPointCount(g); ++k) pts.push_back({OGR_G_GetX(g, k), OGR_G_GetY(g, k)});
    parts.push_back(std::move(pts));
  } else if (t == wkbMultiLineString || t == wkbGeometryCollection) {
    for (int k = 0; k < OGR_G_GetGeometryCount(g); ++k) add_parts(OGR_G_GetGeometryRef(g, k), parts, other);
  } else {
    other = true;
  }
}

}  // namespace

std::vector<EditLine> read_edit_lines(const std::string& path, const std::string& layer_name, const std::string& key,
                                      bool channels) {
  GDALAllRegister();
  struct Closer {
    void operator()(void* h) const { GDALClose(h); }
  };
  std::unique_ptr<void, Closer> ds(
      GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
  if (!ds) {
    const char* m = CPLGetLastErrorMsg();
    throw InputError(fmt::format("{} = \"{}\": GDAL/OGR cannot open it as a vector file{}", key, path,
                                 m != nullptr && *m != '\0' ? fmt::format(" ({})", m) : std::string()));
  }
  OGRLayerH layer =
      layer_name.empty() ? GDALDatasetGetLayer(ds.get(), 0) : GDALDatasetGetLayerByName(ds.get(), layer_name.c_str());
  if (layer == nullptr) {
    throw InputError(layer_name.empty() ? fmt::format("{} = \"{}\": the file has no layer", key, path)
                                        : fmt::format("{}_layer = \"{}\": no such layer in {}", key, layer_name, path));
  }
  const std::string lname = OGR_L_GetName(layer);
  if (OGRSpatialReferenceH srs = OGR_L_GetSpatialRef(layer); srs != nullptr && OSRIsGeographic(srs) == 0) {
    throw InputError(
        fmt::format("{} = \"{}\", layer \"{}\": not in geographic lon/lat coordinates; reproject it "
                    "(e.g. ogr2ogr -t_srs EPSG:4326)",
                    key, path, lname));
  }
  OGRFeatureDefnH defn = OGR_L_GetLayerDefn(layer);
  const int f_name = field_index(defn, "name"), f_kind = field_index(defn, "kind");
  const int f_depth = field_index(defn, "depth_m"), f_width = field_index(defn, "width_m");
  const int f_height = field_index(defn, "height_m");
  OGR_L_ResetReading(layer);
  std::vector<EditLine> out;
  long index = 0;
  for (OGRFeatureH f = OGR_L_GetNextFeature(layer); f != nullptr; f = OGR_L_GetNextFeature(layer), ++index) {
    std::unique_ptr<void, void (*)(void*)> hold(f, [](void* h) { OGR_F_Destroy(static_cast<OGRFeatureH>(h)); });
    const std::string where = fmt::format("{} = \"{}\", layer \"{}\", feature {}", key, path, lname, index);
    EditLine base;
    base.kind = channels ? LineKind::kChannel : LineKind::kPassage;
    if (f_name >= 0 && OGR_F_IsFieldSetAndNotNull(f, f_name) != 0) base.name = OGR_F_GetFieldAsString(f, f_name);
    if (base.name.empty()) base.name = fmt::format("{} feature {}", key, index);
    if (!channels && f_kind >= 0 && OGR_F_IsFieldSetAndNotNull(f, f_kind) != 0) {
      const std::string k = lower(OGR_F_GetFieldAsString(f, f_kind));
      const std::optional<LineKind> kind = parse_name<LineKind>(k);
      if (kind == LineKind::kBlockage)
        base.kind = LineKind::kBlockage;
      else if (kind != LineKind::kPassage && !k.empty())
        throw InputError(fmt::format("{}: kind = \"{}\" is not \"passage\" or \"blockage\"", where,
                                     OGR_F_GetFieldAsString(f, f_kind)));
    }
    base.depth_m = number_field(f, f_depth, where, "depth_m");
    base.width_m = channels ? number_field(f, f_width, where, "width_m") : std::numeric_limits<double>::quiet_NaN();
    base.height_m = number_field(f, f_height, where, "height_m");
    if (!std::isnan(base.depth_m) && !(std::isfinite(base.depth_m) && base.depth_m > 0.0 && base.depth_m <= 12000.0))
      throw InputError(
          fmt::format("{}: depth_m = {} is not a depth in (0, 12000] m (positive down)", where, base.depth_m));
    if (!std::isnan(base.width_m) && !(std::isfinite(base.width_m) && base.width_m > 0.0 && base.width_m <= 1e6))
      throw InputError(fmt::format("{}: width_m = {} is not a width in (0, 1000000] m", where, base.width_m));
    if (!std::isnan(base.height_m) && !(std::isfinite(base.height_m) && std::abs(base.height_m) <= 12000.0))
      throw InputError(fmt::format("{}: height_m = {} is not a height in [-12000, 12000] m", where, base.height_m));
    std::vector<std::vector<std::array<double, 2>>> parts;
    bool other = false;
    add_parts(OGR_F_GetGeometryRef(f), parts, other);
    if (other || parts.empty()) {
      OGRGeometryH g = OGR_F_GetGeometryRef(f);
      throw InputError(fmt::format("{}: the geometry is {}, not a line (LineString or MultiLineString)", where,
                                   g == nullptr ? std::string("empty") : std::string(OGR_G_GetGeometryName(g))));
    }
    for (std::size_t p = 0; p < parts.size(); ++p) {
      const std::string pw = parts.size() > 1 ? fmt::format("{} (part {})", where, p) : where;
      if (parts[p].size() < 2) throw InputError(fmt::format("{}: a line needs at least two vertices", pw));
      EditLine l = base;
      l.where = pw;
      for (const auto& [x, y] : parts[p]) {
        if (!std::isfinite(x) || !std::isfinite(y) || std::abs(y) > 90.0 || std::abs(x) > 720.0)
          throw InputError(fmt::format("{}: vertex ({}, {}) is not a lon/lat point", pw, x, y));
        l.lon_deg.push_back(x);
        l.lat_deg.push_back(y);
      }
      out.push_back(std::move(l));
    }
  }
  if (out.empty()) throw InputError(fmt::format("{} = \"{}\", layer \"{}\": no line feature", key, path, lname));
  return out;
}

}  // namespace aq::mask
