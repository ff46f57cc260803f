// ViewpointSheet: one printable sheet per viewpoint and scenario (LI TGN 06/19, NatureScot
// v2.2 viewpoint packs): the image at its print size (Camera::print, e.g. 820 × 260 mm)
// centred at the top of the page, and the viewpoint's metadata block (ViewpointRecord)
// below it in columns, with the location plan beside it when the layout has one. Drawn with cairo
// as a PDF (page in points, the image embedded at its full pixel resolution) and as a PNG at the
// print's dpi; both written atomically.
#pragma once

#include <filesystem>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/image/Image.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/scene/ViewpointRecord.h"

namespace sylva {

struct SheetLayout {
    glm::dvec2 page{0.0};      // metres; zero: the image plus margins and the metadata block
    double margin = 0.010;     // metres round the image (at least)
    double fontSize = 0.0022;  // metres (about 6 pt)
    int columns = 4;           // of the metadata block
    // The location plan (LocationMap), drawn square, mapSize wide, right of the metadata
    // block under the image (not owned; null: no map).
    const RgbaImage* locationMap = nullptr;
    double mapSize = 0.07;  // metres
};

class ViewpointSheet {
public:
    // The page size for `print` and `record` under `layout` (layout.page when set). Fails
    // when the image at print size and the metadata block do not fit on the page.
    static Result<glm::dvec2> pageSize(const PrintFormat& print, const ViewpointRecord& record,
                                       const SheetLayout& layout);

    // Writes the sheet as PDF to `pdf` and as PNG (at print.dpi) to `png` (either path may
    // be empty to skip it). `image` is sRGB 8-bit; `print` must be valid. Errors name the
    // file; nothing is left half-written.
    static Status write(const RgbaImage& image, const PrintFormat& print,
                        const ViewpointRecord& record, const SheetLayout& layout,
                        const std::filesystem::path& pdf, const std::filesystem::path& png);
};

}  // namespace sylva
