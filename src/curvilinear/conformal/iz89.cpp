// SPDX-License-Identifier: GPL-3.0-or-later
// Revised IZ89 straightening; see iz89.hpp (seed 000 Sec. 2.3–2.4; digest izogrid.md §5, §6.2).
#include "curvilinear/conformal/iz89.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.hpp"

namespace aq::curvilinear {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;
constexpr double kHalfPi = 0.5 * kPi;
constexpr double kMaxSpan = 1.98 * kPi;  // RECT's guard on the mapped angular span

// exp(ex + i ey) = fr + i fi. Near the identity (most passes) short Taylor polynomials of
// exp(ex), cos(ey), sin(ey) replace the library calls; the three are independent chains, and
// their truncation errors are below 3e-21 in every branch.
inline void complex_exp(double ex, double ey, double& fr, double& fi) {
  const double t = std::max(std::fabs(ex), std::fabs(ey));
  const double y2 = ey * ey;
  double m = 0.0, c = 0.0, sn = 0.0;
  if (t < 1e-8) {
    m = 1.0 + ex * (1.0 + 0.5 * ex);
    c = 1.0 - 0.5 * y2;
    sn = ey;
  } else if (t < 2e-4) {
    m = 1.0 + ex * (1.0 + ex * (1.0 / 2 + ex * (1.0 / 6 + ex * (1.0 / 24))));
    c = 1.0 + y2 * (-1.0 / 2 + y2 * (1.0 / 24));
    sn = ey * (1.0 + y2 * (-1.0 / 6 + y2 * (1.0 / 120)));
  } else if (t < 1e-2) {
    const double x2 = ex * ex;
    // Even and odd parts of exp's series evaluated in x² (shorter dependency chains).
    const double ev = 1.0 + x2 * (1.0 / 2 + x2 * (1.0 / 24 + x2 * (1.0 / 720 + x2 * (1.0 / 40320))));
    const double od = ex * (1.0 + x2 * (1.0 / 6 + x2 * (1.0 / 120 + x2 * (1.0 / 5040 + x2 * (1.0 / 362880)))));
    m = ev + od;
    c = 1.0 + y2 * (-1.0 / 2 + y2 * (1.0 / 24 + y2 * (-1.0 / 720 + y2 * (1.0 / 40320))));
    sn = ey * (1.0 + y2 * (-1.0 / 6 + y2 * (1.0 / 120 + y2 * (-1.0 / 5040 + y2 * (1.0 / 362880)))));
  } else {
    m = std::exp(ex);
    c = std::cos(ey);
    sn = std::sin(ey);
  }
  fr = m * c;
  fi = m * sn;
}

constexpr int kBlock = 64;  // walk positions per unwrapping block

// Angle between consecutive vectors from their cross and dot products: a small angle except
// next to the vertex. atan(t) by its Taylor series for |t| ≤ 1/16 (error < 1e-18), atan2
// otherwise.
inline double small_angle(double cr, double dt) {
  if (dt > 0.0 && std::fabs(cr) <= 0.0625 * dt) {
    const double t = cr / dt, t2 = t * t;
    // t − t³/3 + t⁵/5 − ... − t¹⁵/15
    return t * (1.0 + t2 * (-1.0 / 3 +
                            t2 * (1.0 / 5 +
                                  t2 * (-1.0 / 7 + t2 * (1.0 / 9 + t2 * (-1.0 / 11 + t2 * (1.0 / 13 - t2 / 15)))))));
  }
  return std::atan2(cr, dt);
}

}  // namespace

