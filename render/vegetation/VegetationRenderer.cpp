#include "sylva/render/vegetation/VegetationRenderer.h"

#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <numbers>

#include "DisplacedBillboardRenderer.h"
#include "OcclusionCuller.h"
#include "PointCloudRenderer.h"
#include "sylva/core/base/Check.h"
#include "sylva/core/base/Hash.h"
#include "sylva/core/plantlod/ShadowThresholds.h"

namespace sylva::render {

namespace {

// std430 mirrors of the shader structs (shaders/vegetation/ellipsoid.vert, line.vert).
struct GpuEllipsoid {
    glm::vec4 centerNoise;
    glm::vec4 axis0;
    glm::vec4 axis1;
    glm::vec4 axis2;
    glm::vec4 color;
};
struct GpuLine {
    glm::vec4 startRadius;
    glm::vec4 endRadius;
    glm::vec4 color;
    glm::vec4 errors;
};
static_assert(sizeof(GpuEllipsoid) == 80 && sizeof(GpuLine) == 64);
static_assert(sizeof(DrawInstance) == 80);

// Billboard levels are chosen when their distance bound covers this many pixels.
constexpr double kBillboardPixels = 1.0;

// Binds the five DrawInstance attributes at `firstLocation` to binding point `binding`.
void setInstanceAttributes(GLuint vertexArray, GLuint firstLocation, GLuint binding) {
    for (GLuint i = 0; i < 5; ++i) {
        glEnableVertexArrayAttrib(vertexArray, firstLocation + i);
        glVertexArrayAttribFormat(vertexArray, firstLocation + i, 4, GL_FLOAT, GL_FALSE,
                                  GLuint(i * sizeof(glm::vec4)));
        glVertexArrayAttribBinding(vertexArray, firstLocation + i, binding);
    }
    glVertexArrayBindingDivisor(vertexArray, binding, 1);
}

}  // namespace

// One mesh of one material, instanced (vertex binding 0: MeshVertex, binding 1: the
// DrawInstance buffer).
struct VegetationMesh {
    GlVertexArray vertexArray;
    GlBuffer vertexBuffer, indexBuffer;
    GlTexture ownedTexture;  // meshes of one material share the first one's texture
    GLuint texture = 0;      // what draws bind: ownedTexture, another mesh's, or 0
    GLsizei indexCount = 0;
    glm::vec4 baseColor{1.0f};
    float alphaCutoff = -1.0f;
    bool leaves = false;  // leaf triangles (thinned and recoloured by the season)
};

struct VegetationRenderer::Species {
    std::shared_ptr<const PlantAsset> asset;
    std::uint32_t firstEllipsoid = 0, firstLine = 0;
    std::vector<std::unique_ptr<VegetationMesh>> mesh;
    std::vector<std::vector<std::unique_ptr<VegetationMesh>>> billboardLevels;
    float leafLuminance = 0.1f;   // area-weighted mean luminance of the leaf ellipsoids
    double transitionBand = 0.0;  // addSpecies' band (the impostor captures draw with it)
};

namespace {

struct MeshVertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;
};

// One VegetationMesh per PlantMesh with triangles; textures as sRGB with mipmaps.
// Area-weighted mean luminance (Rec. 709, linear) of the finest ellipsoids, which stand
// for the leaves: the reference the autumn colour is scaled by (seasonalLeafColour).
float meanLeafLuminance(const PlantLod& lod) {
    double sum = 0.0, weight = 0.0;
    for (const LodEllipsoid& e : lod.ellipsoids) {
        if (e.level == 0) {
            sum += double(e.weight) * glm::dot(e.color, glm::vec3(0.2126f, 0.7152f, 0.0722f));
            weight += e.weight;
        }
    }
    return weight > 0.0 ? float(sum / weight) : 0.1f;
}

std::vector<std::unique_ptr<VegetationMesh>> uploadModel(const PlantModel& model,
                                                         GLuint instanceBuffer) {
    std::vector<std::unique_ptr<VegetationMesh>> meshes;
    std::vector<GLuint> textures(model.materials.size(), 0);
    for (const PlantMesh& source : model.meshes) {
        if (source.indices.empty()) {
            continue;
        }
        auto mesh = std::make_unique<VegetationMesh>();
        mesh->leaves = source.part == PlantPart::Leaf;
        std::vector<MeshVertex> vertices(source.positions.size());
        for (std::size_t i = 0; i < vertices.size(); ++i) {
            vertices[i].position = source.positions[i];
            vertices[i].normal = i < source.normals.size() ? source.normals[i] : glm::vec3(0, 0, 1);
            vertices[i].uv = i < source.uvs.size() ? source.uvs[i] : glm::vec2(0.0f);
        }
        mesh->vertexArray = createGlVertexArray();
        mesh->vertexBuffer = createGlBuffer();
        mesh->indexBuffer = createGlBuffer();
        glNamedBufferStorage(mesh->vertexBuffer.get(),
                             GLsizeiptr(vertices.size() * sizeof(MeshVertex)), vertices.data(), 0);
        glNamedBufferStorage(mesh->indexBuffer.get(),
                             GLsizeiptr(source.indices.size() * sizeof(std::uint32_t)),
                             source.indices.data(), 0);
        mesh->indexCount = GLsizei(source.indices.size());
        const GLuint va = mesh->vertexArray.get();
        glVertexArrayVertexBuffer(va, 0, mesh->vertexBuffer.get(), 0, sizeof(MeshVertex));
        glVertexArrayElementBuffer(va, mesh->indexBuffer.get());
        const GLuint offsets[3] = {offsetof(MeshVertex, position), offsetof(MeshVertex, normal),
                                   offsetof(MeshVertex, uv)};
        const GLint sizes[3] = {3, 3, 2};
        for (GLuint a = 0; a < 3; ++a) {
            glEnableVertexArrayAttrib(va, a);
            glVertexArrayAttribFormat(va, a, sizes[a], GL_FLOAT, GL_FALSE, offsets[a]);
            glVertexArrayAttribBinding(va, a, 0);
        }
        glVertexArrayVertexBuffer(va, 1, instanceBuffer, 0, sizeof(DrawInstance));
        setInstanceAttributes(va, 3, 1);
        if (source.material >= 0 && std::size_t(source.material) < model.materials.size()) {
            const PlantMaterial& material = model.materials[std::size_t(source.material)];
            mesh->baseColor = material.baseColor;
            mesh->alphaCutoff = material.alphaMasked ? material.alphaCutoff : -1.0f;
            const PlantTexture& texture = material.baseColorTexture;
            if (texture.width > 0 && texture.height > 0) {
                GLuint& id = textures[std::size_t(source.material)];
                if (id == 0) {
                    const int levels =
                        1 + int(std::floor(std::log2(std::max(texture.width, texture.height))));
                    mesh->ownedTexture = createGlTexture(GL_TEXTURE_2D);
                    id = mesh->ownedTexture.get();
                    glTextureStorage2D(id, levels, GL_SRGB8_ALPHA8, texture.width, texture.height);
                    glTextureSubImage2D(id, 0, 0, 0, texture.width, texture.height, GL_RGBA,
                                        GL_UNSIGNED_BYTE, texture.rgba.data());
                    glGenerateTextureMipmap(id);
                    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
                    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
                    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
                    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
                }
                mesh->texture = id;
            }
        } else {
            mesh->baseColor = glm::vec4(0.35f, 0.3f, 0.25f, 1.0f);
        }
        meshes.push_back(std::move(mesh));
    }
    return meshes;
}

// The billboard-cloud levels an asset carries (finest first; empty when not built).
const std::vector<BillboardLevel>& billboardLevels(const PlantAsset& asset) {
    return asset.lod.billboards.levels;
}

}  // namespace

