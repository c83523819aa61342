#include "shader.hpp"

#include <epoxy/gl.h>

#include <fmt/format.h>
#include <glm/gtc/type_ptr.hpp>

#include "gl_context.hpp"

namespace pba::render {

namespace {

unsigned compile(const std::string& name, GLenum stage, const char* source)
{
    const unsigned shader = glCreateShader(stage);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        glDeleteShader(shader);
        throw RenderError(fmt::format("shader '{}': the {} stage does not compile: {}", name,
                                      stage == GL_VERTEX_SHADER ? "vertex" : "fragment", log));
    }
    return shader;
}

} // namespace

Shader::Shader(std::string name, const char* vertexSource, const char* fragmentSource) : m_name(std::move(name))
{
    const unsigned vs = compile(m_name, GL_VERTEX_SHADER, vertexSource);
    unsigned fs = 0;
    try {
        fs = compile(m_name, GL_FRAGMENT_SHADER, fragmentSource);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    m_program = glCreateProgram();
    glAttachShader(m_program, vs);
    glAttachShader(m_program, fs);
    glLinkProgram(m_program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = GL_FALSE;
    glGetProgramiv(m_program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetProgramInfoLog(m_program, sizeof log, nullptr, log);
        glDeleteProgram(m_program);
        throw RenderError(fmt::format("shader '{}': the program does not link: {}", m_name, log));
    }
}

Shader::~Shader() { glDeleteProgram(m_program); }

void Shader::use() const { glUseProgram(m_program); }

int Shader::location(const char* uniform) const { return glGetUniformLocation(m_program, uniform); }

void Shader::set(const char* uniform, const glm::mat4& value) const
{
    glUniformMatrix4fv(location(uniform), 1, GL_FALSE, glm::value_ptr(value));
}

void Shader::set(const char* uniform, const glm::vec3& value) const { glUniform3fv(location(uniform), 1, glm::value_ptr(value)); }

void Shader::set(const char* uniform, const glm::vec4& value) const { glUniform4fv(location(uniform), 1, glm::value_ptr(value)); }

void Shader::set(const char* uniform, float value) const { glUniform1f(location(uniform), value); }

} // namespace pba::render
