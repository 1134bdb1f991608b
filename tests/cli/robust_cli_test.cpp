// SPDX-License-Identifier: GPL-3.0-or-later
// Issue 23: nothing crashes, hangs, lies or is left behind. Each test here failed on the code
// before the issue: a FIFO or /dev/zero given for a path hung or read forever, a full disk ended
// in SIGSEGV, sizes overflowed into negative numbers, late regional checks named no key, and a
// few values were silently reinterpreted. Every command runs under `timeout`, so a hang fails the
// test (exit 124) instead of stopping the suite.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netcdf.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gdal_priv.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace cli_robust_cli_test {

namespace fs = std::filesystem;
using aq::test::CommandResult;
using aq::test::run_command;
using ::testing::HasSubstr;
using ::testing::Not;

namespace {

const std::string kConfigs = std::string(AQ_SOURCE_DIR) + "/configs/";

// aquatoria with a time limit (a hang is exit 124).
CommandResult aq_run(const std::string& args, int seconds = 60) {
  return run_command("timeout -k 5 " + std::to_string(seconds) + " " + std::string(AQ_BINARY) + " " + args);
}

// A folder with a FIFO, a directory and a regional config naming them.
struct SpecialFiles {
  aq::testing::TempDir dir;
  fs::path fifo = dir / "pipe.nc", fifo_izogrid = dir / "pipe.izogrid", folder = dir / "folder.nc";
  SpecialFiles() {
    if (::mkfifo(fifo.c_str(), 0600) != 0 || ::mkfifo(fifo_izogrid.c_str(), 0600) != 0)
      throw std::runtime_error("mkfifo failed");
    fs::create_directories(folder);
  }
};

void expect_refused(const CommandResult& r, int code, const std::string& path, const std::string& what) {
  EXPECT_EQ(r.exit_code, code) << r.err;
  EXPECT_THAT(r.err, HasSubstr(path));
  EXPECT_THAT(r.err, HasSubstr(what));
  EXPECT_THAT(r.err, Not(HasSubstr("internal")));
}

}  // namespace

TEST(RobustPaths, ConfigFileMustBeARegularFile) {
  SpecialFiles s;
  expect_refused(aq_run("mesh -c " + s.fifo.string()), 2, s.fifo.string(),
                 "is a FIFO (named pipe), not a regular file");
  expect_refused(aq_run("mesh -c /dev/zero"), 2, "/dev/zero", "is a character device, not a regular file");
  expect_refused(aq_run("mesh -c " + s.folder.string()), 2, s.folder.string(), "is a directory, not a regular file");
  expect_refused(aq_run("regional -c " + s.fifo.string()), 2, s.fifo.string(), "is a FIFO");
  expect_refused(aq_run("regional " + s.fifo_izogrid.string()), 1, s.fifo_izogrid.string(), "is a FIFO");
  expect_refused(aq_run("blocks -c /dev/zero"), 2, "/dev/zero", "character device");
}

TEST(RobustPaths, InputRasterMustBeARegularFile) {
  SpecialFiles s;
  for (const std::string& p : {s.fifo.string(), std::string("/dev/zero"), s.folder.string()}) {
    SCOPED_TRACE(p);
    expect_refused(aq_run("mesh -q --set input.path=" + p), 2, "input.path", p);
    expect_refused(aq_run("info " + p), 1, p, "not a regular file");
  }
}

TEST(RobustPaths, GridAndContourFilesMustBeRegularFiles) {
  SpecialFiles s;
  for (const std::string& p : {s.fifo.string(), std::string("/dev/zero"), s.folder.string()})
    expect_refused(aq_run("check " + p), 1, p, "not a regular file");
  const fs::path cfg = s.dir / "region.toml";
  std::ofstream(cfg) << "[regional]\nname = \"t\"\ncontour_file = \"pipe.izogrid\"\n";
  expect_refused(aq_run("regional -c " + cfg.string()), 2, "regional.contour_file", "is a FIFO");
  std::ofstream(cfg) << "[regional]\nname = \"t\"\ncontour_file = \"" << kConfigs << "black_sea.izogrid\"\n"
                     << "[roms]\nglobal_config = \"/dev/zero\"\n[nesting]\nparent = \"folder.nc\"\n";
  const CommandResult r = aq_run("regional -c " + cfg.string());
  expect_refused(r, 2, "roms.global_config", "/dev/zero is a character device");
  EXPECT_THAT(r.err, HasSubstr("nesting.parent"));
  EXPECT_THAT(r.err, HasSubstr("folder.nc is a directory"));
}

TEST(RobustPaths, OutputDirMustBeADirectory) {
  aq::testing::TempDir dir;
  std::ofstream(dir / "file") << "x";
  expect_refused(aq_run("mesh -q --set output.dir=" + (dir / "file").string()), 2, "output.dir",
                 "is a regular file, not a directory");
}

