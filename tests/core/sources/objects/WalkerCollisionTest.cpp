// WalkerCollision on hand-built buildings (boxes with outward faces in a tile at 10° N,
// 20° E): a walk into a wall stops a body radius short of it, measured perpendicular to
// the wall also for an oblique walk, whose rest slides along the wall (positions against
// the analytic ones); a plinth below the step height is stepped onto, a wall above it is
// not climbed; a walker falls onto a roof below the feet; a camera inside a building
// walks out; without meshes nothing changes.
#include "sylva/core/sources/objects/WalkerCollision.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scene/CameraNavigation.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

struct Site {
    Geodetic origin{10.0 * kDegree, 20.0 * kDegree, 0.0};
    glm::dvec3 ecef = Ellipsoid::toEcef(origin);
    glm::dmat3 frame = Ellipsoid::localFrame(origin.latitude, origin.longitude);

    // (east, north) metres of an ECEF point in the tangent plane.
    glm::dvec2 plan(const glm::dvec3& point) const {
        return {glm::dot(point - ecef, frame[0]), glm::dot(point - ecef, frame[1])};
    }
    // A walker standing on the ground (height 0) at (east, north), looking along `heading`.
    Camera walker(double east, double north, double heading, const WalkerBody& body) const {
        Geodetic at = Ellipsoid::toGeodetic(ecef + frame * glm::dvec3(east, north, 0.0));
        at.height = body.eyeHeight;
        Camera camera;
        camera.geodetic = at;
        camera.position = Ellipsoid::toEcef(at);
        camera.axes = Camera::axesFromAngles(at, heading * kDegree, 0.0, 0.0);
        return camera;
    }
};

// An east/north/up box [low, high] (metres about the site) with outward counter-clockwise
// faces, appended to `tile`'s static triangles.
void addBox(MeshTile& tile, const Site& site, const glm::dvec3& low, const glm::dvec3& high) {
    const int faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 1, 3, 2},
                             {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}};
    const auto first = std::uint32_t(tile.geometry.vertices.size());
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 local((corner >> 2 & 1) ? high.x : low.x,
                               (corner >> 1 & 1) ? high.y : low.y, (corner & 1) ? high.z : low.z);
        MeshVertex vertex;
        vertex.position = glm::vec3(site.ecef + site.frame * local - tile.origin);
        tile.geometry.vertices.push_back(vertex);
    }
    for (const auto& face : faces) {
        for (int k : {0, 1, 2, 0, 2, 3}) {
            tile.geometry.indices.push_back(first + std::uint32_t(face[k]));
        }
    }
}

// A long 6 m house north of the walker (north 10..20) and a 0.3 m plinth south of it.
MeshCollision village(const Site& site) {
    auto tile = std::make_shared<MeshTile>();
    tile->origin = site.ecef;
    addBox(*tile, site, {-50, 10, -0.5}, {50, 20, 6});
    addBox(*tile, site, {-5, -20, -0.5}, {5, -10, 0.3});
    tile->boundsCenter = site.ecef;
    tile->boundsRadius = 100.0;
    MeshCollision collision;
    collision.setTiles({tile});
    return collision;
}

TEST(WalkerCollision, AWallStopsTheBodyARadiusShortAndTheRestSlidesAlongIt) {
    const Site site;
    const WalkerBody body;
    const MeshCollision meshes = village(site);
    // Straight at the wall: 15 m asked, 9.7 walked.
    Camera from = site.walker(0, 0, 0, body);
    Camera to = CameraNavigation::walk(from, 15.0, 0.0);
    Camera reached = WalkerCollision::step(meshes, from, to, body);
    glm::dvec2 at = site.plan(reached.position);
    EXPECT_NEAR(at.y, 10.0 - body.radius, 0.01);
    EXPECT_NEAR(at.x, 0.0, 0.01);
    EXPECT_NEAR(reached.geodetic.height, from.geodetic.height, 1e-6);
    EXPECT_NEAR(reached.heading(), from.heading(), 1e-6);
    // At 45°: stops 0.3 m from the wall (perpendicular), 9.7·√2 m along the walk; the rest
    // of the 15 m slides east by its component along the wall.
    from = site.walker(0, 0, 45, body);
    to = CameraNavigation::walk(from, 15.0, 0.0);
    reached = WalkerCollision::step(meshes, from, to, body);
    at = site.plan(reached.position);
    const double walked = (10.0 - body.radius) * std::sqrt(2.0);
    EXPECT_NEAR(at.y, 10.0 - body.radius, 0.01);
    EXPECT_NEAR(at.x, (10.0 - body.radius) + (15.0 - walked) / std::sqrt(2.0), 0.01);
    // Away from the wall and along it: not held.
    from = site.walker(0, 9.7, 90, body);
    to = CameraNavigation::walk(from, 5.0, 0.0);
    EXPECT_NEAR(glm::length(WalkerCollision::step(meshes, from, to, body).position - to.position),
                0.0, 1e-6);
    // Without meshes the walk is the walk.
    const MeshCollision none;
    from = site.walker(0, 0, 0, body);
    to = CameraNavigation::walk(from, 15.0, 0.0);
    EXPECT_NEAR(glm::length(WalkerCollision::step(none, from, to, body).position - to.position),
                0.0, 1e-9);
}

TEST(WalkerCollision, StepsOntoAPlinthNotOntoARoofAndFallsOntoARoofBelow) {
    const Site site;
    const WalkerBody body;
    const MeshCollision meshes = village(site);
    // South onto the 0.3 m plinth: not a wall (below the knee probes), stood on.
    const Camera from = site.walker(0, 0, 180, body);
    const Camera to = CameraNavigation::walk(from, 15.0, 0.0);
    const Camera reached = WalkerCollision::step(meshes, from, to, body);
    EXPECT_NEAR(glm::length(reached.position - to.position), 0.0, 1e-6);
    const double feet = from.geodetic.height - body.eyeHeight;
    EXPECT_NEAR(WalkerCollision::standingHeight(meshes, reached.geodetic.latitude,
                                                reached.geodetic.longitude, feet, 0.0, body),
                0.3, 1e-3);
    // Under the 6 m roof with the feet on the ground: the roof is out of reach.
    const Camera inside = site.walker(0, 15, 0, body);
    EXPECT_NEAR(WalkerCollision::standingHeight(meshes, inside.geodetic.latitude,
                                                inside.geodetic.longitude, 0.0, 0.0, body),
                0.0, 1e-9);
    // Feet 7 m up (a walker dropped from a flight): on the roof.
    EXPECT_NEAR(WalkerCollision::standingHeight(meshes, inside.geodetic.latitude,
                                                inside.geodetic.longitude, 7.0, 0.0, body),
                6.0, 1e-3);
    // Terrain above the plinth there: the terrain.
    EXPECT_NEAR(WalkerCollision::standingHeight(meshes, reached.geodetic.latitude,
                                                reached.geodetic.longitude, 0.0, 0.4, body),
                0.4, 1e-9);
}

TEST(WalkerCollision, ACameraInsideABuildingWalksOut) {
    const Site site;
    const WalkerBody body;
    const MeshCollision meshes = village(site);
    const Camera from = site.walker(0, 15, 180, body);
    const Camera to = CameraNavigation::walk(from, 12.0, 0.0);
    const Camera reached = WalkerCollision::step(meshes, from, to, body);
    EXPECT_NEAR(glm::length(reached.position - to.position), 0.0, 1e-6);
}

}  // namespace
}  // namespace sylva
