#include "sylva/core/sources/vector/FeatureCollection.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include <cpl_error.h>
#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include "sylva/core/sources/GdalDatasetPool.h"

namespace sylva {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr std::uint32_t kNodeCapacity = 16;

double ringSignedArea(const std::vector<glm::dvec2>& ring) {
    double sum = 0.0;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
        sum += ring[i].x * ring[i + 1].y - ring[i + 1].x * ring[i].y;
    }
    return 0.5 * sum;
}

bool ringContains(const std::vector<glm::dvec2>& ring, const glm::dvec2& p) {
    bool inside = false;
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
        const glm::dvec2& a = ring[i];
        const glm::dvec2& b = ring[j];
        if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) {
            inside = !inside;
        }
    }
    return inside;
}

// RAII for GDAL/OGR C handles and the quiet error handler.
struct QuietErrors {
    QuietErrors() {
        CPLPushErrorHandler(CPLQuietErrorHandler);
        CPLErrorReset();
    }
    ~QuietErrors() { CPLPopErrorHandler(); }
};

std::string lastGdalError(const char* fallback) {
    const char* message = CPLGetLastErrorMsg();
    return (message != nullptr && *message != '\0') ? std::string(message) : std::string(fallback);
}

// First unclosed ring of a geometry (before any transformation), if any.
bool hasUnclosedRing(OGRGeometryH geometry) {
    const OGRwkbGeometryType type = wkbFlatten(OGR_G_GetGeometryType(geometry));
    if (type == wkbPolygon) {
        for (int r = 0; r < OGR_G_GetGeometryCount(geometry); ++r) {
            OGRGeometryH ring = OGR_G_GetGeometryRef(geometry, r);
            const int n = OGR_G_GetPointCount(ring);
            if (n == 0) {
                continue;
            }
            if (n < 4 || OGR_G_GetX(ring, 0) != OGR_G_GetX(ring, n - 1) ||
                OGR_G_GetY(ring, 0) != OGR_G_GetY(ring, n - 1)) {
                return true;
            }
        }
        return false;
    }
    if (type == wkbMultiPolygon || type == wkbGeometryCollection) {
        for (int i = 0; i < OGR_G_GetGeometryCount(geometry); ++i) {
            if (hasUnclosedRing(OGR_G_GetGeometryRef(geometry, i))) {
                return true;
            }
        }
    }
    return false;
}

struct Collected {
    std::vector<std::vector<glm::dvec2>> points, lines, rings;
};

std::vector<glm::dvec2> pointsOf(OGRGeometryH geometry) {
    std::vector<glm::dvec2> out;
    const int n = OGR_G_GetPointCount(geometry);
    out.reserve(static_cast<std::size_t>(n));
    constexpr double kRadian = std::numbers::pi / 180.0;
    for (int i = 0; i < n; ++i) {
        out.emplace_back(OGR_G_GetX(geometry, i) * kRadian, OGR_G_GetY(geometry, i) * kRadian);
    }
    return out;
}

void collect(OGRGeometryH geometry, Collected& out) {
    switch (wkbFlatten(OGR_G_GetGeometryType(geometry))) {
        case wkbPoint:
            if (out.points.empty()) {
                out.points.emplace_back();
            }
            for (const glm::dvec2& p : pointsOf(geometry)) {
                out.points.front().push_back(p);
            }
            break;
        case wkbLineString:
        case wkbLinearRing:
            out.lines.push_back(pointsOf(geometry));
            break;
        case wkbPolygon:
            for (int r = 0; r < OGR_G_GetGeometryCount(geometry); ++r) {
                out.rings.push_back(pointsOf(OGR_G_GetGeometryRef(geometry, r)));
            }
            break;
        case wkbMultiPoint:
        case wkbMultiLineString:
        case wkbMultiPolygon:
        case wkbGeometryCollection:
            for (int i = 0; i < OGR_G_GetGeometryCount(geometry); ++i) {
                collect(OGR_G_GetGeometryRef(geometry, i), out);
            }
            break;
        default: {
            // Curves and surfaces: their linear approximation.
            OGRGeometryH linear = OGR_G_GetLinearGeometry(geometry, 0.0, nullptr);
            if (linear != nullptr) {
                if (wkbFlatten(OGR_G_GetGeometryType(linear)) !=
                    wkbFlatten(OGR_G_GetGeometryType(geometry))) {
                    collect(linear, out);
                }
                OGR_G_DestroyGeometry(linear);
            }
            break;
        }
    }
}

}  // namespace

