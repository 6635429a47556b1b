#include "render/cluster_layout.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <limits>
#include <numeric>

#include "model/model.hpp"

namespace walk::render {
namespace {

bool is_glass(const model::PolygonRecord& p) {
  return p.role == std::uint32_t(model::Role::Glass);
}

// The polygons of each unit before ordering: the bundle's clusters, then one unit per drawn polygon that no
// cluster lists (so drawing everything still draws it); without CLUS, one unit per polygon.
std::vector<std::vector<std::uint32_t>> unit_members(const LayoutInput& in) {
  std::vector<std::vector<std::uint32_t>> members;
  if (in.clusters.empty()) {
    members.resize(in.polygons.size());
    for (std::uint32_t p = 0; p < in.polygons.size(); ++p) members[p] = {p};
    return members;
  }
  std::vector<bool> listed(in.polygons.size(), false);
  for (const auto& c : in.clusters) {
    auto& m = members.emplace_back();
    for (std::uint64_t i = c.polygon_first;
         i < std::uint64_t(c.polygon_first) + c.polygon_count && i < in.cluster_polygons.size(); ++i) {
      const std::uint32_t p = in.cluster_polygons[i];
      if (p >= in.polygons.size()) continue;
      m.push_back(p);
      listed[p] = true;
    }
  }
  for (std::uint32_t p = 0; p < in.polygons.size(); ++p)
    if (!listed[p] && is_drawn(in.polygons[p].role)) members.push_back({p});
  return members;
}

// Copies each unit's polygons' ranges of one form (opaque pass, then glass) into `form`.
void lay_out_form(const LayoutInput& in, const std::vector<std::vector<std::uint32_t>>& members,
                  std::span<const std::uint32_t> source, const std::vector<IndexRange>& polygon_ranges,
                  LaidOutForm& form) {
  form.polygons.assign(in.polygons.begin(), in.polygons.end());
  for (auto& p : form.polygons) p.index_count = 0;
  form.opaque.assign(members.size(), {});
  form.glass.assign(members.size(), {});
  for (const bool glass : {false, true}) {
    form.regions.push_back(std::uint32_t(form.indices.size()));
    for (std::size_t u = 0; u < members.size(); ++u) {
      IndexRange& range = (glass ? form.glass : form.opaque)[u];
      range.first = std::uint32_t(form.indices.size());
      for (const std::uint32_t p : members[u]) {
        const auto& poly = in.polygons[p];
        const IndexRange r = polygon_ranges[p];
        if (!is_drawn(poly.role) || is_glass(poly) != glass || r.count == 0) continue;
        if (std::uint64_t(r.first) + r.count > source.size()) continue;
        form.polygons[p].first_index = std::uint32_t(form.indices.size());
        form.polygons[p].index_count = r.count;
        form.indices.insert(form.indices.end(), source.begin() + r.first, source.begin() + r.first + r.count);
      }
      range.count = std::uint32_t(form.indices.size()) - range.first;
    }
  }
}

// Appends `r` to `batch`, merged with the last range when they meet.
void append(DrawBatch& batch, IndexRange r, std::uint64_t& end) {
  if (r.count == 0) return;
  if (!batch.counts.empty() && end == r.first) {
    batch.counts.back() += std::int32_t(r.count);
  } else {
    batch.counts.push_back(std::int32_t(r.count));
    batch.byte_offsets.push_back(std::uintptr_t(std::uint64_t(r.first) * sizeof(std::uint32_t)));
  }
  end = std::uint64_t(r.first) + r.count;
}

// Appends the levels of detail after `form`'s glass, level by level. `cluster_of_unit` gives each unit's
// bundle cluster (a value past the clusters: no levels).
void lay_out_levels(const LayoutInput& in, const std::vector<std::uint32_t>& cluster_of_unit,
                    LaidOutForm& form) {
  const std::size_t units = form.opaque.size();
  form.lod.assign(units, {});
  form.lod_error.assign(units, {});
  const bool has_levels =
      !in.lod_ranges.empty() && in.lod_ranges.size() == in.clusters.size() * model::kLodLevels;
  for (std::uint32_t l = 0; l < model::kLodLevels; ++l) {
    form.regions.push_back(std::uint32_t(form.indices.size()));
    for (std::size_t u = 0; u < units; ++u) {
      IndexRange& range = form.lod[u][l];
      range = l == 0 ? form.opaque[u] : form.lod[u][l - 1];
      form.lod_error[u][l] = l == 0 ? 0.0f : form.lod_error[u][l - 1];
      const std::uint32_t k = cluster_of_unit[u];
      if (!has_levels || k >= in.clusters.size()) continue;
      const auto& r = in.lod_ranges[std::size_t(k) * model::kLodLevels + l];
      if (r.index_count == 0 || std::uint64_t(r.first_index) + r.index_count > in.lod_indices.size())
        continue;
      range = {std::uint32_t(form.indices.size()), r.index_count};
      form.lod_error[u][l] = r.error;
      form.indices.insert(form.indices.end(), in.lod_indices.begin() + r.first_index,
                          in.lod_indices.begin() + r.first_index + r.index_count);
    }
  }
}

// Per VERT id, a class shared by every vertex at bit-identical coordinates (kNoClass: unused by `form`):
// the polygons of one mesh meet at such vertices, and only they may share a vertex without moving an edge.
constexpr std::uint32_t kNoClass = std::numeric_limits<std::uint32_t>::max();
constexpr int kSharedLookup = 16;  // vertices read at one point (share_vertices)
struct PositionClasses {
  std::vector<std::uint32_t> of;  // per VERT id
  std::uint32_t count = 0;
};
PositionClasses position_classes(const LaidOutForm& form, std::span<const model::VertexRecord> vertices,
                                 CoarseVertices how) {
  std::vector<std::uint32_t> used;
  {
    std::vector<bool> seen(vertices.size(), false);
    for (const std::uint32_t v : form.indices)
      if (v < vertices.size() && !seen[v]) {
        seen[v] = true;
        used.push_back(v);
      }
  }
  auto key = [&](std::uint32_t v) {
    std::array<std::uint32_t, 3> k{};
    std::memcpy(k.data(), vertices[v].position, sizeof(k));
    return k;
  };
  const bool own = how == CoarseVertices::OwnPerPolygon;  // each VERT record a class of its own
  if (!own)
    std::sort(used.begin(), used.end(), [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
  PositionClasses classes{std::vector<std::uint32_t>(vertices.size(), kNoClass), 0};
  for (std::size_t i = 0; i < used.size(); ++i) {
    if (i > 0 && (own || key(used[i]) != key(used[i - 1]))) ++classes.count;
    classes.of[used[i]] = classes.count;
  }
  if (!used.empty()) ++classes.count;
  return classes;
}

// Gives `form` vertices of its own (see LaidOutForm::vertices), shared between a unit's polygons wherever
// their corners coincide. The light of the coarse form is per polygon and flat, taken from each triangle's
// provoking vertex (GL's default, the last), so each triangle is rotated (its winding kept) to end on a
// vertex of its own polygon; the other two corners may be any polygon's.
void share_vertices(LaidOutForm& form, std::span<const model::VertexRecord> vertices, CoarseVertices how) {
  const PositionClasses classes = position_classes(form, vertices, how);
  const std::vector<std::uint32_t>& class_of = classes.of;
  // Vertices are shared within one unit's range: a range, or a run of ranges merged, then spans only
  // its own dense run of vertices, which llvmpipe fetches and shades as one linear span (sharing over a
  // whole region shaded a third fewer on Sibenik but measured no faster, its ranges reaching back to
  // other units' vertices).
  std::vector<std::uint32_t> starts(form.regions.begin(), form.regions.end());
  for (const auto* ranges : {&form.opaque, &form.glass})
    for (const IndexRange& r : *ranges) starts.push_back(r.first);
  for (const auto& levels : form.lod)
    for (const IndexRange& r : levels) starts.push_back(r.first);
  std::sort(starts.begin(), starts.end());
  starts.erase(std::unique(starts.begin(), starts.end()), starts.end());

  // Per class, the newest vertex of this unit's range at it (valid while region_of matches); per vertex,
  // the one before it at the same class, so a class's vertices in this range form a list, of which a lookup
  // reads the newest kSharedLookup (a fan of many polygons round one point adds vertices rather than time). A
  // vertex only some triangle's other corner is stays unclaimed, its polygon open: the first triangle that
  // needs a provoking vertex there claims it (a closed mesh has half as many corners as triangles, so each
  // must provoke for one).
  constexpr std::uint32_t kNoVertex = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> newest(classes.count, kNoVertex), region_of(classes.count, 0);
  std::vector<std::uint32_t> previous;  // per form vertex
  std::vector<bool> claimed;            // per form vertex
  std::uint32_t region = 0;
  std::size_t next_start = 0;
  auto newest_at = [&](std::uint32_t k) { return region_of[k] == region ? newest[k] : kNoVertex; };
  // A vertex at class `k` that can provoke for `polygon`: claimed by it, or else unclaimed.
  auto provoking_at = [&](std::uint32_t k, std::uint32_t polygon) {
    std::uint32_t open = kNoVertex;
    int read = 0;
    for (std::uint32_t v = newest_at(k); v != kNoVertex && read < kSharedLookup; v = previous[v], ++read) {
      if (!claimed[v])
        open = v;
      else if (vertices[form.vertices[v]].polygon == polygon)
        return v;
    }
    return open;
  };
  auto add = [&](std::uint32_t vert, std::uint32_t k, bool claim) {
    const auto v = std::uint32_t(form.vertices.size());
    form.vertices.push_back(vert);
    previous.push_back(newest_at(k));
    claimed.push_back(claim);
    newest[k] = v;
    region_of[k] = region;
    return v;
  };
  // Per class, the corners of this range's triangles still to come there: a point few triangles meet is
  // where one of them must claim its vertex, since no other can (a greedy choice without this count
  // leaves such points unclaimed and adds vertices elsewhere).
  std::vector<std::uint32_t> remaining(classes.count, 0);
  auto valid = [&](std::size_t t) {
    return form.indices[t] < vertices.size() && form.indices[t + 1] < vertices.size() &&
           form.indices[t + 2] < vertices.size();  // the bundle reader has checked; kept here too
  };
  for (std::size_t t = 0; t + 2 < form.indices.size(); t += 3) {
    if (next_start < starts.size() && starts[next_start] <= t) {
      while (next_start < starts.size() && starts[next_start] <= t) ++next_start;
      ++region;
      const std::size_t end = next_start < starts.size() ? starts[next_start] : form.indices.size();
      for (std::size_t u = t; u + 2 < end; u += 3)
        if (valid(u))
          for (std::size_t i = 0; i < 3; ++i) ++remaining[class_of[form.indices[u + i]]];
    }
    if (!valid(t)) continue;
    const std::array<std::uint32_t, 3> corner{form.indices[t], form.indices[t + 1], form.indices[t + 2]};
    const std::array<std::uint32_t, 3> k{class_of[corner[0]], class_of[corner[1]], class_of[corner[2]]};
    for (const std::uint32_t c : k) --remaining[c];
    // The provoking corner: one whose vertex already provokes for its polygon; else, of those where a
    // vertex is unclaimed or none is yet (either costs no vertex more), the one fewest triangles still
    // meet; else the first, at a new vertex of its own.
    int provoking = -1;
    std::uint32_t provoking_vertex = kNoVertex;
    std::uint32_t fewest = std::numeric_limits<std::uint32_t>::max();
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t polygon = vertices[corner[i]].polygon;
      const std::uint32_t v = provoking_at(k[i], polygon);
      if (v != kNoVertex && claimed[v]) {  // its own: nothing to choose
        provoking = i;
        provoking_vertex = v;
        break;
      }
      if ((v != kNoVertex || newest_at(k[i]) == kNoVertex) && remaining[k[i]] < fewest) {
        fewest = remaining[k[i]];
        provoking = i;
        provoking_vertex = v;
      }
    }
    if (provoking < 0) provoking = 0;
    if (provoking_vertex == kNoVertex) {
      provoking_vertex = add(corner[provoking], k[provoking], true);
    } else {
      form.vertices[provoking_vertex] = corner[provoking];  // same position; the polygon it provokes for
      claimed[provoking_vertex] = true;
    }
    std::array<std::uint32_t, 3> shared{};
    for (int i = 0; i < 3; ++i) {
      if (i == provoking) continue;
      const std::uint32_t v = newest_at(k[i]);
      shared[i] = v != kNoVertex ? v : add(corner[i], k[i], false);
    }
    shared[provoking] = provoking_vertex;
    for (int i = 0; i < 3; ++i) form.indices[t + i] = shared[(provoking + 1 + i) % 3];
  }
}

}  // namespace

LayoutInput layout_input(const model::Bundle& bundle) {
  return {bundle.polygons(),         bundle.vertices(),       bundle.indices(),
          bundle.coarse_ranges(),    bundle.coarse_indices(), bundle.clusters(),
          bundle.cluster_polygons(), bundle.lod_ranges(),     bundle.lod_indices()};
}

ClusterLayout lay_out_clusters(const LayoutInput& in, CoarseVertices coarse_vertices) {
  auto members = unit_members(in);
  // Draw order: by the first fine index of each unit's drawn polygons, so the compiler's order (polygons a
  // cell sees together, together) carries over; units with nothing drawn go last.
  constexpr std::uint64_t kNothingDrawn = std::numeric_limits<std::uint64_t>::max();
  std::vector<std::uint64_t> key(members.size(), kNothingDrawn);
  for (std::size_t u = 0; u < members.size(); ++u) {
    auto& m = members[u];
    std::sort(m.begin(), m.end(), [&](std::uint32_t a, std::uint32_t b) {
      return in.polygons[a].first_index < in.polygons[b].first_index;
    });
    for (const std::uint32_t p : m)
      if (is_drawn(in.polygons[p].role) && in.polygons[p].index_count > 0)
        key[u] = std::min<std::uint64_t>(key[u], in.polygons[p].first_index);
  }
  std::vector<std::uint32_t> order(members.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });

