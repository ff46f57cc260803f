#include "sylva/core/plantlod/PlantRasterizer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "TexelColour.h"

namespace sylva {

namespace {}  // namespace

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

namespace {

// One mesh's look: its material (may be null), base colour and texture (when it has uvs).
struct MeshLook {
    const PlantMaterial* material = nullptr;
    glm::vec4 base{0.5f, 0.5f, 0.5f, 1.0f};
    const PlantTexture* texture = nullptr;
};

// The target of renderOrthographic: colour, depth and the projection of the view.
class OrthographicTarget {
public:
    OrthographicTarget(const OrthographicView& view, int width, int height)
        : view_(view),
          width_(width),
          height_(height),
          depth_(std::size_t(width) * std::size_t(height), std::numeric_limits<float>::max()),
          toward_(glm::cross(view.right, view.up)),
          scale_(float(width) / std::max(view.maximum.x - view.minimum.x, 1e-9f),
                 float(height) / std::max(view.maximum.y - view.minimum.y, 1e-9f)),
          light_(glm::normalize(0.5f * toward_ - 0.5f * view.right + 0.8f * view.up)) {
        image_.width = width;
        image_.height = height;
        image_.rgba.assign(std::size_t(width) * std::size_t(height) * 4, 0);
    }

    // Pixel x, y (rows from the top) and depth (smaller is nearer).
    glm::vec3 project(const glm::vec3& p) const {
        const glm::vec3 d = p - view_.origin;
        return glm::vec3((glm::dot(d, view_.right) - view_.minimum.x) * scale_.x,
                         (view_.maximum.y - glm::dot(d, view_.up)) * scale_.y,
                         -glm::dot(d, toward_));
    }

    // Triangle `t` (its first index) of a mesh: depth-tested, alpha-tested, lit.
    void drawTriangle(const PlantMesh& mesh, std::size_t t, const MeshLook& look) {
        const std::uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1],
                            i2 = mesh.indices[t + 2];
        const glm::vec3 a = project(mesh.positions[i0]);
        const glm::vec3 b = project(mesh.positions[i1]);
        const glm::vec3 c = project(mesh.positions[i2]);
        const float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        if (std::abs(area) < 1e-12f) {
            return;
        }
        const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
        const int x1 = std::min(width_ - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
        const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
        const int y1 = std::min(height_ - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
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
                const std::size_t pixel = std::size_t(y) * std::size_t(width_) + std::size_t(x);
                if (z >= depth_[pixel]) {
                    continue;
                }
                shade(mesh, {i0, i1, i2}, {w0, w1, w2}, look, z, pixel);
            }
        }
    }

    RasterImage take() { return std::move(image_); }

private:
    // The colour at barycentric `w` of the triangle `i`; nothing where alpha-tested out.
    void shade(const PlantMesh& mesh, const std::array<std::uint32_t, 3>& i, const glm::vec3& w,
               const MeshLook& look, float z, std::size_t pixel) {
        glm::vec3 colour(look.base);
        float alpha = look.base.a;
        if (look.texture != nullptr) {
            const PlantTexture& texture = *look.texture;
            const glm::vec2 uv =
                w[0] * mesh.uvs[i[0]] + w[1] * mesh.uvs[i[1]] + w[2] * mesh.uvs[i[2]];
            const float u = uv.x - std::floor(uv.x);
            const float v = uv.y - std::floor(uv.y);
            const int tx = std::min(texture.width - 1, int(u * float(texture.width)));
            const int ty = std::min(texture.height - 1, int(v * float(texture.height)));
            const std::uint8_t* texel =
                &texture.rgba[(std::size_t(ty) * std::size_t(texture.width) + std::size_t(tx)) * 4];
            colour *= glm::vec3(texelToLinear(texel[0]), texelToLinear(texel[1]),
                                texelToLinear(texel[2]));
            alpha *= float(texel[3]) / 255.0f;
        }
        if (look.material != nullptr && look.material->alphaMasked &&
            alpha < look.material->alphaCutoff) {
            return;
        }
        glm::vec3 normal =
            w[0] * mesh.normals[i[0]] + w[1] * mesh.normals[i[1]] + w[2] * mesh.normals[i[2]];
        if (glm::length(normal) > 0.0f) {
            normal = glm::normalize(normal);
        }
        if (glm::dot(normal, toward_) < 0.0f) {
            normal = -normal;  // light the face we see
        }
        if (view_.lit) {
            colour *= 0.35f + 0.9f * std::max(0.0f, glm::dot(normal, light_));
        }
        depth_[pixel] = z;
        std::uint8_t* out = &image_.rgba[pixel * 4];
        out[0] = linearToTexel(colour.r);
        out[1] = linearToTexel(colour.g);
        out[2] = linearToTexel(colour.b);
        out[3] = 255;
    }

    const OrthographicView& view_;
    int width_, height_;
    RasterImage image_;
    std::vector<float> depth_;
    glm::vec3 toward_;  // towards the eye
    glm::vec2 scale_;
    glm::vec3 light_;
};

MeshLook meshLook(const PlantModel& model, const PlantMesh& mesh) {
    MeshLook look;
    look.material = mesh.material >= 0 && std::size_t(mesh.material) < model.materials.size()
                        ? &model.materials[std::size_t(mesh.material)]
                        : nullptr;
    look.base =
        look.material != nullptr ? look.material->baseColor : glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
    look.texture =
        look.material != nullptr && look.material->baseColorTexture.width > 0 && !mesh.uvs.empty()
            ? &look.material->baseColorTexture
            : nullptr;
    return look;
}

}  // namespace

RasterImage PlantRasterizer::renderOrthographic(
    const PlantModel& model, const OrthographicView& view, int width, int height,
    const std::vector<std::vector<bool>>* triangleMask) {
    SYLVA_CHECK(width > 0 && height > 0);
    OrthographicTarget target(view, width, height);
    for (std::size_t meshIndex = 0; meshIndex < model.meshes.size(); ++meshIndex) {
        const PlantMesh& mesh = model.meshes[meshIndex];
        const MeshLook look = meshLook(model, mesh);
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            if (triangleMask != nullptr && !(*triangleMask)[meshIndex][t / 3]) {
                continue;
            }
            target.drawTriangle(mesh, t, look);
        }
    }
    return target.take();
}

}  // namespace sylva
