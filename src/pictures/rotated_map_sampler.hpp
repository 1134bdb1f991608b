// SPDX-License-Identifier: GPL-3.0-or-later
// The raster under every pixel centre of a map drawn in a rotated frame (the preview's background,
// preview_png.cpp). Pixel (x, y) shows the raster at rotated (λ'(x), φ'(y)); its geographic
// position costs an atan2 and an asin, and Bathymetry::sample costs as much again (together
// about 45 ns, 0.29 s of CPU for the 6.4 M pixels of the ETOPO5 Mercator map). Here the map is
// cut into cells of kCell × kCell pixels, grouped in tiles of kTile × kTile, aligned to the
// map's origin:
//
//   tile (32 × 32 px)        cell (8 × 8 px; corners at pixels 0 and 8, the next cell's first)
//   +---+---+---+---+        o------s------o   o  raster position (column, row) from atan2/asin
//   |   |   |   |   |        |             |   s  checked: exact against the mean of the side's
//   +---+---+---+---+        s      m      s      two corners, within kMaxError / 2
//   |   |   |   |   |        |             |   m  checked: exact against the mean of the four
//   +---+---+---+---+        o------s------o      corners, within kMaxError
//
// Inside a cell that passes, every pixel's raster position is the bilinear blend of the corners'
// (an error within kMaxError for a position that is quadratic over the cell: the side checks
// bound each direction's curvature, which the centre alone cannot: on a conformal map the column
// is a harmonic function of the pixel, whose two curvatures cancel at the centre). The raster
// values under a tile's passing cells (their corners' bounding box and one cell of margin) are
// read once through Bathymetry::values, and each pixel is interpolated bilinearly in that block
// (in float; Bathymetry::sample blends the same four values in double). A cell takes atan2/asin
// and Bathymetry::sample at each of its pixels instead when a check fails (near a geographic
// pole), when its block would reach past the raster's first or last row (or column, on a raster
// that does not wrap), or when the tile's block would exceed kMaxTileValues. Bicubic and
// streamed rasters are sampled the exact way throughout.
//
// So the result is close to the exact one but not equal bit for bit: a pixel's sample point may
// be off by kMaxError of the raster's row spacing (on the ETOPO5 Mercator map: 6.3 M of 6.4 M
// pixels interpolated; 0.066% of the map's pixels in another tint class than the exact sample
// gives); and a no-data value next to a sample exactly on a grid line, which Bathymetry::sample
// skips, spreads to it. Each pixel depends only on its cell and its tile, so the map is the same
// whichever rows a call samples, and on any number of threads.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/rotation.hpp"
#include "raster/bathymetry.hpp"

namespace aq::io {

class RotatedMapSampler {
 public:
  /// A map of width × height pixels; the centre of pixel (x, y) is at rotated (rlon(x), rlat(y))
  /// degrees of the frame of `rotation`. rlon and rlat must be smooth; they are also evaluated
  /// beyond the map's edges, up to the next multiple of kTile (the last tiles' corners).
  RotatedMapSampler(const raster::Bathymetry& bathy, const PoleRotation& rotation, int width, int height,
                    const std::function<double(double)>& rlon, const std::function<double(double)>& rlat);

  [[nodiscard]] int width() const { return width_; }
  [[nodiscard]] int height() const { return height_; }

  /// Elevation (m, NaN for no data) of the map rows y0 .. y0 + rows - 1 into out (rows × width,
  /// row-major). Thread-safe; fastest for y0 and rows multiples of kTile.
  void sample_rows(int y0, int rows, float* out) const;
  /// The same with atan2, asin and Bathymetry::sample at every pixel (the reference).
  void sample_rows_exact(int y0, int rows, float* out) const;

  static constexpr int kCell = 8;
  static constexpr int kTile = 32;
  /// Largest position error of an interpolated pixel, as a distance on the ground in units of
  /// the raster's row spacing (a row step is dlat, a column step dlon cos φ).
  static constexpr double kMaxError = 1.0 / 16.0;
  static constexpr std::int64_t kMaxTileValues = std::int64_t{1} << 15;

 private:
  struct Position {
    double lon_deg, lat_deg;
  };
  // Geographic position of pixel centre (x, y), up to the last tile's far corner.
  [[nodiscard]] Position position(int x, int y) const;
  void sample_tile(int tx, int ty, int y0, int rows, float* out, std::vector<float>& block) const;
  void sample_cell_exact(int x0, int y0, int x1, int y1, int out_y0, float* out) const;

  const raster::Bathymetry& bathy_;
  raster::RasterInfo info_;
  bool fast_ = false;  // bilinear and held whole: the tile path may be used
  int width_ = 0, height_ = 0;
  std::array<std::array<double, 3>, 3> axes_{};  // geographic unit vectors of the rotated x, y, z axes
  std::vector<double> cos_lon_, sin_lon_, cos_lat_, sin_lat_;
};

}  // namespace aq::io
