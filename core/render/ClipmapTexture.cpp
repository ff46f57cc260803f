#include "sylva/render/ClipmapTexture.h"

#include <glad/gl.h>

#include <algorithm>
#include <utility>

#include "sylva/core/image/ColorSpace.h"

namespace sylva::render {

Result<ClipmapTexture> ClipmapTexture::create(int size, int levels, ClipmapFormat format) {
    GLint maxLayers = 0;
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    if (levels > maxLayers) {
        return Error{"clipmap texture: " + std::to_string(levels) + " levels exceed the GL limit of " +
                     std::to_string(maxLayers) + " array layers"};
    }
    ClipmapTexture texture;
    texture.size_ = size;
    texture.levels_ = levels;
    texture.format_ = format;
    const GLenum internal = format == ClipmapFormat::Height  ? GL_R32F
                            : format == ClipmapFormat::Color ? GL_SRGB8_ALPHA8
                                                             : GL_RGB16F;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &texture.texture_);
    glTextureStorage3D(texture.texture_, 1, internal, size, size, levels);
    glTextureParameteri(texture.texture_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture.texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture.texture_, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(texture.texture_, GL_TEXTURE_WRAP_T, GL_REPEAT);
    if (glGetError() != GL_NO_ERROR) {
        return Error{"clipmap texture: cannot allocate " + std::to_string(size) + "x" + std::to_string(size) +
                     "x" + std::to_string(levels)};
    }
    return texture;
}

ClipmapTexture::~ClipmapTexture() {
    if (texture_ != 0) {
        glDeleteTextures(1, &texture_);
    }
}

ClipmapTexture::ClipmapTexture(ClipmapTexture&& other) noexcept { *this = std::move(other); }

ClipmapTexture& ClipmapTexture::operator=(ClipmapTexture&& other) noexcept {
    if (this != &other) {
        if (texture_ != 0) {
            glDeleteTextures(1, &texture_);
        }
        texture_ = std::exchange(other.texture_, 0);
        size_ = other.size_;
        levels_ = other.levels_;
        format_ = other.format_;
        uploadedBytes_ = other.uploadedBytes_;
        staging_ = std::move(other.staging_);
    }
    return *this;
}

void ClipmapTexture::upload(const Clipmap& clipmap, const std::vector<Clipmap::Region>& regions) {
    SYLVA_CHECK(clipmap.size() == size_ && clipmap.levelCount() <= levels_);
    const int channels = clipmap.channels();
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (const Clipmap::Region& region : regions) {
        const std::vector<float>& data = clipmap.data(region.level);
        if (format_ == ClipmapFormat::Color) {
            // Encode to sRGB bytes on the CPU; the GPU decodes before filtering.
            staging_.resize(std::size_t(region.width) * region.height * 4);
            for (int y = 0; y < region.height; ++y) {
                const float* source = data.data() + (std::size_t(region.y + y) * size_ + region.x) * channels;
                std::uint8_t* target = staging_.data() + std::size_t(y) * region.width * 4;
                for (int x = 0; x < region.width; ++x) {
                    for (int c = 0; c < 4; ++c) {
                        const float value = c < channels ? source[x * channels + c] : 1.0f;
                        const float encoded = c < 3 ? linearToSrgb(value) : value;
                        target[x * 4 + c] =
                            static_cast<std::uint8_t>(std::clamp(encoded, 0.0f, 1.0f) * 255.0f + 0.5f);
                    }
                }
            }
            glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
            glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
            glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
            glTextureSubImage3D(texture_, 0, region.x, region.y, region.level, region.width, region.height, 1,
                                GL_RGBA, GL_UNSIGNED_BYTE, staging_.data());
            uploadedBytes_ += staging_.size();
        } else {
            // Floats straight from the clipmap: the row length skips the rest of the level.
            glPixelStorei(GL_UNPACK_ROW_LENGTH, size_);
            glPixelStorei(GL_UNPACK_SKIP_PIXELS, region.x);
            glPixelStorei(GL_UNPACK_SKIP_ROWS, region.y);
            const GLenum layout = channels == 1 ? GL_RED : channels == 2 ? GL_RG : channels == 3 ? GL_RGB : GL_RGBA;
            glTextureSubImage3D(texture_, 0, region.x, region.y, region.level, region.width, region.height, 1,
                                layout, GL_FLOAT, data.data());
            uploadedBytes_ += std::uint64_t(region.width) * region.height * channels * sizeof(float);
        }
    }
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
}

void ClipmapTexture::bind(int unit) const { glBindTextureUnit(static_cast<GLuint>(unit), texture_); }

}  // namespace sylva::render
