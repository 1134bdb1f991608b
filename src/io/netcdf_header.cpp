// SPDX-License-Identifier: GPL-3.0-or-later
// A check of the classic netCDF header (CDF-1, CDF-2 and CDF-5; the netCDF "Classic Format
// Specification") before libnetcdf parses it. libnetcdf trusts the header's counts: a damaged
// file can make nc_open allocate gigabytes for one name (fuzzing found a 4 GB calloc from a 9-byte
// change). This walk reads the header with every count bounded by the bytes that are really in the
// file, and checks that the data of every variable lie within the file, so the readers never
// allocate for data that are not there.
//
//   header   = magic numrecs dim_list gatt_list var_list      magic = 'C' 'D' 'F' 1|2|5
//   list     = ABSENT (0, 0) | tag nelems [item ...]           tag: dim 0x0A, var 0x0B, attr 0x0C
//   dim      = name length                                     name = nelems chars, padded to 4
//   attr     = name nc_type nelems values (padded to 4)
//   var      = name ndims dimid... vatt_list nc_type vsize begin
// Big-endian. Counts are 4 bytes (8 in CDF-5); begin is 4 bytes in CDF-1, else 8.
#include <fmt/format.h>

#include <sys/statvfs.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <vector>

#include "core/input_files.hpp"
#include "core/timer.hpp"
#include "io/netcdf_file.hpp"

namespace aq::io {
namespace {

class HeaderWalk {
 public:
  HeaderWalk(const std::filesystem::path& path, std::ifstream& in, std::uint64_t file_size)
      : path_(path), in_(in), file_size_(file_size) {}

  void run() {
    need(4);
    version_ = b_[3];
    pos_ = 4;
    const std::uint64_t nrecs = numrecs();
    // dimensions
    std::vector<std::uint64_t> dims;
    std::size_t record_dim = std::numeric_limits<std::size_t>::max();
    const std::uint64_t ndims = list(0x0A, "dimension");
    for (std::uint64_t k = 0; k < ndims; ++k) {
      name("dimension");
      dims.push_back(count("dimension length"));
      if (dims.back() == 0) record_dim = dims.size() - 1;
    }
    attributes("global attribute");
    const std::uint64_t nvars = list(0x0B, "variable");
    for (std::uint64_t v = 0; v < nvars; ++v) {
      name("variable");
      const std::uint64_t nd = count("variable rank");
      if (nd > NC_MAX_VAR_DIMS) fail(fmt::format("a variable of rank {}", nd));
      std::uint64_t elems = 1;
      bool record = false;
      for (std::uint64_t d = 0; d < nd; ++d) {
        const std::uint64_t id = count("dimension id");
        if (id >= dims.size()) fail(fmt::format("dimension id {} of {} dimensions", id, dims.size()));
        if (id == record_dim && d == 0) {
          record = true;
          continue;
        }
        if (id == record_dim) fail("the record dimension is not a variable's first");
        elems = mul(elems, dims[id]);
      }
      attributes("variable attribute");
      const std::uint64_t size = type_size(word());
      (void)(version_ == 5 ? u64() : word());  // vsize: 2^32 - 1 stands for "larger" in CDF-2
      const std::uint64_t begin = version_ == 1 ? word() : u64();
      const std::uint64_t bytes = mul(mul(elems, size), record ? nrecs : 1);
      if (begin > file_size_ || bytes > file_size_ - begin)
        fail(fmt::format("a variable of {} bytes at offset {} (the file is cut short?)", bytes, begin));
    }
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(
        fmt::format("{}: damaged netCDF header: {} in a file of {} bytes", path_.string(), what, file_size_));
  }
  // Makes n more bytes at pos_ available, reading the file in growing pieces (a header is
  // usually a few kB; the data after it is never read here).
  void need(std::uint64_t n) {
    if (n > file_size_ - pos_) fail(fmt::format("{} bytes needed at offset {}", n, pos_));
    if (pos_ + n <= b_.size()) return;
    const std::uint64_t want =
        std::min<std::uint64_t>(file_size_, std::max<std::uint64_t>(pos_ + n, 2 * b_.size() + 4096));
    const std::size_t old = b_.size();
    b_.resize(static_cast<std::size_t>(want));
    in_.seekg(static_cast<std::streamoff>(old));
    in_.read(reinterpret_cast<char*>(b_.data() + old), static_cast<std::streamsize>(want - old));
    if (static_cast<std::uint64_t>(in_.gcount()) != want - old) fail("a short read");
  }
  std::uint32_t word() {
    need(4);
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) v = (v << 8) | b_[pos_++];
    return v;
  }
  std::uint64_t u64() {
    const std::uint64_t hi = word();
    return (hi << 32) | word();
  }
  // NON_NEG: 4 bytes, 8 in CDF-5; a 4-byte count above 2^31 - 1 is negative, hence invalid.
  std::uint64_t count(const char* what) {
    const std::uint64_t v = version_ == 5 ? u64() : word();
    if (version_ != 5 && v > 0x7fffffffu) fail(fmt::format("{} {}", what, v));
    return v;
  }
  // numrecs: a count, or all ones (STREAMING: the record count is not known; taken as 0).
  std::uint64_t numrecs() {
    const std::uint64_t v = version_ == 5 ? u64() : word();
    if (v == (version_ == 5 ? ~std::uint64_t{0} : std::uint64_t{0xffffffffu})) return 0;
    if (version_ != 5 && v > 0x7fffffffu) fail(fmt::format("numrecs {}", v));
    return v;
  }
  static std::uint64_t mul(std::uint64_t a, std::uint64_t b) {
    if (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a) return std::numeric_limits<std::uint64_t>::max();
    return a * b;
  }
  std::uint64_t type_size(std::uint32_t t) const {
    switch (t) {
      case NC_BYTE:
      case NC_CHAR:
      case NC_UBYTE:
        return 1;
      case NC_SHORT:
      case NC_USHORT:
        return 2;
      case NC_INT:
      case NC_FLOAT:
      case NC_UINT:
        return 4;
      case NC_DOUBLE:
      case NC_INT64:
      case NC_UINT64:
        return 8;
      default:
        fail(fmt::format("data type {}", t));
    }
  }
  // A list's tag and length; ABSENT is a zero tag with a zero length. Each item takes at least
  // 4 bytes, which bounds the length by the bytes left.
  std::uint64_t list(std::uint32_t tag, const char* what) {
    const std::uint32_t t = word();
    const std::uint64_t n = count(what);
    if (t == 0 && n == 0) return 0;
    if (t != tag) fail(fmt::format("{} list tag {}", what, t));
    if (n > (file_size_ - pos_) / 4) fail(fmt::format("{} {}s", n, what));
    return n;
  }
  void skip_padded(std::uint64_t n) {
    if (n > file_size_) fail(fmt::format("{} bytes of names or values", n));
    const std::uint64_t padded = (n + 3) / 4 * 4;
    need(padded);
    pos_ += padded;
  }
  void name(const char* what) {
    const std::uint64_t n = count("name length");
    if (n > NC_MAX_NAME) fail(fmt::format("a {} name of {} bytes", what, n));
    skip_padded(n);
  }
  void attributes(const char* what) {
    const std::uint64_t n = list(0x0C, what);
    for (std::uint64_t k = 0; k < n; ++k) {
      name(what);
      const std::uint64_t size = type_size(word());
      const std::uint64_t nelems = count("attribute length");
      skip_padded(mul(nelems, size));
    }
  }

