// Kept apart from the loop so code that never draws with GL (tests with a fake renderer) does not link GL.
#include <glad/gl.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <numbers>
#include <optional>

#include "firmware-host/frame_renderer.hpp"
#include "model/photometric_units.hpp"
#include "render/backend/backend.hpp"

namespace walk::kiosk {
namespace {

// Copies `part` into `out` with its left edge at column x0 (rows top first in both).
void paste(render::Image& out, const render::Image& part, int x0) {
  for (int y = 0; y < part.height && y < out.height; ++y)
    std::copy_n(&part.rgba[std::size_t(y) * part.width * 4], std::size_t(part.width) * 4,
                &out.rgba[(std::size_t(y) * out.width + x0) * 4]);
}

// [display] white_luminance (cd/m2) as the radiosity (W/m2) shown as white: a diffuse surface of radiosity B
// has luminance 179 B / pi.
std::optional<float> white_radiosity(const DisplayConfig& display) {
  if (!display.white_luminance) return std::nullopt;
  return float(*display.white_luminance * std::numbers::pi / model::kLumensPerWatt);
}

// One output (a window, a full-screen monitor or an off-screen surface) showing one or more views side by
// side: stereo eyes and screens of a spanning output each get a renderer of their own (its own refinement,
// accumulation and governor) presented into its part of the output.
class Output {
 public:
  Output(const model::Bundle& bundle, const DisplayConfig& display, int monitor, double views_in_frame)
      : bundle_(bundle),
        refine_(display.refine),
        target_hz_(display.target_hz * views_in_frame),
        frame_timing_(render::parse_frame_timing(display.frame_timing).value_or(render::FrameTiming::Auto)),
        white_radiosity_(white_radiosity(display)),
        light_form_(display.light_form == "full" ? render::DisplayLightForm::Full
                                                 : render::DisplayLightForm::AsCompiled) {
    render::BackendOptions options;
    options.kind = render::parse_backend_kind(display.backend);
    options.width = display.width;
    options.height = display.height;
    options.fullscreen = display.fullscreen;
    options.monitor = monitor;
    options.drm_device = display.drm_device;
    options.title = "Walkthrough";
    options.stereo = display.stereo == "quad_buffer";
    backend_ = render::Backend::create(options);
    backend_->make_current();
    quad_requested_ = options.stereo;
    quad_buffer_ = options.stereo && backend_->stereo();
    if (options.stereo && !quad_buffer_)
      spdlog::warn(
          "display.stereo = \"quad_buffer\": the {} context has no left and right back buffers; "
          "showing mono (use \"side_by_side\" for a 3D monitor or projector that takes it)",
          backend_->name());
  }
  ~Output() {
    try {
      backend_->make_current();  // GL objects must be released with their context current
      renderers_.clear();
    } catch (const std::exception& e) {  // a context already gone: its objects went with it
      spdlog::warn("closing an output: {}", e.what());
    }
  }
  [[nodiscard]] const render::Backend& backend() const { return *backend_; }
  [[nodiscard]] bool close_requested() { return backend_->close_requested(); }
  void set_dimmers(std::span<const float> levels) {
    levels_.assign(levels.begin(), levels.end());
    backend_->make_current();
    for (auto& r : renderers_) r->set_dimmers(levels);
  }
  bool draw(std::span<const render::View> views) {
    backend_->make_current();
    std::vector<render::View> chosen(views.begin(), views.end());
    // Quad-buffer stereo asked for but not granted: the eyes' pairs become their centres.
    if (quad_requested_ && !quad_buffer_ && chosen.size() % 2 == 0) chosen = centres_of_pairs(chosen);
    layout(chosen.size());
    bool any = false;
    std::vector<char> drew(chosen.size(), 0);
    for (std::size_t i = 0; i < chosen.size(); ++i) {
      const Region& at = regions_[i];
      if (refine_) {
        drew[i] = renderers_[i]->refine(chosen[i], at.width, at.height);
      } else {
        renderers_[i]->draw(chosen[i], at.width, at.height);
        drew[i] = 1;
      }
      any = any || drew[i];
    }
    // A swap leaves the back buffer undefined: parts whose view did not change are blitted again.
    if (any && chosen.size() > 1)
      for (std::size_t i = 0; i < chosen.size(); ++i)
        if (!drew[i]) renderers_[i]->present_again();
    drew_ = drew_ || any;
    return any;
  }
  void present() {
    backend_->make_current();
    if (drew_) backend_->present();  // an idle kiosk swaps nothing: the window keeps the converged picture
    drew_ = false;
    backend_->poll_events();
  }
  // The output's picture: every part side by side (left eyes with quad-buffered stereo).
  [[nodiscard]] render::Image capture() const {
    backend_->make_current();
    render::Image out;
    out.width = backend_->width();
    out.height = backend_->height();
    out.rgba.assign(std::size_t(out.width) * out.height * 4, 0);
    for (std::size_t i = 0; i < renderers_.size(); ++i) {
      const Region& at = regions_[i];
      if (at.present.buffer == render::WindowBuffer::BackRight) continue;
      paste(out, renderers_[i]->read_pixels(at.width, at.height), at.present.x);
    }
    return out;
  }

 private:
  struct Region {
    render::PresentRegion present;
    int width = 0, height = 0;
  };

