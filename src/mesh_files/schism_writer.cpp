// SCHISM hgrid.gr3 / hgrid.ll (see schism_writer.hpp): the fort.14 layout with SCHISM's names.
#include "mesh_files/schism_writer.hpp"

#include "mesh_files/fort14_writer.hpp"

namespace aq::io {

WriteStats write_schism_hgrid(const mesh::Mesh& mesh, const std::filesystem::path& path, const SchismOptions& options) {
  Fort14Options o;
  o.title = options.title;
  o.land_count_name = "NLAND";
  return write_fort14(mesh, path, o);
}

}  // namespace aq::io
