// render::BatchRenderer as a library: a small view series (two cameras × two scenarios on
// constant layers, plus a swipe comparison per camera) rendered through it on llvmpipe —
// files, manifest and metadata; resume by content hash; shards that partition the series;
// a job range; cancellation that leaves only finished files; and VideoEncoder with stand-in
// ffmpeg programs (the real one is exercised by the CLI test when installed).
#include "sylva/render/batch/BatchRenderer.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "sylva/core/image/ImageWriter.h"
#include "sylva/dsl/ProjectLoader.h"
#include "sylva/render/batch/VideoEncoder.h"

namespace sylva::render {
namespace {

// Jobs in series order: images east/today, east/drought, west/today, west/drought, then
// the comparisons change/east, change/west.
std::string seriesText(const std::string& dryColour = "#b09060") {
    return "source height : constant { height = 200m }\n"
           "source colour : constant { kind = image; color = #4a7a3a }\n"
           "source dry : constant { kind = image; color = " +
           dryColour +
           " }\n"
           "scenario today { layers = [@height, @colour] }\n"
           "scenario drought { layers = [@height, @dry] }\n"
           "compare change { left = @today; right = @drought; layout = swipe; labels = false }\n"
           "camera east { position = geo(10deg, 20deg, 3km); heading = 90deg; pitch = -20deg }\n"
           "camera west { position = geo(10deg, 20deg, 3km); heading = 270deg; pitch = -20deg }\n"
           "views photos {\n"
           "    scenarios = [@today, @drought]\n"
           "    cameras = [@east, @west]\n"
           "    output = \"{scenario}/{camera}.png\"\n"
           "}\n"
           "render { resolution = [32px, 18px]; atmosphere = false }\n";
}

std::vector<ProjectModel> load(const std::string& text) {
    dsl::LoadResult loaded = dsl::loadProjectFromString(text, "series.sylva");
    EXPECT_FALSE(loaded.hasErrors()) << loaded.render();
    return loaded.scenarios;
}

std::filesystem::path scratch(const std::string& name) {
    const std::filesystem::path folder =
        std::filesystem::path(SYLVA_TEST_OUTPUT_DIR) / "batch" / name;
    std::filesystem::remove_all(folder);
    return folder;
}

// Every regular file below `folder`, relative to it.
std::set<std::string> filesBelow(const std::filesystem::path& folder) {
    std::set<std::string> files;
    if (!std::filesystem::exists(folder)) {
        return files;
    }
    for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
        if (entry.is_regular_file()) {
            files.insert(entry.path().lexically_relative(folder).generic_string());
        }
    }
    return files;
}

std::vector<std::uint8_t> readPixels(const std::filesystem::path& file, int& width, int& height) {
    Result<std::vector<std::uint8_t>> pixels = ImageWriter::readRgba8(file, width, height);
    EXPECT_TRUE(pixels) << file;
    return pixels ? pixels.value() : std::vector<std::uint8_t>{};
}

// Records what the run reports; optionally sets `cancel` after the first job.
class Recorder final : public BatchListener {
public:
    void jobDone(const JobReport& report) override {
        (report.skipped ? skipped : made).push_back(report.job->index);
        if (cancelAfterFirst) {
            cancel.store(true);
        }
    }
    void error(const std::string& message) override { errors.push_back(message); }
    void contactSheetWritten(const std::filesystem::path& file, std::size_t images) override {
        sheets.push_back(file.filename().string() + ":" + std::to_string(images));
    }

