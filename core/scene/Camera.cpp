#include "sylva/core/scene/Camera.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "sylva/core/model/BlockReader.h"
#include "sylva/core/model/Schema.h"

namespace sylva {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMillimetre = 1e-3;

glm::dmat3 axesFromForward(const Geodetic& at, const glm::dvec3& forward, double roll) {
    const glm::dmat3 frame = Ellipsoid::localFrame(at.latitude, at.longitude);
    const glm::dvec3 localUp = frame[2];
    glm::dvec3 right = glm::cross(forward, localUp);
    if (glm::length(right) < 1e-9) {  // looking straight up or down: keep north up
        right = glm::cross(forward, frame[1]);
    }
    right = glm::normalize(right);
    glm::dvec3 up = glm::normalize(glm::cross(right, forward));
    const double c = std::cos(roll), s = std::sin(roll);
    const glm::dvec3 rolledRight = right * c + up * s;
    const glm::dvec3 rolledUp = up * c - right * s;
    return glm::dmat3(rolledRight, rolledUp, -forward);
}

struct NamedBody {
    const char* name;
    double width, height;  // millimetres
};
// Sensor sizes of common bodies (manufacturers' data sheets).
constexpr std::array<NamedBody, 5> kBodies{{{"full_frame", 36.0, 24.0},
                                            {"aps_c", 23.5, 15.6},
                                            {"aps_c_canon", 22.3, 14.9},
                                            {"micro_four_thirds", 17.3, 13.0},
                                            {"medium_format", 43.8, 32.9}}};

// The camera's height from eye_height (above the terrain), the position's third
// component (above the ellipsoid), or the default eye height of a viewpoint.
Status readHeight(const BlockReader& reader, const GeoPosition& position,
                  const Camera::TerrainHeight& terrainHeight, Camera& camera) {
    std::optional<double> eyeHeight = reader.optionalNumber("eye_height");
    if (!eyeHeight && position.height) {
        camera.geodetic.height = *position.height;
        return {};
    }
    const double eye = eyeHeight.value_or(Camera::kDefaultEyeHeight);
    if (!terrainHeight) {
        return Error{reader.where(eyeHeight ? "eye_height" : "position") +
                     "the camera needs a height: write geo(lat, lon, height) or set eye_height "
                     "(no terrain to stand on here)"};
    }
    Result<double> ground = terrainHeight(position.latitude, position.longitude);
    if (!ground) {
        return Error{reader.where(eyeHeight ? "eye_height" : "position") +
                     "cannot find the terrain height: " + ground.error().message};
    }
    camera.groundHeight = ground.value();
    camera.eyeHeight = eye;
    camera.geodetic.height = ground.value() + eye;
    return {};
}

// A list of two lengths or ratios (sensor, output_size, shift); nullopt when absent.
Result<std::optional<glm::dvec2>> readPair(const BlockReader& reader, std::string_view name) {
    const Value* value = reader.value(name);
    if (value == nullptr) {
        return std::optional<glm::dvec2>{};
    }
    const ValueList* list = value->get<ValueList>();
    if (list == nullptr || list->size() != 2 || !(*list)[0].get<Quantity>() ||
        !(*list)[1].get<Quantity>()) {
        return Error{reader.where(name) + "'" + std::string(name) + "' must be a pair [a, b]"};
    }
    return std::optional<glm::dvec2>{
        glm::dvec2((*list)[0].get<Quantity>()->value, (*list)[1].get<Quantity>()->value)};
}

// focal_length with sensor or body: the lens, and the horizontal field it gives.
Status readLens(const BlockReader& reader, Camera& camera) {
    Result<std::optional<glm::dvec2>> sensor = readPair(reader, "sensor");
    if (!sensor) {
        return sensor.error();
    }
    if (reader.value("body") != nullptr) {
        if (const Word* word = reader.value("body")->get<Word>()) {
            camera.lens.body = word->text;
        }
    }
    if (sensor.value() && !camera.lens.body.empty()) {
        return Error{reader.where("body") + "give either 'sensor' or 'body', not both"};
    }
    glm::dvec2 size(36.0 * kMillimetre, 24.0 * kMillimetre);  // 35 mm equivalent
    if (sensor.value()) {
        size = *sensor.value();
        if (!(size.x > 0.0) || !(size.y > 0.0)) {
            return Error{reader.where("sensor") +
                         "the sensor must have a positive width and "
                         "height (got a sensor of zero size)"};
        }
    }
    for (const NamedBody& named : kBodies) {
        if (camera.lens.body == named.name) {
            size = glm::dvec2(named.width, named.height) * kMillimetre;
        }
    }
    if (camera.lens.body.empty() && !sensor.value()) {
        camera.lens.body = "full_frame";
    }
    camera.lens.focalLength = reader.optionalNumber("focal_length").value_or(0.0);
    camera.lens.sensorWidth = size.x;
    camera.lens.sensorHeight = size.y;
    camera.horizontalFov = 2.0 * std::atan(size.x / (2.0 * camera.lens.focalLength));
    return {};
}

// fov (vertical), horizontal_fov or focal_length: at most one of them.
Status readField(const BlockReader& reader, Camera& camera) {
    const char* given = nullptr;
    for (const char* name : {"fov", "horizontal_fov", "focal_length"}) {
        if (reader.block().find(name) == nullptr) {
            continue;
        }
        if (given != nullptr) {
            return Error{reader.where(name) +
                         "give one of 'fov', 'horizontal_fov' and "
                         "'focal_length', not '" +
                         std::string(given) + "' and '" + name + "'"};
        }
        given = name;
    }
    if ((reader.block().find("sensor") || reader.block().find("body")) &&
        (given == nullptr || std::string_view(given) != "focal_length")) {
        return Error{reader.where(reader.block().find("sensor") ? "sensor" : "body") +
                     "a sensor or body needs 'focal_length'"};
    }
    camera.verticalFov = reader.optionalNumber("fov").value_or(Camera::kDefaultVerticalFov);
    camera.horizontalFov = reader.optionalNumber("horizontal_fov").value_or(0.0);
    if (given != nullptr && std::string_view(given) == "focal_length") {
        return readLens(reader, camera);
    }
    return {};
}

// projection, shift and their constraints.
Status readProjection(const BlockReader& reader, Camera& camera) {
    const Value* projection = reader.value("projection");
    const std::string kind =
        projection && projection->get<Word>() ? projection->get<Word>()->text : "planar";
    camera.projection = kind == "cylindrical"       ? CameraProjection::Cylindrical
                        : kind == "equirectangular" ? CameraProjection::Equirectangular
                                                    : CameraProjection::Planar;
    Result<std::optional<glm::dvec2>> shift = readPair(reader, "shift");
    if (!shift) {
        return shift.error();
    }
    camera.lensShift = shift.value().value_or(glm::dvec2(0.0));
    if (camera.projection == CameraProjection::Planar) {
        return {};
    }
    for (const char* name : {"pitch", "roll", "look_at"}) {
        const bool tilted = std::string_view(name) == "look_at"
                                ? reader.block().find(name) != nullptr
                                : reader.optionalNumber(name).value_or(0.0) != 0.0;
        if (tilted) {
            return Error{reader.where(name) + "a panorama's axis is the local vertical: '" +
                         std::string(name) +
                         "' needs projection = planar (move the horizon with shift = [0, y])"};
        }
    }
    if (camera.projection == CameraProjection::Equirectangular) {
        if (reader.block().find("shift") || reader.block().find("fov") ||
            reader.block().find("horizontal_fov") || reader.block().find("focal_length")) {
            return Error{reader.where() +
                         "an equirectangular image always covers 360° × 180°: "
                         "no field of view, focal length or shift"};
        }
        camera.horizontalFov = 2.0 * kPi;
        return {};
    }
    if (!(camera.horizontalFov > 0.0) || camera.horizontalFov > 2.0 * kPi + 1e-12) {
        return Error{reader.where("projection") +
                     "a cylindrical panorama needs 'horizontal_fov' (up to 360°) or "
                     "'focal_length'"};
    }
    if (camera.lensShift.x != 0.0) {
        return Error{reader.where("shift") +
                     "a cylindrical panorama shifts vertically only: shift = [0, y]"};
    }
    return {};
}

Status readPrint(const BlockReader& reader, Camera& camera) {
    Result<std::optional<glm::dvec2>> size = readPair(reader, "output_size");
    if (!size) {
        return size.error();
    }
    const std::optional<double> dpi = reader.optionalNumber("dpi");
    if (!size.value() && !dpi) {
        return {};
    }
    if (!size.value() || !dpi) {
        return Error{reader.where(size.value() ? "output_size" : "dpi") +
                     "a print format needs both 'output_size' and 'dpi'"};
    }
    camera.print = {size.value()->x, size.value()->y, *dpi};
    if (!(camera.print.width > 0) || !(camera.print.height > 0) || camera.print.pixelsWide() < 1 ||
        camera.print.pixelsHigh() < 1 || camera.print.pixelsWide() > 16384 ||
        camera.print.pixelsHigh() > 16384) {
        return Error{reader.where("output_size") + "the print gives " +
                     std::to_string(camera.print.pixelsWide()) + "x" +
                     std::to_string(camera.print.pixelsHigh()) +
                     " pixels, outside 1..16384 per side"};
    }
    return {};
}

}  // namespace

