#include "ViewerOverlay.h"

#include <algorithm>

#include "sylva/core/image/BitmapFont.h"

namespace sylva::render {
namespace {

constexpr std::uint8_t kWhite[3] = {240, 240, 240};
constexpr std::uint8_t kRed[3] = {255, 110, 100};
constexpr std::uint8_t kShade[3] = {20, 20, 24};

// Draws `lines` from (x, y) downwards; returns the y below the last line.
int drawLines(RgbaImage& image, int x, int y, const std::vector<std::string>& lines, int scale,
              const std::uint8_t* colour) {
    for (const std::string& line : lines) {
        BitmapFont::draw(image, x, y, line, scale, colour, kShade);
        y += BitmapFont::textHeight(scale) + scale;
    }
    return y;
}

// `text` cut into lines that fit `width` pixels.
std::vector<std::string> wrap(const std::string& text, int width, int scale) {
    const std::size_t perLine =
        static_cast<std::size_t>(std::max(8, width / (BitmapFont::kCellWidth * scale) - 2));
    std::vector<std::string> lines;
    for (std::size_t start = 0; start < text.size(); start += perLine) {
        lines.push_back(text.substr(start, perLine));
    }
    return lines;
}

}  // namespace

const std::vector<std::string>& ViewerOverlay::helpLines() {
    static const std::vector<std::string> lines = {
        "W/S A/D  forward/back, left/right   Q/E  down/up   Shift  5x faster",
        "arrows or left drag  look (orbit mode: drag the globe)   wheel  closer/farther",
        "Tab  mode: orbit > fly > walk (walk keeps 1.7 m above the ground)",
        "1..9  go to the project's cameras   N  next scenario",
        "T/Y  one hour earlier/later (the sun moves)   [ ]  vegetation quality",
        "P  save the camera into the project   right click  pick a point",
        "H or F1  this help   Esc  quit",
    };
    return lines;
}

void ViewerOverlay::draw(RgbaImage& image, const std::vector<std::string>& status,
                         const std::vector<std::string>& help, const std::string& message,
                         const std::string& error) {
    const int scale = image.width >= 1000 ? 2 : 1;
    const int margin = 4 * scale;
    int y = drawLines(image, margin, margin, status, scale, kWhite);
    if (!help.empty()) {
        drawLines(image, margin, y + 2 * margin, help, scale, kWhite);
    }
    std::vector<std::string> bottom;
    if (!message.empty()) {
        bottom.push_back(message);
    }
    std::vector<std::string> errorLines =
        error.empty() ? std::vector<std::string>{} : wrap(error, image.width, scale);
    const int lineHeight = BitmapFont::textHeight(scale) + scale;
    y = image.height - margin - lineHeight * static_cast<int>(bottom.size() + errorLines.size());
    y = drawLines(image, margin, y, bottom, scale, kWhite);
    drawLines(image, margin, y, errorLines, scale, kRed);
}

}  // namespace sylva::render
