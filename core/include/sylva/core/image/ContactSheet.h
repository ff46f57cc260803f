// ContactSheet: one overview image per view series — a grid of thumbnails, each with
// its label (camera, scenario, time) underneath, in the order given.
#pragma once

#include <string>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/image/Image.h"

namespace sylva {

struct ContactSheetEntry {
    std::string label;
    RgbaImage image;
};

class ContactSheet {
public:
    // Thumbnails `thumbnailWidth` pixels wide (height keeps each image's aspect),
    // `columns` per row (0: about square). Fails on an empty list.
    static Result<RgbaImage> build(const std::vector<ContactSheetEntry>& entries,
                                   int thumbnailWidth = 320, int columns = 0);
    // Area-averaged reduction in linear light (no aliasing, no darkening of edges).
    static RgbaImage resize(const RgbaImage& image, int width, int height);
};

}  // namespace sylva
