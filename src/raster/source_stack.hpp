// SPDX-License-Identifier: GPL-3.0-or-later
// Private to src/raster: several bathymetry sources behind one Bathymetry (README "Several
// bathymetry sources"). Each source is an ordinary Bathymetry (opened, validated and normalised
// like a single raster); the stack only decides, point by point, which source's sample is used:
//
//   value_k(p) = v_k(p)                              when k is the last source, or w_k(p) = 1
//              = value_{k+1}(p)                       when v_k(p) is NaN (outside / no data)
//              = v_k(p)                               when value_{k+1}(p) is NaN
//              = w_k·v_k(p) + (1 − w_k)·value_{k+1}(p) otherwise
//
// with w_k(p) = s²(3 − 2s), s = min(1, d_k(p)/blend_km) (w_k = 1 when blend_km = 0) and d_k the
// distance in km from p to the edge of source k's data: its grid points that are no-data, that
// have a no-data neighbour (of 8), or that lie on the outermost row/column of a raster not
// covering 360° in longitude or not reaching a pole. d_k is computed once on source k's own grid
// (a Euclidean distance transform, Felzenszwalb & Huttenlocher 2012, on the local equirectangular
// plane of each row: Δx = R·cos φ·Δλ, Δy = R·Δφ, R = 6371.0088 km, capped at blend_km) and
// interpolated bilinearly like the source itself, so it is 0 exactly where source k's bilinear
// samples end and the blend is continuous there.
#pragma once

#include <vector>

#include "raster/bathymetry.hpp"

namespace aq::raster {

struct Bathymetry::Stack {
  std::vector<Bathymetry> sources;    ///< highest priority first, at least 2
  std::vector<Bathymetry> distances;  ///< blend_km > 0: d_k (km) of every source but the last
  double blend_km = 0.0;

  [[nodiscard]] double sample(double lon_deg, double lat_deg) const;
  void sample_points(const double* lon_deg, const double* lat_deg, std::int64_t n, double* out, int* code) const;
  [[nodiscard]] Columns prepare_columns(const double* lons, std::int64_t n, bool skip_tiled) const;
  void sample_row(const Columns& cols, double lat_deg, float* out) const;
  void sample_rows(const Columns& cols, const double* lats, std::int64_t n, const RowSink& sink,
                   const ProgressFn& progress) const;
  void ensure_statistics(const ProgressFn& progress) const;

 private:
  [[nodiscard]] double sample_from(std::size_t k, double lon_deg, double lat_deg) const;
  void points_from(std::size_t k, const double* lon_deg, const double* lat_deg, std::int64_t n, double* out,
                   int* code) const;
  void row_from(std::size_t k, const Columns& cols, double lat_deg, float* out) const;
  void block_from(std::size_t k, const Columns& cols, const double* lats, std::int64_t n, float* const* out) const;
};

/// d (km) to the edge of `source`'s data at every one of its grid points, capped at `cap_km`, as
/// a Bathymetry on the same grid (see the top of this file). `source` must be held whole.
Bathymetry edge_distance_field(const Bathymetry& source, double cap_km);

}  // namespace aq::raster
