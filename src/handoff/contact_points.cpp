// SPDX-License-Identifier: GPL-3.0-or-later
// ROMS contact points of a refinement grid and its parent (see contact_points.hpp).
#include "handoff/contact_points.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/error.hpp"

namespace aq::handoff {

namespace {

enum Type { kRho = 0, kU = 1, kV = 2 };

int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// Points of one type of a ROMS grid by ROMS indices (u: I = file + 1 in ξ; v: J = file + 1 in η).
struct Family {
  int ni = 0, nj = 0, oi = 0, oj = 0;  // file index = ROMS index − o
  const std::vector<double>* lon = nullptr;
  const std::vector<double>* lat = nullptr;
  const std::vector<double>* mask = nullptr;
  [[nodiscard]] std::size_t at(int I, int J) const {
    const int i = I - oi, j = J - oj;
    if (i < 0 || j < 0 || i >= ni || j >= nj)
      throw InternalError(fmt::format("contact points: index ({}, {}) outside a {} x {} family", I, J, ni, nj));
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(ni) + static_cast<std::size_t>(i);
  }
};

Family parent_family(const io::RomsGridFields& p, Type t) {
  switch (t) {
    case kRho:
      return {p.L + 1, p.M + 1, 0, 0, &p.lon_rho, &p.lat_rho, &p.mask_rho};
    case kU:
      return {p.L, p.M + 1, 1, 0, &p.lon_u, &p.lat_u, &p.mask_u};
    default:
      return {p.L + 1, p.M, 0, 1, &p.lon_v, &p.lat_v, &p.mask_v};
  }
}

// One direction of a point: fractional coarse coordinate num/(2r), donor index, offset p in [0, 1).
struct Axis {
  int num = 0;      // ξ = num / (2r)
  int donor = 0;    // Idg
  double p = 0.0;   // ξ − ξ(Idg)
  double xi = 0.0;  // ξ
  double xi_dg = 0.0;
};

// `centred`: ρ-like along this direction (fine index i at Io + (i − ½)/r, donor ρ at Idg + ½);
// else u-like (fine I at Io + (I − 1)/r, donor at Idg).
Axis axis(int index, int lo, int r, bool centred) {
  Axis a;
  if (centred) {
    a.num = 2 * r * lo + 2 * index - 1;
    a.donor = lo + floor_div(index - (r + 1) / 2, r);
    a.p = static_cast<double>(a.num - 2 * r * a.donor - r) / static_cast<double>(2 * r);
    a.xi_dg = a.donor + 0.5;
  } else {
    a.num = 2 * r * lo + 2 * (index - 1);
    a.donor = lo + floor_div(index - 1, r);
    a.p = static_cast<double>(a.num - 2 * r * a.donor) / static_cast<double>(2 * r);
    a.xi_dg = a.donor;
  }
  a.xi = static_cast<double>(a.num) / static_cast<double>(2 * r);
  if (!(a.p >= 0.0 && a.p < 1.0))
    throw InternalError(fmt::format("contact points: offset {} outside [0, 1) at index {}", a.p, index));
  return a;
}

// Bilinear weights of the donor cell's corners (Idg,Jdg), (Idg+1,Jdg), (Idg+1,Jdg+1), (Idg,Jdg+1).
std::array<double, 4> bilinear_weights(const Axis& ax, const Axis& ay) {
  return {(1 - ax.p) * (1 - ay.p), ax.p * (1 - ay.p), ax.p * ay.p, (1 - ax.p) * ay.p};
}

// Σ w_k value(corner k) over those corners; value(I, J) takes the donor's indices.
template <typename Value>
double bilinear(const std::array<double, 4>& w, const Axis& ax, const Axis& ay, Value value) {
  const int I = ax.donor, J = ay.donor;
  return w[0] * value(I, J) + w[1] * value(I + 1, J) + w[2] * value(I + 1, J + 1) + w[3] * value(I, J + 1);
}

std::array<double, 3> quadratic(double p, double alpha) {
  return {0.5 * p * (p - 1.0) + alpha, 1.0 - p * p - 2.0 * alpha, 0.5 * p * (p + 1.0) + alpha};
}

}  // namespace

std::string refinement_box_problem(const curvilinear::RefineBox& b, int PL, int PM) {
  if (b.i_left >= 2 && b.j_bottom >= 2 && b.i_right <= PL - 1 && b.j_top <= PM - 1 && b.i_left < b.i_right &&
      b.j_bottom < b.j_top)
    return {};
  return fmt::format(
      "the refinement box I {}..{}, J {}..{} must lie within the parent's psi points I 2..{}, J 2..{} (the parent "
      "has psi I 1..{}, J 1..{}; ROMS takes the coarse data for 3 fine rows outside the box from whole coarse "
      "cells)",
      b.i_left, b.i_right, b.j_bottom, b.j_top, PL - 1, PM - 1, PL, PM);
}

std::vector<double> parent_rho_on_fine(const io::RomsGridFields& parent, const std::vector<double>& field,
                                       const curvilinear::RefineBox& box) {
  return parent_rho_on_fine(field, parent.L, parent.M, box);
}

std::vector<double> parent_rho_on_fine(const std::vector<double>& field, int parent_L, int parent_M,
                                       const curvilinear::RefineBox& box) {
  if (const std::string bad = refinement_box_problem(box, parent_L, parent_M); !bad.empty()) throw ConfigError(bad);
  const std::size_t pni = static_cast<std::size_t>(parent_L) + 1;
  if (field.size() != pni * (static_cast<std::size_t>(parent_M) + 1))
    throw InternalError(fmt::format("parent_rho_on_fine: {} values for {} x {} parent rho points", field.size(),
                                    parent_L + 1, parent_M + 1));
  const int L = box.L(), M = box.M();
  std::vector<double> out(static_cast<std::size_t>(L + 1) * static_cast<std::size_t>(M + 1));
  for (int j = 0; j <= M; ++j) {
    const Axis ay = axis(j, box.j_bottom, box.factor, true);
    for (int i = 0; i <= L; ++i) {
      const Axis ax = axis(i, box.i_left, box.factor, true);
      out[static_cast<std::size_t>(j) * static_cast<std::size_t>(L + 1) + static_cast<std::size_t>(i)] = bilinear(
          bilinear_weights(ax, ay), ax, ay,
          [&](int a, int b) { return field[static_cast<std::size_t>(b) * pni + static_cast<std::size_t>(a)]; });
    }
  }
  return out;
}

io::ContactFile refinement_contact(const io::RomsGridFields& parent, const curvilinear::RefineBox& box,
                                   const curvilinear::CGrid& fine, int pad, ContactSummary* summary,
                                   const ReceiverValues* receiver) {
  if (const std::string bad = refinement_box_problem(box, parent.L, parent.M); !bad.empty()) throw ConfigError(bad);
  const int r = box.factor, L = box.L(), M = box.M(), Lm = L - 1, Mm = M - 1;
  const int Io = box.i_left, Ie = box.i_right, Jo = box.j_bottom, Je = box.j_top;
  if (pad < 4 || fine.L != L + 2 * pad || fine.M != M + 2 * pad)
    throw InternalError(fmt::format("refinement_contact: the fine C-grid is {} x {} with pad {}, expected {} x {}",
                                    fine.L, fine.M, pad, L + 2 * pad, M + 2 * pad));
  if (receiver != nullptr) {
    const auto n = [](int a, int b) { return static_cast<std::size_t>(a) * static_cast<std::size_t>(b); };
    if (receiver->h.size() != n(L + 1, M + 1) || receiver->mask_rho.size() != n(L + 1, M + 1) ||
        receiver->mask_u.size() != n(L, M + 1) || receiver->mask_v.size() != n(L + 1, M))
      throw InternalError(
          fmt::format("refinement_contact: the receiver's values do not fit {} x {} rho points", L + 1, M + 1));
  }
  // The fine grid file's value at a point of it (ROMS indices), if given and inside the grid.
  const auto receiver_at = [&](Type t, int i, int j) -> std::optional<std::size_t> {
    if (receiver == nullptr) return std::nullopt;
    const int fi = t == kU ? i - 1 : i, fj = t == kV ? j - 1 : j;  // file indices
    const int ni = t == kU ? L : L + 1, nj = t == kV ? M : M + 1;
    if (fi < 0 || fj < 0 || fi >= ni || fj >= nj) return std::nullopt;
    return static_cast<std::size_t>(fj) * static_cast<std::size_t>(ni) + static_cast<std::size_t>(fi);
  };
  const double alpha = (1.0 / (r * r) - 1.0) / 24.0;
  const Family coarse[3] = {parent_family(parent, kRho), parent_family(parent, kU), parent_family(parent, kV)};
  // Fine points by ROMS index in the padded C-grid.
  const auto fine_point = [&](Type t, int I, int J) -> std::size_t {
    switch (t) {
      case kRho:
        return fine.rho.at(I + pad, J + pad);
      case kU:
        return fine.u.at(I - 1 + pad, J + pad);
      default:
        return fine.v.at(I + pad, J - 1 + pad);
    }
  };
  const auto fine_lonlat = [&](Type t, std::size_t k) {
    const curvilinear::StaggeredPoints& s = t == kRho ? fine.rho : t == kU ? fine.u : fine.v;
    return std::pair{s.lon_deg[k], s.lat_deg[k]};
  };
  // The coarse ρ mask at the coarse ρ cell holding fine ρ (i, j).
  const auto fine_rho_mask = [&](int i, int j) {
    const int ic = Io + floor_div(2 * i - 1, 2 * r), jc = Jo + floor_div(2 * j - 1, 2 * r);
    return parent.mask_rho[coarse[kRho].at(ic, jc)];
  };

  io::ContactFile f;
  f.Lm = {parent.L - 1, Lm};
  f.Mm = {parent.M - 1, Mm};
  f.refine_factor = {0, r};
  f.parent_box = {Io, Ie, Jo, Je};
  ContactSummary sum;
  std::vector<double> ratios;

  const auto push_common = [&](int region, int boundary, int Idg, int Jdg, int Irg, int Jrg, double xi_dg,
                               double eta_dg, double xi_rg, double eta_rg, std::pair<double, double> dg,
                               std::pair<double, double> rg, double mask) {
    f.contact_region.push_back(region);
    f.on_boundary.push_back(boundary);
    f.Idg.push_back(Idg);
    f.Jdg.push_back(Jdg);
    f.Irg.push_back(Irg);
    f.Jrg.push_back(Jrg);
    f.xi_dg.push_back(xi_dg);
    f.eta_dg.push_back(eta_dg);
    f.xi_rg.push_back(xi_rg);
    f.eta_rg.push_back(eta_rg);
    f.Xdg.push_back(dg.first);
    f.Ydg.push_back(dg.second);
    f.Xrg.push_back(rg.first);
    f.Yrg.push_back(rg.second);
    f.mask.push_back(mask);
    if (mask > 0.5) ++sum.wet_points;
  };
  const auto push_fill = [&] {
    for (auto* v : {&f.h, &f.f, &f.pm, &f.pn, &f.dndx, &f.dmde, &f.angle}) v->push_back(io::kContactFill);
  };
  const auto close_type = [&](io::ContactRegion& reg, Type t, int start) {
    const int end = static_cast<int>(f.size());
    if (t == kRho) {
      reg.NstrR = start;
      reg.NendR = end;
    } else if (t == kU) {
      reg.NstrU = start;
      reg.NendU = end;
    } else {
      reg.NstrV = start;
      reg.NendV = end;
    }
    return static_cast<std::size_t>(end - start + 1);
  };

  // Region 1: coarse → fine, the band around the fine interior.
  io::ContactRegion& r1 = f.regions[0];
  r1.donor_grid = 1;
  r1.receiver_grid = 2;
  for (const Type t : {kRho, kU, kV}) {
    const int start = static_cast<int>(f.size()) + 1;
    const int i0 = t == kU ? -2 : -3, j0 = t == kV ? -2 : -3;
    const int ia = t == kU ? 2 : 1, ja = t == kV ? 2 : 1;  // the excluded interior ia..Lm × ja..Mm
    const Family& C = coarse[t];
    for (int j = j0; j <= M + 2; ++j)
      for (int i = i0; i <= L + 2; ++i) {
        if (i >= ia && i <= Lm && j >= ja && j <= Mm) continue;
        const Axis ax = axis(i, Io, r, t != kU), ay = axis(j, Jo, r, t != kV);
        const std::array<double, 4> w = bilinear_weights(ax, ay);
        int boundary = 0;
        if (t == kU && j >= 1 && j <= Mm) boundary = i == 1 ? 1 : i == L ? 3 : 0;
        if (t == kV && i >= 1 && i <= Lm) boundary = j == 1 ? 2 : j == M ? 4 : 0;
        const std::optional<std::size_t> own = receiver_at(t, i, j);
        double mask = t == kRho ? fine_rho_mask(i, j)
                      : t == kU ? fine_rho_mask(i - 1, j) * fine_rho_mask(i, j)
                                : fine_rho_mask(i, j - 1) * fine_rho_mask(i, j);
        if (own) mask = (t == kRho ? receiver->mask_rho : t == kU ? receiver->mask_u : receiver->mask_v)[*own];
        const std::size_t dk = C.at(ax.donor, ay.donor), fk = fine_point(t, i, j);
        push_common(1, boundary, ax.donor, ay.donor, i, j, ax.xi_dg, ay.xi_dg, ax.xi, ay.xi,
                    {(*C.lon)[dk], (*C.lat)[dk]}, fine_lonlat(t, fk), mask);
        f.Lweight.push_back(w);
        const auto qx = quadratic(ax.p, alpha), qy = quadratic(ay.p, alpha);
        std::array<double, 9> q{};
        for (std::size_t b = 0; b < 3; ++b)
          for (std::size_t a = 0; a < 3; ++a) q[3 * b + a] = qx[a] * qy[b];
        f.Qweight.push_back(q);
        if (t != kRho) {
          push_fill();
          continue;
        }
        const auto rho_field = [&](const std::vector<double>& v) {
          return bilinear(w, ax, ay, [&](int a, int b) { return v[parent.rho_at(a, b)]; });
        };
        const double h = rho_field(parent.h), cor = rho_field(parent.f), pm = rho_field(parent.pm);
        const double s = bilinear(w, ax, ay, [&](int a, int b) { return std::sin(parent.angle[parent.rho_at(a, b)]); });
        const double co =
            bilinear(w, ax, ay, [&](int a, int b) { return std::cos(parent.angle[parent.rho_at(a, b)]); });
        f.h.push_back(own ? receiver->h[*own] : h);
        f.f.push_back(cor);
        f.angle.push_back(std::atan2(s, co));
        f.pm.push_back(fine.pm[fk]);
        f.pn.push_back(fine.pn[fk]);
        f.dndx.push_back(fine.dndx[fk]);
        f.dmde.push_back(fine.dmde[fk]);
        if (pm > 0.0) ratios.push_back(fine.pm[fk] / pm);
      }
    sum.coarse_to_fine[t] = close_type(r1, t, start);
  }

  // Region 2: fine → coarse, the coarse points inside the fine grid.
  io::ContactRegion& r2 = f.regions[1];
  r2.donor_grid = 2;
  r2.receiver_grid = 1;
  const int centre = (r + 1) / 2;
  for (const Type t : {kRho, kU, kV}) {
    const int start = static_cast<int>(f.size()) + 1;
    const Family& C = coarse[t];
    const int i0 = t == kU ? Io + 1 : Io, j0 = t == kV ? Jo + 1 : Jo;
    for (int j = j0; j <= Je - 1; ++j)
      for (int i = i0; i <= Ie - 1; ++i) {
        const int Idg = t == kU ? 1 + (i - Io) * r : centre + (i - Io) * r;
        const int Jdg = t == kV ? 1 + (j - Jo) * r : centre + (j - Jo) * r;
        const std::size_t ck = C.at(i, j), fk = fine_point(t, Idg, Jdg);
        const double xi_rg = t == kU ? i : i + 0.5, eta_rg = t == kV ? j : j + 0.5;
        const double xi_dg = t == kU ? Idg : Idg + 0.5, eta_dg = t == kV ? Jdg : Jdg + 0.5;
        push_common(2, 0, Idg, Jdg, i, j, xi_dg, eta_dg, xi_rg, eta_rg, fine_lonlat(t, fk),
                    {(*C.lon)[ck], (*C.lat)[ck]}, (*C.mask)[ck]);
        f.Lweight.push_back({});
        f.Qweight.push_back({});
        if (t != kRho) {
          push_fill();
          continue;
        }
        f.h.push_back(parent.h[ck]);
        f.f.push_back(parent.f[ck]);
        f.pm.push_back(parent.pm[ck]);
        f.pn.push_back(parent.pn[ck]);
        f.dndx.push_back(parent.dndx[ck]);
        f.dmde.push_back(parent.dmde[ck]);
        f.angle.push_back(parent.angle[ck]);
      }
    sum.fine_to_coarse[t] = close_type(r2, t, start);
  }

  sum.points = f.size();
  if (!ratios.empty()) {
    std::sort(ratios.begin(), ratios.end());
    sum.ratio_median = ratios[ratios.size() / 2];
  }
  if (summary != nullptr) *summary = sum;
  return f;
}

}  // namespace aq::handoff
