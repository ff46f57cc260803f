// GridMesh: the brute-force terrain of `sylva bench terrain`: every sample of an
// ElevationGrid a vertex (ECEF relative to a centre, float), every cell two triangles,
// drawn with bench/grid.vert|frag into the bound G-buffer (reversed-Z, depth GREATER).
// Needs a current GL 4.5 context; owns its vertex array and buffers.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "GridElevationSource.h"
#include "sylva/core/base/Result.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/render/gl/GlHandle.h"
#include "sylva/render/gl/ShaderLibrary.h"
#include "sylva/render/gl/ShaderProgram.h"

namespace sylva::bench {

class GridMesh {
public:
    // `library` must hold the bench shaders (withBenchShaders); `centre` is the ECEF
    // point vertices are stored relative to (metres). Fails if the shaders do not build.
    static Result<GridMesh> create(const render::ShaderLibrary& library, const ElevationGrid& grid,
                                   const glm::dvec3& centre);
    GridMesh() = default;  // move-only: the GL objects are GlHandles

    std::size_t triangles() const { return indexCount_ / 3; }
    void draw(const Camera& camera, const glm::dmat4& projection);

private:
    render::ShaderProgram program_;
    render::GlVertexArray vertexArray_;
    render::GlBuffer vertexBuffer_;
    render::GlBuffer indexBuffer_;
    std::size_t indexCount_ = 0;
    glm::dvec3 centre_{};
};

}  // namespace sylva::bench
