// PhotoReader: reads a baseline photograph for a photomontage (issue 18) through
// OpenImageIO: the pixels as 8-bit sRGB RGBA (grey and RGB photographs are expanded,
// alpha opaque; 16-bit and float files are converted by OIIO) and the EXIF fields camera
// matching starts from (CIPA DC-008 tags, as OIIO names them): FocalLengthIn35mmFilm,
// FocalLength, GPS position and image direction, DateTimeOriginal. The EXIF Orientation
// tag is reported, not applied: the pixels are as stored.
//
// Fails (Result error: the path and the reason) when the file is missing, not an image
// OIIO can read, empty, or larger than kMaxPixels.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "sylva/core/base/Result.h"
#include "sylva/core/image/Image.h"

namespace sylva {

struct PhotoExif {
    std::optional<double> focalLength35mm;  // millimetres (FocalLengthIn35mmFilm)
    std::optional<double> focalLength;      // millimetres of the real lens (FocalLength)
    std::optional<double> latitude;         // degrees, north positive (GPS)
    std::optional<double> longitude;        // degrees, east positive (GPS)
    std::optional<double> altitude;         // metres (GPSAltitude, sign from its ref)
    std::optional<double> direction;        // degrees clockwise from north (GPSImgDirection)
    std::string dateTimeOriginal;           // "YYYY:MM:DD HH:MM:SS" as written, or empty
    int orientation = 1;                    // EXIF Orientation (1: as stored)
};

struct Photo {
    RgbaImage image;
    PhotoExif exif;
};

class PhotoReader {
public:
    static constexpr long long kMaxPixels = 400'000'000;

    static Result<Photo> read(const std::filesystem::path& path);
};

}  // namespace sylva
