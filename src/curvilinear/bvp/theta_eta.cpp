// SPDX-License-Identifier: GPL-3.0-or-later
// Q1 finite elements and PCG for the θ-, η-equations; see theta_eta.hpp.
#include "curvilinear/bvp/theta_eta.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <exception>

#include "core/error.hpp"

namespace aq::curvilinear {

namespace {

// The 9-point stencil of node k: a[9k + 3(dj+1) + (di+1)] couples (i, j) to (i+di, j+dj).
struct Stencil {
  int nx = 0, ny = 0;
  std::vector<double> a;
  [[nodiscard]] double& at(int i, int j, int di, int dj) {
    return a[9 * (static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i)) +
             static_cast<std::size_t>(3 * (dj + 1) + (di + 1))];
  }
};

// Local corner order 0 = (0,0), 1 = (1,0), 2 = (1,1), 3 = (0,1) of a cell.
constexpr std::array<int, 4> kCi{0, 1, 1, 0};
constexpr std::array<int, 4> kCj{0, 0, 1, 1};

Stencil assemble(const SurfaceGrid& g) {
  Stencil s{g.nx_pts, g.ny_pts, std::vector<double>(9 * g.p.size(), 0.0)};
  const double gp[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  for (int j = 0; j + 1 < g.ny_pts; ++j) {
    for (int i = 0; i + 1 < g.nx_pts; ++i) {
      const Vec3 p00 = g(i, j), p10 = g(i + 1, j), p11 = g(i + 1, j + 1), p01 = g(i, j + 1);
      double k[4][4] = {};
      for (double zeta : gp) {
        for (double xi : gp) {
          const Vec3 rx = (1 - zeta) * (p10 - p00) + zeta * (p11 - p01);
          const Vec3 rz = (1 - xi) * (p01 - p00) + xi * (p11 - p10);
          const double g11 = dot(rx, rx), g12 = dot(rx, rz), g22 = dot(rz, rz);
          const double sg = norm(cross(rx, rz));
          if (!(sg > 0.0) || !std::isfinite(sg))
            throw NumericalError(fmt::format("theta/eta equations: reference cell ({}, {}) is degenerate", i, j));
          const double dn[4][2] = {{-(1 - zeta), -(1 - xi)}, {1 - zeta, -xi}, {zeta, xi}, {-zeta, 1 - xi}};
          for (int a = 0; a < 4; ++a) {
            const double ca0 = (g22 * dn[a][0] - g12 * dn[a][1]) / sg;
            const double ca1 = (g11 * dn[a][1] - g12 * dn[a][0]) / sg;
            for (int b = 0; b < 4; ++b) k[a][b] += 0.25 * (ca0 * dn[b][0] + ca1 * dn[b][1]);
          }
        }
      }
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) s.at(i + kCi[a], j + kCj[a], kCi[b] - kCi[a], kCj[b] - kCj[a]) += k[a][b];
    }
  }
  return s;
}

// One problem's matrix on a grid padded by one ghost layer (index (i+1) + (j+1)(nx+2)), so that
// the loops have no branches: couplings to fixed and ghost nodes are 0, a fixed row is the
// identity. Unknowns are the corrections on free nodes (0 on fixed ones).
struct Padded {
  int nx = 0, ny = 0, w = 0;
  std::vector<double> a;  // 9 per padded node
  std::array<long, 9> off{};
  [[nodiscard]] std::size_t pad(int i, int j) const {
    return static_cast<std::size_t>(j + 1) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i + 1);
  }
};

Padded padded(const Stencil& s, const std::vector<char>& fixed) {
  Padded m;
  m.nx = s.nx;
  m.ny = s.ny;
  m.w = s.nx + 2;
  m.a.assign(9 * static_cast<std::size_t>(m.w) * static_cast<std::size_t>(s.ny + 2), 0.0);
  for (int dj = -1; dj <= 1; ++dj)
    for (int di = -1; di <= 1; ++di) m.off[static_cast<std::size_t>(3 * (dj + 1) + di + 1)] = dj * m.w + di;
  for (int j = 0; j < s.ny; ++j) {
    for (int i = 0; i < s.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(s.nx) + static_cast<std::size_t>(i);
      double* row = &m.a[9 * m.pad(i, j)];
      if (fixed[k] != 0) {
        row[4] = 1.0;
        continue;
      }
      for (int dj = -1; dj <= 1; ++dj) {
        if (j + dj < 0 || j + dj >= s.ny) continue;
        for (int di = -1; di <= 1; ++di) {
          if (i + di < 0 || i + di >= s.nx) continue;
          const std::size_t mm = static_cast<std::size_t>(static_cast<long>(k) + dj * s.nx + di);
          if (fixed[mm] == 0) row[3 * (dj + 1) + di + 1] = s.a[9 * k + static_cast<std::size_t>(3 * (dj + 1) + di + 1)];
        }
      }
    }
  }
  return m;
}

