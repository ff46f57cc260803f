#include "CairoSurface.h"

#include <cstddef>
#include <cstdint>

#include "sylva/core/base/Check.h"

namespace sylva {

cairo_surface_t* cairoSurfaceOf(const RgbaImage& image, cairo_format_t format) {
    SYLVA_CHECK(format == CAIRO_FORMAT_ARGB32 || format == CAIRO_FORMAT_RGB24);
    const bool premultiplied = format == CAIRO_FORMAT_ARGB32;
    cairo_surface_t* surface = cairo_image_surface_create(format, image.width, image.height);
    cairo_surface_flush(surface);
    unsigned char* data = cairo_image_surface_get_data(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    for (int y = 0; y < image.height; ++y) {
        auto* row = reinterpret_cast<std::uint32_t*>(data + std::size_t(y) * std::size_t(stride));
        for (int x = 0; x < image.width; ++x) {
            const std::uint8_t* p = image.at(x, y);
            // Cairo stores native-endian 0xAARRGGBB words; RGB24 ignores the top byte.
            const std::uint32_t a = premultiplied ? p[3] : 255u;
            const auto channel = [a](std::uint32_t c) { return (c * a + 127) / 255; };
            row[x] = (a << 24) | (channel(p[0]) << 16) | (channel(p[1]) << 8) | channel(p[2]);
        }
    }
    cairo_surface_mark_dirty(surface);
    return surface;
}

RgbaImage opaqueImageOf(cairo_surface_t* surface, int width, int height) {
    cairo_surface_flush(surface);
    const unsigned char* data = cairo_image_surface_get_data(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    RgbaImage image(width, height);
    for (int y = 0; y < height; ++y) {
        const auto* row =
            reinterpret_cast<const std::uint32_t*>(data + std::size_t(y) * std::size_t(stride));
        for (int x = 0; x < width; ++x) {
            std::uint8_t* p = image.at(x, y);
            p[0] = std::uint8_t(row[x] >> 16);
            p[1] = std::uint8_t(row[x] >> 8);
            p[2] = std::uint8_t(row[x]);
            p[3] = 255;
        }
    }
    return image;
}

}  // namespace sylva
