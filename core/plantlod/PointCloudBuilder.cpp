// Seed 000 ch. 3: point-sampled vegetation. The thesis takes its samples from a
// generator's leaves (one point per leaf); here the source mesh is sampled by area, so
// any imported or generated PlantModel becomes a cloud of surfels of one size.
#include "sylva/core/plantlod/PointCloudBuilder.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "TexelColour.h"

namespace sylva {

namespace {

// Nearest texel of `texture` at `uv` (rows from the top as in glTF): linear RGB
// and alpha.
glm::vec4 sampleTexture(const PlantTexture& texture, glm::vec2 uv) {
    // Inside [0, 1] clamped (a sample on the far edge keeps its texel), outside repeated.
    const auto wrap = [](float c) { return c >= 0.0f && c <= 1.0f ? c : c - std::floor(c); };
    const float u = wrap(uv.x), v = wrap(uv.y);
    const int x = std::min(texture.width - 1, int(u * float(texture.width)));
    const int y = std::min(texture.height - 1, int(v * float(texture.height)));
    const std::uint8_t* texel = texture.rgba.data() + (std::size_t(y) * texture.width + x) * 4;
    return {texelToLinear(texel[0]), texelToLinear(texel[1]), texelToLinear(texel[2]),
            float(texel[3]) / 255.0f};
}

struct Triangle {
    std::uint32_t mesh = 0, first = 0;  // the mesh and its first index of the triangle
    float area = 0.0f;
};

}  // namespace

std::uint32_t PointCloudBuilder::packColor(glm::vec3 linear) {
    return std::uint32_t(linearToTexel(linear.r)) | std::uint32_t(linearToTexel(linear.g)) << 8 |
           std::uint32_t(linearToTexel(linear.b)) << 16 | 0xFF000000u;
}

glm::vec3 PointCloudBuilder::unpackColor(std::uint32_t packed) {
    return {texelToLinear(std::uint8_t(packed & 0xFF)),
            texelToLinear(std::uint8_t(packed >> 8 & 0xFF)),
            texelToLinear(std::uint8_t(packed >> 16 & 0xFF))};
}

Result<PointCloud> PointCloudBuilder::build(const PlantModel& model,
                                            const PointCloudOptions& options) {
    if (options.samples < 1 || options.samples > 10000000 || !(options.coverage > 0.0f)) {
        return Error{"point cloud: samples must be within 1..10000000 and coverage positive"};
    }
    std::vector<Triangle> triangles;
    double totalArea = 0.0;
    for (std::size_t m = 0; m < model.meshes.size(); ++m) {
        const PlantMesh& mesh = model.meshes[m];
        for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            const glm::vec3 a = mesh.positions[mesh.indices[i]];
            const glm::vec3 b = mesh.positions[mesh.indices[i + 1]];
            const glm::vec3 c = mesh.positions[mesh.indices[i + 2]];
            const float area = 0.5f * glm::length(glm::cross(b - a, c - a));
            if (area > 0.0f) {
                triangles.push_back({std::uint32_t(m), std::uint32_t(i), area});
                totalArea += area;
            }
        }
    }
    if (triangles.empty()) {
        return Error{"point cloud: the model '" + model.name + "' has no triangle to sample"};
    }
    const double areaPerSample = totalArea / options.samples;
    const float radius =
        float(std::sqrt(double(options.coverage) * areaPerSample / std::numbers::pi));
    std::mt19937 random(options.seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    PointCloud cloud;
    cloud.points.reserve(std::size_t(options.samples));
    // Stratified by triangle: each gets its expected count, the fraction by chance.
    for (const Triangle& triangle : triangles) {
        const PlantMesh& mesh = model.meshes[triangle.mesh];
        const PlantMaterial* material =
            mesh.material >= 0 && std::size_t(mesh.material) < model.materials.size()
                ? &model.materials[std::size_t(mesh.material)]
                : nullptr;
        const double expected = double(triangle.area) / areaPerSample;
        const int count = int(expected) + (unit(random) < float(expected - std::floor(expected)));
        const std::uint32_t i0 = mesh.indices[triangle.first],
                            i1 = mesh.indices[triangle.first + 1],
                            i2 = mesh.indices[triangle.first + 2];
        const glm::vec3 a = mesh.positions[i0], b = mesh.positions[i1], c = mesh.positions[i2];
        const glm::vec3 faceNormal = glm::normalize(glm::cross(b - a, c - a));
        // A randomly offset R2 sequence (Roberts 2018) folded into the triangle: evenly
        // spread samples, so the discs close the surface (random ones leave e^-coverage
        // of it open).
        const float offsetU = unit(random), offsetV = unit(random);
        for (int s = 0; s < count; ++s) {
            constexpr float kR2U = 0.7548776662f, kR2V = 0.5698402910f;
            float u = offsetU + float(s) * kR2U, v = offsetV + float(s) * kR2V;
            u -= std::floor(u);
            v -= std::floor(v);
            if (u + v > 1.0f) {
                u = 1.0f - u;
                v = 1.0f - v;
            }
            const float wa = 1.0f - u - v, wb = u, wc = v;
            glm::vec4 color = material ? material->baseColor : glm::vec4(0.35f, 0.3f, 0.25f, 1.0f);
            if (material && material->baseColorTexture.width > 0 && mesh.uvs.size() > i2 &&
                mesh.uvs.size() > std::max(i0, i1)) {
                const glm::vec2 uv = wa * mesh.uvs[i0] + wb * mesh.uvs[i1] + wc * mesh.uvs[i2];
                color *= sampleTexture(material->baseColorTexture, uv);
            }
            if (material && material->alphaMasked && color.a < material->alphaCutoff) {
                continue;  // a hole of the leaf's cut-out
            }
            PlantPoint point;
            point.position = wa * a + wb * b + wc * c;
            point.radius = radius;
            glm::vec3 normal = faceNormal;
            if (mesh.normals.size() == mesh.positions.size()) {
                const glm::vec3 n =
                    wa * mesh.normals[i0] + wb * mesh.normals[i1] + wc * mesh.normals[i2];
                if (glm::dot(n, n) > 1e-12f) {
                    normal = glm::normalize(n);
                }
            }
            point.normal = normal;
            point.color = packColor(glm::vec3(color));
            cloud.points.push_back(point);
        }
    }
    if (cloud.points.empty()) {
        return Error{"point cloud: every sample of '" + model.name +
                     "' fell on a transparent texel"};
    }
    cloud.boundsMinimum = cloud.boundsMaximum = cloud.points.front().position;
    for (const PlantPoint& p : cloud.points) {
        cloud.boundsMinimum = glm::min(cloud.boundsMinimum, p.position);
        cloud.boundsMaximum = glm::max(cloud.boundsMaximum, p.position);
    }
    return cloud;
}

}  // namespace sylva
