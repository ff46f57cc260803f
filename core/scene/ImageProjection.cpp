#include "sylva/core/scene/ImageProjection.h"

#include <cmath>
#include <numbers>

namespace sylva {
namespace {
constexpr double kPi = std::numbers::pi;
}

ImageProjection::ImageProjection(const Camera& camera, int width, int height)
    : kind_(camera.projection),
      width_(width),
      height_(height),
      position_(camera.position),
      axes_(camera.axes) {
    SYLVA_CHECK(width > 0 && height > 0);
    const Camera fitted = camera.fitted(width, height);
    switch (kind_) {
        case CameraProjection::Planar:
            focal_ = (height / 2.0) / std::tan(fitted.verticalFov / 2);
            principal_ = glm::dvec2(width / 2.0 - camera.lensShift.x * width,
                                    height / 2.0 + camera.lensShift.y * height);
            break;
        case CameraProjection::Cylindrical:
            focal_ = width / camera.horizontalFov;
            principal_ = glm::dvec2(width / 2.0, height / 2.0 + camera.lensShift.y * height);
            break;
        case CameraProjection::Equirectangular:
            focal_ = width / (2.0 * kPi);
            principal_ = glm::dvec2(width / 2.0, height / 2.0);
            break;
    }
}

double ImageProjection::horizontalFov() const {
    switch (kind_) {
        case CameraProjection::Planar:
            return 2.0 * std::atan(width_ / (2.0 * focal_));
        case CameraProjection::Cylindrical:
            return width_ / focal_;
        case CameraProjection::Equirectangular:
            return 2.0 * kPi;
    }
    return 0.0;
}

double ImageProjection::verticalFov() const {
    switch (kind_) {
        case CameraProjection::Planar:
        case CameraProjection::Cylindrical:
            return 2.0 * std::atan(height_ / (2.0 * focal_));
        case CameraProjection::Equirectangular:
            return kPi;
    }
    return 0.0;
}

glm::dvec3 ImageProjection::viewDirection(const glm::dvec2& pixel) const {
    const double u = pixel.x - principal_.x;
    const double v = principal_.y - pixel.y;
    switch (kind_) {
        case CameraProjection::Planar:
            return glm::normalize(glm::dvec3(u / focal_, v / focal_, -1.0));
        case CameraProjection::Cylindrical: {
            const double angle = u / focal_;
            return glm::normalize(glm::dvec3(std::sin(angle), v / focal_, -std::cos(angle)));
        }
        case CameraProjection::Equirectangular: {
            const double angle = u * 2.0 * kPi / width_;
            const double elevation = v * kPi / height_;
            return glm::dvec3(std::cos(elevation) * std::sin(angle), std::sin(elevation),
                              -std::cos(elevation) * std::cos(angle));
        }
    }
    return glm::dvec3(0, 0, -1);
}

std::optional<glm::dvec2> ImageProjection::pixelOf(const glm::dvec3& direction) const {
    switch (kind_) {
        case CameraProjection::Planar: {
            if (!(direction.z < 0.0)) {
                return std::nullopt;
            }
            const double depth = -direction.z;
            return glm::dvec2(principal_.x + focal_ * direction.x / depth,
                              principal_.y - focal_ * direction.y / depth);
        }
        case CameraProjection::Cylindrical: {
            const double horizontal = std::hypot(direction.x, direction.z);
            if (!(horizontal > 0.0)) {
                return std::nullopt;
            }
            const double angle = std::atan2(direction.x, -direction.z);
            return glm::dvec2(principal_.x + focal_ * angle,
                              principal_.y - focal_ * direction.y / horizontal);
        }
        case CameraProjection::Equirectangular: {
            const double angle = std::atan2(direction.x, -direction.z);
            const double elevation = std::atan2(direction.y, std::hypot(direction.x, direction.z));
            return glm::dvec2(principal_.x + angle * width_ / (2.0 * kPi),
                              principal_.y - elevation * height_ / kPi);
        }
    }
    return std::nullopt;
}

glm::dvec3 ImageProjection::ecefDirection(const glm::dvec2& pixel) const {
    return axes_ * viewDirection(pixel);
}

std::optional<glm::dvec2> ImageProjection::pixelOfPoint(const glm::dvec3& ecef) const {
    return pixelOf(glm::transpose(axes_) * (ecef - position_));
}

double ImageProjection::viewingDistance(double printWidth) const {
    if (kind_ == CameraProjection::Planar) {
        return printWidth / (2.0 * std::tan(horizontalFov() / 2));
    }
    return printWidth / horizontalFov();
}

}  // namespace sylva