Result<std::unique_ptr<VegetationRenderer>> VegetationRenderer::create(
    const ShaderLibrary& library) {
    std::unique_ptr<VegetationRenderer> renderer(new VegetationRenderer());
    struct Program {
        ShaderProgram* target;
        const char* vertex;
        const char* fragment;
    };
    for (const Program& p :
         {Program{&renderer->ellipsoidProgram_, "vegetation/ellipsoid.vert",
                  "vegetation/ellipsoid.frag"},
          Program{&renderer->lineProgram_, "vegetation/line.vert", "vegetation/line.frag"},
          Program{&renderer->meshProgram_, "vegetation/mesh.vert", "vegetation/mesh.frag"},
          Program{&renderer->ellipsoidShadowProgram_, "shadows/ellipsoid_shadow.vert",
                  "shadows/ellipsoid_shadow.frag"},
          Program{&renderer->lineShadowProgram_, "shadows/line_shadow.vert",
                  "shadows/line_shadow.frag"}}) {
        Result<ShaderProgram> program = ShaderProgram::create(
            library, {{GL_VERTEX_SHADER, p.vertex}, {GL_FRAGMENT_SHADER, p.fragment}});
        if (!program) {
            return program.error();
        }
        *p.target = std::move(program.value());
    }
    // Ellipsoid sprites up to the driver's largest point size (llvmpipe: 255 pixels);
    // larger ones are drawn as quads.
    GLfloat pointSizes[2] = {1.0f, 1.0f};
    glGetFloatv(GL_POINT_SIZE_RANGE, pointSizes);
    renderer->maximumPointSize_ = std::max(1.0f, pointSizes[1]);
    renderer->occlusion_ = std::make_unique<OcclusionCuller>();
    Result<std::unique_ptr<PointCloudRenderer>> points = PointCloudRenderer::create(library);
    if (!points) {
        return points.error();
    }
    renderer->pointClouds_ = std::move(points.value());
    Result<std::unique_ptr<DisplacedBillboardRenderer>> displaced =
        DisplacedBillboardRenderer::create(library);
    if (!displaced) {
        return displaced.error();
    }
    renderer->displacedBillboards_ = std::move(displaced.value());
    renderer->instanceBuffer_ = createGlBuffer();
    renderer->primitiveArray_ = createGlVertexArray();
    Result<std::unique_ptr<ImpostorRenderer>> impostors = ImpostorRenderer::create(library);
    if (!impostors) {
        return impostors.error();
    }
    renderer->impostors_ = std::move(impostors.value());
    setInstanceAttributes(renderer->primitiveArray_.get(), 0, 0);
    return renderer;
}

// Out of line: Species and VegetationMesh are complete only here.
VegetationRenderer::~VegetationRenderer() = default;

