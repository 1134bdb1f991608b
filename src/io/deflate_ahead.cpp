// SPDX-License-Identifier: GPL-3.0-or-later
// netCDF-4 chunks compressed ahead, handed to HDF5 through the program's compress2 (see
// deflate_ahead.hpp).
#include "io/deflate_ahead.hpp"

#include <dlfcn.h>
#include <xxhash.h>
#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <mutex>
#include <unordered_map>
#include <vector>

namespace aq::io {

namespace {

using Compress2 = int (*)(Bytef*, uLongf*, const Bytef*, uLong, int);

// compress2 as zlib (1.2.13) implements it, from zlib's stream functions: used only when zlib's
// own compress2 cannot be found behind the program's.
int stream_compress2(Bytef* dest, uLongf* dest_len, const Bytef* source, uLong source_len, int level) {
  z_stream s{};
  int err = deflateInit(&s, level);
  if (err != Z_OK) return err;
  const uInt max = static_cast<uInt>(-1);
  uLong left = *dest_len;
  *dest_len = 0;
  s.next_out = dest;
  s.avail_out = 0;
  s.next_in = const_cast<Bytef*>(source);
  s.avail_in = 0;
  do {
    if (s.avail_out == 0) {
      s.avail_out = left > static_cast<uLong>(max) ? max : static_cast<uInt>(left);
      left -= s.avail_out;
    }
    if (s.avail_in == 0) {
      s.avail_in = source_len > static_cast<uLong>(max) ? max : static_cast<uInt>(source_len);
      source_len -= s.avail_in;
    }
    err = deflate(&s, source_len != 0 ? Z_NO_FLUSH : Z_FINISH);
  } while (err == Z_OK);
  *dest_len = s.total_out;
  deflateEnd(&s);
  return err == Z_STREAM_END ? Z_OK : err;
}

// zlib's compress2 (the next one after the program's).
Compress2 zlib_compress2() {
  static const Compress2 f = [] {
    auto* g = reinterpret_cast<Compress2>(dlsym(RTLD_NEXT, "compress2"));
    return g != nullptr ? g : &stream_compress2;
  }();
  return f;
}

// The output buffer HDF5's deflate filter gives compress2 (H5Z_DEFLATE_SIZE_ADJUST in HDF5's
// H5Zdeflate.c): a chunk that would not fit fails in prepare() as it fails there, and is left to
// zlib when HDF5 asks.
std::size_t hdf5_bound(std::size_t n) {
  return static_cast<std::size_t>(std::ceil(static_cast<double>(n) * 1.001)) + 12;
}

struct Key {
  std::size_t bytes = 0;
  int level = 0;
  XXH128_hash_t hash{};
  bool operator==(const Key& o) const {
    return bytes == o.bytes && level == o.level && hash.low64 == o.hash.low64 && hash.high64 == o.hash.high64;
  }
};
struct KeyHash {
  std::size_t operator()(const Key& k) const { return static_cast<std::size_t>(k.hash.low64); }
};
struct Entry {
  std::vector<unsigned char> compressed;
  int uses = 0;  // prepared chunks with these bytes not yet asked for
};

std::mutex g_owner;                 // one DeflateAhead at a time
std::mutex g_lock;                  // the cache and the counts
std::atomic<bool> g_on{false};      // a DeflateAhead is alive and active
std::atomic<bool> g_allowed{true};  // DeflateAhead::allow
std::unordered_map<Key, Entry, KeyHash> g_cache;
std::int64_t g_hits = 0, g_misses = 0;

}  // namespace

}  // namespace aq::io

// The program's compress2 (see deflate_ahead.hpp): a prepared chunk's bytes, else zlib's.
extern "C" int compress2(Bytef* dest, uLongf* destLen, const Bytef* source, uLong sourceLen, int level) {
  using namespace aq::io;
  if (g_on.load(std::memory_order_acquire) && sourceLen > 0) {
    const Key key{static_cast<std::size_t>(sourceLen), level,
                  XXH3_128bits(source, static_cast<std::size_t>(sourceLen))};
    const std::lock_guard<std::mutex> lock(g_lock);
    const auto it = g_cache.find(key);
    if (it != g_cache.end() && it->second.compressed.size() <= *destLen) {
      const std::vector<unsigned char>& c = it->second.compressed;
      std::memcpy(dest, c.data(), c.size());
      *destLen = static_cast<uLongf>(c.size());
      if (--it->second.uses == 0) g_cache.erase(it);
      ++g_hits;
      return Z_OK;
    }
    ++g_misses;
  }
  return aq::io::zlib_compress2()(dest, destLen, source, sourceLen, level);
}

