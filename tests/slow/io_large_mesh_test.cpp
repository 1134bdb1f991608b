// SPDX-License-Identifier: GPL-3.0-or-later
// Writers on a ~10-million-triangle mesh (a regular band of the 0.4° L=2 lattice from the South
// pole to 70°N): every format is written and its counts checked; wall times are printed (they are
// benchmarks, not assertions: the machine is shared).
#include <gtest/gtest.h>

#include <iostream>

#include "core/timer.hpp"
#include "mesh_files/fort14_writer.hpp"
#include "mesh_files/msh_writer.hpp"
#include "mesh_files/text_writer.hpp"
#include "mesh_files/ugrid_writer.hpp"
#include "mesh_files/vtu_writer.hpp"
#include "pictures/preview_png.hpp"
#include "support/io_test_mesh.hpp"
#include "support/temp_dir.hpp"

namespace aq::io::slow_io_large_mesh_test {
namespace {

TEST(LargeMeshWriters, TenMillionTriangles) {
  const Lattice lattice = Lattice::make(0.4, 2, -180.0);  // nx = 3600, ny = 1800
  Timer build;
  const mesh::Mesh m = testing::regular_band_mesh(lattice, 0, 1400);
  const std::int64_t rows = 1400, nx = lattice.nx;
  ASSERT_EQ(m.triangle_count(), 2 * rows * nx);  // 10 080 000
  std::cout << "mesh: " << m.triangle_count() << " triangles, " << m.node_count() << " nodes, built in "
            << build.wall_s() << " s\n";
  testing::TempDir dir;
  auto report = [&](const char* what, const WriteStats& s, const Timer& t) {
    std::cout << what << ": " << t.wall_s() << " s wall, " << static_cast<double>(s.bytes) / 1e6 << " MB\n";
    RecordProperty(what, std::to_string(t.wall_s()));
  };
  {
    Timer t;
    MshOptions o;
    o.binary = true;
    const WriteStats s = write_msh(m, dir / "m.msh", o);
    report("msh binary", s, t);
    EXPECT_EQ(s.elements, m.triangle_count());
    EXPECT_EQ(s.seam_duplicates, rows + 1);
    EXPECT_EQ(s.nodes, m.node_count() + rows + 1);
  }
  {
    Timer t;
    const WriteStats s = write_msh(m, dir / "a.msh");
    report("msh ascii", s, t);
  }
  {
    Timer t;
    const WriteStats s = write_ugrid(m, dir / "m.nc");
    report("ugrid", s, t);
    EXPECT_EQ(s.elements, m.triangle_count());
  }
  {
    Timer t;
    const WriteStats s = write_vtu(m, dir / "m.vtu");
    report("vtu", s, t);
    EXPECT_EQ(s.merged_pole_nodes, nx - 1);  // the South pole row
    EXPECT_EQ(s.dropped_elements, nx);       // one triangle per pole-row square
  }
  {
    Timer t;
    const WriteStats s = write_fort14(m, dir / "m.14");
    report("fort14", s, t);
  }
  {
    Timer t;
    const WriteStats s = write_text(m, dir / "m.txt");
    report("text", s, t);
  }
  {
    const auto bathy =
        raster::Bathymetry::from_grid(std::vector<float>(360 * 181, -3000.0f), 360, 181, -180.0, -90.0, 1.0, 1.0);
    Timer t;
    PreviewOptions o;
    const WriteStats s = write_preview_png(m, bathy, dir / "m.png", o);
    report("png 2400 px", s, t);
  }
}

}  // namespace
}  // namespace aq::io::slow_io_large_mesh_test
