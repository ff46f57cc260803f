// Wirelines and photomontage on the GPU path (render/batch PhotomontageRenderer and the
// masks of core/image ProposalMask), checked against independent references:
//  - the proposal's rendered silhouette (mask of the depth comparison) lies within 1 px
//    of the outline of the building's true geometry — the convex hull of its eight
//    corners projected on the CPU by ImageProjection — and that outline is covered;
//  - an existing building in front hides the proposal: no proposal pixel where the CPU
//    projection of the occluder covers the proposal's;
//  - end to end through `photo` blocks: a photograph stand-in rendered by Sylva from a
//    known camera (baseline only), control points projected from that camera, a camera
//    block guessed 1.2° off: the matched camera is within 0.05° of the truth and the
//    photomontage equals the proposed scenario rendered directly from the true camera
//    (RMSE ≤ 2 code values), and the files are written; a failing photo writes nothing;
//  - `compare { mode = wireline }` in a views series (planar and a 90° cylindrical
//    panorama): every line pixel lies within 1 px of the boundary of the proposal as the
//    two scenario images show it (the pixels where they differ), and nearly all of that
//    boundary has a line pixel within 1 px.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <unistd.h>

#include "SceneRenderSupport.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/image/ProposalMask.h"
#include "sylva/core/scene/ImageProjection.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/objects/BuildingsSource.h"
#include "sylva/core/sources/raster/ConstantSource.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/dsl/ProjectLoader.h"
#include "sylva/render/batch/PhotomontageRenderer.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {
namespace {

namespace fs = std::filesystem;
constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kLatitude = -7.96, kLongitude = -34.90;  // degrees
constexpr double kGround = 100.0;                         // metres above the ellipsoid
constexpr int kWidth = 320, kHeight = 180;

double metresEast() {
    return Ellipsoid::primeVerticalRadius(kLatitude * kDegree) * std::cos(kLatitude * kDegree) *
           kDegree;
}
double metresNorth() {
    return Ellipsoid::meridionalRadius(kLatitude * kDegree) * kDegree;
}

fs::path folder() {
    const fs::path path =
        fs::temp_directory_path() / ("sylva-montage-" + std::to_string(::getpid()));
    fs::create_directories(path);
    return path;
}

// Longitude/latitude (degrees) of (east, north) metres from the test point.
glm::dvec2 lonLat(double east, double north) {
    return {kLongitude + east / metresEast(), kLatitude + north / metresNorth()};
}

// A flat-roofed box footprint centred (east, north), half sizes in metres, height h.
std::string box(int id, double east, double north, double half, double height) {
    std::string ring;
    const double corners[5][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {-1, -1}};
    for (int i = 0; i < 5; ++i) {
        const glm::dvec2 p = lonLat(east + corners[i][0] * half, north + corners[i][1] * half);
        char text[96];
        std::snprintf(text, sizeof text, "%s[%.10f,%.10f]", i ? "," : "", p.x, p.y);
        ring += text;
    }
    char head[128];
    std::snprintf(head, sizeof head, R"({"type":"Feature","id":%d,"properties":{"h":%.1f},)", id,
                  height);
    return std::string(head) + R"("geometry":{"type":"Polygon","coordinates":[[)" + ring + "]]}}";
}

fs::path writeGeoJson(const std::string& name, const std::string& features) {
    const fs::path path = folder() / name;
    std::ofstream(path) << R"({"type":"FeatureCollection","features":[)" << features << "]}";
    return path;
}

// The eight corners (ECEF) of a box: footprint corners at the ground and at the roof.
std::vector<glm::dvec3> boxCorners(double east, double north, double half, double height) {
    std::vector<glm::dvec3> corners;
    for (double z : {kGround, kGround + height}) {
        for (const auto& c :
             {glm::dvec2(-1, -1), glm::dvec2(1, -1), glm::dvec2(1, 1), glm::dvec2(-1, 1)}) {
            const glm::dvec2 p = lonLat(east + c.x * half, north + c.y * half);
            corners.push_back(Ellipsoid::toEcef({p.y * kDegree, p.x * kDegree, z}));
        }
    }
    return corners;
}

// Convex hull (Andrew's monotone chain), counter-clockwise in pixel coordinates.
std::vector<glm::dvec2> hull(std::vector<glm::dvec2> points) {
    std::sort(points.begin(), points.end(),
              [](auto a, auto b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    auto cross = [](glm::dvec2 o, glm::dvec2 a, glm::dvec2 b) {
        return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
    std::vector<glm::dvec2> out(2 * points.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        while (k >= 2 && cross(out[k - 2], out[k - 1], points[i]) <= 0)
            --k;
        out[k++] = points[i];
    }
    for (std::size_t i = points.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && cross(out[k - 2], out[k - 1], points[i]) <= 0)
            --k;
        out[k++] = points[i];
    }
    out.resize(k - 1);
    return out;
}

double distanceToSegment(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
    const glm::dvec2 ab = b - a;
    const double t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
    return glm::length(p - (a + t * ab));
}

double distanceToOutline(glm::dvec2 p, const std::vector<glm::dvec2>& polygon) {
    double best = 1e30;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        best = std::min(best, distanceToSegment(p, polygon[i], polygon[(i + 1) % polygon.size()]));
    }
    return best;
}

bool inside(glm::dvec2 p, const std::vector<glm::dvec2>& polygon) {
    return std::all_of(polygon.begin(), polygon.end(), [&](const glm::dvec2& a) {
        const glm::dvec2 b = polygon[(&a - polygon.data() + 1) % polygon.size()];
        return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x) >= 0;
    });
}

// A camera at eye height 200 m south-west of the test point looking at the box.
Camera oblique() {
    Camera c;
    const glm::dvec2 p = lonLat(-140.0, -140.0);
    c.geodetic = {p.y * kDegree, p.x * kDegree, kGround + 30.0};
    c.position = Ellipsoid::toEcef(c.geodetic);
    c.axes = Camera::axesFromAngles(c.geodetic, 45.0 * kDegree, -2.0 * kDegree, 0.0);
    c.verticalFov = 30.0 * kDegree;
    return c;
}

class PhotomontageRender : public SceneRenderFixture {
protected:
    std::vector<float> depth(const std::vector<const MeshSource*>& meshes, const Camera& camera) {
        TerrainLayers layers{&ground_, nullptr, &normals_, {}, meshes};
        RenderSettings settings;
        settings.width = kWidth;
        settings.height = kHeight;
        settings.atmosphere = false;
        settings.ocean = false;
        settings.sunDirection = glm::normalize(camera.position);
        Result<Image> image = renderer_->render(layers, evaluator_, camera, settings);
        EXPECT_TRUE(image) << image.error().message;
        return renderer_->depth();
    }

