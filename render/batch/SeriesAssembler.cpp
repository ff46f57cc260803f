#include "sylva/render/batch/SeriesAssembler.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <string>
#include <system_error>
#include <vector>

#include "sylva/core/image/ContactSheet.h"
#include "sylva/core/image/ImageComparison.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/image/Photomontage.h"
#include "sylva/core/image/ToneMapping.h"
#include "sylva/core/model/BlockReader.h"
#include "sylva/core/scene/PhotoViewpoint.h"
#include "sylva/render/batch/VideoEncoder.h"

namespace sylva::render {
namespace {

// An image of the series as displayed: EXR tone-mapped, anything else 8-bit sRGB.
Result<RgbaImage> readDisplayed(const std::filesystem::path& path) {
    if (ImageWriter::isExr(path)) {
        Result<LinearImage> linear = ImageWriter::readLinear(path);
        if (!linear) {
            return linear.error();
        }
        return ToneMapping::display(linear.value());
    }
    RgbaImage image;
    Result<std::vector<std::uint8_t>> pixels =
        ImageWriter::readRgba8(path, image.width, image.height);
    if (!pixels) {
        return pixels.error();
    }
    image.pixels = std::move(pixels.value());
    return image;
}

// An image of the series as radiance: EXR as stored, anything else through the inverse
// tone map.
Result<LinearImage> readRadiance(const std::filesystem::path& path) {
    if (ImageWriter::isExr(path)) {
        return ImageWriter::readLinear(path);
    }
    Result<RgbaImage> image = readDisplayed(path);
    if (!image) {
        return image.error();
    }
    return ToneMapping::radiance(image.value());
}

// The comparison image of `job` from its two inputs (RgbaImage or LinearImage).
template <typename Image>
Result<Image> composeImages(const RenderJob& job, BlockReader& reader, const Image& first,
                            const Image& second, const std::string& firstName,
                            const std::string& secondName) {
    if (job.kind == RenderJobKind::Blend) {
        return ImageComparison::blend(first, second, job.blendAmount);
    }
    const Value* layout = reader.value("layout");
    const std::string mode = layout && layout->get<Word>() ? layout->get<Word>()->text : "swipe";
    Result<Image> made = Error{"unknown comparison"};
    if (mode == "side_by_side") {
        made = ImageComparison::sideBySide(first, second);
    } else if (mode == "difference") {
        made = ImageComparison::difference(first, second);
    } else {
        made = ImageComparison::swipe(first, second, reader.optionalNumber("split").value_or(0.5));
    }
    if (made && reader.boolean("labels", true) && mode != "difference") {
        ImageComparison::label(made.value(), firstName);
        ImageComparison::label(made.value(), secondName, true);
    }
    return made;
}

// The thumbnail label of an image: camera or path frame, scenario, blend amount, time.
std::string sheetLabel(const RenderJob& job) {
    // Appended piecewise: GCC 12's -Wrestrict misfires on `label += " " + text`.
    std::string label = job.path.empty() ? job.camera : job.path;
    if (!job.path.empty()) {
        label.append(" #").append(std::to_string(job.frame));
    }
    label.append(" ").append(job.scenario);
    if (job.step >= 0) {
        char text[16];
        std::snprintf(text, sizeof text, " t=%.2f", job.blendAmount);
        label.append(text);
    }
    if (job.time) {
        label.append(" ").append(job.time->text().substr(11, 5));
    }
    return label;
}

}  // namespace

void SeriesAssembler::assemble() {
    for (const RenderJob& job : run_.plan().jobs()) {
        if (job.kind == RenderJobKind::Image) {
            continue;
        }
        if (run_.cancelled()) {
            return;
        }
        if (run_.skipIfCurrent(job)) {
            continue;
        }
        if (job.kind == RenderJobKind::Video) {
            encode(job);
        } else {
            compose(job);
        }
    }
}

void SeriesAssembler::encode(const RenderJob& job) {
    const auto start = std::chrono::steady_clock::now();
    BatchPlan& plan = run_.plan();
    if (std::any_of(job.frames.begin(), job.frames.end(),
                    [&](std::size_t frame) { return run_.failed(frame); })) {
        run_.fail(job, job.output.string() + ": not encoded: some of its frames failed");
        return;
    }
    const std::filesystem::path frames = plan.job(job.frames.front()).output.parent_path();
    const std::string ffmpeg =
        plan.ffmpeg().empty() ? VideoEncoder::findOnPath("ffmpeg") : plan.ffmpeg();
    if (Status encoded = VideoEncoder(ffmpeg.empty() ? std::string("ffmpeg") : ffmpeg)
                             .encode(frames, job.output, job.framesPerSecond);
        !encoded) {
        run_.fail(job, encoded.error().message);
        return;
    }
    // The frames were only the video's input.
    std::error_code ignored;
    std::filesystem::remove_all(frames, ignored);
    JobReport report;
    report.job = &job;
    report.seconds = run_.record(job, start, 0, static_cast<int>(job.frames.size()));
    run_.done(report);
}

bool SeriesAssembler::isWireline(const BatchPlan& plan, const RenderJob& job) {
    if (job.kind != RenderJobKind::Compare) {
        return false;
    }
    const Value* mode = BlockReader(plan.comparisonBlock(job), nullptr).value("mode");
    return mode != nullptr && mode->get<Word>() != nullptr && mode->get<Word>()->text == "wireline";
}

void SeriesAssembler::composeWireline(const RenderJob& job, const Block& block) {
    const auto start = std::chrono::steady_clock::now();
    const BatchPlan& plan = run_.plan();
    const std::string where =
        block.location.toString() + ": compare '" + block.name + "' (mode = wireline): ";
    if (ImageWriter::isExr(job.output)) {
        run_.fail(job, where +
                           "wirelines are drawn in 8-bit sRGB; give the views an output "
                           "template ending in .png");
        return;
    }
    const BatchRun::Depth* left = run_.depthOf(job.first);
    const BatchRun::Depth* right = run_.depthOf(job.second);
    Result<RgbaImage> image = readDisplayed(plan.job(job.first).output);
    if (left == nullptr || right == nullptr || !image) {
        run_.fail(job,
                  job.output.string() + ": not drawn: " +
                      (image ? std::string("the depth of the images it compares is not in this run "
                                           "(one failed, or they were rendered by another "
                                           "process: a wireline is made in the run that "
                                           "renders its images)")
                             : image.error().message));
        return;
    }
    const std::size_t pixels = static_cast<std::size_t>(image->width) * image->height;
    if (left->depth.size() != pixels || right->depth.size() != pixels) {
        run_.fail(job, where + "the two scenarios were rendered at different sizes");
        return;
    }
    // depth = near / distance: the right render's depths on the left render's near plane.
    std::vector<float> proposed = right->depth;
    for (float& depth : proposed) {
        depth = static_cast<float>(depth * (left->near / right->near));
    }
    const WirelineMasks masks =
        WirelineMasks::fromDepths(left->depth, proposed, image->width, image->height);
    const BlockReader reader(block, SchemaRegistry::builtin().find(block.keyword));
    Photomontage::drawWireline(image.value(), masks, wirelineStyleOf(reader));
    if (Status written = ImageWriter::writeRgba8(job.output, image->width, image->height,
                                                 image->pixels, plan.metadataFor(job));
        !written) {
        run_.fail(job, written.error().message);
        return;
    }
    JobReport report;
    report.job = &job;
    report.seconds = run_.record(job, start);
    report.width = image->width;
    report.height = image->height;
    report.firstScenario = plan.job(job.first).scenario;
    report.secondScenario = plan.job(job.second).scenario;
    run_.done(report);
}

void SeriesAssembler::compose(const RenderJob& job) {
    const auto start = std::chrono::steady_clock::now();
    const BatchPlan& plan = run_.plan();
    const Block& block = plan.comparisonBlock(job);
    if (isWireline(plan, job)) {
        composeWireline(job, block);
        return;
    }
    BlockReader reader(block, SchemaRegistry::builtin().find(block.keyword));
    const std::string& firstName = plan.job(job.first).scenario;
    const std::string& secondName = plan.job(job.second).scenario;
    const std::filesystem::path& firstFile = plan.job(job.first).output;
    const std::filesystem::path& secondFile = plan.job(job.second).output;
    // Reads both scenario images (radiance for EXR, displayed pixels otherwise), composes
    // them and writes the result; false after reporting a failure.
    Status written;
    int width = 0, height = 0;
    const auto composeFiles = [&](const auto& read, const auto& write) {
        const auto a = read(firstFile);
        const auto b = read(secondFile);
        if (!a || !b) {
            run_.fail(job, job.output.string() + ": cannot read the images to compare: " +
                               (!a ? a.error().message : b.error().message));
            return false;
        }
        const auto made = composeImages(job, reader, a.value(), b.value(), firstName, secondName);
        if (!made) {
            run_.fail(job, block.location.toString() + ": " + block.keyword + " '" + block.name +
                               "': " + made.error().message);
            return false;
        }
        width = made.value().width;
        height = made.value().height;
        written = write(made.value());
        return true;
    };
    const bool composed =
        ImageWriter::isExr(job.output)
            ? composeFiles(readRadiance,
                           [&](const LinearImage& image) {
                               return ImageWriter::writeLinear(job.output, image,
                                                               plan.metadataFor(job));
                           })
            : composeFiles(readDisplayed, [&](const RgbaImage& image) {
                  return ImageWriter::writeRgba8(job.output, image.width, image.height,
                                                 image.pixels, plan.metadataFor(job));
              });
    if (!composed) {
        return;
    }
    if (!written) {
        run_.fail(job, written.error().message);
        return;
    }
    JobReport report;
    report.job = &job;
    report.seconds = run_.record(job, start);
    report.width = width;
    report.height = height;
    report.firstScenario = firstName;
    report.secondScenario = secondName;
    run_.done(report);
}

void SeriesAssembler::writeContactSheets() {
    const BatchPlan& plan = run_.plan();
    if (!plan.wholeSeries() || run_.summary().failed > 0) {
        return;
    }
    std::map<std::string, std::vector<ContactSheetEntry>> sheets;
    for (const RenderJob& job : plan.jobs()) {
        if (job.kind == RenderJobKind::Video || job.video) {
            continue;
        }
        Result<RgbaImage> image = readDisplayed(job.output);
        if (!image) {
            continue;
        }
        const int width = image.value().width;
        const int height = image.value().height;
        sheets[job.view].push_back(
            {sheetLabel(job),
             ContactSheet::resize(image.value(), 320,
                                  std::max(1, 320 * height / std::max(width, 1)))});
    }
    for (const auto& [view, entries] : sheets) {
        if (entries.size() < 2) {
            continue;
        }
        Result<RgbaImage> sheet = ContactSheet::build(entries, 320);
        const std::filesystem::path file =
            plan.selection().outputFolder / (view + "_contact_sheet.png");
        if (sheet && ImageWriter::writeRgba8(file, sheet.value().width, sheet.value().height,
                                             sheet.value().pixels, plan.sheetMetadata(view))) {
            run_.listener().contactSheetWritten(file, entries.size());
        }
    }
}

}  // namespace sylva::render
