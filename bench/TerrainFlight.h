// The terrain bench flight (`sylva bench terrain`, also flown by `sylva bench shading`):
// a DEM of the demo project's relief around 46° N 8° E, a descent from 800 km to 50 m
// (the altitudes of seed 001 Table 4.1), its render settings and its terrain layers.
// CPU only; the sources must outlive the renders that use them.
#pragma once

#include <memory>
#include <numbers>
#include <vector>

#include "GridElevationSource.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/sources/graph/SourceGraph.h"
#include "sylva/core/sources/raster/HypsometricSource.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::bench {

inline constexpr double kFlightCentreLatitude = 46.0 * std::numbers::pi / 180.0;  // radians
inline constexpr double kFlightCentreLongitude = 8.0 * std::numbers::pi / 180.0;  // radians

// `samples`² heights (metres) over a square of `degrees` around the centre.
ElevationGrid makeFlightDem(int samples, double degrees);
// The same surface with `factor` times the samples per side (bilinear).
ElevationGrid upsample(const ElevationGrid& grid, int factor);

struct FlightFrame {
    Camera camera;
    double altitude;  // metres above the DEM
};

// `framesPerSegment` frames between successive altitudes, approaching the centre from
// the south, looking down from space and towards the horizon near the ground.
std::vector<FlightFrame> terrainFlight(const ElevationGrid& grid, int framesPerSegment);

// The demo project's sun and exposure, no ocean, width × height.
render::RenderSettings flightRenderSettings(int width, int height);

// The flight's layers: the DEM, its normal map and the hypsometric colours (the schema's
// defaults).
class FlightTerrain {
public:
    explicit FlightTerrain(ElevationGrid grid);
    TerrainLayers layers() const { return {&elevation_, &colour_, &normals_, {}, {}}; }

private:
    GridElevationSource elevation_;
    NormalMapSource normals_;
    HypsometricSource colour_;
};

}  // namespace sylva::bench
