// ROMS contact points of a child grid in its parent (see contact_points.hpp).
#include "handoff/contact_points.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace aq::handoff {

namespace {

// One staggered family of the parent: ni × nj points, (i, j) at j·ni + i.
struct Family {
  int ni = 0, nj = 0;
  const std::vector<double>* lon = nullptr;
  const std::vector<double>* lat = nullptr;
  const std::vector<double>* mask = nullptr;
  [[nodiscard]] std::size_t at(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(ni) + static_cast<std::size_t>(i);
  }
};

double unwrap(double lon, double ref) { return lon + 360.0 * std::round((ref - lon) / 360.0); }

constexpr double kInside = 1e-10;  // tolerance of the cell test in fractional cell coordinates

// Inverts the bilinear map of cell (i, j) at (x, y) (longitude unwrapped near the cell) by Newton's
// method. Returns false when it does not converge.
bool invert_cell(const Family& F, int i, int j, double x, double y, double& p, double& q) {
  const std::size_t k1 = F.at(i, j), k2 = F.at(i + 1, j), k3 = F.at(i + 1, j + 1), k4 = F.at(i, j + 1);
  const double ref = (*F.lon)[k1];
  const double x1 = ref, x2 = unwrap((*F.lon)[k2], ref), x3 = unwrap((*F.lon)[k3], ref), x4 = unwrap((*F.lon)[k4], ref);
  const double y1 = (*F.lat)[k1], y2 = (*F.lat)[k2], y3 = (*F.lat)[k3], y4 = (*F.lat)[k4];
  const double px = unwrap(x, ref);
  const double bx = x2 - x1, cx = x4 - x1, dx = x1 - x2 + x3 - x4;
  const double by = y2 - y1, cy = y4 - y1, dy = y1 - y2 + y3 - y4;
  p = 0.5;
  q = 0.5;
  for (int it = 0; it < 60; ++it) {
    const double fx = x1 + bx * p + cx * q + dx * p * q - px;
    const double fy = y1 + by * p + cy * q + dy * p * q - y;
    const double a11 = bx + dx * q, a12 = cx + dx * p, a21 = by + dy * q, a22 = cy + dy * p;
    const double det = a11 * a22 - a12 * a21;
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return false;
    const double dp = (fx * a22 - fy * a12) / det, dq = (a11 * fy - a21 * fx) / det;
    p -= dp;
    q -= dq;
    if (!std::isfinite(p) || !std::isfinite(q) || std::abs(p) > 1e6 || std::abs(q) > 1e6) return false;
    if (std::abs(dp) < 1e-15 && std::abs(dq) < 1e-15) return true;
  }
  return std::isfinite(p) && std::isfinite(q);
}

bool inside(double p, double q) { return p >= -kInside && p <= 1 + kInside && q >= -kInside && q <= 1 + kInside; }

struct Located {
  int i = -1, j = -1;  // lower-left corner, file indices
  double p = 0, q = 0;
};

// The cell of F containing (x, y), or i = -1.
Located locate(const Family& F, double x, double y) {
  // Coarse scan: the nearest point (local metric cos φ on longitude).
  const double c = std::cos(y * M_PI / 180.0);
  double best = std::numeric_limits<double>::infinity();
  int bi = 0, bj = 0;
  for (int j = 0; j < F.nj; ++j)
    for (int i = 0; i < F.ni; ++i) {
      const std::size_t k = F.at(i, j);
      const double dlon = (unwrap(x, (*F.lon)[k]) - (*F.lon)[k]) * c, dlat = y - (*F.lat)[k];
      const double d2 = dlon * dlon + dlat * dlat;
      if (d2 < best) {
        best = d2;
        bi = i;
        bj = j;
      }
    }
  Located r;
  const auto try_cell = [&](int i, int j, double& p, double& q) {
    if (i < 0 || j < 0 || i > F.ni - 2 || j > F.nj - 2) return false;
    return invert_cell(F, i, j, x, y, p, q);
  };
  // The four cells around the nearest point, then walk from the first that inverts.
  int wi = -1, wj = -1;
  double wp = 0, wq = 0;
  for (const auto& [di, dj] : {std::pair{0, 0}, std::pair{-1, 0}, std::pair{0, -1}, std::pair{-1, -1}}) {
    double p = 0, q = 0;
    if (!try_cell(bi + di, bj + dj, p, q)) continue;
    if (inside(p, q)) return {bi + di, bj + dj, p, q};
    if (wi < 0) {
      wi = bi + di;
      wj = bj + dj;
      wp = p;
      wq = q;
    }
  }
  for (int step = 0; wi >= 0 && step < 200; ++step) {
    const int ni = std::clamp(wi + static_cast<int>(std::floor(wp)), 0, F.ni - 2);
    const int nj = std::clamp(wj + static_cast<int>(std::floor(wq)), 0, F.nj - 2);
    if (ni == wi && nj == wj) break;  // at the parent's edge
    double p = 0, q = 0;
    if (!try_cell(ni, nj, p, q)) break;
    wi = ni;
    wj = nj;
    wp = p;
    wq = q;
    if (inside(p, q)) return {wi, wj, p, q};
  }
  // Last resort: every cell.
  for (int j = 0; j + 1 < F.nj; ++j)
    for (int i = 0; i + 1 < F.ni; ++i) {
      double p = 0, q = 0;
      if (try_cell(i, j, p, q) && inside(p, q)) return {i, j, p, q};
    }
  return r;
}

std::array<double, 4> bilinear(double p, double q) { return {(1 - p) * (1 - q), p * (1 - q), p * q, (1 - p) * q}; }

// Lagrange weights at offsets -1, 0, 1 for position t relative to the centre.
std::array<double, 3> lagrange3(double t) { return {0.5 * t * (t - 1), (1 - t) * (1 + t), 0.5 * t * (t + 1)}; }

std::array<double, 9> biquadratic(const Family& F, const Located& c) {
  const int ci = std::clamp(c.i, 1, F.ni - 2), cj = std::clamp(c.j, 1, F.nj - 2);
  const auto wx = lagrange3(c.i + c.p - ci), wy = lagrange3(c.j + c.q - cj);
  std::array<double, 9> w{};
  for (std::size_t b = 0; b < 3; ++b)
    for (std::size_t a = 0; a < 3; ++a) w[3 * b + a] = wx[a] * wy[b];
  return w;
}

}  // namespace

