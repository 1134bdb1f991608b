// SPDX-License-Identifier: GPL-3.0-or-later
// The forest engine's stages of the global run (see pipeline.hpp).
#include "forest/pipeline.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "core/error.hpp"
#include "core/timer.hpp"
#include "core/types.hpp"
#include "forest/bounds.hpp"
#include "forest/classify.hpp"
#include "forest/comm.hpp"
#include "forest/fill.hpp"
#include "forest/lattice_forest.hpp"
#include "forest/mesh_forest.hpp"
#include "forest/patches.hpp"
#include "forest/pyramid.hpp"
#include "forest/sparse_set.hpp"
#include "mask/lattice_coords.hpp"
#include "mask/passages.hpp"
#include "mask/pinches.hpp"
#include "mesh/templates.hpp"
#include "quadtree/balance.hpp"
#include "quadtree/build_leaves.hpp"
#include "size/terms.hpp"

namespace aq::forest {

struct ForestState {
  Comm comm;
  std::unique_ptr<LatticeBrick> brick;
  std::unique_ptr<PatchForest> patches;
  std::vector<PatchBits> wet;  ///< per local patch: the pixel classes' wet pixels
  /// A floodplain run (h < 0): per local patch, the pixels wet at the datum (the pixel rule at
  /// 0 m, mask::WetArea::datum_wet); empty otherwise.
  std::vector<PatchBits> datum_wet;
  /// The water at the datum, whose pixels beyond a regional domain make its edge open.
  [[nodiscard]] const std::vector<PatchBits>& water() const { return datum_wet.empty() ? wet : datum_wet; }
};

namespace {

double round3(double x) { return std::round(x * 1000.0) / 1000.0; }

std::int64_t count_pixels(const std::vector<PatchBits>& v, std::int64_t p) {
  std::int64_t n = 0;
  for (const PatchBits& b : v) n += b.state == Fill::kAll ? p * p : b.state == Fill::kMixed ? b.bits.count() : 0;
  return n;
}

// The domain's pixels in a patch (from its shape: no bitmap of the lattice).
PatchBits domain_patch(const mask::Domain& d, const PatchGrid& g, std::int64_t key) {
  const std::int64_t p = g.size;
  PatchBits b;
  b.state = Fill::kMixed;
  b.bits = d.window(g.gx(key) * p, g.gy(key) * p, p, p);
  b.normalise();
  return b;
}

PatchBits intersect(const PatchBits& a, const PatchBits& b, std::int64_t p) {
  if (a.state == Fill::kNone || b.state == Fill::kNone) return {};
  if (a.state == Fill::kAll) return b;
  if (b.state == Fill::kAll) return a;
  PatchBits out = a;
  for (std::size_t k = 0; k < out.bits.words().size(); ++k) out.bits.words()[k] &= b.bits.words()[k];
  out.normalise();
  (void)p;
  return out;
}

// a \ b.
PatchBits subtract(const PatchBits& a, const PatchBits& b, std::int64_t p) {
  if (a.state == Fill::kNone || b.state == Fill::kAll) return {};
  if (b.state == Fill::kNone) return a;
  PatchBits out;
  out.state = Fill::kMixed;
  out.bits = a.dense(p);
  for (std::size_t k = 0; k < out.bits.words().size(); ++k) out.bits.words()[k] &= ~b.bits.words()[k];
  out.normalise();
  return out;
}

// mask::regional_seeds on the forest: the configured seeds inside the domain, else the deepest
// wet pixel inside (ties: smallest (j, i)) over all ranks.
std::vector<std::array<double, 2>> regional_seeds(const PatchForest& pf, const mask::Domain& domain,
                                                  const std::vector<PatchBits>& wet_in, const Lattice& lattice,
                                                  const PoleRotation& rot, const raster::Bathymetry& bathy,
                                                  const std::vector<std::array<double, 2>>& seeds, const Logger& log) {
  std::vector<std::array<double, 2>> out;
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    double rl = 0.0, rp = 0.0, x = 0.0, y = 0.0;
    rot.to_rotated(seeds[k][0], seeds[k][1], rl, rp);
    mask::deg_to_lattice_xy(lattice, {rl, rp}, x, y);
    if (!mask::on_lattice(lattice, x, y)) continue;
    const auto i = static_cast<std::int64_t>(std::floor(x)), j = static_cast<std::int64_t>(std::floor(y));
    if (domain.contains(i, std::min(j, lattice.ny - 1))) out.push_back(seeds[k]);
  }
  if (!out.empty()) {
    if (out.size() < seeds.size())
      log.info("domain: {} of the {} mask.seeds are inside the domain and seed the fill", out.size(), seeds.size());
    return out;
  }
  struct Deepest {
    double z = std::numeric_limits<double>::infinity();
    std::int64_t j = -1, i = -1;
  };
  Deepest mine;
  const PatchGrid& g = pf.grid();
  const std::int64_t p = g.size;
  for (std::size_t l = 0; l < pf.local_count(); ++l) {
    const PatchBits& w = wet_in[l];
    if (w.state == Fill::kNone) continue;
    const std::int64_t key = pf.key(l), i0 = g.gx(key) * p, j0 = g.gy(key) * p;
    for (std::int64_t y = 0; y < p; ++y)
      for (std::int64_t x = 0; x < p; ++x) {
        if (!w.get(x, y)) continue;
        const mask::LonLat c = mask::pixel_center_lattice_deg(lattice, {i0 + x, j0 + y});
        double lon = c.lon_deg, la = c.lat_deg;
        if (!rot.identity()) rot.to_geographic(c.lon_deg, c.lat_deg, lon, la);
        const double z = bathy.sample(lon, la);
        const std::int64_t j = j0 + y, i = i0 + x;
        if (std::isfinite(z) && (z < mine.z || (z == mine.z && (j < mine.j || (j == mine.j && i < mine.i)))))
          mine = {z, j, i};
      }
  }
  const std::vector<Deepest> all = pf.comm().allgatherv(std::vector<Deepest>{mine});
  Deepest best;
  for (const Deepest& d : all)
    if (d.j >= 0 && (d.z < best.z || (d.z == best.z && (d.j < best.j || (d.j == best.j && d.i < best.i))))) best = d;
  if (best.j < 0) throw InputError(fmt::format("domain: no wet pixel inside the {}", domain.description));
  const mask::LonLat c = mask::pixel_center_lattice_deg(lattice, {best.i, best.j});
  double lon = c.lon_deg, la = c.lat_deg;
  if (!rot.identity()) rot.to_geographic(c.lon_deg, c.lat_deg, lon, la);
  log.info(
      "domain: no mask.seeds point is inside the domain; the fill starts at the deepest wet pixel inside, "
      "{:.4f}°E {:.4f}°N ({:.0f} m)",
      lon, la, best.z);
  return {{lon, la}};
}

// The grid cells' filled-pixel counts over the patches of every rank (FieldGrid::filled_counts).
std::vector<std::int32_t> filled_counts(const PatchForest& pf, const std::vector<PatchBits>& filled,
                                        const size::FieldGrid& grid) {
  const PatchGrid& g = pf.grid();
  const std::int64_t p = g.size, s = grid.pixels_per_cell();
  std::vector<std::int32_t> count(static_cast<std::size_t>(grid.cells()), 0);
  for (std::size_t l = 0; l < pf.local_count(); ++l) {
    const PatchBits& b = filled[l];
    if (b.state == Fill::kNone) continue;
    const std::int64_t key = pf.key(l), i0 = g.gx(key) * p, j0 = g.gy(key) * p;
    if (s >= p) {
      const std::int64_t n = b.state == Fill::kAll ? p * p : b.bits.count();
      count[static_cast<std::size_t>(grid.index(i0 / s, j0 / s))] += static_cast<std::int32_t>(n);
      continue;
    }
    for (std::int64_t y = 0; y < p; ++y)
      for (std::int64_t x = 0; x < p; ++x)
        if (b.get(x, y)) ++count[static_cast<std::size_t>(grid.index((i0 + x) / s, (j0 + y) / s))];
  }
  pf.comm().sum_in_place(count);
  return count;
}

// The size field's cells (size::FieldCells): the coast cells hold a pixel that is neither filled
// (sea, with a floodplain) nor, in a regional run, `open` water beyond the domain's edge
// (size/terms.hpp shore_cells), else one not filled (coast_cells); with a floodplain the cells'
// sea pixels.
size::FieldCells field_cells(const PatchForest& pf, const std::vector<PatchBits>& filled,
                             const std::vector<PatchBits>& open, const std::vector<PatchBits>& sea, bool regional,
                             const size::FieldGrid& grid) {
  size::FieldCells cells;
  cells.filled = filled_counts(pf, filled, grid);
  const bool floodplain = !sea.empty();
  if (floodplain) cells.sea = filled_counts(pf, sea, grid);
  if (!regional && !floodplain) {
    cells.coast = size::coast_cells(grid, cells.filled);
    return cells;
  }
  const std::int64_t p = pf.grid().size;
  std::vector<PatchBits> coast(pf.local_count());
  PatchBits all;
  all.state = Fill::kAll;
  for (std::size_t l = 0; l < coast.size(); ++l) {
    coast[l] = subtract(all, floodplain ? sea[l] : filled[l], p);
    if (regional) coast[l] = subtract(coast[l], open[l], p);
  }
  const std::vector<std::int32_t> count = filled_counts(pf, coast, grid);
  cells.coast.resize(count.size());
  for (std::size_t k = 0; k < count.size(); ++k) cells.coast[k] = count[k] > 0 ? 1 : 0;
  return cells;
}

// mask's find_inland_sea on the forest: the sea pixels not 4-connected through sea to a seed
// window's sea pixels (WetArea::inland_sea_*), counted and boxed over all ranks.
void inland_sea(const PatchForest& pf, const std::vector<PatchBits>& sea, const std::vector<mask::PixelIJ>& windows,
                int k, const Lattice& lattice, const PoleRotation& rot, mask::WetArea& area) {
  const PatchGrid& g = pf.grid();
  const std::int64_t p = g.size;
  std::vector<PatchBits> starts(pf.local_count());
  for (const mask::PixelIJ& w : windows)
    for (std::int64_t dj = 0; dj < k; ++dj)
      for (std::int64_t di = 0; di < k; ++di) {
        const mask::PixelIJ q{(w.i + di) % lattice.nx, w.j + dj};
        if (q.j >= lattice.ny) continue;
        const std::int64_t l = pf.local_index(g.key(q.i / p, q.j / p));
        if (l < 0) continue;
        PatchBits& s = starts[static_cast<std::size_t>(l)];
        if (s.state == Fill::kNone) {
          s.state = Fill::kMixed;
          s.bits = Bitmap(p, p);
        }
        s.bits.set(q.i % p, q.j % p);
      }
  for (std::size_t l = 0; l < starts.size(); ++l) starts[l] = intersect(starts[l], sea[l], p);
  const Unreached u = forest_unreached(pf, sea, starts);
  area.inland_sea_pixels = pf.comm().sum(count_pixels(u.pixels, p));
  if (area.inland_sea_pixels == 0) return;
  area.inland_sea_components = u.stats.count - u.stats.touching_probe;
  std::array<double, 4> box{-1e9, -1e9, -1e9, -1e9};  // -lon_min, lon_max, -lat_min, lat_max
  for (std::size_t l = 0; l < pf.local_count(); ++l) {
    const PatchBits& b = u.pixels[l];
    if (b.state == Fill::kNone) continue;
    const std::int64_t key = pf.key(l), i0 = g.gx(key) * p, j0 = g.gy(key) * p;
    for (std::int64_t y = 0; y < p; ++y)
      for (std::int64_t x = 0; x < p; ++x) {
        if (!b.get(x, y)) continue;
        const mask::LonLat c =
            mask::lattice_to_geographic(rot, mask::pixel_center_lattice_deg(lattice, {i0 + x, j0 + y}));
        box = {std::max(box[0], -c.lon_deg), std::max(box[1], c.lon_deg), std::max(box[2], -c.lat_deg),
               std::max(box[3], c.lat_deg)};
      }
  }
  const std::vector<std::array<double, 4>> all = pf.comm().allgatherv(std::vector<std::array<double, 4>>{box});
  for (const std::array<double, 4>& b : all)
    for (std::size_t q = 0; q < 4; ++q) box[q] = std::max(box[q], b[q]);
  area.inland_sea_lon_min = -box[0];
  area.inland_sea_lon_max = box[1];
  area.inland_sea_lat_min = -box[2];
  area.inland_sea_lat_max = box[3];
}

// This rank's memory with its leaves known: the elements are those the mesh stage's templates make
// from each leaf's midside code (a level-L pixel has none), so their sum is the mesh's count.
RankMemory rank_memory(const std::vector<quadtree::Leaf>& leaves, const std::vector<quadtree::LeafNeighbourhood>& nb,
                       int levels, bool triangles) {
  RankMemory m;
  m.peak_bytes = peak_rss_bytes();
  m.leaves = static_cast<std::int64_t>(leaves.size());
  for (std::size_t k = 0; k < leaves.size(); ++k)
    m.elements += triangles ? mesh::triangle_count(leaves[k].level < levels ? nb[k].midside : 0U) : 2;
  return m;
}

}  // namespace

