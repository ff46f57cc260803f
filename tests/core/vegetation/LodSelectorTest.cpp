// LodSelector (issue 7): bucket prefixes hold every primitive an error in the bucket may
// draw; culling by frustum, near plane and screen size; the mesh handover lists an
// instance for both the mesh and the primitives; the drawn transform is the instance's;
// the output is the same for any thread count and frame after frame; billboard levels
// and species are limited to what the 16-bit run keys hold.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/vegetation/LodSelector.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180;

// Three ellipsoid levels and a line hierarchy with quasi-continuous intervals.
PlantAsset makeAsset() {
    PlantAsset asset;
    asset.name = "test";
    const float switches[4] = {0.0f, 0.05f, 0.2f, std::numeric_limits<float>::infinity()};
    const int counts[3] = {16, 4, 1};
    for (int level = 2; level >= 0; --level) {
        for (int i = 0; i < counts[level]; ++i) {
            LodEllipsoid e;
            e.center = glm::vec3(float(i % 4) - 1.5f, float(i / 4) - 1.5f, 5.0f);
            e.radii = glm::vec3(0.2f * float(1 << (2 * level)));
            e.errorMinimum = switches[level];
            e.errorMaximum = switches[level + 1];
            e.level = std::uint32_t(level);
            e.weight = 1.0f;
            asset.lod.ellipsoids.push_back(e);
        }
    }
    for (int i = 0; i < 50; ++i) {
        LodLine l;
        l.start = glm::vec3(0.0f, 0.0f, float(i) * 0.1f);
        l.end = l.start + glm::vec3(0.0f, 0.0f, 0.1f);
        l.errorMaximum = i == 0 ? std::numeric_limits<float>::infinity() : 0.5f / float(i);
        l.errorMinimum = i == 49 ? 0.0f : 0.5f / float(i + 1);
        asset.lod.lines.push_back(l);
    }
    asset.lod.boundsMinimum = glm::vec3(-3.0f, -3.0f, 0.0f);
    asset.lod.boundsMaximum = glm::vec3(3.0f, 3.0f, 10.0f);
    return asset;
}

TEST(LodSelector, BucketPrefixesHoldEveryPrimitiveTheirErrorsDraw) {
    const PlantAsset asset = makeAsset();
    const double band = 0.35;
    const SpeciesLod lod = LodSelector::describe(asset, band);
    EXPECT_EQ(lod.ellipsoidCount, 21u);
    EXPECT_EQ(lod.lineCount, 50u);
    EXPECT_NEAR(lod.sphereRadius, 0.5f * std::sqrt(6.0f * 6.0f * 2.0f + 100.0f), 1e-5f);
    // Level 0 leaves: radius 0.2 m → mean diameter 0.4 m over 5 pixels.
    EXPECT_NEAR(lod.meshError, 0.4f / 5.0f, 1e-6f);
    for (int b = 0; b + 1 < LodSelector::kBucketCount; ++b) {
        EXPECT_GE(lod.ellipsoidPrefix[b], lod.ellipsoidPrefix[b + 1]);
        EXPECT_GE(lod.linePrefix[b], lod.linePrefix[b + 1]);
        // Any error in the bucket, widened by the fade band, draws only primitives of
        // the prefix.
        const double low = LodSelector::bucketLowerError(b) * std::exp(-band / 2);
        for (std::size_t i = 0; i < asset.lod.ellipsoids.size(); ++i) {
            if (asset.lod.ellipsoids[i].errorMaximum > low) {
                EXPECT_LT(i, lod.ellipsoidPrefix[b]) << "bucket " << b;
            }
        }
        for (std::size_t i = 0; i < asset.lod.lines.size(); ++i) {
            if (asset.lod.lines[i].errorMaximum > low) {
                EXPECT_LT(i, lod.linePrefix[b]) << "bucket " << b;
            }
        }
        // The bucket's largest ellipsoid bounds every ellipsoid an error in it may fade in
        // (the renderer sizes its sprites by it).
        const double high = LodSelector::bucketLowerError(b + 1) * std::exp(band / 2);
        for (const LodEllipsoid& e : asset.lod.ellipsoids) {
            if (e.errorMaximum > low && e.errorMinimum < high) {
                EXPECT_GE(lod.ellipsoidRadius[b], e.radii.x) << "bucket " << b;
            }
        }
    }
    EXPECT_FLOAT_EQ(lod.ellipsoidRadius[LodSelector::kBucketCount - 1], 0.2f * 16.0f);
    EXPECT_EQ(LodSelector::bucketOf(LodSelector::bucketLowerError(10) * 1.01), 10);
    EXPECT_EQ(LodSelector::bucketOf(0.0), 0);
    EXPECT_EQ(LodSelector::bucketOf(1e30), LodSelector::kBucketCount - 1);
}

