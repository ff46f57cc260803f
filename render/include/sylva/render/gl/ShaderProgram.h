// ShaderProgram: a linked GL program built from ShaderLibrary files (vertex + fragment,
// optionally geometry/tessellation, or a single compute shader).
//
// Ownership: move-only RAII; owns the GL program object and deletes it in the destructor,
// so it must be destroyed while its GL context is alive and current. Every call needs that
// context current on the calling thread.
//
// Failures: create() returns an Error for preprocessing errors, compile errors (the driver
// log rewritten so each message names the original file and line, e.g.
// "shaders/terrain/terrain.vert:12: error: ...") and link errors (with the link log).
// Uniform setters silently ignore names the program does not have (the GLSL compiler drops
// unused uniforms, so a missing one is normal while editing shaders).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/render/gl/GlHandle.h"
#include "sylva/render/gl/ShaderLibrary.h"

namespace sylva::render {

struct ShaderStage {
    std::uint32_t type;  // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER, ...
    std::string path;    // relative to the shaders root, e.g. "terrain/terrain.vert"
};

class ShaderProgram {
public:
    // Preprocesses each stage with `defines`, compiles and links. Stage types must be
    // distinct.
    static Result<ShaderProgram> create(const ShaderLibrary& library,
                                        const std::vector<ShaderStage>& stages,
                                        std::string_view defines = {});

    ShaderProgram() = default;  // empty: id() == 0
    // A moved-from program is empty.
    ShaderProgram(ShaderProgram&& other) noexcept;
    ShaderProgram& operator=(ShaderProgram&& other) noexcept;
    ShaderProgram(const ShaderProgram&) = delete;
    ShaderProgram& operator=(const ShaderProgram&) = delete;

    void use() const;
    std::uint32_t id() const { return program_.get(); }

    // Location of a uniform (cached after the first lookup); -1 when it does not exist.
    int uniformLocation(std::string_view name);

    // Setters work without use(): they write through glProgramUniform*.
    void setInt(std::string_view name, int value);
    void setUint(std::string_view name, std::uint32_t value);
    void setFloat(std::string_view name, float value);
    void setVec2(std::string_view name, const glm::vec2& value);
    void setVec3(std::string_view name, const glm::vec3& value);
    void setVec4(std::string_view name, const glm::vec4& value);
    void setIVec2(std::string_view name, const glm::ivec2& value);
    void setMat3(std::string_view name, const glm::mat3& value);
    void setMat4(std::string_view name, const glm::mat4& value);

private:
    explicit ShaderProgram(GlProgram program) : program_(std::move(program)) {}

    // Heterogeneous lookup so string_view names need no allocation on cache hits.
    struct NameHash {
        using is_transparent = void;
        std::size_t operator()(std::string_view name) const {
            return std::hash<std::string_view>{}(name);
        }
    };

    GlProgram program_;
    std::unordered_map<std::string, int, NameHash, std::equal_to<>> locations_;
};

}  // namespace sylva::render
