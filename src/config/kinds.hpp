// SPDX-License-Identifier: GPL-3.0-or-later
// The enumerated options of the global run and of the regional run's [roms] section: each an enum
// with ONE name table (core/enum_names.hpp) that the key table (global_config.cpp, regional.cpp),
// its error messages and help, the run report's echo, the command line and the Python binding read.
// The stages take these enums and never see the names. Options whose enum a stage below config
// needs live there with their table: quadtree.lattice (core/lattice.hpp LatticeKind), the regional
// kinds (grid_params/grid_kinds.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "core/enum_names.hpp"

namespace aq::config {

/// input.interpolation: how the raster is sampled between its points.
enum class Interpolation { kBilinear, kBicubic };
inline constexpr std::array<EnumName<Interpolation>, 2> kInterpolationNames{{
    {Interpolation::kBilinear, "bilinear", "the seed's rule, on the smallest cell of raster points"},
    {Interpolation::kBicubic, "bicubic", "a C2 spline"},
}};
constexpr std::span<const EnumName<Interpolation>> enum_names(Interpolation) { return kInterpolationNames; }

/// mask.sampling: what makes a pixel wet.
enum class Sampling { kVertex, kArea };
inline constexpr std::array<EnumName<Sampling>, 2> kSamplingNames{{
    {Sampling::kVertex, "vertex", "the seed's rule: a pixel is wet when its 4 vertices are"},
    {Sampling::kArea, "area", "the deepest raster cell inside the pixel decides"},
}};
constexpr std::span<const EnumName<Sampling>> enum_names(Sampling) { return kSamplingNames; }

/// quadtree.balance: which neighbours the 2:1 smoothing holds to one level apart.
enum class BalanceMode {
  kFace,    ///< leaves sharing a piece of side differ by <= 1 level
  kCorner,  ///< also leaves touching only at a corner
};
inline constexpr std::array<EnumName<BalanceMode>, 2> kBalanceModeNames{{
    {BalanceMode::kFace, "face", "leaves sharing a piece of side differ by at most one level"},
    {BalanceMode::kCorner, "corner", "also leaves touching only at a corner"},
}};
constexpr std::span<const EnumName<BalanceMode>> enum_names(BalanceMode) { return kBalanceModeNames; }

/// mesh.elements: which elements the mesh and its files hold.
enum class ElementKinds { kTriangles, kSquares, kBoth };
inline constexpr std::array<EnumName<ElementKinds>, 3> kElementKindsNames{{
    {ElementKinds::kTriangles, "triangles", "the squares split by the templates"},
    {ElementKinds::kSquares, "squares", "the quadtree leaves with their hanging nodes"},
    {ElementKinds::kBoth, "both", "triangles and squares"},
}};
constexpr std::span<const EnumName<ElementKinds>> enum_names(ElementKinds) { return kElementKindsNames; }
[[nodiscard]] constexpr bool has_triangles(ElementKinds k) { return k != ElementKinds::kSquares; }
[[nodiscard]] constexpr bool has_squares(ElementKinds k) { return k != ElementKinds::kTriangles; }

/// mesh.diagonal: the diagonal of squares without midside nodes.
enum class Diagonal {
  kNE,         ///< SW–NE
  kNW,         ///< SE–NW
  kAlternate,  ///< "ne" when a + b of the square is even, "nw" when odd (a chequerboard)
};
inline constexpr std::array<EnumName<Diagonal>, 3> kDiagonalNames{{
    {Diagonal::kNE, "ne", "south-west to north-east"},
    {Diagonal::kNW, "nw", "south-east to north-west"},
    {Diagonal::kAlternate, "alternate", "a chequerboard of the two"},
}};
constexpr std::span<const EnumName<Diagonal>> enum_names(Diagonal) { return kDiagonalNames; }

/// domain.kind: what `aquatoria mesh` meshes. kAuto is resolved by the config reader
/// (DomainOptions::resolved is never kAuto).
enum class DomainKind { kAuto, kGlobal, kBox, kPolygon };
inline constexpr std::array<EnumName<DomainKind>, 4> kDomainKindNames{{
    {DomainKind::kAuto, "auto",
     "\"polygon\" when domain.polygon is set, else \"box\" when domain.box is, else \"global\""},
    {DomainKind::kGlobal, "global", "the whole connected ocean"},
    {DomainKind::kBox, "box", "the water inside domain.box"},
    {DomainKind::kPolygon, "polygon", "the water inside domain.polygon"},
}};
constexpr std::span<const EnumName<DomainKind>> enum_names(DomainKind) { return kDomainKindNames; }

/// output.formats: the files `aquatoria mesh` writes, in the order it writes them
/// (app/mesh_outputs.cpp).
enum class OutputFormat { kMsh, kUgrid, kVtu, kFort14, kText, kPng, kFesom, kSchism, kTif };
inline constexpr std::array<EnumName<OutputFormat>, 9> kOutputFormatNames{{
    {OutputFormat::kMsh, "msh", "Gmsh MSH 4.1"},
    {OutputFormat::kUgrid, "ugrid", "UGRID-1.0 netCDF"},
    {OutputFormat::kVtu, "vtu", "ParaView VTU"},
    {OutputFormat::kFort14, "fort14", "ADCIRC fort.14"},
    {OutputFormat::kText, "text", "plain text nodes, elements, boundary"},
    {OutputFormat::kPng, "png", "the preview picture"},
    {OutputFormat::kFesom, "fesom", "FESOM2 nod2d/elem2d/aux3d.out"},
    {OutputFormat::kSchism, "schism", "SCHISM hgrid.gr3/.ll and bctides.in"},
    {OutputFormat::kTif, "tif", "the global run file: the fill, pixel classes and levels as GeoTIFF"},
}};
constexpr std::span<const EnumName<OutputFormat>> enum_names(OutputFormat) { return kOutputFormatNames; }

/// output.vtu_coordinates: where the VTU points are.
enum class VtuCoordinates { kUnitSphere, kWgs84 };
inline constexpr std::array<EnumName<VtuCoordinates>, 2> kVtuCoordinatesNames{{
    {VtuCoordinates::kUnitSphere, "sphere", "on the unit sphere"},
    {VtuCoordinates::kWgs84, "wgs84", "WGS84 earth-centred x, y, z in metres"},
}};
constexpr std::span<const EnumName<VtuCoordinates>> enum_names(VtuCoordinates) { return kVtuCoordinatesNames; }

/// quadtree.engine: what holds the quadtree (README "The forest engine"). Both write the same
/// files; the forest needs the AQ_MPI build.
enum class QuadtreeEngine {
  kDense,   ///< bitmaps over every pixel of the lattice, in one process (the default)
  kForest,  ///< a p4est forest of the level-0 squares: leaves only, on one or many MPI ranks
};
inline constexpr std::array<EnumName<QuadtreeEngine>, 2> kQuadtreeEngineNames{{
    {QuadtreeEngine::kDense, "dense", "bitmaps over every pixel of the lattice, in one process"},
    {QuadtreeEngine::kForest, "forest", "a p4est forest of the level-0 squares on one or many MPI ranks"},
}};
constexpr std::span<const EnumName<QuadtreeEngine>> enum_names(QuadtreeEngine) { return kQuadtreeEngineNames; }
/// The name of `e` (kQuadtreeEngineNames).
[[nodiscard]] inline const char* engine_name(QuadtreeEngine e) { return name_of(e).data(); }

/// The forest engine's patches (forest/patches.hpp) are P × P pixels, P = 2^min(L, this): what
/// its stencils (the coastal band, the K-cursor) may reach across.
inline constexpr int kForestMaxPatchLog2 = 7;
/// P, the side of the forest engine's patches in pixels, for quadtree.levels = `levels` (>= 0).
[[nodiscard]] constexpr std::int64_t forest_patch_pixels(int levels) {
  return std::int64_t{1} << (levels < kForestMaxPatchLog2 ? levels : kForestMaxPatchLog2);
}

/// output.png_color: what fills the elements of the preview (pictures/preview_png.hpp).
enum class PreviewColour { kLevel, kAngle, kSize, kTarget, kElevation };
inline constexpr std::array<EnumName<PreviewColour>, 5> kPreviewColourNames{{
    {PreviewColour::kLevel, "level", "the quadtree level"},
    {PreviewColour::kAngle, "angle", "the smallest angle on the sphere"},
    {PreviewColour::kSize, "size", "the size achieved in km, log classes"},
    {PreviewColour::kTarget, "target", "the size field, on the scale of \"size\""},
    {PreviewColour::kElevation, "elevation", "each element's mean node elevation: the floodplain above the datum"},
}};
constexpr std::span<const EnumName<PreviewColour>> enum_names(PreviewColour) { return kPreviewColourNames; }

/// roms.depth_statistic: the elevation of a ρ cell from the raster (mask/cell_elevation.hpp).
enum class CellStatistic { kAuto, kPoint, kMean, kMedian, kMin };
inline constexpr std::array<EnumName<CellStatistic>, 5> kCellStatisticNames{{
    {CellStatistic::kAuto, "auto", "mean when the raster is finer than the cells, else point"},
    {CellStatistic::kPoint, "point", "the interpolated sample at the cell centre"},
    {CellStatistic::kMean, "mean", "cell-area average of the raster points inside"},
    {CellStatistic::kMedian, "median", "of the raster points inside"},
    {CellStatistic::kMin, "min", "the deepest raster point inside"},
}};
constexpr std::span<const EnumName<CellStatistic>> enum_names(CellStatistic) { return kCellStatisticNames; }

}  // namespace aq::config
