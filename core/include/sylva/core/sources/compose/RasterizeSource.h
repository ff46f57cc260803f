// RasterizeSource (`source x : rasterize`): vector features, or plant instances, drawn
// into a mask (one channel, coverage in [0, 1]) or an image (linear RGB + alpha =
// coverage), anti-aliased by exact area coverage (polygons) and box-filtered
// cross-sections (lines, outlines, discs) from CoverageRasterizer.
//
//  - polygons: filled (fill = true) and/or outlined with `outline` metres, centred
//    on the boundary;
//  - lines: `line_width` metres wide, round joins and caps;
//  - points: discs of `point_radius` metres;
//  - instances: discs of point_radius x instance scale (crown markers until the
//    vegetation renderer exists), coloured colour x instance tint; instances of the
//    neighbour tiles that reach into this tile are drawn too, so discs are seamless.
//    Tiles coarser than the plants source's minimumLevel() are left transparent.
// With minimum_texels > 0, lines and outlines narrower than that many texels (of the
// tile's north-south texel size) are drawn that wide at the opacity metric width / drawn
// width, so their ink stays metric at every level (coverage × area summed over a tile is
// length × width): a thin line fades with distance instead of widening. Since the clipmap
// draws a level where its texels are at most about a pixel, this is a minimum width on
// screen, not a texel minimum that floods coarse levels (issue 16).
// Colour: `color`, or per feature from `color_attribute`, either a hex string
// ("#1a8c3f" or "1a8c3f", sRGB) or a key of the `colors` mapping. Features are
// composited in file order with the "over" operator. Colours are sRGB as written and
// output in linear RGB. A value missing from `colors`, a malformed hex string or a
// missing attribute is an error naming the file, feature, attribute and value.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/sources/Source.h"
#include "sylva/core/sources/SourceBuildContext.h"
#include "sylva/core/sources/plants/PlantsSource.h"
#include "sylva/core/sources/vector/FeatureSource.h"

namespace sylva {

struct RasterizeParameters {
    bool image = true;  // false: a mask
    bool fill = true;
    double outline = 0.0;      // metres; 0: none
    double lineWidth = 10.0;   // metres
    double pointRadius = 5.0;  // metres
    // Lines and outlines narrower than this many texels are drawn that wide at opacity
    // width / drawn width (their ink stays metric); 0: exactly their width.
    double minimumTexels = 0.0;
    glm::vec3 color{1.0f};  // linear RGB
    double opacity = 1.0;
    std::string colorAttribute;
    std::vector<std::pair<std::string, glm::vec3>> colors;  // value -> linear RGB
};

class RasterizeSource final : public Source {
public:
    // Exactly one of features / instances is non-null.
    RasterizeSource(std::string name, const FeatureSource* features, const PlantsSource* instances,
                    RasterizeParameters parameters);
    static Result<std::unique_ptr<Source>> create(const SourceBuildContext& context);

    // Fails when the features fail to load, an attribute or colour is bad, or the
    // plants source fails.
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override;

    // "#rrggbb", "rrggbb", "#rgb" (sRGB) -> linear RGB; nullopt when malformed.
    static std::optional<glm::vec3> parseHexColor(const std::string& text);

private:
    const FeatureSource* features_;
    const PlantsSource* instances_;
    RasterizeParameters parameters_;
};

}  // namespace sylva
