# The GL 3.3 core loader is generated at build time by Debian's python3-glad (works offline), so no
# generated code is committed. Each backend hands glad its own proc-address function.
find_program(GLAD_EXECUTABLE glad REQUIRED)
set(GLAD_OUT ${CMAKE_BINARY_DIR}/glad)
add_custom_command(
  OUTPUT ${GLAD_OUT}/src/gl.c ${GLAD_OUT}/include/glad/gl.h
  COMMAND ${GLAD_EXECUTABLE} --quiet --out-path ${GLAD_OUT} --api gl:core=3.3 --extensions GL_KHR_debug,GL_ARB_pipeline_statistics_query --reproducible c
  COMMENT "Generating the GL 3.3 core loader with glad"
  VERBATIM)
add_library(walk_glad STATIC ${GLAD_OUT}/src/gl.c)
target_include_directories(walk_glad PUBLIC ${GLAD_OUT}/include)
set_target_properties(walk_glad PROPERTIES POSITION_INDEPENDENT_CODE ON)