    std::vector<std::size_t> made, skipped;
    std::vector<std::string> errors, sheets;
    bool cancelAfterFirst = false;
    std::atomic<bool> cancel{false};
};

BatchSummary runSeries(BatchRenderer& batch, const BatchSelection& selection, Recorder& recorder) {
    Result<BatchPlan> plan = batch.plan(selection);
    EXPECT_TRUE(plan) << plan.error().message;
    if (!plan) {
        return {};
    }
    Result<BatchSummary> summary = batch.run(plan.value(), recorder, &recorder.cancel);
    EXPECT_TRUE(summary) << summary.error().message;
    return summary ? summary.value() : BatchSummary{};
}

TEST(BatchRenderer, RendersASeriesWithComparisonsAContactSheetAndAManifest) {
    BatchRenderer batch;
    ASSERT_TRUE(batch.setProject(load(seriesText())));
    BatchSelection selection;
    selection.outputFolder = scratch("series");
    Recorder recorder;
    const BatchSummary summary = runSeries(batch, selection, recorder);
    EXPECT_EQ(summary.total, 6u);
    EXPECT_EQ(summary.failed, 0);
    EXPECT_EQ(summary.degraded, 0);
    EXPECT_TRUE(recorder.errors.empty()) << recorder.errors.front();
    // Images first, one viewpoint's scenarios together, then the comparisons.
    EXPECT_EQ(recorder.made, (std::vector<std::size_t>{0, 1, 2, 3, 4, 5}));
    EXPECT_EQ(recorder.sheets, std::vector<std::string>{"photos_contact_sheet.png:6"});
    EXPECT_EQ(filesBelow(selection.outputFolder),
              (std::set<std::string>{"today/east.png", "today/west.png", "drought/east.png",
                                     "drought/west.png", "change/east.png", "change/west.png",
                                     "photos_contact_sheet.png", "manifest.json"}));

    // The swipe shows today left of the split and drought right of it, pixel for pixel.
    int width = 0, height = 0;
    const std::vector<std::uint8_t> today =
        readPixels(selection.outputFolder / "today/east.png", width, height);
    const std::vector<std::uint8_t> drought =
        readPixels(selection.outputFolder / "drought/east.png", width, height);
    const std::vector<std::uint8_t> swipe =
        readPixels(selection.outputFolder / "change/east.png", width, height);
    ASSERT_EQ(width, 32);
    ASSERT_EQ(height, 18);
    const std::size_t bottomLeft = (std::size_t(height - 1) * width + 2) * 4;
    const std::size_t bottomRight = (std::size_t(height - 1) * width + width - 3) * 4;
    EXPECT_NE(today, drought);
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(swipe[bottomLeft + c], today[bottomLeft + c]);
        EXPECT_EQ(swipe[bottomRight + c], drought[bottomRight + c]);
    }

    // The manifest and the metadata carry the plan's hash of each job.
    RenderManifest manifest(selection.outputFolder / "manifest.json");
    ASSERT_TRUE(manifest.load());
    EXPECT_EQ(manifest.entries().size(), 6u);
    Result<BatchPlan> plan = BatchPlan::make(batch.project(), batch.setup().value(), selection);
    ASSERT_TRUE(plan);
    for (const RenderJob& job : plan->jobs()) {
        const std::string relative = plan->relativeOutput(job.output);
        ASSERT_TRUE(manifest.entries().count(relative)) << relative;
        EXPECT_EQ(manifest.entries().at(relative).hash, plan->hashOf(job));
        EXPECT_TRUE(manifest.isCurrent(relative, plan->hashOf(job)));
    }
    Result<ImageMetadata> metadata = ImageWriter::readMetadata(
        selection.outputFolder / "change/west.png", {"sylva:compare", "sylva:scenario"});
    ASSERT_TRUE(metadata);
    ASSERT_TRUE(metadata->find("sylva:scenario"));
    EXPECT_EQ(*metadata->find("sylva:scenario"), "today | drought");
    EXPECT_EQ(*metadata->find("sylva:compare"), "change");
}

TEST(BatchRenderer, ResumeSkipsCurrentJobsAndRemakesWhatAnEditChanged) {
    BatchSelection selection;
    selection.outputFolder = scratch("resume");
    {
        BatchRenderer batch;
        ASSERT_TRUE(batch.setProject(load(seriesText())));
        Recorder recorder;
        EXPECT_EQ(runSeries(batch, selection, recorder).done, 6u);
    }
    selection.resume = true;
    BatchRenderer batch;
    ASSERT_TRUE(batch.setProject(load(seriesText())));
    Recorder unchanged;
    EXPECT_EQ(runSeries(batch, selection, unchanged).skipped, 6);
    EXPECT_TRUE(unchanged.made.empty());
    // Another colour for the drought scenario: its images and both comparisons change,
    // today's images stay.
    ASSERT_TRUE(batch.setProject(load(seriesText("#806040"))));
    Recorder edited;
    const BatchSummary summary = runSeries(batch, selection, edited);
    EXPECT_EQ(summary.skipped, 2);
    EXPECT_EQ(edited.skipped, (std::vector<std::size_t>{0, 2}));
    EXPECT_EQ(edited.made, (std::vector<std::size_t>{1, 3, 4, 5}));
}

