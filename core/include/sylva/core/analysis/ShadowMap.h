// ShadowMap: the images of a shadow study (issue 19), drawn on the CPU into RgbaImage
// (8-bit sRGB) and written through ImageWriter (OIIO, atomic):
//   - a frame: top-down over the analysis grid, north up, `scale` pixels per cell: the
//     grey hillshade of the ground (ZtvMap's hillshade(), lit from the frame's own sun),
//     screens (buildings, canopy: cells with a screen) in brown, cells in shadow darkened
//     to 45 % with a blue tint, the site's outline in yellow (cells of `site` along an
//     edge with a cell outside; `site` empty: none), a caption (date, time, sun
//     elevation and azimuth) and a north arrow;
//   - a contact sheet: the frames of one date (those with the sun up) as thumbnails in
//     rows of `columns`, each captioned with its time.
// Units: the grid's CRS metres; angles in the captions in degrees. No failure in the
// drawing (mismatched sizes are programmer errors); writing returns ImageWriter's error.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sylva/core/analysis/ElevationGrid.h"
#include "sylva/core/analysis/ShadowStudy.h"
#include "sylva/core/base/Result.h"
#include "sylva/core/image/Image.h"

namespace sylva {

// Pixels per cell for a frame: enough for ≥ 640 px on the longer side, at most 16.
int shadowFrameScale(const GridGeometry& grid);

RgbaImage drawShadowFrame(const ElevationGrid& ground, const std::vector<float>& screens,
                          const std::vector<std::uint8_t>& site, const ShadowFrame& frame,
                          const std::string& date, int scale);

RgbaImage drawContactSheet(const std::vector<RgbaImage>& frames,
                           const std::vector<std::string>& captions, int columns,
                           int thumbnailWidth);

Status writeShadowImage(const std::filesystem::path& path, const RgbaImage& image);

}  // namespace sylva
