#include "pba/mesh.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace pba {

Mesh::Mesh(std::vector<glm::vec3> vertices, std::vector<glm::vec3> normals, std::vector<std::uint32_t> indices)
    : m_vertices(std::move(vertices)), m_normals(std::move(normals)), m_indices(std::move(indices))
{
}

Mesh Mesh::quad()
{
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    return Mesh({{-0.5f, -0.5f, 0.0f}, {0.5f, -0.5f, 0.0f}, {0.5f, 0.5f, 0.0f}, {-0.5f, 0.5f, 0.0f}},
                {n, n, n, n}, {0, 1, 2, 0, 2, 3});
}

void Mesh::translate(const glm::vec3& offset) { m_position += offset; }

void Mesh::rotate(float angle, const glm::vec3& axis) { m_rotate = glm::rotate(m_rotate, angle, axis); }

void Mesh::scale(const glm::vec3& factors) { m_scale = glm::scale(m_scale, factors); }

} // namespace pba
