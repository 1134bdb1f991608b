// SPDX-License-Identifier: GPL-3.0-or-later
// Plain option structs of the global run, one per TOML section (ARCHITECTURE §7). Defaults here
// are the defaults of the program; configs/example.toml documents every key (a test keeps the two
// in step). Only src/config knows TOML; every other stage receives these structs. Enumerated
// options are enums (config/kinds.hpp, core/lattice.hpp): their names exist only in those tables.
// Every field is validated at load (config/global_config.cpp), alone and against the others, so a
// stage may take these values as given.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "config/kinds.hpp"
#include "core/lattice.hpp"

namespace aq::config {

struct InputOptions {
  std::string path = "/usr/share/ferret-vis/data/etopo5.cdf";  ///< any GDAL raster in lon/lat
  std::string variable;                                        ///< netCDF variable / subdataset name; empty = first
  int band = 1;                                                ///< 1-based band of the raster (or of the variable)
  bool positive_down = false;                                  ///< file stores depth as positive numbers
  Interpolation interpolation = Interpolation::kBilinear;      ///< the seed's bilinear rule or a C2 spline
  double max_memory_gb = 0.0;                                  ///< refuse runs estimated above this; 0 = 80% of RAM
  double max_abs_elevation_m = 12000.0;  ///< raster values beyond ±this (m) are no-data (sentinels, bad scales)
  /// Several rasters, highest priority first (README "Several bathymetry sources"): at every
  /// sample the first one with data wins. Empty = `path` alone. Giving both is a config error.
  std::vector<std::string> paths;
  double blend_km = 0.0;  ///< blend width (km) inside a higher-priority source's edge; 0 = pure priority
  /// Where input.path / input.paths were set: 0 not, 1 a config file, 2 --set (not keys). Both in
  /// one place is an error; a --set of one replaces the other from the file.
  int path_layer = 0, paths_layer = 0;

