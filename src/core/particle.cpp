#include "pba/particle.hpp"

#include <numbers>

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

} // namespace pba
