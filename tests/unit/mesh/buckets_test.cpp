// SPDX-License-Identifier: GPL-3.0-or-later
// Stable parallel counting sort (mesh/buckets.hpp): the same buckets, in the same order, as the
// serial counting sort, for one and two threads.
#include "mesh/buckets.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "support/omp_threads.hpp"

namespace aq::mesh::unit_mesh_buckets_test {
namespace {

// Item i emits (i·7919 mod 5000, 3i) and, for odd i, twice into bucket 31i mod 5000 (3i + 1, 3i + 2):
// buckets fed from all over the items and an item with two pairs in one bucket.
constexpr std::int64_t kBuckets = 5000;
const auto kPairs = [](std::int64_t i, const auto& emit) {
  emit((i * 7919) % kBuckets, 3 * i);
  if (i % 2 == 1) {
    emit((i * 31) % kBuckets, 3 * i + 1);
    emit((i * 31) % kBuckets, 3 * i + 2);
  }
};

TEST(StableBuckets, SerialCountingSortOrderForOneAndTwoThreads) {
  const std::int64_t n = 200000;
  std::vector<std::int64_t> start(kBuckets + 1, 0);
  for (std::int64_t i = 0; i < n; ++i) kPairs(i, [&](std::int64_t b, std::int64_t) { ++start[b + 1]; });
  for (std::int64_t b = 0; b < kBuckets; ++b) start[b + 1] += start[b];
  std::vector<std::int64_t> values(static_cast<std::size_t>(start.back()));
  std::vector<std::int64_t> cursor(start.begin(), start.end() - 1);
  for (std::int64_t i = 0; i < n; ++i)
    kPairs(i, [&](std::int64_t b, std::int64_t v) { values[static_cast<std::size_t>(cursor[b]++)] = v; });
  for (const int threads : {1, 2}) {
    const testing::ThreadCount use(threads);
#ifdef _OPENMP
    if (threads == 2) {
      ASSERT_EQ(quadtree::block_count(n, 4), 2);  // the parallel path runs
    }
#endif
    const Buckets<std::int64_t> got = stable_buckets<std::int64_t>(n, kBuckets, 4, kPairs);
    EXPECT_EQ(std::vector<std::int64_t>(got.start.begin(), got.start.end()), start) << threads << " threads";
    ASSERT_EQ(got.values.size(), values.size());
    EXPECT_TRUE(std::equal(values.begin(), values.end(), got.values.begin())) << threads << " threads";
  }
}

TEST(StableBuckets, NoItemsGiveEmptyBuckets) {
  const Buckets<int> got = stable_buckets<int>(0, 3, 1, [](std::int64_t, const auto&) {});
  EXPECT_EQ(std::vector<std::int64_t>(got.start.begin(), got.start.end()), (std::vector<std::int64_t>{0, 0, 0, 0}));
  EXPECT_TRUE(got.values.empty());
}

}  // namespace
}  // namespace aq::mesh::unit_mesh_buckets_test