  /// The rasters of the run, highest priority first: `paths`, or `path` alone.
  [[nodiscard]] std::vector<std::string> sources() const { return paths.empty() ? std::vector<std::string>{path} : paths; }
};

struct MaskOptions {
  /// h (metres, -100..12000): a lattice vertex is wet when elevation <= -h. Negative: the mesh
  /// reaches land up to |h| above the datum that is connected to the ocean (a floodplain for storm
  /// surge and inundation; README "A storm-surge mesh").
  double min_depth_m = 0.0;
  int cursor = 2;                                            ///< K of the K-cursor fill, 1..64
  std::vector<std::array<double, 2>> seeds{{-30.0, -50.0}};  ///< lon, lat of fill seeds (degrees)
  double seed_radius_deg = 5.0;     ///< how far a seed may be moved to the nearest all-wet window
  Sampling sampling = Sampling::kVertex;  ///< the seed's vertex rule or the deepest raster cell
  bool remove_pinches = false;      ///< take pixels out until no pinch vertex is left
  bool passages = true;             ///< report the critical-passage table
  /// Passages of the built-in table (names or aliases, mask/passages.hpp) carved open: a channel
  /// at least K pixels wide along the strait's deepest path (README "Passages, channels and rivers").
  std::vector<std::string> passages_open;
  /// GDAL/OGR line file of user passages (carved open) and land blockages (kept dry), attribute
  /// `kind` = "passage" (default) or "blockage"; "" = none. `transects_layer`: "" = the first layer.
  std::string transects, transects_layer;
  /// GDAL/OGR line file of channels and rivers burned in before the fill; "" = none.
  std::string channels, channels_layer;
  /// Width (m) of a channel line without a width_m attribute; 0 = the narrowest the fill keeps (K pixels).
  double channel_width_m = 0.0;
  /// Depth (m, positive down) of a channel line without depth_m, and of a transect the raster closes.
  double channel_depth_m = 10.0;
  /// Warn, naming it, for every wet component the fill leaves out whose area exceeds this (km², WGS84).
  double warn_dropped_km2 = 1e4;
};

// A depth or box rule asks either a level (`level`) or a size (`size_km` > 0, with level = 0):
// then each square in its range takes the level whose size on the sphere is nearest the target
// (quadtree/leaves.hpp). The config reader takes exactly one of the two keys.
struct DepthRule {
  double min_depth_m = 0.0;  ///< rule applies where depth (positive down) is in [min, max)
  double max_depth_m = 0.0;
  int level = 0;         ///< minimum quadtree level there
  double size_km = 0.0;  ///< > 0: square size target (km) instead of a level; 0 = the level form
};

struct BoxRule {
  double lon_min_deg = 0.0, lon_max_deg = 0.0, lat_min_deg = 0.0, lat_max_deg = 0.0;
  int level = 0;         ///< minimum quadtree level inside the box
  double size_km = 0.0;  ///< > 0: square size target (km) instead of a level; 0 = the level form
};

struct QuadtreeOptions {
  double step_deg = 4.0;               ///< Δ0, must divide 180 (in whole arc-seconds)
  int levels = 3;                      ///< L
  int coast_band = 2;                  ///< Chebyshev distance (pixels) from the coast kept at level L
  BalanceMode balance = BalanceMode::kFace;  ///< 2:1 across faces, or faces and corners
  double lon0_deg = -180.0;            ///< western edge of the lattice (the seam)
  LatticeKind lattice = LatticeKind::kLonLat;  ///< the seed's lon/lat rows or Mercator (conformal squares)
  double mercator_lat_max_deg = 86.5;  ///< Mercator rows reach at least ±this latitude (lattice frame)
  double size_km = 0.0;                ///< open-ocean square size target (km); 0 = off
  double coast_size_km = 0.0;          ///< coastal-band square size target (km); 0 = band to level L
  std::vector<DepthRule> depth_rules;
  std::vector<BoxRule> box_rules;
  QuadtreeEngine engine = QuadtreeEngine::kDense;  ///< what holds the quadtree
};

// The target size field h(x) in km (ARCHITECTURE §4.10, src/size): terms combined by minimum,
// clamped to [h_min_km, h_max_km], gradient-limited to |∇h| <= gradation, CFL-bounded last. Every
// term is off at its default (0 or ""), so without a [size] section the quadtree's level rules
// (the seed's D_l rule and coastal band) and quadtree.size_km / coast_size_km decide alone.
struct SizeCoastOptions {
  double h0_km = 0.0;  ///< h = h0 + alpha·d at distance d (km) from the coast; 0 = off
  double alpha = 0.15;  ///< growth of the coast term (km per km)
};
struct SizeFeatureOptions {
  double r = 0.0;  ///< h = 2(d_MA + d)/R: R elements across a channel at its axis; 0 = off
};
struct SizeWavelengthOptions {
  double wl = 0.0;          ///< h = T·√(gH)/wl: elements per tidal wavelength; 0 = off
  double period_h = 12.42;  ///< T (hours), M2 by default
};
struct SizeSlopeOptions {
  double slp = 0.0;       ///< h = (2π/slp)·H/|∇H|: elements per topographic length scale; 0 = off
  double filter = 0.25;   ///< low-pass box half-width as a fraction of the Rossby radius √(gH)/|f|; 0 = none
  double filter_max_km = 500.0;  ///< the box half-width's upper bound (km; the Rossby radius grows without bound at the equator)
};
// Sizes on the floodplain (mask.min_depth_m < 0): land above the datum inside the mesh.
struct SizeInlandOptions {
  double h0_km = 0.0;  ///< h = h0 + alpha·d on the floodplain, d (km) inland from the shoreline at the datum; 0 = off
  double alpha = 0.2;  ///< growth of the inland term (km per km)
};
struct SizeElevationOptions {
  double h0_km = 0.0;     ///< h = h0 + km_per_m·z on the floodplain, z (m) the elevation above the datum; 0 = off
  double km_per_m = 0.5;  ///< growth of the elevation term (km per metre above the datum)
};
struct SizeCflOptions {
  double dt_s = 0.0;          ///< time step (s) the sizes must keep stable: h >= (√(gH)+u)·Δt/Cr_max; 0 = off
  double courant_max = 0.5;   ///< Cr_max
  double velocity_ms = 0.0;   ///< u (m/s) added to the gravity-wave speed
};
struct SizeOptions {
  double h_min_km = 0.0;     ///< lower clamp of the field (km); 0 = none
  double h_max_km = 0.0;     ///< upper clamp (km), also a term everywhere; 0 = none
  double gradation = 0.0;    ///< g: |∇h| <= g (dimensionless); 0 = no gradient limit
  double min_depth_m = 10.0; ///< H is at least this in √(gH) (wavelength, slope, CFL, the time step report)
  int grid_level = -1;       ///< the field's grid: level-c squares; -1 = finest level with <= 2^20 cells
  std::string raster;        ///< a GDAL raster of sizes in km (lon/lat), combined by minimum; "" = none
  SizeCoastOptions coast;
  SizeFeatureOptions feature;
  SizeWavelengthOptions wavelength;
  SizeSlopeOptions slope;
  SizeInlandOptions inland;
  SizeElevationOptions elevation;
  SizeCflOptions cfl;
};

struct RotationOptions {
  bool enabled = false;
  double pole_lon_deg = -44.858333;  ///< the seed's Greenland pole, 44°51'30"W
  double pole_lat_deg = 78.141667;   ///< 78°8'30"N
};

struct MeshOptions {
  ElementKinds elements = ElementKinds::kTriangles;
  Diagonal diagonal = Diagonal::kNE;
};

struct OutputOptions {
  std::string dir = "out";
  std::string name = "mesh";  ///< base name of the output files
  std::vector<OutputFormat> formats{OutputFormat::kMsh,    OutputFormat::kUgrid, OutputFormat::kVtu,
                                    OutputFormat::kFort14, OutputFormat::kText,  OutputFormat::kPng};
  bool msh_binary = false;                 ///< Gmsh MSH 4.1 binary instead of ASCII
  int ugrid_deflate = 1;                   ///< UGRID: 1..9 netCDF-4 deflate level, 0 = classic uncompressed
  VtuCoordinates vtu_coordinates = VtuCoordinates::kUnitSphere;  ///< unit sphere or WGS84 ECEF metres
  int png_width = 2400;                    ///< preview width in pixels
  std::vector<double> png_zoom;            ///< optional [lon_min, lon_max, lat_min, lat_max] zoom box
  PreviewColour png_color = PreviewColour::kLevel;  ///< what fills the preview's elements
  std::vector<double> fesom_levels;        ///< FESOM aux3d.out depth levels (m, positive down); empty = default

