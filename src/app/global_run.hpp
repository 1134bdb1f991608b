// SPDX-License-Identifier: GPL-3.0-or-later
// The global discretizer's pipeline core, shared by `aquatoria mesh` (which writes the mesh),
// `aquatoria blocks` (which ranks coastal blocks of the same run) and `aquatoria regional` (which
// locates a nested grid's boundary points in the same mesh): configuration -> lattice and memory
// check -> bathymetry -> wet area (K-cursor fill) -> quadtree leaves -> mesh -> statistics and
// checks (ARCHITECTURE §4). Output writing stays with each command.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "config/options.hpp"
#include "core/lattice.hpp"
#include "core/log.hpp"
#include "core/report.hpp"
#include "core/rotation.hpp"
#include "mask/carving.hpp"
#include "mask/wet_area.hpp"
#include "mesh/mesh.hpp"
#include "mesh/statistics.hpp"
#include "quadtree/leaves.hpp"
#include "raster/bathymetry.hpp"
#include "size/size_field.hpp"

namespace aq::app {

/// What is known before any data is read: the lattice, the rotation and the memory budget.
struct GlobalSetup {
  Lattice lattice;                      ///< the run's lattice: the global one, or a window of it (regional run)
  Lattice global_lattice;               ///< the global lattice of the configuration
  std::string lattice_note;             ///< why a regional run keeps the global lattice ("" otherwise)
  PoleRotation rotation;
  std::int64_t memory_limit_bytes = 0;  ///< input.max_memory_gb, or 80% of RAM
  std::int64_t lattice_bytes = 0;       ///< estimated bitmaps of the mask and quadtree stages
  std::int64_t triangles_guess = 0;     ///< triangle count guessed before the run (memory model)
  std::int64_t mesh_bytes = 0;          ///< estimated mesh, statistics and writers
  raster::RasterPlan raster;            ///< whole or streamed, from the raster's header (several: summed)
  raster::OpenOptions raster_options;   ///< how the pipeline opens it (several: the first source)
  std::vector<raster::OpenOptions> source_options;  ///< every source, highest priority first
  std::vector<raster::RasterPlan> source_plans;     ///< and its plan (bytes include a blend distance field)
  std::int64_t estimate_bytes = 0;      ///< the whole run (global_run.cpp states the model)
  bool masks_kept = true;               ///< the bitmaps stay beside the mesh (estimate: their sum, not the larger)
  bool forest = false;                  ///< quadtree.engine = "forest": lattice_bytes is the forest per rank
  int ranks = 1;                        ///< MPI ranks of a forest run
};

/// Builds the lattice and rotation of `c`, reads the raster's header (whole or streamed) and
/// refuses, before any data is read, a lattice whose bitmaps would not fit (ConfigError naming
/// quadtree.levels, quadtree.step_deg and input.max_memory_gb) or a run whose memory estimate is
/// above input.max_memory_gb (ConfigError naming the key, the estimate and the limit).
/// A regional run (`[domain]`) gets a window lattice unless `o.allow_window` is false (the commands
/// whose later stages index the global lattice: blocks, the nesting of a ROMS grid in a global run).
/// `o.keep_masks` as the run_global_pipeline that follows will be called: without them (the bitmaps
/// freed before the mesh) the peak is the larger of the bitmap and the mesh parts, not their sum.
struct SetupOptions {
  bool allow_window = true;
  bool keep_masks = true;
  int ranks = 1;  ///< MPI ranks a forest run has (its memory estimate is per rank)
};
GlobalSetup prepare_global_run(const config::GlobalConfig& c, const SetupOptions& o = {});
/// The estimate of `s` had the mesh `triangles` triangles (the model with the count the run made
/// instead of the guess; global_run.cpp states its tolerance).
std::int64_t estimate_bytes_for(const GlobalSetup& s, std::int64_t triangles);
/// The report's "memory" section: the estimate, its parts and the peak RSS so far; with the
/// mesh's `triangles` (> 0) also the estimate for that count (estimate_bytes_for_mesh).
Json memory_json(const GlobalSetup& s, std::int64_t triangles = 0);
/// "memory: estimate ... of ... allowed" before the run.
void log_memory_estimate(const GlobalSetup& s, const Logger& log);

/// Everything the pipeline built; the raster stays open for depths and pictures.
struct GlobalRun {
  GlobalSetup setup;
  std::optional<raster::Bathymetry> bathy;
  mask::Carving carving;  ///< passages, channels and blockages carved into `bathy` (mask/carving.hpp)
  mask::Domain domain;  ///< the meshed region (global: nothing inside)
  mask::WetArea area;
  std::string area_file;          ///< the global run file `area` was read from; "" = computed by the mask stage
  std::string area_file_differs;  ///< when a global run file was present but not reused: why
  size::SizeField size_field;  ///< the target size field (inactive without size terms)
  std::vector<quadtree::Leaf> leaves;
  mesh::Mesh mesh;
  mesh::MeshStatistics statistics;
  /// Per source (highest priority first): mesh nodes whose depth it supplied alone, and nodes
  /// whose depth blends it with the sources below (input.blend_km); nodes without data apart.
  std::vector<std::int64_t> source_nodes, source_blended_nodes;
  std::int64_t no_source_nodes = 0;
};

/// Raster open options from an [input] section (one place for the config -> raster mapping).
raster::OpenOptions raster_options(const config::InputOptions& input, std::int64_t max_memory_bytes);

/// The global run file (mask/global_run_file.hpp) `aquatoria mesh` writes for `c` when
/// output.formats has "tif": <output.dir>/<output.name>.tif.
std::filesystem::path global_run_file_path(const config::GlobalConfig& c);

/// The first stages of run_global_pipeline (read -> mask -> quadtree leaves) and nothing more:
/// `mesh` and `statistics` of the result are empty. For callers that look at the mask and the
/// levels without a mesh (the Python interface's aquatoria.mask). Throws what the stages throw.
GlobalRun run_global_leaves(const config::GlobalConfig& c, const GlobalSetup& setup, const Logger& log, Report* report,
                            bool reuse = false);

/// Runs read -> mask -> quadtree -> mesh -> statistics for `c` (after prepare_global_run);
/// `statistics = false` skips the last stage (WGS84 areas and the mesh checks, the slowest part on
/// fine lattices) for callers that only locate points in a mesh `aquatoria mesh` has checked.
/// Logs the stage lines, the passage table and warnings (pinches, the ocean at the North pole
/// row); fills the report's "input", "lattice", "mask", "quadtree", "mesh" and "statistics"
/// sections when `report` is given. Throws what the stages throw, and InternalError when a mesh
/// check fails (nothing has been written then).
/// With `reuse` set and global_run_file_path(c) present, the mask stage is replaced by reading
/// that file when its inputs match c (log line "mask: reused <file> ..."); when they differ the
/// mask stage runs and a warning names the file and the first differing input.
/// With `keep_masks = false` the lattice bitmaps of `area` (wet_vertices, wet, coastal, filled:
/// 4 bits per pixel, 1.9 GB at 15") are freed as soon as the quadtree has its leaves (`wet` after
/// a regional run's boundary typing); their counts stay. The mesh, its checks and every file but
/// the global run file (`tif`) need none of them. The leaves go too once the mesh is built, unless
/// a preview colours by the size field (its range is taken over the leaves).
GlobalRun run_global_pipeline(const config::GlobalConfig& c, const GlobalSetup& setup, const Logger& log,
                              Report* report, bool statistics = true, bool reuse = false, bool keep_masks = true);

}  // namespace aq::app
