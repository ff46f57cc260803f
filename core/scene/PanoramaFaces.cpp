#include "sylva/core/scene/PanoramaFaces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "sylva/core/base/WorkerPool.h"
#include "sylva/core/image/ColorSpace.h"
#include "sylva/core/scene/ImageProjection.h"

namespace sylva {
namespace {

constexpr double kPi = std::numbers::pi;

// A planar face looking along `forward` with `up` (ECEF, orthonormal) whose tangent
// window is [-halfWidth, halfWidth] × [bottom, top] at `focal` pixels per unit tangent;
// the window is widened to whole pixels (kMargin extra on every side first).
PanoramaFace face(const Camera& camera, const glm::dvec3& forward, const glm::dvec3& up,
                  double halfWidth, double bottom, double top, double focal) {
    const double margin = PanoramaFaces::kMargin / focal;
    halfWidth += margin;
    bottom -= margin;
    top += margin;
    PanoramaFace result;
    result.width = int(std::ceil(2.0 * halfWidth * focal));
    result.height = int(std::ceil((top - bottom) * focal));
    const double grow = (result.height / focal - (top - bottom)) / 2.0;
    bottom -= grow;
    top += grow;
    Camera& planar = result.camera;
    planar.position = camera.position;
    planar.geodetic = camera.geodetic;
    planar.axes = glm::dmat3(glm::cross(forward, up), up, -forward);
    planar.projection = CameraProjection::Planar;
    planar.horizontalFov = 0.0;
    planar.verticalFov = 2.0 * std::atan((top - bottom) / 2.0);
    planar.lensShift = glm::dvec2(0.0, (top + bottom) / (2.0 * (top - bottom)));
    planar.print = {};
    return result;
}

std::vector<PanoramaFace> cylinderStrips(const Camera& camera, int width, int height) {
    const double angle = camera.horizontalFov;
    const double radius = width / angle;  // pixels per radian, and per unit tan(elevation)
    const int strips = std::max(1, int(std::ceil(angle / PanoramaFaces::kMaxStripAngle - 1e-9)));
    const double half = angle / (2.0 * strips);
    const double axisRow = height / 2.0 + camera.lensShift.y * height;
    const double highest = axisRow / radius;            // tan(elevation) of the top row
    const double lowest = (axisRow - height) / radius;  // and of the bottom row
    // Off the strip's centre by Δ, tan(elevation) t appears at t / cos Δ on the face.
    const double top = highest > 0.0 ? highest / std::cos(half) : highest;
    const double bottom = lowest < 0.0 ? lowest / std::cos(half) : lowest;
    const glm::dvec3 right = camera.axes[0], up = camera.axes[1], forward = -camera.axes[2];
    std::vector<PanoramaFace> faces;
    for (int strip = 0; strip < strips; ++strip) {
        const double centre = -angle / 2.0 + (2 * strip + 1) * half;
        const glm::dvec3 direction = std::sin(centre) * right + std::cos(centre) * forward;
        faces.push_back(face(camera, direction, up, std::tan(half), bottom, top, radius));
    }
    return faces;
}

std::vector<PanoramaFace> cubeFaces(const Camera& camera, int width, int height) {
    const double focal = std::max(width / (2.0 * kPi), height / kPi);
    const glm::dvec3 right = camera.axes[0], up = camera.axes[1], back = camera.axes[2];
    const std::array<std::pair<glm::dvec3, glm::dvec3>, 6> views{
        {{-back, up}, {right, up}, {back, up}, {-right, up}, {up, back}, {-up, -back}}};
    std::vector<PanoramaFace> faces;
    for (const auto& [forward, faceUp] : views) {
        faces.push_back(face(camera, forward, faceUp, 1.0, -1.0, 1.0, focal));
    }
    return faces;
}

// Bilinear sample of `image` at pixel position (x, y) (centres at +0.5), clamped to the
// image, in the caller's decoding of the channels.
template <typename Channel, typename Decode>
glm::dvec4 bilinear(const Image<Channel>& image, double x, double y, const Decode& decode) {
    const double u = std::clamp(x - 0.5, 0.0, image.width - 1.0);
    const double v = std::clamp(y - 0.5, 0.0, image.height - 1.0);
    const int x0 = std::min(int(u), image.width - 2 < 0 ? 0 : image.width - 2);
    const int y0 = std::min(int(v), image.height - 2 < 0 ? 0 : image.height - 2);
    const int x1 = std::min(x0 + 1, image.width - 1), y1 = std::min(y0 + 1, image.height - 1);
    const double fx = u - x0, fy = v - y0;
    const auto fetch = [&](int px, int py) {
        const Channel* p = image.at(px, py);
        return glm::dvec4(decode(p[0]), decode(p[1]), decode(p[2]), double(p[3]));
    };
    return (fetch(x0, y0) * (1 - fx) + fetch(x1, y0) * fx) * (1 - fy) +
           (fetch(x0, y1) * (1 - fx) + fetch(x1, y1) * fx) * fy;
}

// Where each output pixel samples: a face and a pixel position in it.
struct Sample {
    std::size_t face = 0;
    glm::dvec2 pixel{0.0};
};

// Finds the sample of any output pixel from its exact direction (ImageProjection), for
// every projection; for a cylinder it also tabulates the columns: a column's face and
// face column are the same on every row (the strips share the cylinder's vertical axis),
// and its face row is affine in the output row (tan(elevation) is), so two exact
// look-ups per column give every pixel of it.
class SampleMap {
public:
    SampleMap(const Camera& camera, int width, int height, const std::vector<PanoramaFace>& faces)
        : faces_(faces), panorama_(camera, width, height) {
        for (const PanoramaFace& face : faces) {
            projections_.emplace_back(face.camera, face.width, face.height);
            forwards_.push_back(-face.camera.axes[2]);
        }
        if (camera.projection != CameraProjection::Cylindrical) {
            return;
        }
        for (int column = 0; column < width; ++column) {
            const Sample first = exact(0, column);
            const Sample second = exact(1, column);
            columns_.push_back(
                {first.face, first.pixel.x, first.pixel.y, second.pixel.y - first.pixel.y});
        }
    }

