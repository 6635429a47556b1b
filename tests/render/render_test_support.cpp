#include "render_test_support.hpp"

namespace walk::render::test {

std::unique_ptr<Backend> headless(BackendKind kind, int width, int height) {
  BackendOptions options;
  options.kind = kind;
  options.width = width;
  options.height = height;
  auto backend = Backend::create(options);
  backend->make_current();
  return backend;
}

View looking_along_x(double sign, double eye_x) {
  View view;
  view.eye = {eye_x, 2.0, 1.5};
  view.forward = {sign, 0.0, 0.0};
  return view;
}

const std::uint8_t* centre(const Image& image) {
  return image.pixel(image.width / 2, image.height / 2);
}

}  // namespace walk::render::test
