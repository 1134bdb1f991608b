// SPDX-License-Identifier: GPL-3.0-or-later
// Core: all-or-nothing outputs, lattice validation, bitmaps, angle helpers, the run report.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <vector>

#include "core/bitmap.hpp"
#include "core/error.hpp"
#include "core/finite.hpp"
#include "core/lattice.hpp"
#include "core/output_files.hpp"
#include "core/report.hpp"
#include "core/temp_registry.hpp"
#include "core/types.hpp"

namespace unit_core_core_test {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

TEST(OutputSet, NothingAppearsWhenTheRunFails) {
  const fs::path dir = fs::temp_directory_path() / "aq_core_outputs_fail";
  fs::remove_all(dir);
  try {
    aq::OutputSet out(dir);
    std::ofstream(out.temp_path("a.txt")) << "partial";
    throw aq::NumericalError("boom");
  } catch (const aq::NumericalError&) {
  }
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(OutputSet, CommitRenamesEverything) {
  const fs::path dir = fs::temp_directory_path() / "aq_core_outputs_ok";
  fs::remove_all(dir);
  aq::OutputSet out(dir);
  std::ofstream(out.temp_path("a.txt")) << "A";
  std::ofstream(out.temp_path("b.txt")) << "B";
  EXPECT_FALSE(fs::exists(dir / "a.txt"));
  const auto files = out.commit();
  ASSERT_EQ(files.size(), 2u);
  EXPECT_TRUE(fs::exists(dir / "a.txt"));
  EXPECT_EQ(aq::file_checksum(dir / "b.txt"), aq::file_checksum(dir / "b.txt"));
  EXPECT_NE(aq::file_checksum(dir / "a.txt"), aq::file_checksum(dir / "b.txt"));
}

// The report's checksum is XXH64 with seed 0, what `xxhsum -H1` prints (values from xxhsum 0.8.1),
// also across the reader's buffer boundary (4 MiB).
TEST(FileChecksum, IsXxh64AsXxhsumPrints) {
  const fs::path dir = fs::temp_directory_path() / "aq_core_checksum";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "a.txt", std::ios::binary) << "A";
  { std::ofstream(dir / "q.bin", std::ios::binary) << std::string(5000000, 'q'); }
  std::ofstream(dir / "empty", std::ios::binary).close();
  EXPECT_EQ(aq::file_checksum(dir / "a.txt"), "13099d40d095b684");
  EXPECT_EQ(aq::file_checksum(dir / "q.bin"), "8c2ea88c6b894209");
  EXPECT_EQ(aq::file_checksum(dir / "empty"), "ef46db3751d8e999");
  EXPECT_THROW(aq::file_checksum(dir / "missing"), aq::InputError);
  fs::remove_all(dir);
}

// What an interrupt handler removes (core/temp_registry.hpp): every temporary of an unfinished
// output set, and the renamed files of an unfinished commit; nothing once the set is committed.
TEST(TempRegistry, RemovesTemporariesOfUnfinishedOutputSets) {
  const fs::path dir = fs::temp_directory_path() / "aq_core_registry";
  fs::remove_all(dir);
  const int before = aq::TempRegistry::in_use();
  {
    aq::OutputSet out(dir);
    for (int k = 0; k < 40; ++k)  // more than one chunk of slots
      std::ofstream(out.temp_path(fmt::format("f{}.txt", k))) << k;
    EXPECT_EQ(aq::TempRegistry::in_use(), before + 40);
    EXPECT_EQ(aq::TempRegistry::remove_registered_temporaries(), 40);
    EXPECT_TRUE(fs::is_empty(dir));
  }
  EXPECT_EQ(aq::TempRegistry::in_use(), before);
  {
    aq::OutputSet out(dir);
    std::ofstream(out.temp_path("a.txt")) << "A";
    out.commit();
    EXPECT_EQ(aq::TempRegistry::in_use(), before);
    EXPECT_EQ(aq::TempRegistry::remove_registered_temporaries(), 0);
    EXPECT_TRUE(fs::exists(dir / "a.txt"));
  }
}

TEST(TempRegistry, AnInterruptedCommitRemovesTheRenamedFilesToo) {
  const fs::path dir = fs::temp_directory_path() / "aq_core_registry_commit";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "tmp_a") << "A";
  std::ofstream(dir / "tmp_b") << "B";
  const int a = aq::TempRegistry::add(dir / "tmp_a", dir / "a");
  const int b = aq::TempRegistry::add(dir / "tmp_b", dir / "b");
  aq::TempRegistry::renaming(a);
  fs::rename(dir / "tmp_a", dir / "a");
  aq::TempRegistry::renamed(a);  // b not renamed yet: the set is partial
  EXPECT_EQ(aq::TempRegistry::remove_registered_temporaries(), 2);
  EXPECT_TRUE(fs::is_empty(dir));
  aq::TempRegistry::release(a);
  aq::TempRegistry::release(b);
  EXPECT_THROW(aq::TempRegistry::add(dir / std::string(5000, 'x'), dir / "c"), aq::OutputError);
}

