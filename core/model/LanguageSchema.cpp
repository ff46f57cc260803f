// The blocks of the project language that are not sources: compare, blend and path,
// plus the language-level attributes of views (times). Kept apart from the source
// kinds in BuiltinSchema.cpp so the two tables can grow independently.
#include <utility>

#include "AttributeBuilders.h"
#include "sylva/core/model/Schema.h"

namespace sylva {
namespace {

using schema::attribute;

AttributeSchema angle(std::string name, double limitDegrees, std::string doc) {
    AttributeSchema a = attribute(std::move(name), ValueType::Number, std::move(doc));
    a.dimension = Dimension::Angle;
    constexpr double kDegree = 3.14159265358979323846 / 180.0;
    a.minimum = -limitDegrees * kDegree;
    a.maximum = limitDegrees * kDegree;
    return a;
}

AttributeSchema scenarioReference(std::string name, std::string doc) {
    AttributeSchema a = attribute(std::move(name), ValueType::Reference, std::move(doc));
    a.target = "scenario";
    a.required = true;
    return a;
}

Value word(std::string text) {
    Value v;
    v.data = Word{std::move(text)};
    return v;
}

Value number(double value, Dimension dimension) {
    Value v;
    v.data = Quantity{value, dimension};
    return v;
}

KindSchema compareBlock() {
    AttributeSchema layout = attribute("layout", ValueType::Word,
                                       "How the two scenarios share the image: a movable "
                                       "swipe line, side by side, or a difference image.");
    layout.words = {"swipe", "side_by_side", "difference"};
    layout.defaultValue = word("swipe");
    AttributeSchema split =
        attribute("split", ValueType::Number, "Position of the swipe line across the image.");
    split.dimension = Dimension::Ratio;
    split.minimum = 0.0;
    split.maximum = 1.0;
    split.defaultValue = number(0.5, Dimension::Ratio);
    AttributeSchema mode = attribute(
        "mode", ValueType::Word,
        "images: the two scenarios' images shown together as `layout` says; wireline: the "
        "outline of what `right` adds to `left` (by depth: buildings, objects, terrain "
        "edits, hidden parts omitted) and the terrain skyline drawn as lines over `left`'s "
        "image (LI TGN 06/19 Type 2); planar and cylindrical cameras, 8-bit outputs (.png) "
        "only.");
    mode.words = {"images", "wireline"};
    mode.defaultValue = word("images");
    KindSchema schema{
        "compare",
        "",
        PortType::None,
        "Two scenarios shown together, e.g. before and after a change.",
        {scenarioReference("left", "Scenario on the left (or before)."),
         scenarioReference("right", "Scenario on the right (or after)."), layout, split,
         [] {
             AttributeSchema labels =
                 attribute("labels", ValueType::Bool, "Draw the scenario names into the image.");
             Value yes;
             yes.data = true;
             labels.defaultValue = yes;
             return labels;
         }(),
         mode}};
    for (AttributeSchema& wireline : wirelineAttributes()) {
        schema.attributes.push_back(std::move(wireline));
    }
    return schema;
}

KindSchema blendBlock() {
    AttributeSchema amount =
        attribute("amount", ValueType::Number, "Weight of `to`: 0% is `from`, 100% is `to`.");
    amount.dimension = Dimension::Ratio;
    amount.minimum = 0.0;
    amount.maximum = 1.0;
    amount.defaultValue = number(0.5, Dimension::Ratio);
    AttributeSchema steps =
        attribute("steps", ValueType::Number,
                  "Make a sequence of this many images from t = 0 to 1 (`amount` is then unused); "
                  "the views' output template then needs {step} (000, 001 ...) or {t} (0.000 ... "
                  "1.000).");
    steps.dimension = Dimension::None;
    steps.minimum = 2.0;
    steps.maximum = 1000.0;
    return {"blend",
            "",
            PortType::None,
            "A mix of two scenarios, e.g. a planting half-way grown: one image, or a "
            "sequence from `from` to `to`.",
            {scenarioReference("from", "Scenario at 0%."),
             scenarioReference("to", "Scenario at 100%."), amount, steps}};
}

KindSchema pathBlock() {
    AttributeSchema interpolate =
        attribute("interpolate", ValueType::Word, "How positions and angles move between keys.");
    interpolate.words = {"linear", "catmull_rom", "step"};
    interpolate.defaultValue = word("catmull_rom");

    AttributeSchema at = attribute("at", ValueType::Number, "Time of the key from the start.");
    at.dimension = Dimension::Time;
    at.minimum = 0.0;
    at.required = true;
    AttributeSchema position =
        attribute("position", ValueType::Geo, "Camera position at this key.");
    position.required = true;
    AttributeSchema keys = attribute("keys", ValueType::List,
                                     "Key frames { at, position, heading | look_at, pitch, "
                                     "roll } in ascending time.");
    keys.element = ValueType::Object;
    keys.required = true;
    keys.fields = {at,
                   position,
                   angle("heading", 360, "Compass direction of view."),
                   angle("pitch", 90, "View elevation above the horizon."),
                   angle("roll", 180, "Rotation about the view direction."),
                   attribute("look_at", ValueType::Geo, "A point to look at."),
                   [] {
                       AttributeSchema eyeHeight = attribute(
                           "eye_height", ValueType::Number,
                           "Height above the terrain (replaces the position's height); when "
                           "every key has one the camera follows the ground between keys.");
                       eyeHeight.dimension = Dimension::Length;
                       eyeHeight.minimum = 0.01;
                       return eyeHeight;
                   }()};
    AttributeSchema fps = attribute("fps", ValueType::Number, "Frames per second.");
    fps.minimum = 1;
    fps.maximum = 240;
    fps.defaultValue = number(25, Dimension::None);
    AttributeSchema fov = angle("fov", 170, "Vertical field of view.");
    fov.minimum = 1 * 3.14159265358979323846 / 180.0;
    fov.defaultValue = number(60 * 3.14159265358979323846 / 180.0, Dimension::Angle);
    return {"path",
            "",
            PortType::None,
            "A camera animation: key frames interpolated over time.",
            {interpolate, keys, fps, fov}};
}

// The language-level attributes of views: times and paths (unless it has them already).
void addViewsAttributes(KindSchema& views) {
    if (!views.find("times")) {
        AttributeSchema times =
            attribute("times", ValueType::List,
                      "Dates and times to render (2024-06-21T09:00-03:00); the sun follows them.");
        times.element = ValueType::DateTime;
        views.attributes.push_back(std::move(times));
    }
    if (!views.find("paths")) {
        AttributeSchema paths = attribute("paths", ValueType::List, "Camera paths to render.");
        paths.element = ValueType::Reference;
        paths.target = "path";
        views.attributes.push_back(std::move(paths));
    }
}

}  // namespace

void addLanguageSchema(SchemaRegistry& registry) {
    registry.add(compareBlock());
    registry.add(blendBlock());
    registry.add(pathBlock());
    if (KindSchema* views = registry.edit("views")) {
        addViewsAttributes(*views);
    }
}

}  // namespace sylva
