// MeshCollision: the grid lookup of a tile's static triangles against an independent
// brute-force oracle (plane crossing and edge-side tests over every triangle) on random
// segments and triangles; front faces only; placed model parts through their placement
// (scaled, turned, mirrored: still hit from the outside) against the analytic faces of a cube;
// tiles dropped from the set are not hit.
#include "sylva/core/sources/objects/MeshCollision.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "sylva/core/geo/Ellipsoid.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// The local east/north/up frame and origin of the test tile (10° N, 20° E, 200 m).
struct Site {
    Geodetic origin{10.0 * kDegree, 20.0 * kDegree, 200.0};
    glm::dvec3 ecef = Ellipsoid::toEcef(origin);
    glm::dmat3 frame = Ellipsoid::localFrame(origin.latitude, origin.longitude);
    glm::dvec3 at(double east, double north, double up) const {
        return ecef + frame * glm::dvec3(east, north, up);
    }
};

// The earliest front-face crossing by brute force: the plane's crossing point, then the
// point on the inner side of all three edges.
double oracleFraction(const MeshTile& tile, const glm::dvec3& start, const glm::dvec3& end) {
    const glm::dvec3 a = start - tile.origin, d = end - start;
    double best = std::numeric_limits<double>::infinity();
    const auto& v = tile.geometry.vertices;
    const auto& index = tile.geometry.indices;
    for (std::size_t i = 0; i < index.size(); i += 3) {
        const glm::dvec3 p0(v[index[i]].position), p1(v[index[i + 1]].position),
            p2(v[index[i + 2]].position);
        const glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
        const double along = glm::dot(d, n);
        if (along >= 0.0) {
            continue;
        }
        const double t = glm::dot(p0 - a, n) / along;
        if (t < 0.0 || t > 1.0) {
            continue;
        }
        const glm::dvec3 x = a + d * t;
        if (glm::dot(glm::cross(p1 - p0, x - p0), n) >= 0 &&
            glm::dot(glm::cross(p2 - p1, x - p1), n) >= 0 &&
            glm::dot(glm::cross(p0 - p2, x - p2), n) >= 0) {
            best = std::min(best, t);
        }
    }
    return best;
}

TEST(MeshCollision, GridFindsTheSameFirstHitsAsBruteForce) {
    const Site site;
    auto tile = std::make_shared<MeshTile>();
    tile->origin = site.ecef;
    std::mt19937 random(5);
    std::uniform_real_distribution<double> plan(-600.0, 600.0), size(-15.0, 15.0),
        height(0.0, 30.0);
    for (int i = 0; i < 3000; ++i) {
        const glm::dvec3 centre(plan(random), plan(random), height(random));
        for (int corner = 0; corner < 3; ++corner) {
            MeshVertex vertex;
            vertex.position = glm::vec3(
                site.frame * (centre + glm::dvec3(size(random), size(random), size(random))));
            tile->geometry.indices.push_back(std::uint32_t(tile->geometry.vertices.size()));
            tile->geometry.vertices.push_back(vertex);
        }
    }
    tile->boundsCenter = site.ecef;
    tile->boundsRadius = 1000.0;
    MeshCollision collision;
    collision.setTiles({tile});
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
        // Short walker-like segments, long diagonal ones and vertical ones.
        const glm::dvec3 start = site.at(plan(random), plan(random), height(random));
        const double reach = i % 3 == 0 ? 5.0 : i % 3 == 1 ? 200.0 : 0.0;
        const glm::dvec3 end =
            i % 3 == 2 ? start - site.frame[2] * 40.0
                       : start + site.frame * glm::dvec3(size(random) * reach, size(random) * reach,
                                                         size(random));
        const double expected = oracleFraction(*tile, start, end);
        const std::optional<MeshHit> hit = collision.firstHit(start, end);
        ASSERT_EQ(hit.has_value(), std::isfinite(expected)) << "segment " << i;
        if (hit) {
            ++hits;
            EXPECT_NEAR(hit->fraction, expected, 1e-7) << "segment " << i;
            EXPECT_LT(glm::dot(hit->normal, end - start), 0.0) << "faces the start";
        }
    }
    EXPECT_GT(hits, 200);  // the comparison is not vacuous
}

// A unit cube (-0.5..0.5) with outward counter-clockwise faces, as one model part.
std::shared_ptr<MeshModel> unitCube() {
    auto model = std::make_shared<MeshModel>();
    ModelPart part;
    part.name = "cube";
    const int faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 1, 3, 2},
                             {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}};
    for (int corner = 0; corner < 8; ++corner) {
        MeshVertex vertex;
        vertex.position =
            glm::vec3((corner >> 2 & 1) - 0.5f, (corner >> 1 & 1) - 0.5f, (corner & 1) - 0.5f);
        part.geometry.vertices.push_back(vertex);
    }
    for (const auto& face : faces) {
        for (int k : {0, 1, 2, 0, 2, 3}) {
            part.geometry.indices.push_back(std::uint32_t(face[k]));
        }
    }
    model->parts.push_back(part);
    model->boundsRadius = std::sqrt(3.0) / 2;
    return model;
}

TEST(MeshCollision, PlacedModelsAreHitOnTheirScaledTurnedAndMirroredFaces) {
    const Site site;
    auto tile = std::make_shared<MeshTile>();
    tile->origin = site.ecef;
    tile->model = unitCube();
    tile->boundsCenter = site.ecef;
    tile->boundsRadius = 200.0;
    // A 4 m cube centred 30 m east, 2 m up; a 6 m one 60 m north turned by 90° and
    // mirrored (its faces wind the other way in ECEF; the outside stays the outside).
    ModelPlacement plain;
    plain.position = site.at(30, 0, 2);
    plain.axes = site.frame * 4.0;
    ModelPlacement mirrored;
    mirrored.position = site.at(0, 60, 3);
    mirrored.axes = site.frame *
                    glm::dmat3(glm::dvec3(0, -6, 0), glm::dvec3(6, 0, 0), glm::dvec3(0, 0, 6)) *
                    glm::dmat3(glm::dvec3(-1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1));
    tile->placements = {plain, mirrored};
    MeshCollision collision;
    collision.setTiles({tile});

    // East into the first cube's west face (east = 28): 28 of 100 m.
    std::optional<MeshHit> hit = collision.firstHit(site.at(0, 0, 1), site.at(100, 0, 1));
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->fraction, 0.28, 1e-9);
    EXPECT_NEAR(glm::dot(hit->normal, site.frame[0]), -1.0, 1e-9);
    // North into the mirrored cube's south face (north = 57).
    hit = collision.firstHit(site.at(0, 0, 1), site.at(0, 100, 1));
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->fraction, 0.57, 1e-9);
    EXPECT_NEAR(glm::dot(hit->normal, site.frame[1]), -1.0, 1e-9);
    // Down onto its top (up = 6) from 10 m.
    hit = collision.firstHit(site.at(0, 60, 10), site.at(0, 60, 0));
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->fraction, 0.4, 1e-9);
    EXPECT_NEAR(glm::dot(hit->normal, site.frame[2]), 1.0, 1e-9);
    // From inside outwards: back faces only, nothing hit.
    EXPECT_FALSE(collision.firstHit(site.at(30, 0, 2), site.at(40, 0, 2)));
    EXPECT_FALSE(collision.firstHit(site.at(0, 60, 3), site.at(0, 70, 3)));
    // A tile no longer in the set is not searched.
    collision.setTiles({});
    EXPECT_FALSE(collision.firstHit(site.at(0, 0, 1), site.at(100, 0, 1)));
}

}  // namespace
}  // namespace sylva