  const std::filesystem::path& path_;
  std::ifstream& in_;
  std::vector<unsigned char> b_;
  std::uint64_t file_size_;
  std::size_t pos_ = 0;
  int version_ = 0;
};

}  // namespace

void check_netcdf_header(const std::filesystem::path& path) {
  // Opening a FIFO blocks; a device never ends: only regular files are read.
  if (const std::string bad = input_file_problem(path); !bad.empty())
    throw InputError(fmt::format("{}: {}", path.string(), bad));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open", path.string()));
  char magic[4] = {};
  in.read(magic, 4);
  if (in.gcount() != 4 || magic[0] != 'C' || magic[1] != 'D' || magic[2] != 'F' ||
      (magic[3] != 1 && magic[3] != 2 && magic[3] != 5))
    return;  // netCDF-4/HDF5 or not netCDF at all: nc_open decides
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(fmt::format("{}: cannot read its size: {}", path.string(), ec.message()));
  in.clear();
  HeaderWalk(path, in, size).run();
}

void check_declared_size(const std::filesystem::path& path, double values, const std::string& what) {
  const double bytes = values * 8.0, limit = 0.8 * static_cast<double>(physical_memory_bytes());
  if (!(bytes <= limit))
    throw InputError(
        fmt::format("{}: declares {} ({:.3g} values, {:.1f} GB to hold), more than the {:.1f} GB of 80% "
                    "of this machine's memory",
                    path.string(), what, values, bytes / 1e9, limit / 1e9));
}

std::string write_failure_note(const std::filesystem::path& path) {
  const int err = errno;
  if (err == ENOSPC || err == EDQUOT || err == EFBIG || err == EIO)
    return fmt::format(" ({}{})", std::strerror(err), err == ENOSPC ? ": ENOSPC" : "");
  struct statvfs fs {};
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  if (::statvfs(dir.c_str(), &fs) == 0 && static_cast<std::uint64_t>(fs.f_bavail) * fs.f_frsize < (64u << 10))
    return fmt::format(" ({}: ENOSPC, the file system of {} is full)", std::strerror(ENOSPC), dir.string());
  return {};
}

void open_for_reading(const std::filesystem::path& path, NcFile& nc) {
  check_netcdf_header(path);
  nc_check<InputError>(nc_open(path.c_str(), NC_NOWRITE, nc.out()), path, "open");
}

}  // namespace aq::io
