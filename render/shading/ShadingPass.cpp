#include "sylva/render/shading/ShadingPass.h"

#include <glad/gl.h>

namespace sylva::render {

Result<std::unique_ptr<ShadingPass>> ShadingPass::create(const ShaderLibrary& library) {
    std::unique_ptr<ShadingPass> pass(new ShadingPass());
    Result<ShaderProgram> program = ShaderProgram::create(
        library,
        {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "shading/shade.frag"}});
    if (!program) {
        return program.error();
    }
    pass->program_ = std::move(program.value());
    pass->emptyVertexArray_ = createGlVertexArray();
    return pass;
}

void ShadingPass::run(const Framebuffer& gbuffer, const Framebuffer& target, const Camera& camera,
                      const glm::dmat4& projection, double near, const ShadingSettings& settings) {
    target.bind();
    glDisable(GL_DEPTH_TEST);
    program_.use();
    const glm::dmat3 view = camera.viewRotation();
    program_.setInt("uAlbedo", 0);
    program_.setInt("uNormal", 1);
    program_.setInt("uDepth", 2);
    program_.setVec2("uProjectionScale",
                     glm::vec2(float(projection[0][0]), float(projection[1][1])));
    program_.setVec2("uProjectionOffset",
                     glm::vec2(float(projection[2][0]), float(projection[2][1])));
    program_.setFloat("uNear", float(near));
    program_.setMat3("uViewToEcef", glm::mat3(glm::transpose(view)));
    program_.setVec3("uCameraEcef", glm::vec3(camera.position));
    program_.setVec3("uSunView", glm::vec3(glm::normalize(view * settings.sunDirection)));
    program_.setVec3("uSunEcef", glm::vec3(glm::normalize(settings.sunDirection)));
    program_.setInt("uAtmosphere", settings.atmosphere ? 1 : 0);
    program_.setFloat("uExposure", float(settings.exposure));
    glBindTextureUnit(0, gbuffer.colorTexture(0));
    glBindTextureUnit(1, gbuffer.colorTexture(1));
    glBindTextureUnit(2, gbuffer.depthTexture());
    glBindVertexArray(emptyVertexArray_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
}

}  // namespace sylva::render
