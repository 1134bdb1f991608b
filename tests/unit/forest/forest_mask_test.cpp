// SPDX-License-Identifier: GPL-3.0-or-later
// The forest engine's lattice brick, pixel classes and K-cursor fill against the dense engine on
// the real ETOPO5: the same bits on the seed's lattice, on a rotated one and on finer ones.
#include <gtest/gtest.h>

#include <string>

#include "forest/classify.hpp"
#include "forest/fill.hpp"
#include "forest/mpi_session.hpp"
#include "mask/wet_area.hpp"
#include "quadtree/leaves.hpp"

namespace aq::forest::unit_forest_forest_mask_test {
namespace {

// Under mpirun (ctest label mpi: `mpirun -np 2 unit_forest`) every rank runs every test and the
// collectives meet; MPI is ended once after the last test so that mpirun sees a clean exit.
class MpiEnvironment : public ::testing::Environment {
 public:
  void TearDown() override {
    if (mpi_running()) (void)finish_run(0, "", false);
  }
};
[[maybe_unused]] const ::testing::Environment* const kMpi = ::testing::AddGlobalTestEnvironment(new MpiEnvironment);

const raster::Bathymetry& etopo5() {
  static const raster::Bathymetry b = [] {
    raster::OpenOptions o;
    o.path = std::string(AQ_ETOPO_DIR) + "/etopo5.cdf";
    return raster::Bathymetry::open(o);
  }();
  return b;
}

TEST(ForestBrick, TreesAndQuadrantsFollowTheDenseLeafOrder) {
  start_mpi();
  const Lattice lat = Lattice::make(4.0, 3, -180.0);
  const LatticeBrick brick(lat);
  ASSERT_EQ(brick.nx0(), 90);
  ASSERT_EQ(brick.ny0(), 45);
  const Comm comm;
  ForestPtr f = uniform_forest(brick, comm, 2);
  // p4est's order of the level-2 quadrants is the dense order of level-2 leaves.
  quadtree::LeafKey prev{};
  std::int64_t count = 0;
  for (p4est_topidx_t t = f->first_local_tree; t <= f->last_local_tree; ++t) {
    const auto* tree = static_cast<const p4est_tree_t*>(sc_array_index(f->trees, static_cast<size_t>(t)));
    for (size_t k = 0; k < tree->quadrants.elem_count; ++k) {
      const auto* q =
          static_cast<const p4est_quadrant_t*>(sc_array_index(const_cast<sc_array_t*>(&tree->quadrants), k));
      const Square s = brick.square(t, *q);
      ASSERT_EQ(s.level, 2);
      EXPECT_EQ(brick.tree(s.a >> 2, s.b >> 2), t);
      const quadtree::LeafKey key = quadtree::leaf_key(lat, quadtree::Leaf{s.level, s.a, s.b});
      if (count > 0) {
        EXPECT_LT(prev, key) << "quadrant " << count;
      }
      prev = key;
      std::int64_t t2 = 0;
      p4est_quadrant_t back;
      brick.quadrant(s, t2, back);
      EXPECT_EQ(t2, t);
      EXPECT_EQ(back.x, q->x);
      EXPECT_EQ(back.y, q->y);
      ++count;
    }
  }
  EXPECT_EQ(comm.sum(count), 90 * 45 * 16);  // the quadrants of every rank
}

TEST(ForestBrick, FacesJoinTheNeighbouringLevel0Squares) {
  start_mpi();
  for (const bool periodic : {true, false}) {
    Lattice lat = Lattice::make(4.0, 3, -180.0);
    if (!periodic) lat = Lattice::window(lat, 8 * 10, 8 * 20, 8 * 5, 8 * 12);
    const LatticeBrick brick(lat);
    const p4est_connectivity_t* c = brick.connectivity();
    ASSERT_EQ(c->num_trees, brick.trees());
    for (std::int64_t t = 0; t < brick.trees(); ++t) {
      const std::int64_t a0 = brick.tree_a0(t), b0 = brick.tree_b0(t);
      const std::int64_t w = a0 > 0 ? brick.tree(a0 - 1, b0) : periodic ? brick.tree(brick.nx0() - 1, b0) : t;
      const std::int64_t e = a0 + 1 < brick.nx0() ? brick.tree(a0 + 1, b0) : periodic ? brick.tree(0, b0) : t;
      const std::int64_t s = b0 > 0 ? brick.tree(a0, b0 - 1) : t;
      const std::int64_t n = b0 + 1 < brick.ny0() ? brick.tree(a0, b0 + 1) : t;
      EXPECT_EQ(c->tree_to_tree[4 * t + 0], w) << "tree " << t << " west";
      EXPECT_EQ(c->tree_to_tree[4 * t + 1], e) << "tree " << t << " east";
      EXPECT_EQ(c->tree_to_tree[4 * t + 2], s) << "tree " << t << " south";
      EXPECT_EQ(c->tree_to_tree[4 * t + 3], n) << "tree " << t << " north";
      if (::testing::Test::HasFailure()) return;
    }
  }
}

struct Case {
  double step;
  int levels;
  int k;
  bool rotated;
};

class ForestMask : public ::testing::TestWithParam<Case> {};

TEST_P(ForestMask, WetAndFilledBitsEqualTheDenseEngine) {
  start_mpi();
  const Case c = GetParam();
  const Lattice lat = Lattice::make(c.step, c.levels, -180.0);
  const PoleRotation rot = c.rotated ? PoleRotation(-44.858333, 78.141667) : PoleRotation();
  config::MaskOptions o;
  o.cursor = c.k;
  o.passages = false;
  const mask::WetArea dense = mask::compute_wet_area(etopo5(), lat, rot, o, Logger::null(), nullptr);

  const LatticeBrick brick(lat);
  const Comm comm;
  const PatchForest pf(brick, comm);
  const StackBounds bounds(etopo5(), lat.pixel_deg() * static_cast<double>(pf.grid().size), 0.0);
  const PatchClasses pc = classify_patches(pf, etopo5(), bounds, rot, 0.0, mask::PixelWindow{});
  EXPECT_EQ(pc.counts.wet_vertices, dense.classes.wet_vertices);
  EXPECT_EQ(pc.counts.wet, dense.classes.wet);
  EXPECT_EQ(pc.counts.coastal, dense.classes.coastal);
  EXPECT_GT(pc.decided, 0);
  const Bitmap wet = gather_dense(pf, pc.wet);  // on rank 0
  if (comm.root()) {
    EXPECT_TRUE(wet == dense.wet);
  }

  const ForestFill ff = forest_fill(pf, pc.wet, rot, c.k, o.seeds, o.seed_radius_deg, Logger::null());
  const Bitmap filled = gather_dense(pf, ff.filled);
  if (comm.root()) {
    EXPECT_EQ(filled.count(), dense.filled.count());
    EXPECT_TRUE(filled == dense.filled);
  }
  // On several ranks the world ocean spans the trees of every rank: the fill's union-find must
  // join its pieces across the rank boundaries into the one component the dense fill finds.
  std::int64_t mine = 0;
  for (const PatchBits& b : ff.filled) mine += b.state == Fill::kNone ? 0 : 1;
  EXPECT_GT(mine, 0) << "rank " << comm.rank() << " holds no filled patch: the case tests no seam";
  EXPECT_EQ(ff.stats.all_wet_windows, dense.fill.all_wet_windows);
  EXPECT_EQ(ff.stats.reached_windows, dense.fill.reached_windows);
  EXPECT_EQ(ff.stats.filled_pixels, dense.fill.filled_pixels);
  EXPECT_EQ(ff.stats.wet_components, dense.fill.wet_components);
  EXPECT_EQ(ff.stats.wet_components_filled, dense.fill.wet_components_filled);
  EXPECT_EQ(ff.stats.largest_wet_component, dense.fill.largest_wet_component);
  ASSERT_EQ(ff.seeds.size(), dense.seeds.size());
  for (std::size_t n = 0; n < ff.seeds.size(); ++n) {
    EXPECT_EQ(ff.seeds[n].window, dense.seeds[n].window);
    EXPECT_EQ(ff.seeds[n].windows_reached, dense.seeds[n].windows_reached);
  }
}

INSTANTIATE_TEST_SUITE_P(Etopo5, ForestMask,
                         ::testing::Values(Case{4.0, 3, 2, false}, Case{4.0, 3, 3, true}, Case{1.0, 5, 2, false},
                                           Case{2.0, 1, 1, false}));

// A floodplain (h = -30 m on the seed's lattice): the pixels wet at the datum and the inland seas
// (sea pixels the seed windows reach only across the floodplain, forest_unreached over every
// rank's patches) are the dense engine's bits and counts.
TEST(ForestFloodplain, DatumPixelsAndInlandSeasEqualTheDenseEngine) {
  start_mpi();
  const Lattice lat = Lattice::make(4.0, 3, -180.0);
  const PoleRotation rot;
  config::MaskOptions o;
  o.min_depth_m = -30.0;
  o.passages = false;
  const mask::WetArea dense = mask::compute_wet_area(etopo5(), lat, rot, o, Logger::null(), nullptr);
  ASSERT_GT(dense.inland_sea_pixels, 0) << "the case tests no inland sea";
  ASSERT_GT(dense.inland_sea_components, 1);

  const LatticeBrick brick(lat);
  const Comm comm;
  const PatchForest pf(brick, comm);
  const std::int64_t p = pf.grid().size;
  const StackBounds bounds(etopo5(), lat.pixel_deg() * static_cast<double>(p), 0.0);
  const PatchClasses pc = classify_patches(pf, etopo5(), bounds, rot, o.min_depth_m, mask::PixelWindow{});
  const PatchClasses at_datum = classify_patches(pf, etopo5(), bounds, rot, 0.0, mask::PixelWindow{});
  EXPECT_EQ(at_datum.counts.wet, dense.datum_wet_pixels);
  const Bitmap datum = gather_dense(pf, at_datum.wet);
  if (comm.root()) {
    EXPECT_TRUE(datum == dense.datum_wet);
  }
  const ForestFill ff = forest_fill(pf, pc.wet, rot, o.cursor, o.seeds, o.seed_radius_deg, Logger::null());
  std::vector<PatchBits> sea(pf.local_count()), starts(pf.local_count());
  for (std::size_t l = 0; l < sea.size(); ++l) {
    Bitmap b = ff.filled[l].dense(p);
    const Bitmap d = at_datum.wet[l].dense(p);
    for (std::size_t w = 0; w < b.words().size(); ++w) b.words()[w] &= d.words()[w];
    sea[l].state = Fill::kMixed;
    sea[l].bits = std::move(b);
    sea[l].normalise();
  }
  for (const mask::SeedInfo& s : ff.seeds)
    for (std::int64_t dj = 0; dj < o.cursor; ++dj)
      for (std::int64_t di = 0; di < o.cursor; ++di) {
        const std::int64_t i = (s.window.i + di) % lat.nx, j = s.window.j + dj;
        const std::int64_t l = pf.local_index(pf.grid().key(i / p, j / p));
        if (l < 0 || !sea[static_cast<std::size_t>(l)].get(i % p, j % p)) continue;
        PatchBits& b = starts[static_cast<std::size_t>(l)];
        if (b.state == Fill::kNone) {
          b.state = Fill::kMixed;
          b.bits = Bitmap(p, p);
        }
        b.bits.set(i % p, j % p);
      }
  const Unreached u = forest_unreached(pf, sea, starts);
  EXPECT_EQ(u.stats.count - u.stats.touching_probe, dense.inland_sea_components);
  const Bitmap inland = gather_dense(pf, u.pixels);
  if (comm.root()) {
    EXPECT_EQ(inland.count(), dense.inland_sea_pixels);
    // The dense engine's: its sea less what the seed windows' sea pixels reach.
    std::vector<mask::PixelIJ> from;
    for (const mask::SeedInfo& s : dense.seeds)
      for (std::int64_t dj = 0; dj < o.cursor; ++dj)
        for (std::int64_t di = 0; di < o.cursor; ++di) {
          const mask::PixelIJ q{(s.window.i + di) % lat.nx, s.window.j + dj};
          if (dense.sea.get(q.i, q.j)) from.push_back(q);
        }
    Bitmap expect = dense.sea;
    const Bitmap reached = mask::flood_fill(dense.sea, from);
    for (std::size_t w = 0; w < expect.words().size(); ++w) expect.words()[w] &= ~reached.words()[w];
    EXPECT_TRUE(inland == expect);
  }
}

}  // namespace
}  // namespace aq::forest::unit_forest_forest_mask_test
