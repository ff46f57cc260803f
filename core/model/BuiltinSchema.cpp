// The built-in schema: every block keyword and source kind of this Sylva build.
// Adding a source kind means adding its entry here and its implementation under
// core/sources/; the DSL checker, `sylva doc` and docs/dsl.md follow from this table.
#include "sylva/core/model/Schema.h"

#include <numbers>

#include "sylva/core/plantlod/PlantGenerator.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

Value quantity(double value, Dimension dimension) {
    Value v;
    v.data = Quantity{value, dimension};
    return v;
}
Value text(std::string s) {
    Value v;
    v.data = std::move(s);
    return v;
}
Value boolean(bool b) {
    Value v;
    v.data = b;
    return v;
}
Value color(float r, float g, float b) {
    Value v;
    v.data = Color{r, g, b, 1.0f};
    return v;
}

AttributeSchema number(std::string name, Dimension dimension, std::optional<double> defaultValue,
                       std::optional<double> minimum, std::optional<double> maximum,
                       std::string doc) {
    AttributeSchema a;
    a.name = std::move(name);
    a.type = ValueType::Number;
    a.dimension = dimension;
    if (defaultValue) {
        a.defaultValue = quantity(*defaultValue, dimension);
    } else {
        a.required = true;
    }
    a.minimum = minimum;
    a.maximum = maximum;
    a.doc = std::move(doc);
    return a;
}

AttributeSchema optionalNumber(std::string name, Dimension dimension, std::optional<double> minimum,
                               std::optional<double> maximum, std::string doc) {
    AttributeSchema a =
        number(std::move(name), dimension, std::nullopt, minimum, maximum, std::move(doc));
    a.required = false;
    return a;
}

AttributeSchema port(std::string name, PortType type, bool required, std::string doc) {
    AttributeSchema a;
    a.name = std::move(name);
    a.type = ValueType::Reference;
    a.port = type;
    a.target = "source";
    a.required = required;
    a.doc = std::move(doc);
    return a;
}

AttributeSchema simple(std::string name, ValueType type, std::optional<Value> defaultValue,
                       std::string doc) {
    AttributeSchema a;
    a.name = std::move(name);
    a.type = type;
    a.defaultValue = std::move(defaultValue);
    a.doc = std::move(doc);
    return a;
}

AttributeSchema referenceList(std::string name, std::string target, PortType portType,
                              bool required, std::string doc) {
    AttributeSchema a;
    a.name = std::move(name);
    a.type = ValueType::List;
    a.element = ValueType::Reference;
    a.target = std::move(target);
    a.port = portType;
    a.required = required;
    a.doc = std::move(doc);
    return a;
}

AttributeSchema wordChoice(std::string name, std::vector<std::string> words,
                           std::string defaultWord, std::string doc) {
    AttributeSchema a;
    a.name = std::move(name);
    a.type = ValueType::Word;
    a.words = std::move(words);
    Value v;
    v.data = Word{std::move(defaultWord)};
    a.defaultValue = v;
    a.doc = std::move(doc);
    return a;
}

AttributeSchema listOf(std::string name, ValueType element, Dimension dimension, bool required,
                       std::string doc) {
    AttributeSchema a;
    a.name = std::move(name);
    a.type = ValueType::List;
    a.element = element;
    a.dimension = dimension;
    a.required = required;
    a.doc = std::move(doc);
    return a;
}

AttributeSchema requiredString(std::string name, std::string doc) {
    AttributeSchema a = simple(std::move(name), ValueType::String, std::nullopt, std::move(doc));
    a.required = true;
    return a;
}

KindSchema projectBlock() {
    return {"project",
            "",
            PortType::None,
            "Project-wide settings.",
            {simple("title", ValueType::String, text(""), "Title shown in outputs."),
             simple("description", ValueType::String, text(""), "Free text."),
             simple("crs", ValueType::String, text(""),
                    "Coordinate reference system for positions written as [x, y] or [x, y, "
                    "height] lengths instead of geo(...), e.g. \"EPSG:31985\" (UTM zone 25S); "
                    "any definition GDAL/PROJ accepts. Empty: only geo() positions.")}};
}

// Terrain kinds of core/sources/raster (noise, normal_map, hypsometric).

KindSchema noiseSource() {
    return {
        "source",
        "noise",
        PortType::Elevation,
        "Fractal relief on the sphere: continents from fBm of 3D gradient noise and mountains "
        "from a ridged multifractal masked to land, both evaluated on the unit sphere, so "
        "the surface is seamless at the antimeridian and the poles. Octaves finer than two "
        "texels of the requested tile are left out (band-limited), so every pyramid level "
        "is a filtered version of the same surface.",
        {number("seed", Dimension::None, 1, 0, 2147483647, "Random seed."),
         number("amplitude", Dimension::Length, 2500, 0, 1e5,
                "Height of the largest octave, in metres."),
         number("base_wavelength", Dimension::Length, 4.0e6, 1, 4.0e7,
                "Wavelength of the largest octave, in metres."),
         number("octaves", Dimension::None, 24, 1, 32, "Maximum number of octaves."),
         number("lacunarity", Dimension::None, 2.0, 1.5, 4.0,
                "Frequency ratio between successive octaves."),
         number("gain", Dimension::None, 0.5, 0.0, 1.0,
                "Amplitude ratio between successive octaves."),
         number("ridges", Dimension::Ratio, 0.5, 0.0, 1.0,
                "Share of the ridged-multifractal mountains in the relief (0%: continents only)."),
         number("ridge_wavelength", Dimension::Length, 2.0e5, 1, 4.0e7,
                "Wavelength of the largest mountain octave, in metres."),
         number("roughness", Dimension::None, 0.6, 0.0, 1.0,
                "Amplitude ratio between successive mountain octaves."),
         number("offset", Dimension::Length, 0, -1e5, 1e5, "Added to every height, in metres.")}};
}

