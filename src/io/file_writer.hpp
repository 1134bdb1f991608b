// SPDX-License-Identifier: GPL-3.0-or-later
// Buffered output file used by every text and binary writer of src/io. Bytes are collected in
// a memory buffer (text through fmt::format_to, binary through `put`) and handed to the kernel
// in chunks of ~4 MiB with POSIX write(2), so that every failure (no permission, ENOSPC, EIO,
// a failing close on NFS) is seen with its errno and reported as an OutputError naming the file.
// A full chunk is written by a second thread while the caller fills the next one (the kernel's
// copy into the page cache cost the 732 MB MSH of a 1' run 0.8 s on the writing thread); its
// failure is reported by the next flush or close.
// Nothing is written to a final name here: callers pass the temporary path OutputSet gave them.
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <future>
#include <string_view>
#include <type_traits>

namespace aq::io {

class FileWriter {
 public:
  /// Creates (truncates) `path`. Throws OutputError naming it when it cannot be opened.
  explicit FileWriter(std::filesystem::path path);
  /// Closes without reporting errors if `close()` was not called (an exception is unwinding).
  ~FileWriter();
  FileWriter(const FileWriter&) = delete;
  FileWriter& operator=(const FileWriter&) = delete;

  /// The buffer text goes into; call `maybe_flush()` every few thousand appends.
  fmt::memory_buffer& buffer() { return buf_; }
  /// Formats into the buffer.
  template <typename... Args>
  void print(fmt::format_string<Args...> f, Args&&... args) {
    fmt::format_to(std::back_inserter(buf_), f, std::forward<Args>(args)...);
  }
  void text(std::string_view s) { buf_.append(s.data(), s.data() + s.size()); }
  /// Appends raw bytes.
  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const char*>(data);
    buf_.append(p, p + n);
  }
  /// Appends the native (little-endian on every supported machine) bytes of a trivially
  /// copyable value.
  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes(&value, sizeof(T));
  }
  /// Hands the buffer to the kernel when it is larger than the chunk size.
  void maybe_flush() {
    if (buf_.size() >= kChunkBytes) flush();
  }
  /// Hands everything buffered to the kernel: waits for the chunk before (rethrowing its
  /// failure) and writes this one on a second thread. Throws OutputError naming the file.
  void flush();
  /// Flushes and closes. Throws OutputError naming the file. Returns the file size in bytes.
  std::int64_t close();

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  /// Bytes handed to the kernel plus bytes still buffered.
  [[nodiscard]] std::int64_t size() const {
    return written_ + static_cast<std::int64_t>(writing_.size() + buf_.size());
  }

  static constexpr std::size_t kChunkBytes = std::size_t{4} << 20;

 private:
  [[noreturn]] void fail(const char* what, int err) const;

  // write(2) of every byte of `data`; throws OutputError (what the caller of wait() sees).
  void write_all(const fmt::memory_buffer& data) const;
  // Waits for the chunk being written, if any; rethrows its failure.
  void wait();

  std::filesystem::path path_;
  int fd_ = -1;
  std::int64_t written_ = 0;
  fmt::memory_buffer buf_;
  fmt::memory_buffer writing_;   ///< the chunk the second thread writes
  std::future<void> pending_;    ///< its write
};

}  // namespace aq::io
