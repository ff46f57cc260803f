#include "sylva/render/scene/SceneRenderer.h"
#include "sylva/core/vegetation/LeafStates.h"

#include <glad/gl.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <string>

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

#include "sylva/core/atmosphere/Exposure.h"
#include "sylva/core/base/WorkerPool.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scheduler/FrameWantedSet.h"
#include "sylva/core/sources/plants/PlantModelSource.h"
#include "sylva/core/sources/plants/PlantsSource.h"
#include "sylva/core/terrain/ElevationQuery.h"

namespace sylva::render {
namespace {

// Clearance assumed under an interactive camera whose ground came from a coarser level
// than the one it stands on (the finer tile is still being produced), metres.
constexpr double kEstimatedClearance = 0.5;
// The near plane as a fraction of the camera's clearance over the ground (see render()).
constexpr double kNearFraction = 0.05;

int levelRows(const RenderSettings& settings) {
    return settings.levelRows > 0 ? settings.levelRows : settings.height;
}

// A plant asset's build in the background: serial on its own thread (like the Scheduler's
// workers) and five nice steps below the render thread, so frames keep their CPU.
Result<std::shared_ptr<const PlantAsset>> buildAssetInBackground(const PlantModelSource* model) {
#if defined(__linux__)
    const auto thread = static_cast<id_t>(::syscall(SYS_gettid));
    errno = 0;
    const int current = getpriority(PRIO_PROCESS, thread);
    if (errno == 0) {
        (void)setpriority(PRIO_PROCESS, thread, std::min(19, current + 5));
    }
#endif
    WorkerPool::runSeriallyOnThisThread();
    return model->asset();
}

}  // namespace

Result<std::unique_ptr<SceneRenderer>> SceneRenderer::create(const ShaderLibrary& library,
                                                             const TerrainSettings& settings) {
    std::unique_ptr<SceneRenderer> renderer(new SceneRenderer());
    Result<std::unique_ptr<TerrainRenderer>> terrain = TerrainRenderer::create(library, settings);
    if (!terrain) {
        return terrain.error();
    }
    renderer->terrain_ = std::move(terrain.value());
    Result<std::unique_ptr<VegetationRenderer>> vegetation = VegetationRenderer::create(library);
    if (!vegetation) {
        return vegetation.error();
    }
    renderer->vegetation_ = std::move(vegetation.value());
    Result<std::unique_ptr<FarFieldCanopy>> farField = FarFieldCanopy::create(library, settings);
    if (!farField) {
        return farField.error();
    }
    renderer->farField_ = std::move(farField.value());
    Result<std::unique_ptr<MeshRenderer>> meshes = MeshRenderer::create(library);
    if (!meshes) {
        return meshes.error();
    }
    renderer->meshes_ = std::move(meshes.value());
    Result<std::unique_ptr<ShadingPass>> shading = ShadingPass::create(library);
    if (!shading) {
        return shading.error();
    }
    renderer->shading_ = std::move(shading.value());
    Result<std::unique_ptr<AmbientOcclusionPass>> occlusion = AmbientOcclusionPass::create(library);
    if (!occlusion) {
        return occlusion.error();
    }
    renderer->ambientOcclusion_ = std::move(occlusion.value());
    Result<std::unique_ptr<SampleAccumulator>> accumulator = SampleAccumulator::create(library);
    if (!accumulator) {
        return accumulator.error();
    }
    renderer->accumulator_ = std::move(accumulator.value());
    Result<std::unique_ptr<ShadowMaps>> shadowMaps = ShadowMaps::create();
    if (!shadowMaps) {
        return shadowMaps.error();
    }
    renderer->shadowMaps_ = std::move(shadowMaps.value());
    return renderer;
}

SceneRenderer::~SceneRenderer() {
    finishAssetBuilds();
}

void SceneRenderer::finishAssetBuilds() {
    for (auto& [hash, build] : assetBuilds_) {
        build.wait();
    }
    assetBuilds_.clear();
}

glm::dmat4 SceneRenderer::projection(double verticalFov, double aspect, double near,
                                     const glm::dvec2& lensShift) {
    const double f = 1.0 / std::tan(verticalFov / 2);
    glm::dmat4 p(0.0);
    p[0][0] = f / aspect;
    p[1][1] = f;
    // Off-axis by the lens shift: ndc = scale * x / -z - 2 shift, so the optical axis
    // lands at ndc -2 shift (ImageProjection's principal point).
    p[2][0] = 2.0 * lensShift.x;
    p[2][1] = 2.0 * lensShift.y;
    p[2][3] = -1.0;  // w = -z
    p[3][2] = near;  // z = near, so depth = near / distance after the divide
    return p;
}

Status SceneRenderer::ensureTargets(int width, int height, bool linearOutput) {
    const int outputs = linearOutput ? 2 : 1;
    if (gbuffer_.id() != 0 && gbuffer_.width() == width && gbuffer_.height() == height &&
        output_.colorCount() == outputs) {
        return Status::success();
    }
    Result<Framebuffer> gbuffer =
        Framebuffer::create(width, height, {GL_RGBA16F, GL_RGBA16F}, true);
    if (!gbuffer) {
        return gbuffer.error();
    }
    // The shading pass writes radiance to location 1; without that attachment GL drops it.
    Result<Framebuffer> output =
        Framebuffer::create(width, height,
                            linearOutput ? std::vector<std::uint32_t>{GL_RGBA8, GL_RGBA32F}
                                         : std::vector<std::uint32_t>{GL_RGBA8},
                            false);
    if (!output) {
        return output.error();
    }
    gbuffer_ = std::move(gbuffer.value());
    output_ = std::move(output.value());
    return Status::success();
}

Result<double> SceneRenderer::readyGround(const TerrainLayers& layers, TileProvider& provider,
                                          const Camera& camera, const RenderSettings& settings) {
    const ElevationQuery query(*layers.elevation, provider);
    const double latitude = camera.geodetic.latitude;
    const double longitude = camera.geodetic.longitude;
    // The levels seen from the last known ground (sea level at first), probed finest
    // first; every tile probed is one the terrain's clipmaps want anyway.
    const double estimate = groundKnown_ ? groundHeight_ : 0.0;
    const LevelRange levels = terrain_->visibleLevels(
        camera, std::max(camera.geodetic.height - estimate, 0.01), levelRows(settings));
    for (int level = levels.finest; level >= 0; --level) {
        Result<std::optional<double>> ground =
            query.readyGroundHeight(latitude, longitude, level, level);
        if (!ground) {
            return ground.error();
        }
        if (ground.value()) {
            statistics_.groundLevel = level;
            return *ground.value();
        }
    }
    statistics_.groundLevel = -1;
    if (groundKnown_) {
        return groundHeight_;  // the last frame's, until a tile under the camera arrives
    }
    // The very first frame: the coarsest level (two tiles cover the globe), waited for.
    statistics_.groundLevel = 0;
    return query.groundHeight(latitude, longitude, 0);
}

Result<LevelRange> SceneRenderer::prepareTerrain(const TerrainLayers& layers,
                                                 TileProvider& provider, const Camera& camera,
                                                 const RenderSettings& settings) {
    // Height above the terrain at the nadir, from the level that will be drawn there:
    // estimate with a coarse level first, then refine at the finest visible level.
    // Interactive frames take the finest level that is ready instead of waiting.
    const ElevationQuery query(*layers.elevation, provider);
    Result<double> ground = Error{""};
    LevelRange levels;
    if (settings.waitForTiles) {
        ground = query.groundHeight(camera.geodetic.latitude, camera.geodetic.longitude, 12);
        if (!ground) {
            return ground.error();
        }
        levels = terrain_->visibleLevels(
            camera, std::max(camera.geodetic.height - ground.value(), 0.01), levelRows(settings));
        ground =
            query.groundHeight(camera.geodetic.latitude, camera.geodetic.longitude, levels.finest);
        statistics_.groundLevel = levels.finest;
    } else {
        ground = readyGround(layers, provider, camera, settings);
    }
    if (!ground) {
        return ground.error();
    }
    double groundHeight = ground.value();
    if (settings.ocean) {
        groundHeight = std::max(groundHeight, 0.0);
    }
    groundHeight_ = groundHeight;
    groundKnown_ = true;
    statistics_.groundHeight = groundHeight;
    double aboveTerrain = camera.geodetic.height - groundHeight;
    if (!settings.waitForTiles) {
        levels = terrain_->visibleLevels(camera, std::max(aboveTerrain, kEstimatedClearance),
                                         levelRows(settings));
        // The nadir probe's level is not the level the camera was placed on: a coarser
        // one's ground may pass over a camera on finer terrain, a finer one's (ready
        // before the levels between) under a walker the viewer placed on the finest
        // resident level. Estimate the clearance rather than fail the frame; the viewer
        // keeps its cameras above the ground it draws.
        aboveTerrain = std::max(aboveTerrain, kEstimatedClearance);
    }
    if (aboveTerrain <= 0.0) {
        char buffer[160];
        std::snprintf(buffer, sizeof buffer,
                      "the camera is %.2f m below the terrain (ground at %.2f m)", -aboveTerrain,
                      groundHeight);
        return Error{buffer};
    }
    levels = terrain_->visibleLevels(camera, aboveTerrain, levelRows(settings));
    statistics_.heightAboveTerrain = aboveTerrain;
    return terrain_->update(layers, provider, camera, levels, std::nullopt, settings.waitForTiles);
}

Result<std::vector<const InstanceBatch*>> SceneRenderer::streamVegetation(
    const TerrainLayers& layers, TileProvider& provider, const Camera& camera,
    const RenderSettings& settings) {
    statistics_.vegetationStream = {};
    statistics_.pendingSpecies = 0;
    std::vector<const InstanceBatch*> batches = settings.instanceBatches;
    if (layers.plants.empty()) {
        return batches;
    }
    Result<std::vector<VegetationStreamLayer>> streamLayers =
        vegetationLayers(layers, settings.waitForTiles);
    if (!streamLayers) {
        return streamLayers.error();
    }
    VegetationStreamSettings stream;
    stream.pixelAngle = 2.0 * std::tan(camera.verticalFov / 2) / settings.height;
    stream.minimumPixels = settings.vegetation.minimumPixels;
    stream.maximumDistance = settings.vegetation.maximumDistance;
    stream.heightAboveGround = statistics_.heightAboveTerrain;
    stream.wait = settings.waitForTiles;
    stream.date = settings.plantDate;  // growth; and the season of each species:
    vegetation_->setLeafStates(leafStates(streamLayers.value(), vegetation_->speciesCount(),
                                          settings.plantDate, camera.geodetic.latitude));
    Result<std::vector<const InstanceBatch*>> streamed = vegetationStream_.update(
        streamLayers.value(), provider, camera, vegetation_->speciesLods(), stream);
    if (!streamed) {
        return streamed.error();
    }
    batches.insert(batches.end(), streamed.value().begin(), streamed.value().end());
    statistics_.vegetationStream = vegetationStream_.statistics();
    return batches;
}

Status SceneRenderer::drawShadowMaps(const Camera& camera,
                                     const std::vector<const InstanceBatch*>& batches,
                                     const RenderSettings& settings) {
    const auto shadowStart = std::chrono::steady_clock::now();
    std::vector<ShadowCaster*> casters{terrain_.get()};
    if (!batches.empty()) {
        casters.push_back(vegetation_.get());  // the batches just drawn
    }
    if (meshesStreamed_) {
        casters.push_back(meshes_.get());
    }
    casters.insert(casters.end(), settings.shadowCasters.begin(), settings.shadowCasters.end());
    if (Status shadows = shadowMaps_->render(camera, double(settings.width) / settings.height,
                                             settings.sunDirection, settings.shadows, casters);
        !shadows) {
        return shadows;
    }
    glFinish();  // only to time the pass
    statistics_.shadowPassSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - shadowStart).count();
    return Status::success();
}

