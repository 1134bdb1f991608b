// SPDX-License-Identifier: GPL-3.0-or-later
// Gmsh MSH 4.1 writer (see msh_writer.hpp for the layout).
#include "mesh_files/msh_writer.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "io/depth.hpp"
#include "io/file_writer.hpp"
#include "mesh_files/pole_merge.hpp"
#include "mesh_files/seam_nodes.hpp"

namespace aq::io {

namespace {

constexpr int kTypeLine = 1, kTypeTriangle = 2, kTypeQuad = 3;
constexpr int kCurveCoast = 1, kCurveSeam = 2, kCurveSeamCopy = 3, kCurveOpen = 4, kCurveIsland = 5, kCurveRiver = 6;
constexpr int kPhysCoast = 1, kPhysOcean = 2, kPhysOceanSquares = 3, kPhysOpen = 4, kPhysIsland = 5, kPhysRiver = 6;

// Writes MSH tokens either as ASCII words separated by spaces or as native binary values.
class MshOut {
 public:
  MshOut(FileWriter& file, bool binary) : f_(file), binary_(binary) {}
  [[nodiscard]] bool binary() const { return binary_; }
  FileWriter& file() { return f_; }

  void size(std::uint64_t v) {
    if (binary_) {
      f_.put(v);
    } else {
      sep();
      fmt::format_to(std::back_inserter(f_.buffer()), FMT_COMPILE("{}"), v);
    }
  }
  void i32(std::int32_t v) {
    if (binary_) {
      f_.put(v);
    } else {
      sep();
      fmt::format_to(std::back_inserter(f_.buffer()), FMT_COMPILE("{}"), v);
    }
  }
  void f64(double v) {
    if (binary_) {
      f_.put(v);
    } else {
      sep();
      fmt::format_to(std::back_inserter(f_.buffer()), FMT_COMPILE("{}"), v);
    }
  }
  void eol() {
    if (!binary_) f_.text("\n");
    first_ = true;
    f_.maybe_flush();
  }
  void begin(std::string_view section) {
    f_.print("${}\n", section);
    first_ = true;
  }
  void end(std::string_view section) {
    if (binary_) f_.text("\n");
    f_.print("$End{}\n", section);
    f_.maybe_flush();
  }

 private:
  void sep() {
    if (!first_) f_.text(" ");
    first_ = false;
  }
  FileWriter& f_;
  bool binary_;
  bool first_ = true;
};

struct Box {
  double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity()};
  double hi[3] = {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                  -std::numeric_limits<double>::infinity()};
  void add(const std::array<double, 3>& p) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  }
  void write(MshOut& out) const {
    const bool empty = lo[0] > hi[0];
    for (int a = 0; a < 3; ++a) out.f64(empty ? 0.0 : lo[a]);
    for (int a = 0; a < 3; ++a) out.f64(empty ? 0.0 : hi[a]);
  }
};

// The written node set: output ids 0..count-1 (tag = id + 1), their positions, and the mesh
// node whose data each one carries.
class NodeSet {
 public:
  NodeSet(const mesh::Mesh& mesh, const MshOptions& options)
      : mesh_(mesh), plane_(options.coordinates == MshCoordinates::kPlane) {
    if (plane_) {
      seam_.emplace(mesh, options.elements);
    } else {
      merge_.emplace(mesh);
    }
  }
  [[nodiscard]] bool plane() const { return plane_; }
  [[nodiscard]] const SeamNodes& seam() const { return *seam_; }    // plane only
  [[nodiscard]] const PoleMerge& merge() const { return *merge_; }  // sphere only
  [[nodiscard]] std::int64_t duplicates() const { return plane_ ? seam_->count() : 0; }
  [[nodiscard]] std::int64_t count() const {
    return plane_ ? mesh_.node_count() + seam_->count() : merge_->output_count();
  }
  [[nodiscard]] NodeId source(NodeId o) const {
    if (!plane_) return merge_->source(o);
    return o < mesh_.node_count() ? o : seam_->originals()[static_cast<std::size_t>(o - mesh_.node_count())];
  }
  [[nodiscard]] std::array<double, 3> position(NodeId o) const {
    const NodeId n = source(o);
    if (plane_) {
      const std::int64_t i = o < mesh_.node_count() ? mesh_.node_i[n] : mesh_.lattice.nx;
      return {plane_lon_deg(mesh_.lattice, i) + mesh_.plane_dx_deg(n), mesh_.plane_y_deg(n), 0.0};
    }
    const double lo = mesh_.lon_deg[n] * kDegToRad, la = mesh_.lat_deg[n] * kDegToRad;
    return {std::cos(la) * std::cos(lo), std::cos(la) * std::sin(lo), std::sin(la)};
  }

