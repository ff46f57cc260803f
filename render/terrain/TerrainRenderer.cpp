#include "sylva/render/terrain/TerrainRenderer.h"

#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <utility>

#include "sylva/core/base/Hash.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/terrain/ElevationQuery.h"

namespace sylva::render {
namespace {

constexpr int kMaxClipmapLevels = 32;  // matches MAX_CLIPMAP_LEVELS in clipmap.glsl
// Pyramid level = ring level - offset: colour and normals get twice the height's
// resolution (see Clipmap::windowFor).
constexpr int kHeightLevelOffset = 2;
constexpr int kDetailLevelOffset = 1;

glm::mat3 toFloat(const glm::dmat3& m) {
    return glm::mat3(m);
}

// Metres between the camera and the nadir ceiling (terrain.vert's uNadirCeiling): the
// capped ground under a camera below every resident level's ground, or less than this
// above it. SceneRenderer keeps its near plane closer than the drawn ground
// (TerrainFrameStatistics::nadirGround), so it is never clipped away.
constexpr double kNadirCeilingMargin = 1.0;

// A resident level whose ground under the camera is below it (`level` -1: none is).
struct Standing {
    int level = -1;
    double ground = 0;  // metres (ellipsoid height), of `level` at the nadir
};

// Interactive frames: the finest of the resident levels (`resident` down to
// `blendLevel`, all brought up this frame, then `fallback`) whose ground under the camera
// is below it. A camera placed on finer terrain that is still loading (a walker 1.7 m
// over the DEM) would otherwise look at a smoother, higher coarse surface from below and
// see the sky through it. Level -1 when none is (the resident level is kept then, and
// update() caps the ground near the nadir instead).
Standing standingLevel(const Source& elevation, TileProvider& provider, const Camera& camera,
                       int resident, int blendLevel, int fallback) {
    const ElevationQuery query(elevation, provider);
    std::vector<int> candidates;
    for (int level = resident; level >= blendLevel && level >= 0; --level) {
        candidates.push_back(level);
    }
    if (fallback >= 0 && fallback < blendLevel) {
        candidates.push_back(fallback);
    }
    for (int level : candidates) {
        Result<std::optional<double>> ground = query.readyGroundHeight(
            camera.geodetic.latitude, camera.geodetic.longitude, level, level);
        if (ground && ground.value() && *ground.value() < camera.geodetic.height) {
            return {level, *ground.value()};
        }
    }
    return {};
}

}  // namespace

Result<std::unique_ptr<TerrainRenderer>> TerrainRenderer::create(const ShaderLibrary& library,
                                                                 const TerrainSettings& settings) {
    if (settings.maxLevel < 2 || settings.maxLevel >= kMaxClipmapLevels) {
        return Error{"terrain: max_level must be within 2.." +
                     std::to_string(kMaxClipmapLevels - 1)};
    }
    std::unique_ptr<TerrainRenderer> renderer(new TerrainRenderer());
    renderer->settings_ = settings;
    Result<ShaderProgram> program =
        ShaderProgram::create(library, {{GL_VERTEX_SHADER, "terrain/terrain.vert"},
                                        {GL_FRAGMENT_SHADER, settings.fragmentShader}});
    if (!program) {
        return program.error();
    }
    renderer->program_ = std::move(program.value());
    Result<ShaderProgram> shadowProgram =
        ShaderProgram::create(library, {{GL_VERTEX_SHADER, "terrain/terrain.vert"},
                                        {GL_FRAGMENT_SHADER, "shadows/depth_only.frag"}});
    if (!shadowProgram) {
        return shadowProgram.error();
    }
    renderer->shadowProgram_ = std::move(shadowProgram.value());

    const TerrainRings rings(settings.columns, settings.ringsPerLevel);
    renderer->ring_ = upload(rings.ringMesh());
    renderer->fill_ = upload(rings.fillMesh());

    const int levels = settings.maxLevel + 1;
    renderer->height_ = std::make_unique<Clipmap>(levels, settings.clipmapSize, 1);
    renderer->color_ = std::make_unique<Clipmap>(levels, settings.clipmapSize, 4);
    renderer->normals_ = std::make_unique<Clipmap>(levels, settings.clipmapSize, 3);
    Result<ClipmapTexture> height =
        ClipmapTexture::create(settings.clipmapSize, levels, ClipmapFormat::Height);
    Result<ClipmapTexture> color =
        ClipmapTexture::create(settings.clipmapSize, levels, ClipmapFormat::Color);
    Result<ClipmapTexture> normals =
        ClipmapTexture::create(settings.clipmapSize, levels, ClipmapFormat::Normals);
    for (const auto* texture : {&height, &color, &normals}) {
        if (!*texture) {
            return texture->error();
        }
    }
    renderer->heightTexture_ = std::move(height.value());
    renderer->colorTexture_ = std::move(color.value());
    renderer->normalTexture_ = std::move(normals.value());
    return renderer;
}

TerrainRenderer::~TerrainRenderer() = default;

TerrainRenderer::Mesh TerrainRenderer::upload(const TerrainMesh& mesh) {
    Mesh result;
    result.vertexArray = createGlVertexArray();
    result.vertexBuffer = createGlBuffer();
    result.indexBuffer = createGlBuffer();
    const GLuint vertexArray = result.vertexArray.get();
    glNamedBufferStorage(result.vertexBuffer.get(),
                         GLsizeiptr(mesh.vertices.size() * sizeof(TerrainVertex)),
                         mesh.vertices.data(), 0);
    glNamedBufferStorage(result.indexBuffer.get(),
                         GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
                         mesh.indices.data(), 0);
    glVertexArrayVertexBuffer(vertexArray, 0, result.vertexBuffer.get(), 0, sizeof(TerrainVertex));
    glVertexArrayElementBuffer(vertexArray, result.indexBuffer.get());
    glEnableVertexArrayAttrib(vertexArray, 0);
    glVertexArrayAttribFormat(vertexArray, 0, 4, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vertexArray, 0, 0);
    glEnableVertexArrayAttrib(vertexArray, 1);
    glVertexArrayAttribFormat(vertexArray, 1, 1, GL_FLOAT, GL_FALSE, offsetof(TerrainVertex, seam));
    glVertexArrayAttribBinding(vertexArray, 1, 0);
    result.indexCount = static_cast<std::int32_t>(mesh.indices.size());
    return result;
}

LevelRange TerrainRenderer::visibleLevels(const Camera& camera, double heightAboveTerrain,
                                          int pixels) const {
    return LevelVisibility::visibleLevels(camera.geodetic.height, heightAboveTerrain,
                                          settings_.maxTerrainHeight, camera.verticalFov, pixels,
                                          settings_.maxLevel);
}

void TerrainRenderer::dropChangedSources(const TerrainLayers& layers) {
    // A different source (another scenario, an edited parameter) means different
    // texels under the same windows: drop that layer's levels.
    const std::uint64_t hashes[3] = {layers.elevation->contentHash(), layers.normals->contentHash(),
                                     hasColor_ ? layers.color->contentHash() : 0};
    Clipmap* clipmaps[3] = {height_.get(), normals_.get(), color_.get()};
    for (int layer = 0; layer < 3; ++layer) {
        if (hashes[layer] != sourceHashes_[layer]) {
            for (int level = 0; level < clipmaps[layer]->levelCount(); ++level) {
                clipmaps[layer]->invalidate(level);
            }
            sourceHashes_[layer] = hashes[layer];
        }
    }
}

Status TerrainRenderer::bringUpLevel(int level, const LevelWindows& windows, TileProvider& provider,
                                     bool wait, ReadyTiles& ready, bool& pending) {
    const int size = settings_.clipmapSize;
    // Every tile of the level's windows: ready, pending (not yet produced) or failed.
    Status status;
    while (true) {
        pending = false;
        for (const auto& [layer, window] : windows) {
            for (const TileKey& key : Clipmap::tilesFor(window, size)) {
                const auto id = std::make_pair(layer->source->contentHash(), key);
                if (ready.count(id) != 0) {
                    continue;
                }
                TileLookup lookup =
                    provider.tryGet(*layer->source, key, level + settings_.priorityOffset);
                if (lookup.state == TileLookup::State::Ready) {
                    ready.emplace(id, std::move(lookup.tile));
                } else if (lookup.state == TileLookup::State::Failed) {
                    status = lookup.error;
                } else {
                    pending = true;
                }
            }
        }
        if (!status || !pending || !wait) {
            break;
        }
        provider.waitForProgress(std::chrono::milliseconds(20));
    }
    if (!status || pending) {
        return status;
    }
    for (const auto& [layer, window] : windows) {
        const Clipmap::Fetch fetch = [&](const TileKey& key) -> Result<TilePointer> {
            auto it = ready.find({layer->source->contentHash(), key});
            SYLVA_CHECK_MESSAGE(it != ready.end(), "clipmap update outside Clipmap::tilesFor");
            return it->second;
        };
        status = layer->clipmap->update(level, window, fetch);
        layer->texture->upload(*layer->clipmap, layer->clipmap->takeDirtyRegions());
        if (!status) {
            return status;
        }
    }
    return status;
}

Result<LevelRange> TerrainRenderer::update(
    const TerrainLayers& layers, TileProvider& provider, const Camera& camera,
    const LevelRange& wanted, std::optional<std::chrono::steady_clock::time_point> deadline,
    bool waitForAll) {
    SYLVA_CHECK(layers.elevation != nullptr && layers.normals != nullptr);
    const auto start = std::chrono::steady_clock::now();
    const double latitude = camera.geodetic.latitude;
    const double longitude = camera.geodetic.longitude;
    const int size = settings_.clipmapSize;
    hasColor_ = layers.color != nullptr;
    dropChangedSources(layers);
    const LayerSlot layerList[] = {
        {height_.get(), &heightTexture_, layers.elevation, kHeightLevelOffset},
        {normals_.get(), &normalTexture_, layers.normals, kDetailLevelOffset},
        {color_.get(), &colorTexture_, layers.color, kDetailLevelOffset}};
    // The coarser neighbour blends; interactive frames also keep the levels from the
    // resident root up, so something coarse is always there to draw.
    const bool rooted = !waitForAll && settings_.residentLevel >= 0;
    int firstLevel = std::max(0, wanted.coarsest - 1);  // = blendLevel below
    if (rooted) {
        firstLevel = std::min(firstLevel, settings_.residentLevel);
    }

    // Seed 001 Algorithm 3: gather the tiles of every level (coarse before fine by
    // priority), hand the list over (queued tasks of the previous focus are cancelled,
    // running ones finish and stay cached), then bring levels up coarse to fine.
    struct LevelTiles {
        LevelWindows windows;
    };
    std::vector<LevelTiles> levelTiles(std::size_t(wanted.finest - firstLevel + 1));
    std::vector<TileRequest> requests;
    for (int level = firstLevel; level <= wanted.finest; ++level) {
        for (const LayerSlot& layer : layerList) {
            if (layer.source == nullptr) {
                continue;
            }
            const ClipmapWindow window =
                Clipmap::windowFor(level, latitude, longitude, size, layer.levelOffset);
            if (layer.clipmap->valid(level) && layer.clipmap->window(level) == window) {
                continue;
            }
            levelTiles[std::size_t(level - firstLevel)].windows.emplace_back(&layer, window);
            for (const TileKey& key : Clipmap::tilesFor(window, size)) {
                requests.push_back({layer.source, key, level + settings_.priorityOffset});
            }
        }
    }
    provider.setFocus(latitude, longitude);
    provider.setWanted(requests);

    statistics_.wanted = wanted;
    statistics_.degraded.clear();
    statistics_.waitingLevel = -1;
    const int blendLevel = std::max(0, wanted.coarsest - 1);
    int resident = wanted.finest;  // the finest level brought up (all coarser drawn ones are)
    int fallback = -1;             // the finest level brought up coarser than the rings
    // Tiles already obtained in this call, so a level waited for keeps them even if the
    // cache prunes meanwhile.
    ReadyTiles ready;
    for (int level = firstLevel; level <= wanted.finest; ++level) {
        // Batch rendering waits for every level; interactive frames only for the
        // resident root, or (without one) for nothing.
        bool pending = false;
        Status status =
            bringUpLevel(level, levelTiles[std::size_t(level - firstLevel)].windows, provider,
                         waitForAll || (rooted && level == firstLevel), ready, pending);
        if (!status) {
            if (level <= wanted.coarsest) {
                return status.error();
            }
            resident = level - 1;
            statistics_.degraded = "level " + std::to_string(level) +
                                   " failed, drawing up to level " + std::to_string(resident) +
                                   ": " + status.error().message;
            break;
        }
        if (pending && level < blendLevel) {
            // A fallback level coarser than any drawn ring: the finer ones go on.
            statistics_.waitingLevel =
                statistics_.waitingLevel < 0 ? level : statistics_.waitingLevel;
            continue;
        }
        if (pending) {
            // Not an error: the workers are still producing; a later frame draws it.
            resident = level - 1;
            statistics_.waitingLevel = level;
            break;
        }
        if (level < wanted.coarsest) {
            fallback = level;
        }
        if (deadline && level >= wanted.coarsest && level < wanted.finest &&
            std::chrono::steady_clock::now() > *deadline) {
            resident = level;
            statistics_.degraded = "time limit reached after level " + std::to_string(level);
            break;
        }
    }
    // The rings from the coarsest wanted to the finest resident level; when even the
    // coarsest wanted is not resident, the rings show the finest resident coarser level
    // (rooted), or nothing is drawn (no root: an empty range).
    if (resident < wanted.coarsest) {
        resident = fallback;  // rings drawn without blending: one level is enough
    }
    statistics_.residentLevel = resident;
    statistics_.nadirGround.reset();
    nadirCeiling_.reset();
    if (rooted && resident >= 0) {
        resident = standOrCap(*layers.elevation, provider, camera, resident, blendLevel, fallback);
    }
    // Rooted: every wanted ring is drawn, those finer than the resident level sampling it
    // (no blend). The ring mesh near the nadir stays fine, so its surface there is the
    // bilinear ground standingLevel checked (a coarse fill disk's big flat triangles
    // could pass above the camera and show the sky below the horizon).
    LevelRange drawn = wanted;
    drawn.finest = rooted ? wanted.finest : resident;
    textureCeiling_ = resident;
    statistics_.textureLevel = resident;
    const std::uint64_t uploaded = heightTexture_.uploadedBytes() + normalTexture_.uploadedBytes() +
                                   colorTexture_.uploadedBytes();
    statistics_.uploadedBytes = uploaded - uploadedBefore_;
    uploadedBefore_ = uploaded;
    statistics_.updateSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return drawn;
}

TerrainFrameStatistics TerrainRenderer::statistics() const {
    TerrainFrameStatistics statistics = statistics_;
    if (nadirCeiling_) {
        statistics.nadirCeiling = nadirCeiling_->height;
    }
    return statistics;
}

int TerrainRenderer::standOrCap(const Source& elevation, TileProvider& provider,
                                const Camera& camera, int resident, int blendLevel, int fallback) {
    const Standing standing =
        standingLevel(elevation, provider, camera, resident, blendLevel, fallback);
    // No resident level's ground is (clearly) below the camera: an aircraft over a valley
    // that the coarse levels, averaging its ridges, fill above it. Drawn as is, that
    // surface lies over the camera near the nadir and rays looking down pass under it to
    // the sky; the ceiling lowers it there (terrain.vert, uNadirCeiling).
    const double ceiling = camera.geodetic.height - kNadirCeilingMargin;
    if (standing.level < 0 || standing.ground > ceiling) {
        nadirCeiling_ = NadirCeiling{ceiling, camera.geodetic.latitude, camera.geodetic.longitude};
        statistics_.nadirGround = ceiling;
    } else {
        statistics_.nadirGround = standing.ground;
    }
    return standing.level >= 0 ? standing.level : resident;
}

void TerrainRenderer::draw(const Camera& camera, const glm::dmat4& projection,
                           const LevelRange& levels, bool ocean) {
    const glm::dmat3 view = camera.viewRotation();
    program_.setMat3("uEcefToView", toFloat(view));
    program_.setInt("uHasColor", hasColor_ ? 1 : 0);
    program_.setInt("uColor", 1);
    program_.setInt("uNormals", 2);
    colorTexture_.bind(1);
    normalTexture_.bind(2);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);  // reversed-Z
    glDisable(GL_CULL_FACE);
    statistics_.levels = levels;
    lastLevels_ = levels;
    lastOcean_ = ocean;
    statistics_.triangles = drawRings(program_, camera, view, projection, levels, ocean);
}