// input.path = "...etopo5.cdf\u0000x" read etopo5.cdf (the name was cut at the NUL).
TEST(RobustMessages, NulInAPathIsRefused) {
  aq::testing::TempDir dir;
  std::ofstream(dir / "nul.toml") << "[input]\npath = \"/usr/share/ferret-vis/data/etopo5.cdf\\u0000x\"\n";
  const CommandResult r = aq_run("mesh -q -c " + (dir / "nul.toml").string() + " -o " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("input.path: contains a NUL byte"));
  EXPECT_FALSE(fs::exists(dir / "out" / "seed_4deg_L3.msh"));
}

// [1, 13, 11, 7] was sorted into [1, 7, 11, 13] without a word.
TEST(RobustMessages, CornersOutOfOrderAreRefused) {
  const CommandResult r = aq_run("regional -q -c " + kConfigs + "black_sea.toml --set 'regional.corners=[1,13,11,7]'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("regional.corners: [1, 13, 11, 7]: the corner numbers must increase"));
}

// ny = 200000 failed after 15 s inside the boundary-node stage naming no key; nx = 2e9 was
// printed as -294967295; uscale = 1e-300 failed in the C-grid stage without naming uscale.
TEST(RobustMessages, RegionalSizesAndScalesNameTheirKeyAtOnce) {
  CommandResult r = aq_run("regional -q -c " + kConfigs + "black_sea.toml --set regional.ny=200000", 20);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("regional.ny: nx = 65, ny = 200000: a supergrid of about 400001 x 400001 points"));
  EXPECT_THAT(r.err, HasSubstr("black_sea.toml"));
  r = aq_run("regional -q -c " + kConfigs + "black_sea.toml --set regional.nx=2000000000", 20);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("regional.nx: nx = 2000000000"));
  EXPECT_THAT(r.err, Not(HasSubstr("-294967295")));
  r = aq_run("regional -q -c " + kConfigs + "black_sea.toml --set regional.uscale=1e-300", 20);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("regional.uscale: uscale = 1e-300: must be within [1e-9, 1e3]"));
}

// Issue 33: three inputs a new user may give that were taken: `info --at nan,nan` (exit 0), a
// box meant as [-5, 10] but written [10, -5] (a 345° band meshed across the seam, exit 0), a
// raster whose geotransform has a pixel of 1e300° (meshed as a tiny raster). Each is refused at
// once with the value and exit 2 (usage, configuration) or 1 (the input file), writing nothing.
TEST(RobustMessages, TheBadInputsOfIssue33AreRefused) {
  aq::testing::TempDir dir;
  CommandResult r = aq_run(std::string("info ") + AQ_ETOPO_DIR + "/etopo60.cdf --at nan,nan");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("--at nan,nan: expected LON,LAT in degrees, finite"));
  r = aq_run("mesh -q -c " + kConfigs + "north_sea.toml --set 'domain.box=[10, -5, 49, 61]' -o " +
             (dir / "box").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("domain.box: lon_min = 10 > lon_max = -5 reads as a box across the seam 345° wide"));
  EXPECT_THAT(r.err, HasSubstr("write [-5, 10, 49, 61]"));
  EXPECT_FALSE(fs::exists(dir / "box"));
  GDALAllRegister();
  GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GTiff")->Create((dir / "huge.tif").c_str(), 20, 10, 1,
                                                                             GDT_Int16, nullptr);
  double gt[6] = {0.0, 1e300, 0.0, 90.0, 0.0, -18.0};
  ds->SetGeoTransform(gt);
  std::vector<std::int16_t> v(200, -3000);
  EXPECT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 20, 10, v.data(), 20, 10, GDT_Int16, 0, 0, nullptr),
            CE_None);
  GDALClose(ds);
  r = aq_run("mesh -q --set input.path=" + (dir / "huge.tif").string() + " -o " + (dir / "huge").string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr((dir / "huge.tif").string() + ": the geotransform's pixel is 1e+300° × -18°"));
  EXPECT_THAT(fs::exists(dir / "huge") ? std::distance(fs::directory_iterator(dir / "huge"), {}) : 0, 0);
}

// Found by probing as a new user (issue 33): a graticule spacing of 1e-6° drew lines for minutes
// (now coarsened to at most 200 lines a way), a picture edge at -1e300° reached the coastline
// stage as an empty window naming no key, a FIFO as domain.polygon blocked OGR for ever.
TEST(RobustMessages, ProbedRegionalAndDomainValuesAreHandled) {
  aq::testing::TempDir dir;
  CommandResult r = aq_run("regional -q -c " + kConfigs + "black_sea.toml --set regional.latlongrid=1e-6 " +
                               "--stop-after map -o " + (dir / "map").string(),
                           30);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "map" / "black_sea_map.png"));
  r = aq_run("regional -q -c " + kConfigs + "black_sea.toml --set regional.west_edge=-1e300 --stop-after map");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("regional.west_edge: west_edge = -1e+300: must be a longitude within [-360, 360]"));
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0600), 0);
  r = aq_run("mesh -q --set domain.polygon=" + (dir / "fifo").string() + " -o " + (dir / "out").string(), 30);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("domain.polygon: " + (dir / "fifo").string() + " is a FIFO"));
}

