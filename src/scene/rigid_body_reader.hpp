#pragma once
// The `rigid_bodies` of a scene (docs/scenes.md): a shape (box, sphere, cylinder, or a closed
// triangle mesh from an OBJ file next to the scene), its density or mass, its pose and motion.
#include <filesystem>
#include <optional>
#include <set>
#include <string>

#include "json_reader.hpp"
#include "mesh_library.hpp"
#include "pba/world.hpp"

namespace pba::scene_detail {

/// `directory`: where a mesh's relative path starts (the scene file's folder); empty for a
/// built-in scene, which may not name a mesh file. `meshes`: the scene's meshes so far, which
/// bodies naming the same OBJ file share. Whether the body is drawn as a die (`"die": true`).
bool readRigidBody(const Json& value, const std::string& path, const std::string& file,
                   const std::filesystem::path& directory, World& world, std::set<std::string>& names,
                   MeshLibrary& meshes);

/// Why `shape` has no usable mass properties even at 1 kg/m^3 ("too large": its inertia
/// overflows, "too small": it underflows to zero), or nothing if it has them.
std::optional<std::string> sizeProblem(const Shape& shape);

} // namespace pba::scene_detail
