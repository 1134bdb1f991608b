// SPDX-License-Identifier: GPL-3.0-or-later
// Byte GeoTIFF (raster/byte_geotiff.hpp): what is written reads back (values, georeferencing,
// band names, metadata), the bytes do not depend on the run or the thread count, no sidecar
// file appears, and a write failure names the file.
#include "raster/byte_geotiff.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "support/temp_dir.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace aq::raster::unit_raster_byte_geotiff_test {
namespace {

namespace fs = std::filesystem;

ByteGeoTiffLayout layout() {
  ByteGeoTiffLayout l;
  l.width = 700;  // more than one 512 tile each way
  l.height = 530;
  l.west_deg = -180.0;
  l.north_deg = 90.0;
  l.pixel_deg = 0.25;
  l.band_names = {"first", "second"};
  l.metadata = {{"AQ_A", "one"}, {"AQ_B", "x = y; z"}};
  return l;
}

std::uint8_t value(int band, std::int64_t r, std::int64_t c) {
  return static_cast<std::uint8_t>((band * 7 + r * 3 + c) % 251);
}

void write(const fs::path& p) {
  write_byte_geotiff(p, layout(), [](std::int64_t r0, std::int64_t rows, std::vector<std::vector<std::uint8_t>>& b) {
    for (std::size_t band = 0; band < b.size(); ++band)
      for (std::int64_t r = 0; r < rows; ++r)
        for (std::int64_t c = 0; c < 700; ++c)
          b[band][static_cast<std::size_t>(r * 700 + c)] = value(static_cast<int>(band), r0 + r, c);
  });
}

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ByteGeoTiff, RoundTripsValuesGeoreferencingAndMetadata) {
  aq::testing::TempDir dir;
  const fs::path p = dir / "a.tmp";  // any extension: OutputSet temporaries
  write(p);
  EXPECT_FALSE(fs::exists(dir / "a.tmp.aux.xml"));
  const ByteGeoTiff t(p);
  const auto& l = t.layout();
  EXPECT_EQ(l.width, 700);
  EXPECT_EQ(l.height, 530);
  EXPECT_DOUBLE_EQ(l.west_deg, -180.0);
  EXPECT_DOUBLE_EQ(l.north_deg, 90.0);
  EXPECT_DOUBLE_EQ(l.pixel_deg, 0.25);
  ASSERT_EQ(l.band_names.size(), 2u);
  EXPECT_EQ(l.band_names[1], "second");
  EXPECT_EQ(t.metadata("AQ_B"), "x = y; z");
  EXPECT_EQ(t.metadata("AQ_MISSING"), "");
  std::vector<std::uint8_t> row(700 * 3);
  for (const int band : {1, 2}) {
    t.read_rows(band, 511, 3, row.data());  // across the tile boundary
    for (std::int64_t r = 0; r < 3; ++r)
      for (std::int64_t c = 0; c < 700; ++c)
        ASSERT_EQ(row[static_cast<std::size_t>(r * 700 + c)], value(band - 1, 511 + r, c));
  }
  EXPECT_LT(fs::file_size(p), 700u * 530u * 2u);  // compressed
}

TEST(ByteGeoTiff, BytesAreTheSameForEveryRunAndThreadCount) {
  aq::testing::TempDir dir;
  write(dir / "a.tif");
  write(dir / "b.tif");
#ifdef _OPENMP
  const int n = omp_get_max_threads();
  omp_set_num_threads(1);
  write(dir / "c.tif");
  omp_set_num_threads(n);
#else
  write(dir / "c.tif");
#endif
  EXPECT_EQ(bytes(dir / "a.tif"), bytes(dir / "b.tif"));
  EXPECT_EQ(bytes(dir / "a.tif"), bytes(dir / "c.tif"));
}

TEST(ByteGeoTiff, FailuresNameTheFile) {
  EXPECT_THROW(write("/nonexistent_dir_aq/x.tif"), OutputError);
  try {
    const ByteGeoTiff t("/nonexistent_dir_aq/x.tif");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_dir_aq/x.tif"), std::string::npos);
  }
}

}  // namespace
}  // namespace aq::raster::unit_raster_byte_geotiff_test
