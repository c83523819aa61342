#pragma once
// The vector types every part of pba shares. Simulation state is double
// precision (the integrator study measures errors far below float's rounding);
// kernels are templates over the scalar so swarms can run them in float.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace pba {

using glm::dmat3;
using glm::dquat;
using glm::dvec3;
template <class T>
using Vec3 = glm::vec<3, T, glm::defaultp>;

} // namespace pba