KindSchema normalMapSource() {
    return {"source",
            "normal_map",
            PortType::Normals,
            "Metric surface normals on the WGS84 ellipsoid (ECEF unit vectors) from an elevation "
            "source, by central differences over the tile border: seamless across tiles and "
            "correct at any latitude.",
            {port("height", PortType::Elevation, true, "Elevation to differentiate."),
             number("exaggeration", Dimension::None, 1.0, 0.0, 100.0,
                    "Scale applied to slopes before normalising.")}};
}

KindSchema hypsometricSource() {
    return {
        "source",
        "hypsometric",
        PortType::Image,
        "Colour from elevation and slope: a hypsometric ramp of height/colour stops "
        "(sRGB colours, interpolated in linear RGB), water below sea level, and rock on "
        "slopes steeper than slope_start, fully at slope_end.",
        {port("height", PortType::Elevation, true, "Elevation that drives the ramp."),
         port("normals", PortType::Normals, false,
              "Surface normals for the slope; derived from `height` when absent."),
         simple("ramp", ValueType::List, std::nullopt,
                "List of stops { height = <length>, color = <colour> } in ascending height; "
                "a built-in Earth-like ramp when absent."),
         simple("water", ValueType::Color, color(0.06f, 0.16f, 0.30f), "Colour below 0 m."),
         simple("shallow_water", ValueType::Color, color(0.10f, 0.32f, 0.42f),
                "Colour just below 0 m, blended to `water` over water_depth."),
         number("water_depth", Dimension::Length, 400, 1, 1e5,
                "Depth over which shallow_water turns into water."),
         simple("rock", ValueType::Color, color(0.42f, 0.39f, 0.35f), "Colour of steep slopes."),
         number("slope_start", Dimension::Angle, 28 * kDegree, 0, 90 * kDegree,
                "Slope where rock starts to show."),
         number("slope_end", Dimension::Angle, 45 * kDegree, 0, 90 * kDegree,
                "Slope where the surface is fully rock.")}};
}

// Image kinds of core/sources/raster and core/sources/compose. The output port of raster,
// constant, adjust and blend depends on their attributes (`kind`, or the inputs), so
// their schema output is `none` (see setOutputFrom in makeBuiltin).

KindSchema rasterSource() {
    return {
        "source",
        "raster",
        PortType::None,
        "Any raster GDAL reads (GeoTIFF/COG, VRT, JPEG2000 where the driver exists, PNG/JPEG "
        "with a world file ...) in any CRS, reprojected on the fly to the longitude/latitude "
        "tile grid: every texel centre is transformed to the file's CRS (exactly, or interpolated "
        "along rows where that is within 0.125 source pixels, like GDAL's approximate "
        "transformer), the window it spans is read (through the file's overviews, averaged, when "
        "a texel covers more than "
        "one pixel) and resampled. Outputs an elevation (one channel, metres; its coverage is "
        "a separate mask that `blend` uses) or an image (linear RGB + alpha = coverage). "
        "Texels outside the file or on no-data have coverage 0. A missing, truncated or "
        "unreadable file, or one without a usable CRS, fails every tile with one message "
        "naming the file and the reason.",
        {requiredString("file", "Path of the raster, relative to the project file."),
         wordChoice("kind", {"auto", "elevation", "image"}, "auto",
                    "What the bands are: elevation (one band, metres after the band's "
                    "vertical unit), image (one to three bands as RGB), or auto: one band is "
                    "elevation, more are an image."),
         listOf("bands", ValueType::Number, Dimension::None, false,
                "Band numbers to read, from 1 (e.g. [3, 2, 1] for Landsat true colour); default "
                "[1] for elevation, [1, 2, 3] for images (or [1] for one-band files)."),
         optionalNumber("nodata", Dimension::None, std::nullopt, std::nullopt,
                        "Raw value meaning no data, in addition to the file's own nodata, "
                        "alpha band or mask."),
         wordChoice("resampling", {"nearest", "bilinear", "cubic"}, "bilinear",
                    "Kernel for magnification (Keys cubic as in GDAL); minification always "
                    "averages, except with nearest."),
         number("scale", Dimension::None, 1.0, std::nullopt, std::nullopt,
                "Multiplies values (after the band's own scale/offset; 8-bit image bands are "
                "first divided by 255)."),
         number("offset", Dimension::None, 0.0, std::nullopt, std::nullopt,
                "Added to values after `scale` (in the file's vertical unit for elevation)."),
         listOf("bounds", ValueType::Number, Dimension::Angle, false,
                "[west, south, east, north]: places a file without georeferencing (e.g. a world "
                "image) on WGS84 longitude/latitude; overrides the file's own."),
         simple("srgb", ValueType::Bool, std::nullopt,
                "Images: decode values from sRGB to linear (default: true for 8-bit bands, "
                "false otherwise). Use false for band arithmetic such as NDVI."),
         number("fill", Dimension::Length, 0.0, -1e5, 1e5,
                "Elevation outside the coverage, in metres.")}};
}

