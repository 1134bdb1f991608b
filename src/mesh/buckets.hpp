// SPDX-License-Identifier: GPL-3.0-or-later
// Stable counting sort of (bucket, value) pairs in parallel, for the per-node adjacency of mesh
// checks (statistics.cpp: half-edges by their smaller node; mesh_files/sphere_quality.cpp:
// triangles round each node). Items 0..n-1 emit pairs; the values of a bucket come out in item
// order (and, within an item, in emission order): the order of the serial loop
//
//     for item: for (bucket, value) of item: values[cursor[bucket]++] = value
//
// for any thread count. The items are cut into contiguous blocks (quadtree/parallel.hpp); each
// block counts its pairs per bucket, the counts are turned into each block's first slot per bucket
// (bucket-major, block-minor prefix sums), and each block writes its pairs from there:
//
//     bucket:      0          1          2
//     block:     0   1      0   1      0   1
//     counts:    2   1      0   3      1   0      ->  slots: 0 2 | 3 3 | 6 7 (end 7)
//
// Memory: blocks × buckets 64-bit cursors while it runs, besides the result.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include "quadtree/parallel.hpp"

namespace aq::mesh {

/// Allocator whose resize() leaves new elements of a trivial type uninitialised (no zeroing
/// pass): for arrays that a parallel loop fills completely, so that the first touch of their pages
/// is spread over the threads.
template <class T>
struct UninitialisedAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitialisedAllocator<U>;
  };
  UninitialisedAllocator() = default;
  template <class U>
  UninitialisedAllocator(const UninitialisedAllocator<U>& /*other*/) noexcept {}  // NOLINT: rebinding
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;  // default-initialisation: no value for trivial types
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    std::allocator_traits<std::allocator<T>>::construct(static_cast<std::allocator<T>&>(*this), p,
                                                        std::forward<Args>(args)...);
  }
};

/// A flat array that a parallel loop fills (see UninitialisedAllocator).
template <class T>
using FillVector = std::vector<T, UninitialisedAllocator<T>>;

/// Values grouped by bucket: bucket b holds values[start[b] .. start[b + 1]).
template <class T>
struct Buckets {
  FillVector<std::int64_t> start;  ///< size buckets + 1, start[0] = 0
  FillVector<T> values;
};

/// Groups the pairs of items 0..n_items-1 by bucket, stably (see the top of this file).
/// `pairs(item, emit)` calls `emit(bucket, value)` for each pair of the item, bucket in
/// [0, n_buckets); it is called twice per item (count, then fill) and must emit the same pairs in
/// the same order both times; it may run on several threads at once. `work_per_item` (about the
/// word operations per item) decides whether to run in parallel (quadtree::block_count).
template <class T, class Pairs>
Buckets<T> stable_buckets(std::int64_t n_items, std::int64_t n_buckets, std::int64_t work_per_item,
                          const Pairs& pairs) {
  const int blocks = quadtree::block_count(n_items, work_per_item);
  const auto nb = static_cast<std::size_t>(n_buckets);
  // cursor[block · n_buckets + bucket]: the block's pair count, then its next slot. Each block
  // zeroes its own row, and the arrays below are first written in parallel loops, so that their
  // pages are first touched on all the threads.
  FillVector<std::int64_t> cursor(static_cast<std::size_t>(blocks) * nb);
  quadtree::for_each_block(n_items, blocks, [&](int b, std::int64_t begin, std::int64_t end) {
    std::int64_t* c = cursor.data() + static_cast<std::size_t>(b) * nb;
    std::fill(c, c + nb, std::int64_t{0});
    for (std::int64_t i = begin; i < end; ++i) pairs(i, [c](std::int64_t bucket, const T& /*value*/) { ++c[bucket]; });
  });
  Buckets<T> out;
  out.start.resize(nb + 1);
  std::int64_t* start = out.start.data();
  start[0] = 0;
  std::int64_t* cur = cursor.data();
#pragma omp parallel for default(none) if (blocks > 1) shared(start, cur, n_buckets, blocks, nb) schedule(static)
  for (std::int64_t v = 0; v < n_buckets; ++v) {
    std::int64_t sum = 0;
    for (int b = 0; b < blocks; ++b) sum += cur[static_cast<std::size_t>(b) * nb + static_cast<std::size_t>(v)];
    start[v + 1] = sum;
  }
  for (std::size_t v = 0; v < nb; ++v) start[v + 1] += start[v];
#pragma omp parallel for default(none) if (blocks > 1) shared(start, cur, n_buckets, blocks, nb) schedule(static)
  for (std::int64_t v = 0; v < n_buckets; ++v) {
    std::int64_t slot = start[v];
    for (int b = 0; b < blocks; ++b) {
      std::int64_t& c = cur[static_cast<std::size_t>(b) * nb + static_cast<std::size_t>(v)];
      const std::int64_t count = c;
      c = slot;
      slot += count;
    }
  }
  out.values.resize(static_cast<std::size_t>(out.start.back()));
  T* values = out.values.data();
  quadtree::for_each_block(n_items, blocks, [&](int b, std::int64_t begin, std::int64_t end) {
    std::int64_t* c = cursor.data() + static_cast<std::size_t>(b) * nb;
    for (std::int64_t i = begin; i < end; ++i)
      pairs(i, [c, values](std::int64_t bucket, const T& value) { values[c[bucket]++] = value; });
  });
  return out;
}

}  // namespace aq::mesh
