// Plain option structs of the global run, one per TOML section (ARCHITECTURE §7). Defaults here
// are the defaults of the program; configs/example.toml documents every key (a test keeps the two
// in step). Only src/config knows TOML; every other stage receives these structs.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace aq::config {

struct InputOptions {
  std::string path = "/usr/share/ferret-vis/data/etopo5.cdf";  ///< any GDAL raster in lon/lat
  std::string variable;                                        ///< netCDF variable / subdataset name; empty = first
  int band = 1;                                                ///< 1-based band of the raster (or of the variable)
  bool positive_down = false;                                  ///< file stores depth as positive numbers
  std::string interpolation = "bilinear";                      ///< "bilinear" (seed rule) or "bicubic" (C2 spline)
  double max_memory_gb = 0.0;                                  ///< refuse runs estimated above this; 0 = 80% of RAM
  double max_abs_elevation_m = 12000.0;  ///< raster values beyond ±this (m) are no-data (sentinels, bad scales)
};

struct MaskOptions {
  double min_depth_m = 0.0;                                  ///< h: a lattice vertex is wet when elevation <= -h
  int cursor = 2;                                            ///< K of the K-cursor fill, 1..64
  std::vector<std::array<double, 2>> seeds{{-30.0, -50.0}};  ///< lon, lat of fill seeds (degrees)
  double seed_radius_deg = 5.0;     ///< how far a seed may be moved to the nearest all-wet window
  std::string sampling = "vertex";  ///< "vertex" (seed rule) or "area" (min over raster cells)
  bool remove_pinches = false;      ///< take pixels out until no pinch vertex is left
  bool passages = true;             ///< report the critical-passage table
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
  std::string balance = "face";        ///< "face" or "corner"
  double lon0_deg = -180.0;            ///< western edge of the lattice (the seam)
  std::string lattice = "lonlat";      ///< "lonlat" (the seed's) or "mercator" (conformal squares)
  double mercator_lat_max_deg = 86.5;  ///< Mercator rows reach at least ±this latitude (lattice frame)
  double size_km = 0.0;                ///< open-ocean square size target (km); 0 = off
  double coast_size_km = 0.0;          ///< coastal-band square size target (km); 0 = band to level L
  std::vector<DepthRule> depth_rules;
  std::vector<BoxRule> box_rules;
};

struct RotationOptions {
  bool enabled = false;
  double pole_lon_deg = -44.858333;  ///< the seed's Greenland pole, 44°51'30"W
  double pole_lat_deg = 78.141667;   ///< 78°8'30"N
};

struct MeshOptions {
  std::string elements = "triangles";  ///< "triangles", "squares" or "both"
  std::string diagonal = "ne";         ///< "ne", "nw" or "alternate"
};

/// The values output.formats knows, in the order write_mesh_outputs (app/mesh_outputs.hpp) writes them.
inline const std::vector<std::string>& output_format_names() {
  static const std::vector<std::string> names{"msh", "ugrid", "vtu", "fort14", "text", "png", "fesom", "schism", "tif"};
  return names;
}

struct OutputOptions {
  std::string dir = "out";
  std::string name = "mesh";  ///< base name of the output files
  std::vector<std::string> formats{"msh", "ugrid", "vtu", "fort14", "text", "png"};
  bool msh_binary = false;                 ///< Gmsh MSH 4.1 binary instead of ASCII
  int ugrid_deflate = 1;                   ///< UGRID: 1..9 netCDF-4 deflate level, 0 = classic uncompressed
  std::string vtu_coordinates = "sphere";  ///< "sphere" (unit sphere) or "wgs84" (metres, ECEF)
  int png_width = 2400;                    ///< preview width in pixels
  std::vector<double> png_zoom;            ///< optional [lon_min, lon_max, lat_min, lat_max] zoom box
  std::string png_color = "level";         ///< preview fill: "level", "angle" (min angle) or "size" (km)
  std::vector<double> fesom_levels;        ///< FESOM aux3d.out depth levels (m, positive down); empty = default
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

/// The whole configuration of a global run.
struct GlobalConfig {
  InputOptions input;
  MaskOptions mask;
  QuadtreeOptions quadtree;
  RotationOptions rotation;
  MeshOptions mesh;
  OutputOptions output;
  BlocksOptions blocks;
};

}  // namespace aq::config
