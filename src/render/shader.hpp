#pragma once
#include <string>

#include <glm/glm.hpp>

namespace pba::render {

/// A linked GLSL program. Compile and link failures throw RenderError with the shader's
/// name, its stage and the driver's log.
class Shader {
public:
    Shader(std::string name, const char* vertexSource, const char* fragmentSource);
    ~Shader();
    Shader(const Shader&) = delete;
    Shader& operator=(const Shader&) = delete;

    void use() const;
    void set(const char* uniform, const glm::mat4& value) const;
    void set(const char* uniform, const glm::vec3& value) const;
    void set(const char* uniform, const glm::vec4& value) const;
    void set(const char* uniform, float value) const;
    const std::string& name() const { return m_name; }

private:
    int location(const char* uniform) const;
    std::string m_name;
    unsigned m_program = 0;
};

} // namespace pba::render
