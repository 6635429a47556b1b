#include "compiler/geometry/t_junctions.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <map>
#include <optional>
#include <span>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "common/hash.hpp"

namespace walk::compiler {
namespace {

using model::Vec3;
using Triangle = std::array<std::uint32_t, 3>;
using Edge = std::pair<std::uint32_t, std::uint32_t>;  // directed: first -> second

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (std::uint64_t(a) << 32) | b;
}

struct BoundaryEdge {
  std::uint32_t a = 0, b = 0;  // directed as in its triangle
  std::uint32_t triangle = 0;
};

// Edges of a mesh without their reverse in the same mesh: the polygon's outline and its holes, into `out`
// (cleared first). A mesh of one triangle (most of a furnished model's polygons) is all outline; others look
// up reversed edges in a sorted list, `scratch`: over a million meshes, allocations per edge or per mesh
// would cost more than the search.
void boundary_edges(const PolygonMesh& mesh, std::vector<BoundaryEdge>& out,
                    std::vector<std::uint64_t>& scratch) {
  const std::size_t count = mesh.triangles.size() / 3;
  out.clear();
  const auto each_edge = [&](auto&& visit) {
    for (std::size_t t = 0; t < count; ++t)
      for (int e = 0; e < 3; ++e)
        visit(mesh.triangles[3 * t + e], mesh.triangles[3 * t + (e + 1) % 3], static_cast<std::uint32_t>(t));
  };
  if (count == 1) {
    // A repeated index leaves no area and no boundary: its edges a->b and b->a cancel, as below.
    const std::uint32_t* corners = mesh.triangles.data();
    if (corners[0] == corners[1] || corners[1] == corners[2] || corners[2] == corners[0]) return;
    each_edge([&](std::uint32_t a, std::uint32_t b, std::uint32_t t) { out.push_back({a, b, t}); });
    return;
  }
  scratch.clear();
  each_edge([&](std::uint32_t a, std::uint32_t b, std::uint32_t) { scratch.push_back(edge_key(a, b)); });
  std::sort(scratch.begin(), scratch.end());
  each_edge([&](std::uint32_t a, std::uint32_t b, std::uint32_t t) {
    if (!std::binary_search(scratch.begin(), scratch.end(), edge_key(b, a))) out.push_back({a, b, t});
  });
}

// Boundary vertices of all meshes in a hash grid of cubes of side `cell`: sorted (cell key, vertex) pairs.
struct VertexGrid {
  struct Entry {
    std::uint64_t key;
    std::uint32_t vertex;
  };
  double cell = 1.0;
  std::vector<Entry> entries;

  [[nodiscard]] std::array<std::int64_t, 3> cell_of(const Vec3& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x / cell)),
            static_cast<std::int64_t>(std::floor(p.y / cell)),
            static_cast<std::int64_t>(std::floor(p.z / cell))};
  }
  static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
    // 21 bits per axis, wrapped: distinct cells may share a key, which only adds candidates to reject.
    constexpr std::uint64_t mask = (1u << 21) - 1;
    return (std::uint64_t(x) & mask) | ((std::uint64_t(y) & mask) << 21) | ((std::uint64_t(z) & mask) << 42);
  }
  void build(const std::vector<Vec3>& points) {
    entries.resize(points.size());
    for (std::uint32_t i = 0; i < points.size(); ++i) {
      const auto c = cell_of(points[i]);
      entries[i] = {key(c[0], c[1], c[2]), i};
    }
    std::sort(entries.begin(), entries.end(), [](const Entry& l, const Entry& r) {
      return l.key != r.key ? l.key < r.key : l.vertex < r.vertex;
    });
  }
  // Every vertex within `cell` of a point of segment ab (and some farther), appended to `out`, unsorted.
  void near_segment(const Vec3& a, const Vec3& b, std::vector<std::uint32_t>& out) const {
    // Samples at most half a cell apart: a point within `cell / 2` of the segment is within a cell of a
    // sample, so in one of the 27 cells around it.
    const double length = glm::distance(a, b);
    const auto steps = static_cast<std::size_t>(std::ceil(2.0 * length / cell));
    for (std::size_t k = 0; k <= steps; ++k) {
      const Vec3 p = steps == 0 ? a : a + (b - a) * (double(k) / double(steps));
      const auto c = cell_of(p);
      for (std::int64_t dx = -1; dx <= 1; ++dx)
        for (std::int64_t dy = -1; dy <= 1; ++dy)
          for (std::int64_t dz = -1; dz <= 1; ++dz) {
            const std::uint64_t k2 = key(c[0] + dx, c[1] + dy, c[2] + dz);
            auto it = std::lower_bound(entries.begin(), entries.end(), k2,
                                       [](const Entry& e, std::uint64_t v) { return e.key < v; });
            for (; it != entries.end() && it->key == k2; ++it) out.push_back(it->vertex);
          }
    }
  }
};