KindSchema constantSource() {
    return {"source",
            "constant",
            PortType::None,
            "One height or one colour everywhere, full coverage.",
            {wordChoice("kind", {"elevation", "image"}, "elevation", "Elevation or image output."),
             number("height", Dimension::Length, 0.0, -1e5, 1e5,
                    "Elevation in metres (kind = elevation)."),
             simple("color", ValueType::Color, color(0.5f, 0.5f, 0.5f),
                    "Colour (sRGB as written, output in linear RGB; its alpha is the alpha).")}};
}

KindSchema adjustSource() {
    return {"source",
            "adjust",
            PortType::None,
            "Colour corrections of an image, per texel, applied to sRGB-encoded values in [0, 1] "
            "(as image editors do) in this order: levels (black/white point), gamma, brightness, "
            "contrast about mid grey, saturation and hue (rotation about the grey axis with "
            "Rec. 709 luma kept); the result is clamped to [0, 1] and decoded to linear RGB. "
            "Alpha passes through.",
            {port("input", PortType::None, true, "Image to adjust."),
             number("brightness", Dimension::None, 0.0, -1.0, 1.0, "Added to the encoded values."),
             number("contrast", Dimension::None, 1.0, 0.0, 10.0, "Scale of the distance from 0.5."),
             number("saturation", Dimension::None, 1.0, 0.0, 10.0,
                    "Scale of the distance from the luma grey (0: greyscale)."),
             number("hue", Dimension::Angle, 0.0, -360 * kDegree, 360 * kDegree,
                    "Rotation of the hue about the grey axis."),
             number("gamma", Dimension::None, 1.0, 0.05, 20.0,
                    "Exponent 1/gamma on the encoded values (above 1 brightens mid tones)."),
             number("black", Dimension::None, 0.0, 0.0, 1.0, "Levels: input value mapped to 0."),
             number("white", Dimension::None, 1.0, 0.0, 1.0, "Levels: input value mapped to 1.")}};
}

KindSchema blendSource() {
    return {"source",
            "blend",
            PortType::None,
            "Lays `over` on `base`. Weight = opacity x over's coverage (image alpha, or the "
            "coverage of an elevation raster) x mask, where feather > 0 fades the coverage in "
            "over about `feather` metres inside its edge (from the coverage at the pyramid level "
            "whose texels are twice the feather, bilinearly interpolated, so the fade is the same "
            "at every level and seamless across tiles). Images: modes normal, multiply, screen, "
            "add, min, max in linear RGB. Elevation: replace (= normal), add, min, max, so a local "
            "DEM merges into a global relief without a step.",
            {port("base", PortType::None, true, "The source underneath (elevation or image)."),
             port("over", PortType::None, true, "The source laid on top, of the same port type."),
             port("mask", PortType::Mask, false, "Optional weight in [0, 1]."),
             number("opacity", Dimension::Ratio, 1.0, 0.0, 1.0, "Overall weight of `over`."),
             number("feather", Dimension::Length, 0.0, 0.0, 1e7,
                    "Width of the fade inside the edge of over's coverage, in metres."),
             wordChoice(
                 "mode", {"normal", "replace", "multiply", "screen", "add", "min", "max"}, "normal",
                 "How over combines with base (elevation: normal/replace, add, min, max).")}};
}

KindSchema maskSource() {
    return {
        "source",
        "mask",
        PortType::Mask,
        "A mask in [0, 1] from one to four inputs: a band expression (e.g. NDVI "
        "`(nir - red) / (nir + red) > 0.35`), or a colour classification (1 where the "
        "texel's nearest class colour is `select`), then morphological open/close and a "
        "feather (box blur twice) with radii in metres, computed over the 3 x 3 neighbour "
        "tiles so the result is seamless. Expressions: numbers, + - * / ^, unary -, "
        "comparisons < <= > >= == != (1 or 0), and (&&), or (||), not (!), min(a, b), max(a, b), "
        "abs(x), sqrt(x), clamp(x, lo, hi), and names: `b1`..`b4` are channels of the first "
        "input, `<input>` its first channel, `<input>.b1`..`.b4` (or .r .g .b .a) its channels. "
        "Division by zero gives 0. No-data texels (coverage 0) give 0.",
        {port("input", PortType::None, true,
              "First input (image, mask or elevation); `b1`..`b4` are its channels."),
         port("input2", PortType::None, false, "Second input, named by its source name."),
         port("input3", PortType::None, false, "Third input."),
         port("input4", PortType::None, false, "Fourth input."),
         simple("expression", ValueType::String, text(""),
                "The band expression; empty: `b1`, or the classification when `classes` is set."),
         listOf("classes", ValueType::Color, Dimension::None, false,
                "Class colours (sRGB) for classification of the first input, compared in "
                "linear RGB."),
         number("select", Dimension::None, 1, 1, 64, "The class (from 1) that gives 1."),
         number("open", Dimension::Length, 0.0, 0.0, 1e5,
                "Radius of a morphological opening (erode, then dilate): removes specks."),
         number("close", Dimension::Length, 0.0, 0.0, 1e5,
                "Radius of a morphological closing (dilate, then erode): fills holes."),
         number("feather", Dimension::Length, 0.0, 0.0, 1e5,
                "Blur radius of the edges, in metres.")}};
}

