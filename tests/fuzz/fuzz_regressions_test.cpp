// SPDX-License-Identifier: GPL-3.0-or-later
// Replays every kept fuzz input (tests/fuzz_regressions/<target>/*: inputs that once crashed, hung
// or tripped a sanitizer, found by scripts/fuzz.sh) through its target. Each must now end in a
// clear aq::Error or succeed; when a file NAME.expect sits beside the input, the error message
// must contain its text (the first line). The sanitizer build of the suite runs the same inputs
// under ASan+UBSan. Also checks the folders name only known targets.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz/targets.hpp"

namespace fuzz_fuzz_regressions_test {

namespace {

namespace fs = std::filesystem;

const fs::path kDir = fs::path(AQ_SOURCE_DIR) / "tests" / "fuzz_regressions";

std::vector<std::uint8_t> bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(FuzzRegressions, EveryFolderNamesATarget) {
  ASSERT_TRUE(fs::is_directory(kDir));
  for (const auto& e : fs::directory_iterator(kDir)) {
    if (!e.is_directory()) continue;
    EXPECT_NE(aq::fuzz::find_target(e.path().filename().string()), nullptr) << e.path();
  }
}

TEST(FuzzRegressions, KeptInputsEndInAClearErrorOrSucceed) {
  int replayed = 0;
  for (const aq::fuzz::Target& t : aq::fuzz::targets()) {
    const fs::path dir = kDir / std::string(t.name);
    if (!fs::is_directory(dir)) continue;
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file() && e.path().extension() != ".expect") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
      const std::vector<std::uint8_t> b = bytes_of(f);
      SCOPED_TRACE(f.string());
      std::string message;
      EXPECT_NO_THROW(message = t.run(b.data(), b.size()));
      fs::path expect = f;
      expect += ".expect";
      if (fs::exists(expect)) {
        std::string want;
        std::getline(std::ifstream(expect) >> std::ws, want);
        EXPECT_NE(message.find(want), std::string::npos) << "message: " << message << "\nwanted: " << want;
      }
      ++replayed;
    }
  }
  RecordProperty("replayed", replayed);
}

}  // namespace

}  // namespace fuzz_fuzz_regressions_test
