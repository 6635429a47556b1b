#pragma once
// The build's version: the project's (CMakeLists.txt) and `git describe` of the source at build time, e.g.
// "0.1.0+git.890d9a5c1e" or "0.1.0+git.890d9a5c1e-dirty"; the project's alone outside a git checkout.
namespace walk {

[[nodiscard]] const char* version();

}  // namespace walk
