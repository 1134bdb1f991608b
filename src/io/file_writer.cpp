// Buffered POSIX output with errno-checked writes.
#include "io/file_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.hpp"

namespace aq::io {

FileWriter::FileWriter(std::filesystem::path path) : path_(std::move(path)) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) fail("cannot create", errno);
  buf_.reserve(kChunkBytes + (kChunkBytes >> 2));
}

FileWriter::~FileWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void FileWriter::fail(const char* what, int err) const {
  throw OutputError(fmt::format("{}: {}: {}", path_.string(), what, std::strerror(err)));
}

void FileWriter::flush() {
  const char* p = buf_.data();
  std::size_t left = buf_.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("write failed", errno);
    }
    if (n == 0) fail("write failed", ENOSPC);
    p += n;
    left -= static_cast<std::size_t>(n);
    written_ += n;
  }
  buf_.clear();
}

std::int64_t FileWriter::close() {
  flush();
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("close failed", errno);
  return written_;
}

}  // namespace aq::io