namespace {

// Scratch of one iz89_straighten call, shared by the threads of a sweep.
struct Workspace {
  double* px;
  double* py;
  const char* corner_flag;
  int nb, nwalk, nblocks;
  std::vector<double> theta, block_min, block_max;
};

struct SweepResult {
  double max_angle = 0.0;
  int clamped = 0;
  bool collapsed = false;
};

// Vertex maps k0..k1−1 of a pass on `threads` threads (bit-identical for any count).
SweepResult sweep(Workspace& ws, int k0, int k1, int threads) {
  double* px = ws.px;
  double* py = ws.py;
  const char* corner_flag = ws.corner_flag;
  const int nb = ws.nb, nwalk = ws.nwalk, nblocks = ws.nblocks;
  double* theta_p = ws.theta.data();
  double* bmin_p = ws.block_min.data();
  double* bmax_p = ws.block_max.data();
  SweepResult out;
#ifndef _OPENMP
  (void)threads;
#endif
#pragma omp parallel num_threads(threads) default(none) \
    shared(out, px, py, corner_flag, theta_p, bmin_p, bmax_p, nb, nwalk, nblocks, k0, k1)
  {
    int tid = 0, nt = 1;
#ifdef _OPENMP
    tid = omp_get_thread_num();
    nt = omp_get_num_threads();
#endif
    // My blocks: [b0, b1).
    const int b0 = static_cast<int>(static_cast<long long>(nblocks) * tid / nt);
    const int b1 = static_cast<int>(static_cast<long long>(nblocks) * (tid + 1) / nt);
    std::vector<int> block_turns(static_cast<std::size_t>(nblocks));  // private: every thread computes all
    int* turns_p = block_turns.data();
    double pass_max = 0.0;
    int clamped = 0;
    bool collapsed = false;
    for (int k = k0; k < k1; ++k) {
      // Vertex data, computed identically by every thread from the shared polygon.
      const int km = k == 0 ? nb - 1 : k - 1;
      const int kp = k == nb - 1 ? 0 : k + 1;
      const double xk = px[k], yk = py[k];
      const double ax = xk - px[km], ay = yk - py[km];
      const double bx = px[kp] - xk, by = py[kp] - yk;
      const double cr = ax * by - ay * bx, dt = ax * bx + ay * by;
      const double l2 = ax * ax + ay * ay;
      if (!(l2 > 0.0) || !(bx * bx + by * by > 0.0) || !std::isfinite(cr + dt)) {
        collapsed = true;
        break;
      }
      double ang = 0.0, a_int = 0.0;  // turning angle from the target and interior angle
      if (corner_flag[k] != 0) {
        if (cr > 0.0) {
          ang = std::atan2(-dt, cr);  // α' = α − π/2, small near convergence
          a_int = kHalfPi - ang;
        } else {  // reflex or straight "corner": α' leaves (−π/2, π/2)
          a_int = kPi - std::atan2(cr, dt);
          ang = kHalfPi - a_int;
        }
      } else {
        ang = std::atan2(cr, dt);  // α, small near convergence
        a_int = kPi - ang;
      }
      pass_max = std::max(pass_max, std::fabs(ang));
      if (ang == 0.0) continue;           // the identity map
      double eps = ang / a_int;           // P − 1 = (T − A_int)/A_int
      const double ubx = -ax, uby = -ay;  // backward ray (unnormalised)

      // Phase 1: θ within each of my blocks, relative to the block's absolute start, and the
      // block's range of relative θ.
      for (int b = b0; b < b1; ++b) {
        const int wb = 1 + b * kBlock, we = std::min(wb + kBlock, nwalk + 1);
        int j = k + wb;
        if (j >= nb) j -= nb;
        double pdx = px[j] - xk, pdy = py[j] - yk;
        double t = std::atan2(ubx * pdy - uby * pdx, ubx * pdx + uby * pdy);
        double lo = t, hi = t;
        theta_p[wb] = t;
        for (int w = wb + 1; w < we; ++w) {
          if (++j == nb) j = 0;
          const double dx = px[j] - xk, dy = py[j] - yk;
          t += small_angle(pdx * dy - pdy * dx, pdx * dx + pdy * dy);
          theta_p[w] = t;
          lo = std::min(lo, t);
          hi = std::max(hi, t);
          pdx = dx;
          pdy = dy;
        }
        bmin_p[b] = lo;
        bmax_p[b] = hi;
      }
#pragma omp barrier
      // Phase 2 (every thread, identically): 2π multiples at the block joins by a short serial
      // prefix (block starts lie in (−π, π], θ_{k+1} = −A_int), and the span of θ.
      {
        double lo = 0.0, hi = 0.0;  // θ_{k−1} = 0 is part of the span
        int turns = static_cast<int>(std::lround((-a_int - theta_p[1]) / kTwoPi));
        for (int b = 0; b < nblocks; ++b) {
          const int wb = 1 + b * kBlock;
          if (b > 0) {
            const double prev_end = theta_p[wb - 1] + kTwoPi * static_cast<double>(turns);
            turns = static_cast<int>(std::lround((prev_end - theta_p[wb]) / kTwoPi));
          }
          turns_p[b] = turns;
          const double add = kTwoPi * static_cast<double>(turns);
          lo = std::min(lo, bmin_p[b] + add);  // rounding is monotone: = min over θ + add
          hi = std::max(hi, bmax_p[b] + add);
        }
        // Guard on the mapped span (RECT's clamp).
        const double span = hi - lo;
        if ((1.0 + eps) * span > kMaxSpan) {
          eps = kMaxSpan / span - 1.0;
          ++clamped;
        }
      }
      // Phase 3: the power map of my points.
      {
        const double inv_l2 = 1.0 / l2;
        for (int b = b0; b < b1; ++b) {
          const int wb = 1 + b * kBlock, we = std::min(wb + kBlock, nwalk + 1);
          const double add = kTwoPi * static_cast<double>(turns_p[b]);
          int j = k + wb;
          if (j >= nb) j -= nb;
          for (int w = wb; w < we; ++w, ++j) {
            if (j == nb) j = 0;
            const double dx = px[j] - xk, dy = py[j] - yk;
            const double lr = 0.5 * std::log((dx * dx + dy * dy) * inv_l2);
            double fr = 1.0, fi = 0.0;
            complex_exp(eps * lr, eps * (theta_p[w] + add), fr, fi);
            px[j] = xk + (fr * dx - fi * dy);
            py[j] = yk + (fi * dx + fr * dy);
          }
        }
      }
#pragma omp barrier
    }
#pragma omp master
    {
      out.max_angle = pass_max;
      out.clamped = clamped;
      out.collapsed = collapsed;
    }
  }
  return out;
}

// Chooses between one thread and `max_threads` by timing chunks of vertex maps: the results do
// not depend on the choice, the speed does (each vertex map costs two barriers, which a busy
// machine can make far slower than the work they split). The slower mode is re-timed now and
// then, less often the slower it was.
class ThreadChooser {
 public:
  explicit ThreadChooser(int max_threads) : max_(max_threads) {}
  int next() {
    if (max_ <= 1) return 1;
    if (t_[0] < 0.0) return 1;
    if (t_[1] < 0.0) return max_;
    const int fast = t_[0] <= t_[1] ? 0 : 1;
    const double ratio = std::min(64.0, std::max(t_[0], t_[1]) / std::min(t_[0], t_[1]));
    if (++since_probe_ >= static_cast<int>(16.0 * ratio)) {
      since_probe_ = 0;
      return fast == 0 ? max_ : 1;
    }
    return fast == 0 ? 1 : max_;
  }
  void record(int threads, double seconds_per_vertex) {
    double& t = t_[threads == 1 ? 0 : 1];
    t = t < 0.0 ? seconds_per_vertex : 0.5 * (t + seconds_per_vertex);
  }