  ClusterLayout layout;
  const std::size_t pvs_ids = in.clusters.empty() ? in.polygons.size() : in.clusters.size();
  layout.unit_of.assign(pvs_ids, 0);
  std::vector<std::vector<std::uint32_t>> ordered(members.size());
  for (std::uint32_t rank = 0; rank < order.size(); ++rank) {
    if (order[rank] < pvs_ids) layout.unit_of[order[rank]] = rank;
    ordered[rank] = std::move(members[order[rank]]);
  }

  layout.boxes.assign(ordered.size(), empty_box());
  layout.drawn.assign(ordered.size(), 0);
  layout.unit_of_polygon.assign(in.polygons.size(), ClusterLayout::kNoUnit);
  for (std::size_t u = 0; u < ordered.size(); ++u) {
    for (const std::uint32_t p : ordered[u]) {
      const auto& poly = in.polygons[p];
      if (!is_drawn(poly.role) || poly.index_count == 0) continue;
      ++layout.drawn[u];
      layout.unit_of_polygon[p] = std::uint32_t(u);
      for (std::uint64_t v = poly.first_vertex;
           v < std::uint64_t(poly.first_vertex) + poly.vertex_count && v < in.vertices.size(); ++v)
        grow(layout.boxes[u], in.vertices[v].position);
    }
  }