struct Insertion {
  double t = 0.0;            // along the edge, 0..1
  std::uint32_t vertex = 0;  // global boundary vertex
};

// Splits `pieces` (which hold the directed edge a->b once) along that edge at `points`, fanning from the
// piece's third corner. Orientation is kept: (a, x1, c), (x1, x2, c), ..., (xk, b, c).
void split_edge(std::vector<Triangle>& pieces, std::uint32_t a, std::uint32_t b,
                const std::vector<std::uint32_t>& points) {
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    for (int e = 0; e < 3; ++e) {
      if (pieces[i][e] != a || pieces[i][(e + 1) % 3] != b) continue;
      const std::uint32_t c = pieces[i][(e + 2) % 3];
      pieces[i] = {a, points.front(), c};
      std::uint32_t from = points.front();
      for (std::size_t k = 1; k < points.size(); ++k) {
        pieces.push_back({from, points[k], c});
        from = points[k];
      }
      pieces.push_back({from, b, c});
      return;
    }
  }
}

bool has_edge(const Triangle& t, std::uint32_t a, std::uint32_t b) {
  for (int e = 0; e < 3; ++e)
    if (t[e] == a && t[(e + 1) % 3] == b) return true;
  return false;
}

Triangle triangle_at(const PolygonMesh& mesh, std::size_t t) {
  return {mesh.triangles[3 * t], mesh.triangles[3 * t + 1], mesh.triangles[3 * t + 2]};
}

// The edge each triangle shares with its quad partner, paired as the renderer's find_quads pairs them:
// scanning the list, a triangle and the next one are a pair when they share an edge, and the scan goes on
// after the pair; otherwise it moves on by one. Unpaired triangles get no edge.
std::vector<std::optional<Edge>> quad_partner_edges(const PolygonMesh& mesh) {
  const std::size_t count = mesh.triangles.size() / 3;
  std::vector<std::optional<Edge>> out(count);
  for (std::size_t t = 0; t + 1 < count;) {
    const Triangle me = triangle_at(mesh, t), next = triangle_at(mesh, t + 1);
    bool paired = false;
    for (int e = 0; e < 3 && !paired; ++e) {
      if (!has_edge(next, me[(e + 1) % 3], me[e])) continue;
      out[t] = Edge(me[e], me[(e + 1) % 3]);
      out[t + 1] = Edge(me[(e + 1) % 3], me[e]);
      paired = true;
    }
    t += paired ? 2 : 1;
  }
  return out;
}

// A unit vector up to sign, for keys that treat both facings alike: its first component clearly away from
// zero (a unit vector has one of at least 0.577) made positive. Not the largest one: at 45 degrees two are
// equal, and noise would pick either.
Vec3 up_to_sign(const Vec3& u) {
  int lead = 0;
  while (lead < 2 && std::abs(u[lead]) <= 0.25) ++lead;
  return u[lead] < 0.0 ? -u : u;
}

// Along an axis: two coordinates the same to kAxialNoise.
bool axial(const Vec3& a, const Vec3& b) {
  const auto same = [](double p, double q) { return std::abs(p - q) <= kAxialNoise; };
  return same(a.x, b.x) + same(a.y, b.y) + same(a.z, b.z) >= 2;
}

// A mesh of no area has no plane to keep a point in (a zero normal passes any plane test).
bool has_plane(const PolygonMesh& mesh) {
  return glm::dot(mesh.normal, mesh.normal) > 0.5;
}

