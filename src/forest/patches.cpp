// SPDX-License-Identifier: GPL-3.0-or-later
// Patches of the forest engine (see patches.hpp).
#include "forest/patches.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

#include "core/error.hpp"
#include "quadtree/bits.hpp"

namespace aq::forest {

PatchGrid PatchGrid::make(const Lattice& lat) {
  PatchGrid g;
  g.lat = lat;
  g.plog = std::min(lat.levels, kMaxPatchLog2);
  g.level = lat.levels - g.plog;
  g.size = std::int64_t{1} << g.plog;
  g.npx = lat.nx >> g.plog;
  g.npy = lat.ny >> g.plog;
  g.per_tree = std::int64_t{1} << g.level;
  g.periodic = lat.periodic();
  return g;
}

std::int64_t PatchGrid::key_at(std::int64_t x, std::int64_t y) const {
  if (y < 0 || y >= npy) return -1;
  if (x < 0 || x >= npx) {
    if (!periodic) return -1;
    x = ((x % npx) + npx) % npx;
  }
  return key(x, y);
}

std::int64_t PatchGrid::neighbour(std::int64_t x, std::int64_t y, std::int64_t dx, std::int64_t dy) const {
  return key_at(x + dx, y + dy);
}

std::int64_t PatchGrid::tree_of(std::int64_t k) const {
  const std::int64_t nx0 = npx >> level;
  return (gy(k) >> level) * nx0 + (gx(k) >> level);
}

void PatchBits::normalise() {
  if (state != Fill::kMixed) return;
  const std::int64_t n = bits.count();
  if (n == 0) {
    state = Fill::kNone;
    bits = Bitmap();
  } else if (n == bits.nx() * bits.ny()) {
    state = Fill::kAll;
    bits = Bitmap();
  }
}

Bitmap PatchBits::dense(std::int64_t p) const {
  if (state == Fill::kMixed) return bits;
  Bitmap b(p, p);
  if (state == Fill::kAll)
    for (std::int64_t j = 0; j < p; ++j) quadtree::bits::set_range(b.row(j), 0, p);
  return b;
}

void or_bits_at(std::uint64_t* dst, std::int64_t off, const std::uint64_t* src, std::int64_t n) {
  const std::int64_t words = (n + 63) / 64;
  const int sh = static_cast<int>(off & 63);
  std::uint64_t* d = dst + (off >> 6);
  for (std::int64_t w = 0; w < words; ++w) {
    std::uint64_t v = src[w];
    if (w == words - 1) v &= quadtree::bits::last_word_mask(n);
    d[w] |= v << sh;
    if (sh != 0) {
      const std::uint64_t hi = v >> (64 - sh);
      if (hi != 0) d[w + 1] |= hi;
    }
  }
}

void take_bits(const std::uint64_t* src, std::int64_t off, std::uint64_t* dst, std::int64_t n) {
  const std::int64_t words = (n + 63) / 64;
  const int sh = static_cast<int>(off & 63);
  const std::uint64_t* s = src + (off >> 6);
  const std::int64_t src_words_needed = ((off & 63) + n + 63) / 64;
  for (std::int64_t w = 0; w < words; ++w) {
    std::uint64_t v = s[w] >> sh;
    if (sh != 0 && w + 1 < src_words_needed) v |= s[w + 1] << (64 - sh);
    dst[w] = v;
  }
  dst[words - 1] &= quadtree::bits::last_word_mask(n);
}

Bitmap centre_of(const Bitmap& window, std::int64_t p) {
  Bitmap c(p, p);
  for (std::int64_t j = 0; j < p; ++j) take_bits(window.row(p + j), p, c.row(j), p);
  return c;
}

PatchForest::PatchForest(const LatticeBrick& brick, const Comm& comm)
    : brick_(brick), comm_(comm), grid_(PatchGrid::make(brick.lattice())) {
  forest_ = uniform_forest(brick, comm_, grid_.level);
  local_tree_range(forest_.get(), first_tree_, last_tree_);
  p4est_t* f = forest_.get();
  keys_.reserve(static_cast<std::size_t>(f->local_num_quadrants));
  for (std::int64_t t = first_tree_; t < last_tree_; ++t) {
    const auto* tree = static_cast<const p4est_tree_t*>(sc_array_index(f->trees, static_cast<size_t>(t)));
    tree_first_local_.push_back(static_cast<std::int64_t>(keys_.size()));
    if (static_cast<std::int64_t>(tree->quadrants.elem_count) != grid_.per_tree * grid_.per_tree)
      throw InternalError("forest: a tree of the patch forest is split between ranks");
    for (size_t k = 0; k < tree->quadrants.elem_count; ++k) {
      const auto* q =
          static_cast<const p4est_quadrant_t*>(sc_array_index(const_cast<sc_array_t*>(&tree->quadrants), k));
      const Square s = brick_.square(t, *q);
      keys_.push_back(grid_.key(s.a, s.b));
    }
  }
  ghost_.reset(p4est_ghost_new(f, P4EST_CONNECT_FULL));
  const sc_array_t& gq = ghost_->ghosts;
  ghost_keys_.reserve(gq.elem_count);
  for (size_t g = 0; g < gq.elem_count; ++g) {
    const auto* q = static_cast<const p4est_quadrant_t*>(sc_array_index(const_cast<sc_array_t*>(&gq), g));
    const Square s = brick_.square(q->p.piggy3.which_tree, *q);
    const std::int64_t k = grid_.key(s.a, s.b);
    ghost_index_[k] = static_cast<std::int64_t>(g);
    ghost_keys_.push_back(k);
  }
}

std::int64_t PatchForest::local_index(std::int64_t k) const {
  const std::int64_t t = grid_.tree_of(k);
  if (t < first_tree_ || t >= last_tree_) return -1;
  const std::int64_t m = grid_.per_tree - 1;
  const auto px = static_cast<std::uint64_t>(grid_.gx(k) & m), py = static_cast<std::uint64_t>(grid_.gy(k) & m);
  return tree_first_local_[static_cast<std::size_t>(t - first_tree_)] +
         static_cast<std::int64_t>(quadtree::bits::morton(px, py));
}

std::int64_t PatchForest::ghost_index(std::int64_t k) const {
  const auto it = ghost_index_.find(k);
  return it == ghost_index_.end() ? -1 : it->second;
}

std::vector<char> PatchForest::exchange_bytes(const std::vector<char>& local, std::size_t bytes) const {
  const sc_array_t& mirrors = ghost_->mirrors;
  std::vector<void*> mirror_data(mirrors.elem_count);
  for (size_t m = 0; m < mirrors.elem_count; ++m) {
    const auto* q = static_cast<const p4est_quadrant_t*>(sc_array_index(const_cast<sc_array_t*>(&mirrors), m));
    mirror_data[m] = const_cast<char*>(local.data()) + static_cast<std::size_t>(q->p.piggy3.local_num) * bytes;
  }
  std::vector<char> out(ghost_->ghosts.elem_count * bytes);
  p4est_ghost_exchange_custom(forest_.get(), ghost_.get(), bytes, mirror_data.data(), out.data());
  return out;
}

std::vector<char> PatchForest::exchange_records(std::size_t bytes,
                                                const std::function<void(std::size_t, char*)>& pack) const {
  const sc_array_t& mirrors = ghost_->mirrors;
  std::vector<char> packed(mirrors.elem_count * bytes, 0);
  std::vector<void*> mirror_data(mirrors.elem_count);
  for (size_t m = 0; m < mirrors.elem_count; ++m) {
    const auto* q = static_cast<const p4est_quadrant_t*>(sc_array_index(const_cast<sc_array_t*>(&mirrors), m));
    pack(static_cast<std::size_t>(q->p.piggy3.local_num), packed.data() + m * bytes);
    mirror_data[m] = packed.data() + m * bytes;
  }
  std::vector<char> out(ghost_->ghosts.elem_count * bytes);
  p4est_ghost_exchange_custom(forest_.get(), ghost_.get(), bytes, mirror_data.data(), out.data());
  return out;
}

std::vector<PatchBits> PatchForest::exchange(const std::vector<PatchBits>& local) const {
  const std::int64_t p = grid_.size;
  const std::int64_t wpr = (p + 63) / 64;
  const std::size_t words = static_cast<std::size_t>(wpr * p);
  const std::size_t bytes = 8 * (1 + words);
  // Only mirrors are sent: pack those.
  const sc_array_t& mirrors = ghost_->mirrors;
  std::vector<char> packed(mirrors.elem_count * bytes, 0);
  std::vector<void*> mirror_data(mirrors.elem_count);
  for (size_t m = 0; m < mirrors.elem_count; ++m) {
    const auto* q = static_cast<const p4est_quadrant_t*>(sc_array_index(const_cast<sc_array_t*>(&mirrors), m));
    const PatchBits& b = local[static_cast<std::size_t>(q->p.piggy3.local_num)];
    char* dst = packed.data() + m * bytes;
    dst[0] = static_cast<char>(b.state);
    if (b.state == Fill::kMixed) std::memcpy(dst + 8, b.bits.words().data(), words * 8);
    mirror_data[m] = dst;
  }
  std::vector<char> raw(ghost_->ghosts.elem_count * bytes);
  p4est_ghost_exchange_custom(forest_.get(), ghost_.get(), bytes, mirror_data.data(), raw.data());
  std::vector<PatchBits> out(ghost_->ghosts.elem_count);
  for (std::size_t g = 0; g < out.size(); ++g) {
    const char* src = raw.data() + g * bytes;
    out[g].state = static_cast<Fill>(src[0]);
    if (out[g].state == Fill::kMixed) {
      out[g].bits = Bitmap(p, p);
      std::memcpy(out[g].bits.words().data(), src + 8, words * 8);
    }
  }
  return out;
}

const PatchBits* PatchForest::find(std::int64_t k, const std::vector<PatchBits>& mine,
                                   const std::vector<PatchBits>& ghosts) const {
  if (k < 0) return nullptr;
  if (const std::int64_t l = local_index(k); l >= 0) return &mine[static_cast<std::size_t>(l)];
  if (const std::int64_t g = ghost_index(k); g >= 0 && static_cast<std::size_t>(g) < ghosts.size())
    return &ghosts[static_cast<std::size_t>(g)];
  return nullptr;
}

Bitmap PatchForest::assemble(std::size_t local, const std::vector<PatchBits>& mine,
                             const std::vector<PatchBits>& ghosts, const OutsideRule& outside) const {
  const std::int64_t p = grid_.size;
  Bitmap w(3 * p, 3 * p);
  const std::int64_t k = keys_[local];
  const std::int64_t gx = grid_.gx(k), gy = grid_.gy(k);
  std::vector<std::uint64_t> ones(static_cast<std::size_t>((p + 63) / 64), ~std::uint64_t{0});
  for (std::int64_t dy = -1; dy <= 1; ++dy) {
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      const std::int64_t nk = grid_.neighbour(gx, gy, dx, dy);
      const std::int64_t x0 = (dx + 1) * p, y0 = (dy + 1) * p;
      bool fill = false;
      const PatchBits* b = nullptr;
      if (nk < 0) {
        const bool row_out = gy + dy < 0 || gy + dy >= grid_.npy;
        fill = row_out ? outside.row_value : outside.col_value;
      } else {
        b = find(nk, mine, ghosts);
        if (b == nullptr)
          throw InternalError(fmt::format("forest: patch ({}, {}) is neither local nor a ghost", gx + dx, gy + dy));
        fill = b->state == Fill::kAll;
      }
      if (fill) {
        for (std::int64_t j = 0; j < p; ++j) or_bits_at(w.row(y0 + j), x0, ones.data(), p);
      } else if (b != nullptr && b->state == Fill::kMixed) {
        for (std::int64_t j = 0; j < p; ++j) or_bits_at(w.row(y0 + j), x0, b->bits.row(j), p);
      }
    }
  }
  return w;
}

