// Seed 004 §3.2 (views over the upper hemisphere, baked through frame buffer objects),
// §3.4 (three texture resolutions), §3.5 (group billboards of a region's objects) and
// seed 000 ch. 7 (two-level validity test of dynamic impostors); see the header.
#include "sylva/render/vegetation/ImpostorRenderer.h"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "sylva/core/base/Check.h"

namespace sylva::render {

namespace {

constexpr int kLevels = int(ImpostorViewSet::kResolutions.size());

// The GL state a capture changes, restored on destruction.
class SavedTarget {
public:
    SavedTarget() {
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_);
        glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_);
        glGetIntegerv(GL_VIEWPORT, viewport_);
        glGetIntegerv(GL_CLIP_ORIGIN, &origin_);
        glGetIntegerv(GL_CLIP_DEPTH_MODE, &depthMode_);
    }
    ~SavedTarget() {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw_));
        glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read_));
        glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
        glClipControl(GLenum(origin_), GLenum(depthMode_));
    }
    SavedTarget(const SavedTarget&) = delete;
    SavedTarget& operator=(const SavedTarget&) = delete;

private:
    GLint draw_ = 0, read_ = 0, viewport_[4] = {0, 0, 0, 0}, origin_ = 0, depthMode_ = 0;
};

// The capture frame of a view direction (toward the eye): right, up, toward.
void viewFrame(const glm::vec3& toward, glm::vec3& right, glm::vec3& up) {
    right = std::abs(toward.z) < 0.99f ? glm::normalize(glm::cross(glm::vec3(0, 0, 1), toward))
                                       : glm::vec3(1, 0, 0);
    up = glm::cross(toward, right);
}

GlTexture arrayTexture(GLenum format, int size, int layers, int levels, GLenum filter) {
    GlTexture texture = createGlTexture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(texture.get(), levels, format, size, size, layers);
    glTextureParameteri(texture.get(), GL_TEXTURE_MIN_FILTER,
                        levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : filter);
    glTextureParameteri(texture.get(), GL_TEXTURE_MAG_FILTER, filter);
    glTextureParameteri(texture.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

// The infinite reversed-Z perspective of SceneRenderer::projection, symmetric, with the
// half-angle tangent `tangent` both ways.
glm::dmat4 capturePerspective(double tangent, double near) {
    glm::dmat4 p(0.0);
    p[0][0] = 1.0 / tangent;
    p[1][1] = 1.0 / tangent;
    p[2][3] = -1.0;
    p[3][2] = near;
    return p;
}

// Coverage-preserving alpha mipmaps (Castaño 2010): averaged alpha falls below the 0.5
// test at coarse levels and far plants would vanish; per level and layer the alpha is
// scaled so that as many texels pass as at level 0 (same covered fraction), and the
// colour stays premultiplied by the alpha stored (filtering then dividing by alpha
// gives the covered texels' mean colour).
void preserveCoverage(GLuint texture, int size, int layers, int mips) {
    std::vector<float> base(std::size_t(size) * size * layers * 4);
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(base.size() * sizeof(float)),
                      base.data());
    const std::size_t basePixels = std::size_t(size) * size;
    std::vector<double> covered(std::size_t(layers), 0.0);
    for (int layer = 0; layer < layers; ++layer) {
        std::size_t count = 0;
        for (std::size_t i = 0; i < basePixels; ++i) {
            count += base[(std::size_t(layer) * basePixels + i) * 4 + 3] >= 0.5f ? 1 : 0;
        }
        covered[std::size_t(layer)] = double(count) / double(basePixels);
    }
    for (int level = 1; level < mips; ++level) {
        const int side = std::max(1, size >> level);
        const std::size_t pixels = std::size_t(side) * side;
        std::vector<float> texels(pixels * layers * 4);
        glGetTextureImage(texture, level, GL_RGBA, GL_FLOAT, GLsizei(texels.size() * sizeof(float)),
                          texels.data());
        for (int layer = 0; layer < layers; ++layer) {
            float* data = texels.data() + std::size_t(layer) * pixels * 4;
            const auto passing = [&](float scale) {
                std::size_t count = 0;
                for (std::size_t i = 0; i < pixels; ++i) {
                    count += data[i * 4 + 3] * scale >= 0.5f ? 1 : 0;
                }
                return double(count) / double(pixels);
            };
            float low = 1.0f, high = 64.0f;
            for (int step = 0; step < 24; ++step) {
                const float middle = 0.5f * (low + high);
                (passing(middle) < covered[std::size_t(layer)] ? low : high) = middle;
            }
            const float scale = passing(low) >= covered[std::size_t(layer)] ? low : high;
            for (std::size_t i = 0; i < pixels; ++i) {
                float* texel = data + i * 4;
                if (texel[3] <= 0.0f) {
                    continue;
                }
                const float alpha = std::min(1.0f, texel[3] * scale);
                for (int c = 0; c < 3; ++c) {
                    texel[c] = texel[c] / texel[3] * alpha;
                }
                texel[3] = alpha;
            }
        }
        glTextureSubImage3D(texture, level, 0, 0, 0, side, side, layers, GL_RGBA, GL_FLOAT,
                            texels.data());
    }
}

int nextPowerOfTwo(double value, int largest) {
    int size = 32;
    while (size < largest && double(size) < value) {
        size *= 2;
    }
    return size;
}

}  // namespace