const char* projectionName(CameraProjection projection) {
    switch (projection) {
        case CameraProjection::Planar:
            return "planar";
        case CameraProjection::Cylindrical:
            return "cylindrical";
        case CameraProjection::Equirectangular:
            return "equirectangular";
    }
    return "planar";
}

Camera Camera::fitted(int width, int height) const {
    SYLVA_CHECK(width > 0 && height > 0);
    Camera camera = *this;
    switch (projection) {
        case CameraProjection::Planar:
            if (horizontalFov > 0.0) {
                camera.verticalFov =
                    2.0 * std::atan(std::tan(horizontalFov / 2) * double(height) / width);
            }
            break;
        case CameraProjection::Cylindrical:
            camera.verticalFov = 2.0 * std::atan(double(height) * horizontalFov / (2.0 * width));
            break;
        case CameraProjection::Equirectangular:
            camera.verticalFov = kPi;
            break;
    }
    return camera;
}

double Camera::heading() const {
    const glm::dmat3 frame = Ellipsoid::localFrame(geodetic.latitude, geodetic.longitude);
    const glm::dvec3 forward = -axes[2];
    return std::atan2(glm::dot(forward, frame[0]), glm::dot(forward, frame[1]));
}

double Camera::pitch() const {
    const glm::dmat3 frame = Ellipsoid::localFrame(geodetic.latitude, geodetic.longitude);
    return std::asin(std::clamp(glm::dot(-axes[2], frame[2]), -1.0, 1.0));
}