// Vector and vegetation kinds of core/sources/{vector,compose,plants}.

KindSchema featuresSource() {
    return {
        "source",
        "features",
        PortType::Features,
        "Vector features from any OGR data set (Shapefile, GeoJSON, GeoPackage, KML ...) in any "
        "CRS: "
        "one layer, optionally filtered by an OGR SQL attribute filter, reprojected to WGS84 "
        "longitude/latitude and kept in memory with a spatial index (an STR-packed R-tree), "
        "loaded "
        "once per content on first use. Features crossing the antimeridian stay whole; rings "
        "around "
        "a pole are closed along it. Consumed by rasterize, elevation_edit and plants (features "
        "are "
        "not a terrain layer). An unreadable file, a missing layer, a filter naming a missing "
        "field "
        "or broken geometry (invalid, empty, unclosed rings; see `invalid`) fail with one message "
        "naming the file, layer, feature or field and the reason.",
        {requiredString("file", "Path of the data set, relative to the project file."),
         simple("layer", ValueType::String, text(""), "Layer name; the first layer when empty."),
         simple("where", ValueType::String, text(""),
                "OGR SQL attribute filter, e.g. \"continent = 'South America'\"; every feature "
                "when empty."),
         wordChoice(
             "invalid", {"error", "skip", "repair"}, "error",
             "Broken geometry: fail (naming the feature), leave the feature out, or repair it "
             "(OGR MakeValid).")}};
}

KindSchema rasterizeSource() {
    return {
        "source",
        "rasterize",
        PortType::None,
        "Draws features (or plant instances as crown discs) into a mask (coverage in [0, 1]) or "
        "an "
        "image (linear RGB + alpha = coverage), anti-aliased: polygons by exact area coverage, "
        "lines, "
        "outlines and discs by box-filtered cross-sections, with widths in metres on the "
        "ellipsoid "
        "(right at any latitude). Features composite in file order. Colour: `color`, or per "
        "feature "
        "from `color_attribute` as a hex string (\"#1a8c3f\") or through the `colors` mapping. "
        "Instances: discs of point_radius x instance scale, colour x instance tint, drawn from "
        "the "
        "plants source's minimum level on (coarser tiles stay transparent).",
        {port("features", PortType::Features, false, "Features to draw (or `instances`)."),
         port("instances", PortType::Instances, false,
              "Plant instances to draw as discs (or `features`)."),
         wordChoice("kind", {"image", "mask"}, "image",
                    "Output: an image (colour + alpha) or a mask."),
         simple("fill", ValueType::Bool, boolean(true), "Fill polygons."),
         number("outline", Dimension::Length, 0.0, 0.0, 1e6,
                "Width of polygon outlines in metres, centred on the boundary; 0: none."),
         number("line_width", Dimension::Length, 10.0, 0.0, 1e6,
                "Width of line features in metres."),
         number("point_radius", Dimension::Length, 5.0, 0.0, 1e6,
                "Radius of point features in metres (instances: times their scale)."),
         number("minimum_texels", Dimension::None, 0.0, 0.0, 16.0,
                "Lines and outlines narrower than this many texels are drawn that wide but "
                "fainter (opacity = width / drawn width), so their ink stays metric at every "
                "level: a 1 or 1.5 keeps thin lines continuous from afar without flooding coarse "
                "levels; 0: exactly their width in metres."),
         simple("color", ValueType::Color, color(1.0f, 1.0f, 1.0f), "Fixed colour (sRGB)."),
         simple("color_attribute", ValueType::String, text(""),
                "Attribute giving each feature's colour: a hex string, or a key of `colors`."),
         simple("colors", ValueType::Object, std::nullopt,
                "Mapping from attribute values to colours, e.g. { forest = #1a5c2a, water = "
                "#1f4e8c }."),
         number("opacity", Dimension::Ratio, 1.0, 0.0, 1.0, "Scales the coverage.")}};
}

