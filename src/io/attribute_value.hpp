// SPDX-License-Identifier: GPL-3.0-or-later
// The value of an attribute of aquatoria's netCDF files (written by io::put_attribute,
// netcdf_file.hpp): text, a real number or an integer.
#pragma once

#include <cstdint>
#include <string>
#include <variant>

namespace aq::io {

using AttributeValue = std::variant<std::string, double, std::int64_t>;

}  // namespace aq::io
