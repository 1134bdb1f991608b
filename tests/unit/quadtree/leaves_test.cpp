// SPDX-License-Identifier: GPL-3.0-or-later
// Leaves: pyramid, the D_l rule, coastal band, refinement rules, order and locator (leaves.hpp).
#include "quadtree/leaves.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.hpp"
#include "quadtree/bits.hpp"
#include "raster/bathymetry.hpp"
#include "unit/quadtree/mask_fixtures.hpp"

namespace aq::quadtree::unit_quadtree_leaves_test {
namespace {

using testing::draw;
using testing::make_lattice;
using testing::random_mask;

/// Whether every pixel of square (l, a, b) is filled (naive).
bool naive_all(const Bitmap& m, const Lattice& lat, int l, std::int64_t a, std::int64_t b) {
  const std::int64_t s = lat.pixels_per_square(l);
  for (std::int64_t j = b * s; j < (b + 1) * s; ++j)
    for (std::int64_t i = a * s; i < (a + 1) * s; ++i)
      if (!m.get(i, j)) return false;
  return true;
}
bool naive_any(const Bitmap& m, const Lattice& lat, int l, std::int64_t a, std::int64_t b) {
  const std::int64_t s = lat.pixels_per_square(l);
  for (std::int64_t j = b * s; j < (b + 1) * s; ++j)
    for (std::int64_t i = a * s; i < (a + 1) * s; ++i)
      if (m.get(i, j)) return true;
  return false;
}

TEST(Bits, CompactSpreadMorton) {
  EXPECT_EQ(bits::compact_even(0x5555555555555555ULL), 0xffffffffULL);
  EXPECT_EQ(bits::compact_even(0xaaaaaaaaaaaaaaaaULL), 0ULL);
  EXPECT_EQ(bits::spread_even(0xffffffffULL), 0x5555555555555555ULL);
  EXPECT_EQ(bits::spread_even(0b1011ULL), 0b1000101ULL);
  EXPECT_EQ(bits::morton(1, 0), 1ULL);
  EXPECT_EQ(bits::morton(0, 1), 2ULL);
  EXPECT_EQ(bits::morton(3, 5), 0b100111ULL);  // i = 011, j = 101 -> j2 i2 j1 i1 j0 i0 = 1 0 0 1 1 1
  std::mt19937_64 rng(5);
  for (int k = 0; k < 1000; ++k) {
    const std::uint64_t x = rng() & rng();
    ASSERT_EQ(bits::popcount64(x), std::popcount(x));
    ASSERT_EQ(bits::compact_even(bits::spread_even(x)), x & 0xffffffffULL);
  }
  EXPECT_EQ(bits::popcount64(~0ULL), 64);
}

TEST(Bits, RotateAndDilatePeriodicRows) {
  for (const std::int64_t n : {5, 64, 70, 130, 200}) {
    std::mt19937 rng(static_cast<std::uint32_t>(n));
    Bitmap in(n, 1);
    for (std::int64_t i = 0; i < n; ++i)
      if (rng() % 5 == 0) in.set(i, 0);
    for (const std::int64_t s : {-67, -3, -1, 0, 1, 2, 63, 64, 65, 129}) {
      Bitmap out(n, 1);
      bits::rotate_row(in.row(0), out.row(0), n, s);
      for (std::int64_t i = 0; i < n; ++i) {
        ASSERT_EQ(out.get(i, 0), in.get(wrap_index(i - s, n), 0)) << "n " << n << " s " << s << " i " << i;
      }
      EXPECT_EQ(out.count(), in.count());
    }
    for (const std::int64_t r : {0, 1, 2, 3, 7}) {
      Bitmap out(n, 1), tmp(n, 1);
      bits::dilate_row(in.row(0), out.row(0), tmp.row(0), n, r);
      for (std::int64_t i = 0; i < n; ++i) {
        bool expect = false;
        for (std::int64_t d = -r; d <= r; ++d) expect = expect || in.get(wrap_index(i + d, n), 0);
        ASSERT_EQ(out.get(i, 0), expect) << "n " << n << " r " << r << " i " << i;
      }
    }
  }
}

// expand_row and reduce_rows bit by bit against their definitions, on rows mixing all-0 and
// all-1 words and half-words (the shortcut) with random ones, of lengths that end mid-word.
TEST(Bits, ExpandAndReduceRowsMatchPerBitDefinition) {
  std::mt19937_64 rng(11);
  const auto word = [&rng](int kind) -> std::uint64_t {
    switch (kind) {
      case 0:
        return 0;
      case 1:
        return ~0ULL;
      case 2:
        return 0xffffffffULL;  // low half all 1, high half all 0
      case 3:
        return 0xffffffff00000000ULL | (rng() & 0xffffffffULL);
      default:
        return rng();
    }
  };
  for (const std::int64_t n : {6, 64, 70, 128, 200, 320}) {  // bits per child row (even)
    for (int trial = 0; trial < 20; ++trial) {
      Bitmap lo(n, 1), hi(n, 1), parent(n / 2, 1);
      for (Bitmap* b : {&lo, &hi, &parent}) {
        for (std::int64_t w = 0; w < b->words_per_row(); ++w) b->row(0)[w] = word(static_cast<int>(rng() % 5));
        b->row(0)[b->words_per_row() - 1] &= bits::last_word_mask(b->nx());  // padding clear
      }
      Bitmap child(n, 1);
      bits::expand_row(parent.row(0), child.row(0), child.words_per_row());
      for (std::int64_t i = 0; i < n; ++i) ASSERT_EQ(child.get(i, 0), parent.get(i / 2, 0)) << "n " << n << " i " << i;
      EXPECT_EQ(child.count(), 2 * parent.count());
      for (const bool use_or : {false, true}) {
        Bitmap out(n / 2, 1);
        bits::reduce_rows(lo.row(0), hi.row(0), lo.words_per_row(), out.row(0), use_or);
        for (std::int64_t a = 0; a < n / 2; ++a) {
          const bool q[4] = {lo.get(2 * a, 0), lo.get(2 * a + 1, 0), hi.get(2 * a, 0), hi.get(2 * a + 1, 0)};
          const bool want = use_or ? (q[0] || q[1] || q[2] || q[3]) : (q[0] && q[1] && q[2] && q[3]);
          ASSERT_EQ(out.get(a, 0), want) << "n " << n << " a " << a << " or " << use_or;
        }
      }
    }
  }
}

TEST(Leaves, PyramidMatchesNaiveAllAndAny) {
  const Lattice lat = make_lattice(30.0, 3);  // 96 × 48 pixels
  const Bitmap m = random_mask(lat.nx, lat.ny, 7u);
  const LevelMasks masks = make_level_masks(m, lat, 0);
  for (int l = 0; l <= lat.levels; ++l) {
    const Bitmap& om = masks.omega[static_cast<std::size_t>(l)];
    ASSERT_EQ(om.nx(), lat.nx >> (lat.levels - l));
    for (std::int64_t b = 0; b < om.ny(); ++b) {
      for (std::int64_t a = 0; a < om.nx(); ++a) {
        ASSERT_EQ(om.get(a, b), naive_all(m, lat, l, a, b)) << l << " " << a << " " << b;
        ASSERT_EQ(masks.any_at(l).get(a, b), naive_any(m, lat, l, a, b)) << l << " " << a << " " << b;
      }
    }
  }
}

TEST(Leaves, BareRulePartitionsTheFilledSetIntoDl) {
  for (const std::uint32_t seed : {1u, 2u, 3u, 4u}) {
    const Lattice lat = make_lattice(30.0, 4);  // 192 × 96
    const Bitmap m = random_mask(lat.nx, lat.ny, seed, 0.55, 0.0005, 24);
    const LevelMasks masks = make_level_masks(m, lat, 0);
    const std::vector<Leaf> leaves = extract_leaves(masks, lat);
    // Pixel counts per level add up to the filled set, and the leaves cover exactly it.
    const std::vector<std::int64_t> per_level = count_leaves_per_level(masks);
    std::vector<std::int64_t> seen(per_level.size(), 0);
    std::int64_t pixels = 0;
    for (const Leaf& f : leaves) {
      ++seen[static_cast<std::size_t>(f.level)];
      pixels += leaf_size(lat, f) * leaf_size(lat, f);
    }
    EXPECT_EQ(seen, per_level);
    EXPECT_EQ(pixels, m.count());
    EXPECT_EQ(leaf_coverage(leaves, lat), m);
    // D_l: each leaf is filled, and (l >= 1) its parent square is not entirely filled.
    for (const Leaf& f : leaves) {
      ASSERT_TRUE(naive_all(m, lat, f.level, f.a, f.b));
      if (f.level > 0) {
        ASSERT_FALSE(naive_all(m, lat, f.level - 1, f.a / 2, f.b / 2)) << f.level;
      }
    }
    // Several levels occur (the test would be vacuous otherwise).
    EXPECT_GT(per_level[0], 0);
    EXPECT_GT(per_level[static_cast<std::size_t>(lat.levels)], 0);
  }
}

TEST(Leaves, OrderIsRootRowMajorThenMorton) {
  // One 4×4-pixel level-0 square (L = 2) per 90° (n0 = 2: 4 × 2 roots); fill root (1, 0) except
  // its NE pixel, and the whole root (0, 1).
  const Lattice lat = make_lattice(90.0, 2);
  ASSERT_EQ(lat.nx, 16);
  Bitmap m(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < 4; ++j)
    for (std::int64_t i = 4; i < 8; ++i)
      if (!(i == 7 && j == 3)) m.set(i, j);
  for (std::int64_t j = 4; j < 8; ++j)
    for (std::int64_t i = 0; i < 4; ++i) m.set(i, j);
  const std::vector<Leaf> leaves = extract_leaves(make_level_masks(m, lat, 0), lat);
  const std::vector<Leaf> expect{{1, 2, 0}, {1, 3, 0}, {1, 2, 1},  // SW, SE, NW quarters of root (1,0)
                                 {2, 6, 2}, {2, 7, 2}, {2, 6, 3},  // NE quarter split: its SW, SE, NW pixels
                                 {0, 0, 1}};                       // root (0, 1), after the whole root row 0
  EXPECT_EQ(leaves, expect);
  EXPECT_TRUE(leaves_sorted(leaves, lat));
}

TEST(Leaves, CoastalBandIsChebyshevWrapsTheSeamAndIgnoresThePoles) {
  const Lattice lat = make_lattice(30.0, 3);
  for (const int band : {1, 2, 3}) {
    Bitmap m = random_mask(lat.nx, lat.ny, 11u + static_cast<std::uint32_t>(band));
    for (std::int64_t i = 0; i < lat.nx; ++i) m.set(i, lat.ny - 1);  // top row filled: not coast by itself
    const Bitmap cb = coastal_band(m, band);
    for (std::int64_t j = 0; j < lat.ny; ++j) {
      for (std::int64_t i = 0; i < lat.nx; ++i) {
        bool expect = false;
        if (m.get(i, j)) {
          for (std::int64_t dj = -band; dj <= band; ++dj)
            for (std::int64_t di = -band; di <= band; ++di) {
              const std::int64_t jj = j + dj;
              if (jj >= 0 && jj < lat.ny && !m.get(wrap_index(i + di, lat.nx), jj)) expect = true;
            }
        }
        ASSERT_EQ(cb.get(i, j), expect) << "band " << band << " at " << i << "," << j;
      }
    }
  }
}

// The band with coast sources (mask/coast.hpp), against the definition pixel by pixel: a filled
// pixel is in it when a pixel within r is neither filled nor open, or, for a sea pixel, neither
// sea nor open. Open water beyond a domain is no coast; the shoreline inside a floodplain is.
TEST(Leaves, CoastalBandWithCoastSourcesSkipsOpenWaterAndHoldsTheShoreline) {
  const Lattice lat = make_lattice(30.0, 3);
  for (const int band : {1, 2}) {
    const Bitmap m = random_mask(lat.nx, lat.ny, 31u + static_cast<std::uint32_t>(band));
    Bitmap open(lat.nx, lat.ny), sea(lat.nx, lat.ny);
    std::mt19937 rng(7u + static_cast<std::uint32_t>(band));
    for (std::int64_t j = 0; j < lat.ny; ++j)
      for (std::int64_t i = 0; i < lat.nx; ++i) {
        if (!m.get(i, j) && rng() % 3 == 0) open.set(i, j);
        if (m.get(i, j) && rng() % 4 != 0) sea.set(i, j);
      }
    for (const bool with_sea : {false, true}) {
      const mask::CoastSources coast{&open, with_sea ? &sea : nullptr};
      const Bitmap cb = coastal_band(m, band, coast);
      std::int64_t shore_only = 0;
      for (std::int64_t j = 0; j < lat.ny; ++j) {
        for (std::int64_t i = 0; i < lat.nx; ++i) {
          bool edge = false, shore = false;
          for (std::int64_t dj = -band; dj <= band; ++dj)
            for (std::int64_t di = -band; di <= band; ++di) {
              const std::int64_t jj = j + dj, ii = wrap_index(i + di, lat.nx);
              if (jj < 0 || jj >= lat.ny || open.get(ii, jj)) continue;
              edge = edge || !m.get(ii, jj);
              shore = shore || !sea.get(ii, jj);
            }
          const bool expect = m.get(i, j) && (edge || (with_sea && sea.get(i, j) && shore));
          ASSERT_EQ(cb.get(i, j), expect)
              << "band " << band << (with_sea ? " with sea" : "") << " at " << i << "," << j;
          shore_only += expect && !edge ? 1 : 0;
        }
      }
      if (with_sea) {
        EXPECT_GT(shore_only, 0);  // the shoreline inside the fill adds pixels
      }
      // The level masks split the same band to level L.
      const std::vector<Leaf> leaves = extract_leaves(make_level_masks(m, lat, band, coast), lat);
      EXPECT_EQ(leaf_coverage(leaves, lat), m);
      for (const Leaf& f : leaves) {
        if (f.level < lat.levels) {
          ASSERT_FALSE(naive_any(cb, lat, f.level, f.a, f.b));
        }
      }
    }
    // Without sources every unfilled pixel is coast, as before.
    EXPECT_EQ(coastal_band(m, band, {}), coastal_band(m, band));
    EXPECT_NE(coastal_band(m, band, {&open, nullptr}), coastal_band(m, band));
  }
}

// A box's open edge on level-0 square edges: without the open water as coast the squares there
// stay coarse (the D_l rule allows it); counted as coast (no sources) they are split to level L.
TEST(Leaves, OpenWaterBeyondABoxLeavesTheEdgeSquaresCoarse) {
  const Lattice lat = make_lattice(30.0, 3);  // 12 x 6 level-0 squares of 8 x 8 pixels
  Bitmap filled(lat.nx, lat.ny), open(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < lat.ny; ++j)
    for (std::int64_t i = 0; i < lat.nx; ++i) (i >= 16 && i < 48 && j >= 8 && j < 40 ? filled : open).set(i, j);
  const auto finest = [&](const mask::CoastSources& coast) {
    std::int64_t n = 0;
    for (const Leaf& f : extract_leaves(make_level_masks(filled, lat, 2, coast), lat)) n += f.level == lat.levels;
    return n;
  };
  EXPECT_EQ(finest({&open, nullptr}), 0);  // 16 level-0 squares
  EXPECT_EQ(extract_leaves(make_level_masks(filled, lat, 2, {&open, nullptr}), lat).size(), 16u);
  EXPECT_GT(finest({}), 0);
}

TEST(Leaves, CoastalBandLeavesAreFinestAndOthersMaximal) {
  const Lattice lat = make_lattice(30.0, 4);
  const Bitmap m = random_mask(lat.nx, lat.ny, 5u, 0.55, 0.01, 12);
  const int band = 2;
  const Bitmap cb = coastal_band(m, band);
  const std::vector<Leaf> leaves = extract_leaves(make_level_masks(m, lat, band), lat);
  EXPECT_EQ(leaf_coverage(leaves, lat), m);
  std::int64_t coarse = 0;
  for (const Leaf& f : leaves) {
    if (f.level == lat.levels) continue;
    ++coarse;
    // A coarser leaf holds no band pixel, and its parent holds one or is not entirely filled.
    ASSERT_FALSE(naive_any(cb, lat, f.level, f.a, f.b));
    if (f.level > 0) {
      ASSERT_TRUE(naive_any(cb, lat, f.level - 1, f.a / 2, f.b / 2) ||
                  !naive_all(m, lat, f.level - 1, f.a / 2, f.b / 2));
    }
  }
  EXPECT_GT(coarse, 0);
  EXPECT_GT(cb.count(), 0);
}

TEST(Leaves, SeamSquaresSeeTheCoastAcrossTheSeam) {
  // Land only in the easternmost column: with a band of 1 the westernmost column is coastal too.
  const Lattice lat = make_lattice(90.0, 2);  // 16 × 8
  Bitmap m(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < lat.ny; ++j)
    for (std::int64_t i = 0; i < lat.nx - 1; ++i) m.set(i, j);
  const Bitmap cb = coastal_band(m, 1);
  for (std::int64_t j = 0; j < lat.ny; ++j) {
    EXPECT_TRUE(cb.get(0, j));
    EXPECT_TRUE(cb.get(lat.nx - 2, j));
    EXPECT_FALSE(cb.get(1, j));
  }
  const std::vector<Leaf> leaves = extract_leaves(make_level_masks(m, lat, 1), lat);
  for (const Leaf& f : leaves) {
    if (leaf_i0(lat, f) == 0) {
      EXPECT_EQ(f.level, lat.levels) << "a leaf on the western seam column";
    }
  }
}

/// Centres (geographic) of the level-m squares inside leaf f (f.level <= m).
std::vector<std::array<double, 2>> centres_at(const Lattice& lat, const Leaf& f, int m, const PoleRotation& rot) {
  std::vector<std::array<double, 2>> out;
  const int k = m - f.level;
  const double step = lat.step0_deg / static_cast<double>(1 << m);
  for (std::int64_t b = f.b << k; b < (f.b + 1) << k; ++b) {
    for (std::int64_t a = f.a << k; a < (f.a + 1) << k; ++a) {
      double lon = 0, la = 0;
      rot.to_geographic(lat.lon0_deg + (static_cast<double>(a) + 0.5) * step,
                        -90.0 + (static_cast<double>(b) + 0.5) * step, lon, la);
      out.push_back({lon, la});
    }
  }
  return out;
}

Bitmap full_mask(const Lattice& lat) {
  Bitmap m(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < lat.ny; ++j) bits::set_range(m.row(j), 0, lat.nx);
  return m;
}

TEST(Leaves, BoxRuleGivesTheLevelWhereLevelBelowCentresAreInside) {
  const Lattice lat = make_lattice(30.0, 3);
  const Bitmap m = full_mask(lat);
  config::QuadtreeOptions o;
  o.box_rules.push_back({170.0, -170.0, -10.0, 20.0, 2});  // crosses the antimeridian
  const auto inside = [](const std::array<double, 2>& p) {
    return p[1] >= -10.0 && p[1] <= 20.0 && (p[0] >= 170.0 || p[0] <= -170.0);
  };
  LevelMasks masks = make_level_masks(m, lat, 0);
  apply_refinement_rules(masks, lat, o, PoleRotation(), nullptr);
  const std::vector<Leaf> leaves = extract_leaves(masks, lat);
  EXPECT_EQ(leaf_coverage(leaves, lat), m);
  int fine = 0;
  for (const Leaf& f : leaves) {
    // Leaves coarser than 2 hold no level-1 centre inside the box; finer ones exist only
    // because their parent held one.
    if (f.level < 2) {
      for (const auto& p : centres_at(lat, f, 1, PoleRotation())) EXPECT_FALSE(inside(p)) << f.level;
    } else {
      ++fine;
      EXPECT_TRUE(inside(centres_at(lat, Leaf{1, f.a >> 1, f.b >> 1}, 1, PoleRotation())[0]));
    }
    EXPECT_LE(f.level, 2);
  }
  // Level-1 centres inside: λ = ±172.5°, φ = ±7.5°: four level-1 squares, each split in 4.
  EXPECT_EQ(fine, 4 * 4);
}

TEST(Leaves, DepthRuleUsesTheRasterThroughTheRotation) {
  // Depth grows with geographic latitude: elevation = -100·(φ + 90) m.
  const std::int64_t nc = 361, nr = 181;
  std::vector<float> v(static_cast<std::size_t>(nc * nr));
  for (std::int64_t r = 0; r < nr; ++r)
    for (std::int64_t c = 0; c < nc; ++c) v[static_cast<std::size_t>(r * nc + c)] = -100.0f * static_cast<float>(r);
  const raster::Bathymetry bathy = raster::Bathymetry::from_grid(v, nc, nr, -180.0, -90.0, 1.0, 1.0);
  const Lattice lat = make_lattice(30.0, 3);
  const Bitmap m = full_mask(lat);
  config::QuadtreeOptions o;
  o.depth_rules.push_back({9000.0, 13000.0, 3});  // φ in [0°, 40°)
  const PoleRotation rot(-44.858333, 78.141667);
  const auto in_range = [&](const std::array<double, 2>& p) {
    const double depth = -bathy.sample(p[0], p[1]);
    return depth >= 9000.0 && depth < 13000.0;
  };
  LevelMasks masks = make_level_masks(m, lat, 0);
  apply_refinement_rules(masks, lat, o, rot, &bathy);
  const std::vector<Leaf> leaves = extract_leaves(masks, lat);
  int finest = 0;
  for (const Leaf& f : leaves) {
    if (f.level < 3) {
      for (const auto& p : centres_at(lat, f, 2, rot)) EXPECT_FALSE(in_range(p)) << f.level;
    } else {
      ++finest;
      EXPECT_TRUE(in_range(centres_at(lat, Leaf{2, f.a >> 1, f.b >> 1}, 2, rot)[0]));
    }
  }
  EXPECT_GT(finest, 0);
}

TEST(Leaves, LocatorFindsTheLeafOfEveryPixel) {
  const Lattice lat = make_lattice(30.0, 3);
  const Bitmap m = random_mask(lat.nx, lat.ny, 9u);
  const std::vector<Leaf> leaves = extract_leaves(make_level_masks(m, lat, 0), lat);
  const LeafLocator loc(leaves, lat);
  const std::vector<int> lev = testing::level_map(leaves, lat);
  for (std::int64_t j = 0; j < lat.ny; ++j) {
    for (std::int64_t i = 0; i < lat.nx; ++i) {
      const std::int64_t k = loc.find(i, j);
      ASSERT_EQ(k >= 0, m.get(i, j));
      if (k >= 0) {
        ASSERT_EQ(leaves[static_cast<std::size_t>(k)].level, lev[static_cast<std::size_t>(j * lat.nx + i)]);
      }
    }
  }
  EXPECT_EQ(loc.find(-1, 0), loc.find(lat.nx - 1, 0));
  EXPECT_EQ(loc.find(0, lat.ny), -1);
}

TEST(Leaves, BadInputIsReported) {
  const Lattice lat = make_lattice(30.0, 3);
  EXPECT_THROW(make_level_masks(Bitmap(10, 10), lat, 0), InternalError);
  EXPECT_THROW(make_level_masks(Bitmap(lat.nx, lat.ny), lat, -1), InternalError);
  std::vector<Leaf> overlap{{0, 0, 0}, {1, 0, 0}};
  EXPECT_THROW(leaf_coverage(overlap, lat), InternalError);
  std::vector<Leaf> unsorted{{0, 1, 0}, {0, 0, 0}};
  EXPECT_THROW(LeafLocator(unsorted, lat), InternalError);
}

}  // namespace
}  // namespace aq::quadtree::unit_quadtree_leaves_test