Bitmap gather_dense(const PatchForest& pf, const std::vector<PatchBits>& set) {
  const PatchGrid& g = pf.grid();
  const std::int64_t p = g.size;
  const std::int64_t words = (p + 63) / 64 * p;
  // Per local patch: key, state, then its words when mixed.
  std::vector<std::int64_t> flat;
  for (std::size_t l = 0; l < pf.local_count(); ++l) {
    flat.push_back(pf.key(l));
    flat.push_back(static_cast<std::int64_t>(set[l].state));
    if (set[l].state == Fill::kMixed)
      for (const std::uint64_t w : set[l].bits.words()) flat.push_back(static_cast<std::int64_t>(w));
  }
  const std::vector<std::int64_t> all = pf.comm().gatherv(flat, 0);
  Bitmap out;
  if (!pf.comm().root()) return out;
  out = Bitmap(g.lat.nx, g.lat.ny);
  std::vector<std::uint64_t> ones(static_cast<std::size_t>((p + 63) / 64), ~std::uint64_t{0});
  for (std::size_t q = 0; q < all.size();) {
    const std::int64_t key = all[q], state = all[q + 1];
    q += 2;
    const std::int64_t x0 = g.gx(key) * p, y0 = g.gy(key) * p;
    if (state == static_cast<std::int64_t>(Fill::kAll)) {
      for (std::int64_t j = 0; j < p; ++j) or_bits_at(out.row(y0 + j), x0, ones.data(), p);
    } else if (state == static_cast<std::int64_t>(Fill::kMixed)) {
      Bitmap b(p, p);
      for (std::int64_t w = 0; w < words; ++w)
        b.words()[static_cast<std::size_t>(w)] = static_cast<std::uint64_t>(all[q + static_cast<std::size_t>(w)]);
      q += static_cast<std::size_t>(words);
      for (std::int64_t j = 0; j < p; ++j) or_bits_at(out.row(y0 + j), x0, b.row(j), p);
    }
  }
  return out;
}

}  // namespace aq::forest
