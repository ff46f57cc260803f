#include "PhotoDeliverables.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "ProjectSession.h"
#include "sylva/core/base/AtomicFile.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/image/ProposalMask.h"
#include "sylva/core/scene/ViewpointSheet.h"
#include "sylva/render/batch/PhotomontageRenderer.h"

namespace sylva::app {
namespace {

constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;

nlohmann::ordered_json summaryOf(const PlannedPhoto& photo,
                                 const render::PhotomontageResult& result) {
    nlohmann::ordered_json summary;
    const Camera& camera = result.camera;
    summary["name"] = photo.viewpoint.name;
    summary["photo"] = photo.viewpoint.file.string();
    summary["width"] = photo.picture.image.width;
    summary["height"] = photo.picture.image.height;
    summary["camera"] = photo.viewpoint.camera;
    summary["scenario"] = photo.viewpoint.scenario;
    summary["baseline"] = photo.viewpoint.baseline;
    summary["latitude_deg"] = camera.geodetic.latitude * kDegreesPerRadian;
    summary["longitude_deg"] = camera.geodetic.longitude * kDegreesPerRadian;
    summary["height_m"] = camera.geodetic.height;
    summary["heading_deg"] = camera.heading() * kDegreesPerRadian;
    summary["pitch_deg"] = camera.pitch() * kDegreesPerRadian;
    summary["roll_deg"] = CameraMatcher::roll(camera) * kDegreesPerRadian;
    summary["horizontal_fov_deg"] =
        2.0 *
        std::atan(std::tan(camera.verticalFov / 2.0) * photo.picture.image.width /
                  photo.picture.image.height) *
        kDegreesPerRadian;
    summary["vertical_fov_deg"] = camera.verticalFov * kDegreesPerRadian;
    if (photo.picture.exif.focalLength35mm) {
        summary["exif_focal_length_35mm"] = *photo.picture.exif.focalLength35mm;
    }
    if (!photo.picture.exif.dateTimeOriginal.empty()) {
        summary["exif_date_time_original"] = photo.picture.exif.dateTimeOriginal;
    }
    summary["ev100"] = result.ev100;
    summary["proposal_pixels"] = ProposalMask::count(result.proposal);
    if (result.extent) {
        summary["proposal_distance_m"] = result.extent->nearestDistance;
        summary["proposal_extent_deg"] = result.extent->horizontalExtent * kDegreesPerRadian;
    }
    if (result.match) {
        nlohmann::ordered_json points = nlohmann::ordered_json::array();
        for (std::size_t i = 0; i < result.match->residuals.size(); ++i) {
            points.push_back({{"point", photo.viewpoint.controlPoints[i].name},
                              {"residual_x_px", result.match->residuals[i].x},
                              {"residual_y_px", result.match->residuals[i].y},
                              {"residual_px", result.match->residualLengths[i]}});
        }
        summary["control_points"] = std::move(points);
        summary["rms_px"] = result.match->rms;
        summary["iterations"] = result.match->iterations;
    }
    return summary;
}

// Writes the block's files; on a failure removes the ones written before it.
bool writeOutputs(const PlannedPhoto& photo, const render::PhotomontageResult& result,
                  const nlohmann::ordered_json& summary,
                  const std::optional<ViewpointRecord>& record,
                  const std::filesystem::path& outFolder) {
    const std::filesystem::path prefix = outFolder / photo.viewpoint.output;
    std::error_code error;
    std::filesystem::create_directories(prefix.parent_path().empty() ? "." : prefix.parent_path(),
                                        error);
    std::vector<std::filesystem::path> written;
    auto fail = [&](const std::string& message) {
        reportError("photo '" + photo.viewpoint.name + "': " + message);
        for (const std::filesystem::path& path : written) {
            std::filesystem::remove(path, error);
        }
        return false;
    };
    const std::pair<const char*, const RgbaImage*> images[] = {
        {"_montage.png", &result.montage},
        {"_wireline.png", &result.wireline},
        {"_model.png", &result.model},
        {"_annotated.png", &result.annotated}};
    for (const auto& [suffix, image] : images) {
        if (image->pixels.empty()) {  // _annotated.png only when asked for
            continue;
        }
        const std::filesystem::path path = prefix.string() + suffix;
        if (Status ok = ImageWriter::writeRgba8(path, image->width, image->height, image->pixels);
            !ok) {
            return fail(ok.error().message);
        }
        written.push_back(path);
    }
    if (record) {
        SheetLayout layout;
        layout.locationMap = &result.locationMap;
        const std::filesystem::path pdf = prefix.string() + ".sheet.pdf";
        const std::filesystem::path png = prefix.string() + ".sheet.png";
        if (Status ok = ViewpointSheet::write(result.montage, result.camera.print, *record, layout,
                                              pdf, png);
            !ok) {
            return fail(ok.error().message);
        }
        written.push_back(pdf);
        written.push_back(png);
        const std::filesystem::path map = prefix.string() + "_map.png";
        if (Status ok =
                ImageWriter::writeRgba8(map, result.locationMap.width, result.locationMap.height,
                                        result.locationMap.pixels);
            !ok) {
            return fail(ok.error().message);
        }
        written.push_back(map);
    }
    nlohmann::ordered_json document = summary;
    if (record) {
        document["viewpoint"] = nlohmann::ordered_json::parse(record->json());
    }
    const std::filesystem::path json = prefix.string() + ".json";
    if (Status ok = writeFileAtomically(json, document.dump(2) + "\n"); !ok) {
        return fail(json.string() + ": " + ok.error().message);
    }
    return true;
}

}  // namespace

std::optional<std::vector<PlannedPhoto>> planPhotos(const ProjectModel& model,
                                                    const std::vector<std::string>& names,
                                                    bool requireAny) {
    std::vector<PlannedPhoto> planned;
    bool failed = false;
    for (const Block& block : model.photos) {
        if (!names.empty() && std::find(names.begin(), names.end(), block.name) == names.end()) {
            continue;
        }
        Result<PhotoViewpoint> viewpoint = PhotoViewpoint::fromBlock(model, block);
        Result<Photo> picture =
            viewpoint ? viewpoint->readPhoto() : Result<Photo>(viewpoint.error());
        if (!picture) {
            std::fprintf(stderr, "error: %s\n", picture.error().message.c_str());
            failed = true;
            continue;
        }
        planned.push_back({std::move(viewpoint.value()), std::move(picture.value())});
    }
    if (!failed && planned.empty() && requireAny) {
        reportError(model.file.string() + ": the project has no photo block" +
                    (names.size() == 1 ? " named '" + names.front() + "'" : std::string()));
        failed = true;
    }
    return failed ? std::nullopt : std::optional(std::move(planned));
}

bool makePhotos(render::BatchRenderer& batch, const std::vector<PlannedPhoto>& photos,
                const std::filesystem::path& outFolder, nlohmann::ordered_json& summaries) {
    for (const PlannedPhoto& photo : photos) {
        Result<render::PhotomontageResult> result =
            render::PhotomontageRenderer::render(batch, photo.viewpoint, photo.picture);
        if (!result) {
            std::fprintf(stderr, "error: %s\n", result.error().message.c_str());
            return false;
        }
        nlohmann::ordered_json summary = summaryOf(photo, result.value());
        std::optional<ViewpointRecord> record;
        if (photo.viewpoint.sheet) {
            record = render::PhotomontageRenderer::record(batch, photo.viewpoint, result.value());
        }
        if (!writeOutputs(photo, result.value(), summary, record, outFolder)) {
            return false;
        }
        std::fprintf(stderr, "photo '%s': %zu proposal pixels%s\n", photo.viewpoint.name.c_str(),
                     ProposalMask::count(result->proposal),
                     result->match
                         ? (", match rms " + std::to_string(result->match->rms) + " px").c_str()
                         : "");
        summaries.push_back(std::move(summary));
    }
    return true;
}

}  // namespace sylva::app