void GeographicBounds::extend(const glm::dvec2& point) {
    west = std::min(west, point.x);
    east = std::max(east, point.x);
    south = std::min(south, point.y);
    north = std::max(north, point.y);
}

void GeographicBounds::extend(const GeographicBounds& other) {
    west = std::min(west, other.west);
    east = std::max(east, other.east);
    south = std::min(south, other.south);
    north = std::max(north, other.north);
}

GeographicBounds GeographicBounds::empty() {
    constexpr double kHuge = 1e300;
    return {kHuge, kHuge, -kHuge, -kHuge};
}

void FeatureCollection::normalize(Feature& feature) {
    for (std::vector<glm::dvec2>& part : feature.parts) {
        if (part.empty()) {
            continue;
        }
        part.front().x = std::remainder(part.front().x, kTwoPi);
        if (feature.kind == GeometryKind::Point) {
            for (glm::dvec2& p : part) {
                p.x = std::remainder(p.x, kTwoPi);
            }
            continue;
        }
        for (std::size_t i = 1; i < part.size(); ++i) {
            part[i].x += kTwoPi * std::round((part[i - 1].x - part[i].x) / kTwoPi);
        }
        if (feature.kind == GeometryKind::Polygon) {
            const double wrap = part.back().x - part.front().x;
            if (std::abs(wrap) > kPi) {
                // The ring goes once around the globe: it encloses a pole. Close it
                // along the parallel of the pole on the side the ring lies.
                double meanLatitude = 0.0;
                for (const glm::dvec2& p : part) {
                    meanLatitude += p.y;
                }
                const double pole = meanLatitude < 0.0 ? -kPi / 2 : kPi / 2;
                const glm::dvec2 end = part.back();
                const glm::dvec2 start = part.front();
                part.emplace_back(end.x, pole);
                part.emplace_back(start.x, pole);
                part.push_back(start);
            } else if (part.front() != part.back()) {
                part.push_back(part.front());
            }
        }
    }
    if (feature.kind == GeometryKind::Polygon) {
        // Outer rings positive, holes (inside an odd number of other rings) negative.
        for (std::size_t i = 0; i < feature.parts.size(); ++i) {
            std::vector<glm::dvec2>& ring = feature.parts[i];
            if (ring.size() < 4) {
                continue;
            }
            int depth = 0;
            for (std::size_t j = 0; j < feature.parts.size(); ++j) {
                if (j != i && feature.parts[j].size() >= 4 &&
                    ringContains(feature.parts[j], ring.front())) {
                    ++depth;
                }
            }
            const double area = ringSignedArea(ring);
            if ((depth % 2 == 0) != (area > 0.0)) {
                std::reverse(ring.begin(), ring.end());
            }
        }
    }
    feature.bounds = GeographicBounds::empty();
    for (const std::vector<glm::dvec2>& part : feature.parts) {
        for (const glm::dvec2& p : part) {
            feature.bounds.extend(p);
        }
    }
}

std::optional<std::size_t> FeatureCollection::field(std::string_view name) const {
    for (std::size_t i = 0; i < fields_.size(); ++i) {
        if (fields_[i] == name) {
            return i;
        }
    }
    return std::nullopt;
}

std::shared_ptr<const FeatureCollection> FeatureCollection::fromFeatures(
    std::vector<std::string> fields, std::vector<Feature> features) {
    auto collection = std::make_shared<FeatureCollection>();
    collection->fields_ = std::move(fields);
    collection->features_ = std::move(features);
    for (Feature& feature : collection->features_) {
        feature.attributes.resize(collection->fields_.size());
        feature.attributeSet.resize(collection->fields_.size(), false);
        normalize(feature);
    }
    collection->buildIndex();
    return collection;
}

