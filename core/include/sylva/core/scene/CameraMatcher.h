// CameraMatcher: camera matching for verified views (LI TGN 06/19 Type 4): the pose of a
// photograph's camera — heading, pitch and roll, optionally the focal length and the
// position — solved from surveyed control points (a point's ECEF position ↔ its pixel in
// the photograph) by Levenberg–Marquardt on the exact camera model (ImageProjection:
// planar, cylindrical or equirectangular), starting from a first guess (EXIF, or the
// camera block). Residuals are reported per point in pixels.
//
// Parameters, re-linearised at every step: a rotation vector (radians) turning the
// camera's axes about ECEF axes; ln(focal length in pixels); the position's offset in the
// local east/north/up frame (metres). The Jacobian is by central differences (the model
// is smooth and small: 2 rows per point, at most 7 columns); the normal equations are
// damped by λ·diag(JᵀJ) (Marquardt 1963) and solved by Gaussian elimination with pivoting.
//
// Failures (Result errors, nothing returned half-solved): fewer than 4 points, pixels
// (nearly) on one line, a pixel outside the image, a point behind the solved camera or
// not shown by it, and a solve that does not converge (the message lists every residual).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/scene/Camera.h"

namespace sylva {

struct ControlPoint {
    std::string name;     // for messages, e.g. "lens.sylva:12:5: control point 'mast'"
    glm::dvec3 position;  // ECEF, metres
    glm::dvec2 pixel;     // in the photograph (x right, y down, top-left corner 0, 0)
};

struct CameraMatchOptions {
    bool solveFocalLength = false;
    bool solvePosition = false;
    int maximumIterations = 200;
    // The match fails when the rms residual stays above this (pixels).
    double maximumRms = 3.0;
};

struct CameraMatch {
    Camera camera;                      // the solved camera (lens fields kept from the guess)
    std::vector<glm::dvec2> residuals;  // predicted − measured pixel, per point
    std::vector<double> residualLengths;
    double rms = 0.0;  // sqrt(mean |residual|²), pixels
    int iterations = 0;
};

class CameraMatcher {
public:
    static constexpr int kMinimumPoints = 4;

    // Solves `guess` (image of width × height pixels) to `points`.
    static Result<CameraMatch> match(const Camera& guess, int width, int height,
                                     const std::vector<ControlPoint>& points,
                                     const CameraMatchOptions& options = {});

    // Roll of a camera: rotation of its right axis out of the local horizontal, radians.
    static double roll(const Camera& camera);
};

}  // namespace sylva