// std430 mirror of shaders/vegetation/impostor.vert's Impostor (view space, metres).
struct ImpostorRenderer::GpuImpostor {
    glm::vec4 centreRadius;  // bounding-sphere centre; w: model radius
    glm::vec4 right;         // capture right axis × instance scale; w: view layer
    glm::vec4 up;            // capture up axis × instance scale
    glm::vec4 toward;        // capture toward-eye axis × instance scale
    glm::vec4 tint;          // rgb
};

struct ImpostorRenderer::SpeciesAtlas {
    glm::vec3 sphereCenter{0.0f};
    float sphereRadius = 0.0f;
    GlTexture albedo[kLevels], normal[kLevels], depth[kLevels];
};

struct ImpostorRenderer::Group {
    Framebuffer target;  // albedo, normal + distance along the capture ray, depth
    int texels = 0;
    ImpostorGuard guard;        // tile frame (ECEF axes about the batch origin)
    glm::dvec3 viewpoint{0.0};  // capture viewpoint, tile frame
    glm::dmat3 axes{1.0};       // capture right, up, back in ECEF
    double tangent = 0.0;       // half-angle tangent of the capture frustum
    glm::dvec3 origin{0.0};
    std::size_t instanceCount = 0;
    std::uint64_t lastFrame = 0;
};

Result<std::unique_ptr<ImpostorRenderer>> ImpostorRenderer::create(const ShaderLibrary& library) {
    std::unique_ptr<ImpostorRenderer> renderer(new ImpostorRenderer());
    Result<ShaderProgram> single =
        ShaderProgram::create(library, {{GL_VERTEX_SHADER, "vegetation/impostor.vert"},
                                        {GL_FRAGMENT_SHADER, "vegetation/impostor.frag"}});
    if (!single) {
        return single.error();
    }
    renderer->impostorProgram_ = std::move(single.value());
    Result<ShaderProgram> group =
        ShaderProgram::create(library, {{GL_VERTEX_SHADER, "vegetation/impostor_group.vert"},
                                        {GL_FRAGMENT_SHADER, "vegetation/impostor_group.frag"}});
    if (!group) {
        return group.error();
    }
    renderer->groupProgram_ = std::move(group.value());
    renderer->impostorBuffer_ = createGlBuffer();
    renderer->emptyArray_ = createGlVertexArray();
    return renderer;
}

ImpostorRenderer::~ImpostorRenderer() = default;

