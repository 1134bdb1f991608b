// SPDX-License-Identifier: GPL-3.0-or-later
// MPI session and collectives of the forest engine (see mpi_session.hpp and comm.hpp).
#include "forest/comm.hpp"

#include <fmt/format.h>
#include <p4est.h>
#include <sc.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "core/error.hpp"
#include "forest/mpi_session.hpp"

namespace aq::forest {

namespace {

bool g_started = false;
bool g_finished = false;
bool g_agreed = false;  // the error being thrown went through agree()

// Messages travel in pieces of at most this many bytes (MPI counts are int).
constexpr std::uint64_t kPiece = std::uint64_t{1} << 30;

void check(int rc, const char* what) {
  if (rc != MPI_SUCCESS) throw InternalError(fmt::format("MPI: {} failed (code {})", what, rc));
}

}  // namespace

bool launched_by_mpirun() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(v) != nullptr) return true;
  return false;
}

void start_mpi(int* argc, char*** argv) {
  if (g_started) return;
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (initialised == 0) {
    int provided = 0;
    check(MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  }
  // libsc and p4est log through their own handlers: silenced (aquatoria's rank 0 logs).
  sc_init(MPI_COMM_WORLD, 0, 0, nullptr, SC_LP_SILENT);
  p4est_init(nullptr, SC_LP_SILENT);
  g_started = true;
  // A process that does not end through finish_run (a test program) finalises MPI at exit.
  std::atexit([] {
    int done = 0;
    MPI_Finalized(&done);
    if (mpi_running() && done == 0) MPI_Finalize();
    g_finished = true;
  });
}

bool mpi_running() { return g_started && !g_finished; }

int world_rank() {
  if (!mpi_running()) return 0;
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

int world_size() {
  if (!mpi_running()) return 1;
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

int finish_run(int code, const std::string& message, bool print) {
  if (!mpi_running()) {
    if (code != 0 && print && !message.empty()) std::fprintf(stderr, "error: %s\n", message.c_str());
    return code;
  }
  const Comm comm;
  // Ranks done early wait without spinning (OpenMPI's blocking collectives poll a core): a
  // non-blocking barrier tested every 2 ms until the last rank arrives.
  {
    MPI_Request req;
    MPI_Ibarrier(MPI_COMM_WORLD, &req);
    int arrived = 0;
    while (true) {
      MPI_Test(&req, &arrived, MPI_STATUS_IGNORE);
      if (arrived != 0) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }
  // AQ_FOREST_DEBUG=1 (a diagnostic, not a configuration key): every rank says how it ended.
  if (const char* d = std::getenv("AQ_FOREST_DEBUG"); d != nullptr && std::string(d) == "1")
    std::fprintf(stderr, "rank %d of %d: exit %d%s%s\n", comm.rank(), comm.size(), code, message.empty() ? "" : ": ",
                 message.c_str());
  // The lowest failing rank's outcome.
  const std::int64_t first = comm.min(code != 0 ? static_cast<std::int64_t>(comm.rank()) : INT_MAX);
  int agreed = code;
  std::string text = message;
  if (first != INT_MAX) {
    std::vector<int> c{code};
    comm.bcast(c, static_cast<int>(first));
    agreed = c[0];
    comm.bcast(text, static_cast<int>(first));
    if (comm.root() && print && !text.empty()) std::fprintf(stderr, "error: %s\n", text.c_str());
  }
  std::fflush(nullptr);
  // sc_finalize is optional (it only checks libsc's memory balance): MPI alone is finalised.
  MPI_Finalize();
  g_finished = true;
  return agreed;
}

void abort_all(int code, const std::string& message) {
  std::fprintf(stderr, "error (rank %d of %d): %s\n", world_rank(), world_size(), message.c_str());
  std::fflush(nullptr);
  MPI_Abort(MPI_COMM_WORLD, code);
  std::_Exit(code);
}

Comm::Comm(MPI_Comm c) : comm_(c) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

void Comm::barrier() const { check(MPI_Barrier(comm_), "MPI_Barrier"); }

std::int64_t Comm::sum(std::int64_t x) const {
  std::int64_t y = 0;
  check(MPI_Allreduce(&x, &y, 1, MPI_INT64_T, MPI_SUM, comm_), "MPI_Allreduce");
  return y;
}
std::int64_t Comm::max(std::int64_t x) const {
  std::int64_t y = 0;
  check(MPI_Allreduce(&x, &y, 1, MPI_INT64_T, MPI_MAX, comm_), "MPI_Allreduce");
  return y;
}
std::int64_t Comm::min(std::int64_t x) const {
  std::int64_t y = 0;
  check(MPI_Allreduce(&x, &y, 1, MPI_INT64_T, MPI_MIN, comm_), "MPI_Allreduce");
  return y;
}
double Comm::max(double x) const {
  double y = 0;
  check(MPI_Allreduce(&x, &y, 1, MPI_DOUBLE, MPI_MAX, comm_), "MPI_Allreduce");
  return y;
}
double Comm::min(double x) const {
  double y = 0;
  check(MPI_Allreduce(&x, &y, 1, MPI_DOUBLE, MPI_MIN, comm_), "MPI_Allreduce");
  return y;
}

namespace {
template <typename T>
void reduce_pieces(std::vector<T>& v, MPI_Datatype type, MPI_Op op, MPI_Comm comm) {
  const std::size_t per = kPiece / sizeof(T);
  for (std::size_t k = 0; k < v.size(); k += per) {
    const auto n = static_cast<int>(std::min(per, v.size() - k));
    check(MPI_Allreduce(MPI_IN_PLACE, v.data() + k, n, type, op, comm), "MPI_Allreduce");
  }
}
}  // namespace

void Comm::sum_in_place(std::vector<std::int64_t>& v) const { reduce_pieces(v, MPI_INT64_T, MPI_SUM, comm_); }
void Comm::sum_in_place(std::vector<std::int32_t>& v) const { reduce_pieces(v, MPI_INT32_T, MPI_SUM, comm_); }
void Comm::max_in_place(std::vector<std::int64_t>& v) const { reduce_pieces(v, MPI_INT64_T, MPI_MAX, comm_); }
void Comm::or_in_place(std::vector<std::uint64_t>& v) const { reduce_pieces(v, MPI_UINT64_T, MPI_BOR, comm_); }
void Comm::and_in_place(std::vector<std::uint64_t>& v) const { reduce_pieces(v, MPI_UINT64_T, MPI_BAND, comm_); }
void Comm::or_in_place(std::vector<std::uint8_t>& v) const { reduce_pieces(v, MPI_UINT8_T, MPI_BOR, comm_); }

void Comm::bcast_raw(void* data, std::uint64_t n, int root) const {
  auto* p = static_cast<char*>(data);
  for (std::uint64_t k = 0; k < n; k += kPiece) {
    const auto m = static_cast<int>(std::min(kPiece, n - k));
    check(MPI_Bcast(p + k, m, MPI_BYTE, root, comm_), "MPI_Bcast");
  }
}

void Comm::bcast(std::string& s, int root) const {
  std::vector<char> v(s.begin(), s.end());
  bcast(v, root);
  s.assign(v.begin(), v.end());
}

std::vector<char> Comm::gather_bytes(const char* data, std::uint64_t n, int root) const {
  // Sizes first, then point-to-point pieces (any total size).
  std::vector<std::uint64_t> sizes(static_cast<std::size_t>(size_));
  check(MPI_Gather(&n, 1, MPI_UINT64_T, sizes.data(), 1, MPI_UINT64_T, root, comm_), "MPI_Gather");
  std::vector<char> out;
  if (rank_ == root) {
    std::uint64_t total = 0;
    for (const auto s : sizes) total += s;
    out.resize(total);
    std::uint64_t at = 0;
    for (int r = 0; r < size_; ++r) {
      const std::uint64_t m = sizes[static_cast<std::size_t>(r)];
      if (r == root) {
        if (m > 0) std::memcpy(out.data() + at, data, m);
      } else {
        for (std::uint64_t k = 0; k < m; k += kPiece) {
          const auto c = static_cast<int>(std::min(kPiece, m - k));
          check(MPI_Recv(out.data() + at + k, c, MPI_BYTE, r, 77, comm_, MPI_STATUS_IGNORE), "MPI_Recv");
        }
      }
      at += m;
    }
  } else {
    for (std::uint64_t k = 0; k < n; k += kPiece) {
      const auto c = static_cast<int>(std::min(kPiece, n - k));
      check(MPI_Send(data + k, c, MPI_BYTE, root, 77, comm_), "MPI_Send");
    }
  }
  return out;
}

std::vector<char> Comm::allgather_bytes(const char* data, std::uint64_t n, std::vector<std::int64_t>& counts) const {
  std::vector<char> out = gather_bytes(data, n, 0);
  bcast(out, 0);
  counts.clear();
  return out;
}

std::vector<std::vector<char>> Comm::alltoall_bytes(const std::vector<const char*>& ptr,
                                                    const std::vector<std::uint64_t>& len) const {
  const auto n = static_cast<std::size_t>(size_);
  std::vector<std::uint64_t> in_len(n);
  check(MPI_Alltoall(len.data(), 1, MPI_UINT64_T, in_len.data(), 1, MPI_UINT64_T, comm_), "MPI_Alltoall");
  std::vector<std::vector<char>> out(n);
  std::vector<MPI_Request> req;
  for (std::size_t r = 0; r < n; ++r) {
    out[r].resize(in_len[r]);
    if (static_cast<int>(r) == rank_) {
      if (len[r] > 0) std::memcpy(out[r].data(), ptr[r], len[r]);
      continue;
    }
    for (std::uint64_t k = 0; k < in_len[r]; k += kPiece) {
      req.emplace_back();
      check(MPI_Irecv(out[r].data() + k, static_cast<int>(std::min(kPiece, in_len[r] - k)), MPI_BYTE,
                      static_cast<int>(r), 78, comm_, &req.back()),
            "MPI_Irecv");
    }
  }
  for (std::size_t r = 0; r < n; ++r) {
    if (static_cast<int>(r) == rank_) continue;
    for (std::uint64_t k = 0; k < len[r]; k += kPiece) {
      req.emplace_back();
      check(MPI_Isend(ptr[r] + k, static_cast<int>(std::min(kPiece, len[r] - k)), MPI_BYTE, static_cast<int>(r), 78,
                      comm_, &req.back()),
            "MPI_Isend");
    }
  }
  if (!req.empty()) check(MPI_Waitall(static_cast<int>(req.size()), req.data(), MPI_STATUSES_IGNORE), "MPI_Waitall");
  return out;
}

void agree(const Comm& comm, std::exception_ptr local) {
  int code = 0;
  std::string message;
  if (local) {
    try {
      std::rethrow_exception(local);
    } catch (const Error& e) {
      code = e.exit_code();
      message = e.what();
    } catch (const std::exception& e) {
      code = 1;
      message = fmt::format("internal: {}", e.what());
    } catch (...) {
      code = 1;
      message = "internal: an unknown exception";
    }
  }
  const std::int64_t first = comm.min(local ? static_cast<std::int64_t>(comm.rank()) : INT_MAX);
  if (first == INT_MAX) return;
  std::vector<int> c{code};
  comm.bcast(c, static_cast<int>(first));
  comm.bcast(message, static_cast<int>(first));
  g_agreed = true;
  if (c[0] == 2) throw ConfigError(message);
  throw InputError(message);
}

bool error_agreed() { return g_agreed; }

}  // namespace aq::forest