glm::dmat3 Camera::axesFromAngles(const Geodetic& at, double heading, double pitch, double roll) {
    const glm::dmat3 frame = Ellipsoid::localFrame(at.latitude, at.longitude);
    const glm::dvec3 forward =
        std::cos(pitch) * (std::sin(heading) * frame[0] + std::cos(heading) * frame[1]) +
        std::sin(pitch) * frame[2];
    return axesFromForward(at, glm::normalize(forward), roll);
}

glm::dmat3 Camera::axesLookingAt(const Geodetic& from, const glm::dvec3& target) {
    const glm::dvec3 position = Ellipsoid::toEcef(from);
    return axesFromForward(from, glm::normalize(target - position), 0.0);
}

Result<Camera> Camera::fromBlock(const Block& block, const TerrainHeight& terrainHeight) {
    BlockReader reader(block, SchemaRegistry::builtin().find("camera"));
    const std::optional<GeoPosition> position = reader.geo("position");
    if (!position) {
        return Error{reader.where() + "missing 'position'"};
    }
    Camera camera;
    camera.geodetic.latitude = position->latitude;
    camera.geodetic.longitude = position->longitude;
    if (Status height = readHeight(reader, *position, terrainHeight, camera); !height) {
        return height.error();
    }
    camera.position = Ellipsoid::toEcef(camera.geodetic);
    for (Status (*read)(const BlockReader&, Camera&) : {readField, readProjection, readPrint}) {
        if (Status status = read(reader, camera); !status) {
            return status.error();
        }
    }
    if (std::optional<GeoPosition> target = reader.geo("look_at")) {
        Geodetic t{target->latitude, target->longitude, target->height.value_or(0.0)};
        if (!target->height && terrainHeight) {
            if (Result<double> ground = terrainHeight(t.latitude, t.longitude)) {
                t.height = std::max(ground.value(), 0.0);
            }
        }
        const glm::dvec3 targetEcef = Ellipsoid::toEcef(t);
        if (glm::length(targetEcef - camera.position) < 1e-3) {
            return Error{reader.where("look_at") + "look_at is the camera position itself"};
        }
        camera.axes = axesLookingAt(camera.geodetic, targetEcef);
    } else {
        camera.axes =
            axesFromAngles(camera.geodetic, reader.optionalNumber("heading").value_or(0.0),
                           reader.optionalNumber("pitch").value_or(0.0),
                           reader.optionalNumber("roll").value_or(0.0));
    }
    return camera;
}

}  // namespace sylva
