// SPDX-License-Identifier: GPL-3.0-or-later
// DeflateAhead (io/deflate_ahead.hpp): chunks prepared on the threads come back from the
// program's compress2 as the bytes zlib's gives (shuffled as HDF5 shuffles, a partial last chunk
// padded), anything else is compressed by zlib, and a netCDF-4 file written with it has the bytes
// of the same file written without it. unit_io exports compress2 as the aquatoria executable does
// (tests/CMakeLists.txt), so HDF5's calls reach it here too.
#include <gtest/gtest.h>
#include <netcdf.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "io/deflate_ahead.hpp"

namespace unit_io_deflate_ahead_test {

namespace fs = std::filesystem;
using aq::io::DeflateAhead;

#ifdef _OPENMP  // DeflateAhead prepares chunks on the threads: without OpenMP there is nothing to test
namespace {

// zlib's deflate of `in` at `level`, by its stream functions (what compress2 does inside).
std::vector<unsigned char> zlib_bytes(const std::vector<unsigned char>& in, int level) {
  z_stream s{};
  EXPECT_EQ(deflateInit(&s, level), Z_OK);
  std::vector<unsigned char> out(deflateBound(&s, static_cast<uLong>(in.size())) + 16);
  s.next_in = const_cast<unsigned char*>(in.data());
  s.avail_in = static_cast<uInt>(in.size());
  s.next_out = out.data();
  s.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&s, Z_FINISH), Z_STREAM_END);
  out.resize(s.total_out);
  deflateEnd(&s);
  return out;
}

// HDF5's shuffle of a chunk of `e`-byte elements: byte i of element j to i·n + j.
std::vector<unsigned char> shuffled(const unsigned char* p, std::size_t bytes, std::size_t e) {
  const std::size_t n = bytes / e;
  std::vector<unsigned char> out(bytes);
  for (std::size_t i = 0; i < e; ++i)
    for (std::size_t j = 0; j < n; ++j) out[i * n + j] = p[j * e + i];
  return out;
}

// compress2 as HDF5 calls it (the program's, through the dynamic linker).
std::vector<unsigned char> call_compress2(const std::vector<unsigned char>& in, int level) {
  std::vector<unsigned char> out(static_cast<std::size_t>(std::ceil(static_cast<double>(in.size()) * 1.001)) + 12);
  auto n = static_cast<uLongf>(out.size());
  EXPECT_EQ(compress2(out.data(), &n, in.data(), static_cast<uLong>(in.size()), level), Z_OK);
  out.resize(n);
  return out;
}

std::vector<double> field(std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t k = 0; k < n; ++k)
    v[k] = 100.0 * std::sin(0.001 * static_cast<double>(k)) + 0.25 * static_cast<double>(k % 7);
  return v;
}

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A netCDF-4 file with a chunked, shuffled and deflated 2-D double and 1-D int variable, written
// in slabs as the UGRID writer writes, each slab prepared first when `ahead` is given.
void write_file(const fs::path& p, DeflateAhead* ahead) {
  constexpr std::size_t kRows = 300000, kCols = 3, kChunkRows = 65536, kSlab = 262144;  // a slab of 4 chunks: prepared
  int id = -1, d0 = -1, d1 = -1, vd = -1, vi = -1;
  ASSERT_EQ(nc_create(p.c_str(), NC_CLOBBER | NC_NETCDF4, &id), NC_NOERR);
  int old = 0;
  ASSERT_EQ(nc_set_fill(id, NC_NOFILL, &old), NC_NOERR);
  ASSERT_EQ(nc_def_dim(id, "rows", kRows, &d0), NC_NOERR);
  ASSERT_EQ(nc_def_dim(id, "cols", kCols, &d1), NC_NOERR);
  const int dims[2] = {d0, d1};
  ASSERT_EQ(nc_def_var(id, "values", NC_DOUBLE, 2, dims, &vd), NC_NOERR);
  ASSERT_EQ(nc_def_var(id, "index", NC_INT, 1, dims, &vi), NC_NOERR);
  for (const int v : {vd, vi}) {
    const std::size_t chunk[2] = {kChunkRows, kCols};
    ASSERT_EQ(nc_def_var_chunking(id, v, NC_CHUNKED, chunk), NC_NOERR);
    ASSERT_EQ(nc_def_var_deflate(id, v, 1, 1, 1), NC_NOERR);
  }
  ASSERT_EQ(nc_enddef(id), NC_NOERR);
  const std::vector<double> values = field(kRows * kCols);
  std::vector<int> index(kRows);
  for (std::size_t k = 0; k < kRows; ++k) index[k] = static_cast<int>((k * 7919) % 100003);
  for (std::size_t r = 0; r < kRows; r += kSlab) {
    const std::size_t rows = std::min(kSlab, kRows - r);
    const double* vp = values.data() + r * kCols;
    const int* ip = index.data() + r;
    if (ahead != nullptr) {
      ahead->prepare(vp, rows * kCols * 8, kChunkRows * kCols * 8, 8, true, 1);
      ahead->prepare(ip, rows * 4, kChunkRows * 4, 4, true, 1);
    }
    const std::size_t start[2] = {r, 0}, count[2] = {rows, kCols};
    ASSERT_EQ(nc_put_vara_double(id, vd, start, count, vp), NC_NOERR);
    ASSERT_EQ(nc_put_vara_int(id, vi, start, count, ip), NC_NOERR);
  }
  ASSERT_EQ(nc_close(id), NC_NOERR);
}

}  // namespace

