#pragma once
// What the main loop needs from the display: set dimmers, draw a view, save a frame, present it. An
// interface so daemon tests run without GL (a counting fake) and the real kiosk uses render::Renderer.
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "firmware-host/kiosk_config.hpp"
#include "model/bundle.hpp"
#include "render/renderer.hpp"

namespace walk::kiosk {

class FrameRenderer {
 public:
  virtual ~FrameRenderer() = default;
  [[nodiscard]] virtual const char* name() const = 0;
  virtual void set_dimmers(std::span<const float> levels) = 0;  // one per circuit, 0..1
  // Returns whether the picture changed: a refining renderer draws nothing once a still view has converged.
  virtual bool draw(const render::View& view) = 0;
  // Several views of one frame (stereo eyes, screens of a spanning output), each in its own part of the
  // output; returns whether any drew. A renderer with one output part draws the first.
  virtual bool draw_views(std::span<const render::View> views) { return draw(views.front()); }
  // The picture now shown, read back on the render thread (walkd encodes and writes it on another).
  [[nodiscard]] virtual render::Image capture() const = 0;
  virtual void present(bool /*drew*/) {}  // shows a new picture, if drawn; handles window events either way
  [[nodiscard]] virtual bool windowed() const { return false; }  // a window runs in real time
  [[nodiscard]] virtual bool close_requested() { return false; }
};

// The GL renderer on the backend the display config names. Throws walk::Error when it cannot start.
[[nodiscard]] std::unique_ptr<FrameRenderer> make_gl_renderer(const model::Bundle& bundle,
                                                              const DisplayConfig& display);

}  // namespace walk::kiosk
