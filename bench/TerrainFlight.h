// The terrain benchmark's flight (`sylva bench terrain`, also used by `sylva bench
// shading`): a noise DEM like the demo project's relief around (46°N, 8°E), a scripted
// descent from 800 km to 50 m above it (the altitudes of seed 001 Table 4.1) and the
// frame settings (the demo project's sun and exposure, no ocean).
#pragma once

#include <numbers>
#include <vector>

#include "GridElevationSource.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::bench {

// The DEM's centre, radians.
inline constexpr double kFlightCentreLatitude = 46.0 * std::numbers::pi / 180.0;
inline constexpr double kFlightCentreLongitude = 8.0 * std::numbers::pi / 180.0;

struct FlightFrame {
    Camera camera;
    double altitude;  // metres above the DEM
};

// `samples` per side over `degrees` of latitude and longitude.
ElevationGrid makeFlightDem(int samples, double degrees);
// The same surface with `factor` times the samples per side (bilinear).
ElevationGrid upsample(const ElevationGrid& grid, int factor);
// Four segments of `framesPerSegment` frames each, plus the last.
std::vector<FlightFrame> flightFrames(const ElevationGrid& grid, int framesPerSegment);
render::RenderSettings flightSettings(int width, int height, bool waitForTiles);

}  // namespace sylva::bench
