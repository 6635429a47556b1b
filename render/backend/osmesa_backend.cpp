// OSMesa: a core 3.3 context drawing into client memory (llvmpipe). The renderer draws into its own FBO, so
// this buffer only has to exist for OSMesaMakeCurrent.
#include <glad/gl.h>
// glad first: it provides the GL types osmesa.h needs and stops it including <GL/gl.h>.
#include <GL/osmesa.h>

#include <string>
#include <vector>

#include "model/error.hpp"
#include "render/backend/backend_factories.hpp"
#include "render/gl_loader.hpp"

namespace walk::render::detail {
namespace {

class OSMesaBackend final : public Backend {
 public:
  explicit OSMesaBackend(const BackendOptions& options) : width_(options.width), height_(options.height) {
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           24,
                           OSMESA_STENCIL_BITS,
                           0,
                           OSMESA_ACCUM_BITS,
                           0,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           3,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           3,
                           0};
    context_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!context_) throw Error("osmesa: OSMesaCreateContextAttribs failed for a GL 3.3 core context");
    buffer_.resize(std::size_t(width_) * height_ * 4);
    make_current();
  }
  ~OSMesaBackend() override {
    if (context_) OSMesaDestroyContext(context_);
  }

  const char* name() const override { return "osmesa"; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  void make_current() override {
    if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_))
      throw Error("osmesa: OSMesaMakeCurrent failed");
    load_gl(reinterpret_cast<GLADloadfunc>(OSMesaGetProcAddress), "osmesa");
  }

 private:
  int width_;
  int height_;
  OSMesaContext context_ = nullptr;
  std::vector<unsigned char> buffer_;
};

}  // namespace

std::unique_ptr<Backend> make_osmesa_backend(const BackendOptions& options) {
  return std::make_unique<OSMesaBackend>(options);
}

}  // namespace walk::render::detail