Status ImpostorRenderer::addSpecies(std::uint32_t species, const SpeciesLod& lod,
                                    const ModelDrawer& drawModel) {
    SYLVA_CHECK(species == species_.size());
    auto atlas = std::make_unique<SpeciesAtlas>();
    atlas->sphereCenter = lod.sphereCenter;
    atlas->sphereRadius = std::max(lod.sphereRadius, 1e-3f);
    const float radius = atlas->sphereRadius;
    const int views = int(views_.size());
    // Orthographic, reversed-Z: view z in [-3R, -R] (the sphere 2R in front) → depth 0..1.
    glm::mat4 projection(0.0f);
    projection[0][0] = 1.0f / radius;
    projection[1][1] = 1.0f / radius;
    projection[2][2] = 1.0f / (2.0f * radius);
    projection[3][2] = 1.5f;
    projection[3][3] = 1.0f;
    SavedTarget saved;
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    GlFramebuffer framebuffer = createGlFramebuffer();
    const GLuint fbo = framebuffer.get();
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(fbo, 2, buffers);
    for (int level = 0; level < kLevels; ++level) {
        const int size = ImpostorViewSet::kResolutions[std::size_t(level)];
        const int mips = 1 + int(std::log2(double(size)));
        atlas->albedo[level] = arrayTexture(GL_RGBA16F, size, views, mips, GL_LINEAR);
        atlas->normal[level] = arrayTexture(GL_RGBA16F, size, views, 1, GL_NEAREST);
        atlas->depth[level] = arrayTexture(GL_DEPTH_COMPONENT32F, size, views, 1, GL_NEAREST);
        glTextureParameteri(atlas->depth[level].get(), GL_TEXTURE_COMPARE_MODE, GL_NONE);
        for (int view = 0; view < views; ++view) {
            glNamedFramebufferTextureLayer(fbo, GL_COLOR_ATTACHMENT0, atlas->albedo[level].get(), 0,
                                           view);
            glNamedFramebufferTextureLayer(fbo, GL_COLOR_ATTACHMENT1, atlas->normal[level].get(), 0,
                                           view);
            glNamedFramebufferTextureLayer(fbo, GL_DEPTH_ATTACHMENT, atlas->depth[level].get(), 0,
                                           view);
            if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
                return Error{"impostor capture target is incomplete"};
            }
            const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
            const float far = 0.0f;
            glClearNamedFramebufferfv(fbo, GL_COLOR, 0, zero);
            glClearNamedFramebufferfv(fbo, GL_COLOR, 1, zero);
            glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &far);
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            glViewport(0, 0, size, size);
            glm::vec3 right, up;
            const glm::vec3 toward = views_.directions()[std::size_t(view)];
            viewFrame(toward, right, up);
            DrawInstance instance;
            instance.axisX = glm::vec4(right.x, up.x, toward.x, 1.0f);  // w: tolerated error
            instance.axisY = glm::vec4(right.y, up.y, toward.y, 0.0f);
            instance.axisZ = glm::vec4(right.z, up.z, toward.z, 0.0f);
            const glm::vec3 c = lod.sphereCenter;
            instance.origin = glm::vec4(-glm::dot(right, c), -glm::dot(up, c),
                                        -glm::dot(toward, c) - 2.0f * radius, 1.0f);
            instance.tint = glm::vec4(1.0f);
            drawModel(instance, projection);
        }
        glGenerateTextureMipmap(atlas->albedo[level].get());
        preserveCoverage(atlas->albedo[level].get(), size, views, mips);
    }
    species_.push_back(std::move(atlas));
    return Status::success();
}

