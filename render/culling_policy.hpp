#pragma once
// Whether a per-frame culling pays in a cell: the portal walk (portal_view.hpp) or occlusion culling
// (occluders.hpp), one policy each. Where a cell's portals are tight (rooms whose walls lie on cell faces)
// the walk hides what the doors hide; where they are loose (cells that hold the void round a Quake level,
// walls inside cells) it reaches most cells, hides almost nothing and still costs its walk: E1M1, 187 cells
// reached and 1.5 % of the clusters hidden, 0.2-0.5 ms a walk plus 0.1-1 ms of box tests. Occlusion culling
// likewise costs 0.2-1 ms a view and hides nothing in an office whose portals leave only what is seen. So
// each cell's first frames measure the share of triangles the culling hides; below kMinHiddenShare the
// cell rests from it for kRestFrames of its frames, then measures again (the views change as the viewer
// moves). Either way the picture is the same: both cullings are conservative. Pure CPU.
#include <cstdint>
#include <vector>

namespace walk::render {

class CullingPolicy {
 public:
  // Frames a cell is measured over before it is judged.
  static constexpr std::uint32_t kProbeFrames = 16;
  // The share of a frame's triangles the culling must hide to be kept: on llvmpipe a tenth of E1M1's 20,000
  // triangles is about the 1 ms its walk (or occlusion buffer) costs at worst.
  static constexpr double kMinHiddenShare = 0.10;
  // Frames drawn in the cell without walking before it is measured again: about 4 s at 60 Hz.
  static constexpr std::uint32_t kRestFrames = 240;

  explicit CullingPolicy(std::size_t cells) : cells_(cells) {}
  // Should a frame in `cell` cull this way?
  [[nodiscard]] bool applies(std::uint32_t cell) const {
    return cell >= cells_.size() || cells_[cell].resting == 0;
  }
  // After a frame that culled: triangles hidden by the culling and triangles drawn.
  void record(std::uint32_t cell, std::uint64_t hidden, std::uint64_t drawn);
  // After a frame in `cell` that did not cull this way.
  void rested(std::uint32_t cell);
  [[nodiscard]] std::size_t cells_resting() const;

 private:
  struct Cell {
    std::uint64_t hidden = 0, total = 0;
    std::uint32_t probes = 0, resting = 0;
  };
  std::vector<Cell> cells_;
};

}  // namespace walk::render
