// SPDX-License-Identifier: GPL-3.0-or-later
// Word-parallel row primitives against per-bit references on random rows of awkward lengths.
#include "mask/bit_rows.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace aq::mask::bits::unit_mask_bit_rows_test {
namespace {

struct Row {
  std::int64_t n;
  std::vector<std::uint64_t> w;
  Row(std::int64_t n_, std::mt19937& rng, double p) : n(n_), w(static_cast<std::size_t>(words_for(n_)), 0) {
    std::bernoulli_distribution d(p);
    for (std::int64_t i = 0; i < n; ++i)
      if (d(rng)) w[static_cast<std::size_t>(i >> 6)] |= std::uint64_t{1} << (i & 63);
  }
  [[nodiscard]] bool get(std::int64_t i) const { return ((w[static_cast<std::size_t>(i >> 6)] >> (i & 63)) & 1U) != 0; }
};

TEST(BitRows, FindAndCountMatchPerBitReference) {
  std::mt19937 rng(7);
  for (const std::int64_t n : {1, 5, 63, 64, 65, 127, 128, 200, 1000}) {
    for (const double p : {0.02, 0.5, 0.98}) {
      const Row r(n, rng, p);
      std::uniform_int_distribution<std::int64_t> pos(0, n);
      for (int t = 0; t < 200; ++t) {
        std::int64_t a = pos(rng), b = pos(rng);
        if (a > b) std::swap(a, b);
        std::int64_t fs = b, fc = b, lc = a - 1, cnt = 0;
        for (std::int64_t i = a; i < b; ++i) {
          if (r.get(i) && fs == b) fs = i;
          if (!r.get(i) && fc == b) fc = i;
          if (!r.get(i)) lc = i;
          cnt += r.get(i) ? 1 : 0;
        }
        ASSERT_EQ(find_first_set(r.w.data(), a, b), fs) << n << " " << a << " " << b;
        ASSERT_EQ(find_first_clear(r.w.data(), a, b), fc) << n << " " << a << " " << b;
        ASSERT_EQ(find_last_clear(r.w.data(), a, b), lc) << n << " " << a << " " << b;
        ASSERT_EQ(count_range(r.w.data(), a, b), cnt);
      }
    }
  }
}

TEST(BitRows, SetAndClearRangeTouchOnlyTheRange) {
  std::mt19937 rng(8);
  for (const std::int64_t n : {3, 64, 130, 777}) {
    std::uniform_int_distribution<std::int64_t> pos(0, n);
    for (int t = 0; t < 100; ++t) {
      Row r(n, rng, 0.5);
      const Row orig = r;
      std::int64_t a = pos(rng), b = pos(rng);
      if (a > b) std::swap(a, b);
      const bool set = (t % 2) == 0;
      if (set)
        set_range(r.w.data(), a, b);
      else
        clear_range(r.w.data(), a, b);
      for (std::int64_t i = 0; i < n; ++i) {
        const bool expect = (i >= a && i < b) ? set : orig.get(i);
        ASSERT_EQ(r.get(i), expect) << n << " " << a << " " << b << " " << i;
      }
      // Padding stays clear.
      if ((n & 63) != 0) {
        ASSERT_EQ(r.w.back() >> (n & 63), 0U);
      }
    }
  }
}

TEST(BitRows, RotateIsPeriodicShiftForAllShiftsAndOps) {
  std::mt19937 rng(9);
  for (const std::int64_t n : {1, 7, 63, 64, 65, 129, 300}) {
    const Row src(n, rng, 0.5);
    for (const std::int64_t shift : {std::int64_t{0}, std::int64_t{1}, std::int64_t{-1}, std::int64_t{5},
                                     std::int64_t{-70}, n - 1, n, 3 * n + 2}) {
      for (const Combine op : {Combine::kCopy, Combine::kAnd, Combine::kOr}) {
        Row dst(n, rng, 0.5);
        const Row before = dst;
        rotate_row(src.w.data(), dst.w.data(), n, shift, op);
        for (std::int64_t i = 0; i < n; ++i) {
          const std::int64_t k = (((i + shift) % n) + n) % n;
          const bool s = src.get(k);
          const bool expect = op == Combine::kCopy  ? s
                              : op == Combine::kAnd ? (s && before.get(i))
                                                    : (s || before.get(i));
          ASSERT_EQ(dst.get(i), expect) << "n=" << n << " shift=" << shift << " i=" << i;
        }
        if ((n & 63) != 0) {
          ASSERT_EQ(dst.w.back() >> (n & 63), 0U);
        }
      }
    }
  }
}

TEST(BitRows, ReadWriteBitsAcrossWordBoundary) {
  std::vector<std::uint64_t> row(3, 0);
  write_bits(row.data(), 60, 0xABCDULL, 16);
  EXPECT_EQ(read_bits(row.data(), 60, 16), 0xABCDULL);
  EXPECT_EQ(row[0] >> 60, 0xDULL);
  EXPECT_EQ(row[1] & 0xFFFULL, 0xABCULL);
  write_bits(row.data(), 64, ~std::uint64_t{0}, 64);
  EXPECT_EQ(row[1], ~std::uint64_t{0});
  EXPECT_EQ(read_bits(row.data(), 60, 4), 0xDULL);
}

// threshold_row against the straightforward rule (compare as doubles), bit by bit: thresholds
// between floats, on floats, beyond the float range, infinite and NaN; values with NaN, ±0,
// ±inf, subnormals and the floats next to the threshold; row lengths around the word size.
TEST(BitRows, ThresholdRowMatchesDoubleComparison) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  constexpr float kFInf = std::numeric_limits<float>::infinity();
  const float fnan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<double> thresholds = {0.0,
                                          -0.0,
                                          -1e-300,
                                          1e-300,
                                          -0.1,
                                          0.1,
                                          -5.0,
                                          1e39,
                                          -1e39,
                                          kInf,
                                          -kInf,
                                          3.4028234663852886e38,
                                          static_cast<double>(0.1f),
                                          std::nextafter(static_cast<double>(0.1f), 1.0),
                                          std::nextafter(static_cast<double>(-0.1f), -1.0),
                                          std::numeric_limits<double>::quiet_NaN()};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> val(-10.0f, 10.0f);
  for (const double t : thresholds) {
    const auto tf = static_cast<float>(t);
    const std::vector<float> special = {
        fnan, 0.0f, -0.0f, kFInf, -kFInf, 1e-45f, -1e-45f, tf, std::nextafter(tf, kFInf), std::nextafter(tf, -kFInf),
        0.1f, -0.1f};
    for (const std::int64_t n : {1, 3, 4, 63, 64, 65, 130, 1000}) {
      std::vector<float> v(static_cast<std::size_t>(n));
      for (std::int64_t i = 0; i < n; ++i)
        v[static_cast<std::size_t>(i)] =
            i % 3 == 0 ? special[static_cast<std::size_t>(i / 3) % special.size()] : val(rng);
      std::vector<double> d(v.begin(), v.end());
      std::vector<std::uint64_t> got(static_cast<std::size_t>(words_for(n)) + 1, ~std::uint64_t{0});
      std::vector<std::uint64_t> got_d(got);
      threshold_row(v.data(), n, t, got.data());
      threshold_row(d.data(), n, t, got_d.data());
      for (std::int64_t i = 0; i < words_for(n) * 64; ++i) {
        const bool want = i < n && static_cast<double>(v[static_cast<std::size_t>(i)]) <= t;
        ASSERT_EQ(((got[static_cast<std::size_t>(i >> 6)] >> (i & 63)) & 1U) != 0, want)
            << "threshold " << t << ", n " << n << ", bit " << i;
        ASSERT_EQ(((got_d[static_cast<std::size_t>(i >> 6)] >> (i & 63)) & 1U) != 0, want)
            << "double values, threshold " << t << ", n " << n << ", bit " << i;
      }
      EXPECT_EQ(got.back(), ~std::uint64_t{0}) << "wrote past words_for(n)";
    }
  }
}

TEST(BitRows, FloatThresholdIsTheLargestFloatAtOrBelow) {
  EXPECT_EQ(float_threshold(0.0), 0.0f);
  EXPECT_EQ(float_threshold(0.1), std::nextafter(0.1f, -1.0f));  // 0.1f lies above 0.1
  EXPECT_EQ(float_threshold(static_cast<double>(0.1f)), 0.1f);
  EXPECT_EQ(float_threshold(1e39), std::numeric_limits<float>::max());
  EXPECT_EQ(float_threshold(-1e39), -std::numeric_limits<float>::infinity());
  EXPECT_EQ(float_threshold(std::numeric_limits<double>::infinity()), std::numeric_limits<float>::infinity());
  EXPECT_TRUE(std::isnan(float_threshold(std::numeric_limits<double>::quiet_NaN())));
}

}  // namespace
}  // namespace aq::mask::bits::unit_mask_bit_rows_test
