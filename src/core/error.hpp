// SPDX-License-Identifier: GPL-3.0-or-later
// Error types of aquatoria. The library throws; only src/app prints and exits.
// Exit codes (ARCHITECTURE §7): ConfigError and UsageError -> 2, every other aq::Error -> 1.
#pragma once

#include <stdexcept>
#include <string>

namespace aq {

/// Base of every error aquatoria throws. The message names the file, key or value at fault.
class Error : public std::runtime_error {
 public:
  /// NUL bytes of `what` (from a file name or value) become the two characters "\\0", so the
  /// message is printed whole rather than cut at the first one.
  explicit Error(const std::string& what) : std::runtime_error(printable(what)) {}
  explicit Error(const char* what) : Error(std::string(what)) {}
  /// Process exit code the command line maps this error to.
  [[nodiscard]] virtual int exit_code() const noexcept { return 1; }

 private:
  static std::string printable(std::string s) {
    for (std::size_t k = s.find('\0'); k != std::string::npos; k = s.find('\0', k + 2)) s.replace(k, 1, "\\0");
    return s;
  }
};

/// A bad configuration key or value, or a bad command-line argument (exit 2).
class ConfigError : public Error {
 public:
  using Error::Error;
  [[nodiscard]] int exit_code() const noexcept override { return 2; }
};

/// Unreadable, missing or unusable input data (raster, contour, grid file) (exit 1).
class InputError : public Error {
 public:
  using Error::Error;
};

/// An output could not be written (directory not writable, disk full) (exit 1).
class OutputError : public Error {
 public:
  using Error::Error;
};

/// A numerical method failed: no convergence, degenerate geometry (exit 1).
class NumericalError : public Error {
 public:
  using Error::Error;
};

/// A broken internal invariant: a bug, reported instead of writing bad output (exit 1).
class InternalError : public Error {
 public:
  using Error::Error;
};

}  // namespace aq
