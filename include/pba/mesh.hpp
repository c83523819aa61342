#pragma once
// A mesh as plain data: what a renderer needs to upload, nothing it needs to draw.
// The core never touches OpenGL; src/render turns this into buffers.
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

namespace pba {

class Mesh {
public:
    Mesh() = default;
    Mesh(std::vector<glm::vec3> vertices, std::vector<glm::vec3> normals, std::vector<std::uint32_t> indices);

    /// A unit square in the xy plane centred on the origin, facing +z: the practical's default mesh.
    static Mesh quad();

    const std::vector<glm::vec3>& vertices() const { return geometry().vertices; }
    const std::vector<glm::vec3>& normals() const { return geometry().normals; }
    const std::vector<std::uint32_t>& indices() const { return geometry().indices; }

    /// The translation as a matrix (the mesh keeps only its position: a body's setPos writes it
    /// every step, and 12 bytes share the body's hot cache lines where a matrix would not).
    glm::mat4 getTranslate() const
    {
        glm::mat4 t(1.0f);
        t[3] = glm::vec4(m_position, 1.0f);
        return t;
    }
    const glm::mat4& getRotate() const { return m_rotate; }
    const glm::mat4& getScale() const { return m_scale; }
    /// Model matrix: translate * rotate * scale.
    glm::mat4 getModel() const { return getTranslate() * m_rotate * m_scale; }

    glm::vec3 getPos() const { return m_position; }
    void setPos(const glm::vec3& position) { m_position = position; }
    void setPos(int i, float p) { m_position[i] = p; }

    void translate(const glm::vec3& offset);
    void rotate(float angle, const glm::vec3& axis);
    void scale(const glm::vec3& factors);

private:
    glm::vec3 m_position{0.0f}; // first: a body's setPos writes it every step
    glm::mat4 m_rotate{1.0f};
    glm::mat4 m_scale{1.0f};
    /// The vertices, normals and triangles, which never change once made: shared by every copy
    /// of the mesh (a cloth's 16,384 particles hold one quad, not 16,384, and their objects lie
    /// close together in memory). Empty for a default mesh.
    struct Geometry {
        std::vector<glm::vec3> vertices;
        std::vector<glm::vec3> normals;
        std::vector<std::uint32_t> indices;
    };
    const Geometry& geometry() const;

    std::shared_ptr<const Geometry> m_geometry;
};

} // namespace pba
