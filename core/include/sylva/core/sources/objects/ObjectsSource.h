// ObjectsSource (`source x : objects`): one 3D model (ModelImporter: glTF/GLB/OBJ) placed
// at every point feature, or every `spacing` metres along line features, drawn instanced
// (see MeshSource for the access path and the error contract).
//
// A placement's model frame (+Z up, +Y forward, metres) is put at the point, turned so
// +Y points along the heading (clockwise from north; along lines: the line's direction
// plus the heading; or toward `face_toward`), scaled (the scale, a scale attribute, or
// a size attribute matched to `reference_height`), at `height` above the terrain (the
// ground sampled like buildings) or above the ellipsoid (`absolute`). Articulated parts:
// named nodes turned about their own +Z by an attribute or a constant angle per node.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sylva/core/model/Value.h"
#include "sylva/core/sources/SourceBuildContext.h"
#include "sylva/core/sources/objects/MeshSource.h"
#include "sylva/core/sources/vector/FeatureSource.h"

namespace sylva {

struct ObjectsParameters {
    std::filesystem::path model;  // absolute or relative to the working folder
    double scale = 1.0;
    std::string scaleAttribute;
    std::string sizeAttribute;  // metres, matched to referenceHeight
    double referenceHeight = 1.0;
    double heading = 0.0;          // radians, clockwise from north
    std::string headingAttribute;  // degrees
    std::optional<GeoPosition> faceToward;
    double height = 0.0;  // metres above the terrain (or the ellipsoid when absolute)
    std::string heightAttribute;
    bool absolute = false;
    double spacing = 50.0;                                            // metres along lines
    std::vector<std::pair<std::string, std::string>> partAttributes;  // node, attribute (degrees)
    std::vector<std::pair<std::string, double>> partAngles;           // node, radians
};

class ObjectsSource final : public MeshSource {
public:
    ObjectsSource(std::string name, const FeatureSource* features, const Source* elevation,
                  ObjectsParameters parameters);
    ~ObjectsSource() override;

    static Result<std::unique_ptr<Source>> create(const SourceBuildContext& context);

    Result<GeographicBounds> bounds() const override;
    Result<std::shared_ptr<const MeshTile>> tile(const TileKey& key,
                                                 TileProvider& provider) const override;
    std::vector<std::filesystem::path> files() const override { return {parameters_.model}; }

    struct Prepared;  // the model and the checked placements, by tile (ObjectsSource.cpp)

private:
    Result<std::shared_ptr<const Prepared>> prepared() const;

    const FeatureSource* features_;
    const Source* elevation_;
    ObjectsParameters parameters_;
    mutable std::mutex mutex_;
    mutable std::shared_ptr<const Prepared> prepared_;
    mutable std::optional<Error> failure_;
};

}  // namespace sylva