  std::vector<IndexRange> ranges(in.polygons.size());
  for (std::size_t p = 0; p < in.polygons.size(); ++p)
    ranges[p] = {in.polygons[p].first_index, in.polygons[p].index_count};
  lay_out_form(in, ordered, in.indices, ranges, layout.fine);
  if (!in.coarse_indices.empty() && in.coarse_ranges.size() == in.polygons.size()) {
    for (std::size_t p = 0; p < in.polygons.size(); ++p)
      ranges[p] = {in.coarse_ranges[p].first_index, in.coarse_ranges[p].index_count};
    lay_out_form(in, ordered, in.coarse_indices, ranges, layout.coarse);
  }
  std::vector<std::uint32_t> cluster_of_unit(order.size());
  for (std::uint32_t rank = 0; rank < order.size(); ++rank)
    cluster_of_unit[rank] = in.clusters.empty() ? std::uint32_t(in.clusters.size()) : order[rank];
  if (!layout.coarse.empty()) {
    lay_out_levels(in, cluster_of_unit, layout.coarse);
    share_vertices(layout.coarse, in.vertices, coarse_vertices);
  }
  return layout;
}

std::vector<std::uint32_t> units_of(const ClusterLayout& layout, std::span<const std::uint32_t> pvs_ids) {
  std::vector<std::uint32_t> units;
  units.reserve(pvs_ids.size());
  for (const std::uint32_t id : pvs_ids)
    if (id < layout.unit_of.size()) units.push_back(layout.unit_of[id]);
  std::sort(units.begin(), units.end());
  units.erase(std::unique(units.begin(), units.end()), units.end());
  return units;
}

std::vector<std::uint32_t> all_units(const ClusterLayout& layout) {
  std::vector<std::uint32_t> units(layout.units());
  std::iota(units.begin(), units.end(), 0u);
  return units;
}

namespace {

// The error in metres that spans `lod.max_pixels` seen from the nearest point of `box`: an error's angle is
// error / distance radians.
float allowed_error(const Box& box, const LodChoice& lod) {
  return lod.max_pixels / lod.pixels_per_radian * distance_to(lod.eye, box);
}

}  // namespace

bool too_small_to_draw(const ClusterLayout& layout, std::uint32_t u, const LodChoice& lod) {
  if (!lod.leave_out_small || !(lod.max_pixels > 0.0f)) return false;
  const Box& box = layout.boxes[u];
  const glm::vec3 size(box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2]);
  return glm::length(size) <= allowed_error(box, lod);
}

