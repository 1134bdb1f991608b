// SPDX-License-Identifier: GPL-3.0-or-later
// Iso-depth polylines (the coastline for regional maps, ARCHITECTURE §5 stage 0) by GDAL's
// contour generator on an in-memory copy of the raster window (longitudes unwrapped).
#include <fmt/format.h>
#include <gdal_alg.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cmath>

#include "core/error.hpp"
#include "raster/bathymetry.hpp"

namespace aq::raster {

std::vector<Polyline> contour_lines(const Bathymetry& bathy, double level_m, double lon_min, double lon_max,
                                    double lat_min, double lat_max) {
  GDALAllRegister();
  const RasterInfo& in = bathy.info();
  const auto c_lo = static_cast<std::int64_t>(std::floor((lon_min - in.lon_first) / in.dlon)) - 1;
  const auto c_hi = static_cast<std::int64_t>(std::ceil((lon_max - in.lon_first) / in.dlon)) + 1;
  auto r_lo = static_cast<std::int64_t>(std::floor((lat_min - in.lat_first) / in.dlat)) - 1;
  auto r_hi = static_cast<std::int64_t>(std::ceil((lat_max - in.lat_first) / in.dlat)) + 1;
  r_lo = std::max<std::int64_t>(r_lo, 0);
  r_hi = std::min<std::int64_t>(r_hi, in.nrows - 1);
  const std::int64_t nc = c_hi - c_lo + 1;
  const std::int64_t nr = r_hi - r_lo + 1;
  if (nc < 2 || nr < 2 || nc * nr > (1LL << 28)) {
    throw InputError(
        fmt::format("contour window {}..{} × {}..{} is empty or too large", lon_min, lon_max, lat_min, lat_max));
  }
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDataset* ds = mem->Create("", static_cast<int>(nc), static_cast<int>(nr), 1, GDT_Float32, nullptr);
  std::vector<float> south_up(static_cast<std::size_t>(nc * nr)), buf(south_up.size());
  bathy.values(c_lo, nc, r_lo, nr, south_up.data());  // one block read when the raster is streamed
  for (std::int64_t r = 0; r < nr; ++r)
    for (std::int64_t c = 0; c < nc; ++c) {
      const float v = south_up[static_cast<std::size_t>((nr - 1 - r) * nc + c)];  // north-up for GDAL
      buf[static_cast<std::size_t>(r * nc + c)] = std::isnan(v) ? 1e4f : v;       // no data: high land
    }
  if (ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, static_cast<int>(nc), static_cast<int>(nr), buf.data(),
                                     static_cast<int>(nc), static_cast<int>(nr), GDT_Float32, 0, 0,
                                     nullptr) != CE_None) {
    GDALClose(ds);
    throw InputError("contour: cannot fill the in-memory raster");
  }
  double gt[6] = {in.lon_first + (static_cast<double>(c_lo) - 0.5) * in.dlon, in.dlon, 0.0,
                  in.lat_first + (static_cast<double>(r_hi) + 0.5) * in.dlat, 0.0,     -in.dlat};
  ds->SetGeoTransform(gt);

  GDALDriver* vmem = GetGDALDriverManager()->GetDriverByName("Memory");
  GDALDataset* vds = vmem->Create("", 0, 0, 0, GDT_Unknown, nullptr);
  OGRLayer* layer = vds->CreateLayer("contour", nullptr, wkbLineString, nullptr);
  OGRFieldDefn fid("ID", OFTInteger);
  layer->CreateField(&fid);
  OGRFieldDefn fel("ELEV", OFTReal);
  layer->CreateField(&fel);
  double levels[1] = {level_m};
  const CPLErr err =
      GDALContourGenerate(ds->GetRasterBand(1), 0.0, 0.0, 1, levels, 0, 0.0, layer, 0, 1, nullptr, nullptr);
  std::vector<Polyline> out;
  if (err == CE_None) {
    layer->ResetReading();
    OGRFeature* f = nullptr;
    while ((f = layer->GetNextFeature()) != nullptr) {
      const OGRGeometry* g = f->GetGeometryRef();
      if (g != nullptr && wkbFlatten(g->getGeometryType()) == wkbLineString) {
        const auto* ls = g->toLineString();
        Polyline p;
        for (int k = 0; k < ls->getNumPoints(); ++k) {
          p.lon_deg.push_back(ls->getX(k));
          p.lat_deg.push_back(ls->getY(k));
        }
        out.push_back(std::move(p));
      }
      OGRFeature::DestroyFeature(f);
    }
  }
  GDALClose(vds);
  GDALClose(ds);
  if (err != CE_None) throw InputError("GDAL contour generation failed");
  return out;
}

}  // namespace aq::raster
