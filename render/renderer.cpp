// The renderer: static buffers uploaded once, a draw list per cell built on first use, dimmer levels as
// uniforms. Everything is drawn into an FBO owned here; a window only ever receives a blit of it.
#include "render/renderer.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "model/error.hpp"
#include "render/camera.hpp"
#include "render/draw_list.hpp"
#include "render/framebuffer.hpp"
#include "render/gl_check.hpp"
#include "render/light_mixer.hpp"
#include "render/shader.hpp"
#include "render/tonemap.hpp"

namespace walk::render {

struct Renderer::Impl {
  const model::Bundle& bundle;
  ShaderProgram program{"scene", kLightMixerVertexShader, kTonemapFragmentShader};
  GLint u_view_projection = -1, u_light = -1, u_circuit_count = -1, u_levels = -1, u_ambient = -1,
        u_inv_exposure = -1, u_opacity = -1;
  GLuint vao = 0, vbo = 0, ibo = 0, light_buffer = 0, light_texture = 0;
  Framebuffer framebuffer;
  std::vector<float> levels;
  std::vector<std::optional<DrawList>> cell_lists;  // built on first visit
  std::optional<DrawList> all_list;
  bool culling = true;
  float glass_opacity = 0.25f;
  bool present_to_window = false;
  FrameStats stats;

  explicit Impl(const model::Bundle& b) : bundle(b) {}
  ~Impl() {
    glDeleteTextures(1, &light_texture);
    glDeleteBuffers(1, &light_buffer);
    glDeleteBuffers(1, &ibo);
    glDeleteBuffers(1, &vbo);
    glDeleteVertexArrays(1, &vao);
  }

  const DrawList& list_for(std::uint32_t cell) {
    if (cell >= cell_lists.size()) {
      if (!all_list) all_list = build_draw_list_all(bundle.polygons());
      return *all_list;
    }
    auto& slot = cell_lists[cell];
    if (!slot) {
      const auto& record = bundle.cells()[cell];
      slot = build_draw_list(bundle.polygons(), bundle.pvs().subspan(record.pvs_first, record.pvs_count));
    }
    return *slot;
  }
};

Renderer::Renderer(const model::Bundle& bundle) : impl_(std::make_unique<Impl>(bundle)) {
  auto& r = *impl_;
  const auto vertices = bundle.vertices();
  const auto indices = bundle.indices();
  const std::size_t circuits = bundle.circuits().size();
  if (circuits > std::size_t(kMaxCircuits))
    throw Error("bundle '" + bundle.path() + "' has " + std::to_string(circuits) +
                " circuits; the renderer mixes at most " + std::to_string(kMaxCircuits) +
                " (merge circuits that are always dimmed together)");
  if (bundle.light().size() != vertices.size() * circuits * 3)
    throw Error(
        "bundle '" + bundle.path() + "': LGHT holds " + std::to_string(bundle.light().size()) +
        " floats, expected vertices x circuits x 3 = " + std::to_string(vertices.size() * circuits * 3));
  GLint max_texels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  if (bundle.light().size() > std::size_t(max_texels))
    throw Error("bundle '" + bundle.path() + "': " + std::to_string(bundle.light().size()) +
                " radiosity values exceed this GL's texture buffer limit of " + std::to_string(max_texels) +
                "; compile with fewer circuits or a coarser mesh");

  r.u_view_projection = r.program.uniform("u_view_projection");
  r.u_light = r.program.uniform("u_light");
  r.u_circuit_count = r.program.uniform("u_circuit_count");
  r.u_ambient = r.program.uniform("u_ambient");
  r.u_inv_exposure = r.program.uniform("u_inv_exposure");
  r.u_opacity = r.program.uniform("u_opacity");
  // Unused (and so absent) when the shader has no circuits to loop over: not an error then.
  r.u_levels = glGetUniformLocation(r.program.id(), "u_levels[0]");

  r.levels.resize(circuits);
  for (std::size_t c = 0; c < circuits; ++c)
    r.levels[c] = std::clamp(bundle.circuits()[c].default_level, 0.0f, 1.0f);
  r.cell_lists.resize(bundle.cells().size());

  // Static geometry: the VERT records are uploaded as they are (stride 40) and never touched again.
  glGenVertexArrays(1, &r.vao);
  glBindVertexArray(r.vao);
  glGenBuffers(1, &r.vbo);
  glBindBuffer(GL_ARRAY_BUFFER, r.vbo);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size_bytes()), vertices.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(model::VertexRecord),
                        reinterpret_cast<const void*>(offsetof(model::VertexRecord, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(model::VertexRecord),
                        reinterpret_cast<const void*>(offsetof(model::VertexRecord, albedo)));
  glGenBuffers(1, &r.ibo);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r.ibo);  // recorded in the VAO
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size_bytes()), indices.data(), GL_STATIC_DRAW);
  glBindVertexArray(0);

  // Per-circuit radiosity, in LGHT's own layout; an empty buffer object still makes a valid texture.
  glGenBuffers(1, &r.light_buffer);
  glBindBuffer(GL_TEXTURE_BUFFER, r.light_buffer);
  glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(std::max<std::size_t>(bundle.light().size_bytes(), 4)),
               bundle.light().empty() ? nullptr : bundle.light().data(), GL_STATIC_DRAW);
  glGenTextures(1, &r.light_texture);
  glBindTexture(GL_TEXTURE_BUFFER, r.light_texture);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_R32F, r.light_buffer);
  glBindTexture(GL_TEXTURE_BUFFER, 0);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  check_gl("uploading the bundle's buffers");
}

