#include "sylva/render/terrain/ClipmapTexture.h"

#include <glad/gl.h>

#include <algorithm>
#include <cstring>
#include <utility>

#include "sylva/core/image/ColorSpace.h"

namespace sylva::render {

Result<ClipmapTexture> ClipmapTexture::create(int size, int levels, ClipmapFormat format) {
    GLint maxLayers = 0;
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    if (levels > maxLayers) {
        return Error{"clipmap texture: " + std::to_string(levels) +
                     " levels exceed the GL limit of " + std::to_string(maxLayers) +
                     " array layers"};
    }
    ClipmapTexture texture;
    texture.size_ = size;
    texture.levels_ = levels;
    texture.format_ = format;
    const GLenum internal = format == ClipmapFormat::Height  ? GL_R32F
                            : format == ClipmapFormat::Color ? GL_SRGB8_ALPHA8
                                                             : GL_RGB16F;
    texture.texture_ = createGlTexture(GL_TEXTURE_2D_ARRAY);
    const GLuint id = texture.texture_.get();
    glTextureStorage3D(id, 1, internal, size, size, levels);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_REPEAT);
    if (glGetError() != GL_NO_ERROR) {
        return Error{"clipmap texture: cannot allocate " + std::to_string(size) + "x" +
                     std::to_string(size) + "x" + std::to_string(levels)};
    }
    return texture;
}

void ClipmapTexture::upload(const Clipmap& clipmap, const std::vector<Clipmap::Region>& regions) {
    SYLVA_CHECK(clipmap.size() == size_ && clipmap.levelCount() <= levels_);
    if (regions.empty()) {
        return;
    }
    const int channels = clipmap.channels();
    // Colour goes up as sRGB bytes (the GPU decodes before filtering); height and
    // normals as the floats of the CPU clipmap.
    const bool bytes = format_ == ClipmapFormat::Color;
    const std::size_t texelBytes = bytes ? 4 : channels * sizeof(float);
    std::size_t total = 0;
    for (const Clipmap::Region& region : regions) {
        total += std::size_t(region.width) * region.height * texelBytes;
    }
    if (!pixelBuffer_) {
        pixelBuffer_ = createGlBuffer();
    }
    // Orphan the previous storage so a transfer still in flight is never waited for.
    glNamedBufferData(pixelBuffer_.get(), GLsizeiptr(total), nullptr, GL_STREAM_DRAW);
    auto* mapped = static_cast<std::uint8_t*>(glMapNamedBufferRange(
        pixelBuffer_.get(), 0, GLsizeiptr(total), GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT));
    SYLVA_CHECK_MESSAGE(mapped != nullptr, "ClipmapTexture: cannot map the pixel buffer");
    std::size_t offset = 0;
    std::vector<std::size_t> offsets;
    offsets.reserve(regions.size());
    for (const Clipmap::Region& region : regions) {
        offsets.push_back(offset);
        const std::vector<float>& data = clipmap.data(region.level);
        for (int y = 0; y < region.height; ++y) {
            const float* source =
                data.data() + (std::size_t(region.y + y) * size_ + region.x) * channels;
            std::uint8_t* target = mapped + offset + std::size_t(y) * region.width * texelBytes;
            if (!bytes) {
                std::memcpy(target, source, std::size_t(region.width) * texelBytes);
                continue;
            }
            for (int x = 0; x < region.width; ++x) {
                for (int c = 0; c < 4; ++c) {
                    const float value = c < channels ? source[x * channels + c] : 1.0f;
                    const float encoded = c < 3 ? linearToSrgb(value) : value;
                    target[x * 4 + c] =
                        static_cast<std::uint8_t>(std::clamp(encoded, 0.0f, 1.0f) * 255.0f + 0.5f);
                }
            }
        }
        offset += std::size_t(region.width) * region.height * texelBytes;
    }
    glUnmapNamedBuffer(pixelBuffer_.get());

    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, pixelBuffer_.get());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    const GLenum layout = bytes           ? GL_RGBA
                          : channels == 1 ? GL_RED
                          : channels == 2 ? GL_RG
                          : channels == 3 ? GL_RGB
                                          : GL_RGBA;
    const GLenum type = bytes ? GL_UNSIGNED_BYTE : GL_FLOAT;
    for (std::size_t i = 0; i < regions.size(); ++i) {
        const Clipmap::Region& region = regions[i];
        glTextureSubImage3D(texture_.get(), 0, region.x, region.y, region.level, region.width,
                            region.height, 1, layout, type,
                            reinterpret_cast<const void*>(offsets[i]));
    }
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    uploadedBytes_ += total;
}

void ClipmapTexture::bind(int unit) const {
    glBindTextureUnit(static_cast<GLuint>(unit), texture_.get());
}

}  // namespace sylva::render
