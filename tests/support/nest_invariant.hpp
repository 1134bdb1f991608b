// SPDX-License-Identifier: GPL-3.0-or-later
// Test helper: the invariant ROMS two-way refinement needs, checked on the three files alone
// (parent grid, refinement grid, contact points), independently of aquatoria's own code:
//   1. over each parent ρ cell (I, J) inside the refinement (I_left..I_right−1 × J_bottom..J_top−1
//      of the contact file), the parent's h is the refinement's h averaged over the r × r ρ points
//      of that cell, area-weighted with 1/(pm·pn) over its wet points (all when none is wet);
//   2. a wet parent cell there has a wet refinement point (ROMS's average needs one), and its mask
//      is the refinement's at the cell's centre (the rule aquatoria documents);
//   3. at every contact point whose receiver point lies in its receiver grid file (region 1:
//      the refinement's outer ring and boundary u/v; region 2: the parent's points inside), the
//      contact file's h (ρ) and mask (ρ, u, v) are the grid file's values there.
#pragma once

#include <netcdf.h>

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

namespace aq::test {

struct NestInvariant {
  bool read_ok = false;
  std::string read_error;
  int footprint_cells = 0;
  int h_mismatches = 0;  ///< parent cells whose h is not the block average (1e-9 relative)
  double h_max_mismatch_m = 0.0;
  int mask_rule_violations = 0;  ///< parent cells breaking rule 2
  int contact_points_in_grids = 0;
  int contact_h_mismatches = 0, contact_mask_mismatches = 0;
  std::vector<std::string> examples;  ///< the first few problems, for messages

