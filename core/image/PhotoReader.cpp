#include "sylva/core/image/PhotoReader.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <system_error>

namespace sylva {
namespace {

std::optional<double> floatAttribute(const OIIO::ImageSpec& spec, const char* name) {
    const OIIO::ParamValue* value = spec.find_attribute(name);
    if (value == nullptr) {
        return std::nullopt;
    }
    const double number = value->get_float();
    return std::isfinite(number) && number > 0.0 ? std::optional(number) : std::nullopt;
}

// A GPS coordinate stored as degrees, minutes, seconds (three rationals) with its
// hemisphere reference ("N"/"S", "E"/"W").
std::optional<double> gpsAngle(const OIIO::ImageSpec& spec, const char* name, const char* reference,
                               char negative) {
    const OIIO::ParamValue* value = spec.find_attribute(name);
    if (value == nullptr || value->type().numelements() * value->nvalues() < 3) {
        return std::nullopt;
    }
    const float* parts = static_cast<const float*>(value->data());
    if (value->type().basetype != OIIO::TypeDesc::FLOAT) {
        return std::nullopt;
    }
    double angle = parts[0] + parts[1] / 60.0 + parts[2] / 3600.0;
    const std::string hemisphere = spec.get_string_attribute(reference);
    if (!hemisphere.empty() && hemisphere[0] == negative) {
        angle = -angle;
    }
    return angle;
}

PhotoExif readExif(const OIIO::ImageSpec& spec) {
    PhotoExif exif;
    exif.focalLength35mm = floatAttribute(spec, "Exif:FocalLengthIn35mmFilm");
    exif.focalLength = floatAttribute(spec, "Exif:FocalLength");
    exif.latitude = gpsAngle(spec, "GPS:Latitude", "GPS:LatitudeRef", 'S');
    exif.longitude = gpsAngle(spec, "GPS:Longitude", "GPS:LongitudeRef", 'W');
    if (const OIIO::ParamValue* altitude = spec.find_attribute("GPS:Altitude")) {
        const double metres = altitude->get_float();
        exif.altitude = spec.get_int_attribute("GPS:AltitudeRef", 0) == 1 ? -metres : metres;
    }
    if (const OIIO::ParamValue* direction = spec.find_attribute("GPS:ImgDirection")) {
        exif.direction = direction->get_float();
    }
    exif.dateTimeOriginal = spec.get_string_attribute("Exif:DateTimeOriginal");
    exif.orientation = spec.get_int_attribute("Orientation", 1);
    return exif;
}

}  // namespace

Result<Photo> PhotoReader::read(const std::filesystem::path& path) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) {
        return Error{path.string() + ": the photograph does not exist"};
    }
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path.string());
    if (!input) {
        std::string reason = OIIO::geterror();
        return Error{path.string() + ": not a readable image" +
                     (reason.empty() ? std::string() : " (" + reason + ")")};
    }
    const OIIO::ImageSpec& spec = input->spec();
    const long long pixelCount = static_cast<long long>(spec.width) * spec.height;
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
        return Error{path.string() + ": the image is empty"};
    }
    if (pixelCount > kMaxPixels) {
        return Error{path.string() + ": the image has " + std::to_string(pixelCount) +
                     " pixels, more than " + std::to_string(kMaxPixels)};
    }
    Photo photo;
    photo.exif = readExif(spec);
    const int channels = spec.nchannels;
    std::vector<std::uint8_t> stored(static_cast<std::size_t>(pixelCount) * channels);
    if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, stored.data())) {
        return Error{path.string() + ": cannot read the pixels (" + input->geterror() + ")"};
    }
    photo.image = RgbaImage(spec.width, spec.height);
    for (long long i = 0; i < pixelCount; ++i) {
        const std::uint8_t* in = stored.data() + i * channels;
        std::uint8_t* out = photo.image.pixels.data() + i * 4;
        for (int c = 0; c < 3; ++c) {
            out[c] = in[channels >= 3 ? c : 0];  // grey expands to all three
        }
    }
    return photo;
}

}  // namespace sylva
