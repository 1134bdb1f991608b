// SPDX-License-Identifier: GPL-3.0-or-later
// Pinch vertices of Ω_L: word-parallel detection and the round-based removal (see pinches.hpp).
#include "mask/pinches.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <unordered_map>
#include <utility>

#include "core/error.hpp"
#include "mask/bit_rows.hpp"
#include "mask/k_cursor_fill.hpp"

namespace aq::mask {

namespace {

// Pinch bits of vertex row J (1 <= J <= ny-1): bit I set when vertex (I, J) is a pinch of the
// given pattern. west_* are pixel rows shifted so that bit I holds pixel I-1.
struct PinchRow {
  std::vector<std::uint64_t> west_lo, west_hi;
  explicit PinchRow(std::int64_t nw) : west_lo(static_cast<std::size_t>(nw)), west_hi(west_lo.size()) {}

  void compute(const Bitmap& f, std::int64_t J) {
    bits::rotate_row(f.row(J - 1), west_lo.data(), f.nx(), -1, bits::Combine::kCopy);
    bits::rotate_row(f.row(J), west_hi.data(), f.nx(), -1, bits::Combine::kCopy);
  }
  // Words of the two patterns for word w of row J.
  void word(const Bitmap& f, std::int64_t J, std::int64_t w, std::uint64_t& nwse, std::uint64_t& nesw) const {
    const std::uint64_t nwb = west_hi[static_cast<std::size_t>(w)], neb = f.row(J)[w];
    const std::uint64_t swb = west_lo[static_cast<std::size_t>(w)], seb = f.row(J - 1)[w];
    nwse = nwb & seb & ~neb & ~swb;
    nesw = neb & swb & ~nwb & ~seb;
  }
};

// Local evaluation of taking pixel c out of the filled set f (a union of all-filled K-windows).
// Patch: pixels at offsets [-2K, 2K] around c (columns wrap, rows outside the lattice empty);
// windows with lower-left offsets [-2K, K].
struct Removal {
  bool splits = false;        // more pieces of all-filled windows in the (3K+1)² window box
  std::vector<PixelIJ> lost;  // c and the pixels no longer covered by an all-filled window
  std::int64_t cost = 0;      // lost.size() + cut_cost when splits
};

Removal evaluate_removal(const PixelSet& f, int k, PixelIJ c) {
  const std::int64_t nx = f.nx(), ny = f.ny();
  const std::int64_t off = 2 * static_cast<std::int64_t>(k), s = 4 * static_cast<std::int64_t>(k) + 1;
  std::vector<int> sum(static_cast<std::size_t>((s + 1) * (s + 1)), 0);  // 2-D prefix sums of the patch
  const auto ps = [s](std::int64_t x, std::int64_t y) { return static_cast<std::size_t>(y * (s + 1) + x); };
  for (std::int64_t y = 0; y < s; ++y) {
    const std::int64_t j = c.j - off + y;
    for (std::int64_t x = 0; x < s; ++x) {
      const int v = (j >= 0 && j < ny && f.get(wrap_index(c.i - off + x, nx), j)) ? 1 : 0;
      sum[ps(x + 1, y + 1)] = v + sum[ps(x, y + 1)] + sum[ps(x + 1, y)] - sum[ps(x, y)];
    }
  }
  const auto full = [&](std::int64_t x, std::int64_t y) {  // window at patch (x, y) all filled
    const std::int64_t j = c.j - off + y;
    if (x < 0 || y < 0 || x + k > s || y + k > s || j < 0 || j > ny - k) return false;
    return sum[ps(x + k, y + k)] - sum[ps(x, y + k)] - sum[ps(x + k, y)] + sum[ps(x, y)] == k * k;
  };
  const auto holds_c = [&](std::int64_t x, std::int64_t y) {
    return x > off - k && x <= off && y > off - k && y <= off;
  };
  // Window grid: lower-left patch coordinates [0, 3K] (offsets -2K .. K).
  const std::int64_t g = 3 * static_cast<std::int64_t>(k) + 1;
  const auto gi = [g](std::int64_t x, std::int64_t y) { return static_cast<std::size_t>(y * g + x); };
  std::vector<unsigned char> before(static_cast<std::size_t>(g * g)), after(before.size());
  for (std::int64_t y = 0; y < g; ++y)
    for (std::int64_t x = 0; x < g; ++x) before[gi(x, y)] = full(x, y) ? 1 : 0;
  for (std::int64_t y = 0; y < g; ++y)
    for (std::int64_t x = 0; x < g; ++x) after[gi(x, y)] = (before[gi(x, y)] != 0 && !holds_c(x, y)) ? 1 : 0;
  const auto components = [g, &gi](std::vector<unsigned char> m) {
    int n = 0;
    std::vector<std::int64_t> stack;
    for (std::int64_t start = 0; start < g * g; ++start) {
      if (m[static_cast<std::size_t>(start)] == 0) continue;
      ++n;
      m[static_cast<std::size_t>(start)] = 0;
      stack.push_back(start);
      while (!stack.empty()) {
        const std::int64_t q = stack.back();
        stack.pop_back();
        const std::int64_t x = q % g, y = q / g;
        const std::int64_t nb[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
        for (const auto& p : nb) {
          if (p[0] < 0 || p[1] < 0 || p[0] >= g || p[1] >= g || m[gi(p[0], p[1])] == 0) continue;
          m[gi(p[0], p[1])] = 0;
          stack.push_back(p[1] * g + p[0]);
        }
      }
    }
    return n;
  };
  Removal r;
  r.splits = components(after) > components(before);
  // Pixels of the windows that held c: still covered by a surviving window?
  for (std::int64_t y = off - k + 1; y <= off + k - 1; ++y) {
    const std::int64_t j = c.j - off + y;
    if (j < 0 || j >= ny) continue;
    for (std::int64_t x = off - k + 1; x <= off + k - 1; ++x) {
      const std::int64_t i = wrap_index(c.i - off + x, nx);
      if (!f.get(i, j)) continue;
      bool covered = false;
      for (std::int64_t wy = y - k + 1; wy <= y && !covered; ++wy)
        for (std::int64_t wx = x - k + 1; wx <= x && !covered; ++wx) covered = after[gi(wx, wy)] != 0;
      if (!covered) r.lost.push_back({i, j});
    }
  }
  return r;
}

bool in_seed_window(PixelIJ c, int k, std::span<const PixelIJ> seeds, std::int64_t nx) {
  for (const PixelIJ& s : seeds) {
    const std::int64_t di = wrap_index(c.i - s.i, nx);
    if (di < k && c.j >= s.j && c.j < s.j + k) return true;
  }
  return false;
}

// Windows explored per piece by cut_cost, and the cost of cutting a seed off from a large piece.
constexpr std::int64_t kPieceBudget = 4096;
constexpr std::int64_t kCutOffSeed = 64 * kPieceBudget;

// Estimated windows lost beyond the local neighbourhood when the windows holding c go: the
// surviving windows next to them are grouped into pieces by breadth-first searches of at most
// kPieceBudget windows each (pieces that meet merge). A fully explored piece without a seed
// window is lost; a fully explored piece with a seed window keeps only itself; of several large
// (not fully explored) pieces without a seed, all but one count kPieceBudget each.
std::int64_t cut_cost(const PixelSet& f, int k, PixelIJ c, std::span<const PixelIJ> seeds) {
  const std::int64_t nx = f.nx(), ny = f.ny();
  const auto full = [&](std::int64_t i, std::int64_t j) {
    if (j < 0 || j > ny - k) return false;
    for (int b = 0; b < k; ++b)
      for (int a = 0; a < k; ++a)
        if (!f.get(wrap_index(i + a, nx), j + b)) return false;
    return true;
  };
  const auto holds_c = [&](std::int64_t i, std::int64_t j) {
    return wrap_index(c.i - i, nx) < k && c.j - j >= 0 && c.j - j < k;
  };
  const auto survivor = [&](std::int64_t i, std::int64_t j) { return full(i, j) && !holds_c(i, j); };
  const auto is_seed = [&](std::int64_t i, std::int64_t j) {
    for (const PixelIJ& s : seeds)
      if (s.i == i && s.j == j) return true;
    return false;
  };
  struct Piece {
    std::int64_t size = 0;
    bool large = false, seed = false;
    int parent = -1;
  };
  std::vector<Piece> pieces;
  const auto root = [&pieces](int p) {
    while (pieces[static_cast<std::size_t>(p)].parent >= 0) p = pieces[static_cast<std::size_t>(p)].parent;
    return p;
  };
  std::unordered_map<PixelIndex, int> owner;
  std::vector<PixelIJ> queue;
  for (std::int64_t dj = -k + 1; dj <= 0; ++dj) {
    for (std::int64_t di = -k + 1; di <= 0; ++di) {
      const std::int64_t wi = wrap_index(c.i + di, nx), wj = c.j + dj;
      if (!full(wi, wj)) continue;
      const PixelIJ nb[4] = {{wrap_index(wi - 1, nx), wj}, {wrap_index(wi + 1, nx), wj}, {wi, wj - 1}, {wi, wj + 1}};
      for (const PixelIJ& n0 : nb) {
        if (!survivor(n0.i, n0.j) || owner.count(pixel_index(n0, nx)) != 0) continue;
        const int id = static_cast<int>(pieces.size());
        pieces.push_back({});
        owner[pixel_index(n0, nx)] = id;
        queue.assign(1, n0);
        std::size_t head = 0;
        while (head < queue.size()) {
          const PixelIJ w = queue[head++];
          Piece& pc = pieces[static_cast<std::size_t>(id)];
          ++pc.size;
          pc.seed = pc.seed || is_seed(w.i, w.j);
          if (pc.size >= kPieceBudget) {
            pc.large = true;
            break;
          }
          const PixelIJ next[4] = {
              {wrap_index(w.i - 1, nx), w.j}, {wrap_index(w.i + 1, nx), w.j}, {w.i, w.j - 1}, {w.i, w.j + 1}};
          for (const PixelIJ& v : next) {
            if (!survivor(v.i, v.j)) continue;
            const auto it = owner.find(pixel_index(v, nx));
            if (it == owner.end()) {
              owner[pixel_index(v, nx)] = id;
              queue.push_back(v);
            } else if (root(it->second) != root(id)) {
              pieces[static_cast<std::size_t>(root(it->second))].parent = root(id);
            }
          }
        }
      }
    }
  }
  // Sum pieces into their roots.
  std::vector<Piece> roots;
  std::vector<int> root_index(pieces.size(), -1);
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const auto r = static_cast<std::size_t>(root(static_cast<int>(p)));
    if (root_index[r] < 0) {
      root_index[r] = static_cast<int>(roots.size());
      roots.push_back({});
    }
    Piece& t = roots[static_cast<std::size_t>(root_index[r])];
    t.size += pieces[p].size;
    t.large = t.large || pieces[p].large;
    t.seed = t.seed || pieces[p].seed;
  }
  if (roots.size() <= 1) return 0;
  std::int64_t cost = 0;
  const bool any_seed = std::any_of(roots.begin(), roots.end(), [](const Piece& p) { return p.seed; });
  const bool small_seed = std::any_of(roots.begin(), roots.end(), [](const Piece& p) { return p.seed && !p.large; });
  std::int64_t large_without_seed = 0, largest_small = 0;
  for (const Piece& p : roots) {
    if (p.seed) continue;
    if (p.large) {
      cost += small_seed ? kCutOffSeed : 0;
      ++large_without_seed;
    } else {
      cost += p.size;
      largest_small = std::max(largest_small, p.size);
    }
  }
  if (!any_seed) {
    // The seeds are beyond: one large piece (or, when all are small, the largest) stays.
    cost += large_without_seed > 0 ? (large_without_seed - 1) * kPieceBudget : -largest_small;
  } else if (!small_seed) {
    cost += large_without_seed * kPieceBudget;
  }
  return cost;
}

bool still_pinch(const PixelSet& f, const Pinch& p) {
  const std::int64_t nx = f.nx(), I = p.vertex.i, J = p.vertex.j, Iw = wrap_index(I - 1, nx);
  const bool nw = f.get(Iw, J), ne = f.get(I, J), sw = f.get(Iw, J - 1), se = f.get(I, J - 1);
  return p.pattern == PinchPattern::kNwSe ? (nw && se && !ne && !sw) : (ne && sw && !nw && !se);
}

}  // namespace

void ConstBitmapSet::clear(std::int64_t, std::int64_t) {
  throw InternalError("ConstBitmapSet: a read-only pixel set cannot be changed");
}

const char* pinch_pattern_name(PinchPattern p) { return p == PinchPattern::kNwSe ? "1001 (NW-SE)" : "0110 (NE-SW)"; }

std::vector<Pinch> find_pinches(const Bitmap& f) {
  const std::int64_t ny = f.ny(), nw = f.words_per_row();
  std::vector<std::int64_t> offset(static_cast<std::size_t>(std::max<std::int64_t>(ny, 1) + 1), 0);
  // Pass 1: count per vertex row; pass 2: write at the prefix-sum offsets.
#pragma omp parallel default(none) shared(f, ny, nw, offset) if (ny * nw >= bits::kParallelMinWords)
  {
    PinchRow pr(nw);
#pragma omp for schedule(static)
    for (std::int64_t J = 1; J < ny; ++J) {
      pr.compute(f, J);
      std::int64_t n = 0;
      for (std::int64_t w = 0; w < nw; ++w) {
        std::uint64_t a = 0, b = 0;
        pr.word(f, J, w, a, b);
        n += std::popcount(a) + std::popcount(b);
      }
      offset[static_cast<std::size_t>(J + 1)] = n;
    }
  }
  for (std::size_t J = 1; J < offset.size(); ++J) offset[J] += offset[J - 1];
  std::vector<Pinch> out(static_cast<std::size_t>(offset.back()));
#pragma omp parallel default(none) shared(f, ny, nw, offset, out) if (ny * nw >= bits::kParallelMinWords)
  {
    PinchRow pr(nw);
#pragma omp for schedule(static)
    for (std::int64_t J = 1; J < ny; ++J) {
      auto pos = static_cast<std::size_t>(offset[static_cast<std::size_t>(J)]);
      if (pos == static_cast<std::size_t>(offset[static_cast<std::size_t>(J + 1)])) continue;
      pr.compute(f, J);
      for (std::int64_t w = 0; w < nw; ++w) {
        std::uint64_t a = 0, b = 0;
        pr.word(f, J, w, a, b);
        std::uint64_t both = a | b;
        while (both != 0) {
          const int bit = std::countr_zero(both);
          both &= both - 1;
          Pinch p;
          p.vertex = {(w << 6) + bit, J};
          p.pattern = ((a >> bit) & 1U) != 0 ? PinchPattern::kNwSe : PinchPattern::kNeSw;
          out[pos++] = p;
        }
      }
    }
  }
  return out;
}

std::int64_t count_pinches(const Bitmap& f) {
  const std::int64_t ny = f.ny(), nw = f.words_per_row();
  std::int64_t total = 0;
#pragma omp parallel default(none) shared(f, ny, nw) reduction(+ : total) if (ny * nw >= bits::kParallelMinWords)
  {
    PinchRow pr(nw);
#pragma omp for schedule(static)
    for (std::int64_t J = 1; J < ny; ++J) {
      pr.compute(f, J);
      for (std::int64_t w = 0; w < nw; ++w) {
        std::uint64_t a = 0, b = 0;
        pr.word(f, J, w, a, b);
        total += std::popcount(a) + std::popcount(b);
      }
    }
  }
  return total;
}

void locate_pinches(std::vector<Pinch>& pinches, const Lattice& lattice, const PoleRotation& rot) {
  for (Pinch& p : pinches) {
    p.lattice_pos = vertex_lattice_deg(lattice, p.vertex.i, p.vertex.j);
    p.geographic = lattice_to_geographic(rot, p.lattice_pos);
  }
}

std::int64_t resolve_pinches(PixelSet& filled, int k, std::span<const PixelIJ> seed_windows,
                             const std::vector<Pinch>& pinches) {
  const std::int64_t nx = filled.nx();
  std::int64_t chosen = 0;
  for (const Pinch& p : pinches) {
    if (!still_pinch(filled, p)) continue;
    const std::int64_t I = p.vertex.i, J = p.vertex.j, Iw = wrap_index(I - 1, nx);
    PixelIJ a{}, b{};
    if (p.pattern == PinchPattern::kNwSe) {
      a = {Iw, J};     // NW
      b = {I, J - 1};  // SE
    } else {
      a = {I, J};       // NE
      b = {Iw, J - 1};  // SW
    }
    const bool pa = in_seed_window(a, k, seed_windows, nx), pb = in_seed_window(b, k, seed_windows, nx);
    if (pa && pb) continue;
    Removal ra, rb;
    const auto evaluate = [&](PixelIJ c) {
      Removal r = evaluate_removal(filled, k, c);
      r.cost = static_cast<std::int64_t>(r.lost.size()) + (r.splits ? cut_cost(filled, k, c, seed_windows) : 0);
      return r;
    };
    if (!pa) ra = evaluate(a);
    if (!pb) rb = evaluate(b);
    bool take_a = !pa;
    if (!pa && !pb) take_a = std::make_pair(ra.cost, pixel_index(a, nx)) < std::make_pair(rb.cost, pixel_index(b, nx));
    for (const PixelIJ& q : (take_a ? ra : rb).lost) filled.clear(q.i, q.j);
    ++chosen;
  }
  return chosen;
}

PinchRemovalStats remove_pinches(Bitmap& filled, int k, std::span<const PixelIJ> seed_windows) {
  PinchRemovalStats st;
  const std::int64_t before = filled.count();
  std::vector<Pinch> pinches = find_pinches(filled);
  st.pinches_found = static_cast<std::int64_t>(pinches.size());
  while (!pinches.empty()) {
    ++st.rounds;
    BitmapSet set(filled);
    const std::int64_t chosen = resolve_pinches(set, k, seed_windows, pinches);
    st.pixels_chosen += chosen;
    if (chosen == 0) break;
    filled = k_fill(filled, k, seed_windows);
    pinches = find_pinches(filled);
  }
  st.unresolved = static_cast<std::int64_t>(pinches.size());
  st.pixels_removed = before - filled.count();
  return st;
}

}  // namespace aq::mask
