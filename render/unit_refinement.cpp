#include "render/unit_refinement.hpp"

#include <algorithm>

#include "model/model.hpp"

namespace walk::render {

UnitRefinement::UnitRefinement(const RefinementInput& input, std::size_t kept_bytes)
    : input_(input), polygon_first_(input.units + 1, 0), units_(input.units), kept_limit_(kept_bytes) {
  // A counting sort of polygon ids by unit: each unit's polygons in id order.
  for (const std::uint32_t u : input.unit_of_polygon)
    if (u < input.units) ++polygon_first_[u + 1];
  for (std::size_t u = 0; u < input.units; ++u) polygon_first_[u + 1] += polygon_first_[u];
  polygon_ids_.resize(polygon_first_.back());
  std::vector<std::uint32_t> next(polygon_first_.begin(), polygon_first_.end() - 1);
  for (std::uint32_t p = 0; p < input.unit_of_polygon.size(); ++p)
    if (const std::uint32_t u = input.unit_of_polygon[p]; u < input.units) polygon_ids_[next[u]++] = p;
}

UnitRefinement::Update UnitRefinement::update(std::span<const std::uint32_t> units, const RefinementKey& key,
                                              const std::function<glm::vec3(std::uint32_t)>& colour_of,
                                              std::span<std::uint32_t> refined_indices,
                                              const std::function<bool()>& out_of_time) {
  if (key_ != key) {
    key_ = key;
    ++unmade_;
    for (const std::uint32_t u : keeping_) {
      Unit& unit = units_[u];
      kept_bytes_ -= unit.bytes();
      unit.made = false;
      unit.triangles = {};
      kept_bytes_ += unit.bytes();
    }
  }
  ++updates_;
  for (const std::uint32_t u : units)
    if (u < units_.size()) units_[u].seen = updates_;
  Update out;
  for (const std::uint32_t u : units) {
    if (u >= units_.size() || units_[u].made) continue;
    if (!out.made.empty() && out_of_time && out_of_time()) {
      out.finished = false;
      break;
    }
    make(u, colour_of, refined_indices);
    out.made.push_back(u);
  }
  if (kept_bytes_ > kept_limit_) let_go_of_unseen();
  return out;
}

void UnitRefinement::release(Unit& unit) {
  unmade_ += unit.made;
  kept_bytes_ -= unit.bytes();
  const std::uint64_t seen = unit.seen;
  unit = Unit{};
  unit.seen = seen;
}

void UnitRefinement::let_go_of_unseen() {
  // Oldest sight first; the units of this update's sight keep theirs whatever they hold.
  std::sort(keeping_.begin(), keeping_.end(),
            [&](std::uint32_t a, std::uint32_t b) { return units_[a].seen < units_[b].seen; });
  std::size_t k = 0;
  for (; k < keeping_.size() && kept_bytes_ > kept_limit_; ++k) {
    Unit& unit = units_[keeping_[k]];
    if (unit.seen == updates_) break;
    release(unit);
  }
  keeping_.erase(keeping_.begin(), keeping_.begin() + std::ptrdiff_t(k));
}

void UnitRefinement::make(std::uint32_t u, const std::function<glm::vec3(std::uint32_t)>& colour_of,
                          std::span<std::uint32_t> refined_indices) {
  Unit& unit = units_[u];
  kept_bytes_ -= unit.bytes();
  if (!unit.quads_found) {
    const std::span<const std::uint32_t> ids(polygon_ids_.data() + polygon_first_[u],
                                             polygon_first_[u + 1] - polygon_first_[u]);
    unit.quads = find_quads(input_.polygons, ids, input_.indices, input_.vertices);
    unit.quads_found = true;
    keeping_.push_back(u);
  }
  const std::size_t vertices = input_.vertices.size();
  if (!colour_) colour_ = std::make_unique_for_overwrite<glm::vec3[]>(vertices);
  const std::span<const glm::vec3> colour(colour_.get(), vertices);
  // Each corner once: a vertex is shared by up to four quads, and a mix walks its circuits' entries.
  std::vector<std::uint32_t> corners;
  corners.reserve(4 * unit.quads.size());
  for (const Quad& q : unit.quads) corners.insert(corners.end(), q.v.begin(), q.v.end());
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  for (const std::uint32_t v : corners)
    if (v < vertices) colour_[v] = colour_of(v);
  unit.flipped = std::uint32_t(choose_diagonals(unit.quads, colour, refined_indices));
  // Subdivision of opaque quads only: glass is blended and drawn last, apart.
  std::vector<Quad> opaque;
  for (const Quad& q : unit.quads)
    if (input_.polygons[q.polygon].role != std::uint32_t(model::Role::Glass)) opaque.push_back(q);
  Subdivision sub = subdivide(opaque, input_.vertices, colour, key_->threshold, key_->max_depth);
  unit.subdivided = std::uint32_t(sub.replaced_quads.size());
  unit.triangles = std::move(sub.triangles);
  unit.made = true;
  kept_bytes_ += unit.bytes();
}

void UnitRefinement::gather(std::span<const std::uint32_t> units, std::vector<ShadedVertex>& triangles,
                            std::vector<IndexRange>& runs) const {
  triangles.clear();
  runs.assign(units_.size(), {});
  append(units, triangles, runs, 0);
}

void UnitRefinement::append(std::span<const std::uint32_t> units, std::vector<ShadedVertex>& triangles,
                            std::vector<IndexRange>& runs, std::uint32_t first) const {
  for (const std::uint32_t u : units) {
    if (u >= units_.size() || u >= runs.size() || !units_[u].made || runs[u].count > 0) continue;
    const auto& t = units_[u].triangles;
    runs[u] = {first + std::uint32_t(triangles.size()), std::uint32_t(t.size())};
    triangles.insert(triangles.end(), t.begin(), t.end());
  }
}

void UnitRefinement::forget() {
  ++unmade_;
  for (Unit& unit : units_) unit = Unit{};
  keeping_.clear();
  kept_bytes_ = 0;
  key_.reset();
}

RefinementTotals UnitRefinement::totals(std::span<const std::uint32_t> units) const {
  RefinementTotals out;
  for (const std::uint32_t u : units) {
    if (u >= units_.size() || !units_[u].made) continue;
    out.quads_flipped += units_[u].flipped;
    out.quads_subdivided += units_[u].subdivided;
    out.subdivision_triangles += std::uint32_t(units_[u].triangles.size() / 3);
  }
  return out;
}

}  // namespace walk::render
