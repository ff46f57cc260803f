// GlHandle: a move-only owner of one GL object name (buffer, vertex array, texture,
// framebuffer, program or shader), templated on the call that deletes it.
//
// Ownership: the handle deletes its object in the destructor and when it is assigned
// another (or reset); a moved-from handle is empty (get() == 0) and deletes nothing; name 0
// is never deleted. Copies are not possible. Deleting needs the object's GL context (or one
// sharing its objects) current on the calling thread, so a handle must be destroyed or
// reset before its context goes away.
//
// The delete calls live in GlHandle.cpp, so this header (and every public header holding
// handles) stays free of GL headers, like the rest of render/include. Nothing here fails:
// glDelete* ignores unknown names and GL reports no errors for them.
#pragma once

#include <cstdint>
#include <utility>

namespace sylva::render {

// The glDelete* call of each object kind, for one name (defined in GlHandle.cpp).
struct GlDelete {
    static void buffer(std::uint32_t id);
    static void vertexArray(std::uint32_t id);
    static void texture(std::uint32_t id);
    static void framebuffer(std::uint32_t id);
    static void program(std::uint32_t id);
    static void shader(std::uint32_t id);
};

template <void (*Delete)(std::uint32_t)>
class GlHandle {
public:
    GlHandle() = default;  // empty
    // Takes ownership of `id` (0: empty).
    explicit GlHandle(std::uint32_t id) : id_(id) {}
    ~GlHandle() { reset(); }

    GlHandle(GlHandle&& other) noexcept : id_(other.release()) {}
    GlHandle& operator=(GlHandle&& other) noexcept {
        if (this != &other) {
            reset(other.release());
        }
        return *this;
    }
    GlHandle(const GlHandle&) = delete;
    GlHandle& operator=(const GlHandle&) = delete;

    std::uint32_t get() const { return id_; }
    explicit operator bool() const { return id_ != 0; }

    // Gives up ownership without deleting; the handle is empty afterwards.
    std::uint32_t release() { return std::exchange(id_, 0); }
    // Deletes the owned object (if any) and owns `id` instead.
    void reset(std::uint32_t id = 0) {
        if (id_ != 0) {
            Delete(id_);
        }
        id_ = id;
    }

private:
    std::uint32_t id_ = 0;
};

using GlBuffer = GlHandle<&GlDelete::buffer>;
using GlVertexArray = GlHandle<&GlDelete::vertexArray>;
using GlTexture = GlHandle<&GlDelete::texture>;
using GlFramebuffer = GlHandle<&GlDelete::framebuffer>;
using GlProgram = GlHandle<&GlDelete::program>;
using GlShader = GlHandle<&GlDelete::shader>;

// New objects through the GL 4.5 glCreate* calls (the names exist as objects at once, so
// glIs* is true and direct-state-access calls work without binding). `target` is the
// texture target (GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY, ...), `type` the shader stage
// (GL_VERTEX_SHADER, ...). A GL context must be current.
GlBuffer createGlBuffer();
GlVertexArray createGlVertexArray();
GlTexture createGlTexture(std::uint32_t target);
GlFramebuffer createGlFramebuffer();
GlProgram createGlProgram();
GlShader createGlShader(std::uint32_t type);

}  // namespace sylva::render