// Normals a rounding from parallel, either facing: the same plane's direction.
bool parallel(const PolygonMesh& a, const PolygonMesh& b) {
  return std::abs(glm::dot(a.normal, b.normal)) >= 1.0 - kSeamNormalBin;
}

// For each boundary edge of one mesh, the ends of the straight run of boundary edges around it: the outline
// edge it was diced from. A diced edge's own line is off the outline edge's by up to kDicingPointNoise at
// its dicing-point end, enough to land in another line bin than the neighbour's edge across the crease; the
// run's ends are the outline's corners. A vertex with more than one boundary edge leaving or entering it
// (two holes touching) ends the run.
std::vector<std::pair<std::uint32_t, std::uint32_t>> straight_runs(const PolygonMesh& mesh,
                                                                   std::span<const BoundaryEdge> boundary) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> runs(boundary.size());
  for (std::size_t i = 0; i < boundary.size(); ++i) runs[i] = {boundary[i].a, boundary[i].b};
  // One triangle: every edge is an outline edge (asked first, before any edge is looked at).
  // No slanted edge: no crease to key (most of a building).
  if (mesh.triangles.size() <= 3) return runs;
  const bool slanted = std::any_of(boundary.begin(), boundary.end(), [&](const BoundaryEdge& e) {
    return !axial(mesh.vertices[e.a], mesh.vertices[e.b]);
  });
  if (!slanted) return runs;
  // Boundary edges by start and by end vertex, as sorted (vertex, edge) lists; a vertex met twice is not
  // followed.
  constexpr std::uint32_t kNone = ~0u;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> from, to;
  for (std::uint32_t i = 0; i < boundary.size(); ++i) {
    from.emplace_back(boundary[i].a, i);
    to.emplace_back(boundary[i].b, i);
  }
  std::sort(from.begin(), from.end());
  std::sort(to.begin(), to.end());
  const auto edge_at = [](const auto& list, std::uint32_t v) {
    const auto it = std::lower_bound(list.begin(), list.end(), std::pair{v, 0u});
    if (it == list.end() || it->first != v) return kNone;
    return std::next(it) != list.end() && std::next(it)->first == v ? kNone : it->second;
  };
  // Does the vertex between edges p (into it) and n (out of it) lie inside the segment p.a -> n.b?
  const auto straight = [&](std::uint32_t p, std::uint32_t n) {
    const Vec3 &a = mesh.vertices[boundary[p].a], &v = mesh.vertices[boundary[p].b],
               &b = mesh.vertices[boundary[n].b];
    const Vec3 d = b - a;
    const double length2 = glm::dot(d, d);
    if (!(length2 > 0.0)) return false;
    const double t = glm::dot(v - a, d) / length2;
    return t > 0.0 && t < 1.0 && glm::distance(v, a + d * t) <= kDicingPointNoise;
  };
  // The edge after each one around its loop, and whether an edge goes on straight from the one before.
  std::vector<std::uint32_t> next(boundary.size(), kNone);
  std::vector<char> continues(boundary.size(), 0);
  for (std::uint32_t i = 0; i < boundary.size(); ++i) {
    const std::uint32_t n = edge_at(from, boundary[i].b);
    if (n == kNone || edge_at(to, boundary[i].b) != i) continue;
    next[i] = n;
    continues[n] = straight(i, n);
  }
  // Each run from the edge that starts it, once: linear in the boundary. A loop with no start (all of it
  // straight: no area) keeps each edge's own ends.
  for (std::uint32_t first = 0; first < boundary.size(); ++first) {
    if (continues[first]) continue;
    std::uint32_t last = first;
    while (next[last] != kNone && next[last] != first && continues[next[last]]) last = next[last];
    for (std::uint32_t k = first;; k = next[k]) {
      runs[k] = {boundary[first].a, boundary[last].b};
      if (k == last) break;
    }
  }
  return runs;
}

// Which seams a repair pass closes.
struct SeamPass {
  // A vertex is inserted into an edge only within this distance (metres) of the edge's line.
  double line_tolerance = 0.0;
  // Across creases: only the ends of slanted boundary edges offer vertices (a crease along a slanted line
  // has a slanted edge on both sides; axial edges need no repair), only to meshes in another plane
  // (coplanar ones are the in-plane pass's).
  bool creases = false;
};