const std::shared_ptr<const PlantAsset>& VegetationRenderer::asset(std::uint32_t species) const {
    SYLVA_CHECK(species < species_.size());
    return species_[species]->asset;
}

Result<std::uint32_t> VegetationRenderer::addSpecies(std::shared_ptr<const PlantAsset> asset,
                                                     double transitionBand) {
    SYLVA_CHECK(asset != nullptr);
    if (Status fits =
            LodSelector::checkSpecies(species_.size(), billboardLevels(*asset).size(), asset->name);
        !fits) {
        return fits.error();
    }
    auto species = std::make_unique<Species>();
    species->asset = asset;
    species->firstEllipsoid = ellipsoidCount_;
    species->firstLine = lineCount_;
    const PlantLod& lod = asset->lod;

    // Append the primitives to the shared storage buffers (re-created with the new size;
    // species are added once, before drawing).
    std::vector<GpuEllipsoid> ellipsoids(ellipsoidCount_ + lod.ellipsoids.size());
    std::vector<GpuLine> lines(lineCount_ + lod.lines.size());
    if (ellipsoidCount_ > 0) {
        glGetNamedBufferSubData(ellipsoidBuffer_.get(), 0,
                                GLsizeiptr(ellipsoidCount_ * sizeof(GpuEllipsoid)),
                                ellipsoids.data());
    }
    if (lineCount_ > 0) {
        glGetNamedBufferSubData(lineBuffer_.get(), 0, GLsizeiptr(lineCount_ * sizeof(GpuLine)),
                                lines.data());
    }
    for (std::size_t i = 0; i < lod.ellipsoids.size(); ++i) {
        const LodEllipsoid& e = lod.ellipsoids[i];
        GpuEllipsoid& g = ellipsoids[ellipsoidCount_ + i];
        g.centerNoise = glm::vec4(e.center, e.noiseLevel);
        g.axis0 = glm::vec4(e.axes[0] * e.radii.x, e.alphaThreshold);
        g.axis1 = glm::vec4(e.axes[1] * e.radii.y, e.ambientOcclusion);
        g.axis2 = glm::vec4(e.axes[2] * e.radii.z, e.errorMinimum);
        g.color = glm::vec4(e.color, e.errorMaximum);
    }
    for (std::size_t i = 0; i < lod.lines.size(); ++i) {
        const LodLine& l = lod.lines[i];
        GpuLine& g = lines[lineCount_ + i];
        g.startRadius = glm::vec4(l.start, l.startRadius);
        g.endRadius = glm::vec4(l.end, l.endRadius);
        g.color = glm::vec4(l.color, l.ambientOcclusion);
        g.errors = glm::vec4(l.errorMinimum, l.errorMaximum, 0.0f, 0.0f);
    }
    ellipsoidCount_ = std::uint32_t(ellipsoids.size());
    lineCount_ = std::uint32_t(lines.size());
    // Immutable storage cannot grow: new buffers replace (and delete) the old ones.
    ellipsoidBuffer_ = createGlBuffer();
    lineBuffer_ = createGlBuffer();
    // Empty buffers are not bindable as storage: keep at least one element.
    if (ellipsoids.empty()) {
        ellipsoids.resize(1);
    }
    if (lines.empty()) {
        lines.resize(1);
    }
    glNamedBufferStorage(ellipsoidBuffer_.get(),
                         GLsizeiptr(ellipsoids.size() * sizeof(GpuEllipsoid)), ellipsoids.data(),
                         0);
    glNamedBufferStorage(lineBuffer_.get(), GLsizeiptr(lines.size() * sizeof(GpuLine)),
                         lines.data(), 0);

    appendShadowThresholds(*asset);
    species->mesh = uploadModel(asset->model, instanceBuffer_.get());
    species->leafLuminance = meanLeafLuminance(lod);
    SpeciesLod description = LodSelector::describe(*asset, transitionBand);
    for (const BillboardLevel& level : billboardLevels(*asset)) {
        species->billboardLevels.push_back(uploadModel(
            BillboardCloudBuilder::levelModel(level, asset->name), instanceBuffer_.get()));
        for (const std::unique_ptr<VegetationMesh>& mesh : species->billboardLevels.back()) {
            mesh->leaves = false;  // leaves and branches share the texels: not thinned
        }
        description.billboardError.push_back(
            description.billboardError.empty() ? 0.0f : float(level.epsilon / kBillboardPixels));
    }
    species->transitionBand = transitionBand;
    lods_.push_back(description);
    assets_.push_back(asset);
    species_.push_back(std::move(species));
    return std::uint32_t(species_.size() - 1);
}

