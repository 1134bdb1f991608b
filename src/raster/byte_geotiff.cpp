// Byte GeoTIFF writer and reader through GDAL (see byte_geotiff.hpp).
#include "raster/byte_geotiff.hpp"

#include <cpl_conv.h>
#include <fmt/format.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <mutex>
#include <numbers>
#include <system_error>

#include "core/error.hpp"
#include "raster/gdal_handles.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace aq::raster {

namespace {

constexpr int kTile = 512;

// PAM (the .aux.xml sidecar) off for this thread while the object lives.
class NoSidecar {
 public:
  NoSidecar() { CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", "NO"); }
  ~NoSidecar() { CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", nullptr); }
  NoSidecar(const NoSidecar&) = delete;
  NoSidecar& operator=(const NoSidecar&) = delete;
};

}  // namespace

void write_byte_geotiff(const std::filesystem::path& path, const ByteGeoTiffLayout& layout,
                        const ByteRowsSource& rows) {
  gdal_register();
  const NoSidecar no_sidecar;
  const auto fail = [&](const std::string& what) {
    std::error_code ec;
    std::filesystem::remove(path, ec);
    return OutputError(fmt::format("{}: GeoTIFF {}{}", path.string(), what, last_gdal_error()));
  };
  const auto nb = static_cast<int>(layout.band_names.size());
  if (layout.width <= 0 || layout.height <= 0 || nb == 0) throw fail("has no pixels or no bands");
  GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
  if (drv == nullptr) throw fail("driver missing in this GDAL");
  int threads = 1;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  const std::string tile = std::to_string(kTile), nthreads = std::to_string(threads);
  const std::string big =
      static_cast<double>(layout.width) * static_cast<double>(layout.height) * nb > 3.5e9 ? "YES" : "IF_SAFER";
  const std::vector<std::string> opts{"TILED=YES", "BLOCKXSIZE=" + tile, "BLOCKYSIZE=" + tile,      "COMPRESS=DEFLATE",
                                      "ZLEVEL=1",  "INTERLEAVE=BAND",    "NUM_THREADS=" + nthreads, "BIGTIFF=" + big};
  std::vector<char*> copt;
  for (const auto& o : opts) copt.push_back(const_cast<char*>(o.c_str()));
  copt.push_back(nullptr);
  DatasetPtr ds(drv->Create(path.c_str(), static_cast<int>(layout.width), static_cast<int>(layout.height), nb, GDT_Byte,
                            copt.data()));
  if (!ds) throw fail("cannot create");
  // Mercator: a sphere of the Earth's authalic radius R, plane units degrees -> metres (R·π/180).
  constexpr double kRadius = 6371007.181;
  const double unit = layout.mercator ? kRadius * std::numbers::pi / 180.0 : 1.0;
  double gt[6] = {layout.west_deg * unit,  layout.pixel_deg * unit, 0.0, layout.north_deg * unit, 0.0,
                  -layout.pixel_deg * unit};
  if (ds->SetGeoTransform(gt) != CE_None) throw fail("georeferencing");
  OGRSpatialReference srs;
  if (layout.mercator) {
    // x = R·λ, y = R·ln tan(π/4 + φ/2): the lattice's plane degrees times R·π/180.
    if (srs.importFromProj4("+proj=merc +R=6371007.181 +lon_0=0 +x_0=0 +y_0=0 +units=m +no_defs") != OGRERR_NONE)
      throw fail("Mercator coordinate system");
  } else {
    srs.importFromEPSG(4326);
  }
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (ds->SetSpatialRef(&srs) != CE_None) throw fail("coordinate system");
  for (const auto& [k, v] : layout.metadata)
    if (ds->SetMetadataItem(k.c_str(), v.c_str()) != CE_None) throw fail("metadata " + k);
  for (int b = 0; b < nb; ++b) {
    GDALRasterBand* band = ds->GetRasterBand(b + 1);
    band->SetDescription(layout.band_names[static_cast<std::size_t>(b)].c_str());
    if (layout.no_data >= 0 && band->SetNoDataValue(layout.no_data) != CE_None) throw fail("no-data value");
  }
  std::vector<std::vector<std::uint8_t>> buf(static_cast<std::size_t>(nb));
  for (std::int64_t r0 = 0; r0 < layout.height; r0 += kTile) {
    const std::int64_t n = std::min<std::int64_t>(kTile, layout.height - r0);
    for (auto& b : buf) b.assign(static_cast<std::size_t>(n * layout.width), 0);
    rows(r0, n, buf);
    for (int b = 0; b < nb; ++b) {
      if (ds->GetRasterBand(b + 1)->RasterIO(GF_Write, 0, static_cast<int>(r0), static_cast<int>(layout.width),
                                             static_cast<int>(n), buf[static_cast<std::size_t>(b)].data(),
                                             static_cast<int>(layout.width), static_cast<int>(n), GDT_Byte, 0, 0,
                                             nullptr) != CE_None)
        throw fail("write rows");
    }
  }
  CPLErrorReset();
  ds.reset();  // closes: the last tiles are written here
  if (CPLGetLastErrorType() == CE_Failure) throw fail("close");
}

struct ByteGeoTiff::Impl {
  DatasetPtr ds;
};

ByteGeoTiff::ByteGeoTiff(const std::filesystem::path& path) : path_(path), impl_(std::make_unique<Impl>()) {
  gdal_register();
  const NoSidecar no_sidecar;
  // Tiles of one RasterIO request are decoded by GDAL's worker threads (GTiff, GDAL >= 3.6).
  int threads = 1;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  const std::string nthreads = "NUM_THREADS=" + std::to_string(threads);
  const char* open_options[] = {nthreads.c_str(), nullptr};
  impl_->ds.reset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, open_options));
  if (!impl_->ds) throw InputError(fmt::format("{}: cannot open as a raster{}", path.string(), last_gdal_error()));
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
    throw InputError(fmt::format("{}: cannot read band {}{}", path_.string(), band, last_gdal_error()));
}

}  // namespace aq::raster
