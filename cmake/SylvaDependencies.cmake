# Third-party dependencies, all from Debian 12 packages (installed by scripts/setup).
# Works around three packaging quirks (see docs/architecture.md, "Build").

find_package(glm CONFIG REQUIRED)
find_package(Threads REQUIRED)
find_package(GDAL CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)

# OpenImageIO: the config needs openimageio-tools installed and lists a nonexistent
# /usr/include/opencv4 on Debian 12, which we strip from the imported target.
find_package(OpenImageIO CONFIG REQUIRED)
if(NOT EXISTS /usr/include/opencv4)
  foreach(_property INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
    get_target_property(_value OpenImageIO::OpenImageIO ${_property})
    if(_value)
      list(REMOVE_ITEM _value /usr/include/opencv4)
      set_target_properties(OpenImageIO::OpenImageIO PROPERTIES ${_property} "${_value}")
    endif()
  endforeach()
endif()

# GeographicLib ships no CMake config on Debian: use pkg-config.
find_package(PkgConfig REQUIRED)
pkg_check_modules(GEOGRAPHICLIB REQUIRED IMPORTED_TARGET geographiclib)
# The disk tile cache compresses entries with zstd (libzstd-dev; pkg-config).
pkg_check_modules(ZSTD REQUIRED IMPORTED_TARGET libzstd)
# Viewpoint sheets (core/scene/ViewpointSheet): PDF and PNG pages drawn with cairo.
pkg_check_modules(CAIRO REQUIRED IMPORTED_TARGET cairo)

# Plants (sylva_core): tinygltf is used header-only (TINYGLTF_IMPLEMENTATION in
# core/plants/TinyGltf.cpp); its image code is the packaged stb (libstb-dev), whose
# headers live in /usr/include/stb and whose implementation is libstb.so.
find_path(SYLVA_STB_INCLUDE_DIR stb_image.h PATHS /usr/include/stb REQUIRED)
find_library(SYLVA_STB_LIBRARY stb REQUIRED)
find_path(SYLVA_TINYGLTF_INCLUDE_DIR tiny_gltf.h REQUIRED)

# Buildings (sylva_core): roof triangulation and footprint validity with GEOS's C API
# (libgeos-dev; core/sources/objects/FootprintTriangulator).
find_package(GEOS 3.10 CONFIG REQUIRED)

# Levels of detail of imported models (sylva_core): OpenMesh's Decimater with the quadric
# module (libopenmesh-dev; core/sources/objects/MeshSimplifier).
find_package(OpenMesh CONFIG REQUIRED)

# GL side (sylva_render only).
find_package(glfw3 3.3 CONFIG REQUIRED)
pkg_check_modules(OSMESA REQUIRED IMPORTED_TARGET osmesa)
pkg_check_modules(EGL REQUIRED IMPORTED_TARGET egl)
# Dear ImGui (Debian libimgui-dev: the core and the GLFW and OpenGL 3 back ends in one
# static library) for the viewer's panels.
pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)

# glad2 GL 4.5 core loader, generated at build time by the packaged generator
# (python3-glad). `python3 -m glad` may pick another python: call /usr/bin/glad.
find_program(SYLVA_GLAD_EXECUTABLE glad PATHS /usr/bin NO_DEFAULT_PATH)
find_program(SYLVA_GLAD_EXECUTABLE glad REQUIRED)
set(SYLVA_GLAD_DIR ${CMAKE_BINARY_DIR}/glad)
add_custom_command(
  OUTPUT ${SYLVA_GLAD_DIR}/src/gl.c ${SYLVA_GLAD_DIR}/include/glad/gl.h
  COMMAND ${SYLVA_GLAD_EXECUTABLE} --quiet --reproducible --api gl:core=4.5
          --extensions GL_KHR_debug,GL_ARB_texture_filter_anisotropic,GL_EXT_texture_filter_anisotropic
          --out-path ${SYLVA_GLAD_DIR} c
  COMMENT "Generating the glad2 GL 4.5 core loader"
  VERBATIM)
add_library(sylva_glad STATIC ${SYLVA_GLAD_DIR}/src/gl.c)
target_include_directories(sylva_glad SYSTEM PUBLIC ${SYLVA_GLAD_DIR}/include)
set_target_properties(sylva_glad PROPERTIES POSITION_INDEPENDENT_CODE ON)

if(SYLVA_BUILD_TESTS)
  find_package(GTest CONFIG REQUIRED)
  include(GoogleTest)
endif()
