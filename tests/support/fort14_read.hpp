// SPDX-License-Identifier: GPL-3.0-or-later
// Test helper: reads an ADCIRC fort.14 or a SCHISM hgrid.gr3 / .ll (the same layout: a title
// line, "NE NP", NP node lines "id x y depth", NE element lines "id 3 a b c", then NOPE, NETA and
// the open segments, NBOU, NVEL and the land segments "NVELL IBTYPE" with their nodes), the one
// reader of the tests that read our model files back.
#pragma once

#include <array>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace aq::test {

struct Fort14 {
  /// One open or land boundary segment: its nodes (0-based, as listed: a closed land loop repeats
  /// its first node last) and, for a land segment, IBTYPE.
  struct Segment {
    int type = 0;
    std::vector<long> nodes;
  };
  std::string title;
  long elements = 0;                           ///< NE
  std::vector<double> lon, lat, depth;         ///< per node, in file order
  std::vector<std::array<long, 3>> triangles;  ///< 0-based nodes
  long nope = -1, neta = -1, nbou = -1, nvel = -1;
  std::vector<Segment> open, land;
  std::string error;  ///< "" when the whole file was read

  [[nodiscard]] long nodes() const { return static_cast<long>(lon.size()); }
};

/// Reads `p` (a missing or short file gives Fort14::error).
inline Fort14 read_fort14(const std::filesystem::path& p) {
  Fort14 f;
  std::ifstream in(p);
  std::string line;
  std::getline(in, f.title);
  long np = 0;
  in >> f.elements >> np;
  for (long k = 0; k < np && in; ++k) {
    long id = 0;
    double x = 0, y = 0, d = 0;
    in >> id >> x >> y >> d;
    f.lon.push_back(x);
    f.lat.push_back(y);
    f.depth.push_back(d);
  }
  for (long k = 0; k < f.elements && in; ++k) {
    long id = 0, n = 0, a = 0, b = 0, c = 0;
    in >> id >> n >> a >> b >> c;
    f.triangles.push_back({a - 1, b - 1, c - 1});
  }
  const auto count_line = [&](long& v) {  // a count and its comment
    in >> v;
    std::getline(in, line);
  };
  const auto segment = [&](long n, Fort14::Segment& s) {
    for (long k = 0; k < n && in; ++k) {
      long id = 0;
      in >> id;
      s.nodes.push_back(id - 1);
    }
  };
  count_line(f.nope);
  count_line(f.neta);
  for (long s = 0; s < f.nope && in; ++s) {
    Fort14::Segment sg;
    long n = 0;
    count_line(n);
    segment(n, sg);
    f.open.push_back(sg);
  }
  count_line(f.nbou);
  count_line(f.nvel);
  for (long s = 0; s < f.nbou && in; ++s) {
    Fort14::Segment sg;
    long n = 0;
    in >> n >> sg.type;
    std::getline(in, line);
    segment(n, sg);
    f.land.push_back(sg);
  }
  if (!in) f.error = "cannot read or ends early: " + p.string();
  return f;
}

}  // namespace aq::test