Status SceneRenderer::drawSample(const Camera& camera, const glm::dmat4& projection,
                                 const LevelRange& levels,
                                 const std::vector<const InstanceBatch*>& batches,
                                 const RenderSettings& settings, bool renderShadows) {
    gbuffer_.bind();
    gbuffer_.clearColor(0, glm::vec4(0.0f));
    gbuffer_.clearColor(1, glm::vec4(0.0f));
    gbuffer_.clearDepth(0.0f);  // reversed-Z: 0 is infinitely far
    const auto terrainStart = std::chrono::steady_clock::now();
    terrain_->draw(camera, projection, levels, settings.ocean);
    glFinish();  // only to time the pass; the read-back below waits anyway
    statistics_.terrainPassSeconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - terrainStart).count();
    drawMeshes(camera, projection, settings);
    const VegetationSettings vegetation = drawFarField(camera, projection, settings);
    const auto vegetationStart = std::chrono::steady_clock::now();
    if (!batches.empty()) {
        vegetation_->draw(batches, camera, projection, near_, settings.width, settings.height,
                          vegetation);
        glFinish();  // only to time the pass
        statistics_.vegetation = vegetation_->statistics();
        statistics_.vegetationPassSeconds +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - vegetationStart)
                .count();
    }
    if (renderShadows) {
        if (Status shadows = drawShadowMaps(camera, batches, settings); !shadows) {
            return shadows;
        }
    }
    ShadingSettings shading;
    shading.shadowMaps = shadowMaps_.get();
    shading.sunDirection = settings.sunDirection;
    shading.atmosphere = settings.atmosphere;
    shading.atmosphereParameters = settings.atmosphereParameters;
    shading.exposure = exposureScale(statistics_.ev100) * settings.exposure;
    shading.sunVisibilityOutput = settings.sunVisibilityOutput;
    if (settings.ambientOcclusion.enabled) {
        const auto occlusionStart = std::chrono::steady_clock::now();
        Result<std::uint32_t> occlusion =
            ambientOcclusion_->run(gbuffer_, projection, near_, settings.ambientOcclusion);
        if (!occlusion) {
            return occlusion.error();
        }
        shading.ambientOcclusion = occlusion.value();
        glFinish();  // only to time the pass
        statistics_.ambientOcclusionPassSeconds +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - occlusionStart)
                .count();
    }
    shading_->run(gbuffer_, output_, camera, projection, near_, shading);
    return Status::success();
}