Renderer::~Renderer() = default;

void Renderer::set_dimmers(std::span<const float> levels) {
  auto& own = impl_->levels;
  for (std::size_t c = 0; c < std::min(levels.size(), own.size()); ++c)
    own[c] = std::isnan(levels[c]) ? 0.0f : std::clamp(levels[c], 0.0f, 1.0f);
}

std::span<const float> Renderer::dimmers() const {
  return impl_->levels;
}
void Renderer::set_backface_culling(bool enabled) {
  impl_->culling = enabled;
}
void Renderer::set_present_to_window(bool enabled) {
  impl_->present_to_window = enabled;
}
void Renderer::set_glass_opacity(float opacity) {
  impl_->glass_opacity = std::clamp(opacity, 0.0f, 1.0f);
}
float Renderer::glass_opacity() const {
  return impl_->glass_opacity;
}
const FrameStats& Renderer::last_stats() const {
  return impl_->stats;
}

void Renderer::draw(const View& view, int width, int height) {
  auto& r = *impl_;
  const glm::mat4 view_projection_matrix = view_projection(view, double(width) / double(height));
  r.framebuffer.ensure_size(width, height);

  // The eye's cell decides what is drawn; without cells (or outside them all) everything is.
  std::uint32_t cell = FrameStats::kNoCell;
  if (!r.bundle.cells().empty()) {
    const double eye[3] = {view.eye.x, view.eye.y, view.eye.z};
    cell = r.bundle.locate_cell(eye);
    if (cell >= r.bundle.cells().size()) cell = FrameStats::kNoCell;
  }
  const DrawList& list = r.list_for(cell);

  glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer.id());
  glViewport(0, 0, width, height);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  if (r.culling) {
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
  } else {
    glDisable(GL_CULL_FACE);
  }

  if (!list.opaque.empty() || !list.glass.empty()) {
    const auto& meta = r.bundle.meta();
    glUseProgram(r.program.id());
    glUniformMatrix4fv(r.u_view_projection, 1, GL_FALSE, &view_projection_matrix[0][0]);
    glUniform1i(r.u_circuit_count, GLint(r.levels.size()));
    if (r.u_levels >= 0 && !r.levels.empty())
      glUniform1fv(r.u_levels, GLsizei(r.levels.size()), r.levels.data());
    glUniform1f(r.u_ambient, meta.ambient);
    glUniform1f(r.u_inv_exposure, meta.exposure > 0.0f ? 1.0f / meta.exposure : 1.0f);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_BUFFER, r.light_texture);
    glUniform1i(r.u_light, 0);
    glBindVertexArray(r.vao);
    auto draw_batch = [](const DrawBatch& batch) {
      glMultiDrawElements(GL_TRIANGLES, batch.counts.data(), GL_UNSIGNED_INT,
                          reinterpret_cast<const void* const*>(batch.byte_offsets.data()),
                          GLsizei(batch.counts.size()));
    };
    glUniform1f(r.u_opacity, 1.0f);
    if (!list.opaque.empty()) draw_batch(list.opaque);
    if (!list.glass.empty()) {
      // After everything opaque, depth-tested but not written, so glass behind glass still shows. Alpha
      // keeps 1 in the frame so read_pixels stays opaque.
      glUniform1f(r.u_opacity, r.glass_opacity);
      glEnable(GL_BLEND);
      glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
      glDepthMask(GL_FALSE);
      draw_batch(list.glass);
      glDepthMask(GL_TRUE);
      glDisable(GL_BLEND);
    }
    glBindVertexArray(0);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    glUseProgram(0);
  }

  if (r.present_to_window) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r.framebuffer.id());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  check_gl("drawing a frame");

  r.stats.cell = cell;
  r.stats.polygons_drawn = list.polygons;
  r.stats.triangles_drawn = list.triangles;
  r.stats.draw_ranges = std::uint32_t(list.opaque.counts.size() + list.glass.counts.size());
}

Image Renderer::read_pixels(int width, int height) const {
  const auto& fb = impl_->framebuffer;
  if (width != fb.width() || height != fb.height())
    throw Error("read_pixels(" + std::to_string(width) + "x" + std::to_string(height) +
                ") after drawing at " + std::to_string(fb.width()) + "x" + std::to_string(fb.height()) +
                "; draw at the size you read");
  Image image;
  image.width = width;
  image.height = height;
  image.rgba.resize(std::size_t(width) * height * 4);
  std::vector<std::uint8_t> bottom_up(image.rgba.size());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fb.id());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  check_gl("reading pixels");
  // GL's rows run bottom up; Image's run top down.
  const std::size_t row = std::size_t(width) * 4;
  for (int y = 0; y < height; ++y)
    std::copy_n(bottom_up.data() + std::size_t(height - 1 - y) * row, row,
                image.rgba.data() + std::size_t(y) * row);
  return image;
}

}  // namespace walk::render
