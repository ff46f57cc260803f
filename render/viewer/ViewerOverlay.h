// ViewerOverlay: the text the viewer draws over a frame with the built-in BitmapFont
// (core/image): the status lines, the help (key and mouse conventions, the same list as
// docs/viewer.md), the last pick and any error. Drawn into a copy of the frame on the
// CPU, so screenshots never contain it. Private to render/viewer.
#pragma once

#include <string>
#include <vector>

#include "sylva/core/image/Image.h"

namespace sylva::render {

class ViewerOverlay {
public:
    // The help text, one line per entry.
    static const std::vector<std::string>& helpLines();

    // Draws `status` at the top left, `help` (when not empty) below it, `message` (a
    // pick) and `error` (in red, wrapped) at the bottom.
    static void draw(RgbaImage& image, const std::vector<std::string>& status,
                     const std::vector<std::string>& help, const std::string& message,
                     const std::string& error);
};

}  // namespace sylva::render