std::optional<LevelRange> TerrainRenderer::shadowLevels(const ShadowView& view) const {
    if (!lastLevels_ || view.camera == nullptr) {
        return std::nullopt;  // nothing updated yet
    }
    const ShadowCascade& cascade = *view.cascade;
    // Only the levels whose rings can reach the cascade: the disk around the nadir that
    // holds the cascade's box and its depth range towards the sun (two radii), and no
    // finer than the cascade's texels need (the fill disk closes the finest drawn level).
    constexpr double kRadius = 6371000.0;
    const double reach = glm::length(cascade.boxRelative) + 3.0 * cascade.radius;
    LevelRange levels = *lastLevels_;
    // Ring level i covers view angles pi 2^-(i+1) .. pi 2^-i around the nadir.
    const int coarsest = int(std::floor(std::log2(std::numbers::pi * kRadius / (2.0 * reach))));
    // Its heights come from pyramid level i - 2: pi R / (256 2^(i-2)) metres per texel.
    const int finest =
        kHeightLevelOffset + int(std::ceil(std::log2(std::numbers::pi * kRadius /
                                                     (settings_.clipmapSize * cascade.texelSize))));
    levels.finest = std::clamp(finest, levels.coarsest, levels.finest);
    levels.coarsest = std::clamp(coarsest, levels.coarsest, levels.finest);
    return levels;
}