Result<Image> SceneRenderer::render(const TerrainLayers& layers, TileProvider& provider,
                                    const Camera& camera, const RenderSettings& settings) {
    if (settings.width < 1 || settings.height < 1 || settings.width > 16384 ||
        settings.height > 16384) {
        return Error{"image size " + std::to_string(settings.width) + "x" +
                     std::to_string(settings.height) + " is outside 1..16384"};
    }
    if (settings.samples < 1 || settings.samples > SampleAccumulator::kMaxSamples) {
        return Error{"samples " + std::to_string(settings.samples) + " is outside 1.." +
                     std::to_string(SampleAccumulator::kMaxSamples)};
    }
    if (Status status = ensureTargets(settings.width, settings.height, settings.linearOutput);
        !status) {
        return status.error();
    }
    // Interactive frames gather every client's wanted tiles (terrain, canopy, instance
    // tiles, the nadir probe) and hand the Scheduler one list (FrameWantedSet); batch
    // frames wait for everything, client by client, as before.
    FrameWantedSet frameWanted(provider);
    TileProvider& tiles = settings.waitForTiles ? provider : frameWanted;
    Result<LevelRange> ready = prepareTerrain(layers, tiles, camera, settings);
    if (!ready) {
        return ready.error();
    }
    const LevelRange levels = ready.value();
    // One exposure for every sample (and every scenario of the viewpoint and time).
    statistics_.ev100 =
        settings.ev100 ? *settings.ev100 : meterEv100(camera, groundHeight_, settings);
    const auto start = std::chrono::steady_clock::now();
    statistics_.vegetation = {};
    statistics_.terrainPassSeconds = 0;
    statistics_.vegetationPassSeconds = 0;
    statistics_.ambientOcclusionPassSeconds = 0;
    Result<std::vector<const InstanceBatch*>> batches =
        streamVegetation(layers, tiles, camera, settings);
    if (!batches) {
        return batches.error();
    }
    if (Status streamed = streamMeshes(layers, tiles, camera, settings); !streamed) {
        return streamed.error();
    }
    if (Status prepared = prepareFarField(layers, tiles, camera, levels, settings); !prepared) {
        return prepared.error();
    }
    if (!settings.waitForTiles) {
        frameWanted.flush();
        const TerrainFrameStatistics& terrain = terrain_->statistics();
        statistics_.pending =
            terrain.waitingLevel >= 0 || statistics_.groundLevel < terrain.wanted.finest ||
            statistics_.farField.waiting || statistics_.pendingSpecies > 0 ||
            statistics_.vegetationStream.readyTiles < statistics_.vegetationStream.wantedTiles;
    } else {
        statistics_.pending = false;
    }
    // The near plane at a twentieth of the clearance: a walker's eye 1.7 m up has it at
    // 8.5 cm, so a wall at the walker's 0.3 m (or a branch at arm's length) is not cut open
    // (at 0.3 x the clearance it was 0.51 m and the walker saw into the house). Reversed-Z
    // float depth keeps its relative precision at any near distance. The same for every
    // scenario of a view: comparisons of depths (ProposalMask) need one near plane.
    near_ = std::clamp(kNearFraction * statistics_.heightAboveTerrain, 0.02, 1.0e4);
    // The clearance may come from a finer probe than the level the ground near the camera
    // is drawn from (or the nadir ceiling): the near plane stays closer than that ground.
    if (const std::optional<double> ground = terrain_->statistics().nadirGround) {
        near_ = std::min(near_, kNearFraction * (camera.geodetic.height - *ground));
    }
    const glm::dmat4 projection = SceneRenderer::projection(
        camera.verticalFov, double(settings.width) / settings.height, near_, camera.lensShift);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    if (settings.samples == 1) {
        if (Status drawn = drawSample(camera, projection, levels, batches.value(), settings, true);
            !drawn) {
            glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
            return drawn.error();
        }
    } else {
        if (Status begun =
                accumulator_->begin(settings.width, settings.height, settings.linearOutput);
            !begun) {
            glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
            return begun.error();
        }
        // The shadow maps follow the camera, not the sub-pixel shift: drawn with the first
        // sample, looked up by all.
        bool first = true;
        for (const glm::dvec2& offset : SampleAccumulator::pattern(settings.samples)) {
            if (Status drawn = drawSample(
                    camera,
                    SampleAccumulator::shifted(projection, offset, settings.width, settings.height),
                    levels, batches.value(), settings, first);
                !drawn) {
                Framebuffer::unbind();
                glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
                return drawn.error();
            }
            first = false;
            accumulator_->add(output_, 1.0f / float(settings.samples));
        }
        accumulator_->resolve(output_);
    }
    Image image;
    image.width = settings.width;
    image.height = settings.height;
    image.pixels = output_.readPixelsRGBA8(0);
    if (settings.linearOutput) {
        image.radiance = output_.readPixelsFloat(1, 4);
    }
    Framebuffer::unbind();
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    statistics_.terrain = terrain_->statistics();
    statistics_.gpuSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return image;
}

