#include "sylva/bench/TerrainBenchmark.h"

#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "BenchShaders.h"
#include "GridElevationSource.h"
#include "sylva/core/base/ParallelFor.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/scheduler/Scheduler.h"
#include "sylva/core/sources/raster/HypsometricSource.h"
#include "sylva/core/sources/raster/NoiseSource.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/render/gl/Framebuffer.h"
#include "sylva/render/gl/ShaderProgram.h"
#include "sylva/render/scene/SceneRenderer.h"
#include "sylva/render/shading/ShadingPass.h"

namespace sylva::bench {

using namespace sylva::render;
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kCentreLatitude = 46.0 * kDegree;
constexpr double kCentreLongitude = 8.0 * kDegree;
// Altitudes above the ground of seed 001 Table 4.1, metres.
constexpr double kAltitudes[] = {800e3, 100e3, 10e3, 1e3, 50.0};

double median(std::vector<double> values) {
    if (values.empty()) {
        return 0.0;
    }
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return values[values.size() / 2];
}

ElevationGrid makeDem(int samples, double degrees) {
    NoiseParameters parameters;  // the demo project's relief
    parameters.seed = 7;
    parameters.amplitude = 3000;
    parameters.baseWavelength = 3.0e6;
    parameters.ridges = 0.6;
    parameters.ridgeWavelength = 3.0e5;
    parameters.roughness = 0.7;
    const NoiseSource noise("dem", parameters);
    ElevationGrid grid;
    grid.width = grid.height = samples;
    grid.west = kCentreLongitude - degrees / 2 * kDegree;
    grid.east = kCentreLongitude + degrees / 2 * kDegree;
    grid.south = kCentreLatitude - degrees / 2 * kDegree;
    grid.north = kCentreLatitude + degrees / 2 * kDegree;
    grid.heights.resize(std::size_t(samples) * samples);
    const double footprint = grid.sampleSpacingLatitude() * Ellipsoid::kMeanRadius;
    parallelFor(0, samples, [&](int row) {
        const double latitude = grid.north - row * grid.sampleSpacingLatitude();
        for (int column = 0; column < samples; ++column) {
            const double longitude = grid.west + column * grid.sampleSpacingLongitude();
            const glm::dvec3 direction = Ellipsoid::surfaceNormal(latitude, longitude);
            grid.heights[std::size_t(row) * samples + column] =
                float(noise.height(direction, footprint));
        }
    });
    return grid;
}

// The same surface with `factor` times the samples per side (bilinear), i.e. a DEM
// with factor^2 the data.
ElevationGrid upsample(const ElevationGrid& grid, int factor) {
    ElevationGrid fine = grid;
    fine.width = (grid.width - 1) * factor + 1;
    fine.height = (grid.height - 1) * factor + 1;
    fine.heights.assign(std::size_t(fine.width) * fine.height, 0.0f);
    parallelFor(0, fine.height, [&](int row) {
        const double latitude = fine.north - row * fine.sampleSpacingLatitude();
        for (int column = 0; column < fine.width; ++column) {
            fine.heights[std::size_t(row) * fine.width + column] =
                float(grid.at(latitude, fine.west + column * fine.sampleSpacingLongitude(), 0.0));
        }
    });
    return fine;
}

struct FlightFrame {
    Camera camera;
    double altitude;
};

std::vector<FlightFrame> flight(const ElevationGrid& grid, int framesPerSegment) {
    std::vector<FlightFrame> frames;
    const int segments = int(std::size(kAltitudes)) - 1;
    const int total = segments * framesPerSegment + 1;
    for (int frame = 0; frame < total; ++frame) {
        const double progress = double(frame) / (total - 1);
        const int segment = std::min(frame / framesPerSegment, segments - 1);
        const double local = double(frame - segment * framesPerSegment) / framesPerSegment;
        const double altitude = std::exp(std::log(kAltitudes[segment]) * (1 - local) +
                                         std::log(kAltitudes[segment + 1]) * local);
        // Approach the DEM centre from the south while descending; look down from
        // space, towards the horizon near the ground.
        const double latitude = kCentreLatitude - 0.6 * kDegree * (1 - progress);
        const double longitude = kCentreLongitude + 0.2 * kDegree * (1 - progress);
        const double pitch = (-85.0 + 75.0 * std::pow(progress, 0.7)) * kDegree;
        Camera camera;
        camera.geodetic = {latitude, longitude, grid.at(latitude, longitude, 0.0) + altitude};
        camera.position = Ellipsoid::toEcef(camera.geodetic);
        camera.axes = Camera::axesFromAngles(camera.geodetic, 10 * kDegree, pitch, 0.0);
        camera.verticalFov = 60 * kDegree;
        frames.push_back({camera, altitude});
    }
    return frames;
}

// The brute-force reference: every DEM sample a vertex, every cell two triangles.
class GridMesh {
public:
    static Result<GridMesh> create(const ShaderLibrary& library, const ElevationGrid& grid) {
        GridMesh mesh;
        Result<ShaderProgram> program = ShaderProgram::create(
            library,
            {{GL_VERTEX_SHADER, "bench/grid.vert"}, {GL_FRAGMENT_SHADER, "bench/grid.frag"}});
        if (!program) {
            return program.error();
        }
        mesh.program_ = std::move(program.value());
        mesh.centre_ = Ellipsoid::toEcef({kCentreLatitude, kCentreLongitude, 0.0});
        std::vector<float> positions(std::size_t(grid.width) * grid.height * 3);
        parallelFor(0, grid.height, [&](int row) {
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
        parallelFor(0, grid.height - 1, [&](int row) {
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
        glCreateVertexArrays(1, &mesh.vertexArray_);
        glCreateBuffers(2, mesh.buffers_);
        glNamedBufferStorage(mesh.buffers_[0], GLsizeiptr(positions.size() * sizeof(float)),
                             positions.data(), 0);
        glNamedBufferStorage(mesh.buffers_[1], GLsizeiptr(indices.size() * sizeof(std::uint32_t)),
                             indices.data(), 0);
        glVertexArrayVertexBuffer(mesh.vertexArray_, 0, mesh.buffers_[0], 0, 3 * sizeof(float));
        glVertexArrayElementBuffer(mesh.vertexArray_, mesh.buffers_[1]);
        glEnableVertexArrayAttrib(mesh.vertexArray_, 0);
        glVertexArrayAttribFormat(mesh.vertexArray_, 0, 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(mesh.vertexArray_, 0, 0);
        return mesh;
    }
    GridMesh() = default;
    GridMesh(GridMesh&& other) noexcept { *this = std::move(other); }
    GridMesh& operator=(GridMesh&& other) noexcept {
        std::swap(program_, other.program_);
        std::swap(vertexArray_, other.vertexArray_);
        std::swap(buffers_[0], other.buffers_[0]);
        std::swap(buffers_[1], other.buffers_[1]);
        indexCount_ = other.indexCount_;
        centre_ = other.centre_;
        return *this;
    }
    ~GridMesh() {
        if (vertexArray_ != 0) {
            glDeleteVertexArrays(1, &vertexArray_);
            glDeleteBuffers(2, buffers_);
        }
    }
    std::size_t triangles() const { return indexCount_ / 3; }

    void draw(const Camera& camera, const glm::dmat4& projection) {
        const glm::dmat3 view = camera.viewRotation();
        program_.setMat3("uEcefToView", glm::mat3(view));
        program_.setVec3("uCentreToCamera", glm::vec3(view * (centre_ - camera.position)));
        program_.setMat4("uProjection", glm::mat4(projection));
        program_.use();
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GREATER);
        glBindVertexArray(vertexArray_);
        glDrawElements(GL_TRIANGLES, GLsizei(indexCount_), GL_UNSIGNED_INT, nullptr);
        glBindVertexArray(0);
    }

private:
    ShaderProgram program_;
    std::uint32_t vertexArray_ = 0;
    std::uint32_t buffers_[2] = {0, 0};
    std::size_t indexCount_ = 0;
    glm::dvec3 centre_{};
};

}  // namespace

std::string TerrainBenchmarkResult::json() const {
    std::string text = "{\"suite\":\"terrain\",\"metrics\":{";
    bool first = true;
    char buffer[128];
    for (const auto& [key, value] : metrics) {
        std::snprintf(buffer, sizeof buffer, "%s\"%s\":%.6g", first ? "" : ",", key.c_str(), value);
        text += buffer;
        first = false;
    }
    text += ",\"levels_rendered\":[";
    for (std::size_t i = 0; i < levelsPerAltitude.size(); ++i) {
        std::snprintf(buffer, sizeof buffer,
                      "%s{\"altitude_m\":%.6g,\"coarsest\":%d,\"finest\":%d}", i ? "," : "",
                      levelsPerAltitude[i].first, levelsPerAltitude[i].second.first,
                      levelsPerAltitude[i].second.second);
        text += buffer;
    }
    return text + "]}}";
}

Result<TerrainBenchmarkResult> runTerrainBenchmark(const ShaderLibrary& library,
                                                   const TerrainBenchmarkOptions& options) {
    using Clock = std::chrono::steady_clock;
    TerrainBenchmarkResult result;
    const ElevationGrid grid = makeDem(options.demSamples, options.demDegrees);
    const std::vector<FlightFrame> frames = flight(grid, options.framesPerSegment);

    Result<std::unique_ptr<SceneRenderer>> created =
        SceneRenderer::create(library, TerrainSettings{});
    if (!created) {
        return created.error();
    }
    SceneRenderer& renderer = *created.value();
    RenderSettings settings;
    settings.width = options.width;
    settings.height = options.height;
    settings.ocean = false;
    settings.sunDirection = Ellipsoid::surfaceNormal(5 * kDegree, -40 * kDegree);
    settings.exposure = 0.45;  // as the demo project
    settings.waitForTiles = options.waitForTiles;

    // The clipmap flight, twice: over the DEM, and over 16x its samples.
    double trianglesMax[2] = {0, 0};
    std::vector<double> frameMs, updateMs, totalMs, terrainMs, uploadBytes;
    int framesWaiting = 0;  // frames drawn with fewer levels than wanted (tiles still coming)
    double levelsMissing = 0;
    for (int pass = 0; pass < 2; ++pass) {
        const GridElevationSource elevation("dem", pass == 0 ? grid : upsample(grid, 4), 0.0);
        const NormalMapSource normals("dem.normals", &elevation, 1.0);
        HypsometricParameters colours;  // the schema's defaults, linear RGB
        colours.water = {0.0056f, 0.0194f, 0.0742f};
        colours.shallowWater = {0.0100f, 0.0844f, 0.1470f};
        colours.rock = {0.1470f, 0.1274f, 0.1000f};
        const HypsometricSource colour("dem.colour", &elevation, &normals, colours);
        SchedulerOptions schedulerOptions;
        schedulerOptions.format = TileFormat{256, 2};
        schedulerOptions.budgetBytes = options.cacheBytes;
        Scheduler evaluator(schedulerOptions);
        const TerrainLayers layers{&elevation, &colour, &normals, {}};
        for (const FlightFrame& frame : frames) {
            const auto start = Clock::now();
            Result<Image> image = renderer.render(layers, evaluator, frame.camera, settings);
            if (!image) {
                return Error{"terrain benchmark: " + image.error().message};
            }
            const double ms =
                std::chrono::duration<double, std::milli>(Clock::now() - start).count();
            const RenderStatistics& statistics = renderer.statistics();
            trianglesMax[pass] = std::max(trianglesMax[pass], double(statistics.terrain.triangles));
            if (pass == 0 && !options.framesFolder.empty()) {
                char name[32];
                std::snprintf(name, sizeof name, "flight_%03zu.png", totalMs.size());
                const Status written =
                    ImageWriter::writeRgba8(std::filesystem::path(options.framesFolder) / name,
                                            image->width, image->height, image->pixels);
                if (!written) {
                    return written.error();
                }
            }
            if (pass == 0) {
                // The frame proper (draw, shade, read back) and, separately, the CPU
                // clipmap update: with waitForTiles it includes waiting for the
                // workers; without, only copying ready tiles (seed 001 §4.6-4.7).
                frameMs.push_back(statistics.gpuSeconds * 1000.0);
                updateMs.push_back(statistics.terrain.updateSeconds * 1000.0);
                totalMs.push_back(ms);
                terrainMs.push_back(statistics.terrainPassSeconds * 1000.0);
                uploadBytes.push_back(double(statistics.terrain.uploadedBytes));
                if (statistics.terrain.waitingLevel >= 0) {
                    ++framesWaiting;
                    levelsMissing +=
                        statistics.terrain.wanted.finest - statistics.terrain.levels.finest;
                }
                result.levelsPerAltitude.push_back(
                    {frame.altitude,
                     {statistics.terrain.levels.coarsest, statistics.terrain.levels.finest}});
            }
        }
    }

    // The brute-force mesh of the base DEM, drawn into the same G-buffer formats and
    // shaded and read back the same way, on frames sampled along the same flight.
    Result<GridMesh> mesh = GridMesh::create(withBenchShaders(library), grid);
    if (!mesh) {
        return mesh.error();
    }
    Result<Framebuffer> gbuffer =
        Framebuffer::create(options.width, options.height, {GL_RGBA16F, GL_RGBA16F}, true);
    Result<Framebuffer> output =
        Framebuffer::create(options.width, options.height, {GL_RGBA8}, false);
    Result<std::unique_ptr<ShadingPass>> shading = ShadingPass::create(library);
    if (!gbuffer || !output || !shading) {
        return Error{"terrain benchmark: cannot create the brute-force targets"};
    }
    std::vector<double> bruteMs, bruteTotalMs;
    for (int sample = 0; sample < options.bruteForceFrames; ++sample) {
        const FlightFrame& frame = frames[std::size_t(sample) * (frames.size() - 1) /
                                          std::max(1, options.bruteForceFrames - 1)];
        const double aboveTerrain = frame.altitude;
        const double near = std::clamp(0.3 * aboveTerrain, 0.02, 1.0e4);
        const glm::dmat4 projection = SceneRenderer::projection(
            frame.camera.verticalFov, double(options.width) / options.height, near);
        const auto start = Clock::now();
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        gbuffer->bind();
        gbuffer->clearColor(0, glm::vec4(0.0f));
        gbuffer->clearColor(1, glm::vec4(0.0f));
        gbuffer->clearDepth(0.0f);
        mesh->draw(frame.camera, projection);
        glFinish();
        bruteMs.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
        ShadingSettings shade;
        shade.sunDirection = settings.sunDirection;
        shade.exposure = settings.exposure;
        shading.value()->run(gbuffer.value(), output.value(), frame.camera, projection, near,
                             shade);
        (void)output->readPixelsRGBA8(0);
        glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        bruteTotalMs.push_back(
            std::chrono::duration<double, std::milli>(Clock::now() - start).count());
    }
    Framebuffer::unbind();

    result.metrics["ms_per_frame_median"] = median(frameMs);
    result.metrics["update_ms_per_frame_median"] = median(updateMs);
    result.metrics["total_ms_per_frame_median"] = median(totalMs);
    result.metrics["triangles_per_frame_max"] = trianglesMax[0];
    result.metrics["upload_bytes_per_frame_median"] = median(uploadBytes);
    // The terrain methods are compared on the terrain pass (the G-buffer draw); the
    // shading pass that follows is the same per-pixel work for both.
    result.metrics["terrain_pass_ms_median"] = median(terrainMs);
    result.metrics["bruteforce_ms_per_frame"] = median(bruteMs);
    result.metrics["bruteforce_total_ms_per_frame"] = median(bruteTotalMs);
    result.metrics["bruteforce_triangles"] = double(mesh->triangles());
    result.metrics["speedup_vs_bruteforce"] = median(bruteMs) / std::max(median(terrainMs), 1e-9);
    result.metrics["triangles_growth"] = trianglesMax[1] / std::max(trianglesMax[0], 1.0);
    result.metrics["frames"] = double(frames.size());
    result.metrics["frames_waiting_for_tiles"] = framesWaiting;
    result.metrics["levels_missing_per_waiting_frame"] =
        framesWaiting ? levelsMissing / framesWaiting : 0.0;
    result.metrics["wait_for_tiles"] = options.waitForTiles ? 1 : 0;
    result.metrics["width"] = options.width;
    result.metrics["height"] = options.height;
    result.metrics["dem_samples"] = options.demSamples;
    return result;
}

}  // namespace sylva::bench