void TerrainRenderer::drawShadow(const ShadowView& view) {
    const std::optional<LevelRange> levels = shadowLevels(view);
    if (!levels) {
        return;
    }
    shadowProgram_.use();
    drawRings(shadowProgram_, *view.camera, view.lightRotation, view.projection, *levels,
              lastOcean_);
}

std::optional<std::uint64_t> TerrainRenderer::shadowCacheKey(const ShadowView& view) const {
    const std::optional<LevelRange> levels = shadowLevels(view);
    if (!levels) {
        return std::nullopt;
    }
    // What the depth in the cascade's Earth-fixed box (ShadowMaps adds the box and the sun)
    // depends on: the levels drawn, the finest resident level they sample, the ocean and
    // the height source. Not the camera, nor the clipmap's uploads: every level holds its
    // source's tiles (Clipmap copies them unchanged), so a window that scrolls with the
    // camera holds the same heights where it overlaps, and the rings (drawn around the
    // camera) only triangulate the same heightfield a little differently, by less than the
    // levels' own spacing, which is no finer than the cascade's texels (shadowLevels).
    // A camera moving within the box's cell thus keeps the terrain's depth
    // (docs/architecture.md, sun shadows; tested by ShadowTest.SmallCameraSteps*).
    // The nadir ceiling (update()) reshapes the ground around the camera's nadir: while it
    // is on, the depth depends on its height and on that nadir.
    ContentHash hash;
    hash.add(levels->coarsest).add(levels->finest).add(textureCeiling_).add(lastOcean_);
    hash.add(sourceHashes_[0]);
    hash.add(nadirCeiling_.has_value());
    if (nadirCeiling_) {
        hash.add(nadirCeiling_->height).add(nadirCeiling_->latitude).add(nadirCeiling_->longitude);
    }
    return hash.value();
}