    const ConstantSource ground_{"ground", kGround};
    const NormalMapSource normals_{"ground.normals", &ground_, 1.0};
    TileEvaluator evaluator_{TileFormat{256, 2}};
};

TEST_F(PhotomontageRender, WirelineLiesOnTheProjectedOutlineOfTheProposal) {
    FeatureSource features("footprints", writeGeoJson("one.geojson", box(1, 0, 0, 15, 24)), {});
    BuildingsParameters p;
    p.heightAttribute = "h";
    const BuildingsSource proposal("proposal", &features, &ground_, p);
    const Camera camera = oblique();
    const std::vector<float> baseline = depth({}, camera);
    const std::vector<float> proposed = depth({&proposal}, camera);
    const PixelMask mask = ProposalMask::fromDepths(baseline, proposed, kWidth, kHeight);
    const PixelMask lines = ProposalMask::outline(mask, kWidth, kHeight);

    const ImageProjection projection(camera, kWidth, kHeight);
    std::vector<glm::dvec2> pixels;
    for (const glm::dvec3& corner : boxCorners(0, 0, 15, 24)) {
        std::optional<glm::dvec2> pixel = projection.pixelOfPoint(corner);
        ASSERT_TRUE(pixel.has_value());
        pixels.push_back(*pixel);
    }
    const std::vector<glm::dvec2> outline = hull(pixels);
    ASSERT_GE(outline.size(), 4u);
    // Where a wireline pixel puts the silhouette: the middle of its side facing the
    // outside neighbour (the edge crosses between the two pixel centres). Also reported:
    // the pixel centres' distance, which rasterisation bounds by 1 px plus the renderer's
    // sub-pixel difference from the CPU model.
    auto outsideAt = [&](int x, int y) {
        return x >= 0 && y >= 0 && x < kWidth && y < kHeight &&
               mask[std::size_t(y) * kWidth + x] == 0;
    };
    std::size_t count = 0;
    double worst = 0.0, worstCentre = 0.0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            if (lines[std::size_t(y) * kWidth + x] == 0) {
                continue;
            }
            const glm::dvec2 centre(x + 0.5, y + 0.5);
            worstCentre = std::max(worstCentre, distanceToOutline(centre, outline));
            double nearest = 1e30;
            for (const glm::ivec2 step :
                 {glm::ivec2(1, 0), glm::ivec2(-1, 0), glm::ivec2(0, 1), glm::ivec2(0, -1)}) {
                if (outsideAt(x + step.x, y + step.y)) {
                    nearest = std::min(nearest,
                                       distanceToOutline(centre + 0.5 * glm::dvec2(step), outline));
                }
            }
            worst = std::max(worst, nearest);
            ++count;
        }
    }
    EXPECT_GT(count, 60u);
    EXPECT_LE(worst, 1.0) << "a wireline pixel is " << worst << " px off the projected outline";
    EXPECT_LE(worstCentre, 1.25) << "a wireline pixel's centre is " << worstCentre << " px off";
    // Coverage: every point of the projected outline has a wireline pixel within 1.5 px.
    double gap = 0.0;
    for (std::size_t i = 0; i < outline.size(); ++i) {
        const glm::dvec2 a = outline[i], b = outline[(i + 1) % outline.size()];
        for (double t = 0.0; t < 1.0; t += 0.02) {
            const glm::dvec2 q = a + t * (b - a);
            double nearest = 1e30;
            for (int y = std::max(0, int(q.y) - 4); y < std::min(kHeight, int(q.y) + 5); ++y)
                for (int x = std::max(0, int(q.x) - 4); x < std::min(kWidth, int(q.x) + 5); ++x)
                    if (lines[std::size_t(y) * kWidth + x] != 0)
                        nearest = std::min(nearest, glm::length(glm::dvec2(x + 0.5, y + 0.5) - q));
            gap = std::max(gap, nearest);
        }
    }
    EXPECT_LE(gap, 1.5) << "the projected outline is " << gap << " px from any wireline pixel";
    std::printf(
        "wireline: %zu pixels, worst %.3f px off the CPU outline (pixel centres %.3f px), "
        "largest gap %.3f px\n",
        count, worst, worstCentre, gap);
}