namespace {

// The named layer, or the first one.
Result<OGRLayerH> openLayer(GDALDatasetH dataset, const std::string& path,
                            const std::string& name) {
    if (name.empty()) {
        if (GDALDatasetGetLayerCount(dataset) == 0) {
            return Error{path + ": the file has no vector layer"};
        }
        return GDALDatasetGetLayer(dataset, 0);
    }
    OGRLayerH layer = GDALDatasetGetLayerByName(dataset, name.c_str());
    if (layer == nullptr) {
        std::string names;
        for (int i = 0; i < GDALDatasetGetLayerCount(dataset); ++i) {
            names += (i ? ", " : "") + std::string(OGR_L_GetName(GDALDatasetGetLayer(dataset, i)));
        }
        return Error{path + ": no layer '" + name + "' (layers: " + names + ")"};
    }
    return layer;
}

// Owns the layer CRS → WGS84 longitude/latitude transformation (none: the layer has no
// CRS and is taken as longitude/latitude).
class Wgs84Transform {
public:
    Wgs84Transform() = default;
    Wgs84Transform(const Wgs84Transform&) = delete;
    Wgs84Transform& operator=(const Wgs84Transform&) = delete;
    ~Wgs84Transform() {
        if (handle_ != nullptr) {
            OCTDestroyCoordinateTransformation(handle_);
        }
    }

    Status open(OGRLayerH layer, const std::string& where) {
        OGRSpatialReferenceH target = OSRNewSpatialReference(nullptr);
        OSRImportFromEPSG(target, 4326);
        OSRSetAxisMappingStrategy(target, OAMS_TRADITIONAL_GIS_ORDER);
        if (OGRSpatialReferenceH source = OGR_L_GetSpatialRef(layer)) {
            OGRSpatialReferenceH clone = OSRClone(source);
            OSRSetAxisMappingStrategy(clone, OAMS_TRADITIONAL_GIS_ORDER);
            handle_ = OCTNewCoordinateTransformation(clone, target);
            OSRDestroySpatialReference(clone);
            if (handle_ == nullptr) {
                OSRDestroySpatialReference(target);
                return Error{where + ": cannot transform its CRS to WGS84 (" +
                             lastGdalError("no transformation") + ")"};
            }
        }
        OSRDestroySpatialReference(target);
        return Status::success();
    }
    OGRCoordinateTransformationH handle() const { return handle_; }

private:
    OGRCoordinateTransformationH handle_ = nullptr;
};

// A feature's geometry to use: a clone, or (invalid = repair) the repaired geometry;
// nullptr when the feature is to be skipped. Owned by the caller.
Result<OGRGeometryH> usableGeometry(OGRFeatureH handle, const std::string& featureWhere,
                                    const FeatureLoadOptions& options) {
    OGRGeometryH original = OGR_F_GetGeometryRef(handle);
    std::string problem;
    if (original == nullptr || OGR_G_IsEmpty(original)) {
        problem = "empty geometry";
    } else if (hasUnclosedRing(original)) {
        problem = "unclosed polygon ring";
    } else if (!OGR_G_IsValid(original)) {
        problem = "invalid geometry (" + lastGdalError("e.g. a self-intersection") + ")";
    }
    if (problem.empty()) {
        return OGR_G_Clone(original);
    }
    if (options.invalid == FeatureLoadOptions::Invalid::Error) {
        return Error{featureWhere + ": " + problem};
    }
    if (options.invalid == FeatureLoadOptions::Invalid::Skip || original == nullptr ||
        OGR_G_IsEmpty(original)) {
        return static_cast<OGRGeometryH>(nullptr);
    }
    OGRGeometryH repaired = OGR_G_MakeValid(original);
    if (repaired == nullptr) {
        return Error{featureWhere + ": cannot repair " + problem};
    }
    return repaired;
}

// One feature in WGS84 radians with its attributes; nothing when it is skipped (broken
// geometry with invalid = skip or repair, no parts left).
Result<std::optional<Feature>> readFeature(OGRFeatureH handle,
                                           OGRCoordinateTransformationH transform, int fieldCount,
                                           const std::string& where,
                                           const FeatureLoadOptions& options) {
    Feature feature;
    feature.id = OGR_F_GetFID(handle);
    const std::string featureWhere = where + ": feature " + std::to_string(feature.id);
    Result<OGRGeometryH> usable = usableGeometry(handle, featureWhere, options);
    if (!usable) {
        return usable.error();
    }
    if (*usable == nullptr) {
        return std::optional<Feature>{};
    }
    struct DestroyGeometry {
        OGRGeometryH handle;
        ~DestroyGeometry() { OGR_G_DestroyGeometry(handle); }
    } destroyGeometry{*usable};
    if (transform != nullptr && OGR_G_Transform(*usable, transform) != OGRERR_NONE) {
        return Error{featureWhere + ": cannot reproject to WGS84 (" +
                     lastGdalError("outside the CRS") + ")"};
    }
    Collected parts;
    collect(*usable, parts);
    if (!parts.rings.empty()) {
        feature.kind = GeometryKind::Polygon;
        feature.parts = std::move(parts.rings);
    } else if (!parts.lines.empty()) {
        feature.kind = GeometryKind::Line;
        feature.parts = std::move(parts.lines);
    } else {
        feature.kind = GeometryKind::Point;
        feature.parts = std::move(parts.points);
    }
    if (feature.parts.empty()) {
        if (options.invalid == FeatureLoadOptions::Invalid::Error) {
            return Error{featureWhere + ": empty geometry"};
        }
        return std::optional<Feature>{};
    }
    feature.attributes.resize(static_cast<std::size_t>(fieldCount));
    feature.attributeSet.resize(static_cast<std::size_t>(fieldCount), false);
    for (int i = 0; i < fieldCount; ++i) {
        if (OGR_F_IsFieldSetAndNotNull(handle, i)) {
            feature.attributes[std::size_t(i)] = OGR_F_GetFieldAsString(handle, i);
            feature.attributeSet[std::size_t(i)] = true;
        }
    }
    return std::optional<Feature>(std::move(feature));
}

}  // namespace