 private:
  const mesh::Mesh& mesh_;
  bool plane_;
  std::optional<SeamNodes> seam_;
  std::optional<PoleMerge> merge_;
};

// The element blocks. Each is streamed twice at most (count, then write) straight from the
// mesh arrays, so a 10-million-triangle mesh is never copied.
enum class BlockKind { kTriangles, kQuads, kCollapsedQuads, kCoast };

struct Block {
  BlockKind kind;
  int dim, entity, type, nodes_per_element;
  std::int64_t count = 0;
  int physical = kPhysCoast;                    ///< kCoast: the curve's physical group
  const std::vector<std::size_t>* edges = nullptr;  ///< kCoast of a typed mesh: its boundary edges
};

class Blocks {
 public:
  Blocks(const mesh::Mesh& mesh, const NodeSet& nodes, ElementKinds kinds) : mesh_(mesh), nodes_(nodes) {
    const int square_entity = kinds == ElementKinds::kBoth ? 2 : 1;
    if (has_triangles(kinds) && !mesh.triangles.empty()) add({BlockKind::kTriangles, 2, 1, kTypeTriangle, 3});
    if (has_squares(kinds) && !mesh.squares.empty()) {
      add({BlockKind::kQuads, 2, square_entity, kTypeQuad, 4});
      if (!nodes.plane()) add({BlockKind::kCollapsedQuads, 2, square_entity, kTypeTriangle, 3});
    }
    const bool typed = mesh.typed && mesh.boundary_edge_type.size() == mesh.boundary_edges.size();
    if (typed) {  // one curve per boundary type (README "Regional FE meshes")
      for (std::size_t e = 0; e < mesh.boundary_edges.size(); ++e)
        typed_edges_[static_cast<std::size_t>(mesh.boundary_edge_type[e])].push_back(e);
      const int curve[4] = {kCurveCoast, kCurveIsland, kCurveOpen, kCurveRiver};
      const int phys[4] = {kPhysCoast, kPhysIsland, kPhysOpen, kPhysRiver};
      for (const std::size_t t : {std::size_t{0}, std::size_t{2}, std::size_t{1}, std::size_t{3}}) {
        if (typed_edges_[t].empty()) continue;
        Block b{BlockKind::kCoast, 1, curve[t], kTypeLine, 2};
        b.physical = phys[t];
        b.edges = &typed_edges_[t];
        add(b);
      }
    } else if (!mesh.boundary_edges.empty()) {
      add({BlockKind::kCoast, 1, kCurveCoast, kTypeLine, 2});
    }
    if (!nodes.plane()) {
      if (has_triangles(kinds)) dropped_ += static_cast<std::int64_t>(mesh.triangles.size());
      if (has_squares(kinds)) dropped_ += static_cast<std::int64_t>(mesh.squares.size());
      for (const auto& b : list_)
        if (b.dim == 2) dropped_ -= b.count;
    }
  }
  [[nodiscard]] const std::vector<Block>& list() const { return list_; }
  [[nodiscard]] std::int64_t dropped() const { return dropped_; }
  [[nodiscard]] std::int64_t total(int dim) const {
    std::int64_t t = 0;
    for (const auto& b : list_)
      if (dim < 0 || b.dim == dim) t += b.count;
    return t;
  }

