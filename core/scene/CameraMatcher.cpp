#include "sylva/core/scene/CameraMatcher.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "sylva/core/scene/ImageProjection.h"

namespace sylva {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Rotation matrix of rotation vector `v` (axis × angle, radians), Rodrigues' formula.
glm::dmat3 rotation(const glm::dvec3& v) {
    const double angle = glm::length(v);
    if (angle < 1e-300) {
        return glm::dmat3(1.0);
    }
    const glm::dvec3 k = v / angle;
    const glm::dmat3 cross(glm::dvec3(0, k.z, -k.y), glm::dvec3(-k.z, 0, k.x),
                           glm::dvec3(k.y, -k.x, 0));
    return glm::dmat3(1.0) + std::sin(angle) * cross + (1 - std::cos(angle)) * (cross * cross);
}

// Solves A x = b (n × n, row-major) by Gaussian elimination with partial pivoting;
// false when A is singular.
bool solveLinear(std::vector<double> a, std::vector<double> b, int n, std::vector<double>& x) {
    for (int column = 0; column < n; ++column) {
        int pivot = column;
        for (int row = column + 1; row < n; ++row) {
            if (std::abs(a[row * n + column]) > std::abs(a[pivot * n + column])) {
                pivot = row;
            }
        }
        if (!(std::abs(a[pivot * n + column]) > 1e-300)) {
            return false;
        }
        for (int k = 0; k < n; ++k) {
            std::swap(a[column * n + k], a[pivot * n + k]);
        }
        std::swap(b[column], b[pivot]);
        for (int row = column + 1; row < n; ++row) {
            const double factor = a[row * n + column] / a[column * n + column];
            for (int k = column; k < n; ++k) {
                a[row * n + k] -= factor * a[column * n + k];
            }
            b[row] -= factor * b[column];
        }
    }
    x.assign(n, 0.0);
    for (int row = n - 1; row >= 0; --row) {
        double sum = b[row];
        for (int k = row + 1; k < n; ++k) {
            sum -= a[row * n + k] * x[k];
        }
        x[row] = sum / a[row * n + row];
    }
    return true;
}

// The camera model around a current camera: parameters are offsets from it.
class MatchModel {
public:
    MatchModel(int width, int height, const std::vector<ControlPoint>& points,
               const CameraMatchOptions& options)
        : width_(width), height_(height), points_(points), options_(options) {}

    int parameterCount() const {
        return 3 + (options_.solveFocalLength ? 1 : 0) + (options_.solvePosition ? 3 : 0);
    }
    // Finite-difference step of parameter i.
    double step(int i) const { return i >= 3 + (options_.solveFocalLength ? 1 : 0) ? 1e-3 : 1e-7; }

    Camera apply(const Camera& current, const std::vector<double>& p) const {
        Camera camera = current;
        camera.axes = rotation(glm::dvec3(p[0], p[1], p[2])) * current.axes;
        int next = 3;
        if (options_.solveFocalLength) {
            const double scale = std::exp(p[std::size_t(next++)]);
            if (camera.projection == CameraProjection::Cylindrical) {
                camera.horizontalFov = current.horizontalFov / scale;
            } else {
                const double focal = ImageProjection(current, width_, height_).focalPixels();
                camera.horizontalFov = 0.0;
                camera.verticalFov = 2.0 * std::atan(height_ / (2.0 * focal * scale));
            }
        }
        if (options_.solvePosition) {
            const glm::dmat3 frame =
                Ellipsoid::localFrame(current.geodetic.latitude, current.geodetic.longitude);
            camera.position = current.position + frame * glm::dvec3(p[std::size_t(next)],
                                                                    p[std::size_t(next + 1)],
                                                                    p[std::size_t(next + 2)]);
            camera.geodetic = Ellipsoid::toGeodetic(camera.position);
        }
        return camera;
    }

