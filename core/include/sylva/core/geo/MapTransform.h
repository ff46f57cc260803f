// MapTransform: the map transform of spherical geometry clipmaps (seed 001 §5.3.3),
// in a numerically stable form. The static rings live on a view hemisphere whose
// pole is the viewer; a vertex at view angle thetaTilde (radians from the viewer's
// nadir) and bearing (radians clockwise from north) maps to a geodetic position.
//
// The seed rotates the hemisphere point and takes acos/atan2 of the result, which in
// single precision cannot resolve view angles below ~1e-4 rad (it replaces the inner
// rings by an approximation, §5.5.1). Here the transform returns the *offsets*
// (dLat, dLon) from the viewer, computed from sin(thetaTilde) and sin^2(thetaTilde/2)
// so that every term keeps its relative precision: exact at every scale, in float
// on the GPU as in double on the CPU. ecefOffset() turns offsets and a height into a
// position relative to the viewer's ground point, again without cancellation. The
// GLSL in shaders/terrain/map_transform.glsl is a line-by-line copy; tests compare
// both precisions against the direct formulas.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "sylva/core/geo/Ellipsoid.h"

namespace sylva {

template <typename Real>
struct MapOffset {
    Real latitude;   // dLat, radians
    Real longitude;  // dLon, radians, in (-pi, pi]
};

template <typename Real>
class MapTransform {
public:
    // Viewer's ground point (geodetic latitude, radians).
    explicit MapTransform(Real viewerLatitude)
        : sinLat_(std::sin(viewerLatitude)),
          cosLat_(std::cos(viewerLatitude)),
          latitude_(viewerLatitude) {}
    MapTransform(Real sinLatitude, Real cosLatitude, Real latitude)
        : sinLat_(sinLatitude), cosLat_(cosLatitude), latitude_(latitude) {}

    // Offsets of the point at view angle `thetaTilde` in direction `bearing`.
    MapOffset<Real> offset(Real thetaTilde, Real sinBearing, Real cosBearing) const {
        const Real sinTheta = std::sin(thetaTilde);
        const Real halfSin = std::sin(thetaTilde * Real(0.5));
        const Real oneMinusCos = Real(2) * halfSin * halfSin;  // 1 - cos(thetaTilde)
        // The point in the viewer's meridian frame (x towards lon 0 of the viewer, z north).
        const Real px = cosLat_ * (Real(1) - oneMinusCos) - sinLat_ * sinTheta * cosBearing;
        const Real py = sinTheta * sinBearing;
        // sin(lat2) - sin(lat1) without cancellation.
        const Real deltaSin = -sinLat_ * oneMinusCos + cosLat_ * sinTheta * cosBearing;
        const Real cosLat2 = std::sqrt(px * px + py * py);
        const Real sinLat2 = sinLat_ + deltaSin;
        // sin(lat2 - lat1) = s2 c1 - s1 c2 = dS (c1 + s1 (s1 + s2) / (c1 + c2)).
        const Real denominator = cosLat_ + cosLat2;
        Real sinDelta;
        if (denominator > Real(1e-6)) {
            sinDelta = deltaSin * (cosLat_ + sinLat_ * (sinLat_ + sinLat2) / denominator);
        } else {
            sinDelta = sinLat2 * cosLat_ - sinLat_ * cosLat2;  // both near a pole: no cancellation
        }
        MapOffset<Real> result;
        // sinDelta is exact; asin is well conditioned while |dLat| < pi/2 (always: the
        // rings cover at most a hemisphere).
        result.latitude = std::asin(std::clamp(sinDelta, Real(-1), Real(1)));
        result.longitude = std::atan2(py, px);
        return result;
    }

    // Position of (lat1 + dLat, lon1 + dLon, height) minus the ground point
    // (lat1, lon1, 0), in the viewer's meridian frame (ECEF rotated by -lon1 about z).
    glm::vec<3, Real> ecefOffset(const MapOffset<Real>& offset, Real height) const {
        constexpr Real a = Real(Ellipsoid::kSemiMajorAxis);
        constexpr Real e2 = Real(Ellipsoid::kEccentricitySquared);
        const Real halfDLat = offset.latitude * Real(0.5);
        const Real middle = latitude_ + halfDLat;
        const Real sinHalf = std::sin(halfDLat);
        const Real dSin = Real(2) * std::cos(middle) * sinHalf;   // sin lat2 - sin lat1
        const Real dCos = Real(-2) * std::sin(middle) * sinHalf;  // cos lat2 - cos lat1
        const Real sinLat2 = sinLat_ + dSin;
        const Real cosLat2 = cosLat_ + dCos;
        const Real w1 = std::sqrt(Real(1) - e2 * sinLat_ * sinLat_);
        const Real w2 = std::sqrt(Real(1) - e2 * sinLat2 * sinLat2);
        const Real n1 = a / w1;
        const Real n2 = a / w2;
        // N2 - N1 = a (w1 - w2) / (w1 w2), w1 - w2 = e2 (s2^2 - s1^2) / (w1 + w2).
        const Real dN = a * (e2 * dSin * (sinLat2 + sinLat_) / (w1 + w2)) / (w1 * w2);
        const Real halfSinLon = std::sin(offset.longitude * Real(0.5));
        const Real cosLonMinusOne = Real(-2) * halfSinLon * halfSinLon;
        const Real sinLon = std::sin(offset.longitude);
        // N cos(lat) difference, then the three coordinates.
        const Real dNCos = dN * cosLat2 + n1 * dCos;
        const Real nCos2 = n2 * cosLat2;
        glm::vec<3, Real> result;
        result.x = nCos2 * cosLonMinusOne + dNCos + height * cosLat2 * (Real(1) + cosLonMinusOne);
        result.y = (nCos2 + height * cosLat2) * sinLon;
        result.z = (Real(1) - e2) * (dN * sinLat2 + n1 * dSin) + height * sinLat2;
        return result;
    }

private:
    Real sinLat_;
    Real cosLat_;
    Real latitude_;
};

}  // namespace sylva
