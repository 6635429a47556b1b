#pragma once
// The still view's quad diagonals and subdivision (the paper's third and fourth refinement steps), made unit
// by unit for the units a view may draw and kept for the mix they were made under, so a stop costs the CPU
// what the viewer's cell sees rather than the whole model (over every quad of the generated L building, 8.6 M
// triangles, one stop took 1.06 s before its first refined frame). Pure CPU.
#include <cstdint>
#include <functional>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "model/bundle_format.hpp"
#include "render/cluster_layout.hpp"
#include "render/diagonals.hpp"
#include "render/subdivision.hpp"

namespace walk::render {

// What the units are made from: the renderer's fine form as laid out by unit.
struct RefinementInput {
  std::span<const model::PolygonRecord> polygons;  // per polygon, its range in `indices` and its role
  std::span<const std::uint32_t> unit_of_polygon;  // ClusterLayout::kNoUnit: not drawn
  std::size_t units = 0;
  std::span<const model::VertexRecord> vertices;
  std::span<const std::uint32_t> indices;  // the bundle's diagonals, where the quads are found
};

// What the units were made for: when any of it changes, every unit is made again when next seen.
struct RefinementKey {
  std::vector<float> levels;  // the dimmers' mix
  float threshold = 0.0f;     // twist above which a quad is subdivided, in displayed radiosity
  int max_depth = 0;
  bool operator==(const RefinementKey&) const = default;
};

// Sums over a set of units, for FrameStats.
struct RefinementTotals {
  std::uint32_t quads_flipped = 0, quads_subdivided = 0, subdivision_triangles = 0;
};

// What the units not in the last sight may keep of their quads and sub-quads (bytes): past it the units
// seen longest ago let theirs go, and are made again when next seen. The generated L building's largest
// sight (a PVS of 65,136 sub-quad triangles) keeps about 7 MB; without a bound a long tour kept every
// cluster's, up to about 300 MB.
inline constexpr std::size_t kKeptRefinementBytes = std::size_t(64) << 20;

class UnitRefinement {
 public:
  explicit UnitRefinement(const RefinementInput& input, std::size_t kept_bytes = kKeptRefinementBytes);

  struct Update {
    std::vector<std::uint32_t> made;  // units made by this call: their ranges of refined indices changed
    bool finished = true;             // every unit asked for is made
  };
  // Makes each of `units` not yet made for `key`, in the order given: its quads (found on first use), their
  // diagonals by `colour_of` (a vertex's displayed radiosity) written into `refined_indices` (the fine
  // form's layout), and its opaque quads' sub-quads. After each unit made, stops once `out_of_time` says
  // so (when given), leaving the rest for the next call. `units` are the sight: then, while what the units
  // keep is over the bound, units outside it let theirs go, those seen longest ago first.
  Update update(std::span<const std::uint32_t> units, const RefinementKey& key,
                const std::function<glm::vec3(std::uint32_t)>& colour_of,
                std::span<std::uint32_t> refined_indices, const std::function<bool()>& out_of_time = {});

  // The sub-quad triangles of `units` (made ones), concatenated in the order given, and each unit's run in
  // them, in vertices; every other unit's run is empty.
  void gather(std::span<const std::uint32_t> units, std::vector<ShadedVertex>& triangles,
              std::vector<IndexRange>& runs) const;
  // Appends to `triangles` the sub-quad triangles of the made units of `units` that have no run in `runs`
  // (sized by gather) and gives each its run, counted from `first` (the vertices already gathered before
  // `triangles`): what a stop's slice made, after a gather of the same sight.
  void append(std::span<const std::uint32_t> units, std::vector<ShadedVertex>& triangles,
              std::vector<IndexRange>& runs, std::uint32_t first) const;

  // Counts the times made units were unmade (a new mix, forget, or let go past the bound): sub-quads
  // gathered while it had one value are still what the units hold while it has it.
  [[nodiscard]] std::uint64_t unmade() const { return unmade_; }

  [[nodiscard]] RefinementTotals totals(std::span<const std::uint32_t> units) const;

  // Forgets every unit's quads and what was made from them (new refine settings): the next update finds and
  // makes each again.
  void forget();

  // Bytes the units keep now (quads and sub-quad triangles).
  [[nodiscard]] std::size_t kept_bytes() const { return kept_bytes_; }

 private:
  struct Unit {
    bool quads_found = false;
    bool made = false;  // for key_
    std::vector<Quad> quads;
    std::vector<ShadedVertex> triangles;  // its sub-quads' triangles, three vertices each
    std::uint32_t flipped = 0, subdivided = 0;
    std::uint64_t seen = 0;  // the last update whose sight held it
    [[nodiscard]] std::size_t bytes() const {
      return quads.size() * sizeof(Quad) + triangles.size() * sizeof(ShadedVertex);
    }
  };
  void make(std::uint32_t u, const std::function<glm::vec3(std::uint32_t)>& colour_of,
            std::span<std::uint32_t> refined_indices);
  // Lets units not seen in this update drop what they keep, oldest first, until within the bound.
  void let_go_of_unseen();
  void release(Unit& unit);

  RefinementInput input_;
  std::vector<std::uint32_t> polygon_first_, polygon_ids_;  // per unit, its polygons (ids in order)
  std::vector<Unit> units_;
  std::optional<RefinementKey> key_;  // what the made units were made for; none before the first update
  std::size_t kept_limit_ = 0, kept_bytes_ = 0;
  std::vector<std::uint32_t> keeping_;  // units that may keep something (quads found)
  std::uint64_t updates_ = 0, unmade_ = 0;
  // Per vertex, written for the vertices of the quads being made only (the diagonal choice and the
  // subdivision index colour by vertex): left uninitialised, so a model's untouched pages cost nothing.
  std::unique_ptr<glm::vec3[]> colour_;
};

}  // namespace walk::render
