#pragma once
// A scene's "joints": each joins one rigid body to the world, or two rigid bodies, by name.
#include <string>

#include "json_reader.hpp"
#include "pba/world.hpp"

namespace pba::scene_detail {

/// Reads joints[i] at `path` and adds it to the world (after its rigid bodies); returns it.
JointDesc readJoint(const Json& value, const std::string& path, const std::string& file, World& world);

} // namespace pba::scene_detail
