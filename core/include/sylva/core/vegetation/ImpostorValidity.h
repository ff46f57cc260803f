// ImpostorValidity: the two-level impostor validity test of seed 000 ch. 7 (a Guaranteed
// Valid Volume in front of Schaufler's 1995 error metric), for the group impostors of the
// `impostors` vegetation method (seed 004 §3.5: far instances of a tile drawn as one
// image, rendered into a texture and re-used while valid).
//
// Geometry (Schaufler 1995, seed 000 Fig. 7.1). An impostor captured from viewpoint v
// is a plane through the centre c of the group's bounding box, perpendicular to c − v.
// A point p of the group is drawn where the ray from v through p meets that plane, at
// q(p). Seen from another viewpoint v', the impostor is wrong by the angle ∠(p − v',
// q(p) − v'). The precise metric (stage 2) is the largest such angle over the eight box
// corners. The set of viewpoints that see the segment p q(p) under exactly the error
// angle ε is a circle through p and q of radius r = |pq| / (2 sin ε) (central-angle
// theorem, seed 000 Eq. 7.5), rotated about the segment's line; viewpoints inside it
// see a larger angle. The guaranteed valid volume (stage 1) is the sphere about the
// current viewpoint that stays outside all eight of these spindles: its radius is the
// distance to the nearest one, |v' − C| − r with C the circle centre on v''s side.
//
// Algorithm 1 of the seed: inside the GVV → valid, nothing else to do; else the precise
// metric decides whether the impostor is regenerated; either way the GVV is rebuilt
// about the current viewpoint. Counters record each outcome.
//
// Frames: any Cartesian frame in metres, the same for the box, the capture viewpoint and
// the viewpoints tested (the renderer uses the group's tile frame, ECEF axes). Angles are
// radians. Pure functions; no failure modes (degenerate boxes are valid points).
#pragma once

#include <cstddef>

#include <glm/glm.hpp>

namespace sylva {

// One captured impostor: where it was rendered from and what it shows.
struct ImpostorCapture {
    glm::dvec3 viewpoint{0.0};
    glm::dvec3 boxMinimum{0.0};  // the group's axis-aligned bounding box
    glm::dvec3 boxMaximum{0.0};
};

// What the two-level test decided for one impostor in one frame.
enum class ImpostorVerdict {
    InsideGuaranteedVolume,  // stage 1: valid without evaluating the metric
    ValidByMetric,           // stage 2 evaluated: still within the error angle
    Regenerate,              // stage 2 evaluated: the impostor must be rendered again
};

struct ImpostorValidityCounters {
    std::size_t tests = 0;
    std::size_t insideGuaranteedVolume = 0;
    std::size_t validByMetric = 0;
    std::size_t regenerated = 0;
};

// One impostor's state across frames: its capture and the current GVV sphere.
struct ImpostorGuard {
    ImpostorCapture capture;
    glm::dvec3 volumeCentre{0.0};
    double volumeRadius = -1.0;  // < 0: no GVV yet (the next test evaluates the metric)
};

class ImpostorValidity {
public:
    // The largest angle (radians) under which an eight-corner point of the box and its
    // impostor image are seen apart from `viewpoint` (Schaufler's metric, stage 2).
    static double impostorError(const ImpostorCapture& capture, const glm::dvec3& viewpoint);

    // The radius (metres) of the sphere about `viewpoint` inside which the impostor's
    // error stays ≤ errorAngle for every box corner; ≤ 0 when it already exceeds it.
    // errorAngle in (0, π/2).
    static double guaranteedValidRadius(const ImpostorCapture& capture, const glm::dvec3& viewpoint,
                                        double errorAngle);

    // The same for one segment p q whose points are seen as one from the line through
    // them: distance from `viewpoint` to the spindle in which |pq| subtends ≥ errorAngle.
    static double segmentClearance(const glm::dvec3& p, const glm::dvec3& q,
                                   const glm::dvec3& viewpoint, double errorAngle);

    // Where the impostor of `capture` draws point `p` (the ray from the capture viewpoint
    // through p meets the plane through the box centre facing the viewpoint).
    static glm::dvec3 imageOf(const ImpostorCapture& capture, const glm::dvec3& p);

    // The viewpoint reached by moving `distance` metres from `from` toward the nearest
    // invalid viewpoint (the worst direction, for tests and diagnostics).
    static glm::dvec3 worstMove(const ImpostorCapture& capture, const glm::dvec3& from,
                                double errorAngle, double distance);

    explicit ImpostorValidity(double errorAngle) : errorAngle_(errorAngle) {}

    // A fresh capture from `viewpoint`: the guard's GVV is built about it.
    void recapture(ImpostorGuard& guard, const ImpostorCapture& capture) const;

    // Algorithm 1 of seed 000 ch. 7 at `viewpoint`. On Regenerate the caller renders the
    // impostor again and calls recapture(); otherwise the GVV is rebuilt here.
    ImpostorVerdict test(ImpostorGuard& guard, const glm::dvec3& viewpoint);

    double errorAngle() const { return errorAngle_; }
    const ImpostorValidityCounters& counters() const { return counters_; }
    void resetCounters() { counters_ = {}; }

private:
    double errorAngle_;
    ImpostorValidityCounters counters_;
};

}  // namespace sylva
