// LodSelector with occlusion culling (issue 21): splitting a frame into distance rings
// selects every instance exactly once; a depth wall in front of the forest hides every
// instance (and whole batches), counted as occluded; a sky-only depth image hides nothing
// and changes nothing; the drawn sphere holds ellipsoids that stick out of the LoD's box.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/vegetation/LodSelector.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180;
constexpr int kWidth = 160, kHeight = 90;

// One ellipsoid crown 6 m up and a trunk line; the box holds both.
PlantAsset makeTree(float crownRadius = 2.0f) {
    PlantAsset asset;
    asset.name = "tree";
    LodEllipsoid crown;
    crown.center = glm::vec3(0.0f, 0.0f, 6.0f);
    crown.radii = glm::vec3(crownRadius);
    crown.weight = 1.0f;
    asset.lod.ellipsoids.push_back(crown);
    LodLine trunk;
    trunk.end = glm::vec3(0.0f, 0.0f, 6.0f);
    trunk.startRadius = trunk.endRadius = 0.2f;
    asset.lod.lines.push_back(trunk);
    asset.lod.boundsMinimum = glm::vec3(-2.0f, -2.0f, 0.0f);
    asset.lod.boundsMaximum = glm::vec3(2.0f, 2.0f, 8.0f);
    return asset;
}

class LodSelectorOcclusion : public ::testing::Test {
protected:
    void SetUp() override {
        lods_.push_back(LodSelector::describe(makeTree(), 0.35));
        camera_.geodetic = {45.0 * kDegree, 7.0 * kDegree, 1.7};
        camera_.position = Ellipsoid::toEcef(camera_.geodetic);
        camera_.axes = Camera::axesFromAngles(camera_.geodetic, 0.0, 0.0, 0.0);
        camera_.verticalFov = 60 * kDegree;
        settings_.pixelAngle = 2 * std::tan(30 * kDegree) / kHeight;
        settings_.near = 0.5;
        LodSelector::setFrustum(settings_, camera_.verticalFov, double(kWidth) / kHeight);
        // A forest of 20 × 20 trees, 7 m apart, from 20 m ahead, in four batches.
        for (int b = 0; b < 4; ++b) {
            std::vector<InstancePlacement> placements;
            for (int i = 0; i < 100; ++i) {
                placements.push_back(
                    at(20.0 + 7.0 * (b / 2 * 10 + i / 10), -70.0 + 7.0 * (b % 2 * 10 + i % 10)));
            }
            batches_.push_back(LodSelector::makeBatch(placements[0].baseEcef, placements, lods_));
        }
        for (const InstanceBatch& batch : batches_) {
            pointers_.push_back(&batch);
        }
    }
    InstancePlacement at(double north, double east) const {
        InstancePlacement p;
        p.latitude = camera_.geodetic.latitude + north / 6367000.0;
        p.longitude =
            camera_.geodetic.longitude + east / (6367000.0 * std::cos(camera_.geodetic.latitude));
        p.baseEcef = Ellipsoid::toEcef({p.latitude, p.longitude, 0.0});
        return p;
    }
    // The pyramid of a depth image filled with `depth` (reversed-Z, near / distance).
    DepthPyramid pyramidOf(float depth) const {
        const double f = 1.0 / std::tan(camera_.verticalFov / 2);
        glm::dmat4 p(0.0);
        p[0][0] = f * kHeight / kWidth;
        p[1][1] = f;
        p[2][3] = -1.0;
        p[3][2] = settings_.near;
        DepthPyramid pyramid;
        pyramid.build(std::vector<float>(std::size_t(kWidth) * kHeight, depth), kWidth, kHeight, p,
                      settings_.near);
        return pyramid;
    }
    // The drawn instances as raw bytes, sorted (ring order differs from a single pass).
    static std::vector<std::vector<char>> sortedInstances(const std::vector<LodSelection>& parts) {
        std::vector<std::vector<char>> out;
        for (const LodSelection& part : parts) {
            for (const DrawInstance& d : part.instances) {
                const char* bytes = reinterpret_cast<const char*>(&d);
                out.emplace_back(bytes, bytes + sizeof d);
            }
        }
        std::sort(out.begin(), out.end());
        return out;
    }
    std::vector<SpeciesLod> lods_;
    Camera camera_;
    LodSelectionSettings settings_;
    std::vector<InstanceBatch> batches_;
    std::vector<const InstanceBatch*> pointers_;
    LodSelector selector_;
};