  // In the plane every element of the mesh arrays is written, in order: element k of block `b`
  // (its node ids, -1 for a missing seam duplicate) and its level, without visiting the others.
  // Lets the binary writer fill its records on all threads.
  [[nodiscard]] bool random_access() const { return nodes_.plane(); }
  void element(const Block& b, std::int64_t k, std::array<NodeId, 4>& out) const {
    const mesh::Mesh& m = mesh_;
    const SeamNodes& seam = nodes_.seam();
    const auto u = static_cast<std::size_t>(k);
    switch (b.kind) {
      case BlockKind::kTriangles:
        for (int a = 0; a < 3; ++a) out[a] = seam.plane_node(m, m.triangles[u], m.triangles[u][a]);
        return;
      case BlockKind::kQuads:
      case BlockKind::kCollapsedQuads:
        for (int a = 0; a < 4; ++a) out[a] = seam.plane_node(m, m.squares[u], m.squares[u][a]);
        return;
      case BlockKind::kCoast: {
        const auto p = seam.plane_edge(m, m.boundary_edges[b.edges != nullptr ? (*b.edges)[u] : u]);
        out[0] = p[0];
        out[1] = p[1];
        return;
      }
    }
  }
  [[nodiscard]] int level(const Block& b, std::int64_t k) const {
    const auto u = static_cast<std::size_t>(k);
    switch (b.kind) {
      case BlockKind::kTriangles:
        return mesh_.triangle_level[u];
      case BlockKind::kQuads:
      case BlockKind::kCollapsedQuads:
        return mesh_.square_level[u];
      case BlockKind::kCoast:
        return 0;
    }
    return 0;
  }

  // Calls sink(const std::uint64_t* node_tags, int level) for every element of block `b`.
  template <typename Sink>
  void visit(const Block& b, Sink&& sink) const {
    std::array<std::uint64_t, 4> tags{};
    std::array<NodeId, 4> out{};
    const mesh::Mesh& m = mesh_;
    const bool plane = nodes_.plane();
    const SeamNodes* seam = plane ? &nodes_.seam() : nullptr;
    const PoleMerge* merge = plane ? nullptr : &nodes_.merge();
    switch (b.kind) {
      case BlockKind::kTriangles:
        for (std::size_t t = 0; t < m.triangles.size(); ++t) {
          const auto& tri = m.triangles[t];
          if (plane) {
            for (int a = 0; a < 3; ++a) tags[a] = tag(seam->plane_node(m, tri, tri[a]));
          } else {
            if (merge->map_polygon(tri.data(), 3, out.data()) < 3) continue;
            for (int a = 0; a < 3; ++a) tags[a] = tag(out[a]);
          }
          sink(tags.data(), m.triangle_level[t]);
        }
        break;
      case BlockKind::kQuads:
      case BlockKind::kCollapsedQuads:
        for (std::size_t s = 0; s < m.squares.size(); ++s) {
          const auto& sq = m.squares[s];
          if (plane) {
            for (int a = 0; a < 4; ++a) tags[a] = tag(seam->plane_node(m, sq, sq[a]));
          } else {
            const int k = merge->map_polygon(sq.data(), 4, out.data());
            if (k != b.nodes_per_element) continue;
            for (int a = 0; a < k; ++a) tags[a] = tag(out[a]);
          }
          sink(tags.data(), m.square_level[s]);
        }
        break;
      case BlockKind::kCoast:
        for (std::size_t q = 0, nq = b.edges != nullptr ? b.edges->size() : m.boundary_edges.size(); q < nq; ++q) {
          const auto& e = m.boundary_edges[b.edges != nullptr ? (*b.edges)[q] : q];
          if (plane) {
            const auto p = seam->plane_edge(m, e);
            tags[0] = tag(p[0]);
            tags[1] = tag(p[1]);
          } else {
            out[0] = merge->map(e[0]);
            out[1] = merge->map(e[1]);
            if (out[0] == out[1]) continue;  // an edge along a pole row
            tags[0] = tag(out[0]);
            tags[1] = tag(out[1]);
          }
          sink(tags.data(), 0);
        }
        break;
    }
  }