// The impostors method's captures (ImpostorRenderer::addSpecies), made on its first use so
// the other methods do not pay for 17 views × 3 resolutions per species; drawn through the
// mesh path, in species order.
Status VegetationRenderer::captureImpostors() {
    while (impostors_->speciesCount() < species_.size()) {
        const std::uint32_t index = std::uint32_t(impostors_->speciesCount());
        Species* species = species_[index].get();
        const double transitionBand = species->transitionBand;
        const auto drawModel = [&](const DrawInstance& instance, const glm::mat4& projection) {
            if (instanceCapacity_ < sizeof(DrawInstance)) {
                instanceCapacity_ = sizeof(DrawInstance);
                glNamedBufferData(instanceBuffer_.get(), GLsizeiptr(instanceCapacity_), nullptr,
                                  GL_STREAM_DRAW);
            }
            glNamedBufferSubData(instanceBuffer_.get(), 0, sizeof(DrawInstance), &instance);
            meshProgram_.use();
            meshProgram_.setMat4("uProjection", projection);
            meshProgram_.setFloat("uBand", float(transitionBand));
            meshProgram_.setInt("uTexture", 0);
            DrawRun run;
            run.kind = DrawRun::Kind::Mesh;
            run.species = index;
            run.instanceCount = 1;
            drawMeshes(species->mesh, run, glm::vec2(0.0f, std::numeric_limits<float>::infinity()));
            glBindVertexArray(0);
        };
        if (Status captured = impostors_->addSpecies(index, lods_[index], drawModel); !captured)
            return captured;
    }
    return Status::success();
}

void VegetationRenderer::draw(const std::vector<const InstanceBatch*>& batches,
                              const Camera& camera, const glm::dmat4& projection, double near,
                              int pixelsWide, int pixelsHigh, const VegetationSettings& settings) {
    statistics_ = {};
    shadowBatches_ = batches;
    shadowSettings_ = settings;
    if (species_.empty()) {
        return;
    }
    // Rings nearest first; with culling, each is culled against the depth drawn so far.
    // Impostors are drawn in one pass (their group impostors span the distances, and
    // their statistics are per pass).
    const std::vector<OcclusionRing> rings =
        settings.method == VegetationMethod::Impostors
            ? std::vector<OcclusionRing>(1)
            : OcclusionCuller::rings(settings, batches, camera.position);
    for (OcclusionRing ring : rings) {
        if (settings.occlusionCulling) {
            const auto start = std::chrono::steady_clock::now();
            ring.pyramid = &occlusion_->update(pixelsWide, pixelsHigh, projection, near);
            statistics_.occlusionSeconds +=
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        }
        drawRing(batches, camera, projection, near, pixelsWide, pixelsHigh, settings, ring);
    }
}

void VegetationRenderer::drawRing(const std::vector<const InstanceBatch*>& batches,
                                  const Camera& camera, const glm::dmat4& projection, double near,
                                  int pixelsWide, int pixelsHigh,
                                  const VegetationSettings& settings, const OcclusionRing& ring) {
    LodSelectionSettings selection;
    selection.pixelAngle = 2.0 * std::tan(camera.verticalFov / 2) / std::max(pixelsHigh, 1);
    selection.quality = settings.quality;
    selection.minimumPixels = settings.minimumPixels;
    selection.maximumDistance = settings.maximumDistance;
    selection.transitionBand = settings.transitionBand;
    selection.closeUpMesh = settings.closeUpMesh;
    selection.method = settings.method;
    selection.near = near;
    selection.minimumDistance = ring.minimumDistance;
    if (ring.maximumDistance > 0.0) {
        selection.maximumDistance = selection.maximumDistance > 0.0
                                        ? std::min(selection.maximumDistance, ring.maximumDistance)
                                        : ring.maximumDistance;
    }
    selection.occlusion = ring.pyramid;
    // The symmetric frustum that holds the (possibly lens-shifted) image window.
    const double halfWidth =
        (1.0 + std::abs(projection[2][0])) / projection[0][0];  // tangent, right or left
    const double halfHeight = (1.0 + std::abs(projection[2][1])) / projection[1][1];
    LodSelector::setFrustum(selection, 2.0 * std::atan(halfHeight), halfWidth / halfHeight);
    if (settings.method == VegetationMethod::Impostors) {
        drawImpostors(batches, camera, projection, selection);
        return;
    }

    const auto selectStart = std::chrono::steady_clock::now();
    selector_.select(batches, lods_, camera, selection, selection_);
    const auto uploadStart = std::chrono::steady_clock::now();
    statistics_.selectSeconds += std::chrono::duration<double>(uploadStart - selectStart).count();
    statistics_.consideredInstances = selection_.consideredInstances;
    statistics_.visibleInstances += selection_.visibleInstances;
    statistics_.drawnInstances += selection_.instances.size();
    statistics_.ellipsoids += selection_.drawnEllipsoids;
    statistics_.lines += selection_.drawnLines;
    statistics_.occludedInstances += selection_.occludedInstances;
    if (selection_.instances.empty()) {
        return;
    }
    if (settings.method == VegetationMethod::Points) {
        drawPoints(projection, near, pixelsWide, pixelsHigh, selection.pixelAngle);
        return;
    }
    const std::size_t bytes = selection_.instances.size() * sizeof(DrawInstance);
    if (bytes > instanceCapacity_) {
        instanceCapacity_ = bytes + bytes / 2;
        glNamedBufferData(instanceBuffer_.get(), GLsizeiptr(instanceCapacity_), nullptr,
                          GL_STREAM_DRAW);
    } else {
        glInvalidateBufferData(instanceBuffer_.get());
    }
    glNamedBufferSubData(instanceBuffer_.get(), 0, GLsizeiptr(bytes), selection_.instances.data());
    statistics_.uploadSeconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - uploadStart).count();

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);  // reversed-Z
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    const glm::mat4 projectionFloat(projection);
    const float band = float(settings.transitionBand);
    const bool handover = settings.method == VegetationMethod::Lod && settings.closeUpMesh;

    // Ellipsoids (point sprites, and quads for sprites too large), then lines: instanced
    // draws per species and bucket.
    glVertexArrayVertexBuffer(primitiveArray_.get(), 0, instanceBuffer_.get(), 0,
                              sizeof(DrawInstance));
    glBindVertexArray(primitiveArray_.get());
    glEnable(GL_PROGRAM_POINT_SIZE);
    const glm::vec2 viewport{float(pixelsWide), float(pixelsHigh)};
    // Tangent of the angle between the view axis and a frustum corner.
    const double cornerTangent =
        selection.pixelAngle * 0.5 * std::hypot(double(pixelsWide), double(pixelsHigh));
    for (int pass = 0; pass < 2; ++pass) {
        ShaderProgram& program = pass == 0 ? ellipsoidProgram_ : lineProgram_;
        program.use();
        program.setMat4("uProjection", projectionFloat);
        program.setFloat("uNear", float(near));
        program.setFloat("uBand", band);
        settings.farField.apply(program, projection, near, pixelsWide, pixelsHigh);
        if (pass == 0) {
            program.setFloat("uNormalNoise", settings.normalNoise);
            program.setVec2("uViewport", viewport);
            program.setFloat("uMaximumPointSize", maximumPointSize_);
        }
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, pass == 0 ? 0 : 1,
                         pass == 0 ? ellipsoidBuffer_.get() : lineBuffer_.get());
        for (const DrawRun& run : selection_.runs) {
            const std::uint32_t count = pass == 0 ? run.ellipsoids : run.lines;
            if (run.kind != DrawRun::Kind::Primitives || count == 0) {
                continue;
            }
            const Species& species = *species_[run.species];
            program.setFloat("uMeshError", handover ? lods_[run.species].meshError : 0.0f);
            setLeafUniforms(program, run.species, pass == 0);
            if (pass == 1) {
                glDrawArraysInstancedBaseInstance(GL_TRIANGLES, GLint(species.firstLine * 6),
                                                  GLsizei(count * 6), GLsizei(run.instanceCount),
                                                  run.firstInstance);
                ++statistics_.drawCalls;
                continue;
            }
            program.setInt("uQuadPass", 0);
            glDrawArraysInstancedBaseInstance(GL_POINTS, GLint(species.firstEllipsoid),
                                              GLsizei(count), GLsizei(run.instanceCount),
                                              run.firstInstance);
            ++statistics_.drawCalls;
            if (mayExceedPointSize(run, selection.pixelAngle, cornerTangent, near)) {
                program.setInt("uQuadPass", 1);
                glDrawArraysInstancedBaseInstance(GL_TRIANGLES, GLint(species.firstEllipsoid * 6),
                                                  GLsizei(count * 6), GLsizei(run.instanceCount),
                                                  run.firstInstance);
                ++statistics_.drawCalls;
                ++statistics_.quadPassRuns;
            }
        }
    }
    glDisable(GL_PROGRAM_POINT_SIZE);

    drawMeshRuns(projection, near, pixelsWide, pixelsHigh, settings, handover);
    glBindVertexArray(0);
    if (settings.method == VegetationMethod::DisplacedBillboard) {
        drawDisplacedBillboards(projectionFloat, near, viewport, band);
    }
}