void ImpostorRenderer::appendImpostor(std::vector<std::vector<GpuImpostor>>& byLevel,
                                      const DrawInstance& instance, const SpeciesLod& lod,
                                      std::uint32_t species, double pixelAngle) const {
    const SpeciesAtlas& atlas = *species_[species];
    const glm::mat3 axes(glm::vec3(instance.axisX), glm::vec3(instance.axisY),
                         glm::vec3(instance.axisZ));
    const float scale = glm::length(glm::vec3(instance.axisX));
    const glm::vec3 centre = axes * lod.sphereCenter + glm::vec3(instance.origin);
    const float distance = std::max(glm::length(centre), 1e-3f);
    // Toward the eye in the model frame (the axes are a rotation times a uniform scale).
    const glm::vec3 towardEye = glm::transpose(axes) * (-centre);
    const int view = views_.nearest(glm::length(towardEye) > 0.0f ? towardEye : glm::vec3(0, 0, 1));
    const double pixels = 2.0 * atlas.sphereRadius * scale / (double(distance) * pixelAngle);
    const int level = ImpostorViewSet::resolutionLevel(pixels);
    glm::vec3 right, up;
    const glm::vec3 toward = views_.directions()[std::size_t(view)];
    viewFrame(toward, right, up);
    GpuImpostor g;
    g.centreRadius = glm::vec4(centre, atlas.sphereRadius);
    g.right = glm::vec4(axes * right, float(view));
    g.up = glm::vec4(axes * up, 0.0f);
    g.toward = glm::vec4(axes * toward, 0.0f);
    g.tint = instance.tint;
    byLevel[std::size_t(species) * kLevels + std::size_t(level)].push_back(g);
}

void ImpostorRenderer::drawImpostors(const std::vector<std::vector<GpuImpostor>>& byLevel,
                                     const glm::mat4& projection, bool writeDistance) {
    static_assert(sizeof(GpuImpostor) == 80);  // the shader's std430 Impostor
    std::vector<GpuImpostor> all;
    for (const std::vector<GpuImpostor>& list : byLevel) {
        all.insert(all.end(), list.begin(), list.end());
    }
    if (all.empty()) {
        return;
    }
    const std::size_t bytes = all.size() * sizeof(GpuImpostor);
    if (bytes > impostorCapacity_) {
        impostorCapacity_ = bytes + bytes / 2;
        glNamedBufferData(impostorBuffer_.get(), GLsizeiptr(impostorCapacity_), nullptr,
                          GL_STREAM_DRAW);
    }
    glNamedBufferSubData(impostorBuffer_.get(), 0, GLsizeiptr(bytes), all.data());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    impostorProgram_.use();
    impostorProgram_.setMat4("uProjection", projection);
    impostorProgram_.setInt("uWriteDistance", writeDistance ? 1 : 0);
    impostorProgram_.setInt("uAlbedo", 0);
    impostorProgram_.setInt("uNormal", 1);
    impostorProgram_.setInt("uDepth", 2);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, impostorBuffer_.get());
    glBindVertexArray(emptyArray_.get());
    int first = 0;
    for (std::size_t slot = 0; slot < byLevel.size(); ++slot) {
        const std::size_t count = byLevel[slot].size();
        if (count == 0) {
            continue;
        }
        const SpeciesAtlas& atlas = *species_[slot / kLevels];
        const std::size_t level = slot % kLevels;
        glBindTextureUnit(0, atlas.albedo[level].get());
        glBindTextureUnit(1, atlas.normal[level].get());
        glBindTextureUnit(2, atlas.depth[level].get());
        impostorProgram_.setInt("uFirst", first);
        glDrawArraysInstanced(GL_TRIANGLES, 0, 6, GLsizei(count));
        first += int(count);
    }
    glBindVertexArray(0);
}

std::vector<const InstanceBatch*> ImpostorRenderer::partition(
    const std::vector<const InstanceBatch*>& batches, const Camera& camera,
    const LodSelectionSettings& selection, const ImpostorSettings& settings) {
    ++frame_;
    statistics_ = {};
    groupedBatches_.clear();
    std::vector<const InstanceBatch*> near;
    const glm::dmat3 rotation = camera.viewRotation();
    for (const InstanceBatch* batch : batches) {
        if (settings.groupPixels <= 0.0 || batch->instances.empty() || species_.empty()) {
            near.push_back(batch);
            continue;
        }
        const glm::vec3 centre(rotation *
                               (batch->origin + glm::dvec3(batch->boundsCenter) - camera.position));
        const double radius = batch->boundsRadius;
        const double distance = glm::length(centre);
        const double nearest = distance - radius;
        const double pixels =
            2.0 * batch->largestInstanceRadius / (std::max(nearest, 1e-3) * selection.pixelAngle);
        if (selection.maximumDistance > 0.0 && nearest > selection.maximumDistance) {
            continue;
        }
        if (nearest <= radius || pixels >= settings.groupPixels) {
            near.push_back(batch);
            continue;
        }
        bool inside = -double(centre.z) + radius > selection.near;
        for (int i = 0; i < 4 && inside; ++i) {
            inside = glm::dot(selection.sidePlanes[i], centre) + radius >= 0.0;
        }
        if (inside) {
            groupedBatches_.push_back(batch);
        }
    }
    return near;
}