// A 1" lattice at L = 12 printed "memory: estimate -9223188109.45 GB" and died with bad_alloc;
// max_memory_gb = 1e-10 meant "no limit".
TEST(RobustSizes, HugeLatticesAndTinyLimitsAreRefusedBeforeAnyWork) {
  aq::testing::TempDir dir;
  CommandResult r = aq_run("mesh -o " + dir.path().string() +
                           " --set quadtree.step_deg=0.0002777777777777778 --set quadtree.levels=12");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("quadtree.levels = 12"));
  EXPECT_THAT(r.err, Not(HasSubstr("estimate -")));
  r = aq_run("mesh -q -o " + dir.path().string() + " --set input.max_memory_gb=1e-10");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("input.max_memory_gb"));
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

// A netCDF-4 grid file declaring 100000 x 100000 nodes (a few kB on disk) made `check` allocate
// 160 GB before reading anything.
TEST(RobustSizes, GridFilesDeclaringHugeSizesAreRefused) {
  aq::testing::TempDir dir;
  const fs::path f = dir / "huge_xygrid.nc";
  int nc = -1, de = -1, dx = -1, vx = -1, vy = -1;
  ASSERT_EQ(nc_create(f.c_str(), NC_CLOBBER | NC_NETCDF4, &nc), NC_NOERR);
  ASSERT_EQ(nc_def_dim(nc, "eta", 100000, &de), NC_NOERR);
  ASSERT_EQ(nc_def_dim(nc, "xi", 100000, &dx), NC_NOERR);
  const int dims[2] = {de, dx};
  ASSERT_EQ(nc_def_var(nc, "x", NC_DOUBLE, 2, dims, &vx), NC_NOERR);
  ASSERT_EQ(nc_def_var(nc, "y", NC_DOUBLE, 2, dims, &vy), NC_NOERR);
  ASSERT_EQ(nc_close(nc), NC_NOERR);
  ASSERT_LT(fs::file_size(f), 100000u);
  const CommandResult r = aq_run("check " + f.string() + " --json " + (dir / "q.json").string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("declares a grid of 100000 x 100000 nodes"));
  EXPECT_THAT(r.err, Not(HasSubstr("bad_alloc")));
}

// A 240-byte output.name: the temporary ".NAME.msh.tmpPID" was over 255 bytes and the run failed.
TEST(RobustOutputs, LongOutputNamesWork) {
  aq::testing::TempDir dir;
  const std::string name(240, 'n');
  const CommandResult r =
      aq_run("mesh -q -o " + dir.path().string() + " --set output.name=" + name + " --set 'output.formats=[\"text\"]'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / (name + ".txt")));
  EXPECT_TRUE(fs::exists(dir / (name + "_report.json")));
}

// A run killed with SIGKILL left its temporaries for ever; the next run in the folder removes
// them and says so.
TEST(RobustOutputs, TheNextRunRemovesTemporariesOfDeadRuns) {
  aq::testing::TempDir dir;
  const pid_t dead = ::fork();  // a pid no process has: a child that has exited and been reaped
  if (dead == 0) ::_exit(0);
  int status = 0;
  ::waitpid(dead, &status, 0);
  const std::string stale = ".seed_4deg_L3.msh.tmp" + std::to_string(dead);
  std::ofstream(dir / stale) << "partial";
  const CommandResult r = aq_run("mesh -o " + dir.path().string() + " --set 'output.formats=[\"text\"]'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir / stale));
  EXPECT_THAT(r.err, HasSubstr("output: removed " + (dir / stale).string() + ", left by process"));
}

// A full disk while the UGRID (netCDF-4/HDF5) or the MSH file is written: a clear error naming
// the file and ENOSPC, exit 1, nothing left; it was "NetCDF: HDF error" then SIGSEGV (exit 139)
// in HDF5's exit handler. Needs a small tmpfs: mounted in a private user and mount namespace
// (`unshare -rm`), skipped where that is not permitted.
TEST(RobustOutputs, AFullDiskIsAClearErrorNeverACrash) {
  if (run_command("unshare -rm sh -c 'mount -t tmpfs -o size=64k tmpfs /tmp'").exit_code != 0)
    GTEST_SKIP() << "cannot mount a small tmpfs here (unshare -rm + mount -t tmpfs not permitted)";
  aq::testing::TempDir dir;
  for (const std::string& format : {std::string("ugrid"), std::string("msh")}) {
    SCOPED_TRACE(format);
    const std::string d = (dir / format).string();
    fs::create_directories(d);
    const CommandResult r = run_command("timeout -k 5 120 unshare -rm sh -c 'mount -t tmpfs -o size=256k tmpfs " + d +
                                        " && " + AQ_BINARY + " mesh -q -o " + d + " --set output.formats=[\\\"" +
                                        format + "\\\"]; rc=$?; ls -A " + d + "; exit $rc'");
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_THAT(r.err, HasSubstr("No space left on device"));
    EXPECT_THAT(r.err, HasSubstr(format == "ugrid" ? ".nc" : ".msh"));
    EXPECT_EQ(r.out, "") << "left in the folder";
  }
}

}  // namespace cli_robust_cli_test