Result<std::shared_ptr<const FeatureCollection>> FeatureCollection::load(
    const std::string& path, const FeatureLoadOptions& options) {
    GdalDatasetPool::registerDrivers();
    QuietErrors quiet;
    GDALDatasetH dataset =
        GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
    if (dataset == nullptr) {
        return Error{path + ": cannot open as vector data (" +
                     lastGdalError("unknown format or missing file") + ")"};
    }
    struct CloseDataset {
        GDALDatasetH handle;
        ~CloseDataset() { GDALClose(handle); }
    } closeDataset{dataset};
    Result<OGRLayerH> layer = openLayer(dataset, path, options.layer);
    if (!layer) {
        return layer.error();
    }
    const std::string layerName = OGR_L_GetName(*layer);
    const std::string where = path + ": layer '" + layerName + "'";
    if (!options.where.empty()) {
        CPLErrorReset();
        if (OGR_L_SetAttributeFilter(*layer, options.where.c_str()) != OGRERR_NONE) {
            return Error{where + ": where '" + options.where +
                         "': " + lastGdalError("invalid filter")};
        }
    }
    Wgs84Transform transform;
    if (Status opened = transform.open(*layer, where); !opened) {
        return opened.error();
    }

    auto collection = std::make_shared<FeatureCollection>();
    OGRFeatureDefnH definition = OGR_L_GetLayerDefn(*layer);
    const int fieldCount = OGR_FD_GetFieldCount(definition);
    for (int i = 0; i < fieldCount; ++i) {
        collection->fields_.emplace_back(OGR_Fld_GetNameRef(OGR_FD_GetFieldDefn(definition, i)));
    }
    OGR_L_ResetReading(*layer);
    CPLErrorReset();
    while (OGRFeatureH handle = OGR_L_GetNextFeature(*layer)) {
        struct DestroyFeature {
            OGRFeatureH handle;
            ~DestroyFeature() { OGR_F_Destroy(handle); }
        } destroyFeature{handle};
        Result<std::optional<Feature>> feature =
            readFeature(handle, transform.handle(), fieldCount, where, options);
        if (!feature) {
            return feature.error();
        }
        if (*feature) {
            normalize(**feature);
            collection->features_.push_back(std::move(**feature));
        }
    }
    if (CPLGetLastErrorType() >= CE_Failure) {
        return Error{where + ": reading failed (" + lastGdalError("read error") + ")"};
    }
    collection->buildIndex();
    return std::shared_ptr<const FeatureCollection>(std::move(collection));
}

