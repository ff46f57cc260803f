// MarkerFixture: a surveyed scene for verified-view tests and `sylva bench views`: flat
// ground at kGroundHeight metres above the ellipsoid, dark grey, with bright markers at
// surveyed ground points. A marker's brightness is exp(−(θ/θR)²) of the angle θ between a
// ground point and the marker as seen from the viewpoint it was placed for, so its image
// is round and symmetric about the marker's direction (a disc flat on the ground would
// be foreshortened, and its centroid would miss the centre's projection). θR is at least
// a few terrain texels wide (the clipmap's colour has about 0.4° per texel at any
// distance), so texel phase does not move the centroid either. A marker's predicted pixel
// (ImageProjection of its ground point) and its detected centroid in a render are compared to check
// where a projection draws a point; the centroids of a Sylva-rendered "photograph" are the control
// points of the camera-matching fixture.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/image/Image.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/sources/Source.h"
#include "sylva/core/sources/graph/SourceGraph.h"

namespace sylva::bench {

struct Marker {
    Geodetic ground;              // on the fixture's ground (height kGroundHeight)
    glm::dvec3 ecef{};            // the same point
    glm::dvec3 viewpoint{};       // ECEF: the camera it was placed for
    double angularRadius = 0.02;  // radians: the profile's θR
};

class MarkerFixture {
public:
    static constexpr double kGroundHeight = 100.0;

    MarkerFixture();
    ~MarkerFixture();

    // The angular radius of markers that no texel grid moves (about three texels).
    static constexpr double kAngularRadius = 0.022;

    // Places a marker where the ray through `pixel` of `camera` (image width × height)
    // meets the ground. nullopt when the ray misses the ground within 50 km.
    std::optional<Marker> addAt(const Camera& camera, int width, int height,
                                const glm::dvec2& pixel, double angularRadius = kAngularRadius);
    const std::vector<Marker>& markers() const { return *markers_; }

    // Elevation, colour and normals of the scene (the colour depends on the markers added
    // so far: add all markers before the first render).
    TerrainLayers layers() const;

    // The intensity-weighted centroid (pixel position) of the bright marker blob nearest
    // `predicted`, searched within `window` pixels; nullopt when nothing is there.
    static std::optional<glm::dvec2> centroid(const RgbaImage& image, const glm::dvec2& predicted,
                                              double window);

private:
    std::shared_ptr<std::vector<Marker>> markers_;
    std::unique_ptr<Source> elevation_;
    std::unique_ptr<Source> colour_;
    std::unique_ptr<Source> normals_;
};

}  // namespace sylva::bench
