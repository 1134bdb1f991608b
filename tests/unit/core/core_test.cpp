// Core: all-or-nothing outputs, lattice validation, bitmaps, angle helpers, the run report.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "core/bitmap.hpp"
#include "core/error.hpp"
#include "core/lattice.hpp"
#include "core/output_files.hpp"
#include "core/report.hpp"
#include "core/temp_registry.hpp"
#include "core/types.hpp"

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

TEST(Lattice, RejectsStepsThatDoNotDivide180) {
  EXPECT_THROW((void)aq::Lattice::make(7.0, 3, -180.0), aq::ConfigError);
  EXPECT_THROW((void)aq::Lattice::make(0.0, 3, -180.0), aq::ConfigError);
  EXPECT_THROW((void)aq::Lattice::make(4.0, 21, -180.0), aq::ConfigError);
  EXPECT_NO_THROW((void)aq::Lattice::make(1.0 / 60.0, 0, -180.0));
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
