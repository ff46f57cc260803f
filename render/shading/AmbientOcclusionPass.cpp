#include "sylva/render/shading/AmbientOcclusionPass.h"

#include <glad/gl.h>

#include "sylva/core/base/Check.h"

namespace sylva::render {

Result<std::unique_ptr<AmbientOcclusionPass>> AmbientOcclusionPass::create(
    const ShaderLibrary& library) {
    std::unique_ptr<AmbientOcclusionPass> pass(new AmbientOcclusionPass());
    Result<ShaderProgram> occlusion =
        ShaderProgram::create(library, {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                        {GL_FRAGMENT_SHADER, "shading/ambient_occlusion.frag"}});
    if (!occlusion) {
        return occlusion.error();
    }
    Result<ShaderProgram> blur = ShaderProgram::create(
        library, {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                  {GL_FRAGMENT_SHADER, "shading/ambient_occlusion_blur.frag"}});
    if (!blur) {
        return blur.error();
    }
    pass->occlusion_ = std::move(occlusion.value());
    pass->blur_ = std::move(blur.value());
    pass->emptyVertexArray_ = createGlVertexArray();
    return pass;
}

Status AmbientOcclusionPass::ensureTargets(int width, int height) {
    if (raw_.width() == width && raw_.height() == height) {
        return Status::success();
    }
    Result<Framebuffer> raw = Framebuffer::create(width, height, {GL_R16F}, false);
    if (!raw) {
        return raw.error();
    }
    Result<Framebuffer> blurred = Framebuffer::create(width, height, {GL_R16F}, false);
    if (!blurred) {
        return blurred.error();
    }
    raw_ = std::move(raw.value());
    blurred_ = std::move(blurred.value());
    return Status::success();
}

Result<std::uint32_t> AmbientOcclusionPass::run(const Framebuffer& gbuffer,
                                                const glm::dmat4& projection, double near,
                                                const AmbientOcclusionSettings& settings) {
    SYLVA_CHECK(settings.radius > 0.0 && settings.strength >= 0.0 && settings.strength <= 1.0);
    if (Status targets = ensureTargets(gbuffer.width(), gbuffer.height()); !targets) {
        return targets.error();
    }
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glBindVertexArray(emptyVertexArray_.get());
    glBindTextureUnit(0, gbuffer.colorTexture(1));
    glBindTextureUnit(1, gbuffer.depthTexture());

    raw_.bind();
    occlusion_.use();
    occlusion_.setInt("uNormal", 0);
    occlusion_.setInt("uDepth", 1);
    occlusion_.setVec2("uProjectionScale",
                       glm::vec2(float(projection[0][0]), float(projection[1][1])));
    occlusion_.setVec2("uProjectionOffset",
                       glm::vec2(float(projection[2][0]), float(projection[2][1])));
    occlusion_.setFloat("uNear", float(near));
    occlusion_.setFloat("uRadius", float(settings.radius));
    occlusion_.setFloat("uStrength", float(settings.strength));
    occlusion_.setFloat("uMaxPixels", 0.25f * float(gbuffer.height()));
    glDrawArrays(GL_TRIANGLES, 0, 3);

    blurred_.bind();
    blur_.use();
    blur_.setInt("uNormal", 0);
    blur_.setInt("uDepth", 1);
    blur_.setInt("uOcclusion", 2);
    blur_.setVec2("uProjectionScale", glm::vec2(float(projection[0][0]), float(projection[1][1])));
    blur_.setVec2("uProjectionOffset", glm::vec2(float(projection[2][0]), float(projection[2][1])));
    blur_.setFloat("uNear", float(near));
    glBindTextureUnit(2, raw_.colorTexture(0));
    glDrawArrays(GL_TRIANGLES, 0, 3);

    glBindVertexArray(0);
    Framebuffer::unbind();
    return blurred_.colorTexture(0);
}

}  // namespace sylva::render
