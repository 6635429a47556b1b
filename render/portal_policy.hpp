#pragma once
// Whether the per-frame portal walk (portal_view.hpp) pays in a cell. Where a cell's portals are tight (rooms
// whose walls lie on cell faces) the walk hides what the doors hide; where they are loose (cells that hold
// the void round a Quake level, walls inside cells) it reaches most cells, hides almost nothing and still
// costs its walk: E1M1, 187 cells reached and 1.5 % of the clusters hidden, 0.2-0.5 ms a walk plus 0.1-1 ms
// of box tests. So each cell's first frames measure the share of triangles the walk hides; below
// kMinHiddenShare the cell rests from walking for kRestFrames of its frames, then measures again (the views
// change as the viewer moves). Either way the picture is the same: the walk is conservative. Pure CPU.
#include <cstdint>
#include <vector>

namespace walk::render {

class PortalPolicy {
 public:
  // Frames a cell is measured over before it is judged.
  static constexpr std::uint32_t kProbeFrames = 16;
  // The share of a frame's triangles the walk must hide to be kept: on llvmpipe a tenth of E1M1's 20,000
  // triangles is about the 1 ms its walk costs at worst.
  static constexpr double kMinHiddenShare = 0.10;
  // Frames drawn in the cell without walking before it is measured again: about 4 s at 60 Hz.
  static constexpr std::uint32_t kRestFrames = 240;

  explicit PortalPolicy(std::size_t cells) : cells_(cells) {}
  // Should a frame in `cell` walk the portals?
  [[nodiscard]] bool walk(std::uint32_t cell) const {
    return cell >= cells_.size() || cells_[cell].resting == 0;
  }
  // After a frame that walked: triangles hidden by the walk and triangles drawn.
  void record(std::uint32_t cell, std::uint64_t hidden, std::uint64_t drawn);
  // After a frame in `cell` that did not walk.
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