KindSchema elevationEditSource() {
    return {
        "source",
        "elevation_edit",
        PortType::Elevation,
        "Reshapes an elevation with polygons (dams, embankments, pits, cut slopes): flatten to "
        "`height`, raise or lower by `amount`, or slope (the plane through the polygon's centroid "
        "at "
        "`height` rising with `gradient` towards `direction`). Weight 1 inside, smoothstep over "
        "`feather` metres outside the boundary (without feather: the texel's exact area "
        "coverage); "
        "h = h0 + w (target - h0), or h0 +- w amount. Values may come per feature from "
        "attributes.",
        {port("input", PortType::Elevation, true, "The elevation to edit."),
         port("features", PortType::Features, true, "Polygons to apply, in order."),
         wordChoice("mode", {"flatten", "raise", "lower", "slope", "level"}, "flatten",
                    "The edit. `level`: level at the mean input height under the polygon "
                    "(+ amount), e.g. the plots of a proposal's buildings."),
         number("height", Dimension::Length, 0.0, -1e5, 1e5,
                "Target height above the ellipsoid (flatten), or the plane's height at the "
                "centroid (slope)."),
         number("amount", Dimension::Length, 0.0, 0.0, 1e5,
                "Height change (raise, lower; level: added to the mean)."),
         number("gradient", Dimension::Ratio, 0.0, -100.0, 100.0,
                "Slope of the plane, rise per horizontal distance (slope; 10% = 1 m per 10 m)."),
         number("direction", Dimension::Angle, 0.0, -360 * kDegree, 360 * kDegree,
                "Azimuth the plane rises towards, clockwise from north (slope)."),
         number("feather", Dimension::Length, 0.0, 0.0, 1e6,
                "Width of the smooth transition outside the polygon, in metres."),
         simple("height_attribute", ValueType::String, text(""),
                "Attribute with each polygon's height in metres (flatten, slope)."),
         simple("amount_attribute", ValueType::String, text(""),
                "Attribute with each polygon's amount in metres (raise, lower).")}};
}

KindSchema plantsSource() {
    AttributeSchema scale =
        listOf("scale", ValueType::Number, Dimension::None, false,
               "[minimum, maximum] of the random uniform scale; default [0.8, 1.2].");
    return {"source",
            "plants",
            PortType::Instances,
            "Plant instances on the terrain (position, species, scale, rotation, tint) from point "
            "features and by scattering over a density mask and/or polygons: one candidate per "
            "cell of "
            "a fixed global grid (about 100 m / sqrt(per_hectare) wide), jittered inside the cell "
            "shrunk "
            "by spacing / 2 so neighbours are never closer than `spacing`, kept with probability "
            "density x per_hectare x cell area, so counts match the density exactly in "
            "expectation. "
            "Every cell's randomness comes from (seed, cell), so instances are identical whatever "
            "the "
            "tile, worker count or request order, and each instance belongs to exactly one tile. "
            "Heights come from `elevation`. Species mix by share for scattering; for points from "
            "`species_attribute` (through `species_map`). Drawn as trees when a scenario lists "
            "the "
            "source in its `layers` (each species with the `models` entry of its name), and as "
            "crown markers by rasterize.",
            {port("elevation", PortType::Elevation, true,
                  "Terrain the instances stand on (any source giving elevation)."),
             port("density", PortType::Mask, false, "Density in [0, 1] (times per_hectare)."),
             port("features", PortType::Features, false,
                  "Points (one instance each) and/or polygons (scattered over)."),
             port("exclude", PortType::Features, false,
                  "Polygons kept free of plants (e.g. the footprints of a proposal's "
                  "buildings): no instance inside them."),
             number("per_hectare", Dimension::None, 100.0, 0.01, 1e4,
                    "Instances per hectare where the density is 1 (inside polygons)."),
             number("spacing", Dimension::Length, 0.0, 0.0, 1e4,
                    "Minimum distance between scattered instances, in metres (less than the cell "
                    "size)."),
             simple("species", ValueType::Object, std::nullopt,
                    "Species mix for scattering: { name = share, ... }, e.g. { oak = 60%, pine = "
                    "40% }."),
             simple("species_attribute", ValueType::String, text(""),
                    "Points: attribute naming each point's species."),
             simple("species_map", ValueType::Object, std::nullopt,
                    "Points: attribute value -> species name, e.g. { \"Quercus robur\" = \"oak\" "
                    "}; a value "
                    "not in the map is an error."),
             scale,
             simple("scale_attribute", ValueType::String, text(""),
                    "Points: attribute with the scale."),
             simple("rotation_attribute", ValueType::String, text(""),
                    "Points: attribute with the rotation in degrees clockwise from north; random "
                    "otherwise."),
             number("tint_variation", Dimension::Ratio, 0.1, 0.0, 1.0,
                    "Tint brightness is uniform in [1 - v, 1 + v]."),
             number("seed", Dimension::None, 1, 0, 2147483647, "Random seed of the scattering."),
             referenceList("models", "source", PortType::PlantModel, false,
                           "Plant models of the species: [@oak, @palm]; each species is drawn with "
                           "the plant_model source of the same name (a species without one is an "
                           "error). Without `models` the plants are markers only.")}};
}