// The repair among the meshes of `group` (their indices): one plane's, or those with edges on one crease
// line.
void repair_group(std::vector<PolygonMesh>& meshes, std::span<const std::uint32_t> group, double tolerance,
                  const SeamPass& pass, TJunctionStats& stats) {
  // Every mesh's boundary, and its boundary vertices numbered across the group with their mesh.
  std::vector<std::vector<BoundaryEdge>> edges(group.size());  // by place in the group
  // Across creases, each edge's outline edge (the ends of its straight run): a point goes in where it lies
  // on that line, as the corners both planes' intersections put there do, not only near the diced edge.
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> outline(group.size());
  std::vector<std::uint64_t> scratch;
  std::vector<Vec3> points;
  std::vector<std::uint32_t> point_mesh;  // place in the group
  double edge_length_sum = 0.0;
  std::size_t edge_count = 0;
  for (std::uint32_t g = 0; g < group.size(); ++g) {
    const std::uint32_t m = group[g];
    boundary_edges(meshes[m], edges[g], scratch);
    if (pass.creases) {
      auto runs = straight_runs(meshes[m], edges[g]);
      std::size_t kept = 0;
      for (std::size_t i = 0; i < edges[g].size(); ++i) {
        if (axial(meshes[m].vertices[edges[g][i].a], meshes[m].vertices[edges[g][i].b])) continue;
        edges[g][kept] = edges[g][i];
        runs[kept++] = runs[i];
      }
      edges[g].resize(kept);
      runs.resize(kept);
      outline[g] = std::move(runs);
    }
    std::vector<std::uint32_t> on_boundary;
    for (const auto& e : edges[g]) {
      on_boundary.push_back(e.a);
      if (pass.creases) on_boundary.push_back(e.b);
      edge_length_sum += glm::distance(meshes[m].vertices[e.a], meshes[m].vertices[e.b]);
      ++edge_count;
    }
    std::sort(on_boundary.begin(), on_boundary.end());
    on_boundary.erase(std::unique(on_boundary.begin(), on_boundary.end()), on_boundary.end());
    for (std::uint32_t v : on_boundary) {
      points.push_back(meshes[m].vertices[v]);
      point_mesh.push_back(g);
    }
  }
  if (edge_count == 0) return;
  VertexGrid grid;
  // Cells about a boundary edge long (one or two lookups per edge), never under twice the tolerance (the
  // search reaches half a cell from the segment).
  grid.cell = std::max(edge_length_sum / double(edge_count), 2.0 * tolerance);
  if (!(grid.cell > 0.0)) return;
  grid.build(points);

  std::vector<std::uint32_t> near;
  std::vector<Insertion> found;
  for (std::uint32_t g = 0; g < group.size(); ++g) {
    PolygonMesh& mesh = meshes[group[g]];
    if (!has_plane(mesh)) continue;
    // Per triangle, in list order: the edges to split and the points on each, numbered after this mesh's
    // vertices (`base` + global point) until a split is taken and they become vertices of it.
    std::map<std::uint32_t, std::vector<std::pair<Edge, std::vector<std::uint32_t>>>> splits;
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    for (std::size_t i = 0; i < edges[g].size(); ++i) {
      const BoundaryEdge& e = edges[g][i];
      const Vec3 a = mesh.vertices[e.a], b = mesh.vertices[e.b];
      // The line a point must lie on: the edge's own, or across a crease its outline edge's.
      const Vec3 line_a = pass.creases ? mesh.vertices[outline[g][i].first] : a;
      const Vec3 line_d = pass.creases ? mesh.vertices[outline[g][i].second] - line_a : b - a;
      const double line_length2 = glm::dot(line_d, line_d);
      // An edge along an axis keeps two coordinates, which float rounds alike for every point on it: its
      // T-junctions cannot open. Splitting there would only add slivers and vertices.
      if (axial(a, b)) continue;
      const Vec3 d = b - a;
      const double length2 = glm::dot(d, d);
      if (!(length2 > 4.0 * tolerance * tolerance))
        continue;  // no room for a point farther than tol from both ends
      const double length = std::sqrt(length2);
      near.clear();
      grid.near_segment(a, b, near);
      std::sort(near.begin(), near.end());
      near.erase(std::unique(near.begin(), near.end()), near.end());
      found.clear();
      for (std::uint32_t p : near) {
        if (point_mesh[p] == g) continue;
        if (pass.creases && parallel(meshes[group[point_mesh[p]]], mesh)) continue;
        const Vec3& x = points[p];
        const double t = glm::dot(x - a, d) / length2;
        if (t * length <= tolerance || (1.0 - t) * length <= tolerance) continue;
        const double on_line = glm::dot(x - line_a, line_d) / line_length2;
        if (glm::distance(x, line_a + line_d * on_line) > pass.line_tolerance) continue;
        if (std::abs(glm::dot(x - a, mesh.normal)) > kSeamNoise) continue;
        found.push_back({t, p});
      }
      if (found.empty()) continue;
      // Along the edge; points within kSeamNoise of each other (several meshes' copies of one corner) are
      // one.
      std::sort(found.begin(), found.end(), [&](const Insertion& l, const Insertion& r) {
        if (l.t != r.t) return l.t < r.t;
        const Vec3 &pl = points[l.vertex], &pr = points[r.vertex];
        return std::tie(pl.x, pl.y, pl.z) < std::tie(pr.x, pr.y, pr.z);
      });
      found.erase(std::unique(found.begin(), found.end(),
                              [&](const Insertion& l, const Insertion& r) {
                                return glm::distance(points[l.vertex], points[r.vertex]) <= kSeamNoise;
                              }),
                  found.end());
      std::vector<std::uint32_t> numbered;
      for (const auto& f : found) numbered.push_back(base + f.vertex);
      splits[e.triangle].push_back({{e.a, e.b}, std::move(numbered)});
    }
    if (splits.empty()) continue;

    const std::size_t count = mesh.triangles.size() / 3;
    std::vector<Triangle> in_place(count), appended;
    for (std::size_t t = 0; t < count; ++t) in_place[t] = triangle_at(mesh, t);
    const auto partners = quad_partner_edges(mesh);
    const auto at = [&](std::uint32_t v) -> const Vec3& {
      return v < base ? mesh.vertices[v] : points[v - base];
    };
    std::unordered_map<std::uint32_t, std::uint32_t> copy_of;  // global point -> this mesh's vertex
    for (const auto& [t, edge_points] : splits) {
      std::vector<Triangle> pieces{in_place[t]};
      for (const auto& [edge, points_on] : edge_points)
        split_edge(pieces, edge.first, edge.second, points_on);
      // A point off the edge by up to the line tolerance folds a piece over where the triangle is thinner
      // than that (a sliver beside a column cut): such a triangle keeps its T-junction.
      const bool folds = std::any_of(pieces.begin(), pieces.end(), [&](const Triangle& p) {
        return !(glm::dot(glm::cross(at(p[1]) - at(p[0]), at(p[2]) - at(p[0])), mesh.normal) > 0.0);
      });
      if (folds) {
        ++stats.splits_refused;
        continue;
      }
      for (Triangle& piece : pieces)
        for (std::uint32_t& v : piece) {
          if (v < base) continue;
          auto [it, fresh] = copy_of.try_emplace(v - base, static_cast<std::uint32_t>(mesh.vertices.size()));
          if (fresh) {
            mesh.vertices.push_back(points[v - base]);
            ++stats.vertices_inserted;
          }
          v = it->second;
        }
      const auto& partner = partners[t];
      std::size_t keep = 0;
      if (partner)
        for (std::size_t i = 0; i < pieces.size(); ++i)
          if (has_edge(pieces[i], partner->first, partner->second)) keep = i;
      in_place[t] = pieces[keep];
      for (std::size_t i = 0; i < pieces.size(); ++i)
        if (i != keep) appended.push_back(pieces[i]);
      ++stats.triangles_split;
    }
    mesh.triangles.clear();
    for (const auto* list : {&in_place, &appended})
      for (const auto& tri : *list) mesh.triangles.insert(mesh.triangles.end(), tri.begin(), tri.end());
  }
}

