#include "render/cluster_layout.hpp"

#include <algorithm>
#include <cmath>
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

// Gives `form` vertices of its own, numbered by first use within each region (see LaidOutForm::vertices).
void renumber_vertices(LaidOutForm& form, std::size_t vertex_count) {
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> local(vertex_count, kNone);  // VERT id -> this region's id
  std::vector<std::uint32_t> region_of(vertex_count, kNone);
  std::size_t region = 0;
  for (std::size_t i = 0; i < form.indices.size(); ++i) {
    while (region + 1 < form.regions.size() && i >= form.regions[region + 1]) ++region;
    std::uint32_t& v = form.indices[i];
    if (v >= vertex_count) continue;  // the bundle reader has checked; kept out of range here too
    if (region_of[v] != region) {
      region_of[v] = std::uint32_t(region);
      local[v] = std::uint32_t(form.vertices.size());
      form.vertices.push_back(v);
    }
    v = local[v];
  }
}

}  // namespace

LayoutInput layout_input(const model::Bundle& bundle) {
  return {bundle.polygons(),         bundle.vertices(),       bundle.indices(),
          bundle.coarse_ranges(),    bundle.coarse_indices(), bundle.clusters(),
          bundle.cluster_polygons(), bundle.lod_ranges(),     bundle.lod_indices()};
}

ClusterLayout lay_out_clusters(const LayoutInput& in) {
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
    renumber_vertices(layout.coarse, in.vertices.size());
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
