#include "sylva/render/objects/MeshRenderer.h"

#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <set>

#include "sylva/core/geo/Ellipsoid.h"

namespace sylva::render {

struct MeshGpuGeometry {
    GlVertexArray vertexArray;
    GlBuffer vertexBuffer, indexBuffer;
    GLsizei indexCount = 0;
};

struct MeshRenderer::ResidentTile {
    std::shared_ptr<const MeshTile> tile;
    std::unique_ptr<MeshGpuGeometry> geometry;  // null when the tile has no static triangles
    std::uint64_t lastWanted = 0;               // the update that last wanted it
    bool shown = false;                         // wanted by the last update (else kept for later)
    std::size_t bytes = 0;                      // CPU geometry: vertices, indices, placements
};

namespace {

constexpr GLuint kInstanceBinding = 1;
constexpr std::size_t kFloatsPerInstance = 12;  // three rows of a 3×4 matrix
constexpr GLuint kUvAttribute = 6;              // after the instance rows (3–5)

// A base colour texture: sRGB8 with alpha, so sampling returns linear colour; every mip
// level (glGenerateTextureMipmap), repeating, trilinear with 8× anisotropy where offered.
GlTexture uploadTexture(const MeshTexture& image) {
    GlTexture texture = createGlTexture(GL_TEXTURE_2D);
    const GLuint id = texture.get();
    const int levels = 1 + int(std::floor(std::log2(double(std::max(image.width, image.height)))));
    glTextureStorage2D(id, levels, GL_SRGB8_ALPHA8, image.width, image.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(id, 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE,
                        image.pixels.data());
    glGenerateTextureMipmap(id);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    if (GLAD_GL_ARB_texture_filter_anisotropic || GLAD_GL_EXT_texture_filter_anisotropic) {
        glTextureParameterf(id, GL_TEXTURE_MAX_ANISOTROPY, 8.0f);
    }
    return texture;
}

std::unique_ptr<MeshGpuGeometry> upload(const MeshGeometry& geometry) {
    auto gpu = std::make_unique<MeshGpuGeometry>();
    gpu->vertexArray = createGlVertexArray();
    gpu->vertexBuffer = createGlBuffer();
    gpu->indexBuffer = createGlBuffer();
    glNamedBufferStorage(gpu->vertexBuffer.get(),
                         GLsizeiptr(geometry.vertices.size() * sizeof(MeshVertex)),
                         geometry.vertices.data(), 0);
    glNamedBufferStorage(gpu->indexBuffer.get(),
                         GLsizeiptr(geometry.indices.size() * sizeof(std::uint32_t)),
                         geometry.indices.data(), 0);
    gpu->indexCount = GLsizei(geometry.indices.size());
    const GLuint va = gpu->vertexArray.get();
    glVertexArrayVertexBuffer(va, 0, gpu->vertexBuffer.get(), 0, sizeof(MeshVertex));
    glVertexArrayElementBuffer(va, gpu->indexBuffer.get());
    glEnableVertexArrayAttrib(va, 0);
    glVertexArrayAttribFormat(va, 0, 3, GL_FLOAT, GL_FALSE, offsetof(MeshVertex, position));
    glEnableVertexArrayAttrib(va, 1);
    glVertexArrayAttribFormat(va, 1, 3, GL_FLOAT, GL_FALSE, offsetof(MeshVertex, normal));
    glEnableVertexArrayAttrib(va, 2);
    glVertexArrayAttribFormat(va, 2, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(MeshVertex, color));
    glEnableVertexArrayAttrib(va, kUvAttribute);
    glVertexArrayAttribFormat(va, kUvAttribute, 2, GL_FLOAT, GL_FALSE, offsetof(MeshVertex, uv));
    for (GLuint a : {0u, 1u, 2u, kUvAttribute}) {
        glVertexArrayAttribBinding(va, a, 0);
    }
    for (GLuint row = 0; row < 3; ++row) {
        glEnableVertexArrayAttrib(va, 3 + row);
        glVertexArrayAttribFormat(va, 3 + row, 4, GL_FLOAT, GL_FALSE,
                                  GLuint(row * 4 * sizeof(float)));
        glVertexArrayAttribBinding(va, 3 + row, kInstanceBinding);
    }
    glVertexArrayBindingDivisor(va, kInstanceBinding, 1);
    return gpu;
}

// Appends the rows of the model → view transform p ↦ linear * p + translation.
// One instance's 3×4 row-major transform (kFloatsPerInstance floats) appended to `out`.
void appendInstance(std::vector<float>& out, const glm::dmat3& linear,
                    const glm::dvec3& translation) {
    for (int row = 0; row < 3; ++row) {
        out.push_back(float(linear[0][row]));
        out.push_back(float(linear[1][row]));
        out.push_back(float(linear[2][row]));
        out.push_back(float(translation[row]));
    }
}

// Whether a sphere (view-space centre, radius) may be inside the frustum of `projection`
// (planes from the rows of the matrix: Gribb & Hartmann 2001; for reversed-Z the clip
// depth range is 0 ≤ z ≤ w).
bool sphereVisible(const glm::dmat4& projection, const glm::dvec3& center, double radius) {
    const glm::dvec4 c(center, 1.0);
    const auto row = [&](int i) {
        return glm::dvec4(projection[0][i], projection[1][i], projection[2][i], projection[3][i]);
    };
    const glm::dvec4 planes[6] = {row(3) + row(0), row(3) - row(0), row(3) + row(1),
                                  row(3) - row(1), row(2),          row(3) - row(2)};
    for (const glm::dvec4& plane : planes) {
        const double length = glm::length(glm::dvec3(plane));
        if (length > 0.0 && glm::dot(plane, c) < -radius * length) {
            return false;
        }
    }
    return true;
}

}  // namespace

Result<std::unique_ptr<MeshRenderer>> MeshRenderer::create(const ShaderLibrary& library) {
    std::unique_ptr<MeshRenderer> renderer(new MeshRenderer());
    Result<ShaderProgram> mesh = ShaderProgram::create(
        library,
        {{GL_VERTEX_SHADER, "objects/mesh.vert"}, {GL_FRAGMENT_SHADER, "objects/mesh.frag"}});
    if (!mesh) {
        return mesh.error();
    }
    renderer->meshProgram_ = std::move(mesh.value());
    Result<ShaderProgram> depth = ShaderProgram::create(
        library,
        {{GL_VERTEX_SHADER, "objects/mesh.vert"}, {GL_FRAGMENT_SHADER, "objects/depth.frag"}});
    if (!depth) {
        return depth.error();
    }
    renderer->depthProgram_ = std::move(depth.value());
    renderer->instanceBuffer_ = createGlBuffer();
    return renderer;
}

MeshRenderer::~MeshRenderer() = default;

namespace {

// The keys of level MeshSource::kTileLevel whose tiles intersect `bounds` and lie within
// `distance` metres (on the ground) of (latitude, longitude).
std::vector<TileKey> keysNear(const GeographicBounds& bounds, double latitude, double longitude,
                              double distance) {
    const double pi = std::numbers::pi;
    const double north = distance / Ellipsoid::meridionalRadius(latitude);
    const double east =
        distance / (Ellipsoid::primeVerticalRadius(latitude) * std::max(std::cos(latitude), 1e-6));
    const double south = std::max(bounds.south, latitude - north);
    const double top = std::min(bounds.north, latitude + north);
    // Bring the bounds' longitudes next to the camera's (features may be unwrapped).
    const double shift =
        2 * pi * std::round((longitude - 0.5 * (bounds.west + bounds.east)) / (2 * pi));
    const double west = std::max(bounds.west + shift, longitude - east);
    const double eastEdge = std::min(bounds.east + shift, longitude + east);
    std::vector<TileKey> keys;
    if (south > top || west > eastEdge) {
        return keys;
    }
    const int level = MeshSource::kTileLevel;
    const int columns = TileKey::columns(level, 0), rows = TileKey::rows(level);
    const auto column = [&](double lon) {
        return int(std::floor((lon + pi) / (2 * pi) * columns));
    };
    const auto rowOf = [&](double lat) {
        return std::clamp(int(std::floor((pi / 2 - lat) / pi * rows)), 0, rows - 1);
    };
    for (int y = rowOf(top); y <= rowOf(south); ++y) {
        for (int x = column(west); x <= column(eastEdge); ++x) {
            keys.push_back(TileKey{level, 0, ((x % columns) + columns) % columns, y});
        }
    }
    return keys;
}

}  // namespace

Status MeshRenderer::update(const std::vector<const MeshSource*>& sources, TileProvider& provider,
                            const Camera& camera, const MeshSettings& settings) {
    const auto start = std::chrono::steady_clock::now();
    statistics_.tilesBuilt = 0;
    ++updates_;
    std::set<std::pair<std::uint64_t, TileKey>> wanted;
    for (const MeshSource* source : sources) {
        Result<GeographicBounds> bounds = source->bounds();
        if (!bounds) {
            return bounds.error();
        }
        for (const TileKey& key : keysNear(bounds.value(), camera.geodetic.latitude,
                                           camera.geodetic.longitude, settings.maximumDistance)) {
            const std::pair<std::uint64_t, TileKey> id{source->contentHash(), key};
            wanted.insert(id);
            if (auto found = tiles_.find(id); found != tiles_.end()) {
                found->second->lastWanted = updates_;
                continue;
            }
            Result<std::shared_ptr<const MeshTile>> tile = source->tile(key, provider);
            if (!tile) {
                return tile.error();
            }
            auto resident = std::make_unique<ResidentTile>();
            resident->tile = tile.value();
            resident->lastWanted = updates_;
            const MeshTile& built = *tile.value();
            resident->bytes = built.geometry.vertices.size() * sizeof(MeshVertex) +
                              built.geometry.indices.size() * sizeof(std::uint32_t) +
                              built.placements.size() * sizeof(ModelPlacement);
            if (!tile.value()->geometry.empty()) {
                resident->geometry = upload(tile.value()->geometry);
            }
            tiles_.emplace(id, std::move(resident));
            ++statistics_.tilesBuilt;
        }
    }
    // Tiles not wanted now (out of range, or another scenario's) stay, not drawn, within
    // keptBytes: a comparison draws two scenarios a frame and a flight comes back, and
    // dropping them rebuilt a whole city, with its ground samples, at each switch.
    for (auto& [id, resident] : tiles_) {
        resident->shown = resident->lastWanted == updates_;
    }
    dropKeptTiles(settings.keptBytes);
    std::erase_if(models_, [](const auto& entry) { return entry.second.model.use_count() == 1; });
    statistics_.residentTiles = tiles_.size();
    statistics_.buildSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return Status::success();
}

std::vector<std::shared_ptr<const MeshTile>> MeshRenderer::shownTiles() const {
    std::vector<std::shared_ptr<const MeshTile>> shown;
    for (const auto& [id, resident] : tiles_) {
        if (resident->shown) {
            shown.push_back(resident->tile);
        }
    }
    return shown;
}

void MeshRenderer::dropKeptTiles(std::size_t keptBytes) {
    std::vector<std::pair<std::uint64_t, std::pair<std::uint64_t, TileKey>>> kept;  // by age
    std::size_t bytes = 0;
    for (const auto& [id, resident] : tiles_) {
        if (!resident->shown) {
            kept.emplace_back(resident->lastWanted, id);
            bytes += resident->bytes;
        }
    }
    // Wanted longest ago first (a reload's old hashes go this way too).
    std::sort(kept.begin(), kept.end());
    for (const auto& [age, id] : kept) {
        if (bytes <= keptBytes) {
            break;
        }
        auto tile = tiles_.find(id);
        bytes -= tile->second->bytes;
        tiles_.erase(tile);
    }
}

const MeshRenderer::ModelEntry& MeshRenderer::modelEntry(
    const std::shared_ptr<const MeshModel>& model) {
    auto found = models_.find(model.get());
    if (found == models_.end()) {
        ModelEntry entry;
        entry.model = model;
        for (const ModelPart& part : model->parts) {
            std::vector<std::unique_ptr<MeshGpuGeometry>> levels;
            levels.push_back(part.geometry.empty() ? nullptr : upload(part.geometry));
            for (const SimplifiedGeometry& level : part.levels)
                levels.push_back(level.geometry.empty() ? nullptr : upload(level.geometry));
            entry.parts.push_back(std::move(levels));
        }
        for (const MeshTexture& image : model->textures) {
            entry.textures.push_back(uploadTexture(image));
        }
        found = models_.emplace(model.get(), std::move(entry)).first;
    }
    return found->second;
}

namespace {

// The level of detail of one part for a placement whose model-frame metres are `scale`
// world metres, seen at `metresPerPixel` (0: full detail): the coarsest level whose error
// stays below half a pixel.
std::size_t levelFor(const ModelPart& part, double scale, double metresPerPixel) {
    std::size_t chosen = 0;
    for (std::size_t k = 0; k < part.levels.size(); ++k)
        if (part.levels[k].errorMetres * scale <= 0.5 * metresPerPixel)
            chosen = k + 1;
    return chosen;
}

}  // namespace

void MeshRenderer::drawModel(const ResidentTile& resident, const MeshDrawView& view,
                             bool depthOnly) {
    const MeshTile& tile = *resident.tile;
    const MeshModel& model = *tile.model;
    const ModelEntry& entry = modelEntry(tile.model);
    const auto& parts = entry.parts;
    struct Visible {
        const ModelPlacement* placement;
        double scale, metresPerPixel;
    };
    std::vector<Visible> visible;
    for (const ModelPlacement& placement : tile.placements) {
        const double scale = glm::length(placement.axes[0]);
        const glm::dvec3 center =
            view.rotation * (placement.position + placement.axes * model.boundsCenter - view.eye);
        const double radius = model.boundsRadius * scale;
        if (!sphereVisible(view.projection, center, radius)) {
            continue;
        }
        const double metresPerPixel = view.pixelAngle * glm::length(center);
        if (view.pixelAngle > 0.0 && 2.0 * radius < metresPerPixel) {
            continue;  // below a pixel: the terrain colour stands for it
        }
        visible.push_back({&placement, scale, metresPerPixel});
    }
    if (visible.empty()) {
        return;
    }
    // Instances grouped by (part, level), each group contiguous in the instance buffer;
    // the part transforms once per placement.
    std::vector<std::vector<glm::dmat4>> transforms;
    transforms.reserve(visible.size());
    for (const Visible& v : visible)
        transforms.push_back(model.partTransforms(v.placement->partAngles));
    struct Group {
        std::size_t part, level, first = 0, count = 0;
    };
    std::vector<Group> groups;
    instanceScratch_.clear();
    for (std::size_t p = 0; p < model.parts.size(); ++p) {
        for (std::size_t level = 0; level < parts[p].size(); ++level) {
            Group group{p, level, instanceScratch_.size() / kFloatsPerInstance, 0};
            for (std::size_t i = 0; i < visible.size(); ++i) {
                if (levelFor(model.parts[p], visible[i].scale, visible[i].metresPerPixel) != level)
                    continue;
                const ModelPlacement& placement = *visible[i].placement;
                const glm::dmat3 toView = view.rotation * placement.axes;
                appendInstance(instanceScratch_, toView * glm::dmat3(transforms[i][p]),
                               view.rotation * (placement.position - view.eye) +
                                   toView * glm::dvec3(transforms[i][p][3]));
                ++group.count;
            }
            if (group.count > 0)
                groups.push_back(group);
        }
    }
    const std::size_t bytes = instanceScratch_.size() * sizeof(float);
    glNamedBufferData(instanceBuffer_.get(), GLsizeiptr(bytes), instanceScratch_.data(),
                      GL_STREAM_DRAW);
    for (const Group& group : groups) {
        const MeshGpuGeometry* geometry = parts[group.part][group.level].get();
        if (geometry == nullptr) {
            continue;
        }
        if (!depthOnly) {
            const int texture = model.parts[group.part].texture;
            meshProgram_.setInt("uTextured", texture >= 0 ? 1 : 0);
            if (texture >= 0) {
                glBindTextureUnit(0, entry.textures[std::size_t(texture)].get());
            }
        }
        const GLuint va = geometry->vertexArray.get();
        glVertexArrayVertexBuffer(va, kInstanceBinding, instanceBuffer_.get(),
                                  GLintptr(group.first * kFloatsPerInstance * sizeof(float)),
                                  kFloatsPerInstance * sizeof(float));
        glBindVertexArray(va);
        glDrawElementsInstanced(GL_TRIANGLES, geometry->indexCount, GL_UNSIGNED_INT, nullptr,
                                GLsizei(group.count));
        statistics_.trianglesDrawn += std::size_t(geometry->indexCount / 3) * group.count;
    }
    statistics_.placementsDrawn += visible.size();
}

void MeshRenderer::draw(const MeshDrawView& view, bool depthOnly) {
    drawWithDepthTest(view, depthOnly, GL_GREATER);
}

void MeshRenderer::drawShadow(const ShadowView& view) {
    if (view.cascade == nullptr || view.cascade->terrainOnly || view.camera == nullptr) {
        return;
    }
    MeshDrawView light;
    light.eye = view.camera->position;
    light.rotation = view.lightRotation;
    light.projection = view.projection;
    light.pixelAngle = 0.0;  // every placement casts, however small in the cascade
    // The statistics describe the camera's pass; the cascades must not overwrite them.
    const MeshStatistics cameraPass = statistics_;
    drawWithDepthTest(light, true, GL_LESS);  // shadow maps: conventional depth (ShadowCaster.h)
    statistics_ = cameraPass;
}

void MeshRenderer::drawWithDepthTest(const MeshDrawView& view, bool depthOnly,
                                     unsigned depthFunction) {
    statistics_.tilesDrawn = 0;
    statistics_.placementsDrawn = 0;
    statistics_.trianglesDrawn = 0;
    ShaderProgram& program = depthOnly ? depthProgram_ : meshProgram_;
    program.use();
    program.setMat4("uProjection", glm::mat4(view.projection));
    if (!depthOnly) {
        meshProgram_.setInt("uBaseColor", 0);
        meshProgram_.setInt("uTextured", 0);  // buildings: vertex colours only
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(depthFunction);
    glDepthMask(GL_TRUE);
    // Static geometry: one instance per tile, all tiles' transforms in one buffer.
    std::vector<const ResidentTile*> drawn;
    instanceScratch_.clear();
    for (const auto& [id, resident] : tiles_) {
        const MeshTile& tile = *resident->tile;
        if (!resident->shown || !resident->geometry ||
            !sphereVisible(view.projection, view.rotation * (tile.boundsCenter - view.eye),
                           tile.boundsRadius)) {
            continue;
        }
        appendInstance(instanceScratch_, view.rotation, view.rotation * (tile.origin - view.eye));
        drawn.push_back(resident.get());
    }
    if (!drawn.empty()) {
        glNamedBufferData(instanceBuffer_.get(),
                          GLsizeiptr(instanceScratch_.size() * sizeof(float)),
                          instanceScratch_.data(), GL_STREAM_DRAW);
        for (std::size_t i = 0; i < drawn.size(); ++i) {
            const MeshGpuGeometry& geometry = *drawn[i]->geometry;
            glVertexArrayVertexBuffer(geometry.vertexArray.get(), kInstanceBinding,
                                      instanceBuffer_.get(),
                                      GLintptr(i * kFloatsPerInstance * sizeof(float)),
                                      kFloatsPerInstance * sizeof(float));
            glBindVertexArray(geometry.vertexArray.get());
            glDrawElements(GL_TRIANGLES, geometry.indexCount, GL_UNSIGNED_INT, nullptr);
            statistics_.trianglesDrawn += std::size_t(geometry.indexCount / 3);
        }
        statistics_.tilesDrawn = drawn.size();
    }
    // Placed models: instanced per part.
    for (const auto& [id, resident] : tiles_) {
        if (resident->shown && resident->tile->model && !resident->tile->placements.empty() &&
            sphereVisible(view.projection,
                          view.rotation * (resident->tile->boundsCenter - view.eye),
                          resident->tile->boundsRadius)) {
            drawModel(*resident, view, depthOnly);
        }
    }
    glBindVertexArray(0);
}

}  // namespace sylva::render
