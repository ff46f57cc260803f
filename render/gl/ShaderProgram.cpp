#include "sylva/render/gl/ShaderProgram.h"

#include <glad/gl.h>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <utility>

namespace sylva::render {
namespace {

const char* stageName(GLenum type) {
    switch (type) {
        case GL_VERTEX_SHADER:
            return "vertex";
        case GL_FRAGMENT_SHADER:
            return "fragment";
        case GL_GEOMETRY_SHADER:
            return "geometry";
        case GL_TESS_CONTROL_SHADER:
            return "tessellation control";
        case GL_TESS_EVALUATION_SHADER:
            return "tessellation evaluation";
        case GL_COMPUTE_SHADER:
            return "compute";
        default:
            return nullptr;
    }
}

std::string shaderLog(GLuint shader) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
    return log;
}

std::string programLog(GLuint program) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
    return log;
}

}  // namespace

Result<ShaderProgram> ShaderProgram::create(const ShaderLibrary& library,
                                            const std::vector<ShaderStage>& stages,
                                            std::string_view defines) {
    if (stages.empty()) {
        return Error{"ShaderProgram: no shader stages given"};
    }
    std::string names;
    for (std::size_t i = 0; i < stages.size(); ++i) {
        if (stageName(stages[i].type) == nullptr) {
            return Error{"ShaderProgram: " + stages[i].path + ": unknown shader stage type " +
                         std::to_string(stages[i].type)};
        }
        for (std::size_t j = 0; j < i; ++j) {
            if (stages[j].type == stages[i].type) {
                return Error{"ShaderProgram: two " + std::string(stageName(stages[i].type)) +
                             " shaders (" + stages[j].path + ", " + stages[i].path + ")"};
            }
        }
        names += (i == 0 ? "" : ", ") + library.displayName(stages[i].path);
    }

    std::vector<GlShader> shaders;  // deleted on every exit path
    for (const ShaderStage& stage : stages) {
        Result<PreprocessedShader> source = library.preprocessWithMap(stage.path, defines);
        if (!source) {
            return source.error();
        }
        const GLuint shader = shaders.emplace_back(createGlShader(stage.type)).get();
        const char* text = source->source.c_str();
        const auto length = static_cast<GLint>(source->source.size());
        glShaderSource(shader, 1, &text, &length);
        glCompileShader(shader);
        GLint compiled = GL_FALSE;
        glGetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
        if (compiled != GL_TRUE) {
            return Error{"compiling " + std::string(stageName(stage.type)) + " shader " +
                         library.displayName(stage.path) + " failed:\n" +
                         source->translateLog(shaderLog(shader))};
        }
    }

    ShaderProgram program(createGlProgram());
    const GLuint id = program.id();
    for (const GlShader& shader : shaders) {
        glAttachShader(id, shader.get());
    }
    glLinkProgram(id);
    for (const GlShader& shader : shaders) {
        glDetachShader(id, shader.get());
    }
    GLint linked = GL_FALSE;
    glGetProgramiv(id, GL_LINK_STATUS, &linked);
    if (linked != GL_TRUE) {
        return Error{"linking shader program (" + names + ") failed:\n" + programLog(id)};
    }
    return program;
}

ShaderProgram::ShaderProgram(ShaderProgram&& other) noexcept
    : program_(std::move(other.program_)), locations_(std::exchange(other.locations_, {})) {}

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& other) noexcept {
    if (this != &other) {
        program_ = std::move(other.program_);  // deletes the program this one owned
        locations_ = std::exchange(other.locations_, {});
    }
    return *this;
}

void ShaderProgram::use() const {
    SYLVA_CHECK(program_);
    glUseProgram(program_.get());
}

int ShaderProgram::uniformLocation(std::string_view name) {
    SYLVA_CHECK(program_);
    if (auto found = locations_.find(name); found != locations_.end()) {
        return found->second;
    }
    const std::string key(name);
    const GLint location = glGetUniformLocation(program_.get(), key.c_str());
    locations_.emplace(key, location);
    return location;
}

// A location of -1 is ignored by glProgramUniform*, as documented in the header.
void ShaderProgram::setInt(std::string_view name, int value) {
    glProgramUniform1i(program_.get(), uniformLocation(name), value);
}

void ShaderProgram::setUint(std::string_view name, std::uint32_t value) {
    glProgramUniform1ui(program_.get(), uniformLocation(name), value);
}

void ShaderProgram::setFloat(std::string_view name, float value) {
    glProgramUniform1f(program_.get(), uniformLocation(name), value);
}

void ShaderProgram::setVec2(std::string_view name, const glm::vec2& value) {
    glProgramUniform2fv(program_.get(), uniformLocation(name), 1, glm::value_ptr(value));
}

void ShaderProgram::setVec3(std::string_view name, const glm::vec3& value) {
    glProgramUniform3fv(program_.get(), uniformLocation(name), 1, glm::value_ptr(value));
}

void ShaderProgram::setVec4(std::string_view name, const glm::vec4& value) {
    glProgramUniform4fv(program_.get(), uniformLocation(name), 1, glm::value_ptr(value));
}

void ShaderProgram::setIVec2(std::string_view name, const glm::ivec2& value) {
    glProgramUniform2iv(program_.get(), uniformLocation(name), 1, glm::value_ptr(value));
}

void ShaderProgram::setMat3(std::string_view name, const glm::mat3& value) {
    glProgramUniformMatrix3fv(program_.get(), uniformLocation(name), 1, GL_FALSE,
                              glm::value_ptr(value));
}

void ShaderProgram::setMat4(std::string_view name, const glm::mat4& value) {
    glProgramUniformMatrix4fv(program_.get(), uniformLocation(name), 1, GL_FALSE,
                              glm::value_ptr(value));
}

}  // namespace sylva::render
