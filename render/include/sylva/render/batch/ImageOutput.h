// ImageOutput: writes a rendered image under the name its job asks for — EXR paths get
// the linear radiance (half float), every other path the displayed 8-bit sRGB pixels —
// atomically through ImageWriter, with the job's metadata.
#pragma once

#include <filesystem>

#include "sylva/core/base/Result.h"
#include "sylva/core/image/ImageMetadata.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {

class ImageOutput {
public:
    // For EXR, `image` must have been rendered with RenderSettings::linearOutput; its
    // radiance is moved out. Errors name the path.
    static Status write(const std::filesystem::path& path, Image& image,
                        const ImageMetadata& metadata = {});
};

}  // namespace sylva::render
