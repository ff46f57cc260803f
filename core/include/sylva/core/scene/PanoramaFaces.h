// PanoramaFaces: how a cylindrical or equirectangular image is rendered exactly by a
// rasterizer that only draws planar (pinhole) images. The panorama is covered by planar
// faces — vertical strips about the panorama's axis for a cylinder (each strip at most
// kMaxStripAngle wide, its window off-axis by a lens shift to hold exactly the strip's rows),
// the six faces of a cube for an equirectangular image — each with a focal length no
// smaller than the panorama's pixels per radian, so no face is undersampled. Every
// output pixel then takes its exact direction from ImageProjection, picks the face that
// looks most nearly that way and samples it bilinearly (linear light). Column bearings
// are therefore exact (to rounding) and only the image content is interpolated.
#pragma once

#include <vector>

#include "sylva/core/image/Image.h"
#include "sylva/core/scene/Camera.h"

namespace sylva {

struct PanoramaFace {
    Camera camera;  // planar, with verticalFov and lensShift set; same position
    int width = 0;
    int height = 0;
};

class PanoramaFaces {
public:
    // Strips at most this wide (radians). A strip of half-width a covers tan(a)/a / cos(a)
    // times its share of the cylinder in pixels (1.06 at 30°, 1.14 at 45°), but every strip
    // is one more render with its fixed cost: on llvmpipe a 90° panorama in 2 strips of 45°
    // cost 1.36 × a planar image of its size, in 3 of 30° 1.66 × (docs/benchmarks.md ## views).
    static constexpr double kMaxStripAngle = 45.0 * 3.14159265358979323846 / 180.0;
    // Extra pixels round each face, so bilinear sampling never leaves it.
    static constexpr int kMargin = 2;

    // The faces of `camera` (cylindrical or equirectangular) for an image of width ×
    // height pixels. A planar camera is a programmer error (SYLVA_CHECK).
    static std::vector<PanoramaFace> plan(const Camera& camera, int width, int height);

    // The panorama from its rendered faces (`faces[i]` drawn into `images[i]`, sRGB 8-bit,
    // rows top to bottom), sampled bilinearly in linear light.
    static RgbaImage resample(const Camera& camera, int width, int height,
                              const std::vector<PanoramaFace>& faces,
                              const std::vector<const RgbaImage*>& images);
    // The same for linear radiance (EXR output).
    static LinearImage resample(const Camera& camera, int width, int height,
                                const std::vector<PanoramaFace>& faces,
                                const std::vector<const LinearImage*>& images);
    // The panorama's depth from the faces' reversed-Z depth buffers (`depths[i]`: near_i /
    // distance along face i's axis, 0 where nothing is drawn, rows top to bottom, face
    // width × height; `nears[i]` its near plane, metres): per output pixel `near` / the
    // distance along that pixel's ray, from the face pixel nearest its sample position (not
    // interpolated: a silhouette's pixels are never a blend of the two sides, sky stays 0).
    // A wireline's masks (WirelineMasks::fromDepths) compare it between two renders.
    static std::vector<float> resampleDepth(const Camera& camera, int width, int height,
                                            const std::vector<PanoramaFace>& faces,
                                            const std::vector<const std::vector<float>*>& depths,
                                            const std::vector<double>& nears, double near);
};

}  // namespace sylva
