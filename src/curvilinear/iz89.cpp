// Revised IZ89 straightening; see iz89.hpp (seed 000 Sec. 2.3–2.4; digest izogrid.md §5, §6.2).
#include "curvilinear/iz89.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
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

// The barrier between the threads of a sweep, once per vertex map. It polls only briefly (the
// threads' shares of a map end within microseconds of each other on an idle machine), then
// sleeps in the kernel: a thread whose partner was descheduled hands its core over instead of
// spinning it away, as OpenMP's barrier does for up to ~1 ms (measured: 2 threads on a loaded
// machine burnt 25× the CPU time of one).
class SweepBarrier {
 public:
  /// Every one of the team's `threads` threads calls this.
  void wait(int threads) {
    const unsigned gen = generation_.load(std::memory_order_acquire);
    if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == threads) {
      arrived_.store(0, std::memory_order_relaxed);
      generation_.store(gen + 1, std::memory_order_release);
      generation_.notify_all();
      return;
    }
    for (int i = 0; i < kPolls; ++i) {
      if (generation_.load(std::memory_order_acquire) != gen) return;
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
    }
    while (generation_.load(std::memory_order_acquire) == gen) generation_.wait(gen, std::memory_order_acquire);
  }

 private:
  static constexpr int kPolls = 1000;  // ~10–40 µs
  std::atomic<int> arrived_{0};
  std::atomic<unsigned> generation_{0};
};

// Scratch of one iz89_straighten call, shared by the threads of a sweep. The polygon lives in
// two buffers (the caller's arrays and a copy): vertex map k reads one and writes the other, so
// a thread can start map k+1 on its own points while the others still apply map k to theirs.
// θ and the block ranges are double-buffered the same way.
struct Workspace {
  double* px[2];
  double* py[2];
  std::vector<double> qx, qy;  // buffer 1
  const char* corner_flag;
  int nb, nwalk, nblocks;
  std::vector<double> theta[2], block_min[2], block_max[2];
};

struct SweepResult {
  double max_angle = 0.0;
  int clamped = 0;
  bool collapsed = false;
  int maps_done = 0;  // vertex maps applied (all of them unless a collapse stopped the sweep)
};

// One vertex map's data, computed identically by every thread from z_{k−1}, z_k, z_{k+1}.
struct VertexMap {
  double xk = 0.0, yk = 0.0;
  double ubx = 0.0, uby = 0.0;  // backward ray (unnormalised)
  double inv_l2 = 0.0;
  double ang = 0.0, a_int = 0.0, eps = 0.0;
  bool collapsed = false;
};

VertexMap vertex_map(double xm, double ym, double xk, double yk, double xp, double yp, bool corner) {
  VertexMap v;
  v.xk = xk;
  v.yk = yk;
  const double ax = xk - xm, ay = yk - ym;
  const double bx = xp - xk, by = yp - yk;
  const double cr = ax * by - ay * bx, dt = ax * bx + ay * by;
  const double l2 = ax * ax + ay * ay;
  if (!(l2 > 0.0) || !(bx * bx + by * by > 0.0) || !std::isfinite(cr + dt)) {
    v.collapsed = true;
    return v;
  }
  if (corner) {
    if (cr > 0.0) {
      v.ang = std::atan2(-dt, cr);  // α' = α − π/2, small near convergence
      v.a_int = kHalfPi - v.ang;
    } else {  // reflex or straight "corner": α' leaves (−π/2, π/2)
      v.a_int = kPi - std::atan2(cr, dt);
      v.ang = kHalfPi - v.a_int;
    }
  } else {
    v.ang = std::atan2(cr, dt);  // α, small near convergence
    v.a_int = kPi - v.ang;
  }
  v.eps = v.ang / v.a_int;  // P − 1 = (T − A_int)/A_int
  v.ubx = -ax;
  v.uby = -ay;
  v.inv_l2 = 1.0 / l2;
  return v;
}

// The power map of one point with its continuous angle θ (the identity when ang = 0).
inline void map_point(const VertexMap& v, double theta, double x, double y, double& ox, double& oy) {
  if (v.ang == 0.0) {
    ox = x;
    oy = y;
    return;
  }
  const double dx = x - v.xk, dy = y - v.yk;
  const double lr = 0.5 * std::log((dx * dx + dy * dy) * v.inv_l2);
  double fr = 1.0, fi = 0.0;
  complex_exp(v.eps * lr, v.eps * theta, fr, fi);
  ox = v.xk + (fr * dx - fi * dy);
  oy = v.yk + (fi * dx + fr * dy);
}

