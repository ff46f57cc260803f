#include "TerrainFlight.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>

#include "sylva/core/base/WorkerPool.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/sources/raster/NoiseSource.h"

namespace sylva::bench {

using namespace sylva::render;

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kCentreLatitude = kFlightCentreLatitude;
constexpr double kCentreLongitude = kFlightCentreLongitude;
// Altitudes above the ground of seed 001 Table 4.1, metres.
constexpr double kAltitudes[] = {800e3, 100e3, 10e3, 1e3, 50.0};

}  // namespace

ElevationGrid makeFlightDem(int samples, double degrees) {
    NoiseParameters parameters;  // the demo project's relief
    parameters.seed = 7;
    parameters.amplitude = 3000;
    parameters.baseWavelength = 3.0e6;
    parameters.ridges = 0.6;
    parameters.ridgeWavelength = 3.0e5;
    parameters.roughness = 0.7;
    const NoiseSource noise("dem", parameters);
    ElevationGrid grid;
    grid.width = grid.height = samples;
    grid.west = kCentreLongitude - degrees / 2 * kDegree;
    grid.east = kCentreLongitude + degrees / 2 * kDegree;
    grid.south = kCentreLatitude - degrees / 2 * kDegree;
    grid.north = kCentreLatitude + degrees / 2 * kDegree;
    grid.heights.resize(std::size_t(samples) * samples);
    const double footprint = grid.sampleSpacingLatitude() * Ellipsoid::kMeanRadius;
    WorkerPool::shared().run(samples, [&](int row) {
        const double latitude = grid.north - row * grid.sampleSpacingLatitude();
        for (int column = 0; column < samples; ++column) {
            const double longitude = grid.west + column * grid.sampleSpacingLongitude();
            const glm::dvec3 direction = Ellipsoid::surfaceNormal(latitude, longitude);
            grid.heights[std::size_t(row) * samples + column] =
                float(noise.height(direction, footprint));
        }
    });
    return grid;
}

// The same surface with `factor` times the samples per side (bilinear), i.e. a DEM
// with factor^2 the data.
ElevationGrid upsample(const ElevationGrid& grid, int factor) {
    ElevationGrid fine = grid;
    fine.width = (grid.width - 1) * factor + 1;
    fine.height = (grid.height - 1) * factor + 1;
    fine.heights.assign(std::size_t(fine.width) * fine.height, 0.0f);
    WorkerPool::shared().run(fine.height, [&](int row) {
        const double latitude = fine.north - row * fine.sampleSpacingLatitude();
        for (int column = 0; column < fine.width; ++column) {
            fine.heights[std::size_t(row) * fine.width + column] =
                float(grid.at(latitude, fine.west + column * fine.sampleSpacingLongitude(), 0.0));
        }
    });
    return fine;
}

std::vector<FlightFrame> flightFrames(const ElevationGrid& grid, int framesPerSegment) {
    std::vector<FlightFrame> frames;
    const int segments = int(std::size(kAltitudes)) - 1;
    const int total = segments * framesPerSegment + 1;
    for (int frame = 0; frame < total; ++frame) {
        const double progress = double(frame) / (total - 1);
        const int segment = std::min(frame / framesPerSegment, segments - 1);
        const double local = double(frame - segment * framesPerSegment) / framesPerSegment;
        const double altitude = std::exp(std::log(kAltitudes[segment]) * (1 - local) +
                                         std::log(kAltitudes[segment + 1]) * local);
        // Approach the DEM centre from the south while descending; look down from
        // space, towards the horizon near the ground.
        const double latitude = kCentreLatitude - 0.6 * kDegree * (1 - progress);
        const double longitude = kCentreLongitude + 0.2 * kDegree * (1 - progress);
        const double pitch = (-85.0 + 75.0 * std::pow(progress, 0.7)) * kDegree;
        Camera camera;
        camera.geodetic = {latitude, longitude, grid.at(latitude, longitude, 0.0) + altitude};
        camera.position = Ellipsoid::toEcef(camera.geodetic);
        camera.axes = Camera::axesFromAngles(camera.geodetic, 10 * kDegree, pitch, 0.0);
        camera.verticalFov = 60 * kDegree;
        frames.push_back({camera, altitude});
    }
    return frames;
}

// The frame settings of both flights: the demo project's sun and exposure, no ocean.
RenderSettings flightSettings(int width, int height, bool waitForTiles) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.ocean = false;
    settings.sunDirection = Ellipsoid::surfaceNormal(5 * kDegree, -40 * kDegree);
    settings.exposure = 0.45;  // as the demo project
    settings.waitForTiles = waitForTiles;
    return settings;
}

}  // namespace sylva::bench
