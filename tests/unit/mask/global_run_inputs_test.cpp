// SPDX-License-Identifier: GPL-3.0-or-later
// The inputs of the global run file follow a VRT's tiles: changing a tile changes the checksum,
// so `blocks` and `regional` do not reuse a run made from the old tile; a single file keeps the
// items (and checksum) it always had.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "mask/global_run_file.hpp"
#include "support/synthetic_raster.hpp"

namespace aq::mask::unit_mask_global_run_inputs_test {
namespace {

namespace fs = std::filesystem;

bool has_key(const std::vector<std::pair<std::string, std::string>>& items, const std::string& key,
             std::string* value = nullptr) {
  for (const auto& [k, v] : items)
    if (k == key) {
      if (value != nullptr) *value = v;
      return true;
    }
  return false;
}

TEST(GlobalRunInputs, VrtTilesCountBySizeAndTime) {
  const fs::path dir = aq::test::synthetic_dir() / "vrt_inputs";
  fs::create_directories(dir);
  const fs::path tile = aq::test::write_tiff(dir / "tile.tif", 1.0, true, true);
  const fs::path vrt = dir / "mosaic.vrt";
  std::ofstream(vrt) << R"(<VRTDataset rasterXSize="360" rasterYSize="180">
  <SRS>EPSG:4326</SRS>
  <GeoTransform>-180, 1, 0, 90, 0, -1</GeoTransform>
  <VRTRasterBand dataType="Int16" band="1">
    <SimpleSource>
      <SourceFilename relativeToVRT="1">tile.tif</SourceFilename>
      <SourceBand>1</SourceBand>
    </SimpleSource>
  </VRTRasterBand>
</VRTDataset>
)";
  config::GlobalConfig c;
  c.input.path = vrt.string();
  const auto before = mask_inputs(c);
  std::string sources;
  ASSERT_TRUE(has_key(before, "input.source_files", &sources));
  EXPECT_NE(sources.find("tile.tif"), std::string::npos) << sources;
  // A tile rewritten later (same size, newer time): another checksum, and the item says which.
  fs::last_write_time(tile, fs::last_write_time(tile) + std::chrono::seconds(10));
  const auto after = mask_inputs(c);
  EXPECT_NE(mask_inputs_checksum(before), mask_inputs_checksum(after));
  std::string sources_after;
  ASSERT_TRUE(has_key(after, "input.source_files", &sources_after));
  EXPECT_NE(sources, sources_after);
  // The .vrt itself is unchanged.
  std::string t0, t1;
  ASSERT_TRUE(has_key(before, "input.file_mtime", &t0));
  ASSERT_TRUE(has_key(after, "input.file_mtime", &t1));
  EXPECT_EQ(t0, t1);
  // A single file: no source_files item, so its checksum is what older global run files hold.
  c.input.path = tile.string();
  EXPECT_FALSE(has_key(mask_inputs(c), "input.source_files"));
  c.input.path = "/usr/share/ferret-vis/data/etopo5.cdf";
  EXPECT_FALSE(has_key(mask_inputs(c), "input.source_files"));
}

}  // namespace
}  // namespace aq::mask::unit_mask_global_run_inputs_test
