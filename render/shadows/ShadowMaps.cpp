#include "sylva/render/shadows/ShadowMaps.h"

#include <glad/gl.h>

#include <algorithm>
#include <iterator>
#include <optional>
#include <string>

#include "sylva/core/base/Hash.h"

namespace sylva::render {

Result<std::unique_ptr<ShadowMaps>> ShadowMaps::create() {
    std::unique_ptr<ShadowMaps> maps(new ShadowMaps());
    maps->framebuffer_ = createGlFramebuffer();
    return maps;
}

Status ShadowMaps::ensureTexture(int resolution) {
    if (texture_ && resolution_ == resolution) {
        return Status::success();
    }
    GlTexture texture = createGlTexture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(texture.get(), 1, GL_DEPTH_COMPONENT32F, resolution, resolution,
                       kMaxCascades);
    GlTexture cache = createGlTexture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(cache.get(), 1, GL_DEPTH_COMPONENT32F, resolution, resolution, kMaxCascades);
    if (GLenum error = glGetError(); error != GL_NO_ERROR) {
        return Error{"shadow maps: the driver cannot make a " + std::to_string(resolution) +
                     "² × " + std::to_string(kMaxCascades) +
                     " GL_DEPTH_COMPONENT32F texture array (GL error " + std::to_string(error) +
                     ")"};
    }
    // Nearest: shadows.glsl filters itself, comparing each texel with its own depth.
    glTextureParameteri(texture.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(texture.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture.get(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(texture.get(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    texture_ = std::move(texture);
    cache_ = std::move(cache);
    std::fill(std::begin(cacheValid_), std::end(cacheValid_), false);
    std::fill(std::begin(layerValid_), std::end(layerValid_), false);
    resolution_ = resolution;
    glNamedFramebufferDrawBuffer(framebuffer_.get(), GL_NONE);
    glNamedFramebufferReadBuffer(framebuffer_.get(), GL_NONE);
    glNamedFramebufferTextureLayer(framebuffer_.get(), GL_DEPTH_ATTACHMENT, texture_.get(), 0, 0);
    const GLenum status = glCheckNamedFramebufferStatus(framebuffer_.get(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        texture_ = {};
        return Error{
            "shadow maps: a framebuffer with only a GL_DEPTH_COMPONENT32F array layer is "
            "incomplete on this driver (status " +
            std::to_string(status) + ")"};
    }
    return Status::success();
}

Status ShadowMaps::render(const Camera& camera, double aspect, const glm::dvec3& sunDirection,
                          const ShadowSettings& settings,
                          const std::vector<ShadowCaster*>& casters) {
    cascades_ = ShadowCascades::fit(camera, aspect, sunDirection, settings);
    if (cascades_.empty()) {
        std::fill(std::begin(layerValid_), std::end(layerValid_), false);  // nothing to keep
        return Status::success();
    }
    SYLVA_CHECK(int(cascades_.size()) <= kMaxCascades);
    if (Status status = ensureTexture(settings.resolution); !status) {
        cascades_.clear();
        return status;
    }
    lightRotation_ = ShadowCascades::lightRotation(sunDirection);
    const bool sameSun = lightRotation_ == previousLight_;
    // Keys first: which cascades are out of date, and which of those wait their turn.
    std::vector<ShadowView> views(cascades_.size());
    std::vector<CascadeCasters> work;
    for (std::size_t i = 0; i < cascades_.size(); ++i) {
        ShadowView& view = views[i];
        view.camera = &camera;
        view.lightRotation = lightRotation_;
        view.projection = cascades_[i].projection;
        view.sunDirection = glm::normalize(sunDirection);
        view.cascade = &cascades_[i];
        view.cascadeIndex = int(i);
        view.resolution = resolution_;
        work.push_back(castersOf(i, view, casters));
    }
    const std::vector<bool> keep = cascadesToKeep(work, settings.maximumRedraws, sameSun);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
    glViewport(0, 0, resolution_, resolution_);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glEnable(GL_DEPTH_CLAMP);
    glDisable(GL_CULL_FACE);
    cachedCascades_ = 0;
    keptCascades_ = 0;
    for (std::size_t i = 0; i < cascades_.size(); ++i) {
        if (keep[i]) {
            // The layer holds the map of the previous box: that box, seen from here.
            cascades_[i] = ShadowCascades::reexpressed(previous_[i], camera, lightRotation_);
            ++keptFor_[i];
            ++keptCascades_;
            continue;
        }
        glNamedFramebufferTextureLayer(framebuffer_.get(), GL_DEPTH_ATTACHMENT, texture_.get(), 0,
                                       GLint(i));
        drawCascade(i, views[i], work[i]);
        keptFor_[i] = 0;
        layerValid_[i] = true;
    }
    previous_ = cascades_;
    previousLight_ = lightRotation_;
    glDisable(GL_DEPTH_CLAMP);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return Status::success();
}

ShadowMaps::CascadeCasters ShadowMaps::castersOf(std::size_t index, const ShadowView& view,
                                                 const std::vector<ShadowCaster*>& casters) const {
    // The key: the Earth-fixed box (its depths do not depend on the camera, ShadowCascades),
    // the sun and every cacheable caster's own state.
    ContentHash hash;
    const ShadowCascade& cascade = *view.cascade;
    hash.add(cascade.boxLight.x).add(cascade.boxLight.y).add(cascade.boxLight.z);
    hash.add(cascade.radius).add(resolution_);
    for (int column = 0; column < 3; ++column) {
        for (int row = 0; row < 3; ++row) {
            hash.add(view.lightRotation[column][row]);
        }
    }
    CascadeCasters out;
    for (ShadowCaster* caster : casters) {
        if (std::optional<std::uint64_t> key = caster->shadowCacheKey(view)) {
            hash.add(*key);
            out.cached.push_back(caster);
        } else {
            out.drawn.push_back(caster);
        }
    }
    out.key = hash.value();
    out.outOfDate = !out.cached.empty() && !(cacheValid_[index] && cacheKeys_[index] == out.key);
    return out;
}

std::vector<bool> ShadowMaps::cascadesToKeep(const std::vector<CascadeCasters>& work,
                                             int maximumRedraws, bool sameSun) const {
    std::vector<bool> keep(work.size(), false);
    if (maximumRedraws <= 0) {
        return keep;
    }
    // Out-of-date cascades in the order they are redrawn: the finest (what the eye sees
    // nearest), then the ones kept longest (none waits for ever).
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < work.size(); ++i) {
        if (work[i].outOfDate) {
            order.push_back(i);
        }
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        if ((a == 0) != (b == 0)) {
            return a == 0;
        }
        return keptFor_[a] > keptFor_[b];
    });
    for (std::size_t k = std::size_t(maximumRedraws); k < order.size(); ++k) {
        const std::size_t i = order[k];
        // Only a layer that holds a map of this cascade's kind under this sun can wait.
        keep[i] = sameSun && layerValid_[i] && i < previous_.size() &&
                  previous_[i].terrainOnly == cascades_[i].terrainOnly;
    }
    return keep;
}

void ShadowMaps::drawCascade(std::size_t index, const ShadowView& view,
                             const CascadeCasters& casters) {
    const GLint layer = GLint(index);
    if (!casters.cached.empty() && !casters.outOfDate) {
        glCopyImageSubData(cache_.get(), GL_TEXTURE_2D_ARRAY, 0, 0, 0, layer, texture_.get(),
                           GL_TEXTURE_2D_ARRAY, 0, 0, 0, layer, resolution_, resolution_, 1);
        ++cachedCascades_;
    } else {
        const float one = 1.0f;
        glClearNamedFramebufferfv(framebuffer_.get(), GL_DEPTH, 0, &one);
        for (ShadowCaster* caster : casters.cached) {
            caster->drawShadow(view);
        }
        cacheValid_[index] = !casters.cached.empty();
        cacheKeys_[index] = casters.key;
        if (!casters.cached.empty()) {
            glCopyImageSubData(texture_.get(), GL_TEXTURE_2D_ARRAY, 0, 0, 0, layer, cache_.get(),
                               GL_TEXTURE_2D_ARRAY, 0, 0, 0, layer, resolution_, resolution_, 1);
        }
    }
    for (ShadowCaster* caster : casters.drawn) {
        caster->drawShadow(view);
    }
}

std::vector<glm::mat4> ShadowMaps::shadowMatrices() const {
    std::vector<glm::mat4> out;
    for (const ShadowCascade& cascade : cascades_) {
        out.emplace_back(cascade.projection * glm::dmat4(lightRotation_));
    }
    return out;
}

void ShadowMaps::bindUniforms(ShaderProgram& program, const ShadowMaps* maps, int textureUnit) {
    const int count = maps != nullptr ? int(maps->cascades().size()) : 0;
    program.setInt("uShadowMap", textureUnit);
    program.setInt("uShadowCascadeCount", count);
    if (count == 0) {
        return;  // shadows.glsl never samples the map then
    }
    const std::vector<glm::mat4> matrices = maps->shadowMatrices();
    std::vector<float> texels, biases;
    for (const ShadowCascade& cascade : maps->cascades()) {
        texels.push_back(float(cascade.texelSize));
        // One texel in depth units: the depth range is three radii (ShadowCascades).
        biases.push_back(float(cascade.texelSize / (3.0 * cascade.radius)));
    }
    // Uniforms a stage does not use (location -1) are ignored by GL.
    glProgramUniformMatrix4fv(program.id(), program.uniformLocation("uShadowMatrices[0]"), count,
                              GL_FALSE, &matrices[0][0][0]);
    glProgramUniform1fv(program.id(), program.uniformLocation("uShadowTexelSizes[0]"), count,
                        texels.data());
    glProgramUniform1fv(program.id(), program.uniformLocation("uShadowDepthBias[0]"), count,
                        biases.data());
    program.setFloat("uShadowResolution", float(maps->resolution()));
    program.setMat3("uShadowLightRotation", glm::mat3(maps->lightRotation()));
    glBindTextureUnit(GLuint(textureUnit), maps->texture());
}

}  // namespace sylva::render
