// GlRequirements: what Sylva needs from a GL 4.5 core driver beyond the version number —
// limits that GL 4.5 allows to be smaller than Sylva uses (storage buffers in vertex
// shaders may be absent: GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS may be 0) and formats it
// renders to and blends into. GlContext::create checks them once, so a driver that lacks
// one gives one error naming it instead of a failed draw later.
//
// queryGlFeatures needs a current context; checkGlFeatures is pure. A failure is an Error
// naming the first missing feature, the driver's value and what Sylva uses it for.
#pragma once

#include "sylva/core/base/Result.h"

namespace sylva::render {

struct GlFeatures {
    int vertexStorageBlocks = 0;     // GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS
    int arrayTextureLayers = 0;      // GL_MAX_ARRAY_TEXTURE_LAYERS
    int colorAttachments = 0;        // GL_MAX_COLOR_ATTACHMENTS
    int drawBuffers = 0;             // GL_MAX_DRAW_BUFFERS
    int textureSize = 0;             // GL_MAX_TEXTURE_SIZE
    bool rgba16fRenderable = false;  // GL_FRAMEBUFFER_RENDERABLE of GL_RGBA16F (G-buffer)
    bool rgba32fRenderable = false;  // of GL_RGBA32F (radiance, anti-aliasing sums)
    bool rgba32fBlendable = false;   // GL_FRAMEBUFFER_BLEND of GL_RGBA32F (anti-aliasing)
};

// The minimum values Sylva needs (see checkGlFeatures).
GlFeatures requiredGlFeatures();

// Queries the current context.
GlFeatures queryGlFeatures();

// Error "the GL driver lacks a feature Sylva needs: NAME is V, need at least M (for WHAT)"
// for the first shortfall, success otherwise.
Status checkGlFeatures(const GlFeatures& driver);

}  // namespace sylva::render
