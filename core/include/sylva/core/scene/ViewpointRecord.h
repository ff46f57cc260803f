// ViewpointRecord: what a verified view states about itself (LI TGN 06/19 practice,
// NatureScot v2.2; docs/verified-views.md): viewpoint id and name, position (latitude/
// longitude and the project grid), ground and eye height, view bearing, fields of view,
// projection, lens and sensor, print size, dpi and correct viewing distance, date and time
// (local and UTC), sun azimuth and elevation, data sources, Sylva version and project hash.
// One ordered list of fields feeds the sheet's metadata block, the JSON sidecar and the
// image's metadata, so the three always agree.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sylva/core/image/ImageMetadata.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/scene/DateTime.h"

namespace sylva {

struct ViewpointField {
    std::string key;               // JSON key and image metadata name after "sylva:viewpoint:"
    std::string label;             // on the sheet
    std::string text;              // on the sheet and in the image metadata
    std::optional<double> number;  // in the JSON when numeric (SI-friendly units in `key`)
};

struct ViewpointInputs {
    std::string id;        // the camera block's name
    std::string name;      // its title (may be empty)
    std::string scenario;  // the scenario rendered
    int width = 0;         // image pixels
    int height = 0;
    std::optional<DateTime> time;          // as written (its own zone)
    double unixSeconds = 0.0;              // the same instant, when time is set
    std::string crs;                       // the project CRS ("" when none)
    std::vector<std::string> dataSources;  // "name (kind, file)" per layer source
    std::string version;                   // Sylva version
    std::string projectHash;               // hex
    // A scenario with a proposal (buildings, objects; ProposalReach from its geometry):
    // horizontal metres to its nearest part, its horizontal extent and the bearings where
    // that extent starts and ends (radians clockwise from north); a photomontage's camera
    // match rms residual (pixels).
    std::optional<double> proposalDistance;
    std::optional<double> proposalExtent;
    std::optional<double> proposalLeftBearing;
    std::optional<double> proposalRightBearing;
    std::optional<double> matchRms;
};

class ViewpointRecord {
public:
    // The record of `camera` (as fromBlock made it) rendered with `inputs`.
    static ViewpointRecord describe(const Camera& camera, const ViewpointInputs& inputs);

    const std::vector<ViewpointField>& fields() const { return fields_; }
    const ViewpointField* find(const std::string& key) const;
    // "sylva:viewpoint:<key>" = text, for PNG text chunks / EXR attributes.
    void addTo(ImageMetadata& metadata) const;
    // A JSON object: numbers where the field has one, strings otherwise.
    std::string json() const;

private:
    std::vector<ViewpointField> fields_;
};

}  // namespace sylva