  static std::vector<render::View> centres_of_pairs(const std::vector<render::View>& pairs) {
    std::vector<render::View> out;
    for (std::size_t i = 0; i + 1 < pairs.size(); i += 2) {
      render::View centre = pairs[i];
      centre.eye = 0.5 * (pairs[i].eye + pairs[i + 1].eye);
      out.push_back(centre);
    }
    return out;
  }

  // Regions side by side across the output: one per view, or with quad-buffered stereo one per eye pair,
  // the left eye into the left back buffer and the right into the right.
  void layout(std::size_t views) {
    if (views == regions_.size() && backend_->width() == width_ && backend_->height() == height_) return;
    width_ = backend_->width();
    height_ = backend_->height();
    const std::size_t columns = quad_buffer_ && views % 2 == 0 ? views / 2 : views;
    const int column_width = width_ / int(columns);
    regions_.assign(views, {});
    for (std::size_t i = 0; i < views; ++i) {
      const std::size_t column = columns == views ? i : i / 2;
      Region& r = regions_[i];
      r.present.x = int(column) * column_width;
      r.width = column + 1 == columns ? width_ - r.present.x : column_width;
      r.height = height_;
      if (columns != views)
        r.present.buffer = i % 2 ? render::WindowBuffer::BackRight : render::WindowBuffer::BackLeft;
    }
    while (renderers_.size() < views)
      renderers_.push_back(std::make_unique<render::Renderer>(bundle_, light_form_));
    renderers_.resize(views);
    for (std::size_t i = 0; i < views; ++i) {
      auto& r = *renderers_[i];
      r.set_present_to_window(backend_->has_window());
      r.set_present_region(regions_[i].present);
      // Every view's share of the frame: each governor holds (views in the whole frame) x the frame rate.
      r.set_target_rate(target_hz_ * double(views));
      r.set_frame_timing(frame_timing_);
      r.set_exposure(white_radiosity_);
      if (!levels_.empty()) r.set_dimmers(levels_);
    }
  }

  const model::Bundle& bundle_;
  bool refine_;
  double target_hz_;  // the frame rate times the views drawn on the other outputs
  render::FrameTiming frame_timing_;
  std::optional<float> white_radiosity_;  // [display] white_luminance as radiosity (W/m2); none: the bundle's
  render::DisplayLightForm light_form_;   // [display] light_form
  bool quad_requested_ = false, quad_buffer_ = false, drew_ = false;
  std::unique_ptr<render::Backend> backend_;
  std::vector<std::unique_ptr<render::Renderer>> renderers_;
  std::vector<Region> regions_;
  std::vector<float> levels_;
  int width_ = 0, height_ = 0;
};

// The kiosk's display: one output (screens side by side in it when there are several), or with
// display.outputs = "monitors" one output per screen on consecutive monitors from display.monitor.
class GlFrameRenderer final : public FrameRenderer {
 public:
  GlFrameRenderer(const model::Bundle& bundle, const DisplayConfig& display) {
    const std::size_t screens = std::max<std::size_t>(1, display.screens.size());
    const bool per_monitor = display.outputs == "monitors" && screens > 1;
    const std::size_t outputs = per_monitor ? screens : 1;
    for (std::size_t i = 0; i < outputs; ++i)
      outputs_.push_back(std::make_unique<Output>(bundle, display, display.monitor + int(i),
                                                  per_monitor ? double(outputs) : 1.0));
  }
  ~GlFrameRenderer() override { outputs_.clear(); }
  [[nodiscard]] const char* name() const override { return outputs_.front()->backend().name(); }
  void set_dimmers(std::span<const float> levels) override {
    for (auto& o : outputs_) o->set_dimmers(levels);
  }
  bool draw(const render::View& view) override { return draw_views(std::span<const render::View>(&view, 1)); }
  // Views come screen-major; with one output per screen, each output takes its screen's views.
  bool draw_views(std::span<const render::View> views) override {
    if (outputs_.size() == 1 || views.size() % outputs_.size() != 0) return outputs_.front()->draw(views);
    const std::size_t per_output = views.size() / outputs_.size();
    bool any = false;
    for (std::size_t i = 0; i < outputs_.size(); ++i)
      any = outputs_[i]->draw(views.subspan(i * per_output, per_output)) || any;
    return any;
  }
  // Every output's picture side by side.
  [[nodiscard]] render::Image capture() const override {
    if (outputs_.size() == 1) return outputs_.front()->capture();
    std::vector<render::Image> parts;
    render::Image out;
    for (const auto& o : outputs_) {
      parts.push_back(o->capture());
      out.width += parts.back().width;
      out.height = std::max(out.height, parts.back().height);
    }
    out.rgba.assign(std::size_t(out.width) * out.height * 4, 0);
    int x0 = 0;
    for (const auto& p : parts) {
      paste(out, p, x0);
      x0 += p.width;
    }
    return out;
  }
  void present(bool /*drew*/) override {
    for (auto& o : outputs_) o->present();
  }
  [[nodiscard]] bool windowed() const override { return outputs_.front()->backend().has_window(); }
  [[nodiscard]] bool close_requested() override {
    return std::any_of(outputs_.begin(), outputs_.end(), [](auto& o) { return o->close_requested(); });
  }

 private:
  std::vector<std::unique_ptr<Output>> outputs_;
};

}  // namespace

std::unique_ptr<FrameRenderer> make_gl_renderer(const model::Bundle& bundle, const DisplayConfig& display) {
  return std::make_unique<GlFrameRenderer>(bundle, display);
}

}  // namespace walk::kiosk
