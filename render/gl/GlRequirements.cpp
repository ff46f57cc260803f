#include "sylva/render/gl/GlRequirements.h"

#include <glad/gl.h>

#include <string>

namespace sylva::render {

namespace {

bool formatSupports(GLenum format, GLenum property) {
    GLint value = GL_NONE;
    glGetInternalformativ(GL_TEXTURE_2D, format, property, 1, &value);
    return value == GL_FULL_SUPPORT;
}

}  // namespace

GlFeatures requiredGlFeatures() {
    GlFeatures required;
    required.vertexStorageBlocks = 2;  // ellipsoid.vert binding 0, line.vert binding 1
    required.arrayTextureLayers = 32;  // one layer per clipmap level (max_level ≤ 28)
    required.colorAttachments = 2;     // G-buffer albedo + normal; image + radiance
    required.drawBuffers = 2;
    required.textureSize = 16384;  // images up to 16384 pixels wide
    required.rgba16fRenderable = true;
    required.rgba32fRenderable = true;
    required.rgba32fBlendable = true;
    return required;
}

GlFeatures queryGlFeatures() {
    GlFeatures features;
    glGetIntegerv(GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS, &features.vertexStorageBlocks);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &features.arrayTextureLayers);
    glGetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &features.colorAttachments);
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &features.drawBuffers);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &features.textureSize);
    features.rgba16fRenderable = formatSupports(GL_RGBA16F, GL_FRAMEBUFFER_RENDERABLE);
    features.rgba32fRenderable = formatSupports(GL_RGBA32F, GL_FRAMEBUFFER_RENDERABLE);
    features.rgba32fBlendable = formatSupports(GL_RGBA32F, GL_FRAMEBUFFER_BLEND);
    return features;
}

Status checkGlFeatures(const GlFeatures& driver) {
    const GlFeatures required = requiredGlFeatures();
    const std::string lacks = "the GL driver lacks a feature Sylva needs: ";
    const struct {
        const char* name;
        int have, need;
        const char* purpose;
    } limits[] = {
        {"GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS", driver.vertexStorageBlocks,
         required.vertexStorageBlocks, "plant primitives read in vertex shaders"},
        {"GL_MAX_ARRAY_TEXTURE_LAYERS", driver.arrayTextureLayers, required.arrayTextureLayers,
         "one layer per clipmap level"},
        {"GL_MAX_COLOR_ATTACHMENTS", driver.colorAttachments, required.colorAttachments,
         "the G-buffer"},
        {"GL_MAX_DRAW_BUFFERS", driver.drawBuffers, required.drawBuffers, "the G-buffer"},
        {"GL_MAX_TEXTURE_SIZE", driver.textureSize, required.textureSize,
         "images up to 16384 pixels"},
    };
    for (const auto& limit : limits) {
        if (limit.have < limit.need) {
            return Error{lacks + limit.name + " is " + std::to_string(limit.have) +
                         ", need at least " + std::to_string(limit.need) + " (for " +
                         limit.purpose + ")"};
        }
    }
    if (!driver.rgba16fRenderable) {
        return Error{lacks + "rendering to GL_RGBA16F textures (the G-buffer)"};
    }
    if (!driver.rgba32fRenderable) {
        return Error{lacks + "rendering to GL_RGBA32F textures (radiance, anti-aliasing)"};
    }
    if (!driver.rgba32fBlendable) {
        return Error{lacks + "blending into GL_RGBA32F textures (anti-aliasing sums)"};
    }
    return Status::success();
}

}  // namespace sylva::render
