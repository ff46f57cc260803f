#include "GridMesh.h"

#include <glad/gl.h>

#include <utility>
#include <vector>

#include "sylva/core/base/WorkerPool.h"
#include "sylva/core/geo/Ellipsoid.h"

namespace sylva::bench {

using namespace sylva::render;

Result<GridMesh> GridMesh::create(const ShaderLibrary& library, const ElevationGrid& grid,
                                  const glm::dvec3& centre) {
    GridMesh mesh;
    Result<ShaderProgram> program = ShaderProgram::create(
        library, {{GL_VERTEX_SHADER, "bench/grid.vert"}, {GL_FRAGMENT_SHADER, "bench/grid.frag"}});
    if (!program) {
        return program.error();
    }
    mesh.program_ = std::move(program.value());
    mesh.centre_ = centre;
    std::vector<float> positions(std::size_t(grid.width) * grid.height * 3);
    WorkerPool::shared().run(grid.height, [&](int row) {
        const double latitude = grid.north - row * grid.sampleSpacingLatitude();
        for (int column = 0; column < grid.width; ++column) {
            const std::size_t i = std::size_t(row) * grid.width + column;
            const glm::dvec3 p =
                Ellipsoid::toEcef({latitude, grid.west + column * grid.sampleSpacingLongitude(),
                                   double(grid.heights[i])});
            const glm::vec3 relative(p - mesh.centre_);
            positions[i * 3] = relative.x;
            positions[i * 3 + 1] = relative.y;
            positions[i * 3 + 2] = relative.z;
        }
    });
    std::vector<std::uint32_t> indices(std::size_t(grid.width - 1) * (grid.height - 1) * 6);
    WorkerPool::shared().run(grid.height - 1, [&](int row) {
        std::size_t k = std::size_t(row) * (grid.width - 1) * 6;
        for (int column = 0; column < grid.width - 1; ++column) {
            const std::uint32_t a = std::uint32_t(row * grid.width + column);
            const std::uint32_t b = a + std::uint32_t(grid.width);
            for (std::uint32_t v : {a, b, b + 1, a, b + 1, a + 1}) {
                indices[k++] = v;
            }
        }
    });
    mesh.indexCount_ = indices.size();
    mesh.vertexArray_ = render::createGlVertexArray();
    mesh.vertexBuffer_ = render::createGlBuffer();
    mesh.indexBuffer_ = render::createGlBuffer();
    const GLuint vertexArray = mesh.vertexArray_.get();
    glNamedBufferStorage(mesh.vertexBuffer_.get(), GLsizeiptr(positions.size() * sizeof(float)),
                         positions.data(), 0);
    glNamedBufferStorage(mesh.indexBuffer_.get(),
                         GLsizeiptr(indices.size() * sizeof(std::uint32_t)), indices.data(), 0);
    glVertexArrayVertexBuffer(vertexArray, 0, mesh.vertexBuffer_.get(), 0, 3 * sizeof(float));
    glVertexArrayElementBuffer(vertexArray, mesh.indexBuffer_.get());
    glEnableVertexArrayAttrib(vertexArray, 0);
    glVertexArrayAttribFormat(vertexArray, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vertexArray, 0, 0);
    return mesh;
}

void GridMesh::draw(const Camera& camera, const glm::dmat4& projection) {
    const glm::dmat3 view = camera.viewRotation();
    program_.setMat3("uEcefToView", glm::mat3(view));
    program_.setVec3("uCentreToCamera", glm::vec3(view * (centre_ - camera.position)));
    program_.setMat4("uProjection", glm::mat4(projection));
    program_.use();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glBindVertexArray(vertexArray_.get());
    glDrawElements(GL_TRIANGLES, GLsizei(indexCount_), GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
}

}  // namespace sylva::bench