KindSchema plantModelSource() {
    AttributeSchema presetChoice;
    presetChoice.name = "preset";
    presetChoice.type = ValueType::Word;
    presetChoice.words = PlantGenerator::presetNames();
    presetChoice.doc = "Generated tree: a preset of `sylva plant generate`, e.g. `preset = oak`.";
    return {
        "source",
        "plant_model",
        PortType::PlantModel,
        "One plant species for the vegetation renderer: its mesh and its ellipsoid/line level of "
        "detail (seed 001 ch. 3), built once and cached under $SYLVA_CACHE_DIR (else "
        "$XDG_CACHE_HOME/sylva or ~/.cache/sylva) as plants/<content hash>.plod. Either a "
        "generated "
        "tree (`preset`, `leaves`, `seed`) or a `file`: a glTF/GLB/OBJ model (imported), or a "
        ".plod "
        "(level of detail only: no close-up mesh). `lod` gives a prebuilt .plod for a model, read "
        "instead of building. Referenced by a plants source's `models`; the species name is the "
        "source name.",
        {presetChoice,
         optionalNumber("leaves", Dimension::None, 1, 1e6,
                        "Generated tree: exact number of leaves (default: the preset's own)."),
         number("seed", Dimension::None, 1, 0, 2147483647,
                "Generated tree: random seed (also seeds the level-of-detail builder)."),
         simple(
             "file", ValueType::String, std::nullopt,
             "Model file (.gltf, .glb, .obj; leaves/branches as in `sylva plant info`) or a .plod "
             "(level of detail only), relative to the project file."),
         simple("lod", ValueType::String, std::nullopt,
                "Prebuilt .plod of this model (`sylva plant build`), used instead of building."),
         simple("billboards", ValueType::Bool, boolean(false),
                "Also build billboard clouds (seed 003), for comparison.")}};
}

// The blocks that are not sources.

KindSchema scenarioBlock() {
    return {"scenario",
            "",
            PortType::None,
            "A state of the landscape: the layers the terrain is made of. Elevation, "
            "image and normals layers feed the height, colour and normal clipmaps.",
            {referenceList("layers", "source", PortType::None, true,
                           "Sources that form the terrain, at most one per port type.")}};
}

KindSchema cameraBlock() {
    AttributeSchema position = simple("position", ValueType::Geo, std::nullopt,
                                      "geo(lat, lon[, height above the ellipsoid]) or [x, y[, "
                                      "height]] in the project CRS.");
    position.required = true;
    AttributeSchema body;
    body.name = "body";
    body.type = ValueType::Word;
    body.words = {"full_frame", "aps_c", "aps_c_canon", "micro_four_thirds", "medium_format"};
    body.doc =
        "A named camera body for focal_length: full_frame 36 x 24 mm, aps_c 23.5 x 15.6 "
        "mm, aps_c_canon 22.3 x 14.9 mm, micro_four_thirds 17.3 x 13 mm, medium_format "
        "43.8 x 32.9 mm.";
    return {"camera",
            "",
            PortType::None,
            "A viewpoint. Height comes from eye_height (above the terrain) if given, otherwise "
            "from the third component of position (above the ellipsoid), otherwise 1.5 m above "
            "the terrain. The field of view is one of fov (vertical), horizontal_fov or "
            "focal_length (on a sensor or body; full frame when neither is given); the vertical "
            "field of the image follows from its aspect (docs/verified-views.md).",
            {position,
             optionalNumber("eye_height", Dimension::Length, 0.01, 1e8,
                            "Height above the terrain surface, in metres (default 1.5 m when "
                            "position has no height)."),
             number("heading", Dimension::Angle, 0, -360 * kDegree, 360 * kDegree,
                    "Compass direction of view, clockwise from north."),
             number("pitch", Dimension::Angle, 0, -90 * kDegree, 90 * kDegree,
                    "Elevation of the view direction above the local horizon (planar only)."),
             number("roll", Dimension::Angle, 0, -180 * kDegree, 180 * kDegree,
                    "Rotation about the view direction (planar only)."),
             optionalNumber("fov", Dimension::Angle, 1 * kDegree, 170 * kDegree,
                            "Vertical field of view of a planar image (default 60°)."),
             optionalNumber("horizontal_fov", Dimension::Angle, 1 * kDegree, 360 * kDegree,
                            "Horizontal field of view: planar up to 170°, cylindrical up to 360°."),
             optionalNumber("focal_length", Dimension::Length, 1e-4, 10.0,
                            "Lens focal length, e.g. 50mm; with sensor or body it gives the "
                            "horizontal field 2 atan(sensor width / (2 focal length))."),
             listOf("sensor", ValueType::Number, Dimension::Length, false,
                    "Sensor [width, height], e.g. [36mm, 24mm] (default: full frame)."),
             body,
             wordChoice("projection", {"planar", "cylindrical", "equirectangular"}, "planar",
                        "planar (a photograph), cylindrical (columns are bearings at equal angle "
                        "steps; needs horizontal_fov or focal_length) or equirectangular "
                        "(360° x 180°)."),
             listOf("shift", ValueType::Number, Dimension::Ratio, false,
                    "Lens shift [x, y] as fractions of the image width and height (+y raises "
                    "the view window); cylindrical: [0, y] only."),
             listOf("output_size", ValueType::Number, Dimension::Length, false,
                    "Printed image size [width, height], e.g. [820mm, 260mm]; with dpi it sets "
                    "this camera's pixel size."),
             optionalNumber("dpi", Dimension::None, 1, 10000,
                            "Print resolution in dots per inch (with output_size)."),
             simple("look_at", ValueType::Geo, std::nullopt,
                    "A point to look at; replaces heading and pitch.")}};
}

