// CameraPath: a `path` block's key frames, sampled at its frame rate into Cameras.
//
// Positions move on the globe, not through it: the horizontal position is interpolated
// as a unit normal vector ("n-vector", seed-independent; Gade 2010) — linearly by
// spherical interpolation, or by a time-parametrised Catmull–Rom (cubic Hermite with
// tangents (p[i+1] − p[i−1]) / (t[i+1] − t[i−1])) renormalised onto the sphere — so
// poles and the antimeridian need no special cases and `catmull_rom` is C¹ in time.
// Heights are interpolated the same way as scalars: above the terrain when every key
// gives `eye_height` (the terrain is queried per frame, so the camera follows the
// ground), otherwise above the ellipsoid. Orientations are slerped in the local
// east/north/up frame of the interpolated position (so the horizon stays level as the
// camera moves around the globe); when both keys look at a point, the point itself is
// interpolated and looked at.
//
// Units: seconds, radians, metres; frames: geodetic WGS84 and ECEF (see Camera).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/scene/Camera.h"

namespace sylva {

enum class PathInterpolation { Linear, CatmullRom, Step };

struct CameraPathKey {
    double time = 0;                          // seconds from the start of the path
    double latitude = 0;                      // radians
    double longitude = 0;                     // radians
    std::optional<double> height;             // metres above the ellipsoid
    std::optional<double> eyeHeight;          // metres above the terrain (wins over height)
    std::optional<Geodetic> lookAt;           // height NaN when the key did not give one
    double heading = 0, pitch = 0, roll = 0;  // radians, when lookAt is empty
    SourceLocation location;
};

class CameraPath {
public:
    // From a `path` block. Errors (located at the block or key): fewer than two keys,
    // times not ascending, a key without any height.
    static Result<CameraPath> fromBlock(const Block& block);
    CameraPath(std::string name, std::vector<CameraPathKey> keys, PathInterpolation interpolation,
               double framesPerSecond, double verticalFov);

    const std::string& name() const { return name_; }
    double duration() const { return keys_.back().time - keys_.front().time; }
    double framesPerSecond() const { return framesPerSecond_; }
    // Frames at t = start + i / fps for every t within the path (both ends included
    // when the duration is a whole number of frames).
    int frameCount() const;
    double frameTime(int index) const { return keys_.front().time + index / framesPerSecond_; }

    // The camera at `time` (clamped to the path). Fails when the terrain height is
    // needed and unavailable, or the camera would be below the terrain.
    Result<Camera> sample(double time, const Camera::TerrainHeight& terrainHeight) const;

private:
    // A point of the path: its unit position vector (ECEF direction) and the height that
    // is interpolated (above the terrain or the ellipsoid, see heightsAboveTerrain_).
    struct Position {
        glm::dvec3 direction{};
        double height = 0;
    };
    // The height `key` interpolates (eye_height over the terrain is measured here).
    Result<double> keyHeight(const CameraPathKey& key,
                             const Camera::TerrainHeight& terrainHeight) const;
    // The position at `time`, fraction `s` into the segment from key `segment` to the next.
    Result<Position> interpolatePosition(std::size_t segment, double s, double time,
                                         const Camera::TerrainHeight& terrainHeight) const;
    Result<Position> catmullRom(std::size_t segment, double time,
                                const Camera::TerrainHeight& terrainHeight) const;
    // Sets the camera's height above the ellipsoid; fails below the terrain.
    Status placeHeight(Camera& camera, double height, double time,
                       const Camera::TerrainHeight& terrainHeight) const;
    // Both keys look at a point: look at the interpolated point.
    Status lookAtInterpolatedTarget(Camera& camera, const CameraPathKey& a, const CameraPathKey& b,
                                    double s, const Camera::TerrainHeight& terrainHeight) const;
    // The keys' orientations slerped in their local frames, placed in the frame at `at`.
    glm::dmat3 interpolatedAxes(const Geodetic& at, const CameraPathKey& a, const CameraPathKey& b,
                                double s) const;

    std::string name_;
    std::vector<CameraPathKey> keys_;
    PathInterpolation interpolation_;
    double framesPerSecond_;
    double verticalFov_;
    bool heightsAboveTerrain_ = false;
};

}  // namespace sylva
