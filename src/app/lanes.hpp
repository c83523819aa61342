#pragma once
// Integrator lanes: beside each particle that has an exact solution, its ghost where the exact
// solution is, so drift is visible as it happens.
#include <functional>
#include <optional>

#include <glm/glm.hpp>

#include "pba/world.hpp"

namespace pba::app {

/// The ghost function for render::ViewSettings::ghost, from the scene at t = 0.
std::function<std::optional<glm::vec3>(std::size_t, double)> exactGhosts(const World& initial);

} // namespace pba::app