KindSchema viewsBlock() {
    AttributeSchema output =
        simple("output", ValueType::String, text("{camera}.png"),
               "Output path template relative to the --out folder, with {view} {camera} {path} "
               "{frame} {scenario} {time} {time:%H%M} {step} {t}. The extension picks the format: "
               ".png (8-bit sRGB), .exr (linear half-float radiance after exposure, before tone "
               "mapping), .mp4 (one H.264 video per path, encoded by ffmpeg; paths only, no "
               "{frame}). Images carry metadata (camera, scenario, time, project, hashes).");
    return {"views",
            "",
            PortType::None,
            "A series of images to render.",
            {referenceList("cameras", "camera", PortType::None, false,
                           "Cameras to render (a views block needs cameras or paths)."),
             referenceList("scenarios", "scenario", PortType::None, false,
                           "Scenarios to render; the first scenario when absent."),
             output,
             simple("sheet", ValueType::Bool, boolean(false),
                    "Also write a viewpoint sheet per camera image: NAME.sheet.pdf and "
                    "NAME.sheet.png (the image at the camera's output_size, metadata below) and "
                    "NAME.json (the same metadata); the cameras need output_size and dpi."),
             listOf("sheet_size", ValueType::Number, Dimension::Length, false,
                    "Sheet page [width, height], e.g. [841mm, 297mm]; default: the image plus "
                    "margins and the metadata block."),
             referenceList("photos", "photo", PortType::None, false,
                           "Photo blocks made with this series by `sylva render` (their "
                           "photomontage, wirelines and sheets, as `sylva montage` makes "
                           "them, under --out) once every image of the series is written: a "
                           "viewpoint pack from one command.")}};
}