TEST_F(PhotomontageRender, ExistingBuildingsHideTheProposal) {
    // The proposal 60 m behind an existing building on the line of sight.
    FeatureSource existingFeatures("existing",
                                   writeGeoJson("front.geojson", box(1, -60, -60, 10, 30)), {});
    FeatureSource proposalFeatures("proposal", writeGeoJson("back.geojson", box(2, 0, 0, 15, 24)),
                                   {});
    BuildingsParameters p;
    p.heightAttribute = "h";
    const BuildingsSource existing("existing", &existingFeatures, &ground_, p);
    const BuildingsSource proposal("proposal", &proposalFeatures, &ground_, p);
    const Camera camera = oblique();
    const PixelMask mask = ProposalMask::fromDepths(
        depth({&existing}, camera), depth({&existing, &proposal}, camera), kWidth, kHeight);
    const ImageProjection projection(camera, kWidth, kHeight);
    auto outlineOf = [&](const std::vector<glm::dvec3>& corners) {
        std::vector<glm::dvec2> pixels;
        for (const glm::dvec3& corner : corners)
            pixels.push_back(*projection.pixelOfPoint(corner));
        return hull(pixels);
    };
    const std::vector<glm::dvec2> front = outlineOf(boxCorners(-60, -60, 10, 30));
    const std::vector<glm::dvec2> back = outlineOf(boxCorners(0, 0, 15, 24));
    std::size_t hidden = 0, leaked = 0, shown = 0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const glm::dvec2 c(x + 0.5, y + 0.5);
            const bool set = mask[std::size_t(y) * kWidth + x] != 0;
            const bool clear =
                distanceToOutline(c, front) > 1.0 && distanceToOutline(c, back) > 1.0;
            if (clear && inside(c, back) && inside(c, front)) {
                ++hidden;
                leaked += set ? 1 : 0;
            } else if (clear && inside(c, back)) {
                shown += set ? 0 : 1;  // visible proposal pixels missing from the mask
            }
        }
    }
    EXPECT_GT(hidden, 100u);
    EXPECT_EQ(leaked, 0u);
    EXPECT_EQ(shown, 0u);
}

