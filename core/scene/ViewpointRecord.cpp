#include "sylva/core/scene/ViewpointRecord.h"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <numbers>

#include <nlohmann/json.hpp>

#include "sylva/core/geo/ProjectedCoordinates.h"
#include "sylva/core/geo/SolarPosition.h"
#include "sylva/core/scene/ImageProjection.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

std::string format(const char* pattern, double value) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, pattern, value);
    std::string text = buffer;
    // A value that rounds to zero prints without a sign ("0.00°", not "-0.00°").
    if (!text.empty() && text[0] == '-' &&
        text.find_first_of("123456789") > text.find_first_not_of("-0.")) {
        text.erase(0, 1);
    }
    return text;
}

std::string utcText(double unixSeconds) {
    const std::time_t seconds = std::time_t(std::llround(unixSeconds));
    std::tm utc{};
    gmtime_r(&seconds, &utc);
    char buffer[32];
    std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return buffer;
}

class FieldList {
public:
    void text(std::string key, std::string label, std::string value) {
        fields.push_back({std::move(key), std::move(label), std::move(value), std::nullopt});
    }
    // A number shown with `pattern` (printf) and stored exactly in the JSON.
    void number(std::string key, std::string label, const char* pattern, double value) {
        fields.push_back({std::move(key), std::move(label), format(pattern, value), value});
    }
    std::vector<ViewpointField> fields;
};

void describeLens(const Camera& camera, const ImageProjection& image, FieldList& list) {
    list.number("horizontal_fov_deg", "Horizontal field of view", "%.2f°",
                image.horizontalFov() / kDegree);
    list.number("vertical_fov_deg", "Vertical field of view", "%.2f°",
                image.verticalFov() / kDegree);
    list.text("projection", "Projection", projectionName(camera.projection));
    if (camera.lens.focalLength > 0.0) {
        list.number("focal_length_mm", "Focal length", "%.1f mm", camera.lens.focalLength * 1e3);
        list.text("sensor", "Sensor",
                  format("%.1f", camera.lens.sensorWidth * 1e3) + " × " +
                      format("%.1f mm", camera.lens.sensorHeight * 1e3) +
                      (camera.lens.body.empty() ? "" : " (" + camera.lens.body + ")"));
    } else {
        // The 35 mm equivalent of the horizontal field, as practitioners quote it.
        if (camera.projection == CameraProjection::Planar) {
            list.number("focal_length_35mm_mm", "Focal length (35 mm equivalent)", "%.1f mm",
                        18.0 / std::tan(image.horizontalFov() / 2));
        }
    }
    list.number("width_px", "Image width", "%.0f px", image.width());
    list.number("height_px", "Image height", "%.0f px", image.height());
    if (camera.print.valid()) {
        list.text("print_size", "Print size",
                  format("%.0f", camera.print.width * 1e3) + " × " +
                      format("%.0f mm", camera.print.height * 1e3));
        list.number("dpi", "Print resolution", "%.0f dpi", camera.print.dpi);
        list.number("viewing_distance_mm", "Viewing distance", "%.0f mm",
                    image.viewingDistance(camera.print.width) * 1e3);
    }
}

void describeTime(const Camera& camera, const ViewpointInputs& inputs, FieldList& list) {
    if (!inputs.time) {
        list.text("time_local", "Date and time (local)", "not set (fixed sun)");
        return;
    }
    list.text("time_local", "Date and time (local)", inputs.time->text());
    list.text("time_utc", "Date and time (UTC)", utcText(inputs.unixSeconds));
    const SunDirection sun = SolarPosition::seenFrom(inputs.unixSeconds, camera.geodetic.latitude,
                                                     camera.geodetic.longitude);
    list.number("sun_azimuth_deg", "Sun azimuth", "%.1f°", sun.azimuth / kDegree);
    list.number("sun_elevation_deg", "Sun elevation", "%.1f°", sun.elevation / kDegree);
}

}  // namespace