// The selection's Mesh runs (close-ups, the Mesh method) and billboard-cloud levels.
void VegetationRenderer::drawMeshRuns(const glm::dmat4& projection, double near, int pixelsWide,
                                      int pixelsHigh, const VegetationSettings& settings,
                                      bool handover) {
    const glm::mat4 projectionFloat(projection);
    const float band = float(settings.transitionBand);
    meshProgram_.use();
    meshProgram_.setMat4("uProjection", projectionFloat);
    meshProgram_.setFloat("uBand", band);
    settings.farField.apply(meshProgram_, projection, near, pixelsWide, pixelsHigh);
    meshProgram_.setInt("uTexture", 0);
    constexpr float kInfinity = std::numeric_limits<float>::infinity();
    for (const DrawRun& run : selection_.runs) {
        const Species& species = *species_[run.species];
        const SpeciesLod& lod = lods_[run.species];
        if (run.kind == DrawRun::Kind::Mesh) {
            const float maximum = handover ? lod.meshError : kInfinity;
            drawMeshes(species.mesh, run, glm::vec2(0.0f, maximum));
            statistics_.meshInstances += run.instanceCount;
        } else if (run.kind == DrawRun::Kind::Billboard &&
                   run.bucket < species.billboardLevels.size() &&
                   settings.method != VegetationMethod::DisplacedBillboard) {
            const std::size_t level = run.bucket;
            const float minimum = lod.billboardError[level];
            const float maximum =
                level + 1 < lod.billboardError.size() ? lod.billboardError[level + 1] : kInfinity;
            drawMeshes(species.billboardLevels[level], run, glm::vec2(minimum, maximum));
            statistics_.billboardInstances += run.instanceCount;
        }
    }
}

void VegetationRenderer::drawDisplacedBillboards(const glm::mat4& projection, double near,
                                                 glm::vec2 viewport, float band) {
    DisplacedBillboardFrame frame;
    frame.projection = projection;
    frame.near = float(near);
    frame.viewport = viewport;
    frame.band = band;
    statistics_.billboardInstances +=
        displacedBillboards_->draw(selection_, lods_, assets_, instanceBuffer_.get(), frame);
}

