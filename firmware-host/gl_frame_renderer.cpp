// Kept apart from the loop so code that never draws with GL (tests with a fake renderer) does not link GL.
#include <glad/gl.h>

#include "firmware-host/frame_renderer.hpp"
#include "render/backend/backend.hpp"

namespace walk::kiosk {
namespace {

class GlFrameRenderer final : public FrameRenderer {
 public:
  GlFrameRenderer(const model::Bundle& bundle, const DisplayConfig& display) : refine_(display.refine) {
    render::BackendOptions options;
    options.kind = render::parse_backend_kind(display.backend);
    options.width = display.width;
    options.height = display.height;
    options.fullscreen = display.fullscreen;
    options.monitor = display.monitor;
    options.drm_device = display.drm_device;
    options.title = "Walkthrough";
    backend_ = render::Backend::create(options);
    backend_->make_current();
    renderer_ = std::make_unique<render::Renderer>(bundle);
    renderer_->set_present_to_window(backend_->has_window());
    renderer_->set_target_rate(display.target_hz);
  }
  ~GlFrameRenderer() override {
    backend_->make_current();  // GL objects must be released with their context current
    renderer_.reset();
  }
  [[nodiscard]] const char* name() const override { return backend_->name(); }
  void set_dimmers(std::span<const float> levels) override { renderer_->set_dimmers(levels); }
  bool draw(const render::View& view) override {
    if (refine_) return renderer_->refine(view, backend_->width(), backend_->height());
    renderer_->draw(view, backend_->width(), backend_->height());
    return true;
  }
  void save_png(const std::string& path) override {
    render::write_png(path, renderer_->read_pixels(backend_->width(), backend_->height()));
  }
  void present(bool drew) override {
    if (drew) backend_->present();  // an idle kiosk swaps nothing: the window keeps the converged picture
    backend_->poll_events();
  }
  [[nodiscard]] bool windowed() const override { return backend_->has_window(); }
  [[nodiscard]] bool close_requested() override { return backend_->close_requested(); }

 private:
  bool refine_;
  std::unique_ptr<render::Backend> backend_;
  std::unique_ptr<render::Renderer> renderer_;
};

}  // namespace

std::unique_ptr<FrameRenderer> make_gl_renderer(const model::Bundle& bundle, const DisplayConfig& display) {
  return std::make_unique<GlFrameRenderer>(bundle, display);
}

}  // namespace walk::kiosk
