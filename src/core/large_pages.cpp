// SPDX-License-Identifier: GPL-3.0-or-later
// Transparent huge pages for large blocks (large_pages.hpp).
#include "core/large_pages.hpp"

#include <sys/mman.h>
#include <unistd.h>

namespace aq {

PageRange whole_pages_inside(std::uintptr_t address, std::size_t bytes, std::size_t page_bytes) {
  const std::uintptr_t mask = page_bytes - 1;
  const std::uintptr_t first = (address + mask) & ~mask;
  const std::uintptr_t end = (address + bytes) & ~mask;
  if (end <= first) return {first, first};
  return {first, end};
}

void advise_large_pages(void* p, std::size_t bytes) noexcept {
#ifdef MADV_HUGEPAGE
  if (p == nullptr || bytes < kLargeBlockBytes) return;
  static const long page = sysconf(_SC_PAGESIZE);
  if (page <= 0) return;
  const PageRange r = whole_pages_inside(reinterpret_cast<std::uintptr_t>(p), bytes, static_cast<std::size_t>(page));
  // The kernel keeps 4 KiB pages where it has no huge page to give, or where the range is not
  // anonymous memory; the advice cannot fail the allocation.
  if (r.end > r.first) (void)madvise(reinterpret_cast<void*>(r.first), r.end - r.first, MADV_HUGEPAGE);
#else
  (void)p;
  (void)bytes;
#endif
}

}  // namespace aq