// The project of the end-to-end fixture: flat ground, a 24 m box proposed, a camera at
// 30 m eye height with heading `heading` and pitch `pitch`, and one photo block.
std::string fixtureProject(double heading, double pitch, const std::string& scenario,
                           const std::string& photoFile, const std::string& points) {
    const glm::dvec2 p = lonLat(-140.0, -140.0);
    char camera[256];
    std::snprintf(camera, sizeof camera,
                  "camera vp { position = geo(%.10fdeg, %.10fdeg); eye_height = 30m; heading = "
                  "%.4fdeg; pitch = %.4fdeg; fov = 30deg }\n",
                  p.y, p.x, heading, pitch);
    return "source ground : constant { kind = elevation; height = 100m }\n"
           "source colour : constant { kind = image; color = #7a8a5a }\n"
           "source normals : normal_map { height = @ground }\n"
           "source footprints : features { file = \"proposal.geojson\" }\n"
           "source proposal : buildings { features = @footprints; elevation = @ground; "
           "height_attribute = \"h\" }\n"
           "scenario today { layers = [@ground, @colour, @normals] }\n"
           "scenario proposed { layers = [@ground, @colour, @normals, @proposal] }\n" +
           std::string(camera) +
           "render { resolution = [320px, 180px]; shadows = false }\n"
           "photo vp_photo { file = \"" +
           photoFile + "\"; camera = @vp; scenario = @" + scenario + "; baseline = @today\n" +
           points + "}\n";
}

struct FixtureRun {
    PhotoViewpoint photo;
    Photo picture;
    PhotomontageResult result;
};

std::optional<FixtureRun> runFixture(const std::string& text) {
    const fs::path file = folder() / "fixture.sylva";
    std::ofstream(file) << text;
    dsl::LoadResult loaded = dsl::loadProject(file);
    EXPECT_EQ(loaded.render(), "");
    if (!loaded.model)
        return std::nullopt;
    Result<PhotoViewpoint> photo =
        PhotoViewpoint::fromBlock(*loaded.model, loaded.model->photos.at(0));
    EXPECT_TRUE(photo) << photo.error().message;
    Result<Photo> picture = photo ? photo->readPhoto() : Result<Photo>(photo.error());
    EXPECT_TRUE(picture) << picture.error().message;
    if (!picture)
        return std::nullopt;
    BatchRenderer batch(BatchOptions{});
    EXPECT_TRUE(batch.setProject(std::move(loaded.scenarios)));
    Result<PhotomontageResult> result = PhotomontageRenderer::render(batch, *photo, *picture);
    EXPECT_TRUE(result) << result.error().message;
    if (!result)
        return std::nullopt;
    return FixtureRun{std::move(photo.value()), std::move(picture.value()),
                      std::move(result.value())};
}

