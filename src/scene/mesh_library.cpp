#include "mesh_library.hpp"

#include "obj_reader.hpp"

namespace pba::scene_detail {

const RigidBody& MeshLibrary::body(const std::filesystem::path& path)
{
    RegularFile file(path, kMaxMeshFileBytes);
    if (const auto known = m_bodies.find(file.identity()); known != m_bodies.end())
        return known->second;
    ObjMesh obj = parseObj(file.read());
    const Shape shape = Shape::mesh(std::move(obj.vertices), std::move(obj.triangles));
    return m_bodies.emplace(file.identity(), RigidBody(shape, 1.0)).first->second;
}

} // namespace pba::scene_detail
