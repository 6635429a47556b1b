#pragma once
// A real GL FrameRenderer (OSMesa, headless) that also measures each frame: mean brightness of the whole
// image, so end-to-end tests can see a dimmer change in pixels. Uses only render/'s public API.
#include <functional>
#include <memory>
#include <vector>

#include "firmware-host/frame_renderer.hpp"
#include "render/backend/backend.hpp"
#include "render/renderer.hpp"

namespace walk::kiosk::testing {

class GlProbeRenderer final : public FrameRenderer {
 public:
  GlProbeRenderer(const model::Bundle& bundle, int width, int height) : width_(width), height_(height) {
    render::BackendOptions o;
    o.kind = render::parse_backend_kind("osmesa");
    o.width = width;
    o.height = height;
    backend_ = render::Backend::create(o);
    backend_->make_current();
    renderer_ = std::make_unique<render::Renderer>(bundle);
  }
  ~GlProbeRenderer() override {
    backend_->make_current();
    renderer_.reset();
  }
  [[nodiscard]] const char* name() const override { return "osmesa-probe"; }
  void set_dimmers(std::span<const float> l) override {
    levels.assign(l.begin(), l.end());
    renderer_->set_dimmers(l);
  }
  bool draw(const render::View& view) override {
    renderer_->draw(view, width_, height_);
    const render::Image img = renderer_->read_pixels(width_, height_);
    double sum = 0.0;
    for (std::size_t i = 0; i < img.rgba.size(); i += 4)
      sum += img.rgba[i] + img.rgba[i + 1] + img.rgba[i + 2];
    brightness.push_back(sum / (3.0 * width_ * height_));
    if (on_draw) on_draw(brightness.size());
    return true;
  }
  [[nodiscard]] render::Image capture() const override { return renderer_->read_pixels(width_, height_); }

  std::vector<float> levels;
  std::vector<double> brightness;  // per frame, mean of R, G, B in 0..255
  std::function<void(std::size_t frames)> on_draw;

 private:
  int width_, height_;
  std::unique_ptr<render::Backend> backend_;
  std::unique_ptr<render::Renderer> renderer_;
};

}  // namespace walk::kiosk::testing
