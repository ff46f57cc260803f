// FeatureCollection: vector features (points, lines, polygons) with their attributes,
// held in memory in geographic coordinates, with an STR-packed R-tree over their
// bounds so per-tile queries touch only the features near the tile.
//
// Coordinates: x = longitude, y = latitude, radians on WGS84. Longitudes are unwrapped
// along each part (consecutive vertices never differ by more than pi), so a feature
// that crosses the antimeridian has a continuous ring whose longitudes leave
// [-pi, pi] (e.g. 3.0 .. 3.3); its bounds say so, and query() returns it with the
// shift (a multiple of 2 pi) that brings it over the queried window. A ring that
// encircles a pole (its unwrapped longitudes end 2 pi from where they start, as
// Antarctica's do) is closed along the pole. Polygon rings are oriented so that the
// signed area of the feature is positive (outer rings counter-clockwise in
// longitude/latitude, holes clockwise): a non-zero winding fill gives the polygon.
//
// Thread safety: immutable after load(); any number of threads may query.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"

namespace sylva {

struct GeographicBounds {
    double west = 0.0, south = 0.0, east = 0.0, north = 0.0;  // radians; west <= east
    bool intersects(const GeographicBounds& other) const {
        return west <= other.east && other.west <= east && south <= other.north &&
               other.south <= north;
    }
    void extend(const glm::dvec2& point);
    void extend(const GeographicBounds& other);
    static GeographicBounds empty();
};

enum class GeometryKind { Point, Line, Polygon };

struct Feature {
    GeometryKind kind = GeometryKind::Point;
    // Point: one part holding every point (multi-points). Line: one part per line
    // string. Polygon: one part per ring (closed: last vertex == first), all
    // polygons of a multi-polygon together.
    std::vector<std::vector<glm::dvec2>> parts;
    GeographicBounds bounds;
    std::int64_t id = 0;                  // the source's feature id (FID)
    std::vector<std::string> attributes;  // one per field of the collection, as text
    std::vector<bool> attributeSet;       // false: the field is null/unset
};

// A feature returned by a query, with the longitude shift (0 or +-2 pi) to add to
// its coordinates so it lies over the queried window.
struct FeatureHit {
    const Feature* feature = nullptr;
    double longitudeShift = 0.0;
};

struct FeatureLoadOptions {
    std::string layer;  // empty: the first layer
    std::string where;  // OGR SQL attribute filter; empty: every feature
    // What to do with invalid geometry (self-intersections, empty, unclosed rings).
    enum class Invalid { Error, Skip, Repair } invalid = Invalid::Error;
};

class FeatureCollection {
public:
    // Reads every feature of a layer of an OGR data set (Shapefile, GeoJSON,
    // GeoPackage, KML ...) in any CRS, reprojected to WGS84 longitude/latitude.
    // Fails with "<path>: <reason>" (unreadable file), "<path>: no layer '<name>'
    // (layers: ...)", "<path>: layer '<layer>': where '<filter>': <reason>" (e.g. a
    // missing field) or "<path>: layer '<layer>': feature <fid>: <reason>" (invalid,
    // empty or unclosed geometry when options.invalid is Error).
    static Result<std::shared_ptr<const FeatureCollection>> load(const std::string& path,
                                                                 const FeatureLoadOptions& options);

    // Builds a collection from features already in longitude/latitude (tests,
    // generated data). Rings are oriented and longitudes unwrapped as for load().
    static std::shared_ptr<const FeatureCollection> fromFeatures(std::vector<std::string> fields,
                                                                 std::vector<Feature> features);

    const std::vector<std::string>& fields() const { return fields_; }
    const std::vector<Feature>& features() const { return features_; }
    // Index of a field, or nullopt.
    std::optional<std::size_t> field(std::string_view name) const;

    // Features whose bounds intersect `window` (radians; west/east may be any values
    // with west <= east), each with its longitude shift. Order: ascending feature
    // index, so consumers draw deterministically.
    std::vector<FeatureHit> query(const GeographicBounds& window) const;

    // Sorts rings, unwraps longitudes, closes polar rings; used by both constructors.
    static void normalize(Feature& feature);

private:
    struct Node {
        GeographicBounds bounds;
        std::uint32_t first = 0;  // first child node, or first entry for leaves
        std::uint32_t count = 0;
        bool leaf = true;
    };
    void buildIndex();
    void search(std::uint32_t node, const GeographicBounds& window,
                std::vector<std::uint32_t>& out) const;

    std::vector<std::string> fields_;
    std::vector<Feature> features_;
    std::vector<std::uint32_t> entries_;  // feature indices in R-tree leaf order
    std::vector<Node> nodes_;
    std::uint32_t root_ = 0;
};

}  // namespace sylva
