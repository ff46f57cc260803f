#include "sylva/core/image/ImageWriter.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <atomic>
#include <system_error>

namespace sylva {

Status ImageWriter::writeRgba8(const std::filesystem::path& path, int width, int height,
                               const std::vector<std::uint8_t>& pixels) {
    SYLVA_CHECK(width > 0 && height > 0 && pixels.size() == std::size_t(width) * height * 4);
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
    OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    // Our pixels have straight (unassociated) alpha, as PNG stores it: without this
    // OIIO takes them as premultiplied and divides on write.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    spec.attribute("Software", "Sylva");
    bool ok = output->open(temporary.string(), spec) &&
              output->write_image(OIIO::TypeDesc::UINT8, pixels.data());
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

Result<std::vector<std::uint8_t>> ImageWriter::readRgba8(const std::filesystem::path& path,
                                                         int& width, int& height) {
    // Keep alpha straight on reading too (OIIO premultiplies by default).
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path.string(), &config);
    if (!input) {
        return Error{path.string() + ": cannot read image: " + OIIO::geterror()};
    }
    const OIIO::ImageSpec& spec = input->spec();
    width = spec.width;
    height = spec.height;
    std::vector<std::uint8_t> pixels(std::size_t(width) * height * 4, 255);
    const int channels = std::min(spec.nchannels, 4);
    if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, pixels.data(), 4)) {
        return Error{path.string() + ": cannot read image: " + input->geterror()};
    }
    if (channels < 3) {  // grey: copy into G and B
        for (std::size_t i = 0; i < std::size_t(width) * height; ++i) {
            pixels[i * 4 + 1] = pixels[i * 4 + 2] = pixels[i * 4];
        }
    }
    return pixels;
}

}  // namespace sylva