// y = A x on the interior of the padded arrays.
void multiply(const Padded& m, const std::vector<double>& x, std::vector<double>& y) {
  for (int j = 0; j < m.ny; ++j) {
    for (int i = 0; i < m.nx; ++i) {
      const std::size_t k = m.pad(i, j);
      const double* a = &m.a[9 * k];
      double acc = 0.0;
      for (std::size_t q = 0; q < 9; ++q) acc += a[q] * x[static_cast<std::size_t>(static_cast<long>(k) + m.off[q])];
      y[k] = acc;
    }
  }
}

// z = M⁻¹ r for the symmetric Gauss–Seidel preconditioner M = (D+L) D⁻¹ (D+U), natural order.
void precondition(const Padded& m, const std::vector<double>& r, std::vector<double>& z) {
  for (int j = 0; j < m.ny; ++j) {
    for (int i = 0; i < m.nx; ++i) {
      const std::size_t k = m.pad(i, j);
      const double* a = &m.a[9 * k];
      double acc = r[k];
      for (std::size_t q = 0; q < 4; ++q) acc -= a[q] * z[static_cast<std::size_t>(static_cast<long>(k) + m.off[q])];
      z[k] = acc / a[4];
    }
  }
  for (int j = m.ny - 1; j >= 0; --j) {
    for (int i = m.nx - 1; i >= 0; --i) {
      const std::size_t k = m.pad(i, j);
      const double* a = &m.a[9 * k];
      double acc = 0.0;
      for (std::size_t q = 5; q < 9; ++q) acc += a[q] * z[static_cast<std::size_t>(static_cast<long>(k) + m.off[q])];
      z[k] -= acc / a[4];
    }
  }
}

double dot_product(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) s += a[k] * b[k];
  return s;
}

// Solves A u = 0 with u = value on fixed nodes; u holds the guess on entry. Returns CG iterations.
int solve(const Stencil& s, const std::vector<char>& fixed, std::vector<double>& u, const ThetaEtaOptions& o,
          const char* name) {
  const Padded m = padded(s, fixed);
  const std::size_t n = m.a.size() / 9;
  // Right side b = −A u_guess (the full operator, Dirichlet values included) on free nodes: the
  // correction x solves A_free x = b with x = 0 on fixed nodes.
  std::vector<double> b(n, 0.0), x(n, 0.0), r(n), z(n, 0.0), p(n, 0.0), q(n, 0.0);
  double bnorm2 = 0.0;
  for (int j = 0; j < s.ny; ++j) {
    for (int i = 0; i < s.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(s.nx) + static_cast<std::size_t>(i);
      if (fixed[k] != 0) continue;
      double acc = 0.0, dirichlet = 0.0;
      for (int dj = -1; dj <= 1; ++dj) {
        if (j + dj < 0 || j + dj >= s.ny) continue;
        for (int di = -1; di <= 1; ++di) {
          if (i + di < 0 || i + di >= s.nx) continue;
          const std::size_t mm = static_cast<std::size_t>(static_cast<long>(k) + dj * s.nx + di);
          const double c = s.a[9 * k + static_cast<std::size_t>(3 * (dj + 1) + di + 1)];
          acc += c * u[mm];
          if (fixed[mm] != 0) dirichlet += c * u[mm];
        }
      }
      b[m.pad(i, j)] = -acc;
      bnorm2 += dirichlet * dirichlet;
    }
  }
  const double bnorm = std::sqrt(bnorm2);  // the Dirichlet data's size: the scale of the residual
  r = b;
  double rnorm = std::sqrt(dot_product(r, r));
  int it = 0;
  if (bnorm > 0.0 && rnorm > o.tolerance * bnorm) {
    precondition(m, r, z);
    p = z;
    double rz = dot_product(r, z);
    while (rnorm > o.tolerance * bnorm) {
      if (++it > o.max_iterations)
        throw NumericalError(
            fmt::format("theta/eta equations: CG for {} did not converge in {} iterations "
                        "(relative residual {:.2e})",
                        name, o.max_iterations, rnorm / bnorm));
      multiply(m, p, q);
      const double alpha = rz / dot_product(p, q);
      for (std::size_t k = 0; k < n; ++k) {
        x[k] += alpha * p[k];
        r[k] -= alpha * q[k];
      }
      rnorm = std::sqrt(dot_product(r, r));
      precondition(m, r, z);
      const double rz_new = dot_product(r, z);
      const double beta = rz_new / rz;
      rz = rz_new;
      for (std::size_t k = 0; k < n; ++k) p[k] = z[k] + beta * p[k];
    }
  }
  for (int j = 0; j < s.ny; ++j)
    for (int i = 0; i < s.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(s.nx) + static_cast<std::size_t>(i);
      if (fixed[k] == 0) u[k] += x[m.pad(i, j)];
    }
  return it;
}

