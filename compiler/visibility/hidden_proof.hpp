#pragma once
// Makes the conservative PVS tight: for a polygon the portal flow lets through but no sample saw, try to
// prove that every sight line from the cell to it is blocked, and leave it out only when that succeeds.
// A sight line from a cell to a polygon outside it leaves the cell through one of its portals, so the
// proof runs from each portal the cell is seen out of (from the cell box itself for a polygon touching
// the cell). It splits the source (portal or box) and the target polygon into pieces until, for every pair
// of pieces, one plane's fused occluders (occluder_planes.hpp) block all the segments between them: walls
// in several planes that together hide a room do it piece by piece, which is occluder fusion across
// planes. Each pair first casts a sight line between the pieces' centres: one that reaches the polygon
// proves it visible (stop, keep it; on a window's side it only ends that branch), one that is blocked names
// the planes worth testing. Where a plane's
// cover leaves only small parts of the pair's sight lines open (where walls meet, a line past one wall's
// end meets the next), the proof goes on through each open part as a window: every sight line through it
// must be blocked before it (from the source to the window) or after it (from the window to the part of the
// target a line from the source through the window reaches).
// Splitting alone never settles the sight lines through a corner where two walls meet. A polygon left
// undecided when the budget runs out is kept, so the PVS stays conservative. A detail cluster is proven
// hidden face by face of its box (a sight line to it crosses the box's surface first), within the same
// budget of pairs.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "compiler/raycast/ray_caster.hpp"
#include "compiler/visibility/occluder_planes.hpp"

namespace walk::compiler {

struct ProofOptions {
  int max_pairs = 256;  // (viewer piece, target piece) pairs tried per polygon before it is kept
  int max_depth = 24;   // splits and windows along one branch of the proof
  bool cull_back_faces = true;
  // A plane's open part is followed as a window only while it is at most this fraction of the section:
  // where most of the sight lines pass, splitting the pair narrows them faster. 0: no windows.
  double window_fraction = 0.5;
  // Stop once the pairs taken and those the pieces still waiting will take exceed max_pairs: such a proof
  // cannot end hidden. Off: it runs to max_pairs (the tests compare the two).
  bool stop_early = true;
};

enum class Verdict { Hidden, Visible, Undecided };

struct ProofStats {
  std::uint64_t tried = 0, hidden = 0, visible = 0, undecided = 0;
  std::uint64_t pairs = 0;    // piece pairs looked at in all
  std::uint64_t windows = 0;  // of which a window on a plane's open part was source or target
  void add(const ProofStats& o) {
    tried += o.tried;
    hidden += o.hidden;
    visible += o.visible;
    undecided += o.undecided;
    pairs += o.pairs;
    windows += o.windows;
  }
};

// The pairs one item's proof may take, after what hiding it is worth (the triangles it takes out of the
// cell's draw): `proof_pairs` for an item of at least `mean_triangles` (the mean over the items the cell's
// proofs try; none known counts as the full allowance), in proportion below that, never under
// `least_pairs`; a detail cluster gets `least_pairs`. Never over `proof_pairs`, never negative.
[[nodiscard]] int proof_allowance(std::size_t triangles, double mean_triangles, bool cluster, int proof_pairs,
                                  int least_pairs);

class HiddenProver {
 public:
  // `caster` holds the polygons' triangles, each carrying its polygon's index.
  HiddenProver(const std::vector<VisPolygon>& polygons, const RayCaster& caster, bool cull_back_faces);

  // A cell's way out: a portal's convex hull and its plane facing out of the cell (Portal::out_of).
  struct Exit {
    Winding hull;
    Plane out;
  };
  // Is `target` hidden from every point of `cell`, whose sight lines leave it only through `exits`?
  [[nodiscard]] Verdict prove(const Box& cell, std::span<const Exit> exits, std::uint32_t target,
                              const ProofOptions& options, ProofStats* stats = nullptr) const;
  // Is `target` hidden from every point of `viewer` (kept kViewerInset inside its faces), whatever portals
  // the sight lines pass?
  [[nodiscard]] Verdict prove_from_box(const Box& viewer, std::uint32_t target, const ProofOptions& options,
                                       ProofStats* stats = nullptr) const;

  [[nodiscard]] const OccluderPlanes& planes() const { return planes_; }

 private:
  struct Sight {
    bool reaches = false;  // met the target first
    int blockers[4];       // occluder planes of the drawn opaque polygons met before it
    int count = 0;
    bool opaque_unnamed = false;  // blocked by a polygon of no occluder plane (not planar)
  };
  // Polygon ids: the sight line looks for `target` (kNoTarget: none, it ends at a window).
  static constexpr std::uint32_t kNoTarget = 0xffffffffu;
  [[nodiscard]] Sight sight(const model::Vec3& from, const model::Vec3& to, std::uint32_t target) const;
  // What a sight line must reach to see the target: its hull, or a detail cluster's box faces.
  [[nodiscard]] std::vector<Winding> target_outlines(std::uint32_t target) const;
  struct Search;
  struct Piece {
    Winding points;    // a box's eight corners, or a convex winding
    bool box = false;  // split as a box, not clipped as a winding
  };
  // Are all the segments from `source` to `dest` blocked? `dest_is_target`: dest is a piece of the target
  // polygon (else a window); `top`: source is a piece of the viewer, so a sight line that reaches the
  // target proves it visible. `takes`: takes_a_pair's answer for these pieces, where the caller has it.
  [[nodiscard]] bool hidden(const Piece& source, const Winding& dest, bool dest_is_target, bool top,
                            int depth, Search& search, std::optional<bool> takes = std::nullopt) const;
  // Will hidden(source, dest, dest_is_target, ...) take a pair, or settle the piece without one?
  [[nodiscard]] bool takes_a_pair(const Piece& source, const Winding& dest, bool dest_is_target,
                                  std::uint32_t target) const;
  // One branch a proof needs hidden: from `source` to `dest`, a piece of the target or its box.
  struct Job {
    const Piece* source;
    Winding dest;
  };
  // Every job hidden, in order (from the top of a proof), those still to come waiting (Search::pending)
  // while one is proven.
  [[nodiscard]] bool all_hidden(std::span<const Job> jobs, bool dest_is_target, Search& search) const;
  // Both pieces hidden, the second waiting (Search::pending) while the first is proven.
  [[nodiscard]] bool both_hidden(const Piece& s1, const Winding& d1, const Piece& s2, const Winding& d2,
                                 bool dest_is_target, bool top, int depth, Search& search) const;
  [[nodiscard]] bool piece_meets_polygon(const Winding& piece, std::uint32_t target) const;
  // Does the target (opaque, planar) face away from every point of the source piece?
  [[nodiscard]] bool faces_away(const Winding& source, std::uint32_t target) const;

  const std::vector<VisPolygon>& polygons_;
  const RayCaster& caster_;
  bool cull_back_faces_;
  OccluderPlanes planes_;
  std::vector<char> glass_;
  std::vector<char> convex_;  // the polygon fills its hull: every piece of the hull meets it
  std::vector<char> planar_;  // all its triangles lie in the plane of its normal through its hull
};

}  // namespace walk::compiler
