// SPDX-License-Identifier: GPL-3.0-or-later
// VTK XML UnstructuredGrid writer (see vtu_writer.hpp).
#include "mesh_files/vtu_writer.hpp"

#include <fmt/format.h>
#include <GeographicLib/Geocentric.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/depth.hpp"
#include "io/file_writer.hpp"
#include "mesh_files/pole_merge.hpp"

namespace aq::io {

namespace {

constexpr std::uint8_t kVtkTriangle = 5, kVtkPolygon = 7, kVtkQuad = 9;

// The cells after pole merging, visited in a fixed order (triangles, then squares).
class Cells {
 public:
  Cells(const mesh::Mesh& mesh, const PoleMerge& merge, ElementKinds kinds) : m_(mesh), merge_(merge), kinds_(kinds) {
    visit([&](const NodeId*, int k, int, int) {
      ++count_;
      connectivity_ += k;
    });
    if (has_triangles(kinds)) dropped_ += mesh.triangle_count();
    if (has_squares(kinds)) dropped_ += mesh.square_count();
    dropped_ -= count_;
  }
  [[nodiscard]] std::int64_t count() const { return count_; }
  [[nodiscard]] std::int64_t connectivity() const { return connectivity_; }
  [[nodiscard]] std::int64_t dropped() const { return dropped_; }

  // fn(const NodeId* output_nodes, int k, int level, int kind) for every non-degenerate cell.
  template <typename Fn>
  void visit(Fn&& fn) const {
    std::array<NodeId, kMaxSquarePolygon> in{}, out{};
    if (has_triangles(kinds_)) {
      for (std::size_t t = 0; t < m_.triangles.size(); ++t) {
        const int k = merge_.map_polygon(m_.triangles[t].data(), 3, out.data());
        if (k == 3) fn(out.data(), 3, m_.triangle_level[t], 0);
      }
    }
    if (has_squares(kinds_)) {
      for (ElementId s = 0; s < m_.square_count(); ++s) {
        const int k = merge_.map_polygon(in.data(), square_polygon(m_, s, in), out.data());
        if (k >= 3) fn(out.data(), k, m_.square_level[static_cast<std::size_t>(s)], 1);
      }
    }
  }

