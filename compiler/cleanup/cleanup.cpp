#include "compiler/cleanup/cleanup.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <polyclipping/clipper.hpp>
#include <tuple>
#include <unordered_map>

#include "common/hash.hpp"
#include "compiler/geometry/clipper_convert.hpp"
#include "compiler/geometry/plane_frame.hpp"

namespace walk::compiler {
namespace {

using model::Vec3;

// Smallest weld distance whatever the model's size, metres: a micrometre, below any modelling precision.
constexpr double kMinWeld = 1e-9;
// Overlap area (square metres) above which two coplanar faces overlap rather than touch along an edge.
constexpr double kMinOverlap = 1e-6;

struct CellKey {
  long long x, y, z;
  bool operator==(const CellKey&) const = default;
};
struct CellHash {
  std::size_t operator()(const CellKey& k) const {
    return static_cast<std::size_t>(k.x * 73856093LL ^ k.y * 19349663LL ^ k.z * 83492791LL);
  }
};

// Moves every corner onto the first corner seen within `tol` of it.
std::size_t weld(model::Model& model, double tol) {
  std::unordered_map<CellKey, std::vector<Vec3>, CellHash> grid;
  std::size_t moved = 0;
  const auto key = [&](const Vec3& p) {
    return CellKey{static_cast<long long>(std::floor(p.x / tol)),
                   static_cast<long long>(std::floor(p.y / tol)),
                   static_cast<long long>(std::floor(p.z / tol))};
  };
  const auto snap = [&](Vec3& p) {
    const CellKey k = key(p);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find({k.x + dx, k.y + dy, k.z + dz});
          if (it == grid.end()) continue;
          for (const Vec3& q : it->second)
            if (glm::distance(p, q) <= tol) {
              if (p != q) ++moved;
              p = q;
              return;
            }
        }
    grid[k].push_back(p);
  };
  for (auto& poly : model.polygons) {
    for (auto& v : poly.vertices) snap(v);
    for (auto& hole : poly.holes)
      for (auto& v : hole) snap(v);
  }
  return moved;
}

// Removes repeated corners and corners within `tol` of the line through their neighbours.
std::size_t simplify(std::vector<Vec3>& loop, double tol) {
  std::size_t removed = 0;
  bool changed = true;
  while (changed && loop.size() >= 3) {
    changed = false;
    for (std::size_t i = 0; i < loop.size() && loop.size() >= 3; ++i) {
      const Vec3& prev = loop[(i + loop.size() - 1) % loop.size()];
      const Vec3& cur = loop[i];
      const Vec3& next = loop[(i + 1) % loop.size()];
      const Vec3 chord = next - prev;
      const double len = glm::length(chord);
      const double off =
          len > 0.0 ? glm::length(glm::cross(cur - prev, chord)) / len : glm::distance(cur, prev);
      if (cur == prev || off <= tol) {
        loop.erase(loop.begin() + static_cast<std::ptrdiff_t>(i));
        ++removed;
        changed = true;
        --i;
      }
    }
  }
  if (loop.size() < 3) {
    removed += loop.size();
    loop.clear();
  }
  return removed;
}

double planarity_error(const model::Polygon& p, Vec3& normal, double& size) {
  normal = model::area_vector(p.vertices);
  const double len = glm::length(normal);
  model::Bounds b;
  for (const Vec3& v : p.vertices) b.add(v);
  size = std::max({b.size().x, b.size().y, b.size().z});
  if (!(len > 0.0)) return 0.0;
  normal /= len;
  Vec3 centroid(0.0);
  for (const Vec3& v : p.vertices) centroid += v;
  centroid /= static_cast<double>(p.vertices.size());
  double worst = 0.0;
  for (const Vec3& v : p.vertices) worst = std::max(worst, std::abs(glm::dot(v - centroid, normal)));
  for (const auto& hole : p.holes)
    for (const Vec3& v : hole) worst = std::max(worst, std::abs(glm::dot(v - centroid, normal)));
  return worst;
}

// Splits a non-planar face into triangles: a quad along its shorter diagonal, larger faces as a fan from
// the corner that gives the best-shaped first triangle. Holes are not expected on non-planar faces; such a
// face is left as it is.
std::vector<model::Polygon> split(const model::Polygon& p) {
  std::vector<model::Polygon> out;
  const auto& v = p.vertices;
  std::size_t start = 0;
  if (v.size() == 4 && glm::distance(v[1], v[3]) < glm::distance(v[0], v[2])) start = 1;
  for (std::size_t i = 1; i + 1 < v.size(); ++i) {
    model::Polygon t = p;
    t.holes.clear();
    t.vertices = {v[start], v[(start + i) % v.size()], v[(start + i + 1) % v.size()]};
    out.push_back(std::move(t));
  }
  return out;
}

std::size_t coplanar_overlaps(const model::Model& model, double tol, std::size_t& unchecked) {
  // Bucket faces by plane: normal direction rounded to ~1e-4 rad and offset rounded to the weld distance
  // (neighbouring buckets are not searched: faces exactly on a rounding boundary may be missed; this is a
  // report, not a repair).
  std::map<std::array<long long, 4>, std::vector<std::size_t>> planes;
  for (std::size_t i = 0; i < model.polygons.size(); ++i) {
    const auto& p = model.polygons[i];
    Vec3 n = model::area_vector(p.vertices);
    if (!(glm::length(n) > 0.0)) continue;
    n = glm::normalize(n);
    const double d = glm::dot(n, p.vertices[0]);
    planes[{std::llround(n.x * 1e4), std::llround(n.y * 1e4), std::llround(n.z * 1e4),
            std::llround(d / std::max(tol * 10.0, 1e-6))}]
        .push_back(i);
  }
  std::size_t overlaps = 0;
  for (const auto& [key, faces] : planes) {
    if (faces.size() < 2) continue;
    if (faces.size() > kMaxFacesPerPlaneCheck) {
      ++unchecked;
      continue;
    }
    PlaneFrame frame;
    if (!plane_frame(model.polygons[faces[0]].vertices, frame)) continue;
    std::vector<ClipperLib::Path> paths;
    std::vector<std::array<ClipperLib::cInt, 4>> boxes;
    for (std::size_t i : faces) {
      ClipperLib::Path path;
      for (const Vec3& v : model.polygons[i].vertices) path.push_back(to_int(frame.to_2d(v)));
      if (!ClipperLib::Orientation(path)) ClipperLib::ReversePath(path);
      std::array<ClipperLib::cInt, 4> box{INT64_MAX, INT64_MAX, INT64_MIN, INT64_MIN};
      for (const auto& q : path)
        box = {std::min(box[0], q.X), std::min(box[1], q.Y), std::max(box[2], q.X), std::max(box[3], q.Y)};
      paths.push_back(std::move(path));
      boxes.push_back(box);
    }
    for (std::size_t a = 0; a < faces.size(); ++a)
      for (std::size_t b = a + 1; b < faces.size(); ++b) {
        if (boxes[a][2] <= boxes[b][0] || boxes[b][2] <= boxes[a][0] || boxes[a][3] <= boxes[b][1] ||
            boxes[b][3] <= boxes[a][1])
          continue;
        ClipperLib::Clipper c;
        c.AddPath(paths[a], ClipperLib::ptSubject, true);
        c.AddPath(paths[b], ClipperLib::ptClip, true);
        ClipperLib::Paths common;
        c.Execute(ClipperLib::ctIntersection, common, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
        double area = 0.0;
        for (const auto& q : common) area += std::abs(area_m2(q));
        if (area > kMinOverlap) ++overlaps;
      }
  }
  return overlaps;
}

// Between loops in a face's key: no corner lies there (corners beyond 1e8 m are refused on import).
constexpr double kHoleSeparator = 1e300;

// The outer loop from its smallest corner on, in its own order (so the side it faces is kept), then holes
// as given: two faces with equal keys are the same face on the same side once corners are welded.
std::vector<double> face_key(const model::Polygon& p) {
  const auto& v = p.vertices;
  const auto less = [](const Vec3& a, const Vec3& b) {
    return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
  };
  const std::size_t first = std::min_element(v.begin(), v.end(), less) - v.begin();
  std::vector<double> key;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec3& c = v[(first + i) % v.size()];
    key.insert(key.end(), {c.x, c.y, c.z});
  }
  for (const auto& hole : p.holes) {
    key.push_back(kHoleSeparator);
    for (const Vec3& c : hole) key.insert(key.end(), {c.x, c.y, c.z});
  }
  return key;
}

// Drops faces whose key repeats an earlier face's; keeps the first. Returns how many were dropped.
std::size_t drop_duplicates(std::vector<model::Polygon>& polygons, CleanupStats& stats) {
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> seen;  // key hash -> faces kept with it
  std::vector<model::Polygon> kept;
  kept.reserve(polygons.size());
  std::size_t dropped = 0;
  for (auto& p : polygons) {
    const std::vector<double> key = face_key(p);
    auto& same_hash = seen[hash_bytes(0, key.data(), key.size() * sizeof(double))];
    const auto twin = std::find_if(same_hash.begin(), same_hash.end(),
                                   [&](std::size_t k) { return face_key(kept[k]) == key; });
    if (twin != same_hash.end()) {
      if (dropped++ == 0) {
        stats.first_duplicate_line = p.source_line;
        stats.first_duplicated_line = kept[*twin].source_line;
      }
      continue;
    }
    same_hash.push_back(kept.size());
    kept.push_back(std::move(p));
  }
  polygons = std::move(kept);
  return dropped;
}

}  // namespace