// Phase 1 of one block: θ relative to the block's absolute start, and the block's range. The
// block's last point comes from (lx, ly) when `last_given` (a point another thread writes).
inline void block_angles(const VertexMap& v, const double* px, const double* py, int nb, int k, int wb, int we,
                         bool last_given, double lx, double ly, double* theta, double& bmin, double& bmax) {
  int j = k + wb;
  if (j >= nb) j -= nb;
  auto offset = [&](int w, int jj, double& dx, double& dy) {
    const bool given = last_given && w == we - 1;
    dx = (given ? lx : px[jj]) - v.xk;
    dy = (given ? ly : py[jj]) - v.yk;
  };
  double pdx = 0.0, pdy = 0.0;
  offset(wb, j, pdx, pdy);
  double t = std::atan2(v.ubx * pdy - v.uby * pdx, v.ubx * pdx + v.uby * pdy);
  double lo = t, hi = t;
  theta[wb] = t;
  for (int w = wb + 1; w < we; ++w) {
    if (++j == nb) j = 0;
    double dx = 0.0, dy = 0.0;
    offset(w, j, dx, dy);
    t += small_angle(pdx * dy - pdy * dx, pdx * dx + pdy * dy);
    theta[w] = t;
    lo = std::min(lo, t);
    hi = std::max(hi, t);
    pdx = dx;
    pdy = dy;
  }
  bmin = lo;
  bmax = hi;
}

