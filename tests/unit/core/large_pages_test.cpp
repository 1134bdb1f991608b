// SPDX-License-Identifier: GPL-3.0-or-later
// Transparent huge pages for large blocks (core/large_pages.hpp): the whole pages inside a block,
// and the advice as the kernel records it (the "hg" flag of the block's mapping in
// /proc/self/smaps) where the system offers huge pages.
#include "core/large_pages.hpp"

#include <gtest/gtest.h>
#include <sys/mman.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

namespace aq::unit_core_large_pages_test {
namespace {

constexpr std::size_t kPage = 4096;

TEST(LargePages, WholePagesInsideABlock) {
  PageRange r = whole_pages_inside(0x10010, 3 * kPage, kPage);  // starts 16 B into a page
  EXPECT_EQ(r.first, 0x11000u);
  EXPECT_EQ(r.end, 0x13000u);                         // the last page ends 16 B short of the block's end: left out
  r = whole_pages_inside(0x10000, 3 * kPage, kPage);  // aligned: every page
  EXPECT_EQ(r.first, 0x10000u);
  EXPECT_EQ(r.end, 0x13000u);
  r = whole_pages_inside(0x10010, kPage, kPage);  // one page's worth across two pages: none
  EXPECT_EQ(r.first, r.end);
  r = whole_pages_inside(0x10001, 10, kPage);
  EXPECT_EQ(r.first, r.end);
}

// The smaps "VmFlags" line of the mapping that holds `address` ("" when not found).
std::string vm_flags_of(std::uintptr_t address) {
  std::ifstream in("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    std::uintptr_t lo = 0;
    std::uintptr_t hi = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> lo >> dash >> hi && dash == '-') {
      inside = lo <= address && address < hi;
      continue;
    }
    if (inside && line.rfind("VmFlags:", 0) == 0) return line;
  }
  return "";
}

bool huge_pages_offered() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string s;
  std::getline(in, s);
  return !s.empty() && s.find("[never]") == std::string::npos;
}

TEST(LargePages, ALargeBlockIsAdvisedASmallOneIsNot) {
  if (!huge_pages_offered()) GTEST_SKIP() << "transparent huge pages are off on this system";
  const std::size_t bytes = kLargeBlockBytes * 2;
  void* big = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(big, MAP_FAILED);
  const auto base = reinterpret_cast<std::uintptr_t>(big);
  EXPECT_EQ(vm_flags_of(base + kPage).find(" hg"), std::string::npos);
  advise_large_pages(big, kLargeBlockBytes - kPage);  // below the threshold: no advice
  EXPECT_EQ(vm_flags_of(base + kPage).find(" hg"), std::string::npos);
  advise_large_pages(reinterpret_cast<void*>(base + 16), bytes - 16);  // as malloc hands it out
  EXPECT_NE(vm_flags_of(base + kPage).find(" hg"), std::string::npos) << vm_flags_of(base + kPage);
  EXPECT_NE(vm_flags_of(base + bytes - kPage).find(" hg"), std::string::npos);
  EXPECT_EQ(vm_flags_of(base).find(" hg"), std::string::npos);  // the partial first page is left
  munmap(big, bytes);
}

}  // namespace
}  // namespace aq::unit_core_large_pages_test