TEST(PhotomontageFixture, MatchedMontageEqualsTheProposalRenderedFromTheTrueCamera) {
    writeGeoJson("proposal.geojson", box(1, 0, 0, 15, 24));
    ASSERT_TRUE(ImageWriter::writeRgba8(folder() / "blank.png", kWidth, kHeight,
                                        RgbaImage(kWidth, kHeight).pixels));
    // 1. The photograph stand-in: the baseline seen from the true camera.
    std::optional<FixtureRun> truth =
        runFixture(fixtureProject(45.0, -2.0, "today", "blank.png", ""));
    ASSERT_TRUE(truth);
    EXPECT_EQ(ProposalMask::count(truth->result.proposal), 0u);
    ASSERT_TRUE(ImageWriter::writeRgba8(folder() / "standin.png", kWidth, kHeight,
                                        truth->result.proposed.pixels));
    // 2. Control points: surveyed points projected by the true camera, ±0.5 px noise.
    const ImageProjection projection(truth->result.camera, kWidth, kHeight);
    const double survey[6][3] = {{-40, -10, 0}, {30, 40, 0}, {-10, 50, 24},
                                 {20, -30, 10}, {60, 10, 5}, {-50, 30, 40}};
    std::string points = "control_points = [\n";
    for (int i = 0; i < 6; ++i) {
        const glm::dvec2 ll = lonLat(survey[i][0], survey[i][1]);
        const glm::dvec3 ecef =
            Ellipsoid::toEcef({ll.y * kDegree, ll.x * kDegree, kGround + survey[i][2]});
        const glm::dvec2 pixel =
            *projection.pixelOfPoint(ecef) + glm::dvec2(i % 2 ? 0.5 : -0.5, i % 3 ? -0.5 : 0.5);
        char line[200];
        std::snprintf(
            line, sizeof line,
            "  { position = geo(%.10fdeg, %.10fdeg, %.3fm), pixel = [%.3fpx, %.3fpx] }%s\n", ll.y,
            ll.x, kGround + survey[i][2], pixel.x, pixel.y, i < 5 ? "," : "");
        points += line;
    }
    points += "]\n";
    // 3. The montage with a camera block 1.2° and 0.6° off, matched to the points.
    std::optional<FixtureRun> matched =
        runFixture(fixtureProject(43.8, -1.4, "proposed", "standin.png", points));
    ASSERT_TRUE(matched);
    ASSERT_TRUE(matched->result.match.has_value());
    const Camera& solved = matched->result.camera;
    EXPECT_NEAR(solved.heading() / kDegree, 45.0, 0.05);
    EXPECT_NEAR(solved.pitch() / kDegree, -2.0, 0.05);
    EXPECT_LE(matched->result.match->rms, 1.0);
    // 4. The proposal rendered directly from the true camera.
    std::optional<FixtureRun> direct =
        runFixture(fixtureProject(45.0, -2.0, "proposed", "standin.png", ""));
    ASSERT_TRUE(direct);
    const std::vector<std::uint8_t>& a = matched->result.montage.pixels;
    const std::vector<std::uint8_t>& b = direct->result.proposed.pixels;
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); i += 4)
        for (int c = 0; c < 3; ++c)
            sum += std::pow(double(a[i + c]) - b[i + c], 2.0);
    const double rmse = std::sqrt(sum / (a.size() / 4 * 3));
    const std::size_t proposal = ProposalMask::count(matched->result.proposal);
    std::printf(
        "matched heading %.4f pitch %.4f rms %.3f px; montage vs direct RMSE %.3f; "
        "%zu proposal pixels\n",
        solved.heading() / kDegree, solved.pitch() / kDegree, matched->result.match->rms, rmse,
        proposal);
    EXPECT_GT(proposal, 500u);
    EXPECT_LE(rmse, 2.0);
    ASSERT_TRUE(
        ImageWriter::writeRgba8(fs::path(SYLVA_TEST_OUTPUT_DIR) / "photomontage_fixture.png",
                                kWidth, kHeight, matched->result.montage.pixels));
    ASSERT_TRUE(ImageWriter::writeRgba8(
        fs::path(SYLVA_TEST_OUTPUT_DIR) / "photomontage_fixture_wireline.png", kWidth, kHeight,
        matched->result.wireline.pixels));
}