 private:
  int max_;
  double t_[2] = {-1.0, -1.0};
  int since_probe_ = 0;
};

}  // namespace

Iz89Result iz89_straighten(std::span<double> x, std::span<double> y, const std::array<int, 4>& corners,
                           const Iz89Options& options) {
  const int nb = static_cast<int>(x.size());
  if (nb < 4 || y.size() != x.size()) throw InternalError("iz89_straighten: needs >= 4 vertices and equal x, y sizes");
  if (corners[0] != 0 ||
      !(corners[0] < corners[1] && corners[1] < corners[2] && corners[2] < corners[3] && corners[3] < nb))
    throw InternalError("iz89_straighten: corner indices must be 0 < SE < NE < NW < Nb");
  std::vector<char> is_corner(static_cast<std::size_t>(nb), 0);
  for (int c : corners) is_corner[static_cast<std::size_t>(c)] = 1;

  // Walk positions w = 1..nb−2 (point j = k + w mod nb; k−1 stays fixed, θ_{k−1} = 0), cut into
  // fixed blocks of kBlock positions. Each block starts from an absolute atan2 and accumulates
  // the small angles between consecutive points; a serial prefix over the blocks adds the 2π
  // multiples at the joins. Blocks do not depend on the thread count: bit-identical results.
  Workspace ws;
  ws.px = x.data();
  ws.py = y.data();
  ws.corner_flag = is_corner.data();
  ws.nb = nb;
  ws.nwalk = nb - 2;
  ws.nblocks = (ws.nwalk + kBlock - 1) / kBlock;
  ws.theta.assign(static_cast<std::size_t>(nb), 0.0);
  ws.block_min.assign(static_cast<std::size_t>(ws.nblocks), 0.0);
  ws.block_max.assign(static_cast<std::size_t>(ws.nblocks), 0.0);
  int max_threads = 1;
#ifdef _OPENMP
  max_threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  if (nb < options.min_parallel_vertices) max_threads = 1;
#endif
  max_threads = std::max(1, std::min(max_threads, ws.nblocks));
  ThreadChooser chooser(max_threads);
  const int chunk = options.threads > 0 ? nb : 128;  // fixed thread count: one sweep per pass

  // The round-off floor of the turning angles grows like Nb² (each of the Nb maps of a pass
  // perturbs positions by ~1 ulp of the coordinates; angles divide by edges ~ size/Nb):
  // measured 4e-12 at Nb = 460 and 4e-10 at Nb = 5228.
  const double tol = options.angle_tolerance;
  const double floor_thr = std::max(options.floor_threshold, 1e-15 * static_cast<double>(nb) * nb);
  Iz89Result result;
  double best = 1e300;
  for (int pass = 0; pass < options.max_passes; ++pass) {
    double pass_max = 0.0;
    for (int k0 = 0; k0 < nb; k0 += chunk) {
      const int k1 = std::min(nb, k0 + chunk);
      const int threads = options.threads > 0 ? max_threads : chooser.next();
      const auto t0 = std::chrono::steady_clock::now();
      const SweepResult r = sweep(ws, k0, k1, threads);
      chooser.record(threads, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / (k1 - k0));
      if (r.collapsed)
        throw NumericalError(
            "IZ89: a polygon edge collapsed to zero length (nodes coincide); the contour or the node "
            "distribution is degenerate");
      pass_max = std::max(pass_max, r.max_angle);
      result.clamped_maps += r.clamped;
    }
    // Converged at the tolerance, or at the round-off floor (below floor_threshold and no longer
    // falling by the usual decade per pass).
    const bool done = pass_max <= tol || (pass_max < floor_thr && pass_max > 0.3 * best);
    best = std::min(best, pass_max);
    result.passes = pass + 1;
    result.max_angle.push_back(pass_max);
    result.converged = done;
    if (done || !std::isfinite(pass_max)) break;
  }
  for (int i = 0; i < nb; ++i)
    if (!std::isfinite(x[static_cast<std::size_t>(i)]) || !std::isfinite(y[static_cast<std::size_t>(i)]))
      throw NumericalError(fmt::format("IZ89: non-finite coordinates after {} passes (vertex {})", result.passes, i));
  return result;
}

}  // namespace aq::curvilinear
