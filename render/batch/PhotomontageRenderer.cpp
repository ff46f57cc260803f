#include "sylva/render/batch/PhotomontageRenderer.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>

#include "sylva/core/analysis/ProposalReach.h"
#include "sylva/core/base/Hash.h"
#include "sylva/core/image/Photomontage.h"
#include "sylva/core/model/BlockReader.h"
#include "sylva/core/scene/LocationMap.h"
#include "sylva/core/scene/ViewAnnotation.h"
#include "sylva/render/batch/JobView.h"
#include "sylva/render/batch/ViewpointOutput.h"

namespace sylva::render {
namespace {

RgbaImage toRgba(Image&& image) {
    RgbaImage out;
    out.width = image.width;
    out.height = image.height;
    out.pixels = std::move(image.pixels);
    return out;
}

struct DepthRender {
    RgbaImage image;
    std::vector<float> depth;
};

Result<DepthRender> renderWithDepth(SceneRenderer& scene, const TerrainLayers& layers,
                                    TileProvider& tiles, const Camera& camera,
                                    const RenderSettings& settings) {
    Result<Image> image = scene.render(layers, tiles, camera, settings);
    if (!image) {
        return image.error();
    }
    return DepthRender{toRgba(std::move(image.value())), scene.depth()};
}

// The camera of the photograph: its block (ground height from the baseline's terrain),
// fitted to the photograph and matched to the control points.
Status solveCamera(const ProjectModel& model, const PhotoViewpoint& photo, const Photo& picture,
                   const JobView& view, PhotomontageResult& result) {
    const Block* block = model.findCamera(photo.camera);
    SYLVA_CHECK(block != nullptr);  // the DSL checked the reference
    Result<Camera> fitted = photo.fitCamera(view.camera, *block, picture);
    if (!fitted) {
        return fitted.error();
    }
    Result<std::optional<CameraMatch>> matched = photo.match(fitted.value(), picture);
    if (!matched) {
        return matched.error();
    }
    result.match = std::move(matched.value());
    result.camera = result.match ? result.match->camera : fitted.value();
    result.camera = result.camera.fitted(picture.image.width, picture.image.height);
    return Status::success();
}

void makeImages(const PhotoViewpoint& photo, const Photo& picture, DepthRender& baseline,
                DepthRender& proposed, PhotomontageResult& result) {
    const int width = picture.image.width, height = picture.image.height;
    WirelineMasks masks = WirelineMasks::fromDepths(baseline.depth, proposed.depth, width, height);
    result.montage = Photomontage::composite(picture.image, proposed.image, masks.proposal);
    result.wireline = picture.image;
    result.model = std::move(baseline.image);
    for (RgbaImage* image : {&result.wireline, &result.model}) {
        Photomontage::drawWireline(*image, masks, photo.wireline);
    }
    result.proposal = std::move(masks.proposal);
    result.silhouette = std::move(masks.silhouette);
    result.skyline = std::move(masks.skyline);
    result.proposed = std::move(proposed.image);
}

// The proposal for a Type 1 annotated photograph, from its geometry (visible or not):
// ProposalReach's extent seen from `camera`, each placed model's origin labelled with its
// feature id. nullopt without a proposal.
Result<std::optional<ViewProposal>> annotatedProposal(const Camera& camera,
                                                      const std::vector<const MeshSource*>& meshes,
                                                      TileProvider& tiles) {
    Result<ProposalParts> parts = ProposalReach::partsOf(meshes, tiles);
    if (!parts) {
        return parts.error();
    }
    const std::optional<ProposalReach> reach = ProposalReach::measure(camera.geodetic, *parts);
    if (!reach) {
        return std::optional<ViewProposal>();
    }
    ViewProposal proposal;
    proposal.leftBearing = reach->leftBearing;
    proposal.rightBearing = reach->rightBearing;
    proposal.horizontalExtent = reach->horizontalExtent;
    proposal.points = parts->points;
    for (std::size_t i = 0; i < parts->points.size(); ++i) {
        const std::int64_t id = i < parts->pointIds.size() ? parts->pointIds[i] : -1;
        proposal.labels.push_back(id >= 0 ? std::to_string(id) : std::to_string(i + 1));
    }
    return std::optional<ViewProposal>(std::move(proposal));
}

// The location plan: the proposed layers from above the viewpoint, with its wedge.
Status renderLocationMap(SceneRenderer& scene, const TerrainLayers& layers, TileProvider& tiles,
                         RenderSettings settings, PhotomontageResult& result) {
    const Camera& viewpoint = result.camera;
    const double ground =
        std::isfinite(viewpoint.groundHeight) ? viewpoint.groundHeight : viewpoint.geodetic.height;
    result.mapRadius =
        result.extent ? std::max(500.0, 1.25 * result.extent->farthestDistance) : 2000.0;
    const Camera overhead = LocationMap::overhead(viewpoint, ground, result.mapRadius);
    settings.width = settings.height = PhotomontageRenderer::kMapPixels;
    settings.ev100.reset();  // metered for the map's own light
    Result<Image> map = scene.render(layers, tiles, overhead, settings);
    if (!map) {
        return Error{"the location map: " + map.error().message};
    }
    result.locationMap = toRgba(std::move(map.value()));
    LocationMap::draw(result.locationMap, overhead, viewpoint,
                      2.0 * std::atan(std::tan(viewpoint.verticalFov / 2.0) * result.montage.width /
                                      result.montage.height),
                      result.mapRadius);
    return Status::success();
}

}  // namespace

Result<PhotomontageResult> PhotomontageRenderer::render(BatchRenderer& batch,
                                                        const PhotoViewpoint& photo,
                                                        const Photo& picture) {
    const int width = picture.image.width, height = picture.image.height;
    Result<RenderSetup> setup = batch.setup();
    if (!setup) {
        return setup.error();
    }
    Result<TerrainLayers> baselineLayers = batch.project().terrainLayers(photo.baseline);
    Result<TerrainLayers> proposedLayers = batch.project().terrainLayers(photo.scenario);
    if (!baselineLayers || !proposedLayers) {
        return (baselineLayers ? proposedLayers : baselineLayers).error();
    }
    Scheduler& tiles = batch.scheduler(setup.value());
    const ProjectModel& model = batch.project().defaultModel();
    RenderJob job;
    job.camera = photo.camera;
    job.scenario = photo.baseline;
    job.time = photo.time;
    job.unixSeconds = photo.unixSeconds;
    Result<JobView> view =
        JobView::forJob(model, job, baselineLayers.value(), tiles, setup.value(), nullptr);
    if (!view) {
        return view.error();
    }
    PhotomontageResult result;
    if (Status solved = solveCamera(model, photo, picture, view.value(), result); !solved) {
        return solved.error();
    }
    Result<SceneRenderer*> scene = batch.sceneRenderer(setup.value());
    if (!scene) {
        return scene.error();
    }
    RenderSettings settings = view.value().settingsFor(setup.value(), job);
    settings.width = width;
    settings.height = height;
    settings.samples = 1;
    settings.linearOutput = false;
    Result<DepthRender> baseline =
        renderWithDepth(*scene.value(), baselineLayers.value(), tiles, result.camera, settings);
    if (!baseline) {
        return Error{view.value().what + ": " + baseline.error().message};
    }
    // The same exposure for the proposal as for the baseline (one viewpoint, one sun).
    settings.ev100 = scene.value()->statistics().ev100;
    result.ev100 = *settings.ev100;
    result.sun = settings.sunDirection;
    Result<DepthRender> proposed =
        renderWithDepth(*scene.value(), proposedLayers.value(), tiles, result.camera, settings);
    if (!proposed) {
        return Error{view.value().what + ": " + proposed.error().message};
    }
    const std::vector<float> proposedDepth = proposed.value().depth;
    makeImages(photo, picture, baseline.value(), proposed.value(), result);
    result.extent = ProposalExtent::measure(result.proposal, proposedDepth, scene.value()->near(),
                                            result.camera, width, height);
    if (photo.annotated) {
        Result<std::optional<ViewProposal>> proposal =
            annotatedProposal(result.camera, proposedLayers->meshes, tiles);
        if (!proposal) {
            return Error{view.value().what + ": " + proposal.error().message};
        }
        result.annotated = ViewAnnotation::draw(
            picture.image, ViewAnnotation::plan(result.camera, width, height, photo.camera,
                                                proposal->has_value() ? &**proposal : nullptr));
    }
    if (photo.sheet) {
        if (Status map =
                renderLocationMap(*scene.value(), proposedLayers.value(), tiles, settings, result);
            !map) {
            return Error{view.value().what + ": " + map.error().message};
        }
    }
    return result;
}

ViewpointRecord PhotomontageRenderer::record(BatchRenderer& batch, const PhotoViewpoint& photo,
                                             const PhotomontageResult& result) {
    const ProjectModel& model = batch.project().defaultModel();
    ViewpointInputs inputs;
    inputs.id = photo.camera;
    inputs.name = "photo " + photo.name;
    inputs.scenario = photo.scenario;
    inputs.width = result.montage.width;
    inputs.height = result.montage.height;
    inputs.time = photo.time;
    inputs.unixSeconds = photo.unixSeconds;
    BlockReader project(model.project, SchemaRegistry::builtin().find("project"));
    if (const Value* crs = project.value("crs"); crs && crs->get<std::string>()) {
        inputs.crs = *crs->get<std::string>();
    }
    if (Result<TerrainLayers> layers = batch.project().terrainLayers(photo.scenario)) {
        for (const Source* source : {layers->elevation, layers->color}) {
            if (source != nullptr) {
                inputs.dataSources.push_back(source->name() + " (" + source->kind() + ")");
            }
        }
        for (const Source* source : layers->meshes) {
            inputs.dataSources.push_back(source->name() + " (" + source->kind() + ")");
        }
    }
    inputs.version = SYLVA_VERSION;
    ContentHash hash;
    hash.add(model.render.contentHash).add(model.project.contentHash);
    for (const std::vector<Block>* blocks :
         {&model.sources, &model.scenarios, &model.cameras, &model.photos}) {
        for (const Block& block : *blocks) {
            hash.add(block.name).add(block.contentHash);
        }
    }
    char text[20];
    std::snprintf(text, sizeof text, "%016" PRIx64, hash.value());
    inputs.projectHash = text;
    // The proposal's distance and extent from its geometry, as in every viewpoint record
    // (the visible part's, measured on the render, is in the montage's JSON summary).
    if (Result<RenderSetup> setup = batch.setup()) {
        if (Result<TerrainLayers> layers = batch.project().terrainLayers(photo.scenario)) {
            ViewpointOutput::addProposal(result.camera, layers->meshes,
                                         batch.scheduler(setup.value()), inputs);
        }
    }
    if (result.match) {
        inputs.matchRms = result.match->rms;
    }
    return ViewpointRecord::describe(result.camera, inputs);
}

}  // namespace sylva::render