// Sort-Tile-Recursive packing (Leutenegger, Lopez, Edgington 1997): sort by centre x,
// cut into sqrt(n / B) vertical slices, sort each slice by centre y, pack runs of B.
void FeatureCollection::buildIndex() {
    nodes_.clear();
    entries_.resize(features_.size());
    for (std::uint32_t i = 0; i < entries_.size(); ++i) {
        entries_[i] = i;
    }
    struct Item {
        GeographicBounds bounds;
        std::uint32_t index;
    };
    auto pack = [](std::vector<Item>& items) {
        const std::size_t leaves = (items.size() + kNodeCapacity - 1) / kNodeCapacity;
        const std::size_t slices = static_cast<std::size_t>(std::ceil(std::sqrt(double(leaves))));
        const std::size_t perSlice = slices * kNodeCapacity;
        auto centre = [](const GeographicBounds& b, bool x) {
            return x ? b.west + b.east : b.south + b.north;
        };
        std::stable_sort(items.begin(), items.end(), [&](const Item& a, const Item& b) {
            return centre(a.bounds, true) < centre(b.bounds, true);
        });
        for (std::size_t s = 0; s < items.size(); s += perSlice) {
            auto end = items.begin() + std::ptrdiff_t(std::min(items.size(), s + perSlice));
            std::stable_sort(items.begin() + std::ptrdiff_t(s), end,
                             [&](const Item& a, const Item& b) {
                                 return centre(a.bounds, false) < centre(b.bounds, false);
                             });
        }
    };
    std::vector<Item> items;
    for (std::uint32_t i = 0; i < features_.size(); ++i) {
        items.push_back({features_[i].bounds, i});
    }
    if (items.empty()) {
        nodes_.push_back(Node{GeographicBounds::empty(), 0, 0, true});
        root_ = 0;
        return;
    }
    pack(items);
    for (std::size_t i = 0; i < items.size(); ++i) {
        entries_[i] = items[i].index;
    }
    std::vector<Item> level;
    for (std::size_t i = 0; i < items.size(); i += kNodeCapacity) {
        Node node{GeographicBounds::empty(), std::uint32_t(i),
                  std::uint32_t(std::min<std::size_t>(kNodeCapacity, items.size() - i)), true};
        for (std::uint32_t k = 0; k < node.count; ++k) {
            node.bounds.extend(items[i + k].bounds);
        }
        level.push_back({node.bounds, std::uint32_t(nodes_.size())});
        nodes_.push_back(node);
    }
    while (level.size() > 1) {
        pack(level);
        std::vector<Item> parents;
        for (std::size_t i = 0; i < level.size(); i += kNodeCapacity) {
            // Children of one parent must be contiguous: copy them to the end.
            Node parent{GeographicBounds::empty(), std::uint32_t(nodes_.size()),
                        std::uint32_t(std::min<std::size_t>(kNodeCapacity, level.size() - i)),
                        false};
            for (std::uint32_t k = 0; k < parent.count; ++k) {
                const Node child = nodes_[level[i + k].index];
                nodes_.push_back(child);
                parent.bounds.extend(child.bounds);
            }
            parents.push_back({parent.bounds, std::uint32_t(nodes_.size())});
            nodes_.push_back(parent);
        }
        level = std::move(parents);
    }
    root_ = level.front().index;
}

void FeatureCollection::search(std::uint32_t index, const GeographicBounds& window,
                               std::vector<std::uint32_t>& out) const {
    const Node& node = nodes_[index];
    if (node.count == 0 || !node.bounds.intersects(window)) {
        return;
    }
    for (std::uint32_t k = 0; k < node.count; ++k) {
        if (node.leaf) {
            const std::uint32_t feature = entries_[node.first + k];
            if (features_[feature].bounds.intersects(window)) {
                out.push_back(feature);
            }
        } else {
            search(node.first + k, window, out);
        }
    }
}

std::vector<FeatureHit> FeatureCollection::query(const GeographicBounds& window) const {
    std::vector<std::pair<std::uint32_t, double>> found;
    for (const double shift : {0.0, -kTwoPi, kTwoPi}) {
        GeographicBounds shifted = window;
        shifted.west -= shift;
        shifted.east -= shift;
        std::vector<std::uint32_t> indices;
        search(root_, shifted, indices);
        for (std::uint32_t i : indices) {
            found.emplace_back(i, shift);
        }
    }
    std::sort(found.begin(), found.end());
    std::vector<FeatureHit> hits;
    hits.reserve(found.size());
    for (const auto& [index, shift] : found) {
        hits.push_back({&features_[index], shift});
    }
    return hits;
}

}  // namespace sylva
