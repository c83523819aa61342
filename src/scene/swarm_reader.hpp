#pragma once
// The `swarms` of a scene (docs/scenes.md): particles by the thousand or million, stored as
// float arrays, so every number of theirs must fit a float (their memory: memory_estimate.hpp).
#include <set>
#include <string>

#include "json_reader.hpp"
#include "pba/world.hpp"

namespace pba::scene_detail {

/// Swarms compute in single precision: a number of theirs must be a normal float (and 1/m too),
/// or the first step would turn it into an infinity or zero.
constexpr double kFloatMax = 3.4028234663852886e38;
constexpr double kFloatMin = 1.1754943508222875e-38;

bool fitsFloat(double x);

/// One entry of `swarms`, added to the world; its name must be new to `names`.
void readSwarm(const Json& value, const std::string& path, const std::string& file, World& world,
               std::set<std::string>& names);

/// A scene with swarms: the fields that act on them (gravity, drag, blow dryers), turned into
/// each swarm's accelerations in float, must stay finite.
bool swarmFieldsFit(const World& world);

} // namespace pba::scene_detail