Status SceneRenderer::streamMeshes(const TerrainLayers& layers, TileProvider& provider,
                                   const Camera& camera, const RenderSettings& settings) {
    statistics_.meshes = {};
    statistics_.meshPassSeconds = 0;
    meshesStreamed_ = !layers.meshes.empty();
    if (!meshesStreamed_) {
        return Status::success();
    }
    const auto start = std::chrono::steady_clock::now();
    if (Status status = meshes_->update(layers.meshes, provider, camera, settings.meshes);
        !status) {
        return status;
    }
    statistics_.meshPassSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return Status::success();
}

void SceneRenderer::drawMeshes(const Camera& camera, const glm::dmat4& projection,
                               const RenderSettings& settings) {
    if (!meshesStreamed_) {
        return;  // the tiles of another scenario may still be resident
    }
    const auto start = std::chrono::steady_clock::now();
    MeshDrawView view;
    view.eye = camera.position;
    view.rotation = camera.viewRotation();
    view.projection = projection;
    view.pixelAngle = 2.0 * std::tan(camera.verticalFov / 2) / settings.height;
    meshes_->draw(view, false);
    glFinish();  // only to time the pass
    statistics_.meshes = meshes_->statistics();
    statistics_.meshPassSeconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Status SceneRenderer::prepareFarField(const TerrainLayers& layers, TileProvider& provider,
                                      const Camera& camera, const LevelRange& levels,
                                      const RenderSettings& settings) {
    statistics_.farFieldPassSeconds = 0;
    const double pixelAngle = 2.0 * std::tan(camera.verticalFov / 2) / settings.height;
    Result<FarFieldFrame> frame = farField_->update(
        layers, provider, camera, levels, statistics_.heightAboveTerrain, pixelAngle,
        settings.vegetation, settings.farField, settings.waitForTiles, settings.plantDate);
    if (!frame) {
        return frame.error();
    }
    statistics_.farField = frame.value();
    return Status::success();
}

VegetationSettings SceneRenderer::drawFarField(const Camera& camera, const glm::dmat4& projection,
                                               const RenderSettings& settings) {
    VegetationSettings vegetation = settings.vegetation;
    if (!statistics_.farField.drawn) {
        return vegetation;
    }
    const auto start = std::chrono::steady_clock::now();
    farField_->draw(camera, projection, near_, settings.width, settings.height, settings.ocean);
    glFinish();  // only to time the pass
    statistics_.farFieldPassSeconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    vegetation.farField = farField_->fade();
    return vegetation;
}

double SceneRenderer::meterEv100(const Camera& camera, double groundHeight,
                                 const RenderSettings& settings) {
    const AtmosphereParameters& atmosphere = settings.atmosphereParameters;
    const bool inSpace = camera.geodetic.height > atmosphere.topRadius - atmosphere.bottomRadius;
    // From space the day side is what is seen: meter for the sun at the zenith.
    const Geodetic ground{camera.geodetic.latitude, camera.geodetic.longitude, groundHeight};
    const glm::dvec3 point = Ellipsoid::toEcef(ground);
    const glm::dvec3 sun = inSpace ? Ellipsoid::surfaceNormal(ground.latitude, ground.longitude)
                                   : settings.sunDirection;
    return ev100FromIlluminance(luminance(shading_->horizontalIlluminance(point, sun, atmosphere)));
}

Status SceneRenderer::prepareSpecies(const TerrainLayers& layers) {
    Result<std::vector<VegetationStreamLayer>> prepared = vegetationLayers(layers, true);
    return prepared ? Status::success() : Status(prepared.error());
}

Result<std::optional<std::uint32_t>> SceneRenderer::speciesFor(const PlantModelSource& model,
                                                               bool wait) {
    const std::uint64_t hash = model.contentHash();
    if (auto found = speciesOfModel_.find(hash); found != speciesOfModel_.end()) {
        return std::optional<std::uint32_t>(found->second);
    }
    auto build = assetBuilds_.find(hash);
    if (build == assetBuilds_.end() && !wait) {
        // The model outlives the build: finishAssetBuilds() runs before graphs are dropped.
        build = assetBuilds_
                    .emplace(hash, std::async(std::launch::async, buildAssetInBackground, &model))
                    .first;
    }
    if (build != assetBuilds_.end() && !wait &&
        build->second.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
        return std::optional<std::uint32_t>();
    }
    Result<std::shared_ptr<const PlantAsset>> asset = Error{""};
    if (build != assetBuilds_.end()) {
        asset = build->second.get();
        assetBuilds_.erase(build);
    } else {
        asset = model.asset();
    }
    if (!asset) {
        return asset.error();
    }
    Result<std::uint32_t> index = vegetation_->addSpecies(asset.value());
    if (!index) {
        return index.error();
    }
    speciesOfModel_.emplace(hash, index.value());
    // Batches made while the species was missing lack its plants.
    vegetationStream_.clear();
    return std::optional<std::uint32_t>(index.value());
}

Result<std::vector<VegetationStreamLayer>> SceneRenderer::vegetationLayers(
    const TerrainLayers& layers, bool wait) {
    std::vector<VegetationStreamLayer> out;
    statistics_.pendingSpecies = 0;
    for (const PlantsSource* plants : layers.plants) {
        VegetationStreamLayer layer;
        layer.source = plants;
        const std::vector<const PlantModelSource*>& models = plants->models();
        for (std::size_t i = 0; i < plants->speciesNames().size(); ++i) {
            const PlantModelSource* model = i < models.size() ? models[i] : nullptr;
            if (model == nullptr) {
                layer.species.push_back(-1);
                continue;
            }
            Result<std::optional<std::uint32_t>> species = speciesFor(*model, wait);
            if (!species) {
                return species.error();
            }
            if (!species.value()) {
                ++statistics_.pendingSpecies;  // drawn once built: not a hole, the terrain shows
            }
            layer.species.push_back(species.value() ? int(*species.value()) : -1);
        }
        out.push_back(std::move(layer));
    }
    return out;
}

}  // namespace sylva::render
