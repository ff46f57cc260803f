// Seed 000 ch. 3.3 (runtime): per instance the set of its view direction's cell, a prefix
// by screen size, one vertex array per set, instances sharing the samples.
#include "PointCloudRenderer.h"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>

#include "sylva/core/base/Check.h"
#include "sylva/core/plantlod/PointCloudBuilder.h"

namespace sylva::render {

Result<std::unique_ptr<PointCloudRenderer>> PointCloudRenderer::create(
    const ShaderLibrary& library) {
    std::unique_ptr<PointCloudRenderer> renderer(new PointCloudRenderer());
    Result<ShaderProgram> program =
        ShaderProgram::create(library, {{GL_VERTEX_SHADER, "vegetation/point.vert"},
                                        {GL_FRAGMENT_SHADER, "vegetation/point.frag"}});
    if (!program) {
        return program.error();
    }
    renderer->program_ = std::move(program.value());
    renderer->instanceBuffer_ = createGlBuffer();
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

std::uint32_t PointCloudRenderer::prefixLength(double sphereRadius, double error,
                                               std::uint32_t setSize) {
    const double pixels = sphereRadius / std::max(error, 1e-9);
    const double wanted = kSamplesPerPixel * std::numbers::pi * pixels * pixels;
    return std::uint32_t(std::clamp(std::ceil(wanted), 1.0, double(setSize)));
}

void PointCloudRenderer::prepare(std::uint32_t index, const PlantAsset& asset) {
    if (index >= species_.size()) {
        species_.resize(index + 1);
    }
    Species& species = species_[index];
    if (species.built || species.failed) {
        return;
    }
    PointCloudOptions options;
    options.samples = kSamples;
    Result<PointCloud> cloud = PointCloudBuilder::build(asset.model, options);
    if (!cloud) {
        std::fprintf(stderr, "vegetation points: plant '%s' draws nothing: %s\n",
                     asset.name.c_str(), cloud.error().message.c_str());
        species.failed = true;
        return;
    }
    species.sets = VisibleSets::build(cloud.value());
    species.firstSample = std::uint32_t(samples_.size() / 2);
    species.firstIndex = std::uint32_t(indices_.size());
    for (const PlantPoint& p : cloud.value().points) {
        samples_.emplace_back(p.position, p.radius);
        std::uint32_t color = p.color;
        float colorBits = 0.0f;
        std::memcpy(&colorBits, &color, sizeof colorBits);
        samples_.emplace_back(p.normal, colorBits);
    }
    for (std::uint32_t sample : species.sets.cellPoints()) {
        indices_.push_back(species.firstSample + sample);
    }
    species.built = true;
    // Immutable storage, re-created with every species (once per species per process).
    sampleBuffer_ = createGlBuffer();
    glNamedBufferStorage(sampleBuffer_.get(), GLsizeiptr(samples_.size() * sizeof(glm::vec4)),
                         samples_.data(), 0);
    indexBuffer_ = createGlBuffer();
    glNamedBufferStorage(indexBuffer_.get(), GLsizeiptr(indices_.size() * sizeof(std::uint32_t)),
                         indices_.data(), 0);
    glVertexArrayElementBuffer(vertexArray_.get(), indexBuffer_.get());
}

void PointCloudRenderer::groupInstances(const LodSelection& selection,
                                        const std::vector<SpeciesLod>& lods) {
    grouped_.clear();
    groups_.clear();
    std::vector<std::uint32_t> cellOfInstance;
    std::vector<std::uint32_t> counts;
    for (const DrawRun& run : selection.runs) {
        if (run.kind != DrawRun::Kind::Primitives || run.species >= species_.size() ||
            !species_[run.species].built) {
            continue;
        }
        const VisibleSets& sets = species_[run.species].sets;
        const glm::vec3 sphereCenter = lods[run.species].sphereCenter;
        cellOfInstance.resize(run.instanceCount);
        counts.assign(sets.cells().size() + 1, 0);
        for (std::uint32_t i = 0; i < run.instanceCount; ++i) {
            const DrawInstance& instance = selection.instances[run.firstInstance + i];
            // The eye in the model frame: axes are rotation × scale, so A⁻¹ = Aᵀ / s².
            const glm::mat3 axes(glm::vec3(instance.axisX), glm::vec3(instance.axisY),
                                 glm::vec3(instance.axisZ));
            const float scale2 = glm::dot(glm::vec3(instance.axisX), glm::vec3(instance.axisX));
            const glm::vec3 eye = glm::transpose(axes) * -glm::vec3(instance.origin) / scale2;
            glm::vec3 direction = eye - sphereCenter;
            if (glm::dot(direction, direction) < 1e-12f) {
                direction = glm::vec3(0, 0, 1);
            }
            cellOfInstance[i] = sets.cellOf(direction);
            ++counts[cellOfInstance[i] + 1];
        }
        const std::uint32_t base = std::uint32_t(grouped_.size());
        for (std::size_t c = 0; c + 1 < counts.size(); ++c) {
            if (counts[c + 1] > 0) {
                groups_.push_back(
                    {run.species, std::uint32_t(c), run.bucket, base + counts[c], counts[c + 1]});
            }
            counts[c + 1] += counts[c];
        }
        grouped_.resize(base + run.instanceCount);
        for (std::uint32_t i = 0; i < run.instanceCount; ++i) {
            grouped_[base + counts[cellOfInstance[i]]++] =
                selection.instances[run.firstInstance + i];
        }
    }
}

std::size_t PointCloudRenderer::draw(const LodSelection& selection,
                                     const std::vector<SpeciesLod>& lods,
                                     const std::vector<std::shared_ptr<const PlantAsset>>& assets,
                                     const PointCloudFrame& frame) {
    for (const DrawRun& run : selection.runs) {
        if (run.kind == DrawRun::Kind::Primitives) {
            SYLVA_CHECK(run.species < assets.size());
            prepare(run.species, *assets[run.species]);
        }
    }
    groupInstances(selection, lods);
    if (grouped_.empty()) {
        return 0;
    }
    const std::size_t bytes = grouped_.size() * sizeof(DrawInstance);
    if (bytes > instanceCapacity_) {
        instanceCapacity_ = bytes + bytes / 2;
        glNamedBufferData(instanceBuffer_.get(), GLsizeiptr(instanceCapacity_), nullptr,
                          GL_STREAM_DRAW);
    } else {
        glInvalidateBufferData(instanceBuffer_.get());
    }
    glNamedBufferSubData(instanceBuffer_.get(), 0, GLsizeiptr(bytes), grouped_.data());
    glVertexArrayVertexBuffer(vertexArray_.get(), 0, instanceBuffer_.get(), 0,
                              sizeof(DrawInstance));
    glBindVertexArray(vertexArray_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, sampleBuffer_.get());
    glEnable(GL_PROGRAM_POINT_SIZE);
    program_.use();
    program_.setMat4("uProjection", frame.projection);
    program_.setFloat("uNear", frame.near);
    program_.setVec2("uViewport", frame.viewport);
    program_.setFloat("uPixelAngle", frame.pixelAngle);
    program_.setFloat("uMaximumPointSize", frame.maximumPointSize);
    std::size_t drawn = 0;
    for (const Group& group : groups_) {
        const Species& species = species_[group.species];
        const std::uint32_t first = species.sets.cellOffsets()[group.cell];
        const std::uint32_t size = species.sets.cellOffsets()[group.cell + 1] - first;
        const double error = LodSelector::bucketLowerError(int(group.bucket));
        // The largest instance of the group bounds its screen size.
        float scale = 0.0f;
        for (std::uint32_t i = 0; i < group.instanceCount; ++i) {
            scale =
                std::max(scale, glm::length(glm::vec3(grouped_[group.firstInstance + i].axisX)));
        }
        const std::uint32_t count =
            prefixLength(double(lods[group.species].sphereRadius) * scale, error, size);
        program_.setFloat("uRadiusScale",
                          kSplatScale * std::sqrt(float(size) / float(std::max(count, 1u))));
        glDrawElementsInstancedBaseInstance(
            GL_POINTS, GLsizei(count), GL_UNSIGNED_INT,
            reinterpret_cast<const void*>(std::uintptr_t(species.firstIndex + first) *
                                          sizeof(std::uint32_t)),
            GLsizei(group.instanceCount), group.firstInstance);
        drawn += std::size_t(count) * group.instanceCount;
    }
    glDisable(GL_PROGRAM_POINT_SIZE);
    glBindVertexArray(0);
    return drawn;
}

}  // namespace sylva::render