KindSchema renderBlock() {
    AttributeSchema resolution;
    resolution.name = "resolution";
    resolution.type = ValueType::List;
    resolution.element = ValueType::Number;
    resolution.dimension = Dimension::Pixels;
    Value defaultResolution;
    defaultResolution.data =
        ValueList{quantity(1280, Dimension::Pixels), quantity(720, Dimension::Pixels)};
    resolution.defaultValue = defaultResolution;
    resolution.doc = "Image size [width, height] in pixels.";
    Value sun;
    sun.data = GeoPosition{23 * kDegree, 20 * kDegree, std::nullopt};
    return {"render",
            "",
            PortType::None,
            "How images are rendered.",
            {resolution,
             number("samples", Dimension::None, 1, 1, 16,
                    "Anti-aliasing: samples per pixel (a whole number), each a render with the "
                    "image shifted by a sub-pixel offset, averaged in linear light (4: the "
                    "2 x 2 grid, as a twice larger image box-filtered down); costs about that "
                    "many times the time of one image."),
             simple("sun", ValueType::Geo, sun,
                    "Subsolar point: where on Earth the sun stands at the zenith."),
             simple("atmosphere", ValueType::Bool, boolean(true),
                    "Sky, limb glow and aerial perspective (haze)."),
             simple("ocean", ValueType::Bool, boolean(true),
                    "Clamp terrain below 0 m to a flat sea surface."),
             number("visibility", Dimension::Length, 40000.0, 100.0, 280000.0,
                    "Meteorological range (Koschmieder): the distance at which a black object's "
                    "contrast against the horizon sky falls to 2 %. Sets the ground-level "
                    "extinction at 550 nm to 3.912 / visibility (Rayleigh air plus aerosols); "
                    "40 km is a clear day, 10 km hazy, 280 km air without aerosols."),
             number("haze_height", Dimension::Length, 1200.0, 100.0, 20000.0,
                    "Scale height of the aerosols (haze): their density falls by 1/e per "
                    "haze_height of altitude; larger values thicken the haze seen from above."),
             optionalNumber("ev100", Dimension::None, -10.0, 25.0,
                            "Camera exposure value at ISO 100 (a physical camera: 15 for sunny "
                            "noon, about 0 at dusk). Absent: metered for each view from the sun "
                            "and sky light at the ground under the camera (incident-light "
                            "metering, ISO 2720), so one viewpoint and time get one exposure "
                            "in every scenario."),
             simple("shadows", ValueType::Bool, boolean(true),
                    "Sun shadows of terrain and plants (cascaded shadow maps, seed 001 §7.1), "
                    "with long terrain shadows beyond shadow_distance up to 60 km."),
             number("shadow_distance", Dimension::Length, 2000.0, 20.0, 100000.0,
                    "View distance covered by the fine shadow cascades (four, split by the "
                    "practical split scheme of 2048 texels each: at 2 km the nearest cascade's "
                    "texels are about 1 cm, the farthest's about 2.5 m)."),
             simple("ambient_occlusion", ValueType::Bool, boolean(true),
                    "Screen-space ambient occlusion of the sky light (horizon-based, seed 001 "
                    "§7.1): creases, the feet of walls and buildings, the ground under trees "
                    "get less sky; multiplied with the plants' precomputed occlusion; the sun "
                    "is shadowed by the shadow maps only. Costs one pass over the image."),
             number("ambient_occlusion_radius", Dimension::Length, 2.0, 0.1, 100.0,
                    "Radius of the sphere around each point searched for occluders; surfaces "
                    "farther apart (a ridge in front of far terrain, the sky) never occlude. "
                    "Seen under 1.5 pixels (far away) it has no effect."),
             number("ambient_occlusion_strength", Dimension::None, 1.0, 0.0, 1.0,
                    "Sky light = 1 - strength x the occluded fraction of the hemisphere (1: "
                    "the physical fraction; 0: no occlusion)."),
             number("exposure", Dimension::None, 1.0, 0.01, 100.0,
                    "Scale applied to the exposed radiance before tone mapping (2 = one "
                    "stop brighter than ev100 or the metered exposure)."),
             number("max_level", Dimension::None, 24, 4, 28, "Finest clipmap level drawn."),
             number("cache_mb", Dimension::None, 1024, 16, 1048576,
                    "Tile cache budget in MiB (render and watch; --cache-mb overrides it). "
                    "It must hold one frame's tiles, about 250 MiB at 25 levels."),
             simple("disk_cache", ValueType::String, std::nullopt,
                    "Folder of the persistent tile cache shared by processes and machines, "
                    "relative to the project file (render; --disk-cache DIR overrides it, "
                    "--no-disk-cache turns it off). Default: $SYLVA_CACHE_DIR/tiles, else "
                    "$XDG_CACHE_HOME/sylva/tiles, else ~/.cache/sylva/tiles."),
             number("disk_cache_mb", Dimension::None, 16384, 64, 1.0e9,
                    "Disk tile cache budget in MiB; least recently used tiles are removed "
                    "beyond it (--disk-cache-mb overrides it)."),
             wordChoice(
                 "vegetation", {"lod", "billboards", "mesh", "points", "dmbbc", "impostors"}, "lod",
                 "How plants are drawn: ray-cast ellipsoid/line levels of detail with the source "
                 "mesh for close-ups, billboard clouds (from .plod files built with them), or the "
                 "source mesh everywhere (slow; a reference). points: the mesh sampled as discs "
                 "with approximate visible sets per view direction (seed 000 ch. 3); dmbbc: the "
                 "billboard clouds as ray-marched displacement-mapped boxes (seed 000 ch. 5); "
                 "impostors: view-direction impostors at 64/128/256 texels and far tiles as group "
                 "impostors re-used while their parallax stays within a pixel (seeds 004, 000 "
                 "ch. 7). The last three are comparison methods (docs/benchmarks.md)."),
             number("vegetation_quality", Dimension::None, 1.0, 0.1, 10.0,
                    "Divides the error a plant's level of detail may show (metres per pixel): 2 "
                    "draws "
                    "finer levels, 0.5 coarser ones."),
             number("vegetation_distance", Dimension::Length, 6000.0, 10.0, 1.0e6,
                    "Plants farther than this are left to the terrain's colour; nearer ones are "
                    "drawn "
                    "while they cover at least 1.5 pixels."),
             number("far_field_band", Dimension::Length, 500.0, 0.0, 5000.0,
                    "Beyond the plants that are drawn, the forest canopy is drawn as a displaced "
                    "layer over the terrain (heights from the plants' density and species), so "
                    "forested ridges keep their silhouette to the horizon; the trees hand over "
                    "to it by a screen-door fade over this width. 0 switches the far field "
                    "off.")}};
}

SchemaRegistry makeBuiltin() {
    SchemaRegistry registry;
    // Registration order is the order of `sylva doc`, docs/dsl.md and the lists of
    // did-you-mean suggestions.
    for (KindSchema (*kind)() :
         {projectBlock, noiseSource, normalMapSource, hypsometricSource, rasterSource,
          constantSource, adjustSource, blendSource, maskSource, featuresSource, rasterizeSource,
          elevationEditSource, plantsSource, plantModelSource, scenarioBlock, cameraBlock,
          viewsBlock, renderBlock}) {
        registry.add(kind());
    }
    // Sources whose output type follows an attribute (checked by the DSL once the whole
    // graph is known).
    registry.setOutputFrom("raster", "kind");
    registry.setOutputFrom("constant", "kind");
    registry.setOutputFrom("adjust", "input");
    registry.setOutputFrom("blend", "base");
    registry.setOutputFrom("rasterize", "kind");
    addLanguageSchema(registry);
    addObjectsSchema(registry);
    addAnalysisSchema(registry);
    addSeasonsSchema(registry);
    addPhotoSchema(registry);
    return registry;
}

}  // namespace

const SchemaRegistry& SchemaRegistry::builtin() {
    static const SchemaRegistry registry = makeBuiltin();
    return registry;
}

}  // namespace sylva
