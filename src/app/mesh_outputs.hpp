// SPDX-License-Identifier: GPL-3.0-or-later
// All outputs of a global mesh run (ARCHITECTURE §4.8): calls the writer of every format listed
// in output.formats, each into a temporary file of the run's OutputSet (renamed into place only
// when the whole run succeeds), logs one line per file and returns what was written.
//
//   format   file                 writer
//   msh      <name>.msh           Gmsh MSH 4.1, λ–φ plane, ASCII or binary (output.msh_binary)
//   ugrid    <name>.nc            UGRID-1.0 netCDF
//   vtu      <name>.vtu           VTK XML unstructured grid (output.vtu_coordinates)
//   fort14   <name>.14            ADCIRC grid (the `.14` suffix keeps several meshes apart in one
//                                 folder; ADCIRC users link or copy it to fort.14)
//   text     <name>.txt           plain text
//   png      <name>.png           preview map (output.png_width, output.png_color), and
//                                 <name>_zoom.png when output.png_zoom is set
//   fesom    <name>_nod2d.out, <name>_elem2d.out, <name>_aux3d.out   FESOM2 (output.fesom_levels);
//                                 the namelist's Euler angles go to the log and the "fesom" section
//   schism   <name>.gr3, <name>.ll  SCHISM hgrid.gr3 / hgrid.ll (lon/lat, ics = 2)
//   tif      <name>.tif           the global run file (mask/global_run_file.hpp: Ω_L, pixel
//                                 classes, quadtree levels; GeoTIFF), written by the run's
//                                 MeshOutputInfo::global_run_file
// fort14, fesom and schism write the geographic mesh cleaned for the models
// (mesh/model_cleaning.hpp: no triangle with fewer than two neighbours, no pinch vertex; logged,
// the "cleaning" report section), with a warning when a lon-lat lattice gives them triangles with
// an angle above 120°; fesom logs its namelist rotation, schism its time-step range.
// With triangles, the shape quality on the sphere of the geographic mesh (sphere_quality.hpp) is
// logged and becomes the "quality" report section, whatever the formats.
// Every option is checked before the first file is written, so a bad option writes nothing.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/output_jobs.hpp"
#include "config/load.hpp"
#include "config/options.hpp"
#include "core/log.hpp"
#include "core/output_files.hpp"
#include "core/report.hpp"
#include "io/write_stats.hpp"
#include "mesh/mesh.hpp"
#include "mesh/model_cleaning.hpp"
#include "mesh_files/element_kinds.hpp"
#include "mesh_files/ugrid_writer.hpp"
#include "raster/bathymetry.hpp"

namespace aq::io {

/// What the run knows that OutputOptions does not.
struct MeshOutputInfo {
  ElementKinds elements = ElementKinds::kTriangles;  ///< mesh.elements
  std::string source = "aquatoria";                  ///< program and input, for file metadata
  /// Writer of the "tif" format (the mesh alone does not hold the pixel masks); empty = "tif"
  /// is refused (ConfigError naming output.formats).
  std::function<WriteStats(const std::filesystem::path&)> global_run_file;
  /// Write the UGRID file on a thread of its own while the other files are written (see
  /// write_mesh_outputs); false: one file after another.
  bool concurrent = true;
  /// output.png_color = "target": the target size field (km) at each triangle's centre (lattice
  /// mesh order); empty without a size field ("target" then leaves the triangles unfilled).
  std::vector<float> target_km;
  /// [lo, hi] (km) the "size" and "target" colour classes span (the field's range over water), so
  /// both pictures of a run share one scale; empty = each picture's own values.
  std::vector<double> size_scale_km;
};

/// The UGRID writer's options of the "ugrid" format (the Python package's to_xarray describes the
/// same dataset with them).
UgridOptions ugrid_options(const config::OutputOptions& options, const MeshOutputInfo& info);

/// What the cleaning for the models did (the mesh fort14, fesom and schism write), as
/// write_mesh_outputs logs and reports it: the "mesh cleaning: ..." line (with `seconds`, the time
/// the cleaning took), a warning when a lon-lat lattice leaves triangles with an angle above 120°,
/// and the "cleaning" report section. The Python package's Run.model_mesh says the same.
struct ModelMeshNotes {
  std::vector<LogLine> lines;
  Json cleaning;
};
ModelMeshNotes model_mesh_notes(const mesh::ModelMesh& model, double seconds);

/// The warning the "fesom" format gives for a floodplain mesh (floodplain_top_m > 0) of the
/// cleaned model mesh `model` with nodes above the datum (FESOM2 has no wetting and drying: aux3d.out
/// writes them at 0 m); nullopt otherwise. The Python package's Run.model_mesh("fesom") says the same.
std::optional<std::string> fesom_floodplain_warning(const mesh::Mesh& model);

/// Checks output options changed after loading (the Python binding's write(): output.name, and
/// output.formats / png_color against `elements`, config::output_problems); ConfigError listing
/// every problem. load_global() has checked the rest.
void check_mesh_output_options(const config::OutputOptions& options, ElementKinds elements);

/// Writes every requested format (see the table above). The writers in geographic coordinates
/// (ugrid, vtu, text; fort14, fesom, schism cleaned for the models) write the geographic mesh of io/geographic_mesh.hpp
/// (pole cap or merged pole row; one log line per changed pole, and the "geographic_mesh" report section when `report`
/// is given); msh (the λ–φ plane) and png draw the lattice mesh. Throws ConfigError on bad options (before writing
/// anything), OutputError naming the file on write failures. The UGRID writer (netCDF/HDF5, which are not thread-safe)
/// runs on a thread of its own while the others run on this one (info.concurrent), unless the raster is streamed and a
/// preview is written (its reads go through GDAL, whose netCDF driver the preview would call meanwhile). The log lines, the returned files and
/// the error thrown are those of writing one file after another (output_jobs.hpp); every temporary path is reserved and
/// every mesh built on this thread.
std::vector<WrittenFile> write_mesh_outputs(const mesh::Mesh& mesh, const raster::Bathymetry& bathy,
                                            const config::OutputOptions& options, OutputSet& outputs, const Logger& log,
                                            const MeshOutputInfo& info, Report* report = nullptr);

/// As above with the elements the mesh has (triangles if any, else squares).
std::vector<WrittenFile> write_mesh_outputs(const mesh::Mesh& mesh, const raster::Bathymetry& bathy,
                                            const config::OutputOptions& options, OutputSet& outputs,
                                            const Logger& log);

}  // namespace aq::io