TEST(BatchRenderer, ShardsPartitionTheSeriesAndKeepTheirOwnManifests) {
    BatchRenderer batch;
    ASSERT_TRUE(batch.setProject(load(seriesText())));
    BatchSelection selection;
    selection.outputFolder = scratch("shards");
    std::multiset<std::size_t> made;
    for (int shard = 1; shard <= 2; ++shard) {
        selection.shard = {shard, 2};
        Recorder recorder;
        const BatchSummary summary = runSeries(batch, selection, recorder);
        EXPECT_EQ(summary.failed, 0);
        EXPECT_TRUE(recorder.sheets.empty());  // a shard sees only part of the series
        // A comparison lives in the shard of its two images.
        for (std::size_t index : recorder.made) {
            if (index >= 4) {
                const std::size_t camera = index - 4;  // change/east: 0, change/west: 1
                EXPECT_EQ(std::count(recorder.made.begin(), recorder.made.end(), 2 * camera), 1);
                EXPECT_EQ(std::count(recorder.made.begin(), recorder.made.end(), 2 * camera + 1),
                          1);
            }
        }
        made.insert(recorder.made.begin(), recorder.made.end());
    }
    EXPECT_EQ(made, (std::multiset<std::size_t>{0, 1, 2, 3, 4, 5}));
    const std::set<std::string> files = filesBelow(selection.outputFolder);
    EXPECT_TRUE(files.count("manifest.shard-1-of-2.json"));
    EXPECT_TRUE(files.count("manifest.shard-2-of-2.json"));
    EXPECT_FALSE(files.count("manifest.json"));
}

TEST(BatchRenderer, ARangeSelectsJobsByTheirIndexInTheSeries) {
    BatchRenderer batch;
    ASSERT_TRUE(batch.setProject(load(seriesText())));
    BatchSelection selection;
    selection.outputFolder = scratch("range");
    selection.range = JobRange{2, 4};
    Result<BatchPlan> plan = BatchPlan::make(batch.project(), batch.setup().value(), selection);
    ASSERT_TRUE(plan) << plan.error().message;
    std::vector<std::size_t> indices;
    for (const RenderJob& job : plan->jobs()) {
        indices.push_back(job.index);
    }
    EXPECT_EQ(indices, (std::vector<std::size_t>{2, 3, 4}));
    EXPECT_EQ(plan->allJobs().size(), 6u);
    EXPECT_FALSE(plan->wholeSeries());
    // Nothing is written by making a plan.
    EXPECT_FALSE(std::filesystem::exists(selection.outputFolder));

    selection.range = JobRange{5, 6};
    Result<BatchPlan> beyond = BatchPlan::make(batch.project(), batch.setup().value(), selection);
    ASSERT_FALSE(beyond);
    EXPECT_EQ(beyond.error().message, "jobs 5-6 are not within the series' jobs 0-5");
}

TEST(BatchRenderer, CancellationLeavesOnlyFinishedFilesAndResumeCompletesTheRest) {
    BatchRenderer batch;
    ASSERT_TRUE(batch.setProject(load(seriesText())));
    BatchSelection selection;
    selection.outputFolder = scratch("cancel");
    Recorder stopped;
    stopped.cancelAfterFirst = true;
    const BatchSummary summary = runSeries(batch, selection, stopped);
    EXPECT_TRUE(summary.cancelled);
    EXPECT_EQ(summary.done, 1u);
    EXPECT_TRUE(stopped.sheets.empty());
    // The one finished image and a manifest that lists exactly it; no temporary files.
    EXPECT_EQ(filesBelow(selection.outputFolder),
              (std::set<std::string>{"today/east.png", "manifest.json"}));
    RenderManifest manifest(selection.outputFolder / "manifest.json");
    ASSERT_TRUE(manifest.load());
    ASSERT_EQ(manifest.entries().size(), 1u);
    EXPECT_EQ(manifest.entries().begin()->first, "today/east.png");

    selection.resume = true;
    Recorder resumed;
    const BatchSummary rest = runSeries(batch, selection, resumed);
    EXPECT_FALSE(rest.cancelled);
    EXPECT_EQ(resumed.skipped, std::vector<std::size_t>{0});
    EXPECT_EQ(resumed.made, (std::vector<std::size_t>{1, 2, 3, 4, 5}));
}