TEST_F(LodSelectorOcclusion, DistanceRingsSelectEveryInstanceExactlyOnce) {
    LodSelection whole;
    selector_.select(pointers_, lods_, camera_, settings_, whole);
    ASSERT_GT(whole.visibleInstances, 100u);
    std::vector<LodSelection> rings(3);
    const double limits[4] = {0.0, 50.0, 90.0, 0.0};
    std::size_t visible = 0;
    for (int r = 0; r < 3; ++r) {
        LodSelectionSettings ring = settings_;
        ring.minimumDistance = limits[r];
        ring.maximumDistance = limits[r + 1];
        selector_.select(pointers_, lods_, camera_, ring, rings[std::size_t(r)]);
        EXPECT_GT(rings[std::size_t(r)].visibleInstances, 0u) << "ring " << r;
        visible += rings[std::size_t(r)].visibleInstances;
    }
    EXPECT_EQ(visible, whole.visibleInstances);
    EXPECT_EQ(sortedInstances(rings), sortedInstances({whole}));
}

TEST_F(LodSelectorOcclusion, AWallInFrontHidesEverythingAndSkyHidesNothing) {
    LodSelection plain;
    selector_.select(pointers_, lods_, camera_, settings_, plain);
    EXPECT_EQ(plain.occludedInstances, 0u);

    const DepthPyramid sky = pyramidOf(0.0f);
    LodSelectionSettings withSky = settings_;
    withSky.occlusion = &sky;
    LodSelection open;
    selector_.select(pointers_, lods_, camera_, withSky, open);
    EXPECT_EQ(open.occludedInstances, 0u);
    EXPECT_EQ(sortedInstances({open}), sortedInstances({plain}));

    // A wall 10 m ahead: every tree (nearest 20 m, crowns 2 m) is behind it.
    const DepthPyramid wall = pyramidOf(float(settings_.near / 10.0));
    LodSelectionSettings withWall = settings_;
    withWall.occlusion = &wall;
    LodSelection hidden;
    selector_.select(pointers_, lods_, camera_, withWall, hidden);
    EXPECT_EQ(hidden.visibleInstances, 0u);
    EXPECT_TRUE(hidden.instances.empty());
    // Every instance that was visible is counted; batches hidden as a whole count all
    // their instances (also those outside the frustum), so the count may be larger.
    EXPECT_GE(hidden.occludedInstances, plain.visibleInstances);
    EXPECT_LE(hidden.occludedInstances, 400u);

    // A batch 150 m ahead reaching out of the frustum's right side (east 100–219 m; the side
    // is at ~155 m) is hidden as a whole: all of its instances count, also those the
    // frustum would have dropped.
    std::vector<InstancePlacement> wide;
    for (int i = 0; i < 100; ++i) {
        wide.push_back(at(150.0, 100.0 + 1.2 * i));
    }
    const InstanceBatch wideBatch = LodSelector::makeBatch(wide[0].baseEcef, wide, lods_);
    LodSelection wideVisible;
    selector_.select({&wideBatch}, lods_, camera_, settings_, wideVisible);
    EXPECT_GT(wideVisible.visibleInstances, 20u);
    EXPECT_LT(wideVisible.visibleInstances, 80u);
    withWall.occlusion = &wall;
    selector_.select({&wideBatch}, lods_, camera_, withWall, hidden);
    EXPECT_EQ(hidden.occludedInstances, 100u);

    // A wall 25 m ahead hides only the trees behind it; the first row stays.
    const DepthPyramid nearWall = pyramidOf(float(settings_.near / 25.0));
    withWall.occlusion = &nearWall;
    selector_.select(pointers_, lods_, camera_, withWall, hidden);
    EXPECT_GT(hidden.visibleInstances, 0u);
    EXPECT_GT(hidden.occludedInstances, 0u);
    EXPECT_LT(hidden.visibleInstances, plain.visibleInstances);
}

// A coarse ellipsoid wider than the LoD's box: the drawn sphere grows to hold it, so an
// instance whose box sphere is behind a wall but whose crown reaches in front is kept.
TEST_F(LodSelectorOcclusion, TheDrawnSphereHoldsEllipsoidsOutsideTheBox) {
    const PlantAsset wide = makeTree(6.0f);  // crown radius 6 m, box still ±2 m × 8 m
    const SpeciesLod lod = LodSelector::describe(wide, 0.35);
    EXPECT_GE(lod.drawnRadius, glm::length(glm::vec3(0, 0, 6) - lod.sphereCenter) + 6.0f);
    EXPECT_GT(lod.drawnRadius, lod.sphereRadius);
    const std::vector<SpeciesLod> lods{lod};
    const InstanceBatch one = LodSelector::makeBatch(at(30.0, 0.0).baseEcef, {at(30.0, 0.0)}, lods);
    // The box sphere (radius 4.9 m) ends 25.1 m ahead, the crown reaches 24 m: a wall at
    // 24.5 m would hide the box sphere but not the crown.
    const DepthPyramid wall = pyramidOf(float(settings_.near / 24.5));
    LodSelectionSettings withWall = settings_;
    withWall.occlusion = &wall;
    LodSelection out;
    selector_.select({&one}, lods, camera_, withWall, out);
    EXPECT_EQ(out.visibleInstances, 1u);
    EXPECT_EQ(out.occludedInstances, 0u);
}

}  // namespace
}  // namespace sylva
