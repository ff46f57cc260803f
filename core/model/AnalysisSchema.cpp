// The analysis blocks of the project language (issue 19): `ztv`, the bare-earth zone of
// theoretical visibility that `sylva analyse` computes (core/analysis). Kept apart from
// the source kinds and the render blocks so the analyses can grow on their own.
#include <utility>

#include "AttributeBuilders.h"
#include "sylva/core/model/Schema.h"

namespace sylva {
namespace {

using schema::attribute;

AttributeSchema length(std::string name, std::optional<double> defaultValue, double minimum,
                       std::string doc) {
    AttributeSchema a = attribute(std::move(name), ValueType::Number, std::move(doc));
    a.dimension = Dimension::Length;
    a.minimum = minimum;
    a.maximum = 1.0e6;
    if (defaultValue) {
        Value v;
        v.data = Quantity{*defaultValue, Dimension::Length};
        a.defaultValue = v;
    }
    return a;
}

KindSchema ztvBlock() {
    AttributeSchema elevation = attribute(
        "elevation", ValueType::Reference,
        "The terrain: a `raster` source (kind elevation or auto) whose file is a DEM in a "
        "projected CRS in metres; its file is read directly, on its own grid's CRS.");
    elevation.target = "source";
    elevation.port = PortType::Elevation;
    elevation.required = true;

    AttributeSchema position =
        attribute("position", ValueType::Geo,
                  "Where the target stands: geo(lat, lon) or [x, y] in the project CRS.");
    position.required = true;
    AttributeSchema height =
        length("height", std::nullopt, 0.01, "Height of the target's top above the ground.");
    height.required = true;
    AttributeSchema targets = attribute(
        "targets", ValueType::List,
        "The targets { position, height } (turbine tips, masts): the ZTV counts per cell how "
        "many tops are visible. A ztv needs `targets`, `proposal` or both.");
    targets.element = ValueType::Object;
    targets.fields = {position, height};

    AttributeSchema proposal = attribute(
        "proposal", ValueType::List,
        "Targets from the proposal: `objects` sources whose every placed model is a target at "
        "its highest point, rotors swept through a full turn (a turbine's blade tip at twelve "
        "o'clock) above its base, stood on this block's DEM; counted after `targets`.");
    proposal.element = ValueType::Reference;
    proposal.target = "source";

    AttributeSchema extent =
        attribute("extent", ValueType::List,
                  "[west, south, east, north] in metres in the project's `crs` (like [x, y] "
                  "positions; the elevation raster's CRS when the project has none; another "
                  "CRS than the raster's is converted to the box around the extent). The "
                  "whole raster when absent. Must lie inside the raster.");
    extent.element = ValueType::Number;
    extent.dimension = Dimension::Length;
    AttributeSchema extentGeo =
        attribute("extent_geo", ValueType::List,
                  "The extent as two opposite corners in latitude/longitude, [geo(south, west), "
                  "geo(north, east)] (or [x, y] corners in the project's `crs`), converted to "
                  "the box around the rectangle in the elevation raster's CRS; instead of "
                  "`extent`. Must lie inside the raster.");
    extentGeo.element = ValueType::Geo;

    AttributeSchema curvature =
        attribute("curvature", ValueType::Bool,
                  "Earth curvature: terrain sinks by d²/(2R)(1 − refraction) at distance d "
                  "(R = 6 371 008.8 m).");
    Value yes;
    yes.data = true;
    curvature.defaultValue = yes;

    AttributeSchema refraction =
        attribute("refraction", ValueType::Number,
                  "Refraction coefficient k (0.13 standard, 0.075 in some practice notes).");
    refraction.minimum = 0.0;
    refraction.maximum = 0.99;
    Value k;
    k.data = Quantity{0.13, Dimension::None};
    refraction.defaultValue = k;

    AttributeSchema screening = attribute(
        "screening", ValueType::List,
        "Screens for a screened ZTV, added to the bare earth as a surface model: `features` "
        "sources of building footprints (polygons with a numeric height attribute in metres, "
        "`screen_height_attribute`), `raster` sources of canopy height (metres above the "
        "ground, the DEM's CRS) and `plants` sources (each tree a column of its model's height "
        "over its crown radius, the instances the renderer draws). Observers stand on the ground; "
        "a cell whose screen is at "
        "least the observer height tall holds no observer (no data). Empty: bare earth.");
    screening.element = ValueType::Reference;
    screening.target = "source";
    AttributeSchema heightAttribute =
        attribute("screen_height_attribute", ValueType::String,
                  "The attribute of the building footprints that holds their height in metres.");
    Value heightName;
    heightName.data = std::string("height");
    heightAttribute.defaultValue = heightName;

    AttributeSchema output = attribute(
        "output", ValueType::String,
        "GeoTIFF written by `sylva analyse` (relative to --out, default the current folder; "
        "{name} is the block's name): bands visible (0/1), count of targets visible, fraction "
        "of the height visible; DEFLATE, with overviews.");
    Value path;
    path.data = std::string("out/{name}.tif");
    output.defaultValue = path;

    return {"ztv",
            "",
            PortType::None,
            "A zone of theoretical visibility, bare earth or screened by buildings and canopy: "
            "for each cell of the extent, are the targets visible from an observer standing "
            "there (line of sight over the DEM, with Earth curvature and refraction; "
            "docs/analysis.md).",
            {elevation, targets, proposal,
             length("observer_height", 2.0, 0.01, "Eye height above the ground at every cell."),
             extent, extentGeo,
             length("resolution", std::nullopt, 1.0,
                    "Cell size of the analysis grid; the raster's cell size when absent."),
             curvature, refraction, screening, heightAttribute, output}};
}

AttributeSchema dateTimeList(std::string name, std::string doc) {
    AttributeSchema a = attribute(std::move(name), ValueType::List, std::move(doc));
    a.element = ValueType::DateTime;
    return a;
}

AttributeSchema clockTime(std::string name, std::string doc) {
    return attribute(std::move(name), ValueType::DateTime, std::move(doc));
}

AttributeSchema plainNumber(std::string name, double minimum, double maximum,
                            std::optional<double> defaultValue, std::string doc) {
    AttributeSchema a = attribute(std::move(name), ValueType::Number, std::move(doc));
    a.minimum = minimum;
    a.maximum = maximum;
    if (defaultValue) {
        Value v;
        v.data = Quantity{*defaultValue, Dimension::None};
        a.defaultValue = v;
    }
    return a;
}

KindSchema shadowStudyBlock() {
    const KindSchema ztv = ztvBlock();
    AttributeSchema dates = dateTimeList(
        "dates", "The days to study (2024-03-20, 2024-06-21 ...), local days at `utc_offset`.");
    dates.required = true;
    AttributeSchema output = attribute(
        "output", ValueType::String,
        "Folder written by `sylva analyse` (relative to --out; {name} is the block's name): "
        "per date sun_hours_{date}.tif (hours of direct sun, Float32, DEFLATE, overviews), "
        "shadow_{date}_{HHMM}.png per frame and contact_{date}.png.");
    Value path;
    path.data = std::string("out/{name}");
    output.defaultValue = path;
    std::vector<AttributeSchema> attributes = {*ztv.find("elevation"), dates};
    for (const char* shared :
         {"extent", "extent_geo", "resolution", "screening", "screen_height_attribute"})
        attributes.push_back(*ztv.find(shared));
    AttributeSchema site = attribute(
        "site", ValueType::Reference,
        "The site: the polygons of a `features` source (any CRS). Without `extent` the study "
        "covers the site's box grown by `site_margin`; the frames outline the site, and the "
        "summary gives per date the site's mean hours of direct sun and the share of its "
        "cells with at least `sun_hours_target` hours (BRE 209's amenity test: half of the "
        "area with 2 hours on 21 March).");
    site.target = "source";
    site.port = PortType::Features;
    attributes.push_back(site);
    attributes.push_back(length("site_margin", 250.0, 0.0,
                                "Surroundings around the site's polygons that the study covers "
                                "when `extent` is absent: ground and screens out there can shade "
                                "the site (clipped to the elevation raster)."));
    attributes.push_back(length("shadow_reach", 5000.0, 0.0,
                                "How far outside the study's grid ground, buildings and trees "
                                "still cast shadows into it (clipped to the elevation raster): "
                                "a ridge 2 km away shades a valley once the sun is lower than "
                                "its height over 2 km. 0: only the grid itself casts."));
    attributes.push_back(plainNumber("sun_hours_target", 0.0, 24.0, 2.0,
                                     "Hours of direct sun a site cell needs to count in the "
                                     "summary's share (2 in BRE 209)."));
    attributes.push_back(clockTime("from",
                                   "Start of the day window, local clock time (06:00:00); "
                                   "midnight when absent."));
    attributes.push_back(
        clockTime("to",
                  "End of the day window, local clock time (18:00:00); midnight (24:00) "
                  "when absent."));
    attributes.push_back(
        plainNumber("step_minutes", 1.0, 720.0, 60.0, "Minutes between the frames of the window."));
    attributes.push_back(plainNumber("utc_offset", -14.0, 14.0, std::nullopt,
                                     "Hours of local clock time ahead of UTC (-3 in Olinda); the "
                                     "site's longitude / 15° rounded when absent."));
    attributes.push_back(output);
    return {"shadow_study", "", PortType::None,
            "A sun and shadow study over the DEM and the screens (buildings, canopy): for each "
            "date, shadow maps at every step of the day window and the hours of direct sun per "
            "cell, by ray casting along the NOAA solar direction (docs/analysis.md).",
            std::move(attributes)};
}

}  // namespace

void addAnalysisSchema(SchemaRegistry& registry) {
    registry.add(ztvBlock());
    registry.add(shadowStudyBlock());
}

}  // namespace sylva