// Vertex maps k0..k1−1 of a pass on `threads` threads (bit-identical for any count). One
// barrier per vertex map: after it, every thread finds the 2π multiples and the span guard of
// map k (a short serial prefix over all blocks' angles), applies map k to its points into the
// other buffer, maps z_{k+1}, z_{k+2} and the first point of the next thread's range itself
// (the same arithmetic as their owners, so the same bits), and computes its blocks' angles for
// map k+1, whose walk is shifted by one point.
SweepResult sweep(Workspace& ws, int k0, int k1, int threads) {
  const int nb = ws.nb, nwalk = ws.nwalk, nblocks = ws.nblocks;
  const char* corner_flag = ws.corner_flag;
  SweepResult out;
#ifndef _OPENMP
  (void)threads;
#endif
  SweepBarrier barrier;
#pragma omp parallel num_threads(threads) default(none) \
    shared(out, ws, corner_flag, nb, nwalk, nblocks, k0, k1, barrier)
  {
    int tid = 0, nt = 1;
#ifdef _OPENMP
    tid = omp_get_thread_num();
    nt = omp_get_num_threads();
#endif
    // My blocks: [b0, b1), ending at walk position w_hi.
    const int b0 = static_cast<int>(static_cast<long long>(nblocks) * tid / nt);
    const int b1 = static_cast<int>(static_cast<long long>(nblocks) * (tid + 1) / nt);
    const int w_hi = std::min(1 + b1 * kBlock, nwalk + 1);
    const bool walk_end = b1 == nblocks;  // I hold the walk's end and carry z_{k−1} over
    auto block_end = [nwalk](int b) { return std::min(1 + (b + 1) * kBlock, nwalk + 1); };
    std::vector<int> turns(static_cast<std::size_t>(nblocks));  // private: every thread computes all
    double pass_max = 0.0;
    int clamped = 0;
    bool collapsed = false;
    int done = 0;
    VertexMap v;
    {
      const int km = k0 == 0 ? nb - 1 : k0 - 1;
      const int kp = k0 == nb - 1 ? 0 : k0 + 1;
      const double* x = ws.px[0];
      const double* y = ws.py[0];
      v = vertex_map(x[km], y[km], x[k0], y[k0], x[kp], y[kp], corner_flag[k0] != 0);
      if (!v.collapsed && v.ang != 0.0)
        for (int b = b0; b < b1; ++b)
          block_angles(v, x, y, nb, k0, 1 + b * kBlock, block_end(b), false, 0.0, 0.0, ws.theta[0].data(),
                       ws.block_min[0][static_cast<std::size_t>(b)], ws.block_max[0][static_cast<std::size_t>(b)]);
    }
    for (int k = k0; k < k1; ++k) {
      if (v.collapsed) {  // every thread sees the same vertex data
        collapsed = true;
        break;
      }
      pass_max = std::max(pass_max, std::fabs(v.ang));
      const int cur = (k - k0) & 1, nxt = cur ^ 1;
      const double* cx = ws.px[cur];
      const double* cy = ws.py[cur];
      double* ox = ws.px[nxt];
      double* oy = ws.py[nxt];
      const double* th = ws.theta[cur].data();
      if (nt > 1) barrier.wait(nt);
      if (v.ang != 0.0) {
        // 2π multiples at the block joins (block starts lie in (−π, π], θ_{k+1} = −A_int),
        // and the span of θ for the guard.
        const double* bmin = ws.block_min[cur].data();
        const double* bmax = ws.block_max[cur].data();
        double lo = 0.0, hi = 0.0;  // θ_{k−1} = 0 is part of the span
        int t = static_cast<int>(std::lround((-v.a_int - th[1]) / kTwoPi));
        for (int b = 0; b < nblocks; ++b) {
          const int wb = 1 + b * kBlock;
          if (b > 0) {
            const double prev_end = th[wb - 1] + kTwoPi * static_cast<double>(t);
            t = static_cast<int>(std::lround((prev_end - th[wb]) / kTwoPi));
          }
          turns[static_cast<std::size_t>(b)] = t;
          const double add = kTwoPi * static_cast<double>(t);
          lo = std::min(lo, bmin[b] + add);  // rounding is monotone: = min over θ + add
          hi = std::max(hi, bmax[b] + add);
        }
        // Guard on the mapped span (RECT's clamp).
        const double span = hi - lo;
        if ((1.0 + v.eps) * span > kMaxSpan) {
          v.eps = kMaxSpan / span - 1.0;
          ++clamped;
        }
      }
      auto angle = [&](int w, int b) {
        return th[w] + kTwoPi * static_cast<double>(turns[static_cast<std::size_t>(b)]);
      };
      // The power map of my points.
      for (int b = b0; b < b1; ++b) {
        const int wb = 1 + b * kBlock, we = block_end(b);
        int j = k + wb;
        if (j >= nb) j -= nb;
        for (int w = wb; w < we; ++w, ++j) {
          if (j == nb) j = 0;
          map_point(v, angle(w, b), cx[j], cy[j], ox[j], oy[j]);
        }
      }
      if (walk_end && k == k0) {  // z_{k−1} (fixed); later maps find it there, as map k−1's centre
        const int km = k == 0 ? nb - 1 : k - 1;
        ox[km] = cx[km];
        oy[km] = cy[km];
      }
      ++done;
      if (k + 1 == k1) break;
      // Map k+1: z_k stays, z_{k+1} and z_{k+2} are walk positions 1 and 2 of map k.
      const int kp = k + 1 == nb ? 0 : k + 1;
      const int kpp = kp + 1 == nb ? 0 : kp + 1;
      double x1 = 0.0, y1 = 0.0, x2 = 0.0, y2 = 0.0;
      map_point(v, angle(1, 0), cx[kp], cy[kp], x1, y1);
      map_point(v, angle(2, 0), cx[kpp], cy[kpp], x2, y2);
      const VertexMap vn = vertex_map(cx[k], cy[k], x1, y1, x2, y2, corner_flag[kp] != 0);
      if (!vn.collapsed && vn.ang != 0.0 && b0 < b1) {
        // My last point of map k+1 is the next thread's first point of map k.
        double lx = 0.0, ly = 0.0;
        if (!walk_end) {
          int j = k + w_hi;
          if (j >= nb) j -= nb;
          map_point(v, angle(w_hi, b1), cx[j], cy[j], lx, ly);
        }
        for (int b = b0; b < b1; ++b)
          block_angles(vn, ox, oy, nb, kp, 1 + b * kBlock, block_end(b), !walk_end && b == b1 - 1, lx, ly,
                       ws.theta[nxt].data(), ws.block_min[nxt][static_cast<std::size_t>(b)],
                       ws.block_max[nxt][static_cast<std::size_t>(b)]);
      }
      v = vn;
    }
#pragma omp master
    {
      out.max_angle = pass_max;
      out.clamped = clamped;
      out.collapsed = collapsed;
      out.maps_done = done;
    }
  }
  // The polygon after the last map is in buffer (maps_done mod 2), except its centre, which
  // that map left in the other buffer.
  const int done = out.maps_done;
  if (done > 0) {
    const int kl = k0 + done - 1;
    if ((done & 1) == 1) {
      for (int j = 0; j < nb; ++j)
        if (j != kl) {
          ws.px[0][j] = ws.px[1][j];
          ws.py[0][j] = ws.py[1][j];
        }
    } else {
      ws.px[0][kl] = ws.px[1][kl];
      ws.py[0][kl] = ws.py[1][kl];
    }
  }
  return out;
}

// Chooses between one thread and `max_threads` by timing chunks of vertex maps: the results do
// not depend on the choice, the speed does (each vertex map costs a barrier, which a busy
// machine can make far slower than the work it splits). The slower mode is re-timed now and
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
  ws.qx.assign(static_cast<std::size_t>(nb), 0.0);
  ws.qy.assign(static_cast<std::size_t>(nb), 0.0);
  ws.px[0] = x.data();
  ws.py[0] = y.data();
  ws.px[1] = ws.qx.data();
  ws.py[1] = ws.qy.data();
  ws.corner_flag = is_corner.data();
  ws.nb = nb;
  ws.nwalk = nb - 2;
  ws.nblocks = (ws.nwalk + kBlock - 1) / kBlock;
  for (int i = 0; i < 2; ++i) {
    ws.theta[i].assign(static_cast<std::size_t>(nb), 0.0);
    ws.block_min[i].assign(static_cast<std::size_t>(ws.nblocks), 0.0);
    ws.block_max[i].assign(static_cast<std::size_t>(ws.nblocks), 0.0);
  }
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