 private:
  static std::uint64_t tag(NodeId o) {
    if (o < 0) throw InternalError("MSH writer: an element uses a seam node that has no duplicate");
    return static_cast<std::uint64_t>(o) + 1;
  }
  void add(Block b) {
    if (nodes_.plane()) {
      b.count = b.kind == BlockKind::kTriangles ? mesh_.triangle_count()
                : b.kind == BlockKind::kQuads   ? mesh_.square_count()
                : b.edges != nullptr            ? static_cast<std::int64_t>(b.edges->size())
                                                : static_cast<std::int64_t>(mesh_.boundary_edges.size());
    } else {
      visit(b, [&](const std::uint64_t*, int) { ++b.count; });
    }
    if (b.count > 0) list_.push_back(b);
  }

  const mesh::Mesh& mesh_;
  const NodeSet& nodes_;
  std::vector<Block> list_;
  std::array<std::vector<std::size_t>, 4> typed_edges_;  ///< by mesh::BoundaryType
  std::int64_t dropped_ = 0;
};

void write_header(MshOut& out, ElementKinds kinds, bool typed, bool rivers) {
  FileWriter& f = out.file();
  f.text("$MeshFormat\n");
  if (out.binary()) {
    f.text("4.1 1 8\n");
    f.put(std::int32_t{1});
    f.text("\n");
  } else {
    f.text("4.1 0 8\n");
  }
  f.text("$EndMeshFormat\n");
  // Physical names are ASCII in both modes.
  const bool both = kinds == ElementKinds::kBoth;
  f.print("$PhysicalNames\n{}\n", (both ? 3 : 2) + (typed ? 2 : 0) + (rivers ? 1 : 0));
  f.print("1 {} \"{}\"\n2 {} \"ocean\"\n", kPhysCoast, typed ? "mainland" : "coast", kPhysOcean);
  if (both) f.print("2 {} \"ocean_squares\"\n", kPhysOceanSquares);
  if (typed) f.print("1 {} \"open\"\n1 {} \"island\"\n", kPhysOpen, kPhysIsland);
  if (rivers) f.print("1 {} \"river\"\n", kPhysRiver);
  f.text("$EndPhysicalNames\n");
}

void write_entities(MshOut& out, const mesh::Mesh& mesh, const NodeSet& nodes, const Blocks& blocks,
                    ElementKinds kinds) {
  const bool seam_curves = nodes.duplicates() > 0;
  const bool both = kinds == ElementKinds::kBoth;
  Box all, coast, seam, seam_copy;
  for (NodeId o = 0; o < nodes.count(); ++o) all.add(nodes.position(o));
  // A typed (regional) mesh has one curve per boundary type present, each with its own box.
  std::vector<std::pair<const Block*, Box>> typed_curves;
  for (const auto& b : blocks.list()) {
    if (b.kind != BlockKind::kCoast) continue;
    Box box;
    blocks.visit(b, [&](const std::uint64_t* t, int) {
      coast.add(nodes.position(static_cast<NodeId>(t[0]) - 1));
      coast.add(nodes.position(static_cast<NodeId>(t[1]) - 1));
      box.add(nodes.position(static_cast<NodeId>(t[0]) - 1));
      box.add(nodes.position(static_cast<NodeId>(t[1]) - 1));
    });
    if (b.edges != nullptr) typed_curves.emplace_back(&b, box);
  }
  if (seam_curves) {
    const auto& orig = nodes.seam().originals();
    for (std::size_t k = 0; k < orig.size(); ++k) {
      seam.add(nodes.position(orig[k]));
      seam_copy.add(nodes.position(mesh.node_count() + static_cast<NodeId>(k)));
    }
  }
  out.begin("Entities");
  out.size(0);
  out.size((seam_curves ? 2 : 0) + (typed_curves.empty() ? 1 : typed_curves.size()));
  out.size(both ? 2 : 1);
  out.size(0);
  out.eol();
  auto curve = [&](int tag, const Box& box, bool physical, int group = kPhysCoast) {
    out.i32(tag);
    box.write(out);
    out.size(physical ? 1 : 0);
    if (physical) out.i32(group);
    out.size(0);
    out.eol();
  };
  if (typed_curves.empty()) curve(kCurveCoast, coast, true);
  for (const auto& [b, box] : typed_curves) curve(b->entity, box, true, b->physical);
  if (seam_curves) {
    curve(kCurveSeam, seam, false);
    curve(kCurveSeamCopy, seam_copy, false);
  }
  auto surface = [&](int tag, int physical) {
    out.i32(tag);
    all.write(out);
    out.size(1);
    out.i32(physical);
    out.size(0);
    out.eol();
  };
  surface(1, kPhysOcean);
  if (both) surface(2, kPhysOceanSquares);
  out.end("Entities");
}