class WirelineListener final : public BatchListener {
public:
    void jobDone(const JobReport&) override {}
    void error(const std::string& message) override { errors.push_back(message); }
    std::vector<std::string> errors;
};

RgbaImage readImage(const fs::path& path) {
    RgbaImage image;
    Result<std::vector<std::uint8_t>> pixels =
        ImageWriter::readRgba8(path, image.width, image.height);
    EXPECT_TRUE(pixels) << path;
    if (pixels) {
        image.pixels = std::move(pixels.value());
    }
    return image;
}

// A `compare { mode = wireline }` of a views series rendered from the camera whose settings
// after its position are `view`: every red line pixel lies within one pixel of the boundary
// of the pixels where the two scenario images differ, >= 98 % of that boundary has a line
// pixel within one pixel, and away from the lines the image is the left one.
void expectWirelineOnBoundary(const char* view, const std::string& name) {
    writeGeoJson("proposal.geojson", box(1, 0, 0, 15, 24));
    const glm::dvec2 p = lonLat(-140.0, -140.0);
    char camera[256];
    std::snprintf(camera, sizeof camera,
                  "camera vp { position = geo(%.10fdeg, %.10fdeg); eye_height = 30m; %s }\n", p.y,
                  p.x, view);
    const fs::path file = folder() / (name + ".sylva");
    std::ofstream(file)
        << "source ground : constant { kind = elevation; height = 100m }\n"
           "source colour : constant { kind = image; color = #7a8a5a }\n"
           "source normals : normal_map { height = @ground }\n"
           "source footprints : features { file = \"proposal.geojson\" }\n"
           "source proposal : buildings { features = @footprints; elevation = @ground; "
           "height_attribute = \"h\" }\n"
           "scenario today { layers = [@ground, @colour, @normals] }\n"
           "scenario proposed { layers = [@ground, @colour, @normals, @proposal] }\n"
        << camera
        << "render { resolution = [320px, 180px]; shadows = false; atmosphere = false; ev100 = "
           "12 }\n"
           "compare wire { left = @today; right = @proposed; mode = wireline\n"
           "    wireline_color = #ff0000; skyline_color = #00ffff; line_width = 1px }\n"
           "views pack { cameras = [@vp]; scenarios = [@today, @proposed]\n"
           "    output = \"{camera}_{scenario}.png\" }\n";
    dsl::LoadResult loaded = dsl::loadProject(file);
    ASSERT_EQ(loaded.render(), "");
    ASSERT_TRUE(loaded.model);
    BatchRenderer batch(BatchOptions{});
    ASSERT_TRUE(batch.setProject(std::move(loaded.scenarios)));
    BatchSelection selection;
    selection.outputFolder = folder() / (name + "_out");
    Result<BatchPlan> plan = batch.plan(selection);
    ASSERT_TRUE(plan) << plan.error().message;
    WirelineListener listener;
    Result<BatchSummary> summary = batch.run(plan.value(), listener);
    ASSERT_TRUE(summary) << summary.error().message;
    ASSERT_TRUE(listener.errors.empty()) << listener.errors.front();
    EXPECT_EQ(summary->failed, 0);
    const RgbaImage today = readImage(selection.outputFolder / "vp_today.png");
    const RgbaImage proposed = readImage(selection.outputFolder / "vp_proposed.png");
    const RgbaImage wire = readImage(selection.outputFolder / "vp_wire.png");
    ASSERT_EQ(wire.width, kWidth);
    ASSERT_EQ(today.width, kWidth);
    ASSERT_EQ(proposed.width, kWidth);
    // The proposal as the images show it: where the two scenarios' pixels differ.
    PixelMask shown(std::size_t(kWidth) * kHeight, 0);
    for (std::size_t i = 0; i < shown.size(); ++i)
        for (int c = 0; c < 3; ++c)
            if (std::abs(int(today.pixels[i * 4 + c]) - int(proposed.pixels[i * 4 + c])) > 2)
                shown[i] = 1;
    auto inside = [&](int x, int y) {
        return x >= 0 && y >= 0 && x < kWidth && y < kHeight && shown[std::size_t(y) * kWidth + x];
    };
    // Within one pixel: at the proposal's foot the depths differ by less than the mask's
    // tolerance (0.1 % of the distance) while the colours already differ.
    auto isBoundary = [&](int x, int y) {
        return inside(x, y) &&
               (!inside(x - 1, y) || !inside(x + 1, y) || !inside(x, y - 1) || !inside(x, y + 1));
    };
    auto isRed = [&](int x, int y) {
        if (x < 0 || y < 0 || x >= kWidth || y >= kHeight)
            return false;
        const std::uint8_t* w = &wire.pixels[(std::size_t(y) * kWidth + x) * 4];
        return w[0] == 255 && w[1] == 0 && w[2] == 0;
    };
    auto near = [&](int x, int y, auto&& test) {
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                if (test(x + dx, y + dy))
                    return true;
        return false;
    };
    std::size_t red = 0, offBoundary = 0, boundary = 0, drawn = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            red += isRed(x, y);
            offBoundary += isRed(x, y) && !near(x, y, isBoundary);
            boundary += isBoundary(x, y);
            drawn += isBoundary(x, y) && near(x, y, isRed);
        }
    std::printf(
        "wireline compare: %zu red pixels, %zu off the boundary; %zu of %zu boundary "
        "pixels drawn\n",
        red, offBoundary, drawn, boundary);
    EXPECT_GT(red, 100u);
    EXPECT_EQ(offBoundary, 0u);
    EXPECT_GE(double(drawn), 0.98 * double(boundary));
    // Away from the lines the wireline image is the left (today) image.
    std::size_t changed = 0;
    for (std::size_t i = 0; i < shown.size(); ++i) {
        const bool line = (wire.pixels[i * 4] == 255 && wire.pixels[i * 4 + 1] == 0) ||
                          (wire.pixels[i * 4] == 0 && wire.pixels[i * 4 + 1] == 255);
        changed += !line && std::memcmp(&wire.pixels[i * 4], &today.pixels[i * 4], 3) != 0;
    }
    EXPECT_EQ(changed, 0u);
    ASSERT_TRUE(ImageWriter::writeRgba8(fs::path(SYLVA_TEST_OUTPUT_DIR) / (name + ".png"), kWidth,
                                        kHeight, wire.pixels));
}

TEST(CompareWireline, LinesLieOnTheBoundaryOfTheProposal) {
    expectWirelineOnBoundary("heading = 45deg; pitch = -2deg; fov = 30deg", "compare_wireline");
}

// A 90° cylindrical panorama: its depth is resampled from the strips' depth buffers
// (PanoramaFaces::resampleDepth, nearest face pixel, as distance along each pixel's ray), so
// the lines follow the proposal in the resampled image as closely as in a planar one.
TEST(CompareWireline, CylindricalPanoramaLinesLieOnTheBoundaryOfTheProposal) {
    expectWirelineOnBoundary("heading = 60deg; projection = cylindrical; horizontal_fov = 90deg",
                             "compare_wireline_cylindrical");
}

}  // namespace
}  // namespace sylva::render
