// Q1 finite elements and PCG for the θ-, η-equations; see theta_eta.hpp.
#include "curvilinear/theta_eta.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>

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
        for (int b = 0; b < 4; ++b)
          s.at(i + kCi[a], j + kCj[a], kCi[b] - kCi[a], kCj[b] - kCj[a]) += k[a][b];
    }
  }
  return s;
}

// y = A x restricted to the free rows and columns (fixed entries of x are ignored, y = 0 there).
void multiply(const Stencil& s, const std::vector<char>& fixed, const std::vector<double>& x, std::vector<double>& y) {
  for (int j = 0; j < s.ny; ++j) {
    for (int i = 0; i < s.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(s.nx) + static_cast<std::size_t>(i);
      double acc = 0.0;
      if (fixed[k] == 0) {
        for (int dj = -1; dj <= 1; ++dj) {
          if (j + dj < 0 || j + dj >= s.ny) continue;
          for (int di = -1; di <= 1; ++di) {
            if (i + di < 0 || i + di >= s.nx) continue;
            const std::size_t m = static_cast<std::size_t>(static_cast<long>(k) + dj * s.nx + di);
            if (fixed[m] == 0) acc += s.a[9 * k + static_cast<std::size_t>(3 * (dj + 1) + di + 1)] * x[m];
          }
        }
      }
      y[k] = acc;
    }
  }
}

// z = M⁻¹ r for the symmetric Gauss–Seidel preconditioner M = (D+L) D⁻¹ (D+U) on the free nodes.
void precondition(const Stencil& s, const std::vector<char>& fixed, const std::vector<double>& r,
                  std::vector<double>& z) {
  const int nx = s.nx, ny = s.ny;
  auto coef = [&](std::size_t k, int di, int dj) { return s.a[9 * k + static_cast<std::size_t>(3 * (dj + 1) + di + 1)]; };
  auto sweep_row = [&](int j, int i, bool lower) {
    const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i);
    if (fixed[k] != 0) {
      z[k] = 0.0;
      return;
    }
    double acc = 0.0;
    for (int dj = -1; dj <= 1; ++dj) {
      if (j + dj < 0 || j + dj >= ny) continue;
      for (int di = -1; di <= 1; ++di) {
        if (i + di < 0 || i + di >= nx) continue;
        const bool before = dj < 0 || (dj == 0 && di < 0);
        const bool after = dj > 0 || (dj == 0 && di > 0);
        if ((lower && !before) || (!lower && !after)) continue;
        const std::size_t m = static_cast<std::size_t>(static_cast<long>(k) + dj * nx + di);
        if (fixed[m] == 0) acc += coef(k, di, dj) * z[m];
      }
    }
    const double d = coef(k, 0, 0);
    z[k] = lower ? (r[k] - acc) / d : z[k] - acc / d;
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) sweep_row(j, i, true);
  for (int j = ny - 1; j >= 0; --j)
    for (int i = nx - 1; i >= 0; --i) sweep_row(j, i, false);
}

double dot_product(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) s += a[k] * b[k];
  return s;
}

// Solves A u = 0 with u = value on fixed nodes; u holds the guess on entry. Returns CG iterations.
int solve(const Stencil& s, const std::vector<char>& fixed, std::vector<double>& u, const ThetaEtaOptions& o,
          const char* name) {
  const std::size_t n = u.size();
  // b = −A_{free,fixed} u_fixed.
  std::vector<double> b(n, 0.0), r(n), z(n), p(n), q(n);
  for (int j = 0; j < s.ny; ++j) {
    for (int i = 0; i < s.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(s.nx) + static_cast<std::size_t>(i);
      if (fixed[k] != 0) continue;
      for (int dj = -1; dj <= 1; ++dj) {
        if (j + dj < 0 || j + dj >= s.ny) continue;
        for (int di = -1; di <= 1; ++di) {
          if (i + di < 0 || i + di >= s.nx) continue;
          const std::size_t m = static_cast<std::size_t>(static_cast<long>(k) + dj * s.nx + di);
          if (fixed[m] != 0) b[k] -= s.a[9 * k + static_cast<std::size_t>(3 * (dj + 1) + di + 1)] * u[m];
        }
      }
    }
  }
  const double bnorm = std::sqrt(dot_product(b, b));
  std::vector<double> x(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) x[k] = fixed[k] != 0 ? 0.0 : u[k];
  multiply(s, fixed, x, q);
  for (std::size_t k = 0; k < n; ++k) r[k] = b[k] - q[k];
  double rnorm = std::sqrt(dot_product(r, r));
  int it = 0;
  if (bnorm > 0.0 && rnorm > o.tolerance * bnorm) {
    precondition(s, fixed, r, z);
    p = z;
    double rz = dot_product(r, z);
    while (rnorm > o.tolerance * bnorm) {
      if (++it > o.max_iterations)
        throw NumericalError(fmt::format("theta/eta equations: CG for {} did not converge in {} iterations "
                                         "(relative residual {:.2e})",
                                         name, o.max_iterations, rnorm / bnorm));
      multiply(s, fixed, p, q);
      const double alpha = rz / dot_product(p, q);
      for (std::size_t k = 0; k < n; ++k) {
        x[k] += alpha * p[k];
        r[k] -= alpha * q[k];
      }
      rnorm = std::sqrt(dot_product(r, r));
      precondition(s, fixed, r, z);
      const double rz_new = dot_product(r, z);
      const double beta = rz_new / rz;
      rz = rz_new;
      for (std::size_t k = 0; k < n; ++k) p[k] = z[k] + beta * p[k];
    }
  }
  for (std::size_t k = 0; k < n; ++k)
    if (fixed[k] == 0) u[k] = x[k];
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
  out.iterations_theta = solve(s, fixed_theta, out.theta, options, "theta");
  out.iterations_eta = solve(s, fixed_eta, out.eta, options, "eta");
  out.energy_theta = energy(s, out.theta);
  out.energy_eta = energy(s, out.eta);
  return out;
}

}  // namespace aq::curvilinear