    // The exact ECEF direction of an output pixel's centre.
    glm::dvec3 direction(int row, int column) const {
        return panorama_.ecefDirection({column + 0.5, row + 0.5});
    }
    const glm::dvec3& forward(std::size_t face) const { return forwards_[face]; }

    Sample at(int row, int column) const {
        if (columns_.empty()) {
            return exact(row, column);
        }
        const Column& c = columns_[std::size_t(column)];
        return {c.face, glm::dvec2(c.x, c.y0 + row * c.dy)};
    }

private:
    struct Column {
        std::size_t face;
        double x, y0, dy;
    };

    Sample exact(int row, int column) const {
        const glm::dvec3 direction = panorama_.ecefDirection({column + 0.5, row + 0.5});
        std::size_t best = 0;
        for (std::size_t i = 1; i < forwards_.size(); ++i) {
            if (glm::dot(direction, forwards_[i]) > glm::dot(direction, forwards_[best])) {
                best = i;
            }
        }
        const std::optional<glm::dvec2> pixel =
            projections_[best].pixelOf(faces_[best].camera.viewRotation() * direction);
        SYLVA_CHECK(pixel.has_value());  // the most central face always shows the direction
        return {best, *pixel};
    }

    const std::vector<PanoramaFace>& faces_;
    ImageProjection panorama_;
    std::vector<ImageProjection> projections_;
    std::vector<glm::dvec3> forwards_;
    std::vector<Column> columns_;
};

template <typename Channel, typename Decode, typename Encode>
Image<Channel> resampleFaces(const Camera& camera, int width, int height,
                             const std::vector<PanoramaFace>& faces,
                             const std::vector<const Image<Channel>*>& images, const Decode& decode,
                             const Encode& encode) {
    SYLVA_CHECK(faces.size() == images.size() && !faces.empty());
    for (std::size_t i = 0; i < faces.size(); ++i) {
        SYLVA_CHECK(images[i]->width == faces[i].width && images[i]->height == faces[i].height);
    }
    const SampleMap samples(camera, width, height, faces);
    Image<Channel> out(width, height);
    WorkerPool::shared().run(
        height,
        [&](int row) {
            for (int column = 0; column < width; ++column) {
                const Sample sample = samples.at(row, column);
                const glm::dvec4 value =
                    bilinear(*images[sample.face], sample.pixel.x, sample.pixel.y, decode);
                Channel* target = out.at(column, row);
                for (int c = 0; c < 3; ++c) {
                    target[c] = encode(value[c]);
                }
                target[3] =
                    Channel(std::is_floating_point_v<Channel> ? value[3] : std::lround(value[3]));
            }
        },
        4);
    return out;
}

// Linear [0, 1] to 8-bit sRGB through a table of 2^16 steps (error below 0.06 code values
// in the darkest step, where the curve is steepest), so resampling costs no pow() per pixel.
std::uint8_t encodeSrgb(double value) {
    static const std::vector<std::uint8_t> table = [] {
        std::vector<std::uint8_t> codes(65536);
        for (std::size_t i = 0; i < codes.size(); ++i) {
            codes[i] = std::uint8_t(std::lround(linearToSrgb(float(i) / 65535.0f) * 255.0f));
        }
        return codes;
    }();
    return table[std::size_t(std::lround(std::clamp(value, 0.0, 1.0) * 65535.0))];
}

}  // namespace

std::vector<PanoramaFace> PanoramaFaces::plan(const Camera& camera, int width, int height) {
    SYLVA_CHECK(width > 0 && height > 0);
    SYLVA_CHECK(camera.projection != CameraProjection::Planar);
    return camera.projection == CameraProjection::Cylindrical
               ? cylinderStrips(camera, width, height)
               : cubeFaces(camera, width, height);
}

RgbaImage PanoramaFaces::resample(const Camera& camera, int width, int height,
                                  const std::vector<PanoramaFace>& faces,
                                  const std::vector<const RgbaImage*>& images) {
    static const std::array<double, 256> linear = [] {
        std::array<double, 256> table{};
        for (int i = 0; i < 256; ++i) {
            table[std::size_t(i)] = srgbToLinear(float(i) / 255.0f);
        }
        return table;
    }();
    return resampleFaces<std::uint8_t>(
        camera, width, height, faces, images, [](std::uint8_t value) { return linear[value]; },
        [](double value) { return encodeSrgb(value); });
}

LinearImage PanoramaFaces::resample(const Camera& camera, int width, int height,
                                    const std::vector<PanoramaFace>& faces,
                                    const std::vector<const LinearImage*>& images) {
    return resampleFaces<float>(
        camera, width, height, faces, images, [](float value) { return double(value); },
        [](double value) { return float(value); });
}

std::vector<float> PanoramaFaces::resampleDepth(
    const Camera& camera, int width, int height, const std::vector<PanoramaFace>& faces,
    const std::vector<const std::vector<float>*>& depths, const std::vector<double>& nears,
    double near) {
    SYLVA_CHECK(faces.size() == depths.size() && faces.size() == nears.size() && !faces.empty());
    for (std::size_t i = 0; i < faces.size(); ++i) {
        SYLVA_CHECK(depths[i]->size() ==
                    std::size_t(faces[i].width) * std::size_t(faces[i].height));
        SYLVA_CHECK(nears[i] > 0.0);
    }
    const SampleMap samples(camera, width, height, faces);
    std::vector<float> out(std::size_t(width) * std::size_t(height), 0.0f);
    WorkerPool::shared().run(
        height,
        [&](int row) {
            for (int column = 0; column < width; ++column) {
                const Sample sample = samples.at(row, column);
                const PanoramaFace& face = faces[sample.face];
                const int x = std::clamp(int(std::floor(sample.pixel.x)), 0, face.width - 1);
                const int y = std::clamp(int(std::floor(sample.pixel.y)), 0, face.height - 1);
                const float depth =
                    (*depths[sample.face])[std::size_t(y) * std::size_t(face.width) +
                                           std::size_t(x)];
                if (depth <= 0.0f) {
                    continue;  // sky
                }
                // distance along the axis = near_i / depth; along the ray = that / cos θ.
                const double cosine =
                    glm::dot(samples.direction(row, column), samples.forward(sample.face));
                out[std::size_t(row) * std::size_t(width) + std::size_t(column)] =
                    float(near * double(depth) * cosine / nears[sample.face]);
            }
        },
        4);
    return out;
}

}  // namespace sylva