TEST(DeflateAhead, PreparedChunksComeBackAsZlibsBytes) {
  DeflateAhead ahead;
  ASSERT_TRUE(ahead.active()) << "compress2 is not exported by the test program";
  const std::vector<double> v = field(3 * 4096 + 1000);  // three whole chunks of 4096 and a partial one
  const auto* p = reinterpret_cast<const unsigned char*>(v.data());
  constexpr std::size_t kChunk = 4096 * 8;
  ahead.prepare(p, v.size() * 8, kChunk, 8, true, 1);
  for (std::size_t c = 0; c < 4; ++c) {
    std::vector<unsigned char> raw(kChunk, 0);  // the partial chunk padded with zeros
    std::memcpy(raw.data(), p + c * kChunk, std::min(kChunk, v.size() * 8 - c * kChunk));
    const auto in = shuffled(raw.data(), kChunk, 8);
    EXPECT_EQ(call_compress2(in, 1), zlib_bytes(in, 1)) << "chunk " << c;
  }
  EXPECT_EQ(ahead.hits(), 4);
  EXPECT_EQ(ahead.misses(), 0);
  // Not prepared (another level; unshuffled bytes): zlib compresses them, the right bytes.
  const std::vector<unsigned char> other(p, p + kChunk);
  EXPECT_EQ(call_compress2(other, 1), zlib_bytes(other, 1));
  const auto in = shuffled(p, kChunk, 8);
  EXPECT_EQ(call_compress2(in, 3), zlib_bytes(in, 3));
  EXPECT_EQ(ahead.hits(), 4);
  EXPECT_EQ(ahead.misses(), 2);
}

TEST(DeflateAhead, ANetcdf4FileHasTheSameBytesWithAndWithout) {
  const fs::path dir = fs::temp_directory_path();
  const fs::path with = dir / "aq_deflate_ahead_with.nc", without = dir / "aq_deflate_ahead_without.nc";
  std::int64_t hits = 0, misses = 0;
  {
    DeflateAhead ahead;
    ASSERT_TRUE(ahead.active());
    write_file(with, &ahead);
    hits = ahead.hits();
    misses = ahead.misses();
  }
  DeflateAhead::allow(false);
  {
    DeflateAhead off;
    EXPECT_FALSE(off.active());
    write_file(without, nullptr);
  }
  DeflateAhead::allow(true);
  EXPECT_EQ(bytes_of(with), bytes_of(without));
  EXPECT_GE(hits, 8);  // the whole chunks (4 of values, 4 of index); the partial ones may miss
  EXPECT_LE(misses, 2);
  fs::remove(with);
  fs::remove(without);
}
#endif

}  // namespace unit_io_deflate_ahead_test