// A slanted boundary edge's line: direction up to sign in bins of kSeamNormalBin, and the line's point
// nearest the origin in bins of kCreaseLineBin.
using LineKey = std::array<long long, 6>;

LineKey line_key(const Vec3& a, const Vec3& b) {
  const Vec3 u = up_to_sign(glm::normalize(b - a));
  const Vec3 nearest = a - u * glm::dot(a, u);
  return {std::llround(u.x / kSeamNormalBin),       std::llround(u.y / kSeamNormalBin),
          std::llround(u.z / kSeamNormalBin),       std::llround(nearest.x / kCreaseLineBin),
          std::llround(nearest.y / kCreaseLineBin), std::llround(nearest.z / kCreaseLineBin)};
}

// A slanted boundary edge, sorted by the hash of its line: 32 bytes, where the key itself would make a
// furnished model's millions of edges a sort of hundreds of megabytes. Equal hashes are checked by key.
struct LineEdge {
  std::uint64_t line_hash = 0;
  std::uint32_t mesh = 0;
  std::uint32_t a = 0, b = 0;            // the mesh's vertices
  std::uint32_t line_a = 0, line_b = 0;  // the ends of the straight run of boundary edges it is part of
};

// Creases: where two planes meet along a slanted line, each side's corners on it go into the other's edge.
// Only points on the receiving edge's outline edge to double noise (corners both planes' intersections put
// there), so no point leaves the plane it is inserted into by more than kSeamNoise; a dicing point rounded
// off the line stays out. The edges are grouped by the line of the outline edge they were diced from, and
// only the meshes of a line where an end of one mesh's edge lies inside another plane's edge are repaired
// together: over the whole model at once, a grid of every slanted end held thousands of a furnished model's
// small triangles' ends per cell (the conference room ran minutes).
void repair_creases(std::vector<PolygonMesh>& meshes, double tolerance, TJunctionStats& stats) {
  std::vector<LineEdge> edges;
  std::vector<BoundaryEdge> boundary;
  std::vector<std::uint64_t> scratch;
  for (std::uint32_t m = 0; m < meshes.size(); ++m) {
    const PolygonMesh& mesh = meshes[m];
    if (!has_plane(mesh)) continue;
    boundary_edges(mesh, boundary, scratch);
    const auto runs = straight_runs(mesh, boundary);
    for (std::size_t i = 0; i < boundary.size(); ++i) {
      const BoundaryEdge& e = boundary[i];
      const Vec3 a = mesh.vertices[e.a], b = mesh.vertices[e.b];
      if (axial(a, b) || !(glm::distance(a, b) > 2.0 * tolerance)) continue;
      const auto [line_a, line_b] = runs[i];
      const LineKey line = line_key(mesh.vertices[line_a], mesh.vertices[line_b]);
      edges.push_back({hash_bytes(0, line.data(), sizeof(line)), m, e.a, e.b, line_a, line_b});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const LineEdge& l, const LineEdge& r) {
    return l.line_hash != r.line_hash ? l.line_hash < r.line_hash : l.mesh < r.mesh;
  });
  const auto end_of = [&](const LineEdge& e, bool second) -> const Vec3& {
    return meshes[e.mesh].vertices[second ? e.b : e.a];
  };
  // Does an end of `f` lie inside `e`, farther than the tolerance from its ends, in another plane?
  const auto inside = [&](const LineEdge& e, const LineEdge& f) {
    if (e.mesh == f.mesh || parallel(meshes[e.mesh], meshes[f.mesh])) return false;
    const Vec3& ea = end_of(e, false);
    const Vec3 d = end_of(e, true) - ea;
    const double length = glm::length(d);
    for (const Vec3& x : {end_of(f, false), end_of(f, true)}) {
      const double along = glm::dot(x - ea, d) / length;
      if (along > tolerance && along < length - tolerance) return true;
    }
    return false;
  };
  const auto joins = [&](std::span<const LineEdge> line) {
    for (const LineEdge& e : line)
      for (const LineEdge& f : line)
        if (inside(e, f)) return true;
    return false;
  };
  const SeamPass across{.line_tolerance = kSeamNoise, .creases = true};
  std::vector<LineEdge> same_line;
  std::vector<std::uint32_t> group;
  for (std::size_t first = 0, next = 0; first < edges.size(); first = next) {
    next = first + 1;
    while (next < edges.size() && edges[next].line_hash == edges[first].line_hash) ++next;
    if (!joins({edges.data() + first, next - first})) continue;
    // Edges of one hash on different lines (a 64-bit collision) are repaired line by line.
    std::vector<std::pair<LineKey, LineEdge>> keyed;
    for (std::size_t i = first; i < next; ++i)
      keyed.emplace_back(line_key(meshes[edges[i].mesh].vertices[edges[i].line_a],
                                  meshes[edges[i].mesh].vertices[edges[i].line_b]),
                         edges[i]);
    std::stable_sort(keyed.begin(), keyed.end(),
                     [](const auto& l, const auto& r) { return l.first < r.first; });
    for (std::size_t from = 0, to = 0; from < keyed.size(); from = to) {
      same_line.clear();
      for (to = from; to < keyed.size() && keyed[to].first == keyed[from].first; ++to)
        same_line.push_back(keyed[to].second);
      if (!joins(same_line)) continue;
      group.clear();
      for (const LineEdge& e : same_line)
        if (group.empty() || group.back() != e.mesh) group.push_back(e.mesh);
      repair_group(meshes, group, tolerance, across, stats);
    }
  }
}

}  // namespace