    // Residuals (predicted − measured, x and y per point); false when a point is not shown.
    bool residuals(const Camera& camera, std::vector<double>& out) const {
        const ImageProjection image(camera, width_, height_);
        out.resize(points_.size() * 2);
        for (std::size_t i = 0; i < points_.size(); ++i) {
            const std::optional<glm::dvec2> pixel = image.pixelOfPoint(points_[i].position);
            if (!pixel) {
                return false;
            }
            out[2 * i] = pixel->x - points_[i].pixel.x;
            out[2 * i + 1] = pixel->y - points_[i].pixel.y;
        }
        return true;
    }

    double cost(const Camera& camera) const {
        std::vector<double> r;
        if (!residuals(camera, r)) {
            return kInfinity;
        }
        double sum = 0.0;
        for (double value : r) {
            sum += value * value;
        }
        return sum;
    }

private:
    int width_, height_;
    const std::vector<ControlPoint>& points_;
    CameraMatchOptions options_;
};

Status checkPoints(const Camera& guess, int width, int height,
                   const std::vector<ControlPoint>& points, const CameraMatchOptions& options) {
    if (int(points.size()) < CameraMatcher::kMinimumPoints) {
        return Error{"camera matching needs at least " +
                     std::to_string(CameraMatcher::kMinimumPoints) + " control points, got " +
                     std::to_string(points.size())};
    }
    if (options.solveFocalLength && guess.projection == CameraProjection::Equirectangular) {
        return Error{"an equirectangular image has no focal length to solve"};
    }
    glm::dvec2 mean(0.0);
    for (const ControlPoint& point : points) {
        if (!(point.pixel.x >= 0 && point.pixel.x <= width && point.pixel.y >= 0 &&
              point.pixel.y <= height)) {
            char buffer[160];
            std::snprintf(buffer, sizeof buffer, "pixel (%.2f, %.2f) is outside the %dx%d image",
                          point.pixel.x, point.pixel.y, width, height);
            return Error{point.name + ": " + buffer};
        }
        mean += point.pixel / double(points.size());
    }
    // Pixels on one line leave the roll about that line (and more) undetermined.
    double xx = 0, xy = 0, yy = 0;
    for (const ControlPoint& point : points) {
        const glm::dvec2 d = point.pixel - mean;
        xx += d.x * d.x;
        xy += d.x * d.y;
        yy += d.y * d.y;
    }
    const double middle = (xx + yy) / 2, spread = std::hypot((xx - yy) / 2, xy);
    if (!(middle - spread > 1e-4 * (middle + spread))) {
        return Error{
            "the control points' pixels lie on one line (spread across it is below 1% "
            "of the spread along it): add points off that line"};
    }
    const ImageProjection image(guess, width, height);
    for (const ControlPoint& point : points) {
        if (!image.pixelOfPoint(point.position)) {
            return Error{point.name + ": the point is behind the first-guess camera"};
        }
    }
    return {};
}

std::string residualText(const std::vector<ControlPoint>& points, const CameraMatch& match) {
    std::string text;
    for (std::size_t i = 0; i < points.size(); ++i) {
        char buffer[128];
        std::snprintf(buffer, sizeof buffer, "\n  %s: residual %.2f px (%.2f, %.2f)",
                      points[i].name.c_str(), match.residualLengths[i], match.residuals[i].x,
                      match.residuals[i].y);
        text += buffer;
    }
    return text;
}

// One damped Gauss–Newton step from `current`; false when no step lowers the cost.
bool improve(const MatchModel& model, Camera& current, double& cost, double& lambda) {
    const int n = model.parameterCount();
    std::vector<double> r0;
    model.residuals(current, r0);
    const std::size_t m = r0.size();
    std::vector<double> jacobian(m * std::size_t(n));
    std::vector<double> plus, minus;
    for (int j = 0; j < n; ++j) {
        std::vector<double> p(std::size_t(n), 0.0);
        p[std::size_t(j)] = model.step(j);
        const bool a = model.residuals(model.apply(current, p), plus);
        p[std::size_t(j)] = -model.step(j);
        const bool b = model.residuals(model.apply(current, p), minus);
        if (!a || !b) {
            return false;
        }
        for (std::size_t i = 0; i < m; ++i) {
            jacobian[i * std::size_t(n) + std::size_t(j)] =
                (plus[i] - minus[i]) / (2 * model.step(j));
        }
    }
    std::vector<double> normal(std::size_t(n * n), 0.0), gradient(std::size_t(n), 0.0);
    for (std::size_t i = 0; i < m; ++i) {
        for (int a = 0; a < n; ++a) {
            const double ja = jacobian[i * std::size_t(n) + std::size_t(a)];
            gradient[std::size_t(a)] -= ja * r0[i];
            for (int b = 0; b < n; ++b) {
                normal[std::size_t(a * n + b)] +=
                    ja * jacobian[i * std::size_t(n) + std::size_t(b)];
            }
        }
    }
    while (lambda < 1e16) {
        std::vector<double> damped = normal, delta;
        for (int a = 0; a < n; ++a) {
            damped[std::size_t(a * n + a)] += lambda * normal[std::size_t(a * n + a)] + 1e-18;
        }
        if (solveLinear(damped, gradient, n, delta)) {
            const Camera trial = model.apply(current, delta);
            const double trialCost = model.cost(trial);
            if (trialCost < cost) {
                current = trial;
                cost = trialCost;
                lambda = std::max(lambda / 10, 1e-12);
                return true;
            }
        }
        lambda *= 10;
    }
    return false;
}

}  // namespace