void VegetationRenderer::drawPoints(const glm::dmat4& projection, double near, int pixelsWide,
                                    int pixelsHigh, double pixelAngle) {
    statistics_.ellipsoids = statistics_.lines = 0;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);  // reversed-Z
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    PointCloudFrame frame;
    frame.projection = glm::mat4(projection);
    frame.near = float(near);
    frame.viewport = glm::vec2(float(pixelsWide), float(pixelsHigh));
    frame.pixelAngle = float(pixelAngle);
    frame.maximumPointSize = maximumPointSize_;
    statistics_.points = pointClouds_->draw(selection_, lods_, assets_, frame);
}

void VegetationRenderer::setLeafStates(std::vector<LeafState> states) {
    leafStates_ = std::move(states);
}

void VegetationRenderer::setLeafUniforms(ShaderProgram& program, std::uint32_t species,
                                         bool leaves) {
    const LeafState state =
        leaves && species < leafStates_.size() ? leafStates_[species] : LeafState{};
    program.setFloat("uLeafFraction", state.leafFraction);
    const float luminance =
        species < species_.size() ? std::max(species_[species]->leafLuminance, 1e-4f) : 1.0f;
    program.setVec4("uAutumn", glm::vec4(state.autumnColour / luminance, state.autumn));
}

void VegetationRenderer::drawImpostors(const std::vector<const InstanceBatch*>& batches,
                                       const Camera& camera, const glm::dmat4& projection,
                                       LodSelectionSettings selection) {
    if (Status captured = captureImpostors(); !captured) {
        // A GL failure (an incomplete capture target): said once, the plants not drawn.
        if (!impostorFailureReported_)
            std::fprintf(stderr, "sylva: impostors: %s\n", captured.error().message.c_str());
        impostorFailureReported_ = true;
        return;
    }
    const auto selectStart = std::chrono::steady_clock::now();
    const std::vector<const InstanceBatch*> near =
        impostors_->partition(batches, camera, selection, impostorSettings_);
    selector_.select(near, lods_, camera, selection, selection_);
    statistics_.selectSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - selectStart).count();
    statistics_.consideredInstances = selection_.consideredInstances;
    statistics_.visibleInstances = selection_.visibleInstances;
    statistics_.drawnInstances = selection_.instances.size();
    impostors_->draw(selection_, lods_, camera, projection, selection.pixelAngle,
                     impostorSettings_);
}

bool VegetationRenderer::mayExceedPointSize(const DrawRun& run, double pixelAngle,
                                            double cornerTangent, double near) const {
    const SpeciesLod& lod = lods_[run.species];
    const double radius =
        run.bucket < lod.ellipsoidRadius.size() ? lod.ellipsoidRadius[run.bucket] : 0.0;
    if (radius <= 0.0) {
        return false;
    }
    // Every ellipsoid of an instance lies within the instance's bounding sphere, so the
    // sprite's quad (its outline × 1.01, in front of it) is seen under a half-angle of at
    // most beta = atan(1.01 r / nearest sphere distance). On screen (tangent units, one
    // pixel = pixelAngle at the centre) an object of half-angle beta that still overlaps
    // the frustum spans at most tan(corner + 2 beta) - tan(corner).
    double nearest = std::numeric_limits<double>::infinity(), largestScale = 0.0;
    for (std::uint32_t i = run.firstInstance; i < run.firstInstance + run.instanceCount; ++i) {
        const DrawInstance& instance = selection_.instances[i];
        const glm::vec3 axisX(instance.axisX), axisY(instance.axisY), axisZ(instance.axisZ);
        const double scale = glm::length(axisX);
        const glm::vec3 center = glm::vec3(instance.origin) + axisX * lod.sphereCenter.x +
                                 axisY * lod.sphereCenter.y + axisZ * lod.sphereCenter.z;
        nearest = std::min(nearest, double(glm::length(center)) - lod.sphereRadius * scale);
        largestScale = std::max(largestScale, scale);
    }
    if (nearest <= near) {
        return true;
    }
    const double beta = std::atan(radius * largestScale * 1.01 / nearest);
    const double corner = std::atan(cornerTangent);
    constexpr double kRightAngle = std::numbers::pi / 2;
    if (corner + 2.0 * beta >= kRightAngle * 0.99) {
        return true;
    }
    const double pixels = (std::tan(corner + 2.0 * beta) - cornerTangent) / pixelAngle + 2.0;
    return pixels > double(maximumPointSize_);
}

void VegetationRenderer::drawMeshes(const std::vector<std::unique_ptr<VegetationMesh>>& meshes,
                                    const DrawRun& run, glm::vec2 interval) {
    meshProgram_.setVec2("uInterval", interval);
    for (const std::unique_ptr<VegetationMesh>& mesh : meshes) {
        meshProgram_.setVec4("uBaseColor", mesh->baseColor);
        meshProgram_.setFloat("uAlphaCutoff", mesh->alphaCutoff);
        meshProgram_.setInt("uHasTexture", mesh->texture != 0 ? 1 : 0);
        meshProgram_.setFloat("uAmbientOcclusion", 1.0f);
        meshProgram_.setInt("uLeaves", mesh->leaves ? 1 : 0);
        setLeafUniforms(meshProgram_, run.species, mesh->leaves);
        glBindTextureUnit(0, mesh->texture);
        glBindVertexArray(mesh->vertexArray.get());
        glDrawElementsInstancedBaseInstance(GL_TRIANGLES, mesh->indexCount, GL_UNSIGNED_INT,
                                            nullptr, GLsizei(run.instanceCount), run.firstInstance);
        ++statistics_.drawCalls;
    }
}

