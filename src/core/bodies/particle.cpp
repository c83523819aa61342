#include "pba/particle.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

namespace pba {

Particle::Particle()
{
    setMesh(Mesh::quad());
    getMesh().scale(glm::vec3(0.1f));
    getMesh().rotate(std::numbers::pi_v<float> / 2.0f, glm::vec3(1.0f, 0.0f, 0.0f));
    setAcc(dvec3(0.0));
    setVel(dvec3(0.0));
    setMass(1.0);
    setCor(1.0);
}

void Particle::setRadius(double radius)
{
    if (!(std::isfinite(radius) && radius >= 0.0))
        throw std::invalid_argument(fmt::format("radius must be finite and not negative, got {}", radius));
    m_radius = radius;
}

void Particle::setFriction(double friction)
{
    if (!(std::isfinite(friction) && friction >= 0.0))
        throw std::invalid_argument(fmt::format("friction must be finite and not negative, got {}", friction));
    m_friction = friction;
}

} // namespace pba