TEST(OutputSet, UnwritableDirectoryIsAnOutputError) {
  if (geteuid() == 0) {
    // root can write anywhere; use a path under a regular file instead
    const fs::path f = fs::temp_directory_path() / "aq_core_regular_file";
    std::ofstream(f) << "x";
    try {
      aq::OutputSet out(f / "sub");
      FAIL() << "expected OutputError";
    } catch (const aq::OutputError& e) {
      EXPECT_THAT(e.what(), HasSubstr("aq_core_regular_file"));
    }
    return;
  }
  try {
    aq::OutputSet out("/proc/aq_not_writable");
    FAIL() << "expected OutputError";
  } catch (const aq::OutputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/proc/aq_not_writable"));
  }
}

TEST(Lattice, SizesAndCoordinates) {
  const auto l = aq::Lattice::make(4.0, 3, -180.0);
  EXPECT_EQ(l.n0, 45);
  EXPECT_EQ(l.nx, 720);
  EXPECT_EQ(l.ny, 360);
  EXPECT_DOUBLE_EQ(l.pixel_deg(), 0.5);
  EXPECT_DOUBLE_EQ(l.lon_of(720), 180.0);
  EXPECT_DOUBLE_EQ(l.lat_of(360), 90.0);
  const auto f = aq::Lattice::make(16.0 / 60.0, 6, -180.0);  // 15" lattice
  EXPECT_EQ(f.nx, 86400);
  EXPECT_EQ(f.ny, 43200);
  EXPECT_EQ(f.pixel_count(), 86400LL * 43200LL);
}

// quadtree.step_deg and levels are validated at load (tests/unit/config); here they are
// preconditions, whose failure is a bug.
TEST(Lattice, RejectsStepsThatDoNotDivide180) {
  EXPECT_THROW((void)aq::Lattice::make(7.0, 3, -180.0), aq::InternalError);
  EXPECT_THROW((void)aq::Lattice::make(0.0, 3, -180.0), aq::InternalError);
  EXPECT_THROW((void)aq::Lattice::make(4.0, 21, -180.0), aq::InternalError);
  EXPECT_NO_THROW((void)aq::Lattice::make(1.0 / 60.0, 0, -180.0));
}