int lod_level(const ClusterLayout& layout, const LaidOutForm& form, std::uint32_t u, const LodChoice& lod) {
  if (form.lod.empty() || !(lod.max_pixels > 0.0f)) return 0;
  const float allowed = allowed_error(layout.boxes[u], lod);
  int level = 0;
  for (std::uint32_t l = 0; l < model::kLodLevels; ++l)
    if (form.lod_error[u][l] <= allowed) level = int(l) + 1;
  return level;
}

DrawList cluster_draw_list(const ClusterLayout& layout, const LaidOutForm& form,
                           std::span<const std::uint32_t> units, const Frustum* frustum, const LodChoice* lod,
                           const PortalView* portals, const glm::vec3* nearest_first,
                           std::uint32_t run_triangles) {
  DrawList list;
  std::uint64_t opaque_end = 0, glass_end = 0;
  struct Opaque {
    float distance;
    std::uint32_t unit;
    IndexRange range;
  };
  std::vector<Opaque> opaque_units;
  for (const std::uint32_t u : units) {
    if (u >= layout.units() || layout.drawn[u] == 0) continue;
    if (frustum && !frustum->touches(layout.boxes[u])) continue;
    if (lod && too_small_to_draw(layout, u, *lod)) continue;
    const int level = lod ? lod_level(layout, form, u, *lod) : 0;
    const IndexRange opaque = level == 0 ? form.opaque[u] : form.lod[u][std::size_t(level - 1)];
    if (portals && !portals->shows(u)) {
      list.triangles_behind_portals += (opaque.count + form.glass[u].count) / 3;
      continue;
    }
    list.polygons += layout.drawn[u];
    list.triangles += (opaque.count + form.glass[u].count) / 3;
    list.units.push_back(u);
    if (nearest_first)
      opaque_units.push_back({distance_to(*nearest_first, layout.boxes[u]), u, opaque});
    else
      append(list.opaque, opaque, opaque_end);
    append(list.glass, form.glass[u], glass_end);
  }
  // Runs of units adjacent in the buffer, up to run_triangles each, sorted as one by their nearest unit.
  const std::uint64_t run_indices = 3 * std::uint64_t(run_triangles);
  std::size_t runs = 0;
  for (const Opaque& o : opaque_units) {
    Opaque& last = opaque_units[runs == 0 ? 0 : runs - 1];
    if (runs > 0 && last.range.first + last.range.count == o.range.first &&
        last.range.count + o.range.count <= run_indices) {
      last.range.count += o.range.count;
      last.distance = std::min(last.distance, o.distance);
    } else {
      opaque_units[runs++] = o;
    }
  }
  opaque_units.resize(runs);
  std::sort(opaque_units.begin(), opaque_units.end(), [](const Opaque& a, const Opaque& b) {
    return a.distance < b.distance || (a.distance == b.distance && a.unit < b.unit);
  });
  for (const Opaque& o : opaque_units) append(list.opaque, o.range, opaque_end);
  return list;
}

std::uint32_t triangles_of(const ClusterLayout& layout, const LaidOutForm& form,
                           std::span<const std::uint32_t> units, const LodChoice* lod) {
  std::uint32_t triangles = 0;
  for (const std::uint32_t u : units) {
    if (u >= layout.units() || (lod && too_small_to_draw(layout, u, *lod))) continue;
    const int level = lod ? lod_level(layout, form, u, *lod) : 0;
    const IndexRange opaque = level == 0 ? form.opaque[u] : form.lod[u][std::size_t(level - 1)];
    triangles += (opaque.count + form.glass[u].count) / 3;
  }
  return triangles;
}

}  // namespace walk::render