void VegetationRenderer::appendShadowThresholds(const PlantAsset& asset) {
    const PlantLod& lod = asset.lod;
    const std::vector<ShadowThreshold> levels = shadowThresholds(asset.model, lod);
    for (const LodEllipsoid& e : lod.ellipsoids) {
        shadowThresholds_.push_back(e.level < levels.size()
                                        ? glm::vec2(levels[e.level].low, levels[e.level].high)
                                        : glm::vec2(e.alphaThreshold));
    }
    std::vector<glm::vec2> upload = shadowThresholds_;
    if (upload.empty()) {
        upload.resize(1);  // an empty buffer is not bindable as storage
    }
    shadowThresholdBuffer_ = createGlBuffer();
    glNamedBufferStorage(shadowThresholdBuffer_.get(),
                         GLsizeiptr(upload.size() * sizeof(glm::vec2)), upload.data(), 0);
}

std::optional<std::uint64_t> VegetationRenderer::shadowCacheKey(const ShadowView& view) const {
    ContentHash hash;
    if (view.cascade->terrainOnly || species_.empty() || shadowBatches_.empty()) {
        return hash.value();  // drawShadow draws nothing
    }
    const VegetationSettings& settings = shadowSettings_;
    // Not the camera: the selection for the cascade is orthographic with a fixed error in
    // cascade texels (drawShadow), so which levels cast where depends on the box (in
    // ShadowMaps' key) and the batches, not on where the viewer stands in it.
    hash.add(int(settings.method)).add(settings.quality).add(settings.minimumPixels);
    hash.add(settings.transitionBand).add(settings.closeUpMesh).add(settings.shadowErrorTexels);
    hash.add(species_.size()).add(ellipsoidCount_).add(lineCount_);
    for (std::size_t i = 0; i < species_.size(); ++i) {
        const LeafState state = i < leafStates_.size() ? leafStates_[i] : LeafState{};
        hash.add(state.leafFraction);
    }
    for (const InstanceBatch* batch : shadowBatches_) {
        hash.add(batch->contentHash);
    }
    return hash.value();
}

void VegetationRenderer::drawShadow(const ShadowView& view) {
    if (view.cascade->terrainOnly || species_.empty() || shadowBatches_.empty()) {
        return;
    }
    const ShadowCascade& cascade = *view.cascade;
    const VegetationSettings& settings = shadowSettings_;
    // Orthographic selection in the light frame (camera-relative, rotated by the light
    // rotation): a camera at the viewer's position whose view rotation is the light's, the
    // cascade's box as four offset side planes. The tolerated error is the width the
    // shadow lookup blurs an edge over (shadows.glsl: a 3 x 3-texel PCF box), not one
    // texel: finer crown detail is filtered away, and one-texel selection drew the finest
    // levels and meshes of hundreds of trees into every cascade (docs/benchmarks.md,
    // shadow_frame_ratio). Plants still cast down to settings.minimumPixels texels.
    // (settings.shadowErrorTexels, 3 by default.)
    Camera light = *view.camera;
    light.axes = glm::transpose(view.lightRotation);
    LodSelectionSettings selection;
    SYLVA_CHECK(settings.shadowErrorTexels > 0.0);
    selection.pixelAngle = settings.shadowErrorTexels * cascade.texelSize;
    selection.fixedDistance = 1.0;
    selection.quality = settings.quality;
    selection.minimumPixels = settings.minimumPixels / settings.shadowErrorTexels;
    selection.transitionBand = settings.transitionBand;
    selection.closeUpMesh = settings.closeUpMesh;
    // Impostors cast the LoD's shadows (an impostor faces the camera, not the sun).
    selection.method =
        settings.method == VegetationMethod::Impostors ? VegetationMethod::Lod : settings.method;
    selection.closeUpMesh = settings.closeUpMesh && settings.method != VegetationMethod::Impostors;
    selection.near = -1.0e30;
    const glm::dmat4& projection = view.projection;
    const double halfWidth = 1.0 / projection[0][0];
    const glm::dvec2 center(-projection[3][0] * halfWidth, -projection[3][1] * halfWidth);
    selection.sidePlanes[0] = glm::vec3(1, 0, 0);
    selection.sideOffsets[0] = float(halfWidth - center.x);
    selection.sidePlanes[1] = glm::vec3(-1, 0, 0);
    selection.sideOffsets[1] = float(halfWidth + center.x);
    selection.sidePlanes[2] = glm::vec3(0, 1, 0);
    selection.sideOffsets[2] = float(halfWidth - center.y);
    selection.sidePlanes[3] = glm::vec3(0, -1, 0);
    selection.sideOffsets[3] = float(halfWidth + center.y);
    shadowSelector_.select(shadowBatches_, lods_, light, selection, shadowSelection_);
    ++statistics_.shadowCascades;
    if (shadowSelection_.instances.empty()) {
        return;
    }
    const std::size_t bytes = shadowSelection_.instances.size() * sizeof(DrawInstance);
    if (bytes > instanceCapacity_) {
        instanceCapacity_ = bytes + bytes / 2;
        glNamedBufferData(instanceBuffer_.get(), GLsizeiptr(instanceCapacity_), nullptr,
                          GL_STREAM_DRAW);
    } else {
        glInvalidateBufferData(instanceBuffer_.get());
    }
    glNamedBufferSubData(instanceBuffer_.get(), 0, GLsizeiptr(bytes),
                         shadowSelection_.instances.data());
    drawShadowRuns(view, settings);
}

