// The shaders of sylva_bench (bench/shaders), embedded at build time by
// cmake/EmbedShaders.cmake into BenchShaders.cpp under the paths "bench/<file>".
#pragma once

#include <cstddef>

#include "sylva/render/gl/ShaderLibrary.h"

namespace sylva::bench {

extern const render::detail::EmbeddedShader kBenchShaders[];
extern const std::size_t kBenchShadersCount;

// `library` plus the benchmark shaders.
inline render::ShaderLibrary withBenchShaders(const render::ShaderLibrary& library) {
    return library.withEmbedded(kBenchShaders, kBenchShadersCount);
}

}  // namespace sylva::bench