std::string CleanupStats::summary() const {
  return "weld " + std::to_string(weld_tolerance) + " m: welded " + std::to_string(vertices_welded) +
         " corners removed " + std::to_string(corners_removed) + " faces dropped " +
         std::to_string(faces_dropped) + " duplicates dropped " + std::to_string(duplicates_dropped) +
         " non-planar split " + std::to_string(nonplanar_split) + " (+" + std::to_string(triangles_added) +
         " triangles) coplanar overlaps " + std::to_string(coplanar_overlaps) +
         (planes_unchecked ? " (" + std::to_string(planes_unchecked) + " crowded planes unchecked)" : "");
}

CleanupStats clean_up(model::Model& model, double weld_metres) {
  CleanupStats stats;
  const model::Bounds b = bounds_of(model);
  const double diagonal = b.empty() ? 0.0 : glm::length(b.size());
  const double tol = weld_metres > 0.0 ? weld_metres : std::max(kMinWeld, diagonal * kWeldRelative);
  stats.weld_tolerance = tol;
  stats.vertices_welded = weld(model, tol);
  std::vector<model::Polygon> kept;
  kept.reserve(model.polygons.size());
  for (auto& p : model.polygons) {
    stats.corners_removed += simplify(p.vertices, tol);
    for (auto& hole : p.holes) stats.corners_removed += simplify(hole, tol);
    std::erase_if(p.holes, [](const auto& h) { return h.size() < 3; });
    if (p.vertices.size() < 3 || !(0.5 * glm::length(model::area_vector(p.vertices)) > tol * tol)) {
      ++stats.faces_dropped;
      continue;
    }
    Vec3 normal;
    double size = 0.0;
    if (p.vertices.size() > 3 && p.holes.empty() &&
        planarity_error(p, normal, size) > kNonPlanarRelative * size) {
      ++stats.nonplanar_split;
      for (auto& t : split(p)) {
        if (0.5 * glm::length(model::area_vector(t.vertices)) > tol * tol) {
          kept.push_back(std::move(t));
          ++stats.triangles_added;
        }
      }
      continue;
    }
    kept.push_back(std::move(p));
  }
  model.polygons = std::move(kept);
  stats.duplicates_dropped = drop_duplicates(model.polygons, stats);
  stats.coplanar_overlaps = coplanar_overlaps(model, tol, stats.planes_unchecked);
  return stats;
}

}  // namespace walk::compiler
