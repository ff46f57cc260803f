// BitmapFont: a built-in 5 × 7 pixel font (printable ASCII) for labels in comparison
// images and contact sheets, so no font file or library is needed headless. Glyphs
// are drawn on a 6 × 9 cell (one column and two rows of spacing), scaled by an integer.
#pragma once

#include <string_view>

#include "sylva/core/image/Image.h"

namespace sylva {

class BitmapFont {
public:
    static constexpr int kGlyphWidth = 5;
    static constexpr int kGlyphHeight = 7;
    static constexpr int kCellWidth = 6;
    static constexpr int kCellHeight = 9;

    // Size in pixels of `text` at `scale` (one line; characters outside printable
    // ASCII are drawn as '?').
    static int textWidth(std::string_view text, int scale) {
        return static_cast<int>(text.size()) * kCellWidth * scale;
    }
    static int textHeight(int scale) { return kCellHeight * scale; }
    // Whether glyph pixel (column, row) of `character` is set.
    static bool pixel(char character, int column, int row);
    // Draws `text` with its top-left corner at (x, y) in sRGB colour `rgb`, clipped to
    // the image; with `background`, a box of that colour behind it (1 glyph-pixel margin).
    static void draw(RgbaImage& image, int x, int y, std::string_view text, int scale,
                     const std::uint8_t rgb[3], const std::uint8_t* background = nullptr);
};

}  // namespace sylva
