// SPDX-License-Identifier: GPL-3.0-or-later
// The files of a global mesh run, shared by `aquatoria mesh` and the Python interface
// (python/aquatoria, Run.write): every output.formats file of a pipeline's result into an
// OutputSet, the report's "outputs" section, and the run report <name>_report.json. Both callers
// write the same bytes for the same configuration because they go through these functions.
#pragma once

#include <string>
#include <vector>

#include "app/global_run.hpp"
#include "app/output_jobs.hpp"
#include "config/options.hpp"
#include "core/log.hpp"
#include "core/output_files.hpp"
#include "core/report.hpp"
#include "mesh/mesh.hpp"
#include "raster/bathymetry.hpp"

namespace aq::app {

/// The files' "source" (program, version and input raster): MeshOutputInfo::source of the run.
std::string global_mesh_source(const raster::Bathymetry& bathy);

/// Writes every format of c.output.formats for `run` (after run_global_pipeline) into `out` (not
/// committed), the global run file ("tif") included, and sets report["outputs"] (file, format,
/// bytes, checksum, seconds). Throws what io::write_mesh_outputs throws (ConfigError on a bad
/// output option before anything is written, OutputError naming a file).
std::vector<io::WrittenFile> write_global_mesh_files(const config::GlobalConfig& c, const GlobalRun& run,
                                                     OutputSet& out, const Logger& log, Report& report);

/// Writes report.dump() to <c.output.name>_report.json in `out` (not committed); returns that name.
/// Throws OutputError naming the file when it cannot be written.
std::string write_global_report(const config::GlobalConfig& c, const Report& report, OutputSet& out);

/// The report's "mesh_counts" section: nodes, triangles, squares, boundary_loops, pinch_nodes of
/// the lattice mesh.
Json mesh_counts_json(const mesh::Mesh& m);

}  // namespace aq::app
