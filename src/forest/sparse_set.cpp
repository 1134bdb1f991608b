// SPDX-License-Identifier: GPL-3.0-or-later
// The forest's pixel sets gathered on rank 0, and their pinch vertices (see sparse_set.hpp).
#include "forest/sparse_set.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "core/types.hpp"

namespace aq::forest {

SparseSet SparseSet::gather(const PatchForest& pf, const std::vector<PatchBits>& set) {
  const PatchGrid& g = pf.grid();
  const std::int64_t p = g.size;
  const std::int64_t words = (p + 63) / 64 * p;
  std::vector<std::int64_t> flat;
  for (std::size_t l = 0; l < pf.local_count(); ++l) {
    if (set[l].state == Fill::kNone) continue;
    flat.push_back(pf.key(l));
    flat.push_back(static_cast<std::int64_t>(set[l].state));
    if (set[l].state == Fill::kMixed)
      for (const std::uint64_t w : set[l].bits.words()) flat.push_back(static_cast<std::int64_t>(w));
  }
  const std::vector<std::int64_t> all = pf.comm().gatherv(flat, 0);
  SparseSet s;
  s.grid_ = g;
  if (!pf.comm().root()) return s;
  s.state_.assign(static_cast<std::size_t>(g.count()), static_cast<std::uint8_t>(Fill::kNone));
  for (std::size_t q = 0; q < all.size();) {
    const std::int64_t key = all[q];
    const auto state = static_cast<Fill>(all[q + 1]);
    q += 2;
    s.state_[static_cast<std::size_t>(key)] = static_cast<std::uint8_t>(state);
    if (state == Fill::kMixed) {
      Bitmap b(p, p);
      for (std::int64_t w = 0; w < words; ++w)
        b.words()[static_cast<std::size_t>(w)] = static_cast<std::uint64_t>(all[q + static_cast<std::size_t>(w)]);
      q += static_cast<std::size_t>(words);
      s.bits_.emplace(key, std::move(b));
    }
  }
  return s;
}

bool SparseSet::get(std::int64_t i, std::int64_t j) const {
  const std::int64_t p = grid_.size;
  const std::int64_t key = grid_.key(i / p, j / p);
  const auto st = static_cast<Fill>(state_[static_cast<std::size_t>(key)]);
  if (st != Fill::kMixed) return st == Fill::kAll;
  return bits_.at(key).get(i % p, j % p);
}

void SparseSet::clear(std::int64_t i, std::int64_t j) {
  const std::int64_t p = grid_.size;
  const std::int64_t key = grid_.key(i / p, j / p);
  auto& st = state_[static_cast<std::size_t>(key)];
  if (static_cast<Fill>(st) == Fill::kNone) return;
  if (static_cast<Fill>(st) == Fill::kAll) {
    PatchBits all;
    all.state = Fill::kAll;
    bits_[key] = all.dense(p);
    st = static_cast<std::uint8_t>(Fill::kMixed);
  }
  Bitmap& b = bits_.at(key);
  if (!b.get(i % p, j % p)) return;
  b.clear(i % p, j % p);
  cleared_.push_back({i, j});
}

std::int64_t SparseSet::bytes() const {
  std::int64_t n = static_cast<std::int64_t>(state_.size());
  for (const auto& [k, b] : bits_) n += static_cast<std::int64_t>(b.bytes());
  return n;
}

void clear_pixels(const PatchForest& pf, std::vector<PatchBits>& set, const std::vector<mask::PixelIJ>& pixels) {
  const PatchGrid& g = pf.grid();
  const std::int64_t p = g.size;
  for (const mask::PixelIJ& px : pixels) {
    const std::int64_t l = pf.local_index(g.key(px.i / p, px.j / p));
    if (l < 0) continue;
    PatchBits& b = set[static_cast<std::size_t>(l)];
    if (b.state == Fill::kNone) continue;
    if (b.state == Fill::kAll) {
      b.bits = b.dense(p);
      b.state = Fill::kMixed;
    }
    b.bits.clear(px.i % p, px.j % p);
  }
  for (PatchBits& b : set) b.normalise();
}

std::vector<mask::Pinch> forest_pinches(const PatchForest& pf, const std::vector<PatchBits>& set, std::int64_t& total) {
  const PatchGrid& g = pf.grid();
  const std::int64_t p = g.size, ny = g.lat.ny;
  const std::vector<PatchBits> ghosts = pf.exchange(set);
  // Vertex (I, J) belongs to the patch of pixel (I, J); its pixels NW (I-1, J), NE (I, J),
  // SW (I-1, J-1), SE (I, J-1) are in the 3P × 3P window (columns wrap as in the dense rows).
  std::vector<std::int64_t> mine;  // J, I, pattern
  for (std::size_t l = 0; l < pf.local_count(); ++l) {
    const std::int64_t key = pf.key(l);
    bool interior = set[l].state != Fill::kMixed;
    for (std::int64_t dy = -1; dy <= 0 && interior; ++dy)
      for (std::int64_t dx = -1; dx <= 0 && interior; ++dx) {
        const PatchBits* b = pf.find(g.neighbour(g.gx(key), g.gy(key), dx, dy), set, ghosts);
        interior = b != nullptr && b->state == set[l].state;
      }
    if (interior) continue;  // four uniform patches alike around every vertex: no pinch
    const Bitmap w = pf.assemble(l, set, ghosts, OutsideRule{false, false});
    const std::int64_t I0 = g.gx(key) * p, J0 = g.gy(key) * p;
    for (std::int64_t y = 0; y < p; ++y) {
      const std::int64_t J = J0 + y;
      if (J < 1 || J >= ny) continue;
      for (std::int64_t x = 0; x < p; ++x) {
        const bool ne = w.get(p + x, p + y), nw = w.get(p + x - 1, p + y), se = w.get(p + x, p + y - 1),
                   sw = w.get(p + x - 1, p + y - 1);
        const bool nwse = nw && se && !ne && !sw, nesw = ne && sw && !nw && !se;
        if (!nwse && !nesw) continue;
        mine.push_back(J);
        mine.push_back(I0 + x);
        mine.push_back(nwse ? static_cast<std::int64_t>(mask::PinchPattern::kNwSe)
                            : static_cast<std::int64_t>(mask::PinchPattern::kNeSw));
      }
    }
  }
  total = pf.comm().sum(static_cast<std::int64_t>(mine.size() / 3));
  const std::vector<std::int64_t> all = pf.comm().gatherv(mine, 0);
  std::vector<mask::Pinch> out(all.size() / 3);
  for (std::size_t q = 0; q < out.size(); ++q) {
    out[q].vertex = {all[3 * q + 1], all[3 * q]};
    out[q].pattern = static_cast<mask::PinchPattern>(all[3 * q + 2]);
  }
  std::sort(out.begin(), out.end(), [](const mask::Pinch& a, const mask::Pinch& b) {
    return a.vertex.j < b.vertex.j || (a.vertex.j == b.vertex.j && a.vertex.i < b.vertex.i);
  });
  return out;
}

}  // namespace aq::forest