// Writes one $Nodes block; `ids(fn)` calls fn(output id) for every node of the block in order.
template <typename Ids>
void write_node_block(MshOut& out, const NodeSet& nodes, int dim, int tag, std::int64_t count, Ids ids) {
  out.i32(dim);
  out.i32(tag);
  out.i32(0);
  out.size(static_cast<std::uint64_t>(count));
  out.eol();
  FileWriter& f = out.file();
  auto& buf = f.buffer();
  if (out.binary()) {
    ids([&](NodeId o) {
      f.put(static_cast<std::uint64_t>(o + 1));
      f.maybe_flush();
    });
    ids([&](NodeId o) {
      const auto p = nodes.position(o);
      f.bytes(p.data(), sizeof(double) * 3);
      f.maybe_flush();
    });
    return;
  }
  ids([&](NodeId o) {
    fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{}\n"), o + 1);
    f.maybe_flush();
  });
  ids([&](NodeId o) {
    const auto p = nodes.position(o);
    fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{} {} {}\n"), p[0], p[1], p[2]);
    f.maybe_flush();
  });
}

void write_nodes(MshOut& out, const mesh::Mesh& mesh, const NodeSet& nodes) {
  const std::int64_t total = nodes.count();
  const std::vector<NodeId> none;
  const auto& orig = nodes.plane() ? nodes.seam().originals() : none;
  const std::int64_t dups = nodes.duplicates();
  const std::int64_t surface = total - 2 * dups;  // plane: seam originals live on curve 2
  const int blocks = (surface > 0 ? 1 : 0) + (dups > 0 ? 2 : 0);
  out.begin("Nodes");
  out.size(static_cast<std::uint64_t>(blocks));
  out.size(static_cast<std::uint64_t>(total));
  out.size(total > 0 ? 1 : 0);
  out.size(static_cast<std::uint64_t>(total));
  out.eol();
  if (surface > 0) {
    write_node_block(out, nodes, 2, 1, surface, [&](auto&& fn) {
      const std::int64_t n = dups > 0 ? mesh.node_count() : total;
      std::size_t k = 0;
      for (NodeId o = 0; o < n; ++o) {
        if (dups > 0 && k < orig.size() && orig[k] == o) {
          ++k;
          continue;
        }
        fn(o);
      }
    });
  }
  if (dups > 0) {
    write_node_block(out, nodes, 1, kCurveSeam, dups, [&](auto&& fn) {
      for (const NodeId o : orig) fn(o);
    });
    write_node_block(out, nodes, 1, kCurveSeamCopy, dups, [&](auto&& fn) {
      for (NodeId k = 0; k < dups; ++k) fn(mesh.node_count() + k);
    });
  }
  out.end("Nodes");
}

// Appends `count` binary records of `size` bytes, record k written by fill(k, dst), filled by the
// OpenMP threads in batches (the bytes a serial loop would write; the 1' run's 8.8 million
// triangles took a second on one thread). fill returns false for a record it cannot write;
// then nothing more is appended and false is returned.
template <typename Fill>
bool put_records(FileWriter& f, std::int64_t count, std::size_t size, const Fill& fill) {
  constexpr std::int64_t kBatch = std::int64_t{1} << 18;
  auto& buf = f.buffer();
  for (std::int64_t k0 = 0; k0 < count; k0 += kBatch) {
    const std::int64_t n = std::min(kBatch, count - k0);
    const std::size_t at = buf.size();
    buf.resize(at + static_cast<std::size_t>(n) * size);
    char* base = buf.data() + at;
    int bad = 0;
#pragma omp parallel for schedule(static) default(none) shared(fill, base, k0, n, size) reduction(| : bad) \
    if (n >= 4096)
    for (std::int64_t k = 0; k < n; ++k)
      if (!fill(k0 + k, base + static_cast<std::size_t>(k) * size)) bad = 1;
    if (bad != 0) return false;
    f.maybe_flush();
  }
  return true;
}

