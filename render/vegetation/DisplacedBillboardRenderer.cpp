// Seed 000 ch. 5: billboard boxes ray-marched per pixel, on the billboard-cloud levels
// and the level selection of the `billboards` method.
#include "DisplacedBillboardRenderer.h"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "sylva/core/base/Check.h"
#include "sylva/core/plantlod/DisplacedBillboardBuilder.h"

namespace sylva::render {

namespace {

// std430 mirror of shaders/vegetation/displaced_billboard.vert's Box.
struct GpuBox {
    glm::vec4 originHalf;
    glm::vec4 edgeS;
    glm::vec4 edgeT;
    glm::vec4 normal;
    glm::vec4 atlasRect;
};
static_assert(sizeof(GpuBox) == 80);

GlTexture uploadAtlas(const PlantTexture& atlas) {
    GlTexture texture = createGlTexture(GL_TEXTURE_2D);
    const int levels = 1 + int(std::floor(std::log2(std::max(atlas.width, atlas.height))));
    glTextureStorage2D(texture.get(), levels, GL_SRGB8_ALPHA8, atlas.width, atlas.height);
    glTextureSubImage2D(texture.get(), 0, 0, 0, atlas.width, atlas.height, GL_RGBA,
                        GL_UNSIGNED_BYTE, atlas.rgba.data());
    glGenerateTextureMipmap(texture.get());
    glTextureParameteri(texture.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(texture.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

}  // namespace

Result<std::unique_ptr<DisplacedBillboardRenderer>> DisplacedBillboardRenderer::create(
    const ShaderLibrary& library) {
    std::unique_ptr<DisplacedBillboardRenderer> renderer(new DisplacedBillboardRenderer());
    Result<ShaderProgram> program = ShaderProgram::create(
        library, {{GL_VERTEX_SHADER, "vegetation/displaced_billboard.vert"},
                  {GL_FRAGMENT_SHADER, "vegetation/displaced_billboard.frag"}});
    if (!program) {
        return program.error();
    }
    renderer->program_ = std::move(program.value());
    renderer->vertexArray_ = createGlVertexArray();
    const GLuint va = renderer->vertexArray_.get();
    for (GLuint i = 0; i < 5; ++i) {
        glEnableVertexArrayAttrib(va, i);
        glVertexArrayAttribFormat(va, i, 4, GL_FLOAT, GL_FALSE, GLuint(i * sizeof(glm::vec4)));
        glVertexArrayAttribBinding(va, i, 0);
    }
    glVertexArrayBindingDivisor(va, 0, 1);
    return renderer;
}

DisplacedBillboardRenderer::Level& DisplacedBillboardRenderer::prepare(std::uint32_t species,
                                                                       std::uint32_t index,
                                                                       const PlantAsset& asset) {
    if (species >= levels_.size()) {
        levels_.resize(species + 1);
    }
    std::vector<Level>& levels = levels_[species];
    const std::vector<BillboardLevel>& source = asset.lod.billboards.levels;
    SYLVA_CHECK(index < source.size());
    if (levels.size() < source.size()) {
        levels.resize(source.size());
    }
    Level& level = levels[index];
    if (level.built || level.failed) {
        return level;
    }
    const BillboardLevel& billboards = source[index];
    Result<DisplacementAtlas> displacement =
        DisplacedBillboardBuilder::build(asset.model, billboards);
    if (!displacement) {
        std::fprintf(stderr, "vegetation dmbbc: plant '%s' level %u draws nothing: %s\n",
                     asset.name.c_str(), index, displacement.error().message.c_str());
        level.failed = true;
        return level;
    }
    std::vector<GpuBox> boxes;
    for (std::size_t q = 0; q < billboards.quads.size(); ++q) {
        const BillboardQuad& quad = billboards.quads[q];
        GpuBox box;
        box.originHalf = glm::vec4(quad.corners[0], displacement->halfThickness[q]);
        box.edgeS = glm::vec4(quad.corners[1] - quad.corners[0], 0.0f);
        box.edgeT = glm::vec4(quad.corners[3] - quad.corners[0], 0.0f);
        box.normal = glm::vec4(quad.normal, 0.0f);
        // atlasUvs: corner 0 = (u0, v1), corner 2 = (u1, v0) (rows from the top).
        box.atlasRect = glm::vec4(quad.atlasUvs[3], quad.atlasUvs[1]);
        boxes.push_back(box);
    }
    level.boxCount = std::uint32_t(boxes.size());
    level.boxes = createGlBuffer();
    glNamedBufferStorage(level.boxes.get(),
                         GLsizeiptr(std::max<std::size_t>(boxes.size(), 1) * sizeof(GpuBox)),
                         boxes.empty() ? nullptr : boxes.data(), 0);
    level.atlas = uploadAtlas(billboards.atlas);
    level.heights = createGlTexture(GL_TEXTURE_2D);
    glTextureStorage2D(level.heights.get(), 1, GL_RG16F, displacement->width, displacement->height);
    glTextureSubImage2D(level.heights.get(), 0, 0, 0, displacement->width, displacement->height,
                        GL_RG, GL_FLOAT, displacement->heights.data());
    glTextureParameteri(level.heights.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(level.heights.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    level.built = true;
    return level;
}

std::size_t DisplacedBillboardRenderer::draw(
    const LodSelection& selection, const std::vector<SpeciesLod>& lods,
    const std::vector<std::shared_ptr<const PlantAsset>>& assets, std::uint32_t instances,
    const DisplacedBillboardFrame& frame) {
    glVertexArrayVertexBuffer(vertexArray_.get(), 0, instances, 0, sizeof(DrawInstance));
    glBindVertexArray(vertexArray_.get());
    program_.use();
    program_.setMat4("uProjection", frame.projection);
    program_.setFloat("uNear", frame.near);
    program_.setVec2("uViewport", frame.viewport);
    program_.setFloat("uBand", frame.band);
    program_.setInt("uAtlas", 0);
    program_.setInt("uHeights", 1);
    program_.setFloat("uAlphaCutoff", 0.5f);
    program_.setInt("uMaximumSteps", kMaximumSteps);
    // Back faces only (the ray starts where it enters the box; see the fragment shader).
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
    glFrontFace(GL_CCW);
    constexpr float kInfinity = std::numeric_limits<float>::infinity();
    std::size_t drawn = 0;
    for (const DrawRun& run : selection.runs) {
        if (run.kind != DrawRun::Kind::Billboard) {
            continue;
        }
        SYLVA_CHECK(run.species < assets.size());
        const PlantAsset& asset = *assets[run.species];
        if (run.bucket >= asset.lod.billboards.levels.size()) {
            continue;
        }
        Level& level = prepare(run.species, run.bucket, asset);
        if (!level.built || level.boxCount == 0) {
            continue;
        }
        const SpeciesLod& lod = lods[run.species];
        const float maximum = run.bucket + 1 < lod.billboardError.size()
                                  ? lod.billboardError[run.bucket + 1]
                                  : kInfinity;
        program_.setVec2("uInterval", glm::vec2(lod.billboardError[run.bucket], maximum));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, level.boxes.get());
        glBindTextureUnit(0, level.atlas.get());
        glBindTextureUnit(1, level.heights.get());
        glDrawArraysInstancedBaseInstance(GL_TRIANGLES, 0, GLsizei(level.boxCount * 36),
                                          GLsizei(run.instanceCount), run.firstInstance);
        drawn += run.instanceCount;
    }
    glDisable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glBindVertexArray(0);
    return drawn;
}

}  // namespace sylva::render
