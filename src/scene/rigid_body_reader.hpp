#pragma once
// The `rigid_bodies` of a scene (docs/scenes.md): a shape (box, sphere, cylinder, or a closed
// triangle mesh from an OBJ file next to the scene), its density or mass, its pose and motion.
#include <filesystem>
#include <set>
#include <string>

#include "json_reader.hpp"
#include "pba/world.hpp"

namespace pba::scene_detail {

/// `directory`: where a mesh's relative path starts (the scene file's folder); empty for a
/// built-in scene, which may not name a mesh file.
void readRigidBody(const Json& value, const std::string& path, const std::string& file,
                   const std::filesystem::path& directory, World& world, std::set<std::string>& names);

/// The triangles of an OBJ file's `v` and `f` lines (polygons as fans; texture and normal
/// indices ignored; negative indices count back from the last vertex). std::runtime_error
/// with the line number and the reason for anything else it cannot read.
struct ObjMesh {
    std::vector<dvec3> vertices;
    std::vector<std::uint32_t> triangles;
};
ObjMesh readObj(const std::filesystem::path& path);

} // namespace pba::scene_detail
