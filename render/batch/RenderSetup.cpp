#include "sylva/render/batch/RenderSetup.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/model/BlockReader.h"
#include "sylva/core/seasons/PlantDate.h"

namespace sylva::render {
namespace {

// The render block's `resolution = [width, height]` into `settings`.
Status readResolution(BlockReader& renderBlock, RenderSettings& settings) {
    const Value* resolution = renderBlock.value("resolution");
    if (resolution == nullptr) {
        return {};
    }
    const ValueList* list = resolution->get<ValueList>();
    if (list == nullptr || list->size() != 2 || !(*list)[0].get<Quantity>() ||
        !(*list)[1].get<Quantity>()) {
        return Error{renderBlock.where("resolution") + "resolution must be [width, height]"};
    }
    settings.width = static_cast<int>((*list)[0].get<Quantity>()->value);
    settings.height = static_cast<int>((*list)[1].get<Quantity>()->value);
    if (settings.width < 1 || settings.height < 1 || settings.width > 16384 ||
        settings.height > 16384) {
        return Error{renderBlock.where("resolution") + "resolution must be within 1..16384 pixels"};
    }
    return {};
}

// `samples = N` (the schema checked 1..16): a whole number of samples per pixel.
Status readSamples(BlockReader& renderBlock, RenderSettings& settings) {
    const double samples = renderBlock.optionalNumber("samples").value_or(1.0);
    if (samples != std::floor(samples)) {
        char text[32];
        std::snprintf(text, sizeof text, "%g", samples);
        return Error{renderBlock.where("samples") + "samples must be a whole number, not " + text};
    }
    settings.samples = static_cast<int>(samples);
    return {};
}

}  // namespace

Result<RenderSetup> RenderSetup::fromModel(const ProjectModel& model, int overrideWidth,
                                           int overrideHeight) {
    BlockReader renderBlock(model.render, SchemaRegistry::builtin().find("render"));
    RenderSetup setup;
    RenderSettings& settings = setup.settings;
    if (overrideWidth > 0) {
        settings.width = overrideWidth;
        settings.height = overrideHeight;
    } else if (Status read = readResolution(renderBlock, settings); !read) {
        return read.error();
    }
    if (Status read = readSamples(renderBlock, settings); !read) {
        return read.error();
    }
    const GeoPosition sun = renderBlock.geo("sun").value_or(GeoPosition{0.4, 0.35, std::nullopt});
    setup.defaultSun = Ellipsoid::surfaceNormal(sun.latitude, sun.longitude);
    settings.sunDirection = setup.defaultSun;
    if (const Value* date = renderBlock.value("date"); date && date->get<std::string>()) {
        Result<DateTime> parsed = DateTime::parse(*date->get<std::string>());
        Result<PlantDate> day =
            parsed ? PlantDate::fromDateTime(parsed.value()) : Result<PlantDate>(parsed.error());
        if (!day) {
            return Error{renderBlock.where("date") + "date: " + day.error().message};
        }
        settings.plantDate = day.value();
    }
    settings.atmosphere = renderBlock.boolean("atmosphere", true);
    settings.ocean = renderBlock.boolean("ocean", true);
    settings.exposure = renderBlock.optionalNumber("exposure").value_or(1.0);
    settings.ev100 = renderBlock.optionalNumber("ev100");
    Result<AtmosphereParameters> atmosphere = AtmosphereParameters::fromVisibility(
        renderBlock.optionalNumber("visibility").value_or(40000.0),
        renderBlock.optionalNumber("haze_height").value_or(1200.0));
    if (!atmosphere) {
        return Error{renderBlock.where("visibility") + atmosphere.error().message};
    }
    settings.atmosphereParameters = atmosphere.value();
    settings.shadows.enabled = renderBlock.boolean("shadows", true);
    settings.shadows.distance = renderBlock.optionalNumber("shadow_distance").value_or(2000.0);
    settings.ambientOcclusion.enabled = renderBlock.boolean("ambient_occlusion", true);
    settings.ambientOcclusion.radius =
        renderBlock.optionalNumber("ambient_occlusion_radius").value_or(2.0);
    settings.ambientOcclusion.strength =
        renderBlock.optionalNumber("ambient_occlusion_strength").value_or(1.0);
    setup.terrain.maxLevel = static_cast<int>(renderBlock.optionalNumber("max_level").value_or(24));
    setup.cacheMegabytes =
        static_cast<std::size_t>(renderBlock.optionalNumber("cache_mb").value_or(1024));
    if (const Value* folder = renderBlock.value("disk_cache");
        folder && folder->get<std::string>()) {
        std::filesystem::path path(*folder->get<std::string>());
        setup.diskCacheFolder = path.is_absolute() ? path : model.file.parent_path() / path;
    }
    setup.diskCacheMegabytes =
        static_cast<std::uint64_t>(renderBlock.optionalNumber("disk_cache_mb").value_or(16384));
    const Value* vegetationValue = renderBlock.value("vegetation");
    const std::string vegetation = vegetationValue && vegetationValue->get<Word>()
                                       ? vegetationValue->get<Word>()->text
                                       : "lod";
    settings.vegetation.method = vegetation == "mesh"         ? VegetationMethod::Mesh
                                 : vegetation == "billboards" ? VegetationMethod::Billboard
                                 : vegetation == "points"     ? VegetationMethod::Points
                                 : vegetation == "dmbbc"      ? VegetationMethod::DisplacedBillboard
                                 : vegetation == "impostors"  ? VegetationMethod::Impostors
                                                              : VegetationMethod::Lod;
    settings.vegetation.quality = renderBlock.optionalNumber("vegetation_quality").value_or(1.0);
    settings.vegetation.maximumDistance =
        renderBlock.optionalNumber("vegetation_distance").value_or(6000.0);
    settings.farField.band = renderBlock.optionalNumber("far_field_band").value_or(500.0);
    return setup;
}

}  // namespace sylva::render
