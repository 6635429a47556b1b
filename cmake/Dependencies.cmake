# Every dependency comes from a Debian 12 package (scripts/install-deps.sh installs them).
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)
# oneTBB: the compiler stages' parallel loops (work stealing, exceptions carried to the caller).
find_package(TBB REQUIRED)
find_package(meshoptimizer REQUIRED)  # cluster levels of detail (compiler/lod); Debian ships its CMake config
find_package(glm REQUIRED)
find_package(ZLIB REQUIRED)
find_package(PNG REQUIRED)
find_package(JPEG REQUIRED)  # albedo maps (libjpeg-turbo)
find_package(spdlog REQUIRED)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3 REQUIRED)  # walkd's summary.json
pkg_check_modules(TOMLPP REQUIRED IMPORTED_TARGET tomlplusplus)
pkg_check_modules(XXHASH REQUIRED IMPORTED_TARGET libxxhash)  # inputs-unchanged hashes (common/hash)
pkg_check_modules(POLYCLIPPING REQUIRED IMPORTED_TARGET polyclipping)
pkg_check_modules(PIXMAN REQUIRED IMPORTED_TARGET pixman-1)  # the half-resolution level's CPU upscale
find_package(assimp REQUIRED)  # mesh import (OBJ, glTF, 3DS...); Debian ships its CMake config
pkg_check_modules(SYSTEMD REQUIRED IMPORTED_TARGET libsystemd)

if(WALK_WITH_OSMESA)
  pkg_check_modules(OSMESA REQUIRED IMPORTED_TARGET osmesa)
endif()
if(WALK_WITH_EGL)
  pkg_check_modules(EGL REQUIRED IMPORTED_TARGET egl)
endif()
if(WALK_WITH_GLFW)
  pkg_check_modules(GLFW REQUIRED IMPORTED_TARGET glfw3)
endif()
if(WALK_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
