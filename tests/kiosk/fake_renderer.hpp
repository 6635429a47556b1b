#pragma once
// A FrameRenderer without GL: records what the loop asked for, and can request a stop mid-run.
#include <atomic>
#include <csignal>
#include <functional>
#include <vector>

#include "firmware-host/frame_renderer.hpp"

namespace walk::kiosk::testing {

class FakeRenderer final : public FrameRenderer {
 public:
  [[nodiscard]] const char* name() const override { return "fake"; }
  void set_dimmers(std::span<const float> l) override { levels.assign(l.begin(), l.end()); }
  bool draw(const render::View& view) override {
    views.push_back(view);
    if (on_draw) on_draw(views.size());
    return true;
  }
  bool draw_views(std::span<const render::View> v) override {
    view_sets.emplace_back(v.begin(), v.end());
    return draw(v.front());
  }
  [[nodiscard]] render::Image capture() const override {
    ++captures;
    return render::Image{2, 2, std::vector<std::uint8_t>(16, 128)};
  }

  std::vector<float> levels;
  std::vector<render::View> views;                   // the first view of every frame
  std::vector<std::vector<render::View>> view_sets;  // every view of every frame
  mutable std::size_t captures = 0;
  std::function<void(std::size_t frames)> on_draw;
};

}  // namespace walk::kiosk::testing
