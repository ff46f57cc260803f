#include "OcclusionCuller.h"

#include <glad/gl.h>

#include <algorithm>

namespace sylva::render {

std::vector<OcclusionRing> OcclusionCuller::rings(const VegetationSettings& settings,
                                                  const std::vector<const InstanceBatch*>& batches,
                                                  const glm::dvec3& eye) {
    if (!settings.occlusionCulling || settings.occlusionRings < 1 ||
        !(settings.occluderDistance > 0.0)) {
        return {OcclusionRing{}};
    }
    const double maximum = settings.maximumDistance;
    std::vector<OcclusionRing> out;
    double start = 0.0, end = settings.occluderDistance;
    for (int k = 0; k < settings.occlusionRings; ++k) {
        OcclusionRing ring;
        ring.minimumDistance = start;
        const bool last = k + 1 == settings.occlusionRings || (maximum > 0.0 && end >= maximum);
        ring.maximumDistance = last ? 0.0 : end;
        const bool reached = std::any_of(batches.begin(), batches.end(), [&](const auto* batch) {
            const double distance =
                glm::length(batch->origin + glm::dvec3(batch->boundsCenter) - eye);
            const double radius = batch->boundsRadius;
            return distance + radius > ring.minimumDistance &&
                   (last || distance - radius <= ring.maximumDistance);
        });
        if (reached || last) {
            out.push_back(ring);
        }
        if (last) {
            break;
        }
        start = end;
        end *= std::max(settings.occlusionRingRatio, 1.0 + 1e-3);
    }
    return out;
}

const DepthPyramid& OcclusionCuller::update(int pixelsWide, int pixelsHigh,
                                            const glm::dmat4& projection, double near) {
    // Only a framebuffer object with a depth attachment has depth to read.
    GLint framebuffer = 0, type = GL_NONE;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &framebuffer);
    if (framebuffer != 0) {
        glGetNamedFramebufferAttachmentParameteriv(GLuint(framebuffer), GL_DEPTH_ATTACHMENT,
                                                   GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    }
    if (framebuffer == 0 || type == GL_NONE) {
        pyramid_.clear();
        return pyramid_;
    }
    depth_.resize(std::size_t(pixelsWide) * std::size_t(pixelsHigh));
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, pixelsWide, pixelsHigh, GL_DEPTH_COMPONENT, GL_FLOAT, depth_.data());
    pyramid_.build(depth_, pixelsWide, pixelsHigh, projection, near);
    return pyramid_;
}

}  // namespace sylva::render
