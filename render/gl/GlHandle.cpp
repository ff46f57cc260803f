#include "sylva/render/gl/GlHandle.h"

#include <glad/gl.h>

namespace sylva::render {

// The only glDelete* calls of the renderer: every GL object is owned by a GlHandle.
void GlDelete::buffer(std::uint32_t id) {
    glDeleteBuffers(1, &id);
}

void GlDelete::vertexArray(std::uint32_t id) {
    glDeleteVertexArrays(1, &id);
}

void GlDelete::texture(std::uint32_t id) {
    glDeleteTextures(1, &id);
}

void GlDelete::framebuffer(std::uint32_t id) {
    glDeleteFramebuffers(1, &id);
}

void GlDelete::program(std::uint32_t id) {
    glDeleteProgram(id);
}

void GlDelete::shader(std::uint32_t id) {
    glDeleteShader(id);
}

GlBuffer createGlBuffer() {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    return GlBuffer(id);
}

GlVertexArray createGlVertexArray() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return GlVertexArray(id);
}

GlTexture createGlTexture(std::uint32_t target) {
    GLuint id = 0;
    glCreateTextures(target, 1, &id);
    return GlTexture(id);
}

GlFramebuffer createGlFramebuffer() {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    return GlFramebuffer(id);
}

GlProgram createGlProgram() {
    return GlProgram(glCreateProgram());
}

GlShader createGlShader(std::uint32_t type) {
    return GlShader(glCreateShader(type));
}

}  // namespace sylva::render
