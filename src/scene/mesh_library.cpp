#include "mesh_library.hpp"

#include <stdexcept>

#include "obj_reader.hpp"
#include "rigid_body_reader.hpp"

namespace pba::scene_detail {

const RigidBody& MeshLibrary::body(const std::filesystem::path& path)
{
    RegularFile file(path, kMaxMeshFileBytes);
    if (const auto known = m_bodies.find(file.identity()); known != m_bodies.end())
        return known->second;
    ObjMesh obj = parseObj(file.read());
    const Shape shape = Shape::mesh(std::move(obj.vertices), std::move(obj.triangles));
    try {
        return m_bodies.emplace(file.identity(), RigidBody(shape, 1.0)).first->second;
    } catch (const std::invalid_argument& error) {
        throw std::runtime_error(sizeProblem(shape).value_or(error.what()));
    }
}

} // namespace pba::scene_detail