class LodSelectorScene : public ::testing::Test {
protected:
    void SetUp() override {
        lods_.push_back(LodSelector::describe(makeAsset(), 0.35));
        camera_.geodetic = {45.0 * kDegree, 7.0 * kDegree, 1.7};
        camera_.position = Ellipsoid::toEcef(camera_.geodetic);
        camera_.axes = Camera::axesFromAngles(camera_.geodetic, 0.0, 0.0, 0.0);
        camera_.verticalFov = 60 * kDegree;
        settings_.pixelAngle = 2 * std::tan(30 * kDegree) / 720;
        settings_.near = 0.5;
        LodSelector::setFrustum(settings_, camera_.verticalFov, 16.0 / 9.0);
    }
    // A tree `north` metres north and `east` metres east of the camera.
    InstancePlacement at(double north, double east) const {
        InstancePlacement p;
        p.latitude = camera_.geodetic.latitude + north / 6367000.0;
        p.longitude =
            camera_.geodetic.longitude + east / (6367000.0 * std::cos(camera_.geodetic.latitude));
        p.baseEcef = Ellipsoid::toEcef({p.latitude, p.longitude, 0.0});
        return p;
    }
    std::vector<SpeciesLod> lods_;
    Camera camera_;
    LodSelectionSettings settings_;
    LodSelector selector_;
};

TEST_F(LodSelectorScene, CullsBehindOutsideAndTooSmall) {
    const std::vector<InstancePlacement> placements = {
        at(30, 0),      // visible
        at(-30, 0),     // behind
        at(30, 200),    // far outside the right frustum plane
        at(200000, 0),  // 200 km: under a pixel
        at(100, 40),    // visible
    };
    const InstanceBatch batch = LodSelector::makeBatch(camera_.position, placements, lods_);
    LodSelection out;
    selector_.select({&batch}, lods_, camera_, settings_, out);
    EXPECT_EQ(out.consideredInstances, 5u);
    EXPECT_EQ(out.visibleInstances, 2u);
}

TEST_F(LodSelectorScene, WholeBatchesAreCulledByTheirBounds) {
    std::vector<InstancePlacement> behind, ahead;
    for (int i = 0; i < 100; ++i) {
        behind.push_back(at(-40 - i % 10 * 5, i / 10 * 5));
        ahead.push_back(at(40 + i % 10 * 5, i / 10 * 5 - 20));
    }
    const InstanceBatch back = LodSelector::makeBatch(behind[0].baseEcef, behind, lods_);
    const InstanceBatch front = LodSelector::makeBatch(ahead[0].baseEcef, ahead, lods_);
    EXPECT_GT(back.boundsRadius, 30.0f);
    LodSelection out;
    selector_.select({&back, &front}, lods_, camera_, settings_, out);
    EXPECT_EQ(out.consideredInstances, 200u);
    EXPECT_EQ(out.visibleInstances, 100u);
    settings_.maximumDistance = 20.0;
    selector_.select({&back, &front}, lods_, camera_, settings_, out);
    EXPECT_EQ(out.visibleInstances, 0u);
}