namespace aq::io {

DeflateAhead::DeflateAhead() {
  g_owner.lock();
#ifdef _OPENMP
  // HDF5 calls compress2 through the dynamic linker: it reaches this file's only when the
  // program exports it (the aquatoria executable does).
  active_ = g_allowed.load() && dlsym(RTLD_DEFAULT, "compress2") == reinterpret_cast<void*>(&::compress2);
#endif
  const std::lock_guard<std::mutex> lock(g_lock);
  g_cache.clear();
  g_hits = g_misses = 0;
  g_on.store(active_, std::memory_order_release);
}

DeflateAhead::~DeflateAhead() {
  g_on.store(false, std::memory_order_release);
  {
    const std::lock_guard<std::mutex> lock(g_lock);
    std::unordered_map<Key, Entry, KeyHash>().swap(g_cache);
  }
  g_owner.unlock();
}

void DeflateAhead::allow(bool allowed) { g_allowed.store(allowed); }

std::int64_t DeflateAhead::hits() const {
  const std::lock_guard<std::mutex> lock(g_lock);
  return g_hits;
}

std::int64_t DeflateAhead::misses() const {
  const std::lock_guard<std::mutex> lock(g_lock);
  return g_misses;
}

void DeflateAhead::prepare(const void* data, std::size_t bytes, std::size_t chunk_bytes, std::size_t element_bytes,
                           bool shuffle, int level) {
  if (!active_ || bytes == 0 || chunk_bytes == 0 || element_bytes == 0 || level < 1 || level > 9) return;
  const auto* src = static_cast<const unsigned char*>(data);
  const auto chunks = static_cast<std::int64_t>((bytes + chunk_bytes - 1) / chunk_bytes);
  // A slab of a few chunks is left to zlib when HDF5 asks, as without a DeflateAhead: preparing
  // costs a second shuffle and two hashes of every byte, and for one to three chunks of 65536
  // rows (every variable of the seed run: 3 % more instructions in the whole run) that is more
  // CPU than the milliseconds of wall the team saves. The UGRID writer's slabs are 16 chunks.
  constexpr std::int64_t kMinChunks = 4;
  if (chunks < kMinChunks) return;
  std::vector<Key> keys(static_cast<std::size_t>(chunks));
  std::vector<std::vector<unsigned char>> out(keys.size());
  const std::size_t n_el = chunk_bytes / element_bytes;
  const bool shuffled = shuffle && element_bytes > 1 && n_el > 1;
  const Compress2 zlib = zlib_compress2();
#pragma omp parallel default(none) \
    shared(src, bytes, chunk_bytes, element_bytes, chunks, keys, out, level, n_el, shuffled, zlib)
  {
    std::vector<unsigned char> in(shuffled ? chunk_bytes : 0), pad;
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t k = 0; k < chunks; ++k) {
      const std::size_t off = static_cast<std::size_t>(k) * chunk_bytes;
      const std::size_t have = std::min(chunk_bytes, bytes - off);
      const unsigned char* chunk = src + off;
      if (have < chunk_bytes) {  // a partial last chunk, padded with zero bytes
        pad.assign(chunk_bytes, 0);
        std::memcpy(pad.data(), chunk, have);
        chunk = pad.data();
      }
      if (shuffled) {  // byte i of element j goes to i·n + j (HDF5's shuffle; chunks hold whole elements)
        for (std::size_t i = 0; i < element_bytes; ++i) {
          unsigned char* d = in.data() + i * n_el;
          const unsigned char* s = chunk + i;
          for (std::size_t j = 0; j < n_el; ++j) d[j] = s[j * element_bytes];
        }
        chunk = in.data();
      }
      auto& o = out[static_cast<std::size_t>(k)];
      o.resize(hdf5_bound(chunk_bytes));
      auto n = static_cast<uLongf>(o.size());
      if (zlib(o.data(), &n, chunk, static_cast<uLong>(chunk_bytes), level) == Z_OK) {
        o.resize(n);
        o.shrink_to_fit();
        keys[static_cast<std::size_t>(k)] = Key{chunk_bytes, level, XXH3_128bits(chunk, chunk_bytes)};
      } else {
        std::vector<unsigned char>().swap(o);  // zlib fails the same way when HDF5 asks
      }
    }
  }
  const std::lock_guard<std::mutex> lock(g_lock);
  for (std::size_t k = 0; k < keys.size(); ++k) {
    if (out[k].empty()) continue;
    Entry& e = g_cache[keys[k]];
    if (e.uses++ == 0) e.compressed = std::move(out[k]);
  }
}

}  // namespace aq::io
