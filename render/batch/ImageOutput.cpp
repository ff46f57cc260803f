#include "sylva/render/batch/ImageOutput.h"

#include <utility>

#include "sylva/core/image/ImageWriter.h"

namespace sylva::render {

Status ImageOutput::write(const std::filesystem::path& path, Image& image,
                          const ImageMetadata& metadata) {
    if (ImageWriter::isExr(path)) {
        LinearImage radiance;
        radiance.width = image.width;
        radiance.height = image.height;
        radiance.pixels = std::move(image.radiance);
        return ImageWriter::writeLinear(path, radiance, metadata);
    }
    return ImageWriter::writeRgba8(path, image.width, image.height, image.pixels, metadata);
}

}  // namespace sylva::render
