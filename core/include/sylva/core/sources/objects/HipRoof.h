// HipRoof (issue 17): the hip roof of a convex footprint with every side sloping at one pitch — the
// roof of the polygon's straight skeleton (Aichholzer, Aurenhammer, Alberts & Gärtner
// 1995, "A novel type of skeleton for polygons"; Felkel & Obdržálek 1998 for the general
// event algorithm). For a convex polygon the wavefront never splits, so the skeleton is
// found without events: the roof height over a point p is the lower envelope
//     z(p) = eaves + tan(pitch) · min_i d_i(p),
// d_i the distance of p from side i's line, and side i's roof face is the part of the
// footprint where side i is the nearest: the footprint clipped by the half-planes
// d_i(p) ≤ d_j(p), which are linear in p inside a convex polygon (Sutherland–Hodgman).
// A rectangle gives the classic hip roof (ridge length = length − width), a regular
// polygon a pyramid.
//
// Input: a convex ring in a local metric plane (x east, y north), counter-clockwise, open
// (no repeated first corner), at least three corners; non-convex rings are a programmer
// error of the caller (BuildingExtruder asks only for convex ones; SYLVA_CHECK).
// Output: one convex face per side (empty faces left out), each counter-clockwise seen
// from above, corners as (x, y, height) with heights from `eaves` (metres).
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace sylva {

struct HipRoofFace {
    std::size_t side = 0;             // the footprint side (ring[side] → ring[side + 1])
    std::vector<glm::dvec3> corners;  // (x, y, height)
};

std::vector<HipRoofFace> hipRoof(const std::vector<glm::dvec2>& ring, double eaves, double pitch);

}  // namespace sylva
