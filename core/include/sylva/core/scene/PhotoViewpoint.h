// PhotoViewpoint: a `photo` block of the project (core/model PhotoSchema.cpp) read for a
// photomontage (issue 18; LI TGN 06/19 Types 3 and 4): the photograph's file, the camera
// it was taken from, the baseline and proposed scenarios, surveyed control points, the
// time and the look of the wirelines; then the checks that tie the photograph to the
// camera and the camera match (CameraMatcher).
//
// Every failure is a Result error located at the block's attribute ("file:line:col: photo
// 'name': ..."): a missing or unreadable photograph (PhotoReader's reason), a photograph
// whose aspect differs from the camera's print format, a non-planar camera, an EXIF
// 35 mm focal length that disagrees with the camera's lens, 1 to 3 control points (4 are
// needed), a control point without a height, and the matcher's own failures (collinear,
// outside the image, behind the camera, no convergence with every residual listed).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/image/PhotoReader.h"
#include "sylva/core/image/Photomontage.h"
#include "sylva/core/model/BlockReader.h"
#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/scene/CameraMatcher.h"
#include "sylva/core/scene/DateTime.h"

namespace sylva {

// The wireline_color, skyline_color and line_width of a photo block or a wireline compare
// block (the schema's defaults when absent).
WirelineStyle wirelineStyleOf(const BlockReader& reader);

class PhotoViewpoint {
public:
    // The diagonal of the 36 × 24 mm frame: EXIF FocalLengthIn35mmFilm is the focal length
    // giving the photograph's diagonal field on it (CIPA DC-008).
    static constexpr double kFullFrameDiagonal = 0.0432666153;  // metres
    // Relative difference allowed between the EXIF 35 mm focal length and the camera's.
    static constexpr double kLensTolerance = 0.02;
    // Relative difference allowed between the photograph's aspect and the print format's.
    static constexpr double kAspectTolerance = 0.01;

    std::string name;
    std::filesystem::path file;  // resolved against the project file's folder
    std::string camera, scenario, baseline;
    std::optional<DateTime> time;
    double unixSeconds = 0.0;  // the time as a UTC instant, when set
    std::vector<ControlPoint> controlPoints;
    bool solveFocalLength = false;
    double maxResidual = 3.0;  // pixels
    WirelineStyle wireline;    // wireline_color, skyline_color, line_width
    std::string output;        // prefix relative to the output folder, {name} filled in
    bool sheet = false;
    bool annotated = false;  // also the Type 1 annotated photograph (ViewAnnotation)

    static Result<PhotoViewpoint> fromBlock(const ProjectModel& model, const Block& block);

    // Reads the photograph (errors located at `file`).
    Result<Photo> readPhoto() const;
    // `viewpoint` (the camera from its block, `cameraBlock`) made to fit the photograph: planar,
    // the print format's aspect equal to the photograph's, and the lens from the EXIF 35 mm focal
    // length when the camera block gives no field of view (else both must agree).
    Result<Camera> fitCamera(const Camera& viewpoint, const Block& cameraBlock,
                             const Photo& photo) const;
    // The camera solved from the control points (nullopt without any).
    Result<std::optional<CameraMatch>> match(const Camera& guess, const Photo& photo) const;

    // The horizontal field of view of an image of aspect width : height taken with a 35 mm
    // equivalent focal length (metres), and the inverse.
    static double horizontalFovFrom35mm(double focalLength, int width, int height);
    static double equivalent35mm(double horizontalFov, int width, int height);

private:
    const Block* block_ = nullptr;
};

}  // namespace sylva
