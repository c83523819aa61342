#include "pba/mesh.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace pba {

Mesh::Mesh(std::vector<glm::vec3> vertices, std::vector<glm::vec3> normals, std::vector<std::uint32_t> indices)
    : m_geometry(std::make_shared<const Geometry>(Geometry{std::move(vertices), std::move(normals), std::move(indices)}))
{
}

const Mesh::Geometry& Mesh::geometry() const
{
    static const Geometry empty;
    return m_geometry ? *m_geometry : empty;
}

Mesh Mesh::quad()
{
    // Made once: every particle's mesh shares it.
    static const Mesh quad = [] {
        const glm::vec3 n(0.0f, 0.0f, 1.0f);
        return Mesh({{-0.5f, -0.5f, 0.0f}, {0.5f, -0.5f, 0.0f}, {0.5f, 0.5f, 0.0f}, {-0.5f, 0.5f, 0.0f}},
                    {n, n, n, n}, {0, 1, 2, 0, 2, 3});
    }();
    return quad;
}

void Mesh::rotate(float angle, const glm::vec3& axis) { m_rotate = glm::rotate(m_rotate, angle, axis); }

void Mesh::scale(const glm::vec3& factors) { m_scale = glm::scale(m_scale, factors); }

} // namespace pba
