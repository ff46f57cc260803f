// The `photo` block (issue 18, verified views): a baseline photograph taken from a
// camera's viewpoint, the scenarios it shows (baseline) and proposes (scenario), and its
// surveyed control points. `sylva montage` matches the camera to it (core/scene
// CameraMatcher), composites the proposal over it (TGN 06/19 Type 3/4 photomontage) and
// draws the proposal's wireline and the terrain skyline (Type 2/3 wireline, photowire).
#include <utility>

#include "AttributeBuilders.h"
#include "sylva/core/model/Schema.h"

namespace sylva {
namespace {

using schema::attribute;

Value text(std::string value) {
    Value v;
    v.data = std::move(value);
    return v;
}

Value flag(bool value) {
    Value v;
    v.data = value;
    return v;
}

Value quantity(double value, Dimension dimension) {
    Value v;
    v.data = Quantity{value, dimension};
    return v;
}

AttributeSchema reference(std::string name, std::string target, std::string doc) {
    AttributeSchema a = attribute(std::move(name), ValueType::Reference, std::move(doc));
    a.target = std::move(target);
    a.required = true;
    return a;
}

AttributeSchema controlPoints() {
    AttributeSchema position = attribute(
        "position", ValueType::Geo,
        "The surveyed point: geo(lat, lon, height above the ellipsoid) or [x, y, height] in the "
        "project CRS.");
    position.required = true;
    AttributeSchema pixel = attribute(
        "pixel", ValueType::List,
        "Where the point is in the photograph: [x, y] in pixels from the top-left corner.");
    pixel.element = ValueType::Number;
    pixel.dimension = Dimension::Pixels;
    pixel.required = true;
    AttributeSchema name = attribute("name", ValueType::String, "A label for messages.");
    AttributeSchema points = attribute(
        "control_points", ValueType::List,
        "Surveyed control points { position, pixel[, name] }: with 4 or more, the camera's "
        "heading, pitch and roll (and with solve_focal_length its focal length) are solved "
        "from them (TGN 06/19 Type 4) and the residual of each is reported; 1 to 3 are an "
        "error; none: the camera block (and the photo's EXIF lens) is used as it is.");
    points.element = ValueType::Object;
    points.fields = {position, pixel, name};
    return points;
}

AttributeSchema pixels(std::string name, double fallback, double minimum, double maximum,
                       std::string doc) {
    AttributeSchema a = attribute(std::move(name), ValueType::Number, std::move(doc));
    a.dimension = Dimension::Pixels;
    a.minimum = minimum;
    a.maximum = maximum;
    a.defaultValue = quantity(fallback, Dimension::Pixels);
    return a;
}

KindSchema photoBlock() {
    AttributeSchema file = attribute(
        "file", ValueType::String,
        "The baseline photograph (JPEG, PNG or TIFF), relative to the project file. Its EXIF "
        "FocalLengthIn35mmFilm gives the camera's lens when the camera block sets no field of "
        "view, and must agree with it (within 2 %) when it does; DateTimeOriginal is reported.");
    file.required = true;
    AttributeSchema output = attribute(
        "output", ValueType::String,
        "Output prefix relative to --out ({name} is the block's name): writes PREFIX_montage.png "
        "(the proposal over the photograph), PREFIX_wireline.png (the proposal's outline and "
        "the terrain skyline over the photograph), PREFIX_model.png (the same lines over the "
        "rendered baseline) and PREFIX.json (camera, match residuals).");
    output.defaultValue = text("{name}");
    AttributeSchema time = attribute(
        "time", ValueType::DateTime,
        "When the photograph was taken (sets the sun); the render block's sun when absent.");
    AttributeSchema solveFocal =
        attribute("solve_focal_length", ValueType::Bool,
                  "Also solve the focal length from the control points (needs 5 or more).");
    solveFocal.defaultValue = flag(false);
    AttributeSchema sheet =
        attribute("sheet", ValueType::Bool,
                  "Also write PREFIX.sheet.pdf/.png: the photomontage at the camera's print "
                  "size, the viewpoint's record and a location map (the camera needs "
                  "output_size and dpi).");
    sheet.defaultValue = flag(false);
    AttributeSchema annotated =
        attribute("annotated", ValueType::Bool,
                  "Also write PREFIX_annotated.png: the photograph with the viewpoint id, a "
                  "bearing scale along the top edge, the proposal's horizontal extent and its "
                  "placed models' positions drawn into it (TGN 06/19 Type 1).");
    annotated.defaultValue = flag(false);
    KindSchema schema{
        "photo",
        "",
        PortType::None,
        "A baseline photograph for a photomontage (`sylva montage`): the camera is matched "
        "to it, the proposal (what `scenario` adds to `baseline`, by depth) is composited "
        "over it, hidden by the terrain, plants and buildings the baseline has, and the "
        "proposal's wireline and the terrain skyline are drawn (docs/verified-views.md).",
        {file, reference("camera", "camera", "The viewpoint the photograph was taken from."),
         reference("scenario", "scenario", "The scenario with the proposal."),
         reference("baseline", "scenario", "The scenario the photograph shows (existing)."),
         controlPoints(), solveFocal,
         pixels("max_residual", 3.0, 0.1, 1000.0,
                "The match fails when the control points' rms residual is above this."),
         time}};
    for (AttributeSchema& attribute : wirelineAttributes()) {
        schema.attributes.push_back(std::move(attribute));
    }
    schema.attributes.push_back(std::move(output));
    schema.attributes.push_back(std::move(sheet));
    schema.attributes.push_back(std::move(annotated));
    return schema;
}

}  // namespace

std::vector<AttributeSchema> wirelineAttributes() {
    AttributeSchema color =
        attribute("wireline_color", ValueType::Color, "Colour of the proposal's wireline (sRGB).");
    Value red;
    red.data = Color{1.0f, 0.1f, 0.1f, 1.0f};
    color.defaultValue = red;
    AttributeSchema skyline =
        attribute("skyline_color", ValueType::Color, "Colour of the terrain skyline (sRGB).");
    Value cyan;
    cyan.data = Color{0.0f, 0.85f, 1.0f, 1.0f};
    skyline.defaultValue = cyan;
    return {color, skyline,
            pixels("line_width", 3.0, 1.0, 50.0, "Width of the wirelines in pixels.")};
}

void addPhotoSchema(SchemaRegistry& registry) {
    registry.add(photoBlock());
}

}  // namespace sylva