  /// True when `formats` holds `f`.
  [[nodiscard]] bool writes(OutputFormat f) const {
    for (const OutputFormat g : formats)
      if (g == f) return true;
    return false;
  }
};

/// `aquatoria blocks`: coastal blocks of the global run handed to regional grids (ARCHITECTURE §6).
struct BlocksOptions {
  int top = 20;  ///< blocks written, best ranked first (1..999)
  std::vector<std::array<double, 4>>
      boxes;                   ///< [lon_min, lon_max, lat_min, lat_max] (degrees); empty = level-0 squares
  bool shrink_to_wet = false;  ///< move the sides inward over land toward the wet area
  double max_inset = 0.3;      ///< shrink_to_wet: farthest a side moves, fraction of the block (0..0.45)
  int ny = 0;                  ///< cells along η of each regional grid; 0 = from `refinement`
  int refinement = 3;          ///< suggested ny: cells this many times finer than the finest global element
  int points_per_side = 8;     ///< contour control points per side (2..64)
};

/// What `aquatoria mesh` meshes (README "Regional FE meshes"): the whole connected ocean, or only
/// the water inside a lon/lat box or a polygon, with open boundaries where the domain cuts the sea.
struct DomainOptions {
  /// kAuto (the default): kPolygon when `polygon` is set, else kBox when `box` is set, else
  /// kGlobal. Resolved by the config reader into `resolved`.
  DomainKind kind = DomainKind::kAuto;
  DomainKind resolved = DomainKind::kGlobal;  ///< never kAuto
  std::vector<double> box;  ///< [lon_min, lon_max, lat_min, lat_max]; lon_max < lon_min: across the seam
  std::string polygon;      ///< GDAL/OGR vector file (GeoPackage, GeoJSON, Shapefile, ...) in lon/lat
  std::string layer;        ///< layer name; "" = the first layer
  int feature = -1;         ///< feature index (0-based, in the layer's order after `where`); -1 = all
  std::string where;        ///< OGR attribute filter, e.g. "name = 'North Sea'"; "" = none
  [[nodiscard]] bool regional() const { return resolved != DomainKind::kGlobal; }
};

/// The whole configuration of a global run.
struct GlobalConfig {
  DomainOptions domain;
  InputOptions input;
  MaskOptions mask;
  QuadtreeOptions quadtree;
  SizeOptions size;
  RotationOptions rotation;
  MeshOptions mesh;
  OutputOptions output;
  BlocksOptions blocks;
};

}  // namespace aq::config