void ImpostorRenderer::draw(const LodSelection& selected, const std::vector<SpeciesLod>& lods,
                            const Camera& camera, const glm::dmat4& projection, double pixelAngle,
                            const ImpostorSettings& settings) {
    const glm::mat4 projectionFloat(projection);
    std::vector<std::vector<GpuImpostor>> byLevel(species_.size() * kLevels);
    for (const DrawRun& run : selected.runs) {
        if (run.species >= species_.size()) {
            continue;
        }
        for (std::uint32_t i = run.firstInstance; i < run.firstInstance + run.instanceCount; ++i) {
            appendImpostor(byLevel, selected.instances[i], lods[run.species], run.species,
                           pixelAngle);
            ++statistics_.impostorInstances;
        }
    }
    drawImpostors(byLevel, projectionFloat, false);

    ImpostorValidity validity(settings.groupErrorPixels * pixelAngle);
    for (const InstanceBatch* batch : groupedBatches_) {
        std::unique_ptr<Group>& group = groups_[batch];
        if (!group || group->origin != batch->origin ||
            group->instanceCount != batch->instances.size()) {
            group = std::make_unique<Group>();
            group->origin = batch->origin;
            group->instanceCount = batch->instances.size();
        }
        group->lastFrame = frame_;
        const glm::dvec3 centre = batch->origin + glm::dvec3(batch->boundsCenter);
        const double distance = glm::length(camera.position - centre);
        const double radius = batch->boundsRadius;
        const double tangent = std::tan(std::asin(std::min(1.02 * radius / distance, 0.99)));
        // Texels the group covers on screen (its window is 2 D tan across).
        const int texels = nextPowerOfTwo(2.0 * tangent / pixelAngle, settings.largestGroupTexture);
        bool render = group->texels == 0;
        if (!render && texels > group->texels) {
            render = true;
            ++statistics_.resolutionRenders;
        }
        if (!render) {
            render = validity.test(group->guard, camera.position - batch->origin) ==
                     ImpostorVerdict::Regenerate;
        }
        if (render) {
            if (!renderGroup(*group, *batch, lods, camera, texels, validity)) {
                continue;
            }
            ++statistics_.groupsRendered;
        }
        drawGroup(*group, *batch, camera, projectionFloat);
        ++statistics_.groups;
        statistics_.groupInstances += batch->instances.size();
    }
    statistics_.validity = validity.counters();
    // Groups of tiles not drawn for a while are dropped.
    for (auto it = groups_.begin(); it != groups_.end();) {
        it = frame_ - it->second->lastFrame > 16 ? groups_.erase(it) : std::next(it);
    }
}

