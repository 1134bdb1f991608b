// SPDX-License-Identifier: GPL-3.0-or-later
// MPI helpers of the forest engine: a communicator with the collectives the stages use (sums,
// bitwise reductions, gathers of plain-data vectors, all-to-all exchanges) and the error
// agreement that makes a stage fail on every rank with the same message and exit code.
//
// Plain data only: every vector element type must be trivially copyable; messages travel as
// bytes, in pieces of at most 1 GiB (MPI counts are int).
#pragma once

#include <mpi.h>

#include <cstdint>
#include <cstring>
#include <exception>
#include <string>
#include <type_traits>
#include <vector>

namespace aq::forest {

class Comm {
 public:
  explicit Comm(MPI_Comm c = MPI_COMM_WORLD);
  [[nodiscard]] MPI_Comm get() const { return comm_; }
  [[nodiscard]] int rank() const { return rank_; }
  [[nodiscard]] int size() const { return size_; }
  [[nodiscard]] bool root() const { return rank_ == 0; }

  void barrier() const;
  [[nodiscard]] std::int64_t sum(std::int64_t x) const;
  [[nodiscard]] std::int64_t max(std::int64_t x) const;
  [[nodiscard]] std::int64_t min(std::int64_t x) const;
  [[nodiscard]] double max(double x) const;
  [[nodiscard]] double min(double x) const;
  [[nodiscard]] bool any(bool x) const { return max(static_cast<std::int64_t>(x)) != 0; }
  /// Element-wise sums / maxima / bitwise OR / AND over the ranks, in place (every rank gets them).
  void sum_in_place(std::vector<std::int64_t>& v) const;
  void sum_in_place(std::vector<std::int32_t>& v) const;
  void max_in_place(std::vector<std::int64_t>& v) const;
  void or_in_place(std::vector<std::uint64_t>& v) const;
  void and_in_place(std::vector<std::uint64_t>& v) const;
  void or_in_place(std::vector<std::uint8_t>& v) const;

  /// Every rank's `mine`, concatenated in rank order, on every rank.
  template <typename T>
  [[nodiscard]] std::vector<T> allgatherv(const std::vector<T>& mine) const {
    static_assert(std::is_trivially_copyable_v<T>);
    std::vector<std::int64_t> counts;
    std::vector<char> bytes =
        allgather_bytes(reinterpret_cast<const char*>(mine.data()), mine.size() * sizeof(T), counts);
    std::vector<T> out(bytes.size() / sizeof(T));
    if (!out.empty()) std::memcpy(out.data(), bytes.data(), bytes.size());
    return out;
  }
  /// Every rank's `mine`, concatenated in rank order, on `root` (empty elsewhere).
  template <typename T>
  [[nodiscard]] std::vector<T> gatherv(const std::vector<T>& mine, int root = 0) const {
    static_assert(std::is_trivially_copyable_v<T>);
    std::vector<char> bytes = gather_bytes(reinterpret_cast<const char*>(mine.data()), mine.size() * sizeof(T), root);
    std::vector<T> out(bytes.size() / sizeof(T));
    if (!out.empty()) std::memcpy(out.data(), bytes.data(), bytes.size());
    return out;
  }
  /// `v` of `root` on every rank.
  template <typename T>
  void bcast(std::vector<T>& v, int root = 0) const {
    static_assert(std::is_trivially_copyable_v<T>);
    std::uint64_t n = v.size();
    bcast_raw(&n, sizeof n, root);
    v.resize(n);
    bcast_raw(v.data(), n * sizeof(T), root);
  }
  void bcast(std::string& s, int root = 0) const;
  /// send[r] goes to rank r; returns what each rank sent here (index = source rank).
  template <typename T>
  [[nodiscard]] std::vector<std::vector<T>> alltoallv(const std::vector<std::vector<T>>& send) const {
    static_assert(std::is_trivially_copyable_v<T>);
    std::vector<const char*> ptr(static_cast<std::size_t>(size_));
    std::vector<std::uint64_t> len(ptr.size());
    for (int r = 0; r < size_; ++r) {
      ptr[static_cast<std::size_t>(r)] = reinterpret_cast<const char*>(send[static_cast<std::size_t>(r)].data());
      len[static_cast<std::size_t>(r)] = send[static_cast<std::size_t>(r)].size() * sizeof(T);
    }
    std::vector<std::vector<char>> got = alltoall_bytes(ptr, len);
    std::vector<std::vector<T>> out(got.size());
    for (std::size_t r = 0; r < got.size(); ++r) {
      out[r].resize(got[r].size() / sizeof(T));
      if (!out[r].empty()) std::memcpy(out[r].data(), got[r].data(), got[r].size());
    }
    return out;
  }

 private:
  std::vector<char> allgather_bytes(const char* data, std::uint64_t n, std::vector<std::int64_t>& counts) const;
  std::vector<char> gather_bytes(const char* data, std::uint64_t n, int root) const;
  void bcast_raw(void* data, std::uint64_t n, int root) const;
  std::vector<std::vector<char>> alltoall_bytes(const std::vector<const char*>& ptr,
                                                const std::vector<std::uint64_t>& len) const;
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
};

/// The error agreement: `local` is this rank's failure (null when it succeeded). Collective: when
/// any rank failed, every rank throws the error of the lowest failing rank — an aq::Error of the
/// same exit code and message (ConfigError for 2, InputError for 1; a non-aq exception becomes an
/// InternalError naming it). Returns normally when no rank failed.
void agree(const Comm& comm, std::exception_ptr local);

/// Runs `work` on this rank and then agree()s: the stage either succeeds everywhere or fails
/// everywhere with one message. Returns what `work` returns.
template <typename F>
auto collective(const Comm& comm, F&& work) -> decltype(work()) {
  std::exception_ptr error;
  if constexpr (std::is_void_v<decltype(work())>) {
    try {
      work();
    } catch (...) {
      error = std::current_exception();
    }
    agree(comm, error);
  } else {
    decltype(work()) result{};
    try {
      result = work();
    } catch (...) {
      error = std::current_exception();
    }
    agree(comm, error);
    return result;
  }
}

/// Whether the error being handled went through agree() (every rank holds the same one).
[[nodiscard]] bool error_agreed();

}  // namespace aq::forest
