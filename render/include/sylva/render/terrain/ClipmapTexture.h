// ClipmapTexture: the GPU side of one clipmap layer, a 2D texture array with one
// layer per clipmap level (seed 001 §4.3.1). Uploads exactly the regions the CPU
// Clipmap reports as changed, packed into one pixel buffer object per update
// (orphaned and mapped for writing, so the driver can copy asynchronously while the
// CPU goes on), and counts the bytes it sends. Sampled with GL_REPEAT so the toroidal
// addressing needs no shader logic.
//
// Ownership: move-only RAII over the GL texture and pixel buffer (GlHandles; a moved-from
// texture is empty); destroy it while its context is current. Needs a current GL 4.5 context for
// every call.
#pragma once

#include <cstdint>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/terrain/Clipmap.h"
#include "sylva/render/gl/GlHandle.h"

namespace sylva::render {

enum class ClipmapFormat {
    Height,   // 1 channel, metres -> R32F
    Color,    // linear RGB(A) floats -> SRGB8_ALPHA8 (filtered in linear space)
    Normals,  // 3 channels, unit vectors -> RGB16F
};

class ClipmapTexture {
public:
    static Result<ClipmapTexture> create(int size, int levels, ClipmapFormat format);

    ClipmapTexture() = default;

    // Copies `regions` of `clipmap` (same size and level count) to the texture.
    void upload(const Clipmap& clipmap, const std::vector<Clipmap::Region>& regions);
    void bind(int unit) const;

    std::uint32_t id() const { return texture_.get(); }
    std::uint64_t uploadedBytes() const { return uploadedBytes_; }

private:
    GlTexture texture_;
    int size_ = 0;
    int levels_ = 0;
    ClipmapFormat format_ = ClipmapFormat::Height;
    std::uint64_t uploadedBytes_ = 0;
    GlBuffer pixelBuffer_;  // created at the first upload
};

}  // namespace sylva::render
