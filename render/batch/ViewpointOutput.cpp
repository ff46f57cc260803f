#include "sylva/render/batch/ViewpointOutput.h"

#include "sylva/core/analysis/ProposalReach.h"
#include "sylva/core/base/AtomicFile.h"
#include "sylva/core/model/BlockReader.h"
#include "sylva/core/scene/ViewpointSheet.h"

namespace sylva::render {
namespace {

std::filesystem::path beside(const std::filesystem::path& output, const char* suffix) {
    std::filesystem::path path = output;
    path.replace_extension();
    return path.string() + suffix;
}

void addSource(const Source* source, std::vector<std::string>& names) {
    if (source != nullptr) {
        names.push_back(source->name() + " (" + source->kind() + ")");
    }
}

}  // namespace

Result<bool> ViewpointOutput::wantsSheet(const BatchPlan& plan, const RenderJob& job,
                                         const Camera& camera) {
    const Block* views = plan.model().findViews(job.view);
    if (views == nullptr || job.camera.empty()) {
        return false;
    }
    BlockReader reader(*views, SchemaRegistry::builtin().find("views"));
    if (!reader.boolean("sheet", false)) {
        return false;
    }
    if (!camera.print.valid()) {
        return Error{reader.where("sheet") +
                     "a viewpoint sheet needs the print format of camera '" + job.camera +
                     "': set its output_size and dpi"};
    }
    return true;
}

void ViewpointOutput::addProposal(const Camera& camera,
                                  const std::vector<const MeshSource*>& meshes, TileProvider& tiles,
                                  ViewpointInputs& inputs) {
    if (meshes.empty()) {
        return;
    }
    Result<ProposalParts> parts = ProposalReach::partsOf(meshes, tiles);
    const std::optional<ProposalReach> reach =
        parts ? ProposalReach::measure(camera.geodetic, parts.value()) : std::nullopt;
    if (reach) {
        inputs.proposalDistance = reach->nearestDistance;
        inputs.proposalExtent = reach->horizontalExtent;
        inputs.proposalLeftBearing = reach->leftBearing;
        inputs.proposalRightBearing = reach->rightBearing;
    }
}

std::optional<ViewpointRecord> ViewpointOutput::record(const BatchPlan& plan, const RenderJob& job,
                                                       const Camera& camera, int width, int height,
                                                       TileProvider& tiles) {
    if (job.camera.empty()) {
        return std::nullopt;
    }
    ViewpointInputs inputs;
    inputs.id = job.camera;
    inputs.scenario = job.scenario;
    inputs.width = width;
    inputs.height = height;
    inputs.time = job.time;
    inputs.unixSeconds = job.unixSeconds;
    BlockReader project(plan.model().project, SchemaRegistry::builtin().find("project"));
    if (const Value* crs = project.value("crs"); crs && crs->get<std::string>()) {
        inputs.crs = *crs->get<std::string>();
    }
    const TerrainLayers& layers = plan.layersOf(job);
    addSource(layers.elevation, inputs.dataSources);
    addSource(layers.color, inputs.dataSources);
    for (const Source* plants : layers.plants) {
        addSource(plants, inputs.dataSources);
    }
    addProposal(camera, layers.meshes, tiles, inputs);
    inputs.version = SYLVA_VERSION;
    const ImageMetadata metadata = plan.metadataFor(job);
    if (const std::string* hash = metadata.find("sylva:project_hash")) {
        inputs.projectHash = *hash;
    }
    return ViewpointRecord::describe(camera, inputs);
}

Status ViewpointOutput::writeSheet(const BatchPlan& plan, const RenderJob& job,
                                   const Camera& camera, const Image& image,
                                   const ViewpointRecord& record) {
    SheetLayout layout;
    const Block* views = plan.model().findViews(job.view);
    SYLVA_CHECK(views != nullptr);
    BlockReader reader(*views, SchemaRegistry::builtin().find("views"));
    if (const Value* size = reader.value("sheet_size")) {
        const ValueList* list = size->get<ValueList>();
        if (list == nullptr || list->size() != 2) {
            return Error{reader.where("sheet_size") + "sheet_size must be [width, height]"};
        }
        layout.page =
            glm::dvec2((*list)[0].get<Quantity>()->value, (*list)[1].get<Quantity>()->value);
    }
    RgbaImage picture;
    picture.width = image.width;
    picture.height = image.height;
    picture.pixels = image.pixels;
    if (Status sheet = ViewpointSheet::write(picture, camera.print, record, layout,
                                             beside(job.output, ".sheet.pdf"),
                                             beside(job.output, ".sheet.png"));
        !sheet) {
        return Error{reader.where("sheet") + sheet.error().message};
    }
    const std::filesystem::path json = beside(job.output, ".json");
    if (Status written = writeFileAtomically(json, record.json()); !written) {
        std::error_code ignored;  // the sheet without its record is half a deliverable
        std::filesystem::remove(beside(job.output, ".sheet.pdf"), ignored);
        std::filesystem::remove(beside(job.output, ".sheet.png"), ignored);
        return Error{json.string() + ": " + written.error().message};
    }
    return {};
}

}  // namespace sylva::render
