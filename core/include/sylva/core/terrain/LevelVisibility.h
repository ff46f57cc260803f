// LevelVisibility: which ring levels of the spherical clipmap can be seen (seed 001
// §5.4.5). The coarsest level is bounded by the horizon: terrain beyond the view
// angle acos(r / (r + h)) is hidden by the curvature; mountains up to
// `maxTerrainHeight` can rise above it from further away, which adds
// acos(r / (r + maxTerrainHeight)) (the seed's "safety factor", made exact for a
// sphere). The finest level is bounded by the pixel size s = h * 2 tan(fov / 2) /
// pixels at the nadir: rings smaller than theta_min = s / r cover less than a pixel.
#pragma once

namespace sylva {

struct LevelRange {
    int coarsest = 1;  // lowest level index drawn (largest rings)
    int finest = 1;    // highest level index drawn; its fill disk closes the nadir
};

class LevelVisibility {
public:
    // Heights in metres; fov in radians (vertical); pixels: the image height.
    static double horizonViewAngle(double heightAboveEllipsoid, double maxTerrainHeight);
    static double pixelViewAngle(double heightAboveTerrain, double verticalFov, int pixels);
    static LevelRange visibleLevels(double heightAboveEllipsoid, double heightAboveTerrain,
                                    double maxTerrainHeight, double verticalFov, int pixels,
                                    int maxLevel);
};

}  // namespace sylva