double CameraMatcher::roll(const Camera& camera) {
    const glm::dmat3 frame =
        Ellipsoid::localFrame(camera.geodetic.latitude, camera.geodetic.longitude);
    const glm::dvec3 forward = -camera.axes[2];
    glm::dvec3 right = glm::cross(forward, frame[2]);
    if (glm::length(right) < 1e-9) {
        right = glm::cross(forward, frame[1]);
    }
    right = glm::normalize(right);
    const glm::dvec3 up = glm::cross(right, forward);
    return std::atan2(glm::dot(camera.axes[0], up), glm::dot(camera.axes[0], right));
}

Result<CameraMatch> CameraMatcher::match(const Camera& guess, int width, int height,
                                         const std::vector<ControlPoint>& points,
                                         const CameraMatchOptions& options) {
    if (Status valid = checkPoints(guess, width, height, points, options); !valid) {
        return valid.error();
    }
    const MatchModel model(width, height, points, options);
    CameraMatch match;
    match.camera = guess.fitted(width, height);
    double cost = model.cost(match.camera);
    double lambda = 1e-3;
    bool converged = false;
    for (; match.iterations < options.maximumIterations; ++match.iterations) {
        const double before = cost;
        if (!improve(model, match.camera, cost, lambda)) {
            converged = true;  // no damped step lowers the cost: a minimum
            break;
        }
        if (before - cost <= 1e-14 * before + 1e-20) {
            converged = true;
            break;
        }
    }
    std::vector<double> r;
    const bool shown = model.residuals(match.camera, r);
    SYLVA_CHECK(shown);  // every accepted step keeps all points shown (finite cost)
    double sum = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        match.residuals.emplace_back(r[2 * i], r[2 * i + 1]);
        match.residualLengths.push_back(glm::length(match.residuals.back()));
        sum += glm::dot(match.residuals.back(), match.residuals.back());
    }
    match.rms = std::sqrt(sum / double(points.size()));
    if (!converged || !(match.rms <= options.maximumRms)) {
        char buffer[160];
        std::snprintf(buffer, sizeof buffer,
                      "camera matching did not converge: rms %.2f px after %d iterations "
                      "(limit %.2f px)",
                      match.rms, match.iterations, options.maximumRms);
        return Error{buffer + residualText(points, match)};
    }
    // A planar camera sees through the front only; the solve may not flip a point behind.
    const ImageProjection image(match.camera, width, height);
    for (const ControlPoint& point : points) {
        if (!image.pixelOfPoint(point.position)) {
            return Error{point.name + ": the point is behind the matched camera"};
        }
    }
    return match;
}

}  // namespace sylva
