// SPDX-License-Identifier: GPL-3.0-or-later
// Buffered POSIX output with errno-checked writes.
#include "io/file_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/cancel.hpp"
#include "core/error.hpp"

namespace aq::io {

FileWriter::FileWriter(std::filesystem::path path) : path_(std::move(path)) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) fail("cannot create", errno);
  buf_.reserve(kChunkBytes + (kChunkBytes >> 2));
}

FileWriter::~FileWriter() {
  if (pending_.valid()) pending_.wait();  // an exception is unwinding: its error is not reported
  if (fd_ >= 0) ::close(fd_);
}

void FileWriter::fail(const char* what, int err) const {
  throw OutputError(fmt::format("{}: {}: {}", path_.string(), what, std::strerror(err)));
}

void FileWriter::write_all(const fmt::memory_buffer& data) const {
  const char* p = data.data();
  std::size_t left = data.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("write failed", errno);
    }
    if (n == 0) fail("write failed", ENOSPC);
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

void FileWriter::wait() {
  if (!pending_.valid()) return;
  pending_.get();  // rethrows the write's OutputError
  written_ += static_cast<std::int64_t>(writing_.size());
  writing_.clear();
}

void FileWriter::flush() {
  throw_if_cancelled();  // a Python caller's Ctrl-C (core/cancel.hpp): the OutputSet removes the file
  wait();
  if (buf_.size() == 0) return;
  std::swap(buf_, writing_);
  buf_.reserve(kChunkBytes + (kChunkBytes >> 2));
  pending_ = std::async(std::launch::async, [this] { write_all(writing_); });
}

std::int64_t FileWriter::close() {
  wait();
  write_all(buf_);  // the last chunk on this thread: nothing is left to overlap it with
  written_ += static_cast<std::int64_t>(buf_.size());
  buf_.clear();
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("close failed", errno);
  return written_;
}

}  // namespace aq::io
