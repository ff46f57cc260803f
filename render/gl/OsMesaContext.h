// OsMesaContext: a GL 4.5 core context from OSMesa (Mesa's off-screen software renderer)
// with a width x height RGBA8 default framebuffer in client memory. Private to
// sylva_render; use GlContext::create().
//
// Ownership: owns the OSMesaContext and its colour buffer.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "sylva/render/gl/GlContext.h"

namespace sylva::render {

class OsMesaContext final : public GlContext {
public:
    // Fails with the reason only (the caller adds the back end name).
    static Result<std::unique_ptr<GlContext>> create(const ContextOptions& options);

    ~OsMesaContext() override;

    GlBackend backend() const override { return GlBackend::OsMesa; }
    void makeCurrent() override;

private:
    OsMesaContext() = default;

    void* context_ = nullptr;  // OSMesaContext
    int width_ = 0;
    int height_ = 0;
    std::vector<std::uint8_t> buffer_;  // the default framebuffer, RGBA8
};

}  // namespace sylva::render
