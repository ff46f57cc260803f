#include "sylva/render/vegetation/FarFieldCanopy.h"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sylva/core/base/Hash.h"
#include "sylva/core/sources/plants/CanopyLayerSource.h"
#include "sylva/core/sources/plants/PlantModelSource.h"
#include "sylva/core/sources/plants/PlantsSource.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/core/vegetation/LeafStates.h"

namespace sylva::render {

struct FarFieldCanopy::Layers {
    std::unique_ptr<CanopyLayerSource> elevation;
    std::unique_ptr<CanopyLayerSource> cover;
    std::unique_ptr<NormalMapSource> normals;
    std::vector<CanopyProfile> profiles;
    std::vector<std::vector<Phenology>> phenology;  // per profile: its species' tables
    double smallestSphereRadius = 0.0;              // metres
    double tallest = 0.0;                           // metres, largest profile height
    // The tallest profile's: the shader's crowns, tone and occlusion are one stand's (the
    // tallest wins the CEM where stands overlap).
    std::size_t dominant = 0;
};

Result<std::unique_ptr<FarFieldCanopy>> FarFieldCanopy::create(const ShaderLibrary& library,
                                                               const TerrainSettings& settings) {
    TerrainSettings rings = settings;
    rings.fragmentShader = "vegetation/farfield_canopy.frag";
    // An overlay over the terrain: interactive frames draw it once its coarsest level is
    // ready and never wait for it; its tiles follow the terrain's of the same level.
    rings.residentLevel = -1;
    rings.priorityOffset = 1;
    Result<std::unique_ptr<TerrainRenderer>> renderer = TerrainRenderer::create(library, rings);
    if (!renderer) {
        return renderer.error();
    }
    std::unique_ptr<FarFieldCanopy> canopy(new FarFieldCanopy());
    canopy->rings_ = std::move(renderer.value());
    return canopy;
}

FarFieldCanopy::~FarFieldCanopy() = default;

namespace {

// The canopy profile of a plants source, or nullopt when it has no density mask.
Result<std::optional<CanopyProfile>> profileOf(const PlantsSource& plants) {
    const PlantsParameters& parameters = plants.parameters();
    if (plants.density() == nullptr || parameters.species.empty() ||
        plants.models().size() < parameters.species.size()) {
        return std::optional<CanopyProfile>();
    }
    std::vector<CanopySpecies> species;
    for (std::size_t i = 0; i < parameters.species.size(); ++i) {
        const PlantModelSource* model = plants.models()[i];
        if (model == nullptr) {
            return std::optional<CanopyProfile>();  // markers only: no trees, no canopy
        }
        Result<std::shared_ptr<const PlantAsset>> asset = model->asset();
        if (!asset) {
            return asset.error();
        }
        Result<CanopySpecies> one = CanopyProfile::species(asset.value()->lod);
        if (!one) {
            return one.error();
        }
        species.push_back(one.value());
    }
    Result<CanopyProfile> profile = CanopyProfile::make(parameters, species);
    if (!profile) {
        return Error{plants.name() + ": " + profile.error().message};
    }
    return std::optional<CanopyProfile>(profile.value());
}

}  // namespace

Result<const FarFieldCanopy::Layers*> FarFieldCanopy::layersFor(const TerrainLayers& layers) {
    ContentHash hash;
    hash.add(layers.elevation->contentHash());
    for (const PlantsSource* plants : layers.plants) {
        hash.add(plants->contentHash());
        for (const PlantModelSource* model : plants->models()) {
            hash.add(model != nullptr ? model->contentHash() : 0);
        }
    }
    auto found = built_.find(hash.value());
    if (found != built_.end()) {
        return found->second.get();
    }
    auto out = std::make_unique<Layers>();
    std::vector<CanopyStand> stands;
    out->smallestSphereRadius = std::numeric_limits<double>::infinity();
    for (const PlantsSource* plants : layers.plants) {
        Result<std::optional<CanopyProfile>> profile = profileOf(*plants);
        if (!profile) {
            return profile.error();
        }
        if (!profile.value()) {
            continue;
        }
        const CanopyProfile& p = *profile.value();
        stands.push_back({plants->density(), p});
        out->smallestSphereRadius = std::min(out->smallestSphereRadius, p.smallestSphereRadius());
        if (p.height() > out->tallest) {
            out->tallest = p.height();
            out->dominant = out->profiles.size();
        }
        out->profiles.push_back(p);
        out->phenology.push_back(plants->phenology());
    }
    if (!stands.empty()) {
        out->elevation = std::make_unique<CanopyLayerSource>(
            "far-field canopy", CanopyLayer::Elevation, layers.elevation, stands);
        out->cover = std::make_unique<CanopyLayerSource>(
            "far-field canopy cover", CanopyLayer::Cover, layers.elevation, std::move(stands));
        out->normals = std::make_unique<NormalMapSource>("far-field canopy normals",
                                                         out->elevation.get(), 1.0);
    }
    const Layers* result = out.get();
    built_.emplace(hash.value(), std::move(out));
    return result;
}

Result<FarFieldFrame> FarFieldCanopy::update(const TerrainLayers& layers, TileProvider& provider,
                                             const Camera& camera, const LevelRange& terrainLevels,
                                             double heightAboveTerrain, double pixelAngle,
                                             const VegetationSettings& vegetation,
                                             const FarFieldSettings& settings, bool waitForTiles,
                                             const std::optional<PlantDate>& date) {
    frame_ = {};
    settings_ = settings;
    current_ = nullptr;
    if (layers.plants.empty() || vegetation.maximumDistance <= 0.0 || settings.band <= 0.0) {
        return frame_;
    }
    Result<const Layers*> built = layersFor(layers);
    if (!built) {
        return built.error();
    }
    const Layers& canopy = *built.value();
    if (!canopy.elevation) {
        return frame_;
    }
    // Where the trees stop: the instance distance, or nearer where the smallest species
    // drops below minimumPixels (LodSelector culls 2 r < minimumPixels × error).
    const double visible = 2.0 * canopy.smallestSphereRadius * vegetation.quality /
                           (std::max(vegetation.minimumPixels, 1e-3) * pixelAngle);
    frame_.instanceDistance = std::min(vegetation.maximumDistance, visible);
    // Trees are culled by their centre's distance; their fragments reach a crown nearer.
    frame_.fadeEnd = std::max(frame_.instanceDistance - 2.0 * canopy.tallest, 1.0);
    frame_.fadeStart = std::max(frame_.fadeEnd - settings.band, 0.5 * frame_.fadeEnd);
    // Ring level i spans pi R 2^-(i+1) .. pi R 2^-i along the ground from the nadir; levels
    // whose every point is nearer than the fade start (relief allowance 2 km) are skipped.
    constexpr double kRadius = 6371000.0;
    const double vertical = heightAboveTerrain + 2000.0;
    const double groundStart =
        frame_.fadeStart > vertical
            ? std::sqrt(frame_.fadeStart * frame_.fadeStart - vertical * vertical)
            : 0.0;
    LevelRange levels = terrainLevels;
    levels.finest = levels.coarsest;
    for (int level = terrainLevels.coarsest; level <= terrainLevels.finest; ++level) {
        if (std::numbers::pi * kRadius * std::ldexp(1.0, -level) < groundStart) {
            break;
        }
        levels.finest = level;
    }
    TerrainLayers canopyLayers;
    canopyLayers.elevation = canopy.elevation.get();
    canopyLayers.color = canopy.cover.get();
    canopyLayers.normals = canopy.normals.get();
    Result<LevelRange> ready =
        rings_->update(canopyLayers, provider, camera, levels, std::nullopt, waitForTiles);
    if (!ready) {
        return ready.error();
    }
    frame_.levels = ready.value();
    frame_.waiting = rings_->statistics().waitingLevel >= 0;
    frame_.drawn = frame_.levels.finest >= frame_.levels.coarsest;
    current_ = &canopy;
    updateCrowns(canopy, date, camera.geodetic.latitude);
    return frame_;
}

void FarFieldCanopy::updateCrowns(const Layers& canopy, const std::optional<PlantDate>& date,
                                  double latitude) {
    // The leaf states as leafStates() gives them to the drawn trees: the plants source's
    // table per species at the render date and the camera's latitude; full leaf without
    // a date.
    std::vector<LeafState> states = leafStatesOf(canopy.phenology[canopy.dominant], date, latitude);
    const auto same = [](const LeafState& a, const LeafState& b) {
        return a.leafFraction == b.leafFraction && a.autumn == b.autumn &&
               a.autumnColour == b.autumnColour;
    };
    if (crownsOf_ == &canopy && states.size() == crownStates_.size() &&
        std::equal(states.begin(), states.end(), crownStates_.begin(), same)) {
        return;
    }
    crowns_ = canopy.profiles[canopy.dominant].crowns(states);
    crownStates_ = std::move(states);
    crownsOf_ = &canopy;
}

FarFieldFade FarFieldCanopy::fade() const {
    if (!frame_.drawn) {
        return {};
    }
    return {frame_.fadeStart, frame_.fadeEnd};
}

void FarFieldCanopy::draw(const Camera& camera, const glm::dmat4& projection, double near,
                          int width, int height, bool ocean) {
    if (!frame_.drawn || current_ == nullptr) {
        return;
    }
    const CanopyProfile& profile = current_->profiles[current_->dominant];
    ShaderProgram& program = rings_->gbufferProgram();
    fade().apply(program, projection, near, width, height);
    program.setFloat("uMinimumCover", float(settings_.minimumCover));
    program.setFloat("uAmbientOcclusion", float(profile.ambientOcclusion()));
    // The stored albedo is the full-leaf leaf-area mean; the crowns show their own colour
    // on the date (autumn, and the opaque-area weighting of what a line of sight meets).
    glm::dvec3 tone(1.0);
    for (int c = 0; c < 3; ++c) {
        if (profile.albedo()[c] > 1e-6) {
            tone[c] = crowns_.albedo[c] / profile.albedo()[c];
        }
    }
    program.setVec3("uTone", glm::vec3(tone));
    program.setVec4("uCrown",
                    glm::vec4(float(profile.crownWidth()), float(crowns_.topOpaqueArea),
                              float(crowns_.sideOpaqueArea), float(CanopyProfile::kSightDepth)));
    program.setFloat("uCrownOpacity", float(crowns_.sideOpaqueFraction));
    // Nearer than the fade start every canopy fragment would be discarded by the
    // hand-over (fade 0); clipping the rings there spares the rasteriser and the fragment
    // shader the fill disk overhead (at canopy height, so it passes the depth test over
    // the sky and the near ground) and the near parts of the finest rings. The clip is
    // conservative (terrain.vert), so the image is the same.
    program.setFloat("uClipInside", float(frame_.fadeStart));
    glEnable(GL_CLIP_DISTANCE0);
    rings_->draw(camera, projection, frame_.levels, ocean);
    glDisable(GL_CLIP_DISTANCE0);
}

}  // namespace sylva::render
