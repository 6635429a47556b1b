# Optional Embree 3: the reference ray caster ("embree" backend of compiler/raycast). The core builds and
# works without it; with it, walk_compiler links embree and defines WALK_HAVE_EMBREE.
# Included after walk_compiler exists (from bench/CMakeLists.txt).
find_package(embree 3 QUIET)
option(WALK_WITH_EMBREE "Build the Embree 3 ray-caster backend (libembree-dev)" ${embree_FOUND})
if(WALK_WITH_EMBREE AND TARGET walk_compiler)
  if(NOT embree_FOUND)
    message(FATAL_ERROR "WALK_WITH_EMBREE is ON but Embree 3 was not found (apt install libembree-dev)")
  endif()
  target_link_libraries(walk_compiler PUBLIC embree)
  target_compile_definitions(walk_compiler PUBLIC WALK_HAVE_EMBREE=1)
  message(STATUS "Embree ${embree_VERSION}: ray-caster backend 'embree' enabled")
else()
  message(STATUS "Embree ray-caster backend disabled")
endif()