ForestLeaves run_forest_leaves(const config::GlobalConfig& c, const Lattice& lat, const PoleRotation& rot,
                               const raster::Bathymetry& bathy, const mask::Domain& domain, const Logger& log,
                               Report* report) {
  const config::MaskOptions& mo = c.mask;
  const bool regional = domain.regional();
  ForestLeaves out;
  auto st = std::make_shared<ForestState>();
  const Comm& comm = st->comm;
  Json fj;  // the report's "forest" section
  collective(comm, [&] {
    if (!std::isfinite(mo.min_depth_m))
      throw ConfigError(fmt::format("mask.min_depth_m = {}: must be a finite number", mo.min_depth_m));
    // mask.sampling, the seeds, quadtree.levels, coast_band and mask.cursor against the patches:
    // config::load_global refuses what the forest cannot do (forest_check), with its position.
    if (mo.sampling != config::Sampling::kVertex || mo.seeds.empty() || lat.levels < 1)
      throw InternalError("forest: a configuration load_global refuses (area sampling, no seed or no level)");
  });
  st->brick = std::make_unique<LatticeBrick>(lat);
  st->patches = std::make_unique<PatchForest>(*st->brick, comm);
  const PatchForest& pf = *st->patches;
  const PatchGrid& g = pf.grid();
  const std::int64_t p = g.size;
  fj["ranks"] = comm.size();
  fj["trees"] = st->brick->trees();
  fj["patch_pixels"] = p;
  fj["patch_level"] = g.level;
  fj["patches"] = g.count();
  log.info("forest: {} ranks; {} x {} trees (level-0 squares{}), patches of {} x {} pixels (level {}): {}", comm.size(),
           st->brick->nx0(), st->brick->ny0(), st->brick->periodic() ? ", periodic in longitude" : "", p, p, g.level,
           g.count());

  // Pixel classes.
  {
    StageScope stage("classify", report, log);
    // Every rank runs the same checks on the same data: an error is everyone's.
    if (!regional) mask::check_mercator_caps(bathy, lat, rot, mo.min_depth_m);
    const StackBounds bounds(bathy, lat.pixel_deg() * static_cast<double>(p), c.input.blend_km);
    const mask::PixelWindow window =
        regional && rot.identity() ? mask::classify_window(lat, domain) : mask::PixelWindow{};
    // A floodplain: the same pixel rule at the datum as well (one sampling), for the sea inside Ω_L.
    const bool floodplain = mo.min_depth_m < 0.0;
    std::vector<PatchClasses> classes = classify_patches_at(
        pf, bathy, bounds, rot,
        floodplain ? std::vector<double>{mo.min_depth_m, 0.0} : std::vector<double>{mo.min_depth_m}, window);
    PatchClasses& pc = classes.front();
    st->wet = std::move(pc.wet);
    out.area.classes = pc.counts;
    fj["classify"] = Json{{"patches_decided_by_bounds", pc.decided}, {"patches_sampled", pc.sampled}};
    std::string datum;
    if (floodplain) {
      PatchClasses& at_datum = classes.back();
      st->datum_wet = std::move(at_datum.wet);
      out.area.datum_wet_pixels = at_datum.counts.wet;
      fj["classify"]["datum_patches_decided_by_bounds"] = at_datum.decided;
      fj["classify"]["datum_patches_sampled"] = at_datum.sampled;
      datum = fmt::format("; {} wet at the datum", out.area.datum_wet_pixels);
    }
    stage.done(
        fmt::format("{}×{} {}pixels of {:g}°: {} wet, {} coastal, {} dry (h = {:g} m, {} rule; {} patches "
                    "decided by bounds, {} sampled){}",
                    lat.nx, lat.ny, lat.mercator() ? "Mercator " : "", lat.pixel_deg(), pc.counts.wet,
                    pc.counts.coastal, pc.counts.dry, mo.min_depth_m, mo.sampling, pc.decided, pc.sampled, datum));
  }

  // The K-cursor fill (on wet ∩ domain for a regional run).
  std::vector<PatchBits> filled;
  std::vector<PatchBits> open;  // a regional run: the wet pixels beyond the domain (no coast, mask/coast.hpp)
  std::vector<mask::PixelIJ> seed_windows;
  std::vector<PatchBits> sea;  // a floodplain run: the filled pixels wet at the datum
  {
    StageScope stage("fill", report, log);
    std::vector<PatchBits> wet_in = st->wet;
    std::vector<std::array<double, 2>> seeds = mo.seeds;
    if (regional) {
      std::int64_t inside = 0;
      for (std::size_t l = 0; l < pf.local_count(); ++l) {
        const PatchBits d = domain_patch(domain, g, pf.key(l));
        inside += d.state == Fill::kAll ? p * p : d.state == Fill::kMixed ? d.bits.count() : 0;
        wet_in[l] = intersect(wet_in[l], d, p);
        open.push_back(subtract(st->water()[l], d, p));
      }
      inside = comm.sum(inside);
      if (inside == 0)
        throw ConfigError(fmt::format("domain: the {} holds no pixel of the lattice ({}° pixels)", domain.description,
                                      lat.pixel_deg()));
      out.area_domain_pixels = inside;
      seeds = regional_seeds(pf, domain, wet_in, lat, rot, bathy, mo.seeds, log);
    }
    ForestFill ff = forest_fill(pf, wet_in, rot, mo.cursor, seeds, mo.seed_radius_deg, log);
    wet_in = {};
    filled = std::move(ff.filled);
    out.area.fill = ff.stats;
    out.area.seeds = std::move(ff.seeds);
    out.area.filled_pixels = out.area.fill.filled_pixels;
    for (const mask::SeedInfo& s : out.area.seeds) seed_windows.push_back(s.window);
    const mask::FillStats& f = out.area.fill;
    stage.done(fmt::format(
        "K = {}: {} filled pixels ({:.1f}% of wet), {} wet pixels left out, {} wet components", mo.cursor,
        f.filled_pixels,
        f.wet_pixels > 0 ? 100.0 * static_cast<double>(f.filled_pixels) / static_cast<double>(f.wet_pixels) : 0.0,
        f.wet_left_out, f.wet_components));
  }

  // Pinch vertices (and their removal: the choices in the dense order on rank 0's gathered set,
  // the refill on every rank).
  {
    StageScope stage("pinches", report, log);
    mask::PinchReport& pr = out.area.pinches;
    pr.removal_requested = mo.remove_pinches;
    std::int64_t total = 0;
    std::vector<mask::Pinch> pinches = forest_pinches(pf, filled, total);
    if (mo.remove_pinches) {
      mask::PinchRemovalStats& r = pr.removal;
      const std::int64_t before = comm.sum(count_pixels(filled, p));
      r.pinches_found = total;
      while (total > 0) {
        ++r.rounds;
        std::vector<mask::PixelIJ> cleared;
        std::vector<std::int64_t> chosen{0};
        SparseSet set = SparseSet::gather(pf, filled);
        collective(comm, [&] {  // rank 0 alone: its error is everyone's
          if (comm.root()) {
            chosen[0] = mask::resolve_pinches(set, mo.cursor, seed_windows, pinches);
            cleared = set.cleared();
          }
        });
        comm.bcast(chosen, 0);
        r.pixels_chosen += chosen[0];
        if (chosen[0] == 0) break;
        comm.bcast(cleared, 0);
        clear_pixels(pf, filled, cleared);
        filled = forest_refill(pf, filled, mo.cursor, seed_windows);
        pinches = forest_pinches(pf, filled, total);
      }
      r.unresolved = total;
      out.area.filled_pixels = comm.sum(count_pixels(filled, p));
      r.pixels_removed = before - out.area.filled_pixels;
    }
    if (!st->datum_wet.empty()) {  // the sea inside Ω_L (after pinch removal); the rest is floodplain
      sea.resize(pf.local_count());
      for (std::size_t l = 0; l < sea.size(); ++l) sea[l] = intersect(filled[l], st->datum_wet[l], p);
      out.area.floodplain_pixels = out.area.filled_pixels - comm.sum(count_pixels(sea, p));
      inland_sea(pf, sea, seed_windows, mo.cursor, lat, rot, out.area);
      mask::warn_inland_sea(out.area, log);
    }
    pr.total = total;
    pr.pinches = std::move(pinches);
    mask::locate_pinches(pr.pinches, lat, rot);
    if (mo.remove_pinches) {
      const mask::PinchRemovalStats& r = pr.removal;
      stage.done(fmt::format("{} pinch vertices found, {} pixels removed in {} rounds, {} left", r.pinches_found,
                             r.pixels_removed, r.rounds, pr.total));
    } else {
      stage.done(fmt::format("{} pinch vertices (mask.remove_pinches = false)", pr.total));
    }
  }

  // The passage table (a regional run: the passages inside the domain), judged on rank 0's
  // gathered set, marked when carved.
  const std::vector<mask::Passage> table = mask::passage_table(lat, rot, &domain);
  if (mo.passages && !table.empty()) {
    StageScope stage("passages", report, log);
    const SparseSet set = SparseSet::gather(pf, filled);
    collective(comm, [&] {
      if (comm.root()) {
        out.area.passages = mask::judge_passages(table, set, lat, rot);
        mask::mark_carved(out.area.passages, mo);
      }
    });
    int n_open = 0, closed = 0;
    for (const mask::PassageResult& r : out.area.passages) {
      n_open += r.status == mask::PassageStatus::kOpen ? 1 : 0;
      closed += r.status == mask::PassageStatus::kClosed ? 1 : 0;
    }
    stage.done(fmt::format("{} open, {} closed, {} not resolvable", n_open, closed,
                           static_cast<int>(out.area.passages.size()) - n_open - closed));
  }
  if (report != nullptr) {
    (*report)["mask"] = mask::wet_area_json(out.area, mo);
    (*report)["mask"]["lattice"] = Json{{"nx", lat.nx}, {"ny", lat.ny}};
  }

  // The size field (its grid replicated on every rank, from the counts of all ranks).
  out.size_field = size::build_size_field(
      [&](const size::FieldGrid& grid) { return field_cells(pf, filled, open, sea, regional, grid); }, lat, c, rot,
      &bathy, log, report);

  // The quadtree: the pyramid's refinements, the p4est forest, its balance.
  {
    StageScope stage("quadtree", report, log);
    const config::QuadtreeOptions& qo = c.quadtree;
    const quadtree::BalanceMode mode = qo.balance;
    const std::int64_t filled_pixels = comm.sum(count_pixels(filled, p));
    Timer t_masks;
    std::vector<std::int64_t> bare, banded, refined;
    bare = ForestPyramid(pf, filled, 0).leaves_per_level();
    const int band = qo.coast_band != 0 && qo.coast_size_km == 0.0 ? qo.coast_band : 0;
    auto pyr =
        std::make_unique<ForestPyramid>(pf, filled, band, regional ? &open : nullptr, sea.empty() ? nullptr : &sea);
    banded = pyr->leaves_per_level();
    const double masks_s = t_masks.wall_s();
    Timer t_rules;
    pyr->apply_rules(qo, rot, &bathy);
    pyr->apply_size_field(out.size_field);
    const quadtree::GradeStats grade = pyr->grade(out.size_field);
    refined = pyr->leaves_per_level();
    const double rules_s = t_rules.wall_s();
    Timer t_balance;
    auto mf = std::make_unique<MeshForest>(*st->brick, comm, *pyr);
    const std::int64_t active = comm.sum(pyr->active_patches()), fine = comm.sum(pyr->fine_bytes());
    fj["pyramid"] = Json{{"active_patches", active}, {"fine_bytes", fine}};
    pyr.reset();
    // p4est's balance is the dense rule when every filled leaf touching land is a level-L pixel:
    // not in a regional run, whose open boundary is no coast (its leaves follow the other rules).
    const MeshForest::BalanceResult br = mf->balance(mode, band >= 1 && !regional);
    const std::vector<std::int64_t> balanced = mf->leaves_per_level();
    const double balance_s = t_balance.wall_s();
    Timer t_check;
    // The checkers: the counts are global (the same on every rank), so is the error.
    const quadtree::LeafSteps steps{bare, banded, refined, balanced};
    quadtree::check_leaf_steps(steps, lat.levels, filled_pixels);
    const std::int64_t violations = mf->count_violations(mode);
    if (violations != 0)
      throw InternalError(
          fmt::format("quadtree: {} {}-balance violations left after smoothing", violations, name_of(mode)));
    const double check_s = t_check.wall_s();
    // The leaves and their neighbourhoods, gathered on rank 0 in order.
    Timer t_gather;
    const std::vector<quadtree::Leaf> local = mf->local_leaves();
    const std::vector<quadtree::LeafNeighbourhood> local_nb = mf->local_neighbourhoods();
    fj["mesh_forest"] = Json{{"quadrants", mf->quadrants()},
                             {"p4est_bytes_rank0", mf->memory_bytes()},
                             {"balance", br.used_p4est ? "p4est_balance" : "dense rule in rounds"},
                             {"balance_rounds", br.rounds},
                             {"balance_splits", br.forced_splits}};
    mf.reset();
    out.rank_memory = comm.allgatherv(
        std::vector<RankMemory>{rank_memory(local, local_nb, lat.levels, config::has_triangles(c.mesh.elements))});
    out.leaves = comm.gatherv(local, 0);
    out.neighbourhoods = comm.gatherv(local_nb, 0);
    const double gather_s = t_gather.wall_s();
    std::int64_t total_leaves = 0;
    for (const std::int64_t n : balanced) total_leaves += n;
    if (report != nullptr) {
      Json& q = (*report)["quadtree"];
      q["engine"] = "forest";
      quadtree::leaf_steps_json(q, lat, qo, filled_pixels, steps, violations);
      q["leaves"] = total_leaves;
      if (out.size_field.has_grid() && out.size_field.gradation() > 0.0)
        q["grading"] = Json{{"gradation", out.size_field.gradation()},
                            {"grading_splits", grade.splits},
                            {"cfl_refused_splits", grade.cfl_refused}};
      q["timings_s"] = Json{{"masks", round3(masks_s)},
                            {"rules", round3(rules_s)},
                            {"balance", round3(balance_s)},
                            {"check", round3(check_s)},
                            {"gather", round3(gather_s)}};
      (*report)["forest"] = fj;
    }
    stage.done(fmt::format("{} leaves (levels 0..{}: {}), {}-balanced ({} on {} rank(s))", total_leaves, lat.levels,
                           fmt::join(balanced, "/"), name_of(mode), br.used_p4est ? "p4est_balance" : "the dense rule",
                           comm.size()));
  }
  // The wet and filled pixels on rank 0 for the dropped seas (mask/dropped_seas.hpp), on a lattice
  // small enough to hold them there (kDroppedSeasMaxPixels); beyond it the dropped components are
  // counted over the ranks. Last, so that rank 0 holds them only until the app has used them.
  std::int64_t dense_max = kDroppedSeasMaxPixels;
  if (const char* e = std::getenv("AQ_FOREST_DROPPED_MAX_PIXELS")) dense_max = std::atoll(e);  // a test knob
  if (lat.pixel_count() <= dense_max) {
    out.area.wet = gather_dense(pf, st->wet);
    out.area.filled = gather_dense(pf, filled);
  } else {
    std::vector<PatchBits> dropped(pf.local_count());
    for (std::size_t l = 0; l < dropped.size(); ++l) {
      dropped[l] = subtract(st->wet[l], filled[l], p);
      if (regional) dropped[l] = intersect(dropped[l], domain_patch(domain, g, pf.key(l)), p);
    }
    out.dropped_components = forest_components(pf, dropped, std::vector<PatchBits>(pf.local_count())).count;
    out.dropped_pixels = comm.sum(count_pixels(dropped, p));
  }
  out.state = st;
  return out;
}

std::vector<char> wet_outside_domain(const ForestState& state, const mask::Domain& domain,
                                     const std::vector<mask::PixelIJ>& queries) {
  const Comm& comm = state.comm;
  std::vector<mask::PixelIJ> q = queries;
  comm.bcast(q, 0);
  const PatchForest& pf = *state.patches;
  const PatchGrid& g = pf.grid();
  const std::int64_t p = g.size;
  std::vector<std::uint8_t> ans(q.size(), 0);
  for (std::size_t k = 0; k < q.size(); ++k) {
    const std::int64_t l = pf.local_index(g.key(q[k].i / p, q[k].j / p));
    if (l < 0) continue;
    ans[k] =
        (!domain.contains(q[k].i, q[k].j) && state.water()[static_cast<std::size_t>(l)].get(q[k].i % p, q[k].j % p))
            ? 1
            : 0;
  }
  comm.or_in_place(ans);
  if (!comm.root()) return {};
  return std::vector<char>(ans.begin(), ans.end());
}

}  // namespace aq::forest
