#include "render/gl_loader.hpp"

#include <string>

#include "model/error.hpp"

namespace walk::render {

void load_gl(GLADloadfunc load, const char* backend) {
  const int version = gladLoadGL(load);
  if (version == 0)
    throw Error(std::string(backend) + ": could not load OpenGL entry points (is a GL context current?)");
  if (GLAD_VERSION_MAJOR(version) < 3 ||
      (GLAD_VERSION_MAJOR(version) == 3 && GLAD_VERSION_MINOR(version) < 3))
    throw Error(std::string(backend) + ": OpenGL " + std::to_string(GLAD_VERSION_MAJOR(version)) + "." +
                std::to_string(GLAD_VERSION_MINOR(version)) + " context, but 3.3 core is needed");
}

}  // namespace walk::render
