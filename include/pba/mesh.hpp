#pragma once
// A mesh as plain data: what a renderer needs to upload, nothing it needs to draw.
// The core never touches OpenGL; src/render turns this into buffers.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace pba {

class Mesh {
public:
    Mesh() = default;
    Mesh(std::vector<glm::vec3> vertices, std::vector<glm::vec3> normals, std::vector<std::uint32_t> indices);

    /// A unit square in the xy plane centred on the origin, facing +z: the practical's default mesh.
    static Mesh quad();

    const std::vector<glm::vec3>& vertices() const { return m_vertices; }
    const std::vector<glm::vec3>& normals() const { return m_normals; }
    const std::vector<std::uint32_t>& indices() const { return m_indices; }

    const glm::mat4& getTranslate() const { return m_translate; }
    const glm::mat4& getRotate() const { return m_rotate; }
    const glm::mat4& getScale() const { return m_scale; }
    /// Model matrix: translate * rotate * scale.
    glm::mat4 getModel() const { return m_translate * m_rotate * m_scale; }

    glm::vec3 getPos() const { return glm::vec3(m_translate[3]); }
    void setPos(const glm::vec3& position) { m_translate[3] = glm::vec4(position, 1.0f); }
    void setPos(int i, float p) { m_translate[3][i] = p; }

    void translate(const glm::vec3& offset);
    void rotate(float angle, const glm::vec3& axis);
    void scale(const glm::vec3& factors);

private:
    glm::mat4 m_translate{1.0f}; // first: a body's setPos writes it every step
    glm::mat4 m_rotate{1.0f};
    glm::mat4 m_scale{1.0f};
    std::vector<glm::vec3> m_vertices;
    std::vector<glm::vec3> m_normals;
    std::vector<std::uint32_t> m_indices;
};

} // namespace pba
