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

    /// The mesh in its body's own frame: turned and scaled about the body's centre. Where the mesh
    /// is drawn is the body's business (its position, and a rigid body's orientation): the mesh
    /// keeps no position of its own.
    const glm::mat4& getRotate() const { return m_rotate; }
    const glm::mat4& getScale() const { return m_scale; }
    /// rotate * scale: the mesh's vertices in its body's frame.
    glm::mat4 getLocal() const { return m_rotate * m_scale; }

    /// Turns the mesh in its body's frame (the body does not turn).
    void rotate(float angle, const glm::vec3& axis);
    /// Scales the mesh in its body's frame (the body's mass and collisions do not change).
    void scale(const glm::vec3& factors);

private:
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