// Issue 11: 16' typed as 0.2666666666666667 (16 digits) was kept as typed, so the last lattice row
// sat at φ = 90.00000000000003° and the pole row's cell area was NaN. A step within rounding of a
// whole arc-second value is now exactly that value, and every valid Δ0 and L ends at ±90° exactly.
TEST(Lattice, AStepWithinRoundingIsExactlyTheArcSecondLattice) {
  const auto typed = aq::Lattice::make(0.2666666666666667, 4, -180.0);
  const auto exact = aq::Lattice::make(0.26666666666666666, 4, -180.0);
  EXPECT_EQ(typed.step0_deg, 960.0 / 3600.0);
  EXPECT_EQ(typed.step0_deg, exact.step0_deg);
  EXPECT_EQ(typed.pixel_deg(), exact.pixel_deg());
  EXPECT_EQ(typed.ny, 10800);
  EXPECT_EQ(typed.lat_of(typed.ny), 90.0);
  EXPECT_EQ(typed.lat_of(0), -90.0);
  int checked = 0;
  for (std::int64_t arcsec = 1; arcsec <= 648000; ++arcsec) {
    if (648000 % arcsec != 0) continue;
    const double step = static_cast<double>(arcsec) / 3600.0;
    for (const double typed_step : {std::nextafter(step, 0.0), step, std::nextafter(step, 1e9), step * (1 + 1e-13)}) {
      for (int levels = 0; levels <= 20 && (std::int64_t{648000 / arcsec} << levels) <= (std::int64_t{1} << 26);
           ++levels) {
        const auto l = aq::Lattice::make(typed_step, levels, -180.0);
        ASSERT_EQ(l.step0_deg, step) << typed_step;
        ASSERT_EQ(l.lat_of(l.ny), 90.0) << arcsec << "\" L = " << levels;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 1000);
}

TEST(Lattice, StepsNotWithinRoundingAreRefusedWithTheReason) {
  try {
    (void)aq::Lattice::make(0.26667, 4, -180.0);
    FAIL() << "0.26667 was accepted";
  } catch (const aq::InternalError& e) {
    EXPECT_THAT(e.what(), HasSubstr("Δ0 = 0.26667°"));
    EXPECT_THAT(e.what(), HasSubstr("960.012\" is not a whole number of arc-seconds"));
  }
  EXPECT_THAT(aq::Lattice::step_problem(7.0), HasSubstr("does not divide 180°"));
  EXPECT_THAT(aq::Lattice::step_problem(std::nan("")), HasSubstr("not a whole number"));
  EXPECT_EQ(aq::Lattice::step_problem(0.2666666666666667), "");
}

// Checks that must fail on NaN (issue 11): a comparison with NaN is false.
TEST(Finite, ComparisonsAndMaximaFailOnNonFiniteValues) {
  const double nan = std::nan("");
  const double inf = HUGE_VAL;
  EXPECT_TRUE(aq::finite_at_most(0.5, 1.0));
  EXPECT_FALSE(aq::finite_at_most(1.5, 1.0));
  EXPECT_FALSE(aq::finite_at_most(nan, 1.0));
  EXPECT_FALSE(aq::finite_at_most(0.5, nan));
  EXPECT_FALSE(aq::finite_at_most(-inf, 1.0));
  EXPECT_TRUE(std::isnan(aq::nan_max(1.0, nan)));
  EXPECT_TRUE(std::isnan(aq::nan_max(nan, 1.0)));
  EXPECT_EQ(aq::nan_max(1.0, 2.0), 2.0);
  const std::vector<double> v{1.0, 2.0, nan, 3.0, inf};
  EXPECT_EQ(aq::first_non_finite(v), 2);
  EXPECT_EQ(aq::first_non_finite(std::vector<double>{1.0}), -1);
  aq::FiniteChecks c;
  c.values("area", v, [](std::int64_t k) { return "element " + std::to_string(k); });
  c.scalar("total", 4.0);
  c.scalar("sum", nan, "the sum over all elements");
  ASSERT_EQ(c.failures().size(), 2U);
  EXPECT_EQ(c.failures()[0], "area is nan at element 2 (first of 2 non-finite values)");
  EXPECT_EQ(c.failures()[1], "sum is nan at the sum over all elements");
  EXPECT_FALSE(c.ok());
}

TEST(Bitmap, SetGetCountAcrossWordBoundaries) {
  aq::Bitmap b(130, 3);
  EXPECT_EQ(b.words_per_row(), 3);
  b.set(63, 0);
  b.set(64, 0);
  b.set(129, 2);
  EXPECT_TRUE(b.get(63, 0));
  EXPECT_TRUE(b.get(64, 0));
  EXPECT_FALSE(b.get(65, 0));
  EXPECT_TRUE(b.get(129, 2));
  EXPECT_EQ(b.count(), 3);
  b.clear(64, 0);
  EXPECT_EQ(b.count(), 2);
}

// count_bits (POPCNT or not, on the threads for large arrays) and popcount64 against counting
// bit by bit, for word counts around its block size and a 15"-sized lattice row count.
TEST(Bitmap, CountBitsEqualsCountingEveryBit) {
  std::mt19937_64 rng(5);
  for (const std::int64_t n : {std::int64_t{0}, std::int64_t{1}, std::int64_t{65535}, std::int64_t{65536},
                               std::int64_t{65537}, std::int64_t{9 * 65536 + 17}}) {
    std::vector<std::uint64_t> w(static_cast<std::size_t>(n));
    std::int64_t naive = 0;
    for (auto& x : w) {
      x = rng() & rng();  // a quarter of the bits set
      std::int64_t c = 0;
      for (int b = 0; b < 64; ++b) c += static_cast<std::int64_t>((x >> b) & 1U);
      EXPECT_EQ(aq::popcount64(x), c);
      naive += c;
    }
    EXPECT_EQ(aq::count_bits(w.data(), n), naive) << n << " words";
  }
  EXPECT_EQ(aq::popcount64(~std::uint64_t{0}), 64);
}

TEST(Types, WrapHelpers) {
  EXPECT_DOUBLE_EQ(aq::wrap_lon_deg(190.0, -180.0), -170.0);
  EXPECT_DOUBLE_EQ(aq::wrap_lon_deg(-180.0, -180.0), -180.0);
  EXPECT_DOUBLE_EQ(aq::wrap_lon_deg(180.0, -180.0), -180.0);
  EXPECT_EQ(aq::wrap_index(-1, 720), 719);
  EXPECT_EQ(aq::wrap_index(720, 720), 0);
}

TEST(Report, StagesAreRecordedAndLogged) {
  std::vector<std::string> lines;
  aq::Logger log([&](aq::LogLevel, std::string_view m) { lines.emplace_back(m); });
  aq::Report r;
  aq::StageScope s("fill", &r, log);
  s.done("123 pixels");
  r.finish();
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_THAT(lines[0], HasSubstr("fill: done 123 pixels ("));
  EXPECT_EQ(r.root()["stages"][0]["stage"], "fill");
  EXPECT_TRUE(r.root()["total"].contains("peak_rss_mb"));
}

}  // namespace unit_core_core_test