  [[nodiscard]] bool holds() const {
    return read_ok && footprint_cells > 0 && h_mismatches == 0 && mask_rule_violations == 0 &&
           contact_h_mismatches == 0 && contact_mask_mismatches == 0;
  }
  [[nodiscard]] std::string summary() const {
    std::string s = fmt::format(
        "{} footprint cells: {} h mismatches (max {:.4g} m), {} mask-rule violations; {} contact points in the grid "
        "files: {} h and {} mask mismatches",
        footprint_cells, h_mismatches, h_max_mismatch_m, mask_rule_violations, contact_points_in_grids,
        contact_h_mismatches, contact_mask_mismatches);
    if (!read_ok) s += "; read error: " + read_error;
    for (const auto& e : examples) s += "\n  " + e;
    return s;
  }
};

namespace nest_detail {

struct Var2 {
  std::size_t nj = 0, ni = 0;
  std::vector<double> v;
  [[nodiscard]] double at(long i, long j) const {
    return v[static_cast<std::size_t>(j) * ni + static_cast<std::size_t>(i)];
  }
  [[nodiscard]] bool has(long i, long j) const {
    return i >= 0 && j >= 0 && static_cast<std::size_t>(i) < ni && static_cast<std::size_t>(j) < nj;
  }
};

inline bool read_var(int nc, const char* name, Var2& out, std::string& err) {
  int var = -1, ndims = 0, dims[NC_MAX_VAR_DIMS];
  if (nc_inq_varid(nc, name, &var) != NC_NOERR || nc_inq_varndims(nc, var, &ndims) != NC_NOERR ||
      nc_inq_vardimid(nc, var, dims) != NC_NOERR) {
    err = fmt::format("no variable {}", name);
    return false;
  }
  std::size_t n = 1;
  std::vector<std::size_t> len(static_cast<std::size_t>(ndims));
  for (int k = 0; k < ndims; ++k) {
    nc_inq_dimlen(nc, dims[k], &len[static_cast<std::size_t>(k)]);
    n *= len[static_cast<std::size_t>(k)];
  }
  out.ni = ndims >= 1 ? len.back() : 1;
  out.nj = ndims >= 2 ? len[len.size() - 2] : 1;
  out.v.resize(n);
  if (nc_get_var_double(nc, var, out.v.data()) != NC_NOERR) {
    err = fmt::format("cannot read {}", name);
    return false;
  }
  return true;
}

inline bool read_vars(const std::filesystem::path& path, const std::vector<std::pair<const char*, Var2*>>& vars,
                      std::string& err) {
  int nc = -1;
  if (nc_open(path.c_str(), NC_NOWRITE, &nc) != NC_NOERR) {
    err = path.string() + ": cannot open";
    return false;
  }
  bool ok = true;
  for (const auto& [name, v] : vars) ok = ok && read_var(nc, name, *v, err);
  nc_close(nc);
  if (!ok) err = path.string() + ": " + err;
  return ok;
}

}  // namespace nest_detail

inline NestInvariant check_nest_invariant(const std::filesystem::path& parent, const std::filesystem::path& child,
                                          const std::filesystem::path& contact) {
  using nest_detail::Var2;
  NestInvariant r;
  Var2 ph, pmr, pmu, pmv, ch, cmr, cmu, cmv, cpm, cpn;
  Var2 rf, il, ir, jb, jt, nstr_r, nend_r, nstr_u, nend_u, nstr_v, nend_v, recv, irg, jrg, kh, kmask;
  if (!nest_detail::read_vars(parent, {{"h", &ph}, {"mask_rho", &pmr}, {"mask_u", &pmu}, {"mask_v", &pmv}},
                              r.read_error) ||
      !nest_detail::read_vars(
          child, {{"h", &ch}, {"mask_rho", &cmr}, {"mask_u", &cmu}, {"mask_v", &cmv}, {"pm", &cpm}, {"pn", &cpn}},
          r.read_error) ||
      !nest_detail::read_vars(contact,
                              {{"refine_factor", &rf},
                               {"I_left", &il},
                               {"I_right", &ir},
                               {"J_bottom", &jb},
                               {"J_top", &jt},
                               {"NstrR", &nstr_r},
                               {"NendR", &nend_r},
                               {"NstrU", &nstr_u},
                               {"NendU", &nend_u},
                               {"NstrV", &nstr_v},
                               {"NendV", &nend_v},
                               {"receiver_grid", &recv},
                               {"Irg", &irg},
                               {"Jrg", &jrg},
                               {"h", &kh},
                               {"mask", &kmask}},
                              r.read_error))
    return r;
  r.read_ok = true;
  const auto note = [&](const std::string& s) {
    if (r.examples.size() < 12) r.examples.push_back(s);
  };
  // Grid 2 is the refinement.
  const long f = std::lround(rf.v[1]), Io = std::lround(il.v[1]), Ie = std::lround(ir.v[1]), Jo = std::lround(jb.v[1]),
             Je = std::lround(jt.v[1]);

  // 1 and 2: per parent cell.
  for (long J = Jo; J < Je; ++J)
    for (long I = Io; I < Ie; ++I) {
      ++r.footprint_cells;
      double sw = 0, swh = 0, sa = 0, sah = 0;
      int wet = 0;
      for (long j = (J - Jo) * f + 1; j <= (J - Jo + 1) * f; ++j)
        for (long i = (I - Io) * f + 1; i <= (I - Io + 1) * f; ++i) {
          const double a = 1.0 / (cpm.at(i, j) * cpn.at(i, j)), h = ch.at(i, j);
          sa += a;
          sah += a * h;
          if (cmr.at(i, j) < 0.5) continue;
          ++wet;
          sw += a;
          swh += a * h;
        }
      const double avg = sw > 0 ? swh / sw : sah / sa, hp = ph.at(I, J), d = std::abs(hp - avg);
      r.h_max_mismatch_m = std::max(r.h_max_mismatch_m, d);
      if (d > 1e-9 * std::max(1.0, avg)) {
        ++r.h_mismatches;
        note(fmt::format("parent cell ({}, {}): h {} m, refinement average {} m", I, J, hp, avg));
      }
      const long ci = (I - Io) * f + (f + 1) / 2, cj = (J - Jo) * f + (f + 1) / 2;
      const bool pw = pmr.at(I, J) > 0.5;
      if ((pw && wet == 0) || pw != (cmr.at(ci, cj) > 0.5)) {
        ++r.mask_rule_violations;
        note(fmt::format("parent cell ({}, {}): mask {}, refinement centre ({}, {}) mask {}, {} wet points", I, J,
                         pmr.at(I, J), ci, cj, cmr.at(ci, cj), wet));
      }
    }

  // 3: contact points against the receiver grid's file.
  for (int region = 0; region < 2; ++region) {
    const bool to_child = std::lround(recv.v[static_cast<std::size_t>(region)]) == 2;
    const Var2& gh = to_child ? ch : ph;
    const Var2* gm[3] = {to_child ? &cmr : &pmr, to_child ? &cmu : &pmu, to_child ? &cmv : &pmv};
    const Var2* rng[3][2] = {{&nstr_r, &nend_r}, {&nstr_u, &nend_u}, {&nstr_v, &nend_v}};
    for (int t = 0; t < 3; ++t) {
      const long s = std::lround(rng[t][0]->v[static_cast<std::size_t>(region)]),
                 e = std::lround(rng[t][1]->v[static_cast<std::size_t>(region)]);
      for (long n = s; n <= e; ++n) {
        const auto k = static_cast<std::size_t>(n - 1);
        const long I = std::lround(irg.v[k]), J = std::lround(jrg.v[k]);
        const long fi = t == 1 ? I - 1 : I, fj = t == 2 ? J - 1 : J;  // u: I = file + 1; v: J = file + 1
        if (!gm[t]->has(fi, fj)) continue;
        ++r.contact_points_in_grids;
        const char* type = t == 0 ? "rho" : t == 1 ? "u" : "v";
        if (kmask.v[k] != gm[t]->at(fi, fj)) {
          ++r.contact_mask_mismatches;
          note(fmt::format("region {} {} point ({}, {}): contact mask {}, grid {}", region + 1, type, I, J, kmask.v[k],
                           gm[t]->at(fi, fj)));
        }
        if (t == 0 && std::abs(kh.v[k] - gh.at(fi, fj)) > 1e-9 * std::max(1.0, gh.at(fi, fj))) {
          ++r.contact_h_mismatches;
          note(fmt::format("region {} rho point ({}, {}): contact h {} m, grid {} m", region + 1, I, J, kh.v[k],
                           gh.at(fi, fj)));
        }
      }
    }
  }
  return r;
}

}  // namespace aq::test
