// Backend names, selection and errors; the two headless backends agree on the same frame.
#include <glad/gl.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "model/error.hpp"
#include "render_test_support.hpp"
#include "two_rooms.hpp"

namespace walk::render::test {
namespace backend_test {  // named, not anonymous: the suite compiles as unity batches

TEST(BackendNames, RoundTrip) {
  for (BackendKind kind :
       {BackendKind::Auto, BackendKind::OSMesa, BackendKind::EGL, BackendKind::GLFW, BackendKind::GBM})
    EXPECT_EQ(parse_backend_kind(backend_kind_name(kind)), kind);
}

TEST(BackendNames, UnknownNameListsTheAcceptedValues) {
  try {
    (void)parse_backend_kind("vulkan");
    FAIL() << "'vulkan' accepted";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'vulkan'"), std::string::npos) << message;
    EXPECT_NE(message.find("auto, osmesa, egl, glfw"), std::string::npos) << message;
  }
}

// GBM/KMS cannot run here (no /dev/dri); what must hold everywhere is a clear error naming the device.
TEST(Backends, GbmWithoutADisplayDeviceIsAClearError) {
  BackendOptions options;
  options.kind = BackendKind::GBM;
  options.drm_device = "/nonexistent/dri/card7";
  try {
    (void)Backend::create(options);
    FAIL() << "gbm started on a device that does not exist";
  } catch (const Error& e) {
    const std::string message = e.what();
#if WALK_WITH_GBM
    EXPECT_NE(message.find("/nonexistent/dri/card7"), std::string::npos) << message;
#else
    EXPECT_NE(message.find("WALK_WITH_GBM"), std::string::npos) << message;
#endif
    EXPECT_NE(message.find("another backend"), std::string::npos) << message;
  }
}

TEST(Backends, EachHeadlessBackendGivesACoreContext) {
  for (BackendKind kind : {BackendKind::OSMesa, BackendKind::EGL}) {
    auto backend = headless(kind, 64, 48);
    EXPECT_STREQ(backend->name(), backend_kind_name(kind));
    EXPECT_EQ(backend->width(), 64);
    EXPECT_EQ(backend->height(), 48);
    EXPECT_FALSE(backend->has_window());
    GLint version_major = 0, version_minor = 0, profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &version_major);
    glGetIntegerv(GL_MINOR_VERSION, &version_minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    EXPECT_GE(version_major * 10 + version_minor, 33) << backend->name();
    EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT) << backend->name();
  }
}

// Sets (or with nullptr, unsets) an environment variable for one scope: the GLFW test in this binary needs
// DISPLAY intact under xvfb-run.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old, had_ = true;
    if (value)
      ::setenv(name, value, 1);
    else
      ::unsetenv(name);
  }
  ~ScopedEnv() {
    if (had_)
      ::setenv(name_, old_.c_str(), 1);
    else
      ::unsetenv(name_);
  }

 private:
  const char* name_;
  std::string old_;
  bool had_ = false;
};

std::string auto_backend_name() {
  BackendOptions options;
  options.width = 32;
  options.height = 32;
  return Backend::create(options)->name();
}

TEST(Backends, AutoWithoutADisplayPicksEgl) {
  ScopedEnv display("DISPLAY", nullptr), wayland("WAYLAND_DISPLAY", nullptr);
  EXPECT_EQ(auto_backend_name(), "egl");
}

TEST(Backends, AutoFallsBackWhenTheDisplayCannotBeOpened) {
  ScopedEnv display("DISPLAY", ":4242"), wayland("WAYLAND_DISPLAY", nullptr);  // no server there
  EXPECT_EQ(auto_backend_name(), "egl");
}

TEST(Backends, RequestedBackendThatFailsNamesItself) {
#if WALK_WITH_GLFW
  ScopedEnv display("DISPLAY", ":4242"), wayland("WAYLAND_DISPLAY", nullptr);
  BackendOptions options;
  options.kind = BackendKind::GLFW;
  try {
    (void)Backend::create(options);
    FAIL() << "a window opened on a display that does not exist";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'glfw' could not start"), std::string::npos) << message;
    EXPECT_NE(message.find("auto, osmesa, egl, glfw"), std::string::npos) << message;
  }
#endif
}

TEST(Backends, BadSizeIsAnError) {
  BackendOptions options;
  options.kind = BackendKind::OSMesa;
  options.width = 0;
  EXPECT_THROW((void)Backend::create(options), Error);
}

TEST(Backends, OSMesaAndEglDrawTheSameFrame) {
  TwoRooms scene;
  auto bundle = open_two_rooms(scene, "same_frame");
  Image images[2];
  int i = 0;
  for (BackendKind kind : {BackendKind::OSMesa, BackendKind::EGL}) {
    auto backend = headless(kind, 320, 240);
    Renderer renderer(*bundle);
    renderer.draw(looking_along_x(+1.0, 0.5), 320, 240);
    images[i++] = renderer.read_pixels(320, 240);
  }
  ASSERT_EQ(images[0].rgba.size(), images[1].rgba.size());
  int worst = 0;
  for (std::size_t k = 0; k < images[0].rgba.size(); ++k)
    worst = std::max(worst, std::abs(int(images[0].rgba[k]) - int(images[1].rgba[k])));
  EXPECT_LE(worst, 1) << "largest difference between OSMesa and EGL, in 8-bit steps";
}

}  // namespace backend_test
}  // namespace walk::render::test
