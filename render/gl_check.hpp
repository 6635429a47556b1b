#pragma once
// GL error checks that cost nothing in release builds: glGetError stalls a real GPU pipeline.
namespace walk::render {

// Throws walk::Error naming `where` and the GL error when one is pending.
void throw_on_gl_error(const char* where);

#ifdef NDEBUG
inline void check_gl(const char*) {}
#else
inline void check_gl(const char* where) {
  throw_on_gl_error(where);
}
#endif

}  // namespace walk::render