io::ContactFile contact_points(const io::RomsGridFields& parent, const curvilinear::CGrid& child,
                               const std::string& context, ContactSummary* summary) {
  const int PL = parent.L, PM = parent.M;
  const Family rho{PL + 1, PM + 1, &parent.lon_rho, &parent.lat_rho, &parent.mask_rho};
  const Family fu{PL, PM + 1, &parent.lon_u, &parent.lat_u, &parent.mask_u};
  const Family fv{PL + 1, PM, &parent.lon_v, &parent.lat_v, &parent.mask_v};
  io::ContactFile f;
  f.Lm = {PL - 1, child.L - 1};
  f.Mm = {PM - 1, child.M - 1};
  std::vector<double> ratios;
  ContactSummary sum;

  // type 0 ρ, 1 u, 2 v: child family, parent family, ROMS index offsets (child and parent alike).
  for (int type = 0; type < 3; ++type) {
    const curvilinear::StaggeredPoints& cp = type == 0 ? child.rho : type == 1 ? child.u : child.v;
    const Family& F = type == 0 ? rho : type == 1 ? fu : fv;
    const int oi = type == 1 ? 1 : 0, oj = type == 2 ? 1 : 0;
    const int start = static_cast<int>(f.size()) + 1;
    for (int j = 0; j < cp.nj; ++j)
      for (int i = 0; i < cp.ni; ++i) {
        const int side = i == 0 ? 1 : j == 0 ? 2 : i == cp.ni - 1 ? 3 : j == cp.nj - 1 ? 4 : 0;
        if (side == 0) continue;
        const std::size_t k = cp.at(i, j);
        const double x = cp.lon_deg[k], y = cp.lat_deg[k];
        Located c = locate(F, x, y);
        const char* tn = type == 0 ? "rho" : type == 1 ? "u" : "v";
        if (c.i < 0)
          throw ConfigError(fmt::format(
              "{}: the child grid's {} point ({}, {}) at {:.6f}°E {:.6f}°N lies outside the parent grid's {} points "
              "(the child must lie inside its parent, half a parent cell from its edge)",
              context, tn, i + oi, j + oj, x, y, tn));
        c.p = std::clamp(c.p, 0.0, 1.0);
        c.q = std::clamp(c.q, 0.0, 1.0);
        const auto w = bilinear(c.p, c.q);
        f.on_boundary.push_back(side);
        f.Idg.push_back(c.i + oi);
        f.Jdg.push_back(c.j + oj);
        f.Irg.push_back(i + oi);
        f.Jrg.push_back(j + oj);
        f.Xrg.push_back(x);
        f.Yrg.push_back(y);
        f.Lweight.push_back(w);
        f.Qweight.push_back(biquadratic(F, c));
        const std::size_t corner[4] = {F.at(c.i, c.j), F.at(c.i + 1, c.j), F.at(c.i + 1, c.j + 1), F.at(c.i, c.j + 1)};
        const auto big = static_cast<std::size_t>(std::max_element(w.begin(), w.end()) - w.begin());
        f.mask.push_back((*F.mask)[corner[big]]);
        if (f.mask.back() > 0.5) ++sum.wet_points;
        // The parent's ρ fields at the point.
        Located r = type == 0 ? c : locate(rho, x, y);
        if (r.i < 0)
          throw ConfigError(
              fmt::format("{}: the child grid's {} point at {:.6f}°E {:.6f}°N lies outside the parent "
                          "grid's rho points (the child must lie inside its parent)",
                          context, tn, x, y));
        r.p = std::clamp(r.p, 0.0, 1.0);
        r.q = std::clamp(r.q, 0.0, 1.0);
        const auto wr = bilinear(r.p, r.q);
        const std::size_t rc[4] = {rho.at(r.i, r.j), rho.at(r.i + 1, r.j), rho.at(r.i + 1, r.j + 1),
                                   rho.at(r.i, r.j + 1)};
        const auto interp = [&](const std::vector<double>& v) {
          double s = 0;
          for (std::size_t m = 0; m < 4; ++m) s += wr[m] * v[rc[m]];
          return s;
        };
        f.h.push_back(interp(parent.h));
        f.f.push_back(interp(parent.f));
        f.pm.push_back(interp(parent.pm));
        f.pn.push_back(interp(parent.pn));
        f.dndx.push_back(interp(parent.dndx));
        f.dmde.push_back(interp(parent.dmde));
        double s = 0, co = 0;
        for (std::size_t m = 0; m < 4; ++m) {
          s += wr[m] * std::sin(parent.angle[rc[m]]);
          co += wr[m] * std::cos(parent.angle[rc[m]]);
        }
        f.angle.push_back(std::atan2(s, co));
        if (type == 0 && !child.pm.empty()) {
          const double rpm = f.pm.back(), rpn = f.pn.back();
          if (rpm > 0 && rpn > 0)
            ratios.push_back(0.5 * (child.pm[k] / rpm + child.pn[k] / rpn));  // parent step / child step
        }
      }
    const int end = static_cast<int>(f.size());
    const std::size_t count = static_cast<std::size_t>(end - start + 1);
    if (type == 0) {
      f.NstrR = start;
      f.NendR = end;
      sum.rho = count;
    } else if (type == 1) {
      f.NstrU = start;
      f.NendU = end;
      sum.u = count;
    } else {
      f.NstrV = start;
      f.NendV = end;
      sum.v = count;
    }
  }
  sum.points = f.size();
  if (!ratios.empty()) {
    std::sort(ratios.begin(), ratios.end());
    sum.ratio_min = ratios.front();
    sum.ratio_max = ratios.back();
    sum.ratio_median = ratios[ratios.size() / 2];
  }
  f.refine_factor = {1, std::max(1, static_cast<int>(std::lround(sum.ratio_median)))};
  f.attributes.emplace_back("refinement_ratio_median", sum.ratio_median);
  f.attributes.emplace_back("refinement_ratio_min", sum.ratio_min);
  f.attributes.emplace_back("refinement_ratio_max", sum.ratio_max);
  f.attributes.emplace_back(
      "Qweight_stencil",
      std::string("donor points (Idg-1..Idg+1) x (Jdg-1..Jdg+1), shifted inward at the donor's edges, I fastest"));
  f.attributes.emplace_back(
      "note", std::string("the child is an independent orthogonal grid, not an exact refine_factor subdivision of "
                          "the parent's cells; refine_factor is the rounded median refinement ratio"));
  if (summary != nullptr) *summary = sum;
  return f;
}

}  // namespace aq::handoff
