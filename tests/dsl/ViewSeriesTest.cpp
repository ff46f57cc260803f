// View-series expansion (core/scene/ViewSeries) on projects written in the language:
// cameras × paths × scenarios × times, comparisons, templates, collisions and shards.
#include "sylva/core/scene/ViewSeries.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <set>

#include "sylva/dsl/ProjectLoader.h"

namespace sylva {
namespace {

constexpr const char* kProject = R"(
source height : noise { octaves = 4 }
source ground : hypsometric { height = @height }
scenario today { layers = [@height, @ground] }
scenario dam extends today {
    override @height { amplitude = 3km }
}
compare before_after { left = @today; right = @dam; layout = swipe }
blend half { from = @today; to = @dam; amount = 50% }
camera beach { position = geo(-8deg, -34.8deg, 20m) }
camera hill { position = geo(-8.01deg, -34.85deg, 90m); heading = 90deg }
camera tower { position = geo(-8.02deg, -34.86deg, 60m) }
path approach {
    keys = [
        { at = 0s, position = geo(-7.9deg, -34.7deg, 2km), heading = 200deg },
        { at = 1s, position = geo(-8deg, -34.8deg, 500m), heading = 220deg },
    ]
    fps = 4
}
views photos {
    scenarios = [@today, @dam]
    cameras = [@beach, @hill, @tower]
    times = [2024-06-21T09:00-03:00, 2024-06-21T17:30-03:00]
    output = "{scenario}/{camera}_{time:%H%M}.png"
}
views flight {
    paths = [@approach]
    scenarios = [@today]
    output = "flight/{frame}.png"
}
)";

ProjectModel load(const std::string& text) {
    dsl::LoadResult result = dsl::loadProjectFromString(text, "series.sylva");
    EXPECT_EQ(result.render(), "");
    EXPECT_TRUE(result.model.has_value());
    return result.model ? *result.model : ProjectModel{};
}

TEST(ViewSeriesTest, ExpandsCamerasScenariosTimesComparisonsAndPathFrames) {
    const ProjectModel model = load(kProject);
    auto jobs = ViewSeries::expand(model, "out");
    ASSERT_TRUE(jobs.ok()) << jobs.error().message;
    // photos: 3 cameras × 2 times × 2 scenarios = 12 images + 6 compare + 6 blend;
    // flight: 5 frames (0, 0.25 ... 1 s).
    std::size_t images = 0, compares = 0, blends = 0;
    for (const RenderJob& job : jobs.value()) {
        images += job.kind == RenderJobKind::Image;
        compares += job.kind == RenderJobKind::Compare;
        blends += job.kind == RenderJobKind::Blend;
    }
    EXPECT_EQ(images, 12u + 5u);
    EXPECT_EQ(compares, 6u);
    EXPECT_EQ(blends, 6u);
    const RenderJob& first = jobs.value().front();
    EXPECT_EQ(first.output, std::filesystem::path("out/today/beach_0900.png"));
    EXPECT_EQ(first.unixSeconds, 1718971200.0);  // 12:00 UTC
    EXPECT_EQ(jobs.value()[1].output, std::filesystem::path("out/dam/beach_0900.png"));
    EXPECT_EQ(jobs.value()[2].output, std::filesystem::path("out/today/beach_1730.png"));
    EXPECT_EQ(jobs.value()[12].output, std::filesystem::path("out/flight/00000.png"));
    EXPECT_EQ(jobs.value()[16].output, std::filesystem::path("out/flight/00004.png"));
    EXPECT_DOUBLE_EQ(jobs.value()[16].pathTime, 1.0);
    const RenderJob& comparison = jobs.value()[17];
    EXPECT_EQ(comparison.kind, RenderJobKind::Compare);
    EXPECT_EQ(comparison.output, std::filesystem::path("out/before_after/beach_0900.png"));
    EXPECT_EQ(jobs.value()[comparison.first].scenario, "today");
    EXPECT_EQ(jobs.value()[comparison.second].scenario, "dam");
    EXPECT_EQ(jobs.value()[comparison.second].camera, "beach");
    EXPECT_EQ(jobs.value()[comparison.second].time->text(), comparison.time->text());

    auto onlyFlight = ViewSeries::expand(model, "out", "flight");
    ASSERT_TRUE(onlyFlight.ok());
    EXPECT_EQ(onlyFlight.value().size(), 5u);
    EXPECT_EQ(ViewSeries::expand(model, "out", "flights").error().message,
              "series.sylva: no views block named 'flights' (the project has: photos, flight)");
}

TEST(ViewSeriesTest, ShardsPartitionTheJobsAndKeepComparisonsWithTheirImages) {
    const ProjectModel model = load(kProject);
    auto jobs = ViewSeries::expand(model, "out");
    ASSERT_TRUE(jobs.ok());
    for (int count : {1, 2, 3, 5, 7, 40}) {
        std::multiset<std::size_t> seen;
        for (int index = 1; index <= count; ++index) {
            const std::vector<RenderJob> mine = ViewSeries::shard(jobs.value(), index, count);
            std::set<std::size_t> here;
            for (const RenderJob& job : mine) {
                seen.insert(job.index);
                here.insert(job.index);
            }
            for (const RenderJob& job : mine) {
                if (job.kind != RenderJobKind::Image) {
                    EXPECT_TRUE(here.count(job.first) && here.count(job.second));
                }
            }
            // Deterministic: the same shard twice is the same list.
            EXPECT_EQ(ViewSeries::shard(jobs.value(), index, count).size(), mine.size());
        }
        ASSERT_EQ(seen.size(), jobs.value().size()) << count;
        for (std::size_t i = 0; i < jobs.value().size(); ++i) {
            EXPECT_EQ(seen.count(i), 1u) << "job " << i << " over " << count << " shards";
        }
    }
    EXPECT_EQ(ViewSeries::parseShard("2/4").value(), std::make_pair(2, 4));
    EXPECT_EQ(ViewSeries::parseShard("5/4").error().message,
              "--shard expects i/N with 1 <= i <= N (e.g. 2/4), got '5/4'");
    EXPECT_FALSE(ViewSeries::parseShard("1/2x").ok());
}

TEST(ViewSeriesTest, ShardsKeepTheTimesOfOneCameraTogether) {
    // photos: 3 cameras × 2 times = 6 groups; over 3 shards each shard renders one camera
    // (its tiles are produced once), and over 2 shards only one camera is split.
    const ProjectModel model = load(kProject);
    auto jobs = ViewSeries::expand(model, "out", "photos");
    ASSERT_TRUE(jobs.ok()) << jobs.error().message;
    const auto camerasOf = [&](int index, int count) {
        std::set<std::string> cameras;
        for (const RenderJob& job : ViewSeries::shard(jobs.value(), index, count)) {
            cameras.insert(job.camera);
        }
        return cameras;
    };
    for (int index = 1; index <= 3; ++index) {
        EXPECT_EQ(camerasOf(index, 3).size(), 1u) << "shard " << index << " of 3";
    }
    EXPECT_EQ(camerasOf(1, 2).size() + camerasOf(2, 2).size(), 4u);
    EXPECT_EQ(ViewSeries::shard(jobs.value(), 1, 2).size(),
              ViewSeries::shard(jobs.value(), 2, 2).size());
}

TEST(ViewSeriesTest, LocatedErrorsBeforeRendering) {
    auto errorOf = [](const std::string& text) {
        const ProjectModel model = load(text);
        auto jobs = ViewSeries::expand(model, "out");
        return jobs.ok() ? std::string("ok") : jobs.error().message;
    };
    const std::string base = R"(
source height : noise { octaves = 4 }
scenario today { layers = [@height] }
scenario dam extends today { override @height { amplitude = 3km } }
camera beach { position = geo(-8deg, -34.8deg, 20m) }
camera hill { position = geo(-8.01deg, -34.85deg, 90m) }
)";
    EXPECT_EQ(errorOf(base + "views v { cameras = [@beach, @hill]; scenarios = [@today, @dam]; "
                             "output = \"{camera}.png\" }"),
              "series.sylva:7:66: views 'v': two images would be written to 'out/beach.png' "
              "(camera beach, "
              "scenario today; camera beach, scenario dam); add {camera}, {scenario}, {time} or "
              "{frame} to the "
              "output template");
    EXPECT_EQ(errorOf(base + "views v { cameras = [@beach]; times = [2024-06-21T09:00] }"),
              "series.sylva:7:40: views 'v': time 2024-06-21T09:00:00 has no zone: add a UTC "
              "offset such as "
              "2024-06-21T09:00:00+00:00 or Z");
    EXPECT_EQ(errorOf(base + "views v { cameras = [@beach]; output = \"{camera}_{day}.png\" }"),
              "series.sylva:7:31: views 'v': unknown placeholder '{day}' in output template "
              "'{camera}_{day}.png' "
              "(known: {view} {camera} {path} {frame} {scenario} {step} {t} {time} "
              "{time:FORMAT})");
    EXPECT_EQ(errorOf(base + "path p { keys = [{ at = 0s, position = geo(0deg, 0deg, 1km) }] }\n"
                             "views v { paths = [@p]; output = \"{frame}.png\" }"),
              "series.sylva:7:17: path 'p': a path needs at least two keys");
    EXPECT_EQ(errorOf(base + "compare c { left = @today; right = @dam }\n"
                             "views v { cameras = [@beach]; scenarios = [@today, @dam]; output = "
                             "\"{camera}_{time}.png\" }"),
              "series.sylva:8:59: views 'v': the series makes the compare image 'c', so its output "
              "template needs "
              "{scenario}");
    EXPECT_EQ(errorOf(base + "blend b { from = @today; to = @dam; steps = 5 }\n"
                             "views v { cameras = [@beach]; scenarios = [@today, @dam]; output = "
                             "\"{scenario}/{camera}.png\" }"),
              "series.sylva:8:59: views 'v': the blend 'b' is a sequence of 5 images (steps), so "
              "the output template needs {step} or {t}");
    EXPECT_EQ(errorOf(base + "blend b { from = @today; to = @dam; steps = 2.5 }\n"
                             "views v { cameras = [@beach]; scenarios = [@today, @dam]; output = "
                             "\"{scenario}/{camera}{step}.png\" }"),
              "series.sylva:7:37: blend 'b': steps must be a whole number of images, got 2.500000");
}

