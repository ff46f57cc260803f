#include "sylva/core/scene/CameraPath.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/model/BlockReader.h"

namespace sylva {
namespace {

glm::dvec3 unitVector(double latitude, double longitude) {
    return {std::cos(latitude) * std::cos(longitude), std::cos(latitude) * std::sin(longitude),
            std::sin(latitude)};
}

// Spherical linear interpolation of unit vectors (great-circle arc).
glm::dvec3 slerpUnit(const glm::dvec3& a, const glm::dvec3& b, double s) {
    const double cosine = std::clamp(glm::dot(a, b), -1.0, 1.0);
    const double angle = std::acos(cosine);
    if (angle < 1e-12) {
        return a;
    }
    const double sine = std::sin(angle);
    return (std::sin((1 - s) * angle) / sine) * a + (std::sin(s * angle) / sine) * b;
}

// Cubic Hermite on [t0, t1] with tangents m0, m1 (per second).
template <typename T>
T hermite(const T& p0, const T& p1, const T& m0, const T& m1, double t0, double t1, double t) {
    const double h = t1 - t0;
    const double s = (t - t0) / h;
    const double s2 = s * s;
    const double s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * h * m0 + (-2 * s3 + 3 * s2) * p1 +
           (s3 - s2) * h * m1;
}

// Orientation of `axes` relative to the local east/north/up frame at `at`.
glm::dquat localOrientation(const Geodetic& at, const glm::dmat3& axes) {
    const glm::dmat3 frame = Ellipsoid::localFrame(at.latitude, at.longitude);
    return glm::normalize(glm::quat_cast(glm::transpose(frame) * axes));
}

std::optional<double> quantityOf(const Value& value) {
    if (const Quantity* quantity = value.get<Quantity>()) {
        return quantity->value;
    }
    return std::nullopt;
}

}  // namespace

CameraPath::CameraPath(std::string name, std::vector<CameraPathKey> keys,
                       PathInterpolation interpolation, double framesPerSecond, double verticalFov)
    : name_(std::move(name)),
      keys_(std::move(keys)),
      interpolation_(interpolation),
      framesPerSecond_(framesPerSecond),
      verticalFov_(verticalFov) {
    SYLVA_CHECK(keys_.size() >= 2 && framesPerSecond_ > 0);
    heightsAboveTerrain_ = std::all_of(keys_.begin(), keys_.end(), [](const CameraPathKey& key) {
        return key.eyeHeight.has_value();
    });
}

Result<CameraPath> CameraPath::fromBlock(const Block& block) {
    BlockReader reader(block, SchemaRegistry::builtin().find("path"));
    const Value* keysValue = reader.value("keys");
    const ValueList* list = keysValue ? keysValue->get<ValueList>() : nullptr;
    if (!list || list->size() < 2) {
        return Error{reader.where("keys") + "a path needs at least two keys"};
    }
    std::vector<CameraPathKey> keys;
    for (const Value& item : *list) {
        const ValueObject* object = item.get<ValueObject>();
        SYLVA_CHECK(object != nullptr);
        CameraPathKey key;
        key.location = item.location;
        for (const auto& [field, value] : *object) {
            if (field == "at") {
                key.time = quantityOf(value).value_or(0.0);
            } else if (field == "position") {
                const GeoPosition* position = value.get<GeoPosition>();
                SYLVA_CHECK(position != nullptr);
                key.latitude = position->latitude;
                key.longitude = position->longitude;
                key.height = position->height;
            } else if (field == "eye_height") {
                key.eyeHeight = quantityOf(value);
            } else if (field == "look_at") {
                const GeoPosition* target = value.get<GeoPosition>();
                SYLVA_CHECK(target != nullptr);
                key.lookAt =
                    Geodetic{target->latitude, target->longitude,
                             target->height.value_or(std::numeric_limits<double>::quiet_NaN())};
            } else if (field == "heading") {
                key.heading = quantityOf(value).value_or(0.0);
            } else if (field == "pitch") {
                key.pitch = quantityOf(value).value_or(0.0);
            } else if (field == "roll") {
                key.roll = quantityOf(value).value_or(0.0);
            }
        }
        if (!keys.empty() && key.time <= keys.back().time) {
            return Error{key.location.toString() + ": path '" + block.name +
                         "': key times must ascend (this key is not after the one before)"};
        }
        if (!key.height && !key.eyeHeight) {
            return Error{
                key.location.toString() + ": path '" + block.name +
                "': the key needs a height: write geo(lat, lon, height) or set eye_height"};
        }
        keys.push_back(key);
    }
    PathInterpolation interpolation = PathInterpolation::CatmullRom;
    if (const Value* mode = reader.value("interpolate")) {
        if (const Word* word = mode->get<Word>()) {
            interpolation = word->text == "linear"
                                ? PathInterpolation::Linear
                                : (word->text == "step" ? PathInterpolation::Step
                                                        : PathInterpolation::CatmullRom);
        }
    }
    const double fps = reader.optionalNumber("fps").value_or(25.0);
    const double fov = reader.optionalNumber("fov").value_or(60.0 * std::numbers::pi / 180.0);
    return CameraPath(block.name, std::move(keys), interpolation, fps, fov);
}

int CameraPath::frameCount() const {
    // A tiny epsilon keeps the last frame when duration * fps is a whole number.
    return static_cast<int>(std::floor(duration() * framesPerSecond_ + 1e-9)) + 1;
}

Result<Camera> CameraPath::sample(double time, const Camera::TerrainHeight& terrainHeight) const {
    time = std::clamp(time, keys_.front().time, keys_.back().time);
    std::size_t segment = 0;
    while (segment + 2 < keys_.size() && time >= keys_[segment + 1].time) {
        ++segment;
    }
    const CameraPathKey& a = keys_[segment];
    const CameraPathKey& b = keys_[segment + 1];
    const double s = std::clamp((time - a.time) / (b.time - a.time), 0.0, 1.0);

    Result<Position> position = interpolatePosition(segment, s, time, terrainHeight);
    if (!position) {
        return position.error();
    }
    Camera camera;
    camera.verticalFov = verticalFov_;
    const glm::dvec3& direction = position.value().direction;
    camera.geodetic.latitude = std::asin(std::clamp(direction.z, -1.0, 1.0));
    camera.geodetic.longitude = std::atan2(direction.y, direction.x);
    if (Status placed = placeHeight(camera, position.value().height, time, terrainHeight);
        !placed) {
        return placed.error();
    }
    camera.position = Ellipsoid::toEcef(camera.geodetic);

    const bool lookAtBoth = a.lookAt && b.lookAt && interpolation_ != PathInterpolation::Step;
    if (lookAtBoth) {
        if (Status looking = lookAtInterpolatedTarget(camera, a, b, s, terrainHeight); !looking) {
            return looking.error();
        }
        return camera;
    }
    camera.axes = interpolatedAxes(camera.geodetic, a, b, s);
    return camera;
}

Result<double> CameraPath::keyHeight(const CameraPathKey& key,
                                     const Camera::TerrainHeight& terrainHeight) const {
    if (heightsAboveTerrain_) {
        return *key.eyeHeight;
    }
    if (key.eyeHeight) {
        if (!terrainHeight) {
            return Error{"path '" + name_ + "': no terrain to measure eye_height from"};
        }
        Result<double> ground = terrainHeight(key.latitude, key.longitude);
        if (!ground) {
            return ground.error();
        }
        return ground.value() + *key.eyeHeight;
    }
    return *key.height;
}

Result<CameraPath::Position> CameraPath::interpolatePosition(
    std::size_t segment, double s, double time, const Camera::TerrainHeight& terrainHeight) const {
    const CameraPathKey& a = keys_[segment];
    const CameraPathKey& b = keys_[segment + 1];
    Position position;
    if (interpolation_ == PathInterpolation::Step) {
        const CameraPathKey& key = s < 1.0 ? a : b;
        position.direction = unitVector(key.latitude, key.longitude);
        Result<double> h = keyHeight(key, terrainHeight);
        if (!h) {
            return h.error();
        }
        position.height = h.value();
        return position;
    }
    if (interpolation_ == PathInterpolation::Linear) {
        position.direction =
            slerpUnit(unitVector(a.latitude, a.longitude), unitVector(b.latitude, b.longitude), s);
        Result<double> ha = keyHeight(a, terrainHeight);
        Result<double> hb = keyHeight(b, terrainHeight);
        if (!ha || !hb) {
            return !ha ? ha.error() : hb.error();
        }
        position.height = ha.value() + (hb.value() - ha.value()) * s;
        return position;
    }
    return catmullRom(segment, time, terrainHeight);
}

Result<CameraPath::Position> CameraPath::catmullRom(
    std::size_t segment, double time, const Camera::TerrainHeight& terrainHeight) const {
    // Catmull–Rom tangents from the neighbouring keys (one-sided at the ends).
    const std::size_t i0 = segment == 0 ? 0 : segment - 1;
    const std::size_t i3 = std::min(segment + 2, keys_.size() - 1);
    const CameraPathKey* k[4] = {&keys_[i0], &keys_[segment], &keys_[segment + 1], &keys_[i3]};
    glm::dvec3 p[4];
    double h[4];
    for (int i = 0; i < 4; ++i) {
        p[i] = unitVector(k[i]->latitude, k[i]->longitude);
        Result<double> keyH = keyHeight(*k[i], terrainHeight);
        if (!keyH) {
            return keyH.error();
        }
        h[i] = keyH.value();
    }
    // Neighbours on the far side of the globe from this segment would bend the
    // tangent through the Earth; projecting onto the tangent plane keeps it on the
    // surface.
    auto tangent = [&](int before, int after, const glm::dvec3& at) {
        const double dt = k[after]->time - k[before]->time;
        glm::dvec3 m = (p[after] - p[before]) / dt;
        return m - glm::dot(m, at) * at;
    };
    const glm::dvec3 m1 = tangent(0, 2, p[1]);
    const glm::dvec3 m2 = tangent(1, 3, p[2]);
    Position position;
    position.direction = glm::normalize(hermite(p[1], p[2], m1, m2, k[1]->time, k[2]->time, time));
    const double dh1 = (h[2] - h[0]) / (k[2]->time - k[0]->time);
    const double dh2 = (h[3] - h[1]) / (k[3]->time - k[1]->time);
    position.height = hermite(h[1], h[2], dh1, dh2, k[1]->time, k[2]->time, time);
    return position;
}

Status CameraPath::placeHeight(Camera& camera, double height, double time,
                               const Camera::TerrainHeight& terrainHeight) const {
    Result<double> ground = terrainHeight
                                ? terrainHeight(camera.geodetic.latitude, camera.geodetic.longitude)
                                : Result<double>(Error{"no terrain"});
    if (heightsAboveTerrain_) {
        if (!ground) {
            return Error{"path '" + name_ +
                         "': cannot find the terrain height: " + ground.error().message};
        }
        height += ground.value();
    } else if (ground && height < ground.value()) {
        char text[160];
        std::snprintf(text, sizeof text,
                      "path '%s': at %.2f s the camera is %.1f m below the terrain", name_.c_str(),
                      time, ground.value() - height);
        return Error{text};
    }
    camera.geodetic.height = height;
    return {};
}

Status CameraPath::lookAtInterpolatedTarget(Camera& camera, const CameraPathKey& a,
                                            const CameraPathKey& b, double s,
                                            const Camera::TerrainHeight& terrainHeight) const {
    auto targetHeight = [&](const Geodetic& target) {
        if (!std::isnan(target.height)) {
            return target.height;
        }
        Result<double> targetGround = terrainHeight
                                          ? terrainHeight(target.latitude, target.longitude)
                                          : Result<double>(Error{"no terrain"});
        return targetGround ? std::max(targetGround.value(), 0.0) : 0.0;
    };
    const glm::dvec3 ta = unitVector(a.lookAt->latitude, a.lookAt->longitude);
    const glm::dvec3 tb = unitVector(b.lookAt->latitude, b.lookAt->longitude);
    const glm::dvec3 t = slerpUnit(ta, tb, s);
    Geodetic target{std::asin(std::clamp(t.z, -1.0, 1.0)), std::atan2(t.y, t.x), 0.0};
    target.height =
        targetHeight(*a.lookAt) + (targetHeight(*b.lookAt) - targetHeight(*a.lookAt)) * s;
    const glm::dvec3 targetEcef = Ellipsoid::toEcef(target);
    if (glm::length(targetEcef - camera.position) < 1e-3) {
        return Error{"path '" + name_ + "': the camera reaches the point it looks at"};
    }
    camera.axes = Camera::axesLookingAt(camera.geodetic, targetEcef);
    return {};
}

glm::dmat3 CameraPath::interpolatedAxes(const Geodetic& at, const CameraPathKey& a,
                                        const CameraPathKey& b, double s) const {
    // Each key's orientation relative to its own local frame, slerped, then placed in
    // the local frame of the interpolated position.
    auto keyOrientation = [&](const CameraPathKey& key) {
        Geodetic keyAt{key.latitude, key.longitude, key.height.value_or(0.0)};
        glm::dmat3 axes;
        if (key.lookAt) {
            Geodetic target = *key.lookAt;
            if (std::isnan(target.height)) {
                target.height = 0.0;
            }
            axes = Camera::axesLookingAt(keyAt, Ellipsoid::toEcef(target));
        } else {
            axes = Camera::axesFromAngles(keyAt, key.heading, key.pitch, key.roll);
        }
        return localOrientation(keyAt, axes);
    };
    const glm::dquat qa = keyOrientation(a);
    const glm::dquat qb = keyOrientation(b);
    const glm::dquat q =
        interpolation_ == PathInterpolation::Step ? (s < 1.0 ? qa : qb) : glm::slerp(qa, qb, s);
    return Ellipsoid::localFrame(at.latitude, at.longitude) * glm::mat3_cast(q);
}

}  // namespace sylva