// uᵀ A u over all nodes (Dirichlet ones included): the discrete Dirichlet energy.
double energy(const Stencil& s, const std::vector<double>& u) {
  double e = 0.0;
  for (int j = 0; j < s.ny; ++j) {
    for (int i = 0; i < s.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(s.nx) + static_cast<std::size_t>(i);
      double acc = 0.0;
      for (int dj = -1; dj <= 1; ++dj) {
        if (j + dj < 0 || j + dj >= s.ny) continue;
        for (int di = -1; di <= 1; ++di) {
          if (i + di < 0 || i + di >= s.nx) continue;
          acc += s.a[9 * k + static_cast<std::size_t>(3 * (dj + 1) + di + 1)] *
                 u[static_cast<std::size_t>(static_cast<long>(k) + dj * s.nx + di)];
        }
      }
      e += u[k] * acc;
    }
  }
  return e;
}

}  // namespace

double ThetaEta::aspect_ratio() const { return std::sqrt(energy_eta / energy_theta); }

ThetaEta solve_theta_eta(const SurfaceGrid& reference, const ThetaEtaOptions& options,
                         const std::vector<double>& guess_theta, const std::vector<double>& guess_eta) {
  const int nx = reference.nx_pts, ny = reference.ny_pts;
  if (nx < 2 || ny < 2 || reference.p.size() != static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny))
    throw InternalError(fmt::format("solve_theta_eta: a {} x {} reference grid", nx, ny));
  const std::size_t n = reference.p.size();
  const Stencil s = assemble(reference);
  ThetaEta out;
  out.theta = guess_theta.size() == n ? guess_theta : std::vector<double>(n);
  out.eta = guess_eta.size() == n ? guess_eta : std::vector<double>(n);
  std::vector<char> fixed_theta(n, 0), fixed_eta(n, 0);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = reference.at(i, j);
      if (guess_theta.size() != n) out.theta[k] = static_cast<double>(i) / (nx - 1);
      if (guess_eta.size() != n) out.eta[k] = static_cast<double>(j) / (ny - 1);
      if (i == 0 || i == nx - 1) {
        fixed_theta[k] = 1;
        out.theta[k] = i == 0 ? 0.0 : 1.0;
      }
      if (j == 0 || j == ny - 1) {
        fixed_eta[k] = 1;
        out.eta[k] = j == 0 ? 0.0 : 1.0;
      }
    }
  }
  // Two independent serial solves: one per thread when there are two (same bytes either way).
  std::exception_ptr failure[2];
#pragma omp parallel sections default(none) shared(s, fixed_theta, fixed_eta, out, options, failure)
  {
#pragma omp section
    try {
      out.iterations_theta = solve(s, fixed_theta, out.theta, options, "theta");
    } catch (...) {
      failure[0] = std::current_exception();
    }
#pragma omp section
    try {
      out.iterations_eta = solve(s, fixed_eta, out.eta, options, "eta");
    } catch (...) {
      failure[1] = std::current_exception();
    }
  }
  for (const auto& f : failure)
    if (f) std::rethrow_exception(f);
  out.energy_theta = energy(s, out.theta);
  out.energy_eta = energy(s, out.eta);
  return out;
}

}  // namespace aq::curvilinear
