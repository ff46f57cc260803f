// Type 1 annotations (issue 18): the marks drawn into the image — the proposal's placed
// models as ticks, the ends of its horizontal extent, the bearing scale — stand where the
// camera model puts them. The marks are found in the drawn pixels (the intensity-weighted
// centre of each tick across a row) and compared with ImageProjection's projection of the
// proposal's points and with the analytic columns of bearings: planar (level camera)
// x = w/2 + f tan(b − heading), f = (w/2) / tan(HFOV/2); cylindrical x = w/2 + (b − heading) r,
// r = w / HFOV. Within 0.5 px, planar and cylindrical.
#include "sylva/core/scene/ViewAnnotation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>

#include "sylva/core/analysis/ProposalReach.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scene/ImageProjection.h"

namespace sylva {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;
constexpr int kWidth = 1614, kHeight = 512;  // NatureScot 820 × 260 mm at 50 dpi
constexpr double kHeading = 30.0 * kDegree;

Camera camera(CameraProjection projection) {
    Camera camera;
    camera.geodetic = {-7.9858 * kDegree, -34.9048 * kDegree, 41.5};
    camera.position = Ellipsoid::toEcef(camera.geodetic);
    camera.projection = projection;
    camera.axes = Camera::axesFromAngles(camera.geodetic, kHeading, 0.0, 0.0);
    camera.horizontalFov = projection == CameraProjection::Planar ? 53.5 * kDegree : 90.0 * kDegree;
    return camera.fitted(kWidth, kHeight);
}

// Five "turbines" (tower feet at ground level, 3.2 to 4.1 km) spread over 17°, with feature
// ids 1..5, and a building edge reaching 8° further right (the extent's right end).
ProposalParts parts(const Camera& viewpoint) {
    const glm::dmat3 frame =
        Ellipsoid::localFrame(viewpoint.geodetic.latitude, viewpoint.geodetic.longitude);
    const glm::dvec3 foot =
        Ellipsoid::toEcef({viewpoint.geodetic.latitude, viewpoint.geodetic.longitude, 0.0});
    auto at = [&](double bearing, double distance, double up) {
        return foot +
               distance * (std::sin(bearing * kDegree) * frame[0] +
                           std::cos(bearing * kDegree) * frame[1]) +
               up * frame[2];
    };
    ProposalParts result;
    const double bearings[] = {21.3, 25.9, 29.4, 33.7, 38.2};
    const double distances[] = {4100, 3800, 3600, 3400, 3200};
    for (int i = 0; i < 5; ++i) {
        result.points.push_back(at(bearings[i], distances[i], 35.0 + 5 * i));
        result.pointIds.push_back(i + 1);
    }
    result.segments.emplace_back(at(44.0, 2900, 20.0), at(46.2, 2950, 20.0));
    return result;
}

// The centres of the runs of marked pixels along row `row` (weight = `weight(pixel)`,
// zero outside marks): Σ (x + 0.5) w / Σ w over each run.
std::vector<double> markCentres(const RgbaImage& image, int row,
                                const std::function<double(const std::uint8_t*)>& weight) {
    std::vector<double> centres;
    double sum = 0.0, moment = 0.0;
    for (int x = 0; x <= image.width; ++x) {
        const double w = x < image.width ? weight(image.at(x, row)) : 0.0;
        if (w > 0.0) {
            sum += w;
            moment += (x + 0.5) * w;
        } else if (sum > 0.0) {
            centres.push_back(moment / sum);
            sum = moment = 0.0;
        }
    }
    return centres;
}

double red(const std::uint8_t* p) {
    return std::max(0, int(p[0]) - int(p[1]) - 4);
}

RgbaImage grey() {
    RgbaImage image(kWidth, kHeight);
    for (std::size_t i = 0; i < image.pixels.size(); i += 4) {
        image.pixels[i] = image.pixels[i + 1] = image.pixels[i + 2] = 110;
        image.pixels[i + 3] = 255;
    }
    return image;
}

double analyticColumn(const Camera& viewpoint, double bearing) {
    const double offset = std::remainder(bearing - kHeading, 2 * kPi);
    if (viewpoint.projection == CameraProjection::Planar) {
        const double focal = (kWidth / 2.0) / std::tan(viewpoint.horizontalFov / 2.0);
        return kWidth / 2.0 + focal * std::tan(offset);
    }
    return kWidth / 2.0 + offset * kWidth / viewpoint.horizontalFov;
}

void expectNear(const std::vector<double>& found, std::vector<double> expected, double tolerance,
                const char* what) {
    std::sort(expected.begin(), expected.end());
    ASSERT_EQ(found.size(), expected.size()) << what;
    double worst = 0.0;
    for (std::size_t i = 0; i < found.size(); ++i) {
        EXPECT_NEAR(found[i], expected[i], tolerance) << what << " " << i;
        worst = std::max(worst, std::abs(found[i] - expected[i]));
    }
    std::printf("%zu %s marks, largest offset %.3f px\n", found.size(), what, worst);
}

class ViewAnnotationTest : public ::testing::TestWithParam<CameraProjection> {};

TEST_P(ViewAnnotationTest, MarksStandWhereTheCameraModelProjectsTheProposal) {
    const Camera viewpoint = camera(GetParam());
    const ProposalParts proposal = parts(viewpoint);
    // The proposal as PhotomontageRenderer gives it: ProposalReach's arc, the points.
    const std::optional<ProposalReach> reach = ProposalReach::measure(viewpoint.geodetic, proposal);
    ASSERT_TRUE(reach);
    const ViewProposal marks{reach->leftBearing,
                             reach->rightBearing,
                             reach->horizontalExtent,
                             proposal.points,
                             {"1", "2", "3", "4", "5"}};
    const ViewAnnotations plan = ViewAnnotation::plan(viewpoint, kWidth, kHeight, "vp2", &marks);
    const RgbaImage drawn = ViewAnnotation::draw(grey(), plan);

    // The placed models: ticks in the bottom band, at the CPU model's pixel of each point.
    const ImageProjection projection(viewpoint, kWidth, kHeight);
    std::vector<double> expected;
    for (const glm::dvec3& point : proposal.points) {
        expected.push_back(projection.pixelOfPoint(point)->x);
    }
    const int tickRow = int((plan.partTickTop + plan.partTickBottom) / 2.0);
    expectNear(markCentres(drawn, tickRow, red), expected, 0.5, "part tick");
    ASSERT_EQ(plan.parts.size(), 5u);
    EXPECT_EQ(plan.parts.front().label, "1");

    // The extent's ends: the first turbine's bearing and the building edge's far end.
    const double left = 21.3 * kDegree;
    const double right = std::atan2(std::sin(46.2 * kDegree), std::cos(46.2 * kDegree));
    expectNear(markCentres(drawn, kHeight / 2, red),
               {analyticColumn(viewpoint, left), analyticColumn(viewpoint, right)}, 0.5,
               "extent end");

    // The bearing scale: dark ticks under the top band's labels, every 5° (planar 53.5°)
    // or 10° (cylindrical 90°), at the analytic column of each bearing.
    const double step = GetParam() == CameraProjection::Planar ? 5.0 : 10.0;
    EXPECT_NEAR(plan.bearingStep, step * kDegree, 1e-12);
    std::vector<double> ticks;
    for (double bearing = -30.0; bearing < 90.0; bearing += step) {
        const double column = analyticColumn(viewpoint, bearing * kDegree);
        if (column > 4.0 && column < kWidth - 4.0) {
            ticks.push_back(column);
        }
    }
    const int scaleRow = int(plan.topBand - 0.3 * plan.fontSize);
    const auto dark = [](const std::uint8_t* p) { return std::max(0, 218 - int(p[1])); };
    std::vector<double> found = markCentres(drawn, scaleRow, dark);
    found.erase(std::remove_if(found.begin(), found.end(),
                               [](double x) { return x < 4.0 || x > kWidth - 4.0; }),
                found.end());
    expectNear(found, ticks, 0.5, "bearing tick");
    EXPECT_NE(plan.title.find("vp2"), std::string::npos);
    EXPECT_NE(plan.extentText.find("21.3"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Projections, ViewAnnotationTest,
                         ::testing::Values(CameraProjection::Planar,
                                           CameraProjection::Cylindrical));

TEST(ViewAnnotation, WithoutAProposalOnlyTheScaleAndTitle) {
    const Camera viewpoint = camera(CameraProjection::Planar);
    const ViewAnnotations plan = ViewAnnotation::plan(viewpoint, kWidth, kHeight, "vp1", nullptr);
    EXPECT_TRUE(plan.parts.empty());
    EXPECT_FALSE(plan.extentLeft || plan.extentRight || plan.bracket);
    const RgbaImage drawn = ViewAnnotation::draw(grey(), plan);
    EXPECT_TRUE(markCentres(drawn, kHeight / 2, red).empty());
    // Below the top band the image is untouched.
    for (int y = int(plan.topBand) + 1; y < kHeight; ++y) {
        ASSERT_EQ(drawn.at(700, y)[0], 110);
    }
    // Real glyphs in the band: more than a few dark pixels where the title is.
    int darkPixels = 0;
    for (int y = 0; y < int(1.3 * plan.fontSize); ++y) {
        for (int x = 0; x < 300; ++x) {
            darkPixels += drawn.at(x, y)[0] < 80;
        }
    }
    EXPECT_GT(darkPixels, 100);
}

}  // namespace
}  // namespace sylva