TEST(BatchRenderer, AJobThatFailsIsReportedAndTheRunGoesOn) {
    // The west camera is below the terrain (200 m constant ground, camera at 100 m).
    std::string text = seriesText();
    const std::string west = "camera west { position = geo(10deg, 20deg, 3km)";
    text.replace(text.find(west), west.size(), "camera west { position = geo(10deg, 20deg, 100m)");
    BatchRenderer batch;
    ASSERT_TRUE(batch.setProject(load(text)));
    BatchSelection selection;
    selection.outputFolder = scratch("failing");
    Recorder recorder;
    const BatchSummary summary = runSeries(batch, selection, recorder);
    // Both west images fail, so does the comparison made of them; no contact sheet.
    EXPECT_EQ(summary.failed, 3);
    EXPECT_EQ(recorder.made, (std::vector<std::size_t>{0, 1, 4}));
    ASSERT_EQ(recorder.errors.size(), 3u);
    EXPECT_NE(recorder.errors[0].find("series.sylva:8:8: camera 'west'"), std::string::npos)
        << recorder.errors[0];
    EXPECT_NE(recorder.errors[2].find("cannot read the images to compare"), std::string::npos)
        << recorder.errors[2];
    EXPECT_TRUE(recorder.sheets.empty());
    RenderManifest manifest(selection.outputFolder / "manifest.json");
    ASSERT_TRUE(manifest.load());
    EXPECT_EQ(manifest.entries().size(), 3u);
}

// A stand-in for ffmpeg: a shell script at `path` running `body`.
void writeProgram(const std::filesystem::path& path, const std::string& body) {
    std::ofstream(path) << "#!/bin/sh\n" << body << "\n";
    std::filesystem::permissions(path, std::filesystem::perms::owner_all);
}

TEST(VideoEncoder, EncodesThroughTheProgramAndMovesTheVideoIntoPlace) {
    const std::filesystem::path folder = scratch("video");
    const std::filesystem::path frames = folder / ".film.mp4.frames";
    std::filesystem::create_directories(frames);
    // Writes its arguments into the last one (the temporary output).
    const std::filesystem::path program = folder / "fake-ffmpeg";
    writeProgram(program, "for last; do :; done; echo \"$@\" > \"$last\"");
    ASSERT_TRUE(VideoEncoder(program.string()).encode(frames, folder / "film.mp4", 12.5));
    std::ifstream stream(folder / "film.mp4");
    std::stringstream arguments;
    arguments << stream.rdbuf();
    EXPECT_NE(
        arguments.str().find("-framerate 12.5 -start_number 0 -i " +
                             (frames / "%05d.png").string() + " -c:v libx264 -pix_fmt yuv420p"),
        std::string::npos)
        << arguments.str();
    EXPECT_EQ(filesBelow(folder),
              (std::set<std::string>{"fake-ffmpeg", "film.mp4", ".film.mp4.frames/ffmpeg.log"}));
}

TEST(VideoEncoder, AFailingProgramIsAnErrorWithItsMessagesAndLeavesNoFile) {
    const std::filesystem::path folder = scratch("video-fails");
    std::filesystem::create_directories(folder / "frames");
    const std::filesystem::path program = folder / "broken-ffmpeg";
    writeProgram(program, "for last; do :; done; : > \"$last\"; echo 'no codec' >&2; exit 3");
    Status encoded = VideoEncoder(program.string()).encode(folder / "frames", folder / "a.mp4", 24);
    ASSERT_FALSE(encoded);
    EXPECT_EQ(encoded.error().message,
              (folder / "a.mp4").string() + ": ffmpeg failed (exit 3): no codec");
    EXPECT_EQ(filesBelow(folder), (std::set<std::string>{"broken-ffmpeg", "frames/ffmpeg.log"}));

    Status missing = VideoEncoder((folder / "no-such-program").string())
                         .encode(folder / "frames", folder / "b.mp4", 24);
    ASSERT_FALSE(missing);
    EXPECT_NE(missing.error().message.find("ffmpeg failed (exit 127)"), std::string::npos);
    EXPECT_FALSE(std::filesystem::exists(folder / "b.mp4"));
}

TEST(VideoEncoder, FindsProgramsOnPathOnly) {
    EXPECT_FALSE(VideoEncoder::findOnPath("sh").empty());
    EXPECT_TRUE(VideoEncoder::findOnPath("sylva-no-such-program").empty());
}

