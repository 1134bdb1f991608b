// SPDX-License-Identifier: GPL-3.0-or-later
// aq_resample: writes a global lon/lat GeoTIFF (Int16 or Float32) sampled from any raster that
// aquatoria reads, with aquatoria's own sampling (longitude wraps, so a 0..360 source gives a
// seamless result, which gdalwarp does not). Used to make big rasters for benchmarks.
//   aq_resample SRC DST ARCSEC [bilinear|bicubic] [int16|float32]
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "raster/bathymetry.hpp"

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: aq_resample SRC DST ARCSEC [bilinear|bicubic] [int16|float32]\n");
    return 2;
  }
  try {
    aq::raster::OpenOptions o;
    o.path = argv[1];
    const std::string dst = argv[2];
    const double arcsec = std::atof(argv[3]);
    if (!(arcsec > 0) || std::fmod(648000.0, arcsec) != 0.0) {
      std::fprintf(stderr, "aq_resample: ARCSEC %s must divide 648000\n", argv[3]);
      return 2;
    }
    if (argc > 4 && std::string(argv[4]) == "bicubic") o.interpolation = aq::raster::Interpolation::kBicubic;
    const bool f32 = argc > 5 && std::string(argv[5]) == "float32";
    const auto bathy = aq::raster::Bathymetry::open(o);
    const double step = arcsec / 3600.0;
    const auto nx = static_cast<std::int64_t>(std::llround(360.0 / step));
    const auto ny = static_cast<std::int64_t>(std::llround(180.0 / step));
    GDALAllRegister();
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
    char** opts = nullptr;
    opts = CSLSetNameValue(opts, "BIGTIFF", "IF_SAFER");
    GDALDataset* ds =
        drv->Create(dst.c_str(), static_cast<int>(nx), static_cast<int>(ny), 1, f32 ? GDT_Float32 : GDT_Int16, opts);
    CSLDestroy(opts);
    if (ds == nullptr) {
      std::fprintf(stderr, "aq_resample: cannot create %s\n", dst.c_str());
      return 1;
    }
    double gt[6] = {-180.0, step, 0.0, 90.0, 0.0, -step};  // pixel-registered, origin -180
    ds->SetGeoTransform(gt);
    OGRSpatialReference srs;
    srs.importFromEPSG(4326);
    ds->SetSpatialRef(&srs);
    std::vector<double> lons(static_cast<std::size_t>(nx));
    for (std::int64_t i = 0; i < nx; ++i)
      lons[static_cast<std::size_t>(i)] = -180.0 + (static_cast<double>(i) + 0.5) * step;
    const auto cols = bathy.prepare_columns(lons.data(), nx);
    const std::int64_t chunk = 256;
    std::vector<float> buf(static_cast<std::size_t>(nx * chunk));
    for (std::int64_t y0 = 0; y0 < ny; y0 += chunk) {
      const std::int64_t n = std::min(chunk, ny - y0);
#pragma omp parallel for schedule(static)
      for (std::int64_t k = 0; k < n; ++k) {
        const double lat = 90.0 - (static_cast<double>(y0 + k) + 0.5) * step;
        bathy.sample_row(cols, lat, buf.data() + k * nx);
      }
      if (ds->GetRasterBand(1)->RasterIO(GF_Write, 0, static_cast<int>(y0), static_cast<int>(nx), static_cast<int>(n),
                                         buf.data(), static_cast<int>(nx), static_cast<int>(n), GDT_Float32, 0, 0,
                                         nullptr) != CE_None) {
        std::fprintf(stderr, "aq_resample: write error in %s\n", dst.c_str());
        GDALClose(ds);
        return 1;
      }
    }
    GDALClose(ds);
    return 0;
  } catch (const aq::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return e.exit_code();
  }
}
