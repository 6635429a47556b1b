#include "tools/gen/furniture.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <unordered_map>

#include "compiler/import/mesh_reader.hpp"
#include "model/error.hpp"

namespace walk::gen {
namespace {

using model::Vec3;

// What qualifies as furniture, metres: standing on the floor (lowest point within kFloorContact of the
// model's floor), a footprint no larger than a conference table and not a sliver, and tall enough to be seen.
constexpr double kFloorContact = 0.02;
constexpr double kMinFootprint = 0.15, kMaxFootprint = 3.0;
constexpr double kMinHeight = 0.2, kMaxHeight = 2.0;
// A table top: a slab thinner than this, at least kMinSlab across, joined to what stands under it.
constexpr double kMaxSlabThickness = 0.1, kMinSlab = 0.5;
// Shapes whose triangle counts are equal and whose extents agree to this (metres) are the same object: the
// room holds copies of one chair turned by a few degrees, whose boxes differ by up to 4 cm.
constexpr double kSameShape = 0.05;

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void join(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the root is the first face: a stable order
  }
};

struct Cell {
  std::int64_t x, y, z;
  bool operator==(const Cell&) const = default;
};
struct CellHash {
  std::size_t operator()(const Cell& c) const {
    return std::size_t(c.x * 73856093) ^ std::size_t(c.y * 19349663) ^ std::size_t(c.z * 83492791);
  }
};

// Faces whose corners share a kPieceGap cell, or lie in neighbouring cells, are joined: every pair of
// corners closer than kPieceGap is caught, and none farther than about 3.5 kPieceGap.
void join_close_faces(const model::Model& m, UnionFind& uf) {
  std::unordered_map<Cell, std::uint32_t, CellHash> first;
  for (std::uint32_t f = 0; f < m.polygons.size(); ++f)
    for (const Vec3& p : m.polygons[f].vertices) {
      const Cell c{std::int64_t(std::floor(p.x / kPieceGap)), std::int64_t(std::floor(p.y / kPieceGap)),
                   std::int64_t(std::floor(p.z / kPieceGap))};
      const auto [it, added] = first.emplace(c, f);
      if (!added) uf.join(it->second, f);
    }
  for (const auto& [c, f] : first)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = first.find({c.x + dx, c.y + dy, c.z + dz});
          if (it != first.end()) uf.join(it->second, f);
        }
}

struct Piece {
  std::vector<std::uint32_t> faces;
  model::Bounds box;
  std::size_t triangles = 0;
};

bool within_xy(const model::Bounds& inner, const model::Bounds& outer, double slack) {
  return inner.min.x >= outer.min.x - slack && inner.max.x <= outer.max.x + slack &&
         inner.min.y >= outer.min.y - slack && inner.max.y <= outer.max.y + slack;
}

}  // namespace

FurnitureCatalogue cut_furniture(const std::string& path, double scale) {
  compiler::MeshOptions options;
  options.unit_scale = scale;
  options.y_up = true;
  compiler::MeshStats stats;
  const model::Model m = compiler::read_mesh(path, options, &stats);

  UnionFind uf(m.polygons.size());
  join_close_faces(m, uf);
  std::map<std::uint32_t, Piece> by_root;  // ordered by first face: the file's order
  for (std::uint32_t f = 0; f < m.polygons.size(); ++f) {
    Piece& piece = by_root[uf.find(f)];
    piece.faces.push_back(f);
    for (const Vec3& p : m.polygons[f].vertices) piece.box.add(p);
    piece.triangles += m.polygons[f].vertices.size() - 2;
  }
  std::vector<Piece> pieces;
  for (auto& [root, piece] : by_root) pieces.push_back(std::move(piece));
  const double floor_z = model::bounds_of(m).min.z;

  // A table top takes the pieces that stand under it and reach up to it (its legs or pedestal), not
  // those that rise past it (chairs pushed under the table).
  std::vector<bool> taken(pieces.size(), false);
  for (std::size_t s = 0; s < pieces.size(); ++s) {
    const model::Bounds slab = pieces[s].box;
    const Vec3 size = slab.size();
    if (taken[s] || size.z > kMaxSlabThickness || std::min(size.x, size.y) < kMinSlab ||
        slab.min.z - floor_z < kMinHeight)
      continue;
    for (std::size_t p = 0; p < pieces.size(); ++p) {
      if (p == s || taken[p]) continue;
      const model::Bounds& leg = pieces[p].box;
      if (!within_xy(leg, slab, kPieceGap) || leg.max.z > slab.min.z + kPieceGap) continue;
      pieces[s].faces.insert(pieces[s].faces.end(), pieces[p].faces.begin(), pieces[p].faces.end());
      pieces[s].box.add(leg.min);
      pieces[s].box.add(leg.max);
      pieces[s].triangles += pieces[p].triangles;
      taken[p] = true;
    }
  }

  FurnitureCatalogue cat;
  cat.materials = m.materials;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (taken[i]) continue;
    ++cat.pieces;
    Piece& piece = pieces[i];
    const Vec3 size = piece.box.size();
    const double lo = std::min(size.x, size.y), hi = std::max(size.x, size.y);
    if (piece.box.min.z - floor_z > kFloorContact || lo < kMinFootprint || hi > kMaxFootprint ||
        size.z < kMinHeight || size.z > kMaxHeight)
      continue;
    ++cat.standing;
    const bool seen = std::any_of(cat.objects.begin(), cat.objects.end(), [&](const FurnitureObject& o) {
      return o.triangles == piece.triangles && std::abs(o.size.x - size.x) < kSameShape &&
             std::abs(o.size.y - size.y) < kSameShape && std::abs(o.size.z - size.z) < kSameShape;
    });
    if (seen) continue;
    FurnitureObject obj;
    std::sort(piece.faces.begin(), piece.faces.end());
    obj.name = "object " + std::to_string(piece.faces.front());
    obj.size = size;
    obj.triangles = piece.triangles;
    const Vec3 centre(piece.box.centre().x, piece.box.centre().y, piece.box.min.z);
    std::map<std::array<double, 3>, std::uint32_t> index;
    for (std::uint32_t f : piece.faces) {
      FurnitureObject::Face face;
      face.material = m.polygons[f].material;
      for (const Vec3& p : m.polygons[f].vertices) {
        const Vec3 q = p - centre;
        const auto [it, added] = index.emplace(std::array<double, 3>{q.x, q.y, q.z}, obj.vertices.size());
        if (added) obj.vertices.push_back(q);
        face.corners.push_back(it->second);
      }
      obj.faces.push_back(std::move(face));
    }
    cat.objects.push_back(std::move(obj));
  }
  if (cat.objects.empty())
    throw Error(located(path, 0,
                        "no piece of furniture found (nothing stands on the floor and fits " +
                            std::to_string(kMinFootprint) + "-" + std::to_string(kMaxFootprint) +
                            " m across)",
                        "furnish from a model of a furnished room, such as the shared conference room"));
  return cat;
}

}  // namespace walk::gen
