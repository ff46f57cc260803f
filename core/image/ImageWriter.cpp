#include "sylva/core/image/ImageWriter.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <system_error>

namespace sylva {
namespace {

// Writes through OIIO to a temporary file next to `path` and renames it into place.
Status writeAtomically(const std::filesystem::path& path, OIIO::ImageSpec spec,
                       OIIO::TypeDesc pixelType, const void* pixels,
                       const ImageMetadata& metadata) {
    std::error_code error;
    const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : ".";
    std::filesystem::create_directories(folder, error);
    if (error) {
        return Error{path.string() + ": cannot create folder '" + folder.string() +
                     "': " + error.message()};
    }
    static std::atomic<unsigned> counter{0};
    // Same folder (so rename is atomic) and the same extension (so OIIO picks the format).
    const std::filesystem::path temporary =
        folder / (".sylva-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-" +
                  path.filename().string());
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(path.string());
    if (!output) {
        return Error{path.string() + ": cannot write this image format: " + OIIO::geterror()};
    }
    spec.attribute("Software", "Sylva");
    for (const auto& [name, value] : metadata.attributes) {
        spec.attribute(name, value);
    }
    bool ok = output->open(temporary.string(), spec) && output->write_image(pixelType, pixels);
    std::string reason = ok ? "" : output->geterror();
    ok = output->close() && ok;
    if (!ok) {
        if (reason.empty()) {
            reason = output->geterror();
        }
        std::filesystem::remove(temporary, error);
        return Error{path.string() +
                     ": cannot write image: " + (reason.empty() ? "unknown error" : reason)};
    }
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        return Error{path.string() +
                     ": cannot move the finished image into place: " + error.message()};
    }
    return Status::success();
}

// Reads any image as RGBA of `Channel` (OIIO converts to `pixelType`, i.e. scales to the
// channel's range): missing alpha is opaque, grey is copied into G and B, a grey image's
// alpha (its second channel) becomes A.
template <typename Channel>
Result<Image<Channel>> readImage(const std::filesystem::path& path, OIIO::TypeDesc pixelType) {
    // Keep alpha straight on reading too (OIIO premultiplies by default).
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path.string(), &config);
    if (!input) {
        return Error{path.string() + ": cannot read image: " + OIIO::geterror()};
    }
    const OIIO::ImageSpec& spec = input->spec();
    Image<Channel> image(spec.width, spec.height, 0, 0, 0, Image<Channel>::kOpaque);
    const int channels = std::min(spec.nchannels, 4);
    if (!input->read_image(0, 0, 0, channels, pixelType, image.pixels.data(),
                           4 * sizeof(Channel))) {
        return Error{path.string() + ": cannot read image: " + input->geterror()};
    }
    if (channels < 3) {  // grey (+ alpha, read into slot 1): alpha to A, grey into G and B
        for (std::size_t i = 0; i < image.pixels.size(); i += 4) {
            if (channels == 2) {
                image.pixels[i + 3] = image.pixels[i + 1];
            }
            image.pixels[i + 1] = image.pixels[i + 2] = image.pixels[i];
        }
    }
    return image;
}

}  // namespace

Status ImageWriter::writeRgba8(const std::filesystem::path& path, int width, int height,
                               const std::vector<std::uint8_t>& pixels,
                               const ImageMetadata& metadata) {
    SYLVA_CHECK(width > 0 && height > 0 && pixels.size() == std::size_t(width) * height * 4);
    OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    // Our pixels have straight (unassociated) alpha, as PNG stores it: without this
    // OIIO takes them as premultiplied and divides on write.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    return writeAtomically(path, spec, OIIO::TypeDesc::UINT8, pixels.data(), metadata);
}

Status ImageWriter::writeLinear(const std::filesystem::path& path, const LinearImage& image,
                                const ImageMetadata& metadata) {
    SYLVA_CHECK(image.width > 0 && image.height > 0 &&
                image.pixels.size() == std::size_t(image.width) * image.height * 4);
    // Half overflows to infinity above 65504 (the sun's disk can exceed it at high
    // exposure): clamp so every stored value is finite.
    std::vector<float> clamped(image.pixels.size());
    std::transform(image.pixels.begin(), image.pixels.end(), clamped.begin(),
                   [](float value) { return std::clamp(value, -65504.0f, 65504.0f); });
    OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::HALF);
    spec.attribute("oiio:ColorSpace", "Linear");
    spec.attribute("compression", "zip");
    return writeAtomically(path, spec, OIIO::TypeDesc::FLOAT, clamped.data(), metadata);
}

bool ImageWriter::isExr(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension == ".exr";
}

Result<std::vector<std::uint8_t>> ImageWriter::readRgba8(const std::filesystem::path& path,
                                                         int& width, int& height) {
    Result<RgbaImage> image = readImage<std::uint8_t>(path, OIIO::TypeDesc::UINT8);
    if (!image) {
        return image.error();
    }
    width = image.value().width;
    height = image.value().height;
    return std::move(image.value().pixels);
}

Result<LinearImage> ImageWriter::readLinear(const std::filesystem::path& path) {
    return readImage<float>(path, OIIO::TypeDesc::FLOAT);
}

Result<ImageMetadata> ImageWriter::readMetadata(const std::filesystem::path& path,
                                                const std::vector<std::string>& names) {
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path.string());
    if (!input) {
        return Error{path.string() + ": cannot read image: " + OIIO::geterror()};
    }
    ImageMetadata metadata;
    for (const std::string& name : names) {
        const std::string value = input->spec().get_string_attribute(name);
        if (input->spec().find_attribute(name)) {
            metadata.set(name, value);
        }
    }
    return metadata;
}

}  // namespace sylva