Status ImpostorRenderer::renderGroup(Group& group, const InstanceBatch& batch,
                                     const std::vector<SpeciesLod>& lods, const Camera& camera,
                                     int texels, const ImpostorValidity& validity) {
    const glm::dvec3 centre = batch.origin + glm::dvec3(batch.boundsCenter);
    const glm::dvec3 back = glm::normalize(camera.position - centre);
    glm::dvec3 right = glm::cross(camera.axes[1], back);
    right = glm::length(right) > 1e-6 ? glm::normalize(right) : camera.axes[0];
    const glm::dvec3 up = glm::cross(back, right);
    const double distance = glm::length(camera.position - centre);
    const double radius = batch.boundsRadius;
    group.tangent = std::tan(std::asin(std::min(1.02 * radius / distance, 0.99)));
    group.axes = glm::dmat3(right, up, back);
    group.viewpoint = camera.position - batch.origin;
    if (group.texels != texels) {
        Result<Framebuffer> target =
            Framebuffer::create(texels, texels, {GL_RGBA16F, GL_RGBA32F}, true);
        if (!target) {
            return target.error();
        }
        group.target = std::move(target.value());
        group.texels = texels;
        glTextureParameteri(group.target.colorTexture(0), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(group.target.colorTexture(0), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    }
    // The tile's instances in the capture camera's frame; the box for the validity test.
    const glm::dmat3 rotation = glm::transpose(group.axes);
    const double capturePixelAngle = 2.0 * group.tangent / texels;
    std::vector<std::vector<GpuImpostor>> byLevel(species_.size() * kLevels);
    ImpostorCapture capture;
    capture.viewpoint = group.viewpoint;
    capture.boxMinimum = glm::dvec3(std::numeric_limits<double>::infinity());
    capture.boxMaximum = -capture.boxMinimum;
    for (const InstanceBatch::Instance& instance : batch.instances) {
        if (instance.species >= species_.size()) {
            continue;
        }
        const glm::dvec3 sphere(instance.center);
        capture.boxMinimum = glm::min(capture.boxMinimum, sphere - double(instance.radius));
        capture.boxMaximum = glm::max(capture.boxMaximum, sphere + double(instance.radius));
        DrawInstance d;
        d.axisX = glm::vec4(glm::vec3(rotation * glm::dvec3(instance.axes[0])), 1.0f);
        d.axisY = glm::vec4(glm::vec3(rotation * glm::dvec3(instance.axes[1])), 0.0f);
        d.axisZ = glm::vec4(glm::vec3(rotation * glm::dvec3(instance.axes[2])), 0.0f);
        d.origin = glm::vec4(
            glm::vec3(rotation * (batch.origin + glm::dvec3(instance.base) - camera.position)),
            1.0f);
        d.tint = glm::vec4(instance.tint, 1.0f);
        appendImpostor(byLevel, d, lods[instance.species], instance.species, capturePixelAngle);
    }
    {
        SavedTarget saved;
        group.target.bind();
        group.target.clearColor(0, glm::vec4(0.0f));
        group.target.clearColor(1, glm::vec4(0.0f));
        group.target.clearDepth(0.0f);
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        drawImpostors(
            byLevel,
            glm::mat4(capturePerspective(group.tangent, std::max(distance - 1.05 * radius, 0.05))),
            true);
    }
    validity.recapture(group.guard, capture);
    return Status::success();
}

void ImpostorRenderer::drawGroup(const Group& group, const InstanceBatch& batch,
                                 const Camera& camera, const glm::mat4& projection) {
    const glm::dmat3 view = camera.viewRotation();
    const glm::dvec3 viewpoint = view * (batch.origin + group.viewpoint - camera.position);
    const glm::dmat3 toView = view * group.axes;  // capture frame → current view
    // The capture window: the plane through the tile centre facing the capture viewpoint.
    const glm::dvec3 centre =
        view * (batch.origin + glm::dvec3(batch.boundsCenter) - camera.position);
    const double extent =
        glm::length(group.viewpoint - glm::dvec3(batch.boundsCenter)) * group.tangent;
    groupProgram_.use();
    groupProgram_.setMat4("uProjection", projection);
    groupProgram_.setVec3("uCentre", glm::vec3(centre));
    groupProgram_.setVec3("uRight", glm::vec3(toView[0] * extent));
    groupProgram_.setVec3("uUp", glm::vec3(toView[1] * extent));
    groupProgram_.setVec3("uViewpoint", glm::vec3(viewpoint));
    groupProgram_.setMat3("uCaptureToView", glm::mat3(toView));
    groupProgram_.setInt("uAlbedo", 0);
    groupProgram_.setInt("uNormal", 1);
    glBindTextureUnit(0, group.target.colorTexture(0));
    glBindTextureUnit(1, group.target.colorTexture(1));
    glBindVertexArray(emptyArray_.get());
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glBindVertexArray(0);
}

}  // namespace sylva::render
