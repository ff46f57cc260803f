#include "sylva/core/plantlod/PlantRasterizer.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva {

namespace {

float srgbToLinear(std::uint8_t value) {
    const float c = float(value) / 255.0f;
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

std::uint8_t linearToSrgb(float linear) {
    linear = std::clamp(linear, 0.0f, 1.0f);
    const float c =
        linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
    return std::uint8_t(std::lround(c * 255.0f));
}

}  // namespace

RasterImage PlantRasterizer::renderSide(const PlantModel& model, int width, int height) {
    SYLVA_CHECK(width > 0 && height > 0);
    const glm::vec3 minimum = model.boundsMinimum();
    const glm::vec3 maximum = model.boundsMaximum();
    if (!(minimum.x <= maximum.x)) {
        RasterImage empty;
        empty.width = width;
        empty.height = height;
        empty.rgba.assign(std::size_t(width) * std::size_t(height) * 4, 0);
        return empty;
    }
    // Fit the x–z extent with a 3 % margin, the base near the bottom edge.
    const float extentX = std::max(maximum.x - minimum.x, 1e-3f);
    const float extentZ = std::max(maximum.z - minimum.z, 1e-3f);
    const float scale = 0.94f * std::min(float(width) / extentX, float(height) / extentZ);
    OrthographicView view;
    view.origin = glm::vec3(0.5f * (minimum.x + maximum.x), 0.0f, minimum.z);
    view.minimum = glm::vec2(-0.5f * float(width) / scale, -0.03f * float(height) / scale);
    view.maximum = glm::vec2(0.5f * float(width) / scale, 0.97f * float(height) / scale);
    return renderOrthographic(model, view, width, height);
}

RasterImage PlantRasterizer::renderOrthographic(
    const PlantModel& model, const OrthographicView& view, int width, int height,
    const std::vector<std::vector<bool>>* triangleMask) {
    SYLVA_CHECK(width > 0 && height > 0);
    RasterImage image;
    image.width = width;
    image.height = height;
    image.rgba.assign(std::size_t(width) * std::size_t(height) * 4, 0);
    std::vector<float> depth(std::size_t(width) * std::size_t(height),
                             std::numeric_limits<float>::max());
    const glm::vec3 toward = glm::cross(view.right, view.up);  // towards the eye
    const glm::vec2 scale(float(width) / std::max(view.maximum.x - view.minimum.x, 1e-9f),
                          float(height) / std::max(view.maximum.y - view.minimum.y, 1e-9f));
    const glm::vec3 light = glm::normalize(0.5f * toward - 0.5f * view.right + 0.8f * view.up);
    auto project = [&](const glm::vec3& p) {
        const glm::vec3 d = p - view.origin;
        return glm::vec3((glm::dot(d, view.right) - view.minimum.x) * scale.x,
                         (view.maximum.y - glm::dot(d, view.up)) * scale.y, -glm::dot(d, toward));
    };
    for (std::size_t meshIndex = 0; meshIndex < model.meshes.size(); ++meshIndex) {
        const PlantMesh& mesh = model.meshes[meshIndex];
        const PlantMaterial* material =
            mesh.material >= 0 && std::size_t(mesh.material) < model.materials.size()
                ? &model.materials[std::size_t(mesh.material)]
                : nullptr;
        const glm::vec4 base =
            material != nullptr ? material->baseColor : glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
        const PlantTexture* texture =
            material != nullptr && material->baseColorTexture.width > 0 && !mesh.uvs.empty()
                ? &material->baseColorTexture
                : nullptr;
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            if (triangleMask != nullptr && !(*triangleMask)[meshIndex][t / 3]) {
                continue;
            }
            const std::uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1],
                                i2 = mesh.indices[t + 2];
            const glm::vec3 a = project(mesh.positions[i0]);
            const glm::vec3 b = project(mesh.positions[i1]);
            const glm::vec3 c = project(mesh.positions[i2]);
            const float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
            if (std::abs(area) < 1e-12f) {
                continue;
            }
            const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
            const int x1 = std::min(width - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
            const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
            const int y1 = std::min(height - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
            for (int y = y0; y <= y1; ++y) {
                for (int x = x0; x <= x1; ++x) {
                    const float px = float(x) + 0.5f;
                    const float py = float(y) + 0.5f;
                    const float w0 = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) / area;
                    const float w1 = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
                    const float w2 = 1.0f - w0 - w1;
                    if (w0 < 0.0f || w1 < 0.0f || w2 < 0.0f) {
                        continue;
                    }
                    const float z = w0 * a.z + w1 * b.z + w2 * c.z;
                    const std::size_t pixel = std::size_t(y) * std::size_t(width) + std::size_t(x);
                    if (z >= depth[pixel]) {
                        continue;
                    }
                    glm::vec3 colour(base);
                    float alpha = base.a;
                    if (texture != nullptr) {
                        const glm::vec2 uv =
                            w0 * mesh.uvs[i0] + w1 * mesh.uvs[i1] + w2 * mesh.uvs[i2];
                        const float u = uv.x - std::floor(uv.x);
                        const float v = uv.y - std::floor(uv.y);
                        const int tx = std::min(texture->width - 1, int(u * float(texture->width)));
                        const int ty =
                            std::min(texture->height - 1, int(v * float(texture->height)));
                        const std::uint8_t* texel =
                            &texture->rgba[(std::size_t(ty) * std::size_t(texture->width) +
                                            std::size_t(tx)) *
                                           4];
                        colour *= glm::vec3(srgbToLinear(texel[0]), srgbToLinear(texel[1]),
                                            srgbToLinear(texel[2]));
                        alpha *= float(texel[3]) / 255.0f;
                    }
                    if (material != nullptr && material->alphaMasked &&
                        alpha < material->alphaCutoff) {
                        continue;
                    }
                    glm::vec3 normal =
                        w0 * mesh.normals[i0] + w1 * mesh.normals[i1] + w2 * mesh.normals[i2];
                    if (glm::length(normal) > 0.0f) {
                        normal = glm::normalize(normal);
                    }
                    if (glm::dot(normal, toward) < 0.0f) {
                        normal = -normal;  // light the face we see
                    }
                    if (view.lit) {
                        colour *= 0.35f + 0.9f * std::max(0.0f, glm::dot(normal, light));
                    }
                    depth[pixel] = z;
                    std::uint8_t* out = &image.rgba[pixel * 4];
                    out[0] = linearToSrgb(colour.r);
                    out[1] = linearToSrgb(colour.g);
                    out[2] = linearToSrgb(colour.b);
                    out[3] = 255;
                }
            }
        }
    }
    return image;
}

}  // namespace sylva