TEST_F(LodSelectorScene, RunsFollowTheErrorAndTheMeshHandover) {
    // The error grows with distance: 0.08 m/px (the mesh error) lies at ~100 m.
    const double meshDistance = lods_[0].meshError / settings_.pixelAngle;
    std::vector<InstancePlacement> placements = {at(meshDistance * 0.5, 0), at(meshDistance, 0),
                                                 at(meshDistance * 3, 0), at(meshDistance * 20, 0)};
    const InstanceBatch batch = LodSelector::makeBatch(camera_.position, placements, lods_);
    LodSelection out;
    selector_.select({&batch}, lods_, camera_, settings_, out);
    EXPECT_EQ(out.visibleInstances, 4u);
    // The instance at the mesh error is drawn twice (mesh and primitives, faded).
    EXPECT_EQ(out.instances.size(), 5u);
    std::size_t mesh = 0, primitives = 0;
    for (const DrawRun& run : out.runs) {
        (run.kind == DrawRun::Kind::Mesh ? mesh : primitives) += run.instanceCount;
        if (run.kind == DrawRun::Kind::Primitives) {
            EXPECT_EQ(run.ellipsoids, lods_[0].ellipsoidPrefix[run.bucket]);
        }
        for (std::uint32_t i = run.firstInstance; i < run.firstInstance + run.instanceCount; ++i) {
            // The tolerated error decides the run: pixel size at the instance.
            const double error = out.instances[i].axisX.w;
            if (run.kind == DrawRun::Kind::Primitives) {
                EXPECT_EQ(LodSelector::bucketOf(error), int(run.bucket));
            }
        }
    }
    EXPECT_EQ(mesh, 2u);
    EXPECT_EQ(primitives, 3u);
    // Without the handover everything is primitives; the Mesh method only meshes.
    settings_.closeUpMesh = false;
    selector_.select({&batch}, lods_, camera_, settings_, out);
    EXPECT_EQ(out.instances.size(), 4u);
    settings_.method = VegetationMethod::Mesh;
    selector_.select({&batch}, lods_, camera_, settings_, out);
    ASSERT_EQ(out.runs.size(), 1u);
    EXPECT_EQ(out.runs[0].kind, DrawRun::Kind::Mesh);
}

TEST_F(LodSelectorScene, RunBucketsMatchTheExactBucketAwayFromBoundaries) {
    // 400 trees from 2 m to 20 km (log-spaced): the selection's fast logarithm puts each
    // into the bucket of its error, except within 0.5 % of a bucket boundary.
    std::vector<InstancePlacement> placements;
    for (int i = 0; i < 400; ++i) {
        placements.push_back(at(2.0 * std::pow(10000.0, i / 399.0), 0.0));
    }
    const InstanceBatch batch = LodSelector::makeBatch(camera_.position, placements, lods_);
    settings_.closeUpMesh = false;
    settings_.minimumPixels = 0.0;
    LodSelection out;
    selector_.select({&batch}, lods_, camera_, settings_, out);
    EXPECT_GT(out.visibleInstances, 350u);
    std::size_t checked = 0;
    for (const DrawRun& run : out.runs) {
        ASSERT_EQ(run.kind, DrawRun::Kind::Primitives);
        for (std::uint32_t i = run.firstInstance; i < run.firstInstance + run.instanceCount; ++i) {
            const double error = out.instances[i].axisX.w;
            const double position =
                std::log(error / LodSelector::kSmallestError) / std::log(LodSelector::kBucketRatio);
            const double fromBoundary = std::abs(position - std::round(position));
            if (fromBoundary > 0.005 && error > LodSelector::kSmallestError) {
                EXPECT_EQ(int(run.bucket), LodSelector::bucketOf(error)) << "error " << error;
                ++checked;
            } else {
                EXPECT_LE(std::abs(int(run.bucket) - LodSelector::bucketOf(error)), 1);
            }
        }
    }
    EXPECT_GT(checked, 300u);
}