 private:
  const mesh::Mesh& m_;
  const PoleMerge& merge_;
  ElementKinds kinds_;
  std::int64_t count_ = 0, connectivity_ = 0, dropped_ = 0;
};

struct ArrayDecl {
  std::string xml;     // the DataArray element without its offset
  std::int64_t bytes;  // payload bytes (without the UInt64 header)
};

}  // namespace

WriteStats write_vtu(const mesh::Mesh& mesh, const std::filesystem::path& path, const VtuOptions& options) {
  check_elements(mesh, options.elements);
  const PoleMerge merge(mesh);
  const Cells cells(mesh, merge, options.elements);
  const std::int64_t np = merge.output_count();
  const std::int64_t nc = cells.count();
  const bool both = options.elements == ElementKinds::kBoth;

  auto decl = [](const char* type, const char* name, int components, std::int64_t bytes) {
    std::string comp = components > 1 ? fmt::format(" NumberOfComponents=\"{}\"", components) : "";
    return ArrayDecl{fmt::format("<DataArray type=\"{}\" Name=\"{}\"{} format=\"appended\"", type, name, comp), bytes};
  };
  const ArrayDecl depth = decl("Float64", "depth_m", 1, np * 8);
  const ArrayDecl flags = decl("UInt8", "flags", 1, np);
  const ArrayDecl lon = decl("Float64", "lon_deg", 1, np * 8);
  const ArrayDecl lat = decl("Float64", "lat_deg", 1, np * 8);
  const ArrayDecl level = decl("UInt8", "level", 1, nc);
  const ArrayDecl kind = decl("UInt8", "kind", 1, nc);
  const ArrayDecl points = decl("Float64", "Points", 3, np * 24);
  const ArrayDecl conn = decl("Int64", "connectivity", 1, cells.connectivity() * 8);
  const ArrayDecl offs = decl("Int64", "offsets", 1, nc * 8);
  const ArrayDecl types = decl("UInt8", "types", 1, nc);

  std::int64_t offset = 0;
  auto place = [&](const ArrayDecl& a, const char* indent) {
    std::string s = fmt::format("{}{} offset=\"{}\"/>\n", indent, a.xml, offset);
    offset += 8 + a.bytes;
    return s;
  };
  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      "  <UnstructuredGrid>\n";
  xml += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", np, nc);
  // One statement per array: the offsets must follow the write order below.
  const char* in = "        ";
  xml += "      <PointData Scalars=\"depth_m\">\n";
  xml += place(depth, in);
  xml += place(flags, in);
  xml += place(lon, in);
  xml += place(lat, in);
  xml += "      </PointData>\n      <CellData Scalars=\"level\">\n";
  xml += place(level, in);
  if (both) xml += place(kind, in);
  xml += "      </CellData>\n      <Points>\n";
  xml += place(points, in);
  xml += "      </Points>\n      <Cells>\n";
  xml += place(conn, in);
  xml += place(offs, in);
  xml += place(types, in);
  xml += "      </Cells>\n";
  xml += "    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _";

  FileWriter f(path);
  f.text(xml);
  auto header = [&](const ArrayDecl& a) { f.put(static_cast<std::uint64_t>(a.bytes)); };
  auto per_point = [&](const ArrayDecl& a, auto value) {
    header(a);
    for (NodeId o = 0; o < np; ++o) {
      f.put(value(merge.source(o)));
      f.maybe_flush();
    }
  };
  per_point(depth, [&](NodeId n) { return depth_below_datum_m(mesh.depth_m[n]); });
  per_point(flags, [&](NodeId n) { return mesh.node_flags[n]; });
  per_point(lon, [&](NodeId n) { return mesh.lon_deg[n]; });
  per_point(lat, [&](NodeId n) { return mesh.lat_deg[n]; });

  header(level);
  cells.visit([&](const NodeId*, int, int lev, int) {
    f.put(static_cast<std::uint8_t>(lev));
    f.maybe_flush();
  });
  if (both) {
    header(kind);
    cells.visit([&](const NodeId*, int, int, int k) {
      f.put(static_cast<std::uint8_t>(k));
      f.maybe_flush();
    });
  }

  header(points);
  const GeographicLib::Geocentric& earth = GeographicLib::Geocentric::WGS84();
  for (NodeId o = 0; o < np; ++o) {
    const NodeId n = merge.source(o);
    std::array<double, 3> x{};
    if (options.coordinates == VtuCoordinates::kWgs84) {
      earth.Forward(mesh.lat_deg[n], mesh.lon_deg[n], 0.0, x[0], x[1], x[2]);
    } else {
      const double lo = mesh.lon_deg[n] * kDegToRad, la = mesh.lat_deg[n] * kDegToRad;
      x = {std::cos(la) * std::cos(lo), std::cos(la) * std::sin(lo), std::sin(la)};
    }
    f.bytes(x.data(), sizeof(x));
    f.maybe_flush();
  }

  header(conn);
  cells.visit([&](const NodeId* v, int k, int, int) {
    for (int a = 0; a < k; ++a) f.put(static_cast<std::int64_t>(v[a]));
    f.maybe_flush();
  });
  header(offs);
  std::int64_t end = 0;
  cells.visit([&](const NodeId*, int k, int, int) {
    end += k;
    f.put(end);
    f.maybe_flush();
  });
  header(types);
  cells.visit([&](const NodeId*, int k, int, int) {
    f.put(k == 3 ? kVtkTriangle : k == 4 ? kVtkQuad : kVtkPolygon);
    f.maybe_flush();
  });
  f.text("\n  </AppendedData>\n</VTKFile>\n");

  WriteStats stats;
  stats.bytes = f.close();
  stats.nodes = np;
  stats.elements = nc;
  stats.boundary_edges = 0;
  stats.merged_pole_nodes = merge.merged();
  stats.dropped_elements = cells.dropped();
  return stats;
}

}  // namespace aq::io
