// SPDX-License-Identifier: GPL-3.0-or-later
// Byte GeoTIFF writer and reader through GDAL (see byte_geotiff.hpp).
#include "raster/byte_geotiff.hpp"

#include <cpl_conv.h>
#include <fmt/format.h>
#include <gdal_priv.h>

#include <algorithm>
#include <numbers>

#include "core/error.hpp"
#include "raster/gdal_common.hpp"
#include "raster/geotiff_writer.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace aq::raster {

namespace {

constexpr int kTile = 512;

}  // namespace

void write_byte_geotiff(const std::filesystem::path& path, const ByteGeoTiffLayout& layout,
                        const ByteRowsSource& rows) {
  const auto nb = static_cast<int>(layout.band_names.size());
  if (layout.width <= 0 || layout.height <= 0 || nb == 0)
    throw OutputError(fmt::format("{}: GeoTIFF has no pixels or no bands", path.string()));
  int threads = 1;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  GeoTiffSpec spec;
  spec.width = layout.width;
  spec.height = layout.height;
  spec.bands = nb;
  spec.type = GeoTiffType::kByte;
  const std::string tile = std::to_string(kTile), nthreads = std::to_string(threads);
  const std::string big =
      static_cast<double>(layout.width) * static_cast<double>(layout.height) * nb > 3.5e9 ? "YES" : "IF_SAFER";
  spec.creation_options = {"TILED=YES", "BLOCKXSIZE=" + tile, "BLOCKYSIZE=" + tile,      "COMPRESS=DEFLATE",
                           "ZLEVEL=1",  "INTERLEAVE=BAND",    "NUM_THREADS=" + nthreads, "BIGTIFF=" + big};
  // Mercator: a sphere of the Earth's authalic radius R, plane units degrees -> metres (R·π/180).
  constexpr double kRadius = 6371007.181;
  const double unit = layout.mercator ? kRadius * std::numbers::pi / 180.0 : 1.0;
  spec.geotransform = {layout.west_deg * unit,  layout.pixel_deg * unit, 0.0, layout.north_deg * unit, 0.0,
                       -layout.pixel_deg * unit};
  // x = R·λ, y = R·ln tan(π/4 + φ/2): the lattice's plane degrees times R·π/180.
  if (layout.mercator) spec.proj4 = "+proj=merc +R=6371007.181 +lon_0=0 +x_0=0 +y_0=0 +units=m +no_defs";
  spec.metadata = layout.metadata;
  spec.band_names = layout.band_names;
  if (layout.no_data >= 0) spec.no_data = layout.no_data;
  GeoTiffWriter out(path.string(), spec);
  std::vector<std::vector<std::uint8_t>> buf(static_cast<std::size_t>(nb));
  for (std::int64_t r0 = 0; r0 < layout.height; r0 += kTile) {
    const std::int64_t n = std::min<std::int64_t>(kTile, layout.height - r0);
    for (auto& b : buf) b.assign(static_cast<std::size_t>(n * layout.width), 0);
    rows(r0, n, buf);
    for (int b = 0; b < nb; ++b) out.write_rows(b + 1, r0, n, buf[static_cast<std::size_t>(b)].data());
  }
  out.close();
}

struct ByteGeoTiff::Impl {
  DatasetPtr ds;
};

ByteGeoTiff::ByteGeoTiff(const std::filesystem::path& path) : path_(path), impl_(std::make_unique<Impl>()) {
  gdal_init();
  const NoSidecar no_sidecar;
  // Tiles of one RasterIO request are decoded by GDAL's worker threads (GTiff, GDAL >= 3.6).
  int threads = 1;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  const std::string nthreads = "NUM_THREADS=" + std::to_string(threads);
  const char* open_options[] = {nthreads.c_str(), nullptr};
  impl_->ds.reset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, open_options));
  if (!impl_->ds) throw InputError(fmt::format("{}: cannot open as a raster{}", path.string(), gdal_message()));
  GDALDataset& ds = *impl_->ds;
  layout_.width = ds.GetRasterXSize();
  layout_.height = ds.GetRasterYSize();
  double gt[6] = {0, 1, 0, 0, 0, -1};
  ds.GetGeoTransform(gt);
  layout_.west_deg = gt[0];
  layout_.north_deg = gt[3];
  layout_.pixel_deg = gt[1];
  for (int b = 1; b <= ds.GetRasterCount(); ++b) {
    if (ds.GetRasterBand(b)->GetRasterDataType() != GDT_Byte)
      throw InputError(fmt::format("{}: band {} is not a byte band", path.string(), b));
    layout_.band_names.emplace_back(ds.GetRasterBand(b)->GetDescription());
  }
  if (char** md = ds.GetMetadata(); md != nullptr) {
    for (char** p = md; *p != nullptr; ++p) {
      char* key = nullptr;
      const char* value = CPLParseNameValue(*p, &key);
      if (key != nullptr) layout_.metadata.emplace_back(key, value != nullptr ? value : "");
      CPLFree(key);
    }
  }
}

ByteGeoTiff::~ByteGeoTiff() = default;

std::string ByteGeoTiff::metadata(const std::string& key) const {
  for (const auto& [k, v] : layout_.metadata)
    if (k == key) return v;
  return {};
}

void ByteGeoTiff::read_rows(int band, std::int64_t row0, std::int64_t rows, std::uint8_t* out) const {
  if (band < 1 || band > static_cast<int>(layout_.band_names.size()) || row0 < 0 || rows < 0 ||
      row0 + rows > layout_.height)
    throw InternalError(
        fmt::format("{}: read band {} rows {}+{} outside the raster", path_.string(), band, row0, rows));
  if (impl_->ds->GetRasterBand(band)->RasterIO(GF_Read, 0, static_cast<int>(row0), static_cast<int>(layout_.width),
                                               static_cast<int>(rows), out, static_cast<int>(layout_.width),
                                               static_cast<int>(rows), GDT_Byte, 0, 0, nullptr) != CE_None)
    throw InputError(fmt::format("{}: cannot read band {}{}", path_.string(), band, gdal_message()));
}

}  // namespace aq::raster