TEST_F(LodSelectorScene, DrawnTransformPlacesTheModelInViewSpace) {
    InstancePlacement p = at(50, 10);
    p.scale = 2.0f;
    p.heading = float(90 * kDegree);
    const InstanceBatch batch =
        LodSelector::makeBatch(p.baseEcef + glm::dvec3(1000, -500, 30), {p}, lods_);
    settings_.closeUpMesh = false;
    LodSelection out;
    selector_.select({&batch}, lods_, camera_, settings_, out);
    ASSERT_EQ(out.instances.size(), 1u);
    const DrawInstance& d = out.instances[0];
    // Model point (0, 1, 2) m: heading 90° puts model +Y to the east; scale 2.
    const glm::dvec3 east(-std::sin(p.longitude), std::cos(p.longitude), 0.0);
    const glm::dvec3 up = Ellipsoid::surfaceNormal(p.latitude, p.longitude);
    const glm::dvec3 expectedEcef = p.baseEcef + east * 2.0 + up * 4.0;
    const glm::dvec3 expectedView = camera_.viewRotation() * (expectedEcef - camera_.position);
    const glm::vec3 drawn =
        glm::vec3(d.axisY) * 1.0f + glm::vec3(d.axisZ) * 2.0f + glm::vec3(d.origin);
    EXPECT_NEAR(drawn.x, expectedView.x, 2e-3);
    EXPECT_NEAR(drawn.y, expectedView.y, 2e-3);
    EXPECT_NEAR(drawn.z, expectedView.z, 2e-3);
}

// Bytewise equal selections (instances and runs in the same order).
void expectSameSelection(const LodSelection& a, const LodSelection& b) {
    EXPECT_EQ(a.consideredInstances, b.consideredInstances);
    EXPECT_EQ(a.visibleInstances, b.visibleInstances);
    EXPECT_EQ(a.drawnEllipsoids, b.drawnEllipsoids);
    ASSERT_EQ(a.instances.size(), b.instances.size());
    EXPECT_EQ(std::memcmp(a.instances.data(), b.instances.data(),
                          a.instances.size() * sizeof(DrawInstance)),
              0);
    ASSERT_EQ(a.runs.size(), b.runs.size());
    for (std::size_t r = 0; r < a.runs.size(); ++r) {
        EXPECT_EQ(a.runs[r].kind, b.runs[r].kind);
        EXPECT_EQ(a.runs[r].bucket, b.runs[r].bucket);
        EXPECT_EQ(a.runs[r].firstInstance, b.runs[r].firstInstance);
        EXPECT_EQ(a.runs[r].instanceCount, b.runs[r].instanceCount);
    }
}

// 30,000 trees in three batches (several chunks per pass): one thread, three threads and
// a selector reused after another view give the same bytes.
TEST_F(LodSelectorScene, SelectionIsIndependentOfThreadsAndFrames) {
    std::vector<InstanceBatch> batches;
    for (int b = 0; b < 3; ++b) {
        std::vector<InstancePlacement> placements;
        for (int i = 0; i < 10000; ++i) {
            placements.push_back(at(5.0 + (i % 100) * 8.0 + b * 800.0, (i / 100) * 8.0 - 400.0));
        }
        batches.push_back(LodSelector::makeBatch(placements[0].baseEcef, placements, lods_));
    }
    const std::vector<const InstanceBatch*> pointers = {&batches[0], &batches[1], &batches[2]};
    WorkerPool one(1), three(3);
    LodSelector serial(&one), parallel(&three);
    LodSelection a, b, c;
    serial.select(pointers, lods_, camera_, settings_, a);
    EXPECT_GT(a.visibleInstances, 5000u);
    EXPECT_GT(a.runs.size(), 5u);
    parallel.select(pointers, lods_, camera_, settings_, b);
    expectSameSelection(a, b);
    Camera turned = camera_;
    turned.axes = Camera::axesFromAngles(camera_.geodetic, 2.0, -0.2, 0.0);
    parallel.select(pointers, lods_, turned, settings_, c);
    parallel.select(pointers, lods_, camera_, settings_, c);
    expectSameSelection(a, c);
}

