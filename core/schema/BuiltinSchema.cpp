// The built-in schema: every block keyword and source kind of this Sylva build.
// Adding a source kind means adding its entry here and its implementation under
// core/sources/; the DSL checker, `sylva doc` and docs/dsl.md follow from this table.
#include "sylva/core/schema/Schema.h"

#include <numbers>

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
    AttributeSchema a = number(std::move(name), dimension, std::nullopt, minimum, maximum,
                               std::move(doc));
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

SchemaRegistry makeBuiltin() {
    SchemaRegistry registry;

    registry.add({"project", "", PortType::None, "Project-wide settings.",
                  {simple("title", ValueType::String, text(""), "Title shown in outputs."),
                   simple("description", ValueType::String, text(""), "Free text.")}});

    registry.add(
        {"source", "noise", PortType::Elevation,
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
          number("offset", Dimension::Length, 0, -1e5, 1e5, "Added to every height, in metres.")}});

    registry.add(
        {"source", "normal_map", PortType::Normals,
         "Metric surface normals on the WGS84 ellipsoid (ECEF unit vectors) from an elevation "
         "source, by central differences over the tile border: seamless across tiles and "
         "correct at any latitude.",
         {port("height", PortType::Elevation, true, "Elevation to differentiate."),
          number("exaggeration", Dimension::None, 1.0, 0.0, 100.0,
                 "Scale applied to slopes before normalising.")}});

    registry.add(
        {"source", "hypsometric", PortType::Image,
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
                 "Slope where the surface is fully rock.")}});

    registry.add({"scenario", "", PortType::None,
                  "A state of the landscape: the layers the terrain is made of. Elevation, "
                  "image and normals layers feed the height, colour and normal clipmaps.",
                  {referenceList("layers", "source", PortType::None, true,
                                 "Sources that form the terrain, at most one per port type.")}});

    {
        AttributeSchema position = simple("position", ValueType::Geo, std::nullopt,
                                          "geo(lat, lon[, height above the ellipsoid]).");
        position.required = true;
        registry.add(
            {"camera", "", PortType::None,
             "A viewpoint. Height comes from eye_height (above the terrain) if given, otherwise "
             "from the third component of position (above the ellipsoid).",
             {position,
              optionalNumber("eye_height", Dimension::Length, 0.01, 1e8,
                             "Height above the terrain surface, in metres."),
              number("heading", Dimension::Angle, 0, -360 * kDegree, 360 * kDegree,
                     "Compass direction of view, clockwise from north."),
              number("pitch", Dimension::Angle, 0, -90 * kDegree, 90 * kDegree,
                     "Elevation of the view direction above the local horizon."),
              number("roll", Dimension::Angle, 0, -180 * kDegree, 180 * kDegree,
                     "Rotation about the view direction."),
              number("fov", Dimension::Angle, 60 * kDegree, 1 * kDegree, 170 * kDegree,
                     "Vertical field of view."),
              simple("look_at", ValueType::Geo, std::nullopt,
                     "A point to look at; replaces heading and pitch.")}});
    }

    {
        AttributeSchema output = simple("output", ValueType::String, text("{camera}.png"),
                                        "Output path template; {camera} and {scenario} are "
                                        "replaced. Relative to the --out folder.");
        registry.add({"views", "", PortType::None, "A series of images to render.",
                      {referenceList("cameras", "camera", PortType::None, true, "Cameras to render."),
                       referenceList("scenarios", "scenario", PortType::None, false,
                                     "Scenarios to render; the first scenario when absent."),
                       output}});
    }

    {
        AttributeSchema resolution;
        resolution.name = "resolution";
        resolution.type = ValueType::List;
        resolution.element = ValueType::Number;
        resolution.dimension = Dimension::Pixels;
        Value defaultResolution;
        defaultResolution.data = ValueList{quantity(1280, Dimension::Pixels),
                                           quantity(720, Dimension::Pixels)};
        resolution.defaultValue = defaultResolution;
        resolution.doc = "Image size [width, height] in pixels.";
        Value sun;
        sun.data = GeoPosition{23 * kDegree, 20 * kDegree, std::nullopt};
        registry.add(
            {"render", "", PortType::None, "How images are rendered.",
             {resolution,
              simple("sun", ValueType::Geo, sun,
                     "Subsolar point: where on Earth the sun stands at the zenith."),
              simple("atmosphere", ValueType::Bool, boolean(true),
                     "Sky, limb glow and aerial perspective (haze)."),
              simple("ocean", ValueType::Bool, boolean(true),
                     "Clamp terrain below 0 m to a flat sea surface."),
              number("exposure", Dimension::None, 1.0, 0.01, 100.0,
                     "Scale applied to radiance before tone mapping."),
              number("max_level", Dimension::None, 24, 4, 28,
                     "Finest clipmap level drawn.")}});
    }
    return registry;
}

}  // namespace

const SchemaRegistry& SchemaRegistry::builtin() {
    static const SchemaRegistry registry = makeBuiltin();
    return registry;
}

}  // namespace sylva