void write_elements(MshOut& out, const Blocks& blocks) {
  const std::int64_t total = blocks.total(-1);
  out.begin("Elements");
  out.size(blocks.list().size());
  out.size(static_cast<std::uint64_t>(total));
  out.size(total > 0 ? 1 : 0);
  out.size(static_cast<std::uint64_t>(total));
  out.eol();
  FileWriter& f = out.file();
  auto& buf = f.buffer();
  std::uint64_t tag = 1;
  for (const auto& b : blocks.list()) {
    out.i32(b.dim);
    out.i32(b.entity);
    out.i32(b.type);
    out.size(static_cast<std::uint64_t>(b.count));
    out.eol();
    const auto k = static_cast<std::size_t>(b.nodes_per_element);
    if (out.binary() && blocks.random_access()) {
      const std::uint64_t first = tag;
      const bool ok = put_records(f, b.count, sizeof(std::uint64_t) * (k + 1), [&](std::int64_t e, char* dst) {
        std::array<NodeId, 4> nodes{};
        blocks.element(b, e, nodes);
        std::array<std::uint64_t, 5> rec{};
        rec[0] = first + static_cast<std::uint64_t>(e);
        for (std::size_t a = 0; a < k; ++a) {
          if (nodes[a] < 0) return false;
          rec[a + 1] = static_cast<std::uint64_t>(nodes[a]) + 1;
        }
        std::memcpy(dst, rec.data(), sizeof(std::uint64_t) * (k + 1));
        return true;
      });
      if (!ok) throw InternalError("MSH writer: an element uses a seam node that has no duplicate");
      tag += static_cast<std::uint64_t>(b.count);
    } else if (out.binary()) {
      std::array<std::uint64_t, 5> rec{};
      blocks.visit(b, [&](const std::uint64_t* t, int) {
        rec[0] = tag++;
        std::copy_n(t, k, rec.begin() + 1);
        f.bytes(rec.data(), sizeof(std::uint64_t) * (k + 1));
        f.maybe_flush();
      });
    } else {
      blocks.visit(b, [&](const std::uint64_t* t, int) {
        fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{}"), tag++);
        for (std::size_t a = 0; a < k; ++a) fmt::format_to(std::back_inserter(buf), FMT_COMPILE(" {}"), t[a]);
        buf.push_back('\n');
        f.maybe_flush();
      });
    }
  }
  out.end("Elements");
}

void write_periodic(MshOut& out, const mesh::Mesh& mesh, const NodeSet& nodes) {
  const auto& orig = nodes.seam().originals();
  out.begin("Periodic");
  out.size(1);
  out.eol();
  out.i32(1);
  out.i32(kCurveSeamCopy);
  out.i32(kCurveSeam);
  out.eol();
  // Affine transform master -> slave, 4x4 row-major: translation by +360 in x.
  const double affine[16] = {1, 0, 0, 360, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  out.size(16);
  for (const double v : affine) out.f64(v);
  out.eol();
  out.size(orig.size());
  out.eol();
  for (std::size_t k = 0; k < orig.size(); ++k) {
    out.size(static_cast<std::uint64_t>(mesh.node_count()) + k + 1);
    out.size(static_cast<std::uint64_t>(orig[k] + 1));
    out.eol();
  }
  out.end("Periodic");
}

// $NodeData / $ElementData holding one scalar view. `records(fn)` calls fn(tag, value) for each
// record in order; the binary records are (int32 tag, float64 value).
template <typename Records>
void write_data(MshOut& out, std::string_view section, std::string_view view, std::int64_t count, Records records) {
  FileWriter& f = out.file();
  f.print("${}\n1\n\"{}\"\n1\n0\n3\n0\n1\n{}\n", section, view, count);
  auto& buf = f.buffer();
  if (out.binary()) {
    records([&](std::int64_t tag, double v) {
      f.put(static_cast<std::int32_t>(tag));
      f.put(v);
      f.maybe_flush();
    });
    f.text("\n");
  } else {
    records([&](std::int64_t tag, double v) {
      fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{} {}\n"), tag, v);
      f.maybe_flush();
    });
  }
  f.print("$End{}\n", section);
}

}  // namespace

