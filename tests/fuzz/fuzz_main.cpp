// SPDX-License-Identifier: GPL-3.0-or-later
// The libFuzzer entry point of one target, chosen at build time by AQ_FUZZ_TARGET (a name from
// targets.hpp); tests/fuzz/CMakeLists.txt builds one executable fuzz_<target> per target.
#include <cstdlib>

#include "fuzz/targets.hpp"

#define AQ_STR2(x) #x
#define AQ_STR(x) AQ_STR2(x)

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const aq::fuzz::Target* target = aq::fuzz::find_target(AQ_STR(AQ_FUZZ_TARGET));
  if (target == nullptr) std::abort();
  (void)target->run(data, size);
  return 0;
}