TEST(ViewSeriesTest, Mp4TemplatesMakeOneVideoJobPerPathAfterItsFrames) {
    const std::string base = R"(
source height : noise { octaves = 4 }
scenario today { layers = [@height] }
scenario dam extends today { override @height { amplitude = 3km } }
camera beach { position = geo(-8deg, -34.8deg, 20m) }
path approach {
    keys = [
        { at = 0s, position = geo(-7.9deg, -34.7deg, 2km), heading = 200deg },
        { at = 1s, position = geo(-8deg, -34.8deg, 500m), heading = 220deg },
    ]
    fps = 4
}
)";
    const ProjectModel model =
        load(base +
             "views film { paths = [@approach]; scenarios = [@today, @dam]; output = "
             "\"film/{scenario}.mp4\" }");
    auto jobs = ViewSeries::expand(model, "out");
    ASSERT_TRUE(jobs.ok()) << jobs.error().message;
    ASSERT_EQ(jobs.value().size(), 10u + 2u);  // 5 frames x 2 scenarios, 2 videos
    const RenderJob& video = jobs.value()[10];
    EXPECT_EQ(video.kind, RenderJobKind::Video);
    EXPECT_EQ(video.output, std::filesystem::path("out/film/today.mp4"));
    EXPECT_DOUBLE_EQ(video.framesPerSecond, 4.0);
    ASSERT_EQ(video.frames.size(), 5u);
    for (std::size_t i = 0; i < video.frames.size(); ++i) {
        const RenderJob& frame = jobs.value()[video.frames[i]];
        EXPECT_EQ(frame.frame, static_cast<int>(i));
        EXPECT_EQ(frame.scenario, "today");
        EXPECT_EQ(frame.video, std::optional<std::size_t>(10));
        EXPECT_EQ(frame.group, video.group);  // one shard encodes what it rendered
        char name[64];
        std::snprintf(name, sizeof name, "out/film/.today.mp4.frames/%05zu.png", i);
        EXPECT_EQ(frame.output, std::filesystem::path(name));
    }
    EXPECT_EQ(jobs.value()[11].output, std::filesystem::path("out/film/dam.mp4"));

    auto errorOf = [&](const std::string& views) {
        auto expanded = ViewSeries::expand(load(base + views), "out");
        return expanded.ok() ? std::string("ok") : expanded.error().message;
    };
    EXPECT_EQ(errorOf("views v { paths = [@approach]; output = \"{frame}.mp4\" }"),
              "series.sylva:13:32: views 'v': an MP4 holds every frame of a path; remove {frame} "
              "from the output template");
    EXPECT_EQ(errorOf("views v { cameras = [@beach]; output = \"{camera}.mp4\" }"),
              "series.sylva:13:31: views 'v': an MP4 output holds the frames of paths; render "
              "cameras in another views block with an image template such as \"{camera}.png\"");
    EXPECT_EQ(errorOf("views v { paths = [@approach]; scenarios = [@today, @dam]; output = "
                      "\"film.mp4\" }"),
              "series.sylva:13:60: views 'v': two videos would be written to 'out/film.mp4' "
              "(approach today; approach dam); add {path}, {scenario} or {time} to the template");
}