void VegetationRenderer::drawShadowRuns(const ShadowView& view,
                                        const VegetationSettings& settings) {
    const glm::mat4 projection(view.projection);
    const float texel = float(view.cascade->texelSize);
    const float band = float(settings.transitionBand);
    const bool handover = settings.method == VegetationMethod::Lod && settings.closeUpMesh;
    glVertexArrayVertexBuffer(primitiveArray_.get(), 0, instanceBuffer_.get(), 0,
                              sizeof(DrawInstance));
    glBindVertexArray(primitiveArray_.get());
    glEnable(GL_PROGRAM_POINT_SIZE);
    for (int pass = 0; pass < 2; ++pass) {
        ShaderProgram& program = pass == 0 ? ellipsoidShadowProgram_ : lineShadowProgram_;
        program.use();
        program.setMat4("uProjection", projection);
        program.setFloat("uTexelSize", texel);
        program.setFloat("uBand", band);
        program.setVec2("uViewport", glm::vec2(float(view.resolution)));
        program.setFloat("uMaximumPointSize", maximumPointSize_);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, pass == 0 ? 0 : 1,
                         pass == 0 ? ellipsoidBuffer_.get() : lineBuffer_.get());
        if (pass == 0) {
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, shadowThresholdBuffer_.get());
        }
        for (const DrawRun& run : shadowSelection_.runs) {
            const std::uint32_t count = pass == 0 ? run.ellipsoids : run.lines;
            if (run.kind != DrawRun::Kind::Primitives || count == 0) {
                continue;
            }
            const Species& species = *species_[run.species];
            const SpeciesLod& lod = lods_[run.species];
            program.setFloat("uMeshError", handover ? lod.meshError : 0.0f);
            setLeafUniforms(program, run.species, pass == 0);
            if (pass == 1) {
                glDrawArraysInstancedBaseInstance(GL_TRIANGLES, GLint(species.firstLine * 6),
                                                  GLsizei(count * 6), GLsizei(run.instanceCount),
                                                  run.firstInstance);
                continue;
            }
            program.setInt("uQuadPass", 0);
            glDrawArraysInstancedBaseInstance(GL_POINTS, GLint(species.firstEllipsoid),
                                              GLsizei(count), GLsizei(run.instanceCount),
                                              run.firstInstance);
            // Sprites wider than the largest point: the quad pass (same split as the shader).
            float largestScale = 0.0f;
            for (std::uint32_t i = run.firstInstance; i < run.firstInstance + run.instanceCount;
                 ++i) {
                largestScale = std::max(
                    largestScale, glm::length(glm::vec3(shadowSelection_.instances[i].axisX)));
            }
            const float radius = run.bucket < lod.ellipsoidRadius.size()
                                     ? lod.ellipsoidRadius[run.bucket] * largestScale
                                     : 0.0f;
            if (2.0f * (radius * 1.01f + texel) / texel > maximumPointSize_) {
                program.setInt("uQuadPass", 1);
                glDrawArraysInstancedBaseInstance(GL_TRIANGLES, GLint(species.firstEllipsoid * 6),
                                                  GLsizei(count * 6), GLsizei(run.instanceCount),
                                                  run.firstInstance);
            }
        }
    }
    glDisable(GL_PROGRAM_POINT_SIZE);
    // Meshes and billboard clouds: the G-buffer program with the light's projection (its
    // alpha test discards transparent texels; the colour outputs have no attachment here).
    meshProgram_.use();
    meshProgram_.setMat4("uProjection", projection);
    meshProgram_.setFloat("uBand", band);
    FarFieldFade{}.apply(meshProgram_, glm::dmat4(1.0), 1.0, 1, 1);  // no hand-over from the sun
    meshProgram_.setInt("uTexture", 0);
    constexpr float kInfinity = std::numeric_limits<float>::infinity();
    for (const DrawRun& run : shadowSelection_.runs) {
        const Species& species = *species_[run.species];
        const SpeciesLod& lod = lods_[run.species];
        if (run.kind == DrawRun::Kind::Mesh) {
            drawMeshes(species.mesh, run, glm::vec2(0.0f, handover ? lod.meshError : kInfinity));
        } else if (run.kind == DrawRun::Kind::Billboard &&
                   run.bucket < species.billboardLevels.size()) {
            const std::size_t level = run.bucket;
            const float maximum =
                level + 1 < lod.billboardError.size() ? lod.billboardError[level + 1] : kInfinity;
            drawMeshes(species.billboardLevels[level], run,
                       glm::vec2(lod.billboardError[level], maximum));
        }
    }
    glBindVertexArray(0);
}

}  // namespace sylva::render