TJunctionStats repair_t_junctions(std::vector<PolygonMesh>& meshes, double tolerance) {
  TJunctionStats stats;
  // Seams are only repaired between coplanar meshes, so the search runs per plane: meshes grouped by their
  // normal (up to sign, in bins of kSeamNormalBin) and then by offset along it, within kSeamNoise of the
  // previous.
  struct Key {
    std::array<long long, 3> normal;
    double offset;
    std::uint32_t mesh;
  };
  std::vector<Key> keys;
  for (std::uint32_t m = 0; m < meshes.size(); ++m) {
    const PolygonMesh& mesh = meshes[m];
    if (mesh.triangles.empty()) continue;
    const Vec3 n = up_to_sign(mesh.normal);
    keys.push_back({{std::llround(n.x / kSeamNormalBin), std::llround(n.y / kSeamNormalBin),
                     std::llround(n.z / kSeamNormalBin)},
                    glm::dot(n, mesh.vertices[mesh.triangles[0]]),
                    m});
  }
  std::sort(keys.begin(), keys.end(), [](const Key& l, const Key& r) {
    return l.normal != r.normal ? l.normal < r.normal : l.offset < r.offset;
  });
  // Planes with more than one mesh, as runs of `keys`.
  std::vector<std::pair<std::size_t, std::size_t>> planes;
  for (std::size_t first = 0, next = 0; first < keys.size(); first = next) {
    for (next = first + 1; next < keys.size() && keys[next].normal == keys[next - 1].normal &&
                           keys[next].offset - keys[next - 1].offset <= kSeamNoise;
         ++next) {
    }
    if (next - first > 1) planes.emplace_back(first, next);
  }
  const SeamPass in_plane{.line_tolerance = tolerance};
  std::vector<std::uint32_t> group;
  const auto repair_plane = [&](std::pair<std::size_t, std::size_t> plane) {
    group.clear();
    for (std::size_t i = plane.first; i < plane.second; ++i) group.push_back(keys[i].mesh);
    repair_group(meshes, group, tolerance, in_plane, stats);
  };
  for (const auto& plane : planes) repair_plane(plane);
  const std::size_t in_plane_inserted = stats.vertices_inserted;
  std::vector<std::size_t> vertex_counts(meshes.size());
  for (std::size_t m = 0; m < meshes.size(); ++m) vertex_counts[m] = meshes[m].vertices.size();
  repair_creases(meshes, tolerance, stats);
  const std::size_t crease_inserted = stats.vertices_inserted - in_plane_inserted;
  // A point a crease gave one mesh lies on the seam with its coplanar neighbours too, when that seam runs
  // along the crease (two floors meeting under a wall's slanted foot): those planes are repaired again.
  if (crease_inserted > 0)
    for (const auto& plane : planes)
      for (std::size_t i = plane.first; i < plane.second; ++i)
        if (meshes[keys[i].mesh].vertices.size() != vertex_counts[keys[i].mesh]) {
          repair_plane(plane);
          break;
        }
  stats.crease_vertices_inserted = crease_inserted;
  return stats;
}

}  // namespace walk::compiler
