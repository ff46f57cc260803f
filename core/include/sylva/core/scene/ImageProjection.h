// ImageProjection: the exact map between the pixels of a camera's image and directions,
// for the planar (pinhole), cylindrical and equirectangular projections. It is the CPU
// model of what the renderer draws (tests predict a surveyed point's pixel with it),
// what the panorama resampler looks up per pixel, and what camera matching fits.
//
// Pixel coordinates: x right, y down, (0, 0) the top-left corner of the image, pixel
// (i, j) covers [i, i + 1) × [j, j + 1) (its centre is i + 0.5, j + 0.5). View space:
// x right, y up, the camera looks along −z (Camera::axes maps it to ECEF).
//   planar:          f = (height / 2) / tan(verticalFov / 2) pixels; principal point
//                    (w/2 − shift.x·w, h/2 + shift.y·h); pixel = pp + f·(x, −y) / −z.
//   cylindrical:     r = width / horizontalFov pixels per radian; column angle
//                    α = (px − w/2) / r (the bearing is heading + α, exactly);
//                    tan(elevation) = (h/2 + shift.y·h − py) / r.
//   equirectangular: α = (px − w/2) · 2π / w, elevation = (h/2 − py) · π / h.
#pragma once

#include <optional>

#include <glm/glm.hpp>

#include "sylva/core/scene/Camera.h"

namespace sylva {

class ImageProjection {
public:
    // For `camera` (its fitted() field is used) rendered at width × height pixels.
    ImageProjection(const Camera& camera, int width, int height);

    int width() const { return width_; }
    int height() const { return height_; }
    CameraProjection kind() const { return kind_; }
    // Fields of view of the image, radians (planar: of the whole tangent window).
    double horizontalFov() const;
    double verticalFov() const;
    // Planar focal length, or cylinder radius, in pixels (equirectangular: px per radian
    // across).
    double focalPixels() const { return focal_; }

    // Unit view-space direction through pixel position `pixel`.
    glm::dvec3 viewDirection(const glm::dvec2& pixel) const;
    // The pixel position of view-space direction `direction` (need not be unit);
    // nullopt for directions the image cannot show (behind a planar camera, straight up
    // or down in a cylinder). The position may lie outside the image.
    std::optional<glm::dvec2> pixelOf(const glm::dvec3& direction) const;

    // The same for ECEF: the direction through a pixel, and the pixel of a point.
    glm::dvec3 ecefDirection(const glm::dvec2& pixel) const;
    std::optional<glm::dvec2> pixelOfPoint(const glm::dvec3& ecef) const;

    // The distance (metres) at which a print of width `printWidth` (metres) shows every
    // direction at its true angle: planar d = w / (2 tan(HFOV / 2)), cylindrical and
    // equirectangular d = w / HFOV (HFOV in radians).
    double viewingDistance(double printWidth) const;

private:
    CameraProjection kind_;
    int width_, height_;
    glm::dvec2 principal_;  // pixel of the optical axis (planar), or of α = 0, tan el = 0
    double focal_;
    glm::dvec3 position_;
    glm::dmat3 axes_;
};

}  // namespace sylva