TEST(LodSelector, SpeciesAndBillboardLevelsAreChecked) {
    EXPECT_EQ(LodSelector::kMaxBillboardLevels, 16);
    EXPECT_LT(LodSelector::kMaxSpecies * LodSelector::kSlotsPerSpecies, 0xFFFF);
    EXPECT_TRUE(LodSelector::checkSpecies(0, 16, "oak"));
    EXPECT_TRUE(LodSelector::checkSpecies(LodSelector::kMaxSpecies - 1, 0, "oak"));
    const Status levels = LodSelector::checkSpecies(0, 17, "oak");
    ASSERT_FALSE(levels);
    EXPECT_EQ(levels.error().message,
              "plant 'oak': 17 billboard levels, the vegetation renderer draws at most 16 per "
              "species");
    const Status species = LodSelector::checkSpecies(LodSelector::kMaxSpecies, 0, "birch");
    ASSERT_FALSE(species);
    EXPECT_EQ(species.error().message,
              "plant 'birch': species " + std::to_string(LodSelector::kMaxSpecies + 1) +
                  " is one too many, the vegetation renderer draws at most " +
                  std::to_string(LodSelector::kMaxSpecies) + " species");
}

// Two species with 16 billboard levels each: a tree far enough for the last level lands
// in its own species' slot for it, not in the next species' keys.
TEST_F(LodSelectorScene, SixteenBillboardLevelsKeepTheirKeys) {
    lods_.push_back(lods_[0]);
    for (SpeciesLod& lod : lods_) {
        for (int level = 0; level < 16; ++level) {
            lod.billboardError.push_back(level == 0 ? 0.0f
                                                    : 0.05f * std::pow(1.3f, float(level - 1)));
        }
    }
    settings_.method = VegetationMethod::Billboard;
    settings_.minimumPixels = 0.0;
    settings_.transitionBand = 0.0;
    // 1.6 mm/px per metre of distance: 8 mm/px at 5 m (level 0), 19 m/px at 12 km, beyond
    // the start of level 15 (0.05 × 1.3^14 ≈ 2 m/px).
    InstancePlacement near = at(5.0, 0.0), far = at(12000.0, 0.0);
    near.species = 0;
    far.species = 0;
    InstancePlacement other = far;
    other.species = 1;
    const InstanceBatch batch = LodSelector::makeBatch(camera_.position, {near, far, other}, lods_);
    LodSelection out;
    selector_.select({&batch}, lods_, camera_, settings_, out);
    ASSERT_EQ(out.runs.size(), 3u);
    EXPECT_EQ(out.runs[0].species, 0u);
    EXPECT_EQ(out.runs[0].bucket, 0u);
    EXPECT_EQ(out.runs[1].species, 0u);
    EXPECT_EQ(out.runs[1].bucket, 15u);
    EXPECT_EQ(out.runs[2].species, 1u);
    EXPECT_EQ(out.runs[2].bucket, 15u);
    for (const DrawRun& run : out.runs) {
        EXPECT_EQ(run.kind, DrawRun::Kind::Billboard);
    }
}

TEST_F(LodSelectorScene, MoreBillboardLevelsThanTheKeysHoldIsAProgrammerError) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    lods_[0].billboardError.assign(17, 1.0f);
    const InstanceBatch batch = LodSelector::makeBatch(camera_.position, {at(30, 0)}, lods_);
    LodSelection out;
    EXPECT_DEATH(selector_.select({&batch}, lods_, camera_, settings_, out),
                 "billboardError.size\\(\\) <= std::size_t\\(kMaxBillboardLevels\\)");
}

}  // namespace
}  // namespace sylva
