// SPDX-License-Identifier: GPL-3.0-or-later
// Transparent huge pages for the program's large blocks (the lattice bitmaps, mesh tables and
// output buffers of tens to hundreds of MB each).
//
// Linux backs anonymous memory with 4 KiB pages unless a range is advised otherwise (the usual
// setting, /sys/kernel/mm/transparent_hugepage/enabled = madvise). Every 4 KiB page of a new
// block costs a fault and, on a virtual machine, often a fault of the host too: the 15" global run
// took 2.7 million of them and spent 9 of its 54 CPU seconds clearing fresh pages. Advised blocks
// fault 2 MiB at a time: the same run's system time fell from 14 s to 8 s and its wall from 30 s
// to 25 s, with the same peak memory. Where huge pages are off ("never") the advice is ignored.
#pragma once

#include <cstddef>
#include <cstdint>

namespace aq {

/// Blocks of at least this many bytes are advised (smaller ones rarely hold a whole 2 MiB page).
inline constexpr std::size_t kLargeBlockBytes = std::size_t{4} << 20;

/// The whole pages of `page_bytes` inside [address, address + bytes): {first, end}, first == end
/// when none. `page_bytes` is a power of two.
struct PageRange {
  std::uintptr_t first = 0;
  std::uintptr_t end = 0;
};
[[nodiscard]] PageRange whole_pages_inside(std::uintptr_t address, std::size_t bytes, std::size_t page_bytes);

/// Advises the kernel to back the whole pages of [p, p + bytes) with transparent huge pages
/// (madvise MADV_HUGEPAGE). Only a hint: does nothing below kLargeBlockBytes, where the system
/// has no huge pages, or when the kernel refuses; never fails. Safe from any thread.
void advise_large_pages(void* p, std::size_t bytes) noexcept;

}  // namespace aq
