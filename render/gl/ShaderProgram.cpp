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

// Deletes the shader objects of a program under construction on every exit path.
struct ShaderObjects {
    std::vector<GLuint> ids;
    ~ShaderObjects() {
        for (GLuint id : ids) {
            glDeleteShader(id);
        }
    }
};

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

    ShaderObjects shaders;
    for (const ShaderStage& stage : stages) {
        Result<PreprocessedShader> source = library.preprocessWithMap(stage.path, defines);
        if (!source) {
            return source.error();
        }
        const GLuint shader = glCreateShader(stage.type);
        shaders.ids.push_back(shader);
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

    ShaderProgram program(glCreateProgram());
    for (GLuint shader : shaders.ids) {
        glAttachShader(program.program_, shader);
    }
    glLinkProgram(program.program_);
    for (GLuint shader : shaders.ids) {
        glDetachShader(program.program_, shader);
    }
    GLint linked = GL_FALSE;
    glGetProgramiv(program.program_, GL_LINK_STATUS, &linked);
    if (linked != GL_TRUE) {
        return Error{"linking shader program (" + names + ") failed:\n" +
                     programLog(program.program_)};
    }
    return program;
}

ShaderProgram::~ShaderProgram() {
    if (program_ != 0) {
        glDeleteProgram(program_);
    }
}

ShaderProgram::ShaderProgram(ShaderProgram&& other) noexcept
    : program_(std::exchange(other.program_, 0)), locations_(std::move(other.locations_)) {
    other.locations_.clear();
}

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& other) noexcept {
    if (this != &other) {
        if (program_ != 0) {
            glDeleteProgram(program_);
        }
        program_ = std::exchange(other.program_, 0);
        locations_ = std::move(other.locations_);
        other.locations_.clear();
    }
    return *this;
}

void ShaderProgram::use() const {
    SYLVA_CHECK(program_ != 0);
    glUseProgram(program_);
}

int ShaderProgram::uniformLocation(std::string_view name) {
    SYLVA_CHECK(program_ != 0);
    if (auto found = locations_.find(name); found != locations_.end()) {
        return found->second;
    }
    const std::string key(name);
    const GLint location = glGetUniformLocation(program_, key.c_str());
    locations_.emplace(key, location);
    return location;
}

// A location of -1 is ignored by glProgramUniform*, as documented in the header.
void ShaderProgram::setInt(std::string_view name, int value) {
    glProgramUniform1i(program_, uniformLocation(name), value);
}

void ShaderProgram::setUint(std::string_view name, std::uint32_t value) {
    glProgramUniform1ui(program_, uniformLocation(name), value);
}

void ShaderProgram::setFloat(std::string_view name, float value) {
    glProgramUniform1f(program_, uniformLocation(name), value);
}

void ShaderProgram::setVec2(std::string_view name, const glm::vec2& value) {
    glProgramUniform2fv(program_, uniformLocation(name), 1, glm::value_ptr(value));
}

void ShaderProgram::setVec3(std::string_view name, const glm::vec3& value) {
    glProgramUniform3fv(program_, uniformLocation(name), 1, glm::value_ptr(value));
}

void ShaderProgram::setVec4(std::string_view name, const glm::vec4& value) {
    glProgramUniform4fv(program_, uniformLocation(name), 1, glm::value_ptr(value));
}

void ShaderProgram::setIVec2(std::string_view name, const glm::ivec2& value) {
    glProgramUniform2iv(program_, uniformLocation(name), 1, glm::value_ptr(value));
}

void ShaderProgram::setMat3(std::string_view name, const glm::mat3& value) {
    glProgramUniformMatrix3fv(program_, uniformLocation(name), 1, GL_FALSE, glm::value_ptr(value));
}

void ShaderProgram::setMat4(std::string_view name, const glm::mat4& value) {
    glProgramUniformMatrix4fv(program_, uniformLocation(name), 1, GL_FALSE, glm::value_ptr(value));
}

}  // namespace sylva::render
