#pragma once
// Loads the GL 3.3 core entry points through a backend's proc-address function. glad's pointers are
// process-wide, so every backend reloads them when it makes its context current (OSMesa and libGL/EGL are
// different Mesa builds whose pointers must not be mixed).
#include <glad/gl.h>

namespace walk::render {

// Throws walk::Error naming `backend` when loading fails or the context is older than 3.3.
void load_gl(GLADloadfunc load, const char* backend);

}  // namespace walk::render
