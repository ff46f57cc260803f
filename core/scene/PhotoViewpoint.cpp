#include "sylva/core/scene/PhotoViewpoint.h"

#include <cmath>
#include <cstdio>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/model/BlockReader.h"

namespace sylva {
namespace {

std::array<std::uint8_t, 4> bytes(const Color& colour) {
    auto byte = [](float v) {
        return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
    };
    return {byte(colour.r), byte(colour.g), byte(colour.b), byte(colour.a)};
}

}  // namespace

WirelineStyle wirelineStyleOf(const BlockReader& reader) {
    WirelineStyle style;
    style.width = reader.optionalNumber("line_width").value_or(3.0);
    style.silhouette = bytes(reader.color("wireline_color").value_or(Color{1, 0.1f, 0.1f, 1}));
    style.skyline = bytes(reader.color("skyline_color").value_or(Color{0, 0.85f, 1, 1}));
    return style;
}

namespace {

std::string format(const char* pattern, double value) {
    char text[64];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

std::string expandName(std::string pattern, const std::string& name) {
    for (std::size_t at = pattern.find("{name}"); at != std::string::npos;
         at = pattern.find("{name}", at + name.size())) {
        pattern.replace(at, 6, name);
    }
    return pattern;
}

// The control points: ECEF positions (a height is required: a surveyed point is 3D) and
// pixels.
Result<std::vector<ControlPoint>> readControlPoints(const BlockReader& reader) {
    std::vector<ControlPoint> points;
    const Value* value = reader.value("control_points");
    const ValueList* list = value ? value->get<ValueList>() : nullptr;
    if (list == nullptr) {
        return points;
    }
    const std::string what = "photo '" + reader.block().name + "': ";
    for (const Value& item : *list) {
        const ValueObject* object = item.get<ValueObject>();
        SYLVA_CHECK(object != nullptr);
        ControlPoint point;
        point.name =
            item.location.toString() + ": control point " + std::to_string(points.size() + 1);
        const GeoPosition* position = nullptr;
        const ValueList* pixel = nullptr;
        for (const auto& [key, field] : *object) {
            if (key == "position") {
                position = field.get<GeoPosition>();
            } else if (key == "pixel") {
                pixel = field.get<ValueList>();
            } else if (key == "name" && field.get<std::string>()) {
                point.name = item.location.toString() + ": control point '" +
                             *field.get<std::string>() + "'";
            }
        }
        SYLVA_CHECK(position != nullptr && pixel != nullptr);
        if (!position->height) {
            return Error{item.location.toString() + ": " + what +
                         "a control point needs its surveyed height: geo(lat, lon, height)"};
        }
        if (pixel->size() != 2) {
            return Error{item.location.toString() + ": " + what + "pixel must be [x, y]"};
        }
        point.position =
            Ellipsoid::toEcef({position->latitude, position->longitude, *position->height});
        point.pixel = {(*pixel)[0].get<Quantity>()->value, (*pixel)[1].get<Quantity>()->value};
        points.push_back(std::move(point));
    }
    return points;
}

Status readTime(const BlockReader& reader, PhotoViewpoint& photo) {
    if (reader.block().find("time") == nullptr) {
        return Status::success();
    }
    Result<DateTime> time = DateTime::parse(reader.string("time"));
    Result<double> instant = time ? time->unixSeconds() : Result<double>(time.error());
    if (!instant) {
        return Error{reader.where("time") + instant.error().message};
    }
    photo.time = time.value();
    photo.unixSeconds = instant.value();
    return Status::success();
}

}  // namespace

Result<PhotoViewpoint> PhotoViewpoint::fromBlock(const ProjectModel& model, const Block& block) {
    const BlockReader reader(block, SchemaRegistry::builtin().find("photo"));
    PhotoViewpoint photo;
    photo.block_ = &block;
    photo.name = block.name;
    photo.file = model.file.parent_path() / reader.string("file");
    photo.camera = reader.reference("camera").value_or("");
    photo.scenario = reader.reference("scenario").value_or("");
    photo.baseline = reader.reference("baseline").value_or("");
    photo.solveFocalLength = reader.boolean("solve_focal_length", false);
    photo.maxResidual = reader.optionalNumber("max_residual").value_or(3.0);
    photo.wireline = wirelineStyleOf(reader);
    photo.output = expandName(reader.string("output", "{name}"), block.name);
    photo.sheet = reader.boolean("sheet", false);
    photo.annotated = reader.boolean("annotated", false);
    const Block* camera = model.findCamera(photo.camera);
    if (photo.sheet && camera != nullptr &&
        (camera->find("output_size") == nullptr || camera->find("dpi") == nullptr)) {
        return Error{reader.where("sheet") +
                     "a viewpoint sheet needs the print format of camera '" + photo.camera +
                     "': set its output_size and dpi"};
    }
    if (Status time = readTime(reader, photo); !time) {
        return time.error();
    }
    Result<std::vector<ControlPoint>> points = readControlPoints(reader);
    if (!points) {
        return points.error();
    }
    photo.controlPoints = std::move(points.value());
    return photo;
}

Result<Photo> PhotoViewpoint::readPhoto() const {
    SYLVA_CHECK(block_ != nullptr);
    const BlockReader reader(*block_, SchemaRegistry::builtin().find("photo"));
    Result<Photo> photo = PhotoReader::read(file);
    if (!photo) {
        return Error{reader.where("file") + photo.error().message};
    }
    return photo;
}

double PhotoViewpoint::horizontalFovFrom35mm(double focalLength, int width, int height) {
    const double diagonalTangent = kFullFrameDiagonal / (2.0 * focalLength);
    return 2.0 * std::atan(diagonalTangent * width / std::hypot(double(width), double(height)));
}

double PhotoViewpoint::equivalent35mm(double horizontalFov, int width, int height) {
    const double diagonalTangent =
        std::tan(horizontalFov / 2.0) * std::hypot(double(width), double(height)) / width;
    return kFullFrameDiagonal / (2.0 * diagonalTangent);
}

Result<Camera> PhotoViewpoint::fitCamera(const Camera& viewpoint, const Block& cameraBlock,
                                         const Photo& photo) const {
    SYLVA_CHECK(block_ != nullptr);
    const BlockReader reader(*block_, SchemaRegistry::builtin().find("photo"));
    const int width = photo.image.width, height = photo.image.height;
    const std::string size = std::to_string(width) + " x " + std::to_string(height) + " pixels";
    if (viewpoint.projection != CameraProjection::Planar) {
        return Error{reader.where("camera") + "camera '" + this->camera + "' is " +
                     projectionName(viewpoint.projection) +
                     "; a photomontage needs a planar camera (a photograph)"};
    }
    if (viewpoint.print.valid()) {
        const double aspect = double(width) / height;
        const double printAspect = viewpoint.print.width / viewpoint.print.height;
        if (std::abs(aspect / printAspect - 1.0) > kAspectTolerance) {
            return Error{reader.where("file") + "the photograph is " + size + " (aspect " +
                         format("%.3f", aspect) + ") but camera '" + this->camera +
                         "' prints at aspect " + format("%.3f", printAspect) +
                         " (output_size); crop the photograph or change output_size"};
        }
    }
    const bool lensGiven = cameraBlock.find("fov") || cameraBlock.find("horizontal_fov") ||
                           cameraBlock.find("focal_length");
    Camera fitted = viewpoint;
    const std::optional<double> exif = photo.exif.focalLength35mm;
    if (exif && !lensGiven) {
        fitted.horizontalFov = horizontalFovFrom35mm(*exif / 1000.0, width, height);
    } else if (exif) {
        const Camera lens = viewpoint.fitted(width, height);
        const double horizontal =
            viewpoint.horizontalFov > 0.0
                ? viewpoint.horizontalFov
                : 2.0 * std::atan(std::tan(lens.verticalFov / 2.0) * width / height);
        const double ours = equivalent35mm(horizontal, width, height) * 1000.0;
        if (std::abs(ours / *exif - 1.0) > kLensTolerance) {
            return Error{reader.where("file") + "the photograph's EXIF FocalLengthIn35mmFilm is " +
                         format("%.1f", *exif) + " mm but camera '" + this->camera +
                         "' has a 35 mm equivalent of " + format("%.1f", ours) + " mm at " + size +
                         "; remove the camera's field of view to use the "
                         "EXIF lens, or correct it"};
        }
    }
    return fitted;
}

Result<std::optional<CameraMatch>> PhotoViewpoint::match(const Camera& guess,
                                                         const Photo& photo) const {
    SYLVA_CHECK(block_ != nullptr);
    const BlockReader reader(*block_, SchemaRegistry::builtin().find("photo"));
    if (controlPoints.empty()) {
        return std::optional<CameraMatch>();
    }
    const int needed = CameraMatcher::kMinimumPoints + (solveFocalLength ? 1 : 0);
    if (int(controlPoints.size()) < needed) {
        return Error{reader.where("control_points") + "camera matching needs at least " +
                     std::to_string(needed) + " control points, " +
                     std::to_string(controlPoints.size()) + " given"};
    }
    CameraMatchOptions options;
    options.solveFocalLength = solveFocalLength;
    options.maximumRms = maxResidual;
    Result<CameraMatch> solved =
        CameraMatcher::match(guess, photo.image.width, photo.image.height, controlPoints, options);
    if (!solved) {
        return Error{reader.where("control_points") + solved.error().message};
    }
    return std::optional<CameraMatch>(std::move(solved.value()));
}

}  // namespace sylva
