#include "sylva/bench/AtmosphereBenchmark.h"
#include "sylva/bench/BenchmarkMetrics.h"

#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <vector>

#include "BenchShaders.h"
#include "GridMesh.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/render/gl/Framebuffer.h"
#include "sylva/render/scene/SceneRenderer.h"
#include "sylva/render/shading/ShadingPass.h"

namespace sylva::bench {
namespace {

using namespace sylva::render;

constexpr double kDegree = 3.14159265358979323846 / 180.0;
constexpr double kCentreLatitude = 46.0 * kDegree;  // as the terrain bench
constexpr double kCentreLongitude = 8.0 * kDegree;
constexpr double kAltitudes[] = {800e3, 100e3, 10e3, 1e3, 50.0};

// A smooth 4-degree relief (hills of 1.5 km): the G-buffer only decides which pixels
// are ground and how far they are.
ElevationGrid syntheticDem() {
    ElevationGrid grid;
    grid.width = grid.height = 512;
    grid.west = kCentreLongitude - 2 * kDegree;
    grid.east = kCentreLongitude + 2 * kDegree;
    grid.south = kCentreLatitude - 2 * kDegree;
    grid.north = kCentreLatitude + 2 * kDegree;
    grid.heights.resize(std::size_t(grid.width) * grid.height);
    for (int row = 0; row < grid.height; ++row) {
        for (int column = 0; column < grid.width; ++column) {
            const double x = column * 0.07, y = row * 0.05;
            grid.heights[std::size_t(row) * grid.width + column] =
                float(800 + 700 * std::sin(x) * std::cos(y) + 200 * std::sin(3.1 * x + 2.3 * y));
        }
    }
    return grid;
}

// The terrain bench's flight: from 800 km to 50 m, approaching the centre from the south,
// looking down from space and towards the horizon near the ground.
std::vector<Camera> flight(const ElevationGrid& grid, int framesPerSegment) {
    std::vector<Camera> frames;
    const int segments = int(std::size(kAltitudes)) - 1;
    const int total = segments * framesPerSegment + 1;
    for (int frame = 0; frame < total; ++frame) {
        const double progress = double(frame) / (total - 1);
        const int segment = std::min(frame / framesPerSegment, segments - 1);
        const double local = double(frame - segment * framesPerSegment) / framesPerSegment;
        const double altitude = std::exp(std::log(kAltitudes[segment]) * (1 - local) +
                                         std::log(kAltitudes[segment + 1]) * local);
        const double latitude = kCentreLatitude - 0.6 * kDegree * (1 - progress);
        const double longitude = kCentreLongitude + 0.2 * kDegree * (1 - progress);
        const double pitch = (-85.0 + 75.0 * std::pow(progress, 0.7)) * kDegree;
        Camera camera;
        camera.geodetic = {latitude, longitude, grid.at(latitude, longitude, 0.0) + altitude};
        camera.position = Ellipsoid::toEcef(camera.geodetic);
        camera.axes = Camera::axesFromAngles(camera.geodetic, 10 * kDegree, pitch, 0.0);
        camera.verticalFov = 60 * kDegree;
        frames.push_back(camera);
    }
    return frames;
}

// The former shading pass (per-pixel ray march), with the uniforms it had.
void runLegacy(ShaderProgram& program, GLuint vertexArray, const Framebuffer& gbuffer,
               const Framebuffer& target, const Camera& camera, const glm::dmat4& projection,
               double near, const glm::dvec3& sun, bool atmosphere) {
    target.bind();
    glDisable(GL_DEPTH_TEST);
    program.use();
    const glm::dmat3 view = camera.viewRotation();
    program.setInt("uAlbedo", 0);
    program.setInt("uNormal", 1);
    program.setInt("uDepth", 2);
    program.setVec2("uProjectionScale",
                    glm::vec2(float(projection[0][0]), float(projection[1][1])));
    program.setFloat("uNear", float(near));
    program.setMat3("uViewToEcef", glm::mat3(glm::transpose(view)));
    program.setVec3("uCameraEcef", glm::vec3(camera.position));
    program.setVec3("uSunView", glm::vec3(glm::normalize(view * sun)));
    program.setVec3("uSunEcef", glm::vec3(sun));
    program.setInt("uAtmosphere", atmosphere ? 1 : 0);
    program.setFloat("uExposure", 0.45f);
    glBindTextureUnit(0, gbuffer.colorTexture(0));
    glBindTextureUnit(1, gbuffer.colorTexture(1));
    glBindTextureUnit(2, gbuffer.depthTexture());
    glBindVertexArray(vertexArray);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
}

// Milliseconds of `pass` to glFinish, the better of two runs.
template <typename Pass>
double timed(Pass&& pass) {
    double best = 1e30;
    for (int run = 0; run < 2; ++run) {
        glFinish();
        const auto start = std::chrono::steady_clock::now();
        pass();
        glFinish();
        best = std::min(best, std::chrono::duration<double, std::milli>(
                                  std::chrono::steady_clock::now() - start)
                                  .count());
    }
    return best;
}

}  // namespace

std::string AtmosphereBenchmarkResult::json() const {
    return metricsJson("shading", metrics, {NumberFormat::Notation::General, 6});
}

Result<AtmosphereBenchmarkResult> runAtmosphereBenchmark(
    const ShaderLibrary& library, const AtmosphereBenchmarkOptions& options) {
    const ElevationGrid grid = syntheticDem();
    const ShaderLibrary benchLibrary = withBenchShaders(library);
    Result<GridMesh> mesh = GridMesh::create(
        benchLibrary, grid, Ellipsoid::toEcef({kCentreLatitude, kCentreLongitude, 0.0}));
    if (!mesh) {
        return mesh.error();
    }
    Result<std::unique_ptr<ShadingPass>> shading = ShadingPass::create(library);
    if (!shading) {
        return shading.error();
    }
    Result<ShaderProgram> legacy =
        ShaderProgram::create(benchLibrary, {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                             {GL_FRAGMENT_SHADER, "bench/legacy_shade.frag"}});
    if (!legacy) {
        return legacy.error();
    }
    Result<Framebuffer> gbuffer =
        Framebuffer::create(options.width, options.height, {GL_RGBA16F, GL_RGBA16F}, true);
    Result<Framebuffer> output =
        Framebuffer::create(options.width, options.height, {GL_RGBA8}, false);
    if (!gbuffer || !output) {
        return Error{"shading benchmark: cannot create the targets"};
    }
    GlVertexArray vertexArray = createGlVertexArray();
    const glm::dvec3 sun =
        Ellipsoid::surfaceNormal(5 * kDegree, -40 * kDegree);  // as the terrain bench
    ShadingSettings settings;
    settings.sunDirection = sun;
    std::vector<double> lutMs, legacyMs, speedups;
    for (const Camera& camera : flight(grid, options.framesPerSegment)) {
        const double above = camera.geodetic.height -
                             grid.at(camera.geodetic.latitude, camera.geodetic.longitude, 0.0);
        const double near = std::clamp(0.3 * above, 0.02, 1.0e4);
        const glm::dmat4 projection = SceneRenderer::projection(
            camera.verticalFov, double(options.width) / options.height, near);
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        gbuffer->bind();
        gbuffer->clearColor(0, glm::vec4(0.0f));
        gbuffer->clearColor(1, glm::vec4(0.0f));
        gbuffer->clearDepth(0.0f);
        mesh->draw(camera, projection);
        auto lut = [&](bool atmosphere) {
            settings.atmosphere = atmosphere;
            return timed([&] {
                shading.value()->run(gbuffer.value(), output.value(), camera, projection, near,
                                     settings);
            });
        };
        auto old = [&](bool atmosphere) {
            return timed([&] {
                runLegacy(legacy.value(), vertexArray.get(), gbuffer.value(), output.value(),
                          camera, projection, near, sun, atmosphere);
            });
        };
        const double lutShare = std::max(lut(true) - lut(false), 1e-3);
        const double legacyShare = std::max(old(true) - old(false), 1e-3);
        lutMs.push_back(lutShare);
        legacyMs.push_back(legacyShare);
        speedups.push_back(legacyShare / lutShare);
        glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    }
    Framebuffer::unbind();
    AtmosphereBenchmarkResult result;
    result.metrics = {
        {"atmosphere_ms_median", median(lutMs)},  {"atmosphere_legacy_ms_median", median(legacyMs)},
        {"atmosphere_speedup", median(speedups)}, {"atmosphere_frames", double(lutMs.size())},
        {"width", double(options.width)},         {"height", double(options.height)}};
    return result;
}

}  // namespace sylva::bench