TEST(ViewSeriesTest, BlendSequenceRunsFromZeroToOne) {
    const ProjectModel model = load(R"(
source height : noise { octaves = 4 }
scenario today { layers = [@height] }
scenario dam extends today { override @height { amplitude = 3km } }
blend grow { from = @today; to = @dam; steps = 5 }
camera beach { position = geo(-8deg, -34.8deg, 20m) }
views v {
    cameras = [@beach]
    scenarios = [@today, @dam]
    output = "{scenario}/{camera}_{step}_{t}.png"
}
)");
    auto jobs = ViewSeries::expand(model, "out");
    ASSERT_TRUE(jobs.ok()) << jobs.error().message;
    ASSERT_EQ(jobs.value().size(), 2u + 5u);
    EXPECT_EQ(jobs.value()[0].output, std::filesystem::path("out/today/beach__.png"));
    const double expected[] = {0.0, 0.25, 0.5, 0.75, 1.0};
    for (int step = 0; step < 5; ++step) {
        const RenderJob& job = jobs.value()[2 + static_cast<std::size_t>(step)];
        EXPECT_EQ(job.kind, RenderJobKind::Blend);
        EXPECT_EQ(job.step, step);
        EXPECT_DOUBLE_EQ(job.blendAmount, expected[step]);
        EXPECT_EQ(job.first, 0u);
        EXPECT_EQ(job.second, 1u);
        char name[64];
        std::snprintf(name, sizeof name, "out/grow/beach_%03d_%.3f.png", step, expected[step]);
        EXPECT_EQ(job.output, std::filesystem::path(name));
        EXPECT_EQ(job.group, jobs.value()[0].group);  // shards keep the sequence together
    }
}

}  // namespace
}  // namespace sylva