ViewpointRecord ViewpointRecord::describe(const Camera& camera, const ViewpointInputs& inputs) {
    const ImageProjection image(camera, inputs.width, inputs.height);
    FieldList list;
    list.text("id", "Viewpoint", inputs.id);
    if (!inputs.name.empty()) {
        list.text("name", "Name", inputs.name);
    }
    list.text("scenario", "Scenario", inputs.scenario);
    list.number("latitude_deg", "Latitude", "%.6f°", camera.geodetic.latitude / kDegree);
    list.number("longitude_deg", "Longitude", "%.6f°", camera.geodetic.longitude / kDegree);
    if (!inputs.crs.empty()) {
        if (Result<glm::dvec2> grid = ProjectedCoordinates::fromGeodetic(
                inputs.crs, camera.geodetic.latitude, camera.geodetic.longitude)) {
            list.text("grid_crs", "Grid", inputs.crs);
            list.number("grid_x", "Grid easting", "%.1f", grid.value().x);
            list.number("grid_y", "Grid northing", "%.1f", grid.value().y);
        }
    }
    if (std::isfinite(camera.groundHeight)) {
        list.number("ground_height_m", "Ground height (ellipsoid)", "%.1f m", camera.groundHeight);
        list.number("eye_height_m", "Eye height above ground", "%.2f m", camera.eyeHeight);
    }
    list.number("camera_height_m", "Camera height (ellipsoid)", "%.1f m", camera.geodetic.height);
    double bearing = std::remainder(camera.heading(), 2 * std::numbers::pi) / kDegree;
    if (bearing < 0) {
        bearing += 360.0;
    }
    list.number("bearing_deg", "Bearing of view centre", "%.2f°", bearing);
    list.number("pitch_deg", "Pitch", "%.2f°", camera.pitch() / kDegree);
    describeLens(camera, image, list);
    describeTime(camera, inputs, list);
    if (inputs.proposalDistance) {
        list.number("proposal_distance_m", "Nearest part of the proposal", "%.0f m",
                    *inputs.proposalDistance);
    }
    if (inputs.proposalExtent) {
        list.number("proposal_extent_deg", "Horizontal extent of the proposal", "%.2f°",
                    *inputs.proposalExtent / kDegree);
    }
    if (inputs.proposalLeftBearing && inputs.proposalRightBearing) {
        list.number("proposal_from_deg", "Proposal seen from bearing", "%.2f°",
                    *inputs.proposalLeftBearing / kDegree);
        list.number("proposal_to_deg", "Proposal seen to bearing", "%.2f°",
                    *inputs.proposalRightBearing / kDegree);
    }
    if (inputs.matchRms) {
        list.number("match_rms_px", "Camera match rms residual", "%.2f px", *inputs.matchRms);
    }
    std::string sources;
    for (const std::string& source : inputs.dataSources) {
        sources += (sources.empty() ? "" : "; ") + source;
    }
    list.text("data_sources", "Data sources", sources.empty() ? "none" : sources);
    list.text("software", "Software", "Sylva " + inputs.version);
    list.text("project_hash", "Project hash", inputs.projectHash);
    ViewpointRecord record;
    record.fields_ = std::move(list.fields);
    return record;
}

const ViewpointField* ViewpointRecord::find(const std::string& key) const {
    for (const ViewpointField& field : fields_) {
        if (field.key == key) {
            return &field;
        }
    }
    return nullptr;
}

void ViewpointRecord::addTo(ImageMetadata& metadata) const {
    for (const ViewpointField& field : fields_) {
        metadata.set("sylva:viewpoint:" + field.key, field.text);
    }
}

std::string ViewpointRecord::json() const {
    nlohmann::ordered_json object = nlohmann::ordered_json::object();
    for (const ViewpointField& field : fields_) {
        if (field.number) {
            object[field.key] = *field.number;
        } else {
            object[field.key] = field.text;
        }
    }
    return object.dump(2) + "\n";
}

}  // namespace sylva
