#pragma once
// The meshes of one scene: each OBJ file its bodies name is read once, however its path is
// spelt, and the bodies made from it share one shape, one set of contact points and surface
// samples, and one drawn mesh (four bodies of a 76 MB mesh used to read it four times and keep
// four copies of everything made from it).
#include <cstdint>
#include <filesystem>
#include <map>

#include "pba/rigid_body.hpp"
#include "regular_file.hpp"

namespace pba::scene_detail {

/// The largest OBJ file a scene may name.
inline constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t(256) << 20;

class MeshLibrary {
public:
    /// A body shaped as the OBJ file at `path`, at 1 kg/m^3, at rest at the origin: a copy of it
    /// shares what the shape gives (copies of a RigidBody share their form) and is then given
    /// its own mass, pose and motion. std::runtime_error saying why the file is not a usable mesh.
    const RigidBody& body(const std::filesystem::path& path);
    /// How many files have been read.
    std::size_t filesRead() const { return m_bodies.size(); }

private:
    std::map<FileIdentity, RigidBody> m_bodies;
};

} // namespace pba::scene_detail
