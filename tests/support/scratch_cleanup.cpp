// SPDX-License-Identifier: GPL-3.0-or-later
// Every test program links this file: when the program ends, the scratch folders and files it made
// under the temporary directory with its own process id (`aq_<what>_<pid>`, the tests' naming rule:
// cli_outputs.hpp's fresh_dir, synthetic_raster.hpp, the integration runs) are removed, so a suite
// run leaves nothing behind (a quick suite used to leave about 0.7 GB in /tmp every run). They are
// kept when a test failed, or with AQ_TEST_KEEP=1 in the environment, to look at.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace aq_test_scratch_cleanup {

struct RemoveScratchAtExit {
  ~RemoveScratchAtExit() {
    const char* keep = std::getenv("AQ_TEST_KEEP");
    if (keep != nullptr && std::string(keep) != "0") return;
    if (::testing::UnitTest::GetInstance()->Failed()) return;
    namespace fs = std::filesystem;
    const std::string suffix = "_" + std::to_string(::getpid());
    std::error_code ec;
    const fs::path tmp = fs::temp_directory_path(ec);
    if (ec) return;
    std::vector<fs::path> mine;
    for (fs::directory_iterator it(tmp, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string name = it->path().filename().string();
      if (name.size() > 3 + suffix.size() && name.compare(0, 3, "aq_") == 0 &&
          name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
        mine.push_back(it->path());
    }
    for (const fs::path& p : mine) fs::remove_all(p, ec);
  }
};

const RemoveScratchAtExit remove_scratch_at_exit;

}  // namespace aq_test_scratch_cleanup