WriteStats write_msh(const mesh::Mesh& mesh, const std::filesystem::path& path, const MshOptions& options) {
  check_elements(mesh, options.elements);
  const NodeSet nodes(mesh, options);
  const Blocks blocks(mesh, nodes, options.elements);
  if (nodes.count() > std::numeric_limits<std::int32_t>::max() ||
      blocks.total(-1) > std::numeric_limits<std::int32_t>::max()) {
    throw OutputError(fmt::format("{}: mesh too large for MSH 4.1 (its data sections use 32-bit tags)", path.string()));
  }

  FileWriter file(path);
  MshOut out(file, options.binary);
  const bool typed = mesh.typed && mesh.boundary_edge_type.size() == mesh.boundary_edges.size();
  write_header(out, options.elements, typed,
               typed && std::find(mesh.boundary_edge_type.begin(), mesh.boundary_edge_type.end(),
                                  mesh::BoundaryType::kRiver) != mesh.boundary_edge_type.end());
  write_entities(out, mesh, nodes, blocks, options.elements);
  write_nodes(out, mesh, nodes);
  write_elements(out, blocks);
  if (nodes.duplicates() > 0) write_periodic(out, mesh, nodes);

  auto node_view = [&](std::string_view name, auto value) {
    if (out.binary()) {  // the records of write_data, filled on all threads
      file.print("$NodeData\n1\n\"{}\"\n1\n0\n3\n0\n1\n{}\n", name, nodes.count());
      put_records(file, nodes.count(), sizeof(std::int32_t) + sizeof(double), [&](std::int64_t o, char* dst) {
        const auto t = static_cast<std::int32_t>(o + 1);
        const double v = value(nodes.source(o));
        std::memcpy(dst, &t, sizeof t);
        std::memcpy(dst + sizeof t, &v, sizeof v);
        return true;
      });
      file.text("\n$EndNodeData\n");
      return;
    }
    write_data(out, "NodeData", name, nodes.count(), [&](auto&& fn) {
      for (NodeId o = 0; o < nodes.count(); ++o) fn(o + 1, value(nodes.source(o)));
    });
  };
  node_view("depth_m", [&](NodeId n) { return depth_below_datum_m(mesh.depth_m[n]); });
  if (nodes.plane() && mesh.rotation.enabled) {
    node_view("lon_deg", [&](NodeId n) { return mesh.lon_deg[n]; });
    node_view("lat_deg", [&](NodeId n) { return mesh.lat_deg[n]; });
  }
  if (out.binary() && blocks.random_access()) {
    // The same records as below, (int32 tag, float64 level), filled on all threads.
    file.print("$ElementData\n1\n\"level\"\n1\n0\n3\n0\n1\n{}\n", blocks.total(2));
    std::int32_t tag = 1;
    for (const auto& b : blocks.list()) {
      if (b.dim != 2) continue;
      const std::int32_t first = tag;
      put_records(file, b.count, sizeof(std::int32_t) + sizeof(double), [&](std::int64_t e, char* dst) {
        const auto t = static_cast<std::int32_t>(first + e);
        const auto level = static_cast<double>(blocks.level(b, e));
        std::memcpy(dst, &t, sizeof t);
        std::memcpy(dst + sizeof t, &level, sizeof level);
        return true;
      });
      tag += static_cast<std::int32_t>(b.count);
    }
    file.text("\n$EndElementData\n");
  } else {
    write_data(out, "ElementData", "level", blocks.total(2), [&](auto&& fn) {
      std::int64_t tag = 1;
      for (const auto& b : blocks.list())
        if (b.dim == 2) blocks.visit(b, [&](const std::uint64_t*, int level) { fn(tag++, level); });
    });
  }

  WriteStats stats;
  stats.bytes = file.close();
  stats.nodes = nodes.count();
  stats.elements = blocks.total(2);
  stats.boundary_edges = blocks.total(1);
  stats.seam_duplicates = nodes.duplicates();
  stats.merged_pole_nodes = nodes.plane() ? 0 : nodes.merge().merged();
  stats.dropped_elements = blocks.dropped();
  return stats;
}

}  // namespace aq::io
