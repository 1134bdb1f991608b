// Error types of aquatoria. The library throws; only src/app prints and exits.
// Exit codes (ARCHITECTURE §7): ConfigError and UsageError -> 2, every other aq::Error -> 1.
#pragma once

#include <stdexcept>
#include <string>

namespace aq {

/// Base of every error aquatoria throws. The message names the file, key or value at fault.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  /// Process exit code the command line maps this error to.
  [[nodiscard]] virtual int exit_code() const noexcept { return 1; }
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