// Verified views from the project file (issue 18): a 90° cylindrical camera with a print
// format renders at the print's pixel size, carries its viewpoint record in the PNG, and
// `sheet = true` writes the PDF/PNG sheet and the JSON sidecar beside it. A sheet for a
// camera without a print format fails that job, located at `sheet`, writing nothing.
TEST(BatchRenderer, CylindricalViewpointWithSheetFromTheProjectFile) {
    const std::string base =
        "source height : constant { height = 200m }\n"
        "source colour : constant { kind = image; color = #4a7a3a }\n"
        "scenario today { layers = [@height, @colour] }\n"
        "camera vp1 { position = geo(10deg, 20deg); eye_height = 50m; heading = 90deg\n"
        "    projection = cylindrical; horizontal_fov = 90deg\n"
        "    output_size = [100mm, 30mm]; dpi = 50 }\n"
        "camera plain { position = geo(10deg, 20deg, 3km); pitch = -20deg }\n"
        "render { resolution = [32px, 18px]; atmosphere = false }\n";
    BatchRenderer batch;
    ASSERT_TRUE(batch.setProject(
        load(base + "views pack { cameras = [@vp1]; output = \"{camera}.png\"; sheet = true }\n")));
    BatchSelection selection;
    selection.outputFolder = scratch("sheet");
    Recorder recorder;
    const BatchSummary summary = runSeries(batch, selection, recorder);
    EXPECT_EQ(summary.failed, 0);
    ASSERT_TRUE(recorder.errors.empty()) << recorder.errors.front();
    const std::set<std::string> files = filesBelow(selection.outputFolder);
    for (const char* file : {"vp1.png", "vp1.sheet.pdf", "vp1.sheet.png", "vp1.json"}) {
        EXPECT_TRUE(files.count(file)) << file;
    }
    int width = 0, height = 0;
    readPixels(selection.outputFolder / "vp1.png", width, height);
    EXPECT_EQ(width, 197);  // 100 mm at 50 dpi
    EXPECT_EQ(height, 59);  // 30 mm at 50 dpi
    Result<ImageMetadata> metadata = ImageWriter::readMetadata(
        selection.outputFolder / "vp1.png",
        {"sylva:viewpoint:horizontal_fov_deg", "sylva:viewpoint:viewing_distance_mm",
         "sylva:viewpoint:eye_height_m"});
    ASSERT_TRUE(metadata);
    ASSERT_TRUE(metadata->find("sylva:viewpoint:horizontal_fov_deg"));
    EXPECT_EQ(*metadata->find("sylva:viewpoint:horizontal_fov_deg"), "90.00°");
    EXPECT_EQ(*metadata->find("sylva:viewpoint:viewing_distance_mm"), "64 mm");  // 100 / (π/2)
    EXPECT_EQ(*metadata->find("sylva:viewpoint:eye_height_m"), "50.00 m");
    std::ifstream json(selection.outputFolder / "vp1.json");
    const std::string text((std::istreambuf_iterator<char>(json)), {});
    EXPECT_NE(text.find("\"projection\": \"cylindrical\""), std::string::npos) << text;

    BatchRenderer bad;
    ASSERT_TRUE(
        bad.setProject(load(base + "views pack {\n    cameras = [@plain]\n    sheet = true\n}\n")));
    selection.outputFolder = scratch("sheet_without_print");
    Recorder failing;
    const BatchSummary failed = runSeries(bad, selection, failing);
    EXPECT_EQ(failed.failed, 1);
    ASSERT_EQ(failing.errors.size(), 1u);
    EXPECT_NE(failing.errors[0].find("series.sylva:11:13: views 'pack': a viewpoint sheet needs "
                                     "the print format of camera 'plain'"),
              std::string::npos)
        << failing.errors[0];
    EXPECT_FALSE(std::filesystem::exists(selection.outputFolder / "plain.png"));
}

// A sheet is written only after its image: when the image cannot be written (here a
// folder stands where the PNG goes), the job fails and neither the sheet nor its JSON
// record is left beside the missing image.
TEST(BatchRenderer, NoSheetWhenTheImageWriteFails) {
    BatchRenderer batch;
    ASSERT_TRUE(batch.setProject(
        load("source height : constant { height = 200m }\n"
             "source colour : constant { kind = image; color = #4a7a3a }\n"
             "scenario today { layers = [@height, @colour] }\n"
             "camera vp1 { position = geo(10deg, 20deg); eye_height = 50m; heading = 90deg\n"
             "    horizontal_fov = 60deg; output_size = [100mm, 30mm]; dpi = 50 }\n"
             "render { resolution = [32px, 18px]; atmosphere = false }\n"
             "views pack { cameras = [@vp1]; output = \"{camera}.png\"; sheet = true }\n")));
    BatchSelection selection;
    selection.outputFolder = scratch("sheet_image_fails");
    std::filesystem::create_directories(selection.outputFolder / "vp1.png" / "blocker");
    Recorder recorder;
    const BatchSummary summary = runSeries(batch, selection, recorder);
    EXPECT_EQ(summary.failed, 1);
    ASSERT_FALSE(recorder.errors.empty());
    for (const char* file : {"vp1.sheet.pdf", "vp1.sheet.png", "vp1.json"}) {
        EXPECT_FALSE(std::filesystem::exists(selection.outputFolder / file)) << file;
    }
}

}  // namespace
}  // namespace sylva::render
