#include "sylva/core/plantlod/PrimitiveRasterizer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "TexelColour.h"
#include "sylva/core/base/Check.h"
#include "sylva/core/plantlod/EllipsoidNoise.h"

namespace sylva {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

float luminance(const glm::vec3& c) {
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

// A material prepared for drawing: linear luminance and alpha per texel.
struct PreparedMaterial {
    float baseLuminance = 0.5f;
    float baseAlpha = 1.0f;
    bool masked = false;
    float cutoff = 0.5f;
    int width = 0, height = 0;
    std::vector<float> luminance;
    std::vector<float> alpha;
};

PreparedMaterial prepare(const PlantModel& model, int index) {
    PreparedMaterial prepared;
    if (index < 0 || index >= static_cast<int>(model.materials.size())) {
        return prepared;
    }
    const PlantMaterial& material = model.materials[index];
    prepared.baseLuminance = luminance(glm::vec3(material.baseColor));
    prepared.baseAlpha = material.baseColor.a;
    prepared.masked = material.alphaMasked;
    prepared.cutoff = material.alphaCutoff;
    const PlantTexture& texture = material.baseColorTexture;
    if (texture.width > 0 && texture.height > 0 &&
        texture.rgba.size() == static_cast<std::size_t>(texture.width) * texture.height * 4) {
        prepared.width = texture.width;
        prepared.height = texture.height;
        const glm::vec3 base(material.baseColor);
        for (std::size_t i = 0; i < texture.rgba.size(); i += 4) {
            const glm::vec3 c(texelToLinear(texture.rgba[i]), texelToLinear(texture.rgba[i + 1]),
                              texelToLinear(texture.rgba[i + 2]));
            prepared.luminance.push_back(luminance(c * base));
            prepared.alpha.push_back(texture.rgba[i + 3] / 255.0f);
        }
    }
    return prepared;
}

}  // namespace

PrimitiveRasterizer::PrimitiveRasterizer(const glm::vec3& boundsMinimum,
                                         const glm::vec3& boundsMaximum, int resolution,
                                         int viewCount, int supersampling)
    : center_(0.5f * (boundsMinimum + boundsMaximum)),
      radius_(std::max(0.5f * glm::length(boundsMaximum - boundsMinimum), 1e-3f)),
      resolution_(resolution),
      supersampling_(supersampling) {
    SYLVA_CHECK(resolution > 0 && viewCount > 0 && supersampling > 0);
    const int around = std::max(1, viewCount * 3 / 4);
    for (int i = 0; i < viewCount; ++i) {
        const bool high = i >= around;
        const int slot = high ? i - around : i;
        const int slots = high ? viewCount - around : around;
        const float azimuth =
            2.0f * std::numbers::pi_v<float> * (slot + (high ? 0.5f : 0.0f)) / slots;
        const float elevation = glm::radians(high ? 55.0f : 10.0f);
        const glm::vec3 toViewer(std::cos(elevation) * std::cos(azimuth),
                                 std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
        View view;
        view.forward = -toViewer;
        view.right = glm::normalize(glm::cross(view.forward, glm::vec3(0, 0, 1)));
        view.up = glm::cross(view.right, view.forward);
        views_.push_back(view);
    }
}

glm::vec3 PrimitiveRasterizer::toView(const glm::vec3& p, int view) const {
    const View& v = views_[view];
    const glm::vec3 d = p - center_;
    return {glm::dot(d, v.right), glm::dot(d, v.up), glm::dot(d, v.forward)};
}

RasterFrame PrimitiveRasterizer::blankFrame(const PixelRect& rect) const {
    RasterFrame frame;
    frame.rect = rect;
    frame.value.assign(
        static_cast<std::size_t>(std::max(rect.x1 - rect.x0, 0)) * std::max(rect.y1 - rect.y0, 0),
        0.0f);
    frame.depth.assign(frame.value.size(), kInfinity);
    return frame;
}

void PrimitiveRasterizer::drawEllipsoids(std::span<const LodEllipsoid> ellipsoids, int view,
                                         RasterFrame& frame, const EllipsoidStyle& style) const {
    const View& v = views_[view];
    const PixelRect& f = frame.rect;
    const int width = frame.width();
    const float pixel = renderPixelSize();
    for (const LodEllipsoid& e : ellipsoids) {
        glm::vec3 radii = e.radii * style.scale;
        const float largest = std::max({radii.x, radii.y, radii.z});
        if (!(largest > 0.0f)) {
            continue;
        }
        radii = glm::max(radii, glm::vec3(largest * 1e-3f));
        // Unit-sphere coordinates: q = A (x − c) with A = diag(1/r) Rᵀ.
        glm::vec3 a, b, g;
        float halfU = 0.0f, halfV = 0.0f;
        for (int i = 0; i < 3; ++i) {
            a[i] = glm::dot(e.axes[i], v.right) / radii[i];
            b[i] = glm::dot(e.axes[i], v.up) / radii[i];
            g[i] = glm::dot(e.axes[i], v.forward) / radii[i];
            halfU += std::pow(radii[i] * glm::dot(e.axes[i], v.right), 2.0f);
            halfV += std::pow(radii[i] * glm::dot(e.axes[i], v.up), 2.0f);
        }
        halfU = std::sqrt(halfU);
        halfV = std::sqrt(halfV);
        const glm::vec3 c = toView(e.center, view);
        const float gg = glm::dot(g, g);
        const float threshold =
            style.alphaThreshold >= 0.0f ? style.alphaThreshold : e.alphaThreshold;
        const std::uint32_t seed = ellipsoidNoiseSeed(e.center);
        const float cells = std::exp2(e.noiseLevel);
        const float value = luminance(e.color);
        const int x0 =
            std::max(f.x0, static_cast<int>(std::floor((c.x - halfU + radius_) / pixel - 0.5f)));
        const int x1 =
            std::min(f.x1, static_cast<int>(std::ceil((c.x + halfU + radius_) / pixel + 0.5f)));
        const int y0 =
            std::max(f.y0, static_cast<int>(std::floor((radius_ - c.y - halfV) / pixel - 0.5f)));
        const int y1 =
            std::min(f.y1, static_cast<int>(std::ceil((radius_ - c.y + halfV) / pixel + 0.5f)));
        for (int y = y0; y < y1; ++y) {
            const float dv = radius_ - (y + 0.5f) * pixel - c.y;
            for (int x = x0; x < x1; ++x) {
                const float du = (x + 0.5f) * pixel - radius_ - c.x;
                const glm::vec3 p0 = du * a + dv * b;
                const float pg = glm::dot(p0, g);
                const float disc = pg * pg - gg * (glm::dot(p0, p0) - 1.0f);
                if (disc < 0.0f) {
                    continue;
                }
                const float root = std::sqrt(disc);
                float s = (-pg - root) / gg;
                const std::size_t at = static_cast<std::size_t>(y - f.y0) * width + (x - f.x0);
                if (c.z + s >= frame.depth[at]) {
                    continue;
                }
                if (threshold > 0.0f && ellipsoidNoiseCells(p0 + s * g, cells, seed) < threshold) {
                    s = (-pg + root) / gg;  // perforated front: try the back
                    if (c.z + s >= frame.depth[at] ||
                        ellipsoidNoiseCells(p0 + s * g, cells, seed) < threshold) {
                        continue;
                    }
                }
                frame.depth[at] = c.z + s;
                frame.value[at] = value;
            }
        }
    }
}

void PrimitiveRasterizer::clearFrame(RasterFrame& frame) const {
    frame.rect = fullRect();
    const std::size_t pixels = static_cast<std::size_t>(renderSize()) * renderSize();
    frame.value.assign(pixels, 0.0f);
    frame.depth.assign(pixels, kInfinity);
}

PixelRect PrimitiveRasterizer::lineBounds(const LodLine& line, int view, float widthScale) const {
    const float pixel = renderPixelSize();
    const glm::vec3 p = toView(line.start, view);
    const glm::vec3 q = toView(line.end, view);
    const float r = std::max(std::max(line.startRadius, line.endRadius) * widthScale, 0.5f * pixel);
    const int size = renderSize();
    PixelRect rect;
    rect.x0 = std::clamp(
        static_cast<int>(std::floor((std::min(p.x, q.x) - r + radius_) / pixel - 0.5f)), 0, size);
    rect.x1 = std::clamp(
        static_cast<int>(std::ceil((std::max(p.x, q.x) + r + radius_) / pixel + 0.5f)), 0, size);
    rect.y0 = std::clamp(
        static_cast<int>(std::floor((radius_ - std::max(p.y, q.y) - r) / pixel - 0.5f)), 0, size);
    rect.y1 = std::clamp(
        static_cast<int>(std::ceil((radius_ - std::min(p.y, q.y) + r) / pixel + 0.5f)), 0, size);
    return rect;
}

void PrimitiveRasterizer::drawLines(std::span<const LodLine> lines, int view, RasterFrame& frame,
                                    float widthScale) const {
    for (const LodLine& line : lines) {
        drawLine(line, view, frame, widthScale);
    }
}

void PrimitiveRasterizer::drawLine(const LodLine& line, int view, RasterFrame& frame,
                                   float widthScale) const {
    const PixelRect& f = frame.rect;
    const int width = frame.width();
    const float pixel = renderPixelSize();
    const float halfPixel = 0.5f * pixel;
    PixelRect rect = lineBounds(line, view, widthScale);
    rect.x0 = std::max(rect.x0, f.x0);
    rect.y0 = std::max(rect.y0, f.y0);
    rect.x1 = std::min(rect.x1, f.x1);
    rect.y1 = std::min(rect.y1, f.y1);
    if (rect.empty()) {
        return;
    }
    const glm::vec3 p = toView(line.start, view);
    const glm::vec3 q = toView(line.end, view);
    const glm::vec2 e(q.x - p.x, q.y - p.y);
    const float ee = glm::dot(e, e);
    const float value = luminance(line.color);
    const float r0 = line.startRadius * widthScale;
    const float r1 = line.endRadius * widthScale;
    // Per row, only the columns near the part of the axis within reach of the row (the
    // capsule lies within maxReach of its axis): a diagonal line covers a small part of
    // its bounding rectangle. A pixel of margin on each side keeps rounding harmless, so
    // the drawn pixels are exactly those of the full-rectangle loop.
    const float maxReach = std::max({r0, r1, halfPixel});
    for (int y = rect.y0; y < rect.y1; ++y) {
        const float v = radius_ - (y + 0.5f) * pixel;
        float t0 = 0.0f, t1 = 1.0f;
        if (std::abs(e.y) > 1e-12f) {
            t0 = (v - maxReach - p.y) / e.y;
            t1 = (v + maxReach - p.y) / e.y;
            if (t0 > t1) {
                std::swap(t0, t1);
            }
            t0 = std::max(t0, 0.0f);
            t1 = std::min(t1, 1.0f);
            if (t0 > t1) {
                continue;
            }
        } else if (std::abs(p.y - v) > maxReach) {
            continue;
        }
        const float xa = p.x + t0 * e.x, xb = p.x + t1 * e.x;
        const float left = (std::min(xa, xb) - maxReach + radius_) / pixel - 0.5f;
        const float right = (std::max(xa, xb) + maxReach + radius_) / pixel - 0.5f;
        const int xBegin = std::max(rect.x0, static_cast<int>(std::floor(left)) - 1);
        const int xEnd = std::min(rect.x1, static_cast<int>(std::ceil(right)) + 2);
        for (int x = xBegin; x < xEnd; ++x) {
            const glm::vec2 w((x + 0.5f) * pixel - radius_ - p.x, v - p.y);
            const float t = ee > 0.0f ? std::clamp(glm::dot(w, e) / ee, 0.0f, 1.0f) : 0.0f;
            const glm::vec2 off = w - t * e;
            const float distance2 = glm::dot(off, off);
            const float r = r0 + t * (r1 - r0);
            const float drawn = std::max(r, halfPixel);
            if (distance2 > drawn * drawn) {
                continue;
            }
            const float depth =
                p.z + t * (q.z - p.z) - std::sqrt(std::max(r * r - distance2, 0.0f));
            const std::size_t at = static_cast<std::size_t>(y - f.y0) * width + (x - f.x0);
            if (depth >= frame.depth[at]) {
                continue;
            }
            const float coverage = r / drawn;
            if (coverage >= 1.0f) {
                frame.depth[at] = depth;
                frame.value[at] = value;
            } else {
                frame.value[at] += coverage * (value - frame.value[at]);
            }
        }
    }
}

void PrimitiveRasterizer::drawMesh(const PlantModel& model, PlantPart part, bool includeAll,
                                   int view, RasterFrame& frame) const {
    const PixelRect& f = frame.rect;
    const int width = frame.width();
    const float pixel = renderPixelSize();
    for (const PlantMesh& mesh : model.meshes) {
        if (!includeAll && mesh.part != part) {
            continue;
        }
        const PreparedMaterial material = prepare(model, mesh.material);
        const bool textured = material.width > 0 && mesh.uvs.size() == mesh.positions.size();
        std::vector<glm::vec3> projected(mesh.positions.size());
        for (std::size_t i = 0; i < projected.size(); ++i) {
            const glm::vec3 p = toView(mesh.positions[i], view);
            projected[i] = {(p.x + radius_) / pixel, (radius_ - p.y) / pixel, p.z};
        }
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            const std::uint32_t ia = mesh.indices[t], ib = mesh.indices[t + 1],
                                ic = mesh.indices[t + 2];
            if (ia >= projected.size() || ib >= projected.size() || ic >= projected.size()) {
                continue;
            }
            const glm::vec3 A = projected[ia], B = projected[ib], C = projected[ic];
            const float area = (B.x - A.x) * (C.y - A.y) - (B.y - A.y) * (C.x - A.x);
            if (std::abs(area) < 1e-12f) {
                continue;
            }
            const int x0 = std::max(f.x0, static_cast<int>(std::floor(std::min({A.x, B.x, C.x}))));
            const int x1 =
                std::min(f.x1, static_cast<int>(std::ceil(std::max({A.x, B.x, C.x}))) + 1);
            const int y0 = std::max(f.y0, static_cast<int>(std::floor(std::min({A.y, B.y, C.y}))));
            const int y1 =
                std::min(f.y1, static_cast<int>(std::ceil(std::max({A.y, B.y, C.y}))) + 1);
            for (int y = y0; y < y1; ++y) {
                const float py = y + 0.5f;
                for (int x = x0; x < x1; ++x) {
                    const float px = x + 0.5f;
                    const float wa = ((B.x - px) * (C.y - py) - (B.y - py) * (C.x - px)) / area;
                    const float wb = ((C.x - px) * (A.y - py) - (C.y - py) * (A.x - px)) / area;
                    const float wc = 1.0f - wa - wb;
                    if (wa < 0.0f || wb < 0.0f || wc < 0.0f) {
                        continue;
                    }
                    const float depth = wa * A.z + wb * B.z + wc * C.z;
                    const std::size_t at = static_cast<std::size_t>(y - f.y0) * width + (x - f.x0);
                    if (depth >= frame.depth[at]) {
                        continue;
                    }
                    float value = material.baseLuminance;
                    float alpha = material.baseAlpha;
                    if (textured) {
                        const glm::vec2 uv =
                            wa * mesh.uvs[ia] + wb * mesh.uvs[ib] + wc * mesh.uvs[ic];
                        const float fu = uv.x - std::floor(uv.x);
                        const float fv = uv.y - std::floor(uv.y);
                        const int tx =
                            std::min(material.width - 1, static_cast<int>(fu * material.width));
                        const int ty =
                            std::min(material.height - 1, static_cast<int>(fv * material.height));
                        const std::size_t texel =
                            static_cast<std::size_t>(ty) * material.width + tx;
                        value = material.luminance[texel];
                        alpha *= material.alpha[texel];
                    }
                    if (material.masked && alpha < material.cutoff) {
                        continue;
                    }
                    frame.depth[at] = depth;
                    frame.value[at] = value;
                }
            }
        }
    }
}

std::vector<float> PrimitiveRasterizer::resolve(const RasterFrame& frame) const {
    SYLVA_CHECK(frame.rect.x0 == 0 && frame.rect.y0 == 0 && frame.width() == renderSize());
    const int s = supersampling_;
    std::vector<float> out(static_cast<std::size_t>(resolution_) * resolution_, 0.0f);
    const float scale = 1.0f / static_cast<float>(s * s);
    for (int y = 0; y < resolution_; ++y) {
        for (int x = 0; x < resolution_; ++x) {
            float sum = 0.0f;
            for (int j = 0; j < s; ++j) {
                for (int i = 0; i < s; ++i) {
                    sum +=
                        frame
                            .value[static_cast<std::size_t>(y * s + j) * frame.width() + x * s + i];
                }
            }
            out[static_cast<std::size_t>(y) * resolution_ + x] = sum * scale;
        }
    }
    return out;
}

}  // namespace sylva