std::uint64_t TerrainRenderer::drawRings(ShaderProgram& program, const Camera& camera,
                                         const glm::dmat3& rotation, const glm::dmat4& projection,
                                         const LevelRange& levels, bool ocean) {
    const double latitude = camera.geodetic.latitude;
    const double longitude = camera.geodetic.longitude;
    const int size = settings_.clipmapSize;
    // The viewer's meridian frame is ECEF rotated by -longitude about z.
    const double c = std::cos(longitude), s = std::sin(longitude);
    const glm::dmat3 meridianToEcef(glm::dvec3(c, s, 0), glm::dvec3(-s, c, 0), glm::dvec3(0, 0, 1));
    const glm::dvec3 ground = Ellipsoid::toEcef({latitude, longitude, 0.0});

    program.use();
    program.setVec3("uViewerLatitude", glm::vec3(float(std::sin(latitude)),
                                                 float(std::cos(latitude)), float(latitude)));
    program.setFloat("uBearingSign", latitude >= 0 ? 1.0f : -1.0f);
    program.setMat3("uMeridianToView", toFloat(rotation * meridianToEcef));
    program.setVec3("uGroundToCamera", glm::vec3(rotation * (ground - camera.position)));
    program.setMat4("uProjection", glm::mat4(projection));
    program.setFloat("uClipmapSize", float(size));
    program.setInt("uOcean", ocean ? 1 : 0);
    program.setFloat("uRingStep", float(std::exp2(1.0 / settings_.ringsPerLevel) - 1.0));
    program.setFloat("uBearingStep", float(2.0 * std::numbers::pi / settings_.columns));
    program.setInt("uHeight", 0);
    program.setInt("uNadirCeilingOn", nadirCeiling_ ? 1 : 0);
    program.setFloat("uNadirCeiling", nadirCeiling_ ? float(nadirCeiling_->height) : 0.0f);
    for (const auto& [clipmap, name] : {std::pair{height_.get(), "uHeightLevels[0]"},
                                        std::pair{normals_.get(), "uDetailLevels[0]"}}) {
        std::vector<glm::vec4> levelUniforms(kMaxClipmapLevels, glm::vec4(0.0f));
        for (int level = 0; level <= settings_.maxLevel; ++level) {
            if (!clipmap->valid(level)) {
                continue;
            }
            const ClipmapWindow& window = clipmap->window(level);
            const double texelWidth = window.texelWidth(size);
            const double texelHeight = window.texelHeight(size);
            // The viewer's continuous texel coordinate, reduced modulo the size in
            // double so the float the GPU gets is small and exact enough.
            double x = (longitude + std::numbers::pi) / texelWidth;
            double y = (std::numbers::pi / 2 - latitude) / texelHeight;
            x -= std::floor(x / size) * size;
            y -= std::floor(y / size) * size;
            levelUniforms[level] =
                glm::vec4(float(1.0 / texelWidth), float(1.0 / texelHeight), float(x), float(y));
        }
        glProgramUniform4fv(program.id(), program.uniformLocation(name), kMaxClipmapLevels,
                            &levelUniforms[0].x);
    }
    heightTexture_.bind(0);
    std::uint64_t triangles = 0;
    // A ring finer than the resident levels samples the finest resident one.
    for (int level = levels.coarsest; level <= levels.finest; ++level) {
        program.setInt("uLevel", level);
        program.setInt("uTextureLevel", std::min(level, textureCeiling_));
        program.setFloat("uLevelScale", float(std::ldexp(1.0, -level)));
        glBindVertexArray(ring_.vertexArray.get());
        glDrawElements(GL_TRIANGLES, ring_.indexCount, GL_UNSIGNED_INT, nullptr);
        triangles += std::uint64_t(ring_.indexCount / 3);
    }
    // The fill disk closes the finest level down to the nadir; it never blends.
    program.setInt("uLevel", levels.finest);
    program.setInt("uTextureLevel", std::min(levels.finest, textureCeiling_));
    program.setFloat("uLevelScale", float(std::ldexp(1.0, -levels.finest)));
    glBindVertexArray(fill_.vertexArray.get());
    glDrawElements(GL_TRIANGLES, fill_.indexCount, GL_UNSIGNED_INT, nullptr);
    triangles += std::uint64_t(fill_.indexCount / 3);
    glBindVertexArray(0);
    return triangles;
}

}  // namespace sylva::render
