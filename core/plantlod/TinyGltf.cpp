// The one translation unit that compiles tinygltf's implementation (it is used
// header-only; see cmake/SylvaDependencies.cmake). stb_image comes from libstb.so, so
// only tinygltf itself is instantiated here. Warnings are the library's, not ours.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
#pragma GCC diagnostic pop
