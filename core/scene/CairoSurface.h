// Conversions between RgbaImage (8-bit sRGB, straight alpha, rows top to bottom) and cairo
// image surfaces, shared by the annotated photographs (ViewAnnotation) and the viewpoint
// sheets (ViewpointSheet).
#pragma once

#include <cairo.h>

#include "sylva/core/image/Image.h"

namespace sylva {

// A new cairo surface holding `image`, owned by the caller (cairo_surface_destroy).
// CAIRO_FORMAT_ARGB32 premultiplies the colour by alpha (cairo's convention);
// CAIRO_FORMAT_RGB24 drops alpha (the picture is opaque). Other formats are programmer
// errors (checked).
cairo_surface_t* cairoSurfaceOf(const RgbaImage& image, cairo_format_t format);

// The first width × height pixels of an RGB24 or ARGB32 surface as an opaque RgbaImage
// (alpha 255: the annotated picture is opaque).
RgbaImage opaqueImageOf(cairo_surface_t* surface, int width, int height);

}  // namespace sylva
