// SPDX-License-Identifier: GPL-3.0-or-later
// A small independent reader of Gmsh MSH 4.1 files (ASCII and binary) for the writer tests. It
// follows the format description (Gmsh manual, "MSH file format"), not our writer, and fails
// loudly (throws std::runtime_error) on anything it does not expect.
#pragma once

#include <array>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace aq::testing {

struct MshFile {
  bool binary = false;
  std::string version;
  std::vector<std::pair<std::pair<int, int>, std::string>> physical_names;  // ((dim, tag), name)
  std::array<std::size_t, 4> entity_counts{};
  std::map<std::pair<int, int>, std::vector<int>> entity_physicals;  // (dim, tag) -> physicals
  std::map<std::pair<int, int>, std::array<double, 6>> entity_boxes;
  std::map<std::size_t, std::array<double, 3>> nodes;      // tag -> x, y, z
  std::map<std::size_t, std::pair<int, int>> node_entity;  // tag -> (dim, tag)
  std::size_t nodes_declared = 0, min_node = 0, max_node = 0;
  struct Element {
    std::size_t tag;
    int type, dim, entity;
    std::vector<std::size_t> nodes;
  };
  std::vector<Element> elements;
  std::size_t elements_declared = 0;
  struct Periodic {
    int dim, slave, master;
    std::vector<double> affine;
    std::vector<std::pair<std::size_t, std::size_t>> pairs;  // (slave node, master node)
  };
  std::vector<Periodic> periodic;
  std::map<std::string, std::map<std::size_t, double>> node_data, element_data;
  std::vector<std::string> sections;  // in file order

  [[nodiscard]] std::size_t count_type(int type) const {
    std::size_t n = 0;
    for (const auto& e : elements) n += e.type == type ? 1 : 0;
    return n;
  }
};

namespace detail {

class MshCursor {
 public:
  explicit MshCursor(std::string bytes) : s_(std::move(bytes)) {}
  bool binary = false;
  [[nodiscard]] bool eof() const { return p_ >= s_.size(); }
  std::string line() {
    const std::size_t e = s_.find('\n', p_);
    if (e == std::string::npos) throw std::runtime_error("msh: unexpected end of file");
    std::string l = s_.substr(p_, e - p_);
    p_ = e + 1;
    if (!l.empty() && l.back() == '\r') l.pop_back();
    return l;
  }
  std::string word() {
    while (p_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[p_]))) ++p_;
    const std::size_t b = p_;
    while (p_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[p_]))) ++p_;
    if (b == p_) throw std::runtime_error("msh: expected a token");
    return s_.substr(b, p_ - b);
  }
  template <typename T>
  T raw() {
    if (p_ + sizeof(T) > s_.size()) throw std::runtime_error("msh: binary data truncated");
    T v;
    std::memcpy(&v, s_.data() + p_, sizeof(T));
    p_ += sizeof(T);
    return v;
  }
  std::size_t size() { return binary ? raw<std::uint64_t>() : std::stoull(word()); }
  int i32() { return binary ? raw<std::int32_t>() : std::stoi(word()); }
  double f64() { return binary ? raw<double>() : std::stod(word()); }
  int ascii_int() { return std::stoi(word()); }
  // Skips to the line "$End<name>" (after binary data a newline precedes it).
  void end(const std::string& name) {
    const std::string tag = "$End" + name;
    const std::size_t e = s_.find(tag, p_);
    if (e == std::string::npos) throw std::runtime_error("msh: missing " + tag);
    const std::string gap = s_.substr(p_, e - p_);
    for (const char c : gap)
      if (!std::isspace(static_cast<unsigned char>(c))) throw std::runtime_error("msh: junk before " + tag);
    p_ = e;
    line();
  }

 private:
  std::string s_;
  std::size_t p_ = 0;
};

inline void read_view(MshCursor& c, std::map<std::string, std::map<std::size_t, double>>& out,
                      const std::string& section) {
  const int nstr = std::stoi(c.line());
  std::string name;
  for (int k = 0; k < nstr; ++k) {
    std::string l = c.line();
    if (k == 0) name = l.substr(1, l.size() - 2);
  }
  const int nreal = std::stoi(c.line());
  for (int k = 0; k < nreal; ++k) c.line();
  const int nint = std::stoi(c.line());
  std::vector<long> ints;
  for (int k = 0; k < nint; ++k) ints.push_back(std::stol(c.line()));
  if (nint < 3 || ints[1] != 1) throw std::runtime_error("msh: expected a scalar view");
  auto& values = out[name];
  for (long k = 0; k < ints[2]; ++k) {
    const std::size_t tag = c.binary ? static_cast<std::size_t>(c.raw<std::int32_t>()) : std::stoull(c.word());
    values[tag] = c.binary ? c.raw<double>() : std::stod(c.word());
  }
  c.end(section);
}

}  // namespace detail

