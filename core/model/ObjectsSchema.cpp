// The schema of the proposal's source kinds: `buildings` (footprints extruded from the
// terrain) and `objects` (glTF/OBJ models placed from points, lines or positions).
// Implementations: core/sources/objects; drawn by render/objects.
#include <numbers>

#include "AttributeBuilders.h"
#include "sylva/core/model/Schema.h"

namespace sylva {
namespace {

using schema::attribute;

constexpr double kDegree = std::numbers::pi / 180.0;

AttributeSchema reference(std::string name, PortType port, bool required, std::string doc) {
    AttributeSchema a = attribute(std::move(name), ValueType::Reference, std::move(doc));
    a.port = port;
    a.target = "source";
    a.required = required;
    return a;
}

AttributeSchema number(std::string name, Dimension dimension, std::optional<double> defaultValue,
                       double minimum, double maximum, std::string doc) {
    AttributeSchema a = attribute(std::move(name), ValueType::Number, std::move(doc));
    a.dimension = dimension;
    if (defaultValue) {
        Value v;
        v.data = Quantity{*defaultValue, dimension};
        a.defaultValue = v;
    }
    a.minimum = minimum;
    a.maximum = maximum;
    return a;
}

AttributeSchema text(std::string name, std::string defaultText, std::string doc) {
    AttributeSchema a = attribute(std::move(name), ValueType::String, std::move(doc));
    Value v;
    v.data = std::move(defaultText);
    a.defaultValue = v;
    return a;
}

AttributeSchema words(std::string name, std::vector<std::string> choices, std::string defaultWord,
                      std::string doc) {
    AttributeSchema a = attribute(std::move(name), ValueType::Word, std::move(doc));
    a.words = std::move(choices);
    Value v;
    v.data = Word{std::move(defaultWord)};
    a.defaultValue = v;
    return a;
}

AttributeSchema colour(std::string name, Color defaultColor, std::string doc) {
    AttributeSchema a = attribute(std::move(name), ValueType::Color, std::move(doc));
    Value v;
    v.data = defaultColor;
    a.defaultValue = v;
    return a;
}

KindSchema buildingsSource() {
    return {
        "source",
        "buildings",
        PortType::Meshes,
        "Buildings extruded from polygon footprints (holes are courtyards) on the terrain: the "
        "base at the lowest (or mean) terrain height under the footprint, walls reaching down to "
        "the lowest terrain point (never floating on slopes), a flat, gable, hip or pyramid roof "
        "above the eaves. Height from an attribute, floors x storey height, or a constant. Roofs "
        "are triangulated with GEOS (constrained Delaunay). Drawn when a scenario lists the "
        "source in its `layers`; bad features (not polygons, self-intersecting, a missing or "
        "non-numeric height) are errors naming the file and feature id.",
        {reference("features", PortType::Features, true, "Footprint polygons."),
         reference("elevation", PortType::Elevation, true, "Terrain the buildings stand on."),
         number("height", Dimension::Length, 10.0, 0.0, 1000.0,
                "Eaves height above the base when no attribute gives it."),
         text("height_attribute", "", "Attribute with each building's eaves height in metres."),
         text("floors_attribute", "",
              "Attribute with the number of floors (times `storey_height`), used when "
              "`height_attribute` is not given."),
         number("storey_height", Dimension::Length, 3.0, 0.5, 100.0, "Height of one floor."),
         words("base", {"lowest", "mean"}, "lowest",
               "Base of the building: the lowest or the mean terrain height under the footprint "
               "(walls always reach down to the lowest)."),
         words("roof", {"flat", "gable", "hip", "pyramid"}, "flat",
               "Roof shape when no attribute gives it. Gable and hip need a four-cornered "
               "footprint without holes (ridge along the longer sides); other footprints get a "
               "pyramid when convex, else a flat roof."),
         text("roof_attribute", "", "Attribute with the roof shape (flat, gable, hip, pyramid)."),
         number("roof_pitch", Dimension::Angle, 30 * kDegree, 0.0, 75 * kDegree,
                "Pitch of sloped roofs."),
         text("pitch_attribute", "", "Attribute with the roof pitch in degrees."),
         colour("wall_color", Color{0.85f, 0.82f, 0.76f, 1.0f}, "Wall colour (sRGB)."),
         text("wall_color_attribute", "", "Attribute with a hex wall colour (#rrggbb)."),
         colour("roof_color", Color{0.62f, 0.27f, 0.2f, 1.0f}, "Roof colour (sRGB)."),
         text("roof_color_attribute", "", "Attribute with a hex roof colour (#rrggbb).")}};
}

KindSchema objectsSource() {
    AttributeSchema parts = attribute(
        "parts", ValueType::Object,
        "Articulated parts: node name -> attribute with its angle in degrees, e.g. { rotor = "
        "\"rotor_angle\", nacelle = \"yaw\" }; a part turns about its node's up axis (glTF: +Y "
        "of the node; OBJ groups: +Z).");
    AttributeSchema angles = attribute(
        "part_angles", ValueType::Object,
        "Angles of articulated parts for every placement: node name -> angle, e.g. { rotor = "
        "20deg }; an attribute in `parts` overrides it.");
    AttributeSchema model =
        attribute("model", ValueType::String,
                  "The model file (.gltf, .glb, .obj), relative to the project file.");
    model.required = true;
    AttributeSchema toward = attribute(
        "face_toward", ValueType::Geo,
        "Every object's +Y (forward) axis turned toward this point, instead of `heading`.");
    return {
        "source",
        "objects",
        PortType::Meshes,
        "A 3D model (glTF 2.0 .gltf/.glb or OBJ; +Y up for glTF, +Z up for OBJ, metres) placed at "
        "every point feature, or repeated along line features at `spacing`, instanced: one "
        "model, any number of placements. Scale, heading and height may come from attributes; "
        "named nodes can be turned per placement (a turbine's rotor and nacelle).",
        {reference("features", PortType::Features, true,
                   "Points (one object each) or lines (objects at `spacing`)."),
         reference("elevation", PortType::Elevation, true, "Terrain the objects stand on."), model,
         number("scale", Dimension::None, 1.0, 1e-6, 1e6, "Uniform scale of the model."),
         text("scale_attribute", "", "Attribute with each placement's scale."),
         text("size_attribute", "",
              "Attribute with a height in metres that the model's `reference_height` is scaled "
              "to (e.g. a turbine's hub height); overrides `scale`."),
         number("reference_height", Dimension::Length, 1.0, 1e-6, 1e6,
                "Height in the model (metres) that `size_attribute` is matched to."),
         number("heading", Dimension::Angle, 0.0, -360 * kDegree, 360 * kDegree,
                "Heading of the model's +Y axis, clockwise from north (lines: from the line's "
                "direction)."),
         text("heading_attribute", "", "Attribute with the heading in degrees."), toward,
         number("height", Dimension::Length, 0.0, -1e5, 1e5,
                "Height of the model's origin above the terrain (or above the ellipsoid with "
                "`absolute`)."),
         text("height_attribute", "", "Attribute with that height in metres."),
         words("height_mode", {"terrain", "absolute"}, "terrain",
               "`terrain`: heights are above the terrain at the placement; `absolute`: above "
               "the ellipsoid."),
         number("spacing", Dimension::Length, 50.0, 0.01, 1e6,
                "Distance between objects along line features."),
         parts, angles}};
}

}  // namespace

void addObjectsSchema(SchemaRegistry& registry) {
    registry.add(buildingsSource());
    registry.add(objectsSource());
}

}  // namespace sylva
