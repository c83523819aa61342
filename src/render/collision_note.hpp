#pragma once
// What the legend says about collisions: the rule each kind of body in this scene meets the
// surfaces with, and a word about semi-implicit Euler only where a body that the rule applies to
// uses it. Plain text, no ImGui, so it is tested as text.
#include <string>

#include "pba/world.hpp"

namespace pba::render {

/// "collisions: ..." for the world's bodies and swarms; empty when nothing can collide (no
/// surfaces and no rigid bodies).
std::string collisionNote(const World& world);

} // namespace pba::render