inline MshFile parse_msh_bytes(std::string bytes) {
  MshFile f;
  detail::MshCursor c(std::move(bytes));
  while (!c.eof()) {
    const std::string head = c.line();
    if (head.empty()) continue;
    if (head[0] != '$') throw std::runtime_error("msh: expected a section, got '" + head + "'");
    const std::string name = head.substr(1);
    f.sections.push_back(name);
    if (name == "MeshFormat") {
      std::istringstream l(c.line());
      int type = 0, dsize = 0;
      l >> f.version >> type >> dsize;
      if (dsize != 8) throw std::runtime_error("msh: data size must be 8");
      f.binary = c.binary = type == 1;
      if (f.binary && c.raw<std::int32_t>() != 1) throw std::runtime_error("msh: bad endianness marker");
      c.end(name);
    } else if (name == "PhysicalNames") {
      const int n = std::stoi(c.line());
      for (int k = 0; k < n; ++k) {
        std::istringstream l(c.line());
        int dim = 0, tag = 0;
        std::string rest;
        l >> dim >> tag;
        std::getline(l, rest);
        const auto a = rest.find('"'), b = rest.rfind('"');
        f.physical_names.push_back({{dim, tag}, rest.substr(a + 1, b - a - 1)});
      }
      c.end(name);
    } else if (name == "Entities") {
      for (auto& n : f.entity_counts) n = c.size();
      for (int dim = 0; dim < 4; ++dim) {
        for (std::size_t k = 0; k < f.entity_counts[static_cast<std::size_t>(dim)]; ++k) {
          const int tag = c.i32();
          std::array<double, 6> box{};
          for (int a = 0; a < (dim == 0 ? 3 : 6); ++a) box[static_cast<std::size_t>(a)] = c.f64();
          f.entity_boxes[{dim, tag}] = box;
          const std::size_t nphys = c.size();
          auto& phys = f.entity_physicals[{dim, tag}];
          for (std::size_t p = 0; p < nphys; ++p) phys.push_back(c.i32());
          if (dim > 0) {
            const std::size_t nb = c.size();
            for (std::size_t b = 0; b < nb; ++b) c.i32();
          }
        }
      }
      c.end(name);
    } else if (name == "Nodes") {
      const std::size_t blocks = c.size();
      f.nodes_declared = c.size();
      f.min_node = c.size();
      f.max_node = c.size();
      for (std::size_t b = 0; b < blocks; ++b) {
        const int dim = c.i32(), tag = c.i32(), param = c.i32();
        if (param != 0) throw std::runtime_error("msh: parametric nodes not expected");
        const std::size_t n = c.size();
        std::vector<std::size_t> tags(n);
        for (auto& t : tags) t = c.size();
        for (const std::size_t t : tags) {
          std::array<double, 3> x{c.f64(), c.f64(), c.f64()};
          if (!f.nodes.emplace(t, x).second) throw std::runtime_error("msh: duplicate node tag");
          f.node_entity[t] = {dim, tag};
        }
      }
      c.end(name);
    } else if (name == "Elements") {
      const std::size_t blocks = c.size();
      f.elements_declared = c.size();
      c.size();
      c.size();
      for (std::size_t b = 0; b < blocks; ++b) {
        const int dim = c.i32(), tag = c.i32(), type = c.i32();
        const std::size_t n = c.size();
        const int k = type == 1 ? 2 : type == 2 ? 3 : type == 3 ? 4 : -1;
        if (k < 0) throw std::runtime_error("msh: unexpected element type");
        for (std::size_t e = 0; e < n; ++e) {
          MshFile::Element el{c.size(), type, dim, tag, {}};
          for (int a = 0; a < k; ++a) el.nodes.push_back(c.size());
          f.elements.push_back(el);
        }
      }
      c.end(name);
    } else if (name == "Periodic") {
      const std::size_t links = c.size();
      for (std::size_t l = 0; l < links; ++l) {
        MshFile::Periodic p{c.i32(), c.i32(), c.i32(), {}, {}};
        const std::size_t na = c.size();
        for (std::size_t a = 0; a < na; ++a) p.affine.push_back(c.f64());
        const std::size_t np = c.size();
        for (std::size_t a = 0; a < np; ++a) {
          const std::size_t s = c.size();
          p.pairs.push_back({s, c.size()});
        }
        f.periodic.push_back(p);
      }
      c.end(name);
    } else if (name == "NodeData") {
      detail::read_view(c, f.node_data, name);
    } else if (name == "ElementData") {
      detail::read_view(c, f.element_data, name);
    } else {
      throw std::runtime_error("msh: unexpected section $" + name);
    }
  }
  return f;
}

inline std::string read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline MshFile parse_msh(const std::string& path) { return parse_msh_bytes(read_file_bytes(path)); }

}  // namespace aq::testing
