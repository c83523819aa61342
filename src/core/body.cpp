#include "pba/body.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace pba {

void Body::setMesh(Mesh mesh)
{
    m_mesh = std::move(mesh);
    m_mesh.setPos(glm::vec3(m_pos));
}

void Body::setPos(int i, double p)
{
    m_pos[i] = p;
    m_mesh.setPos(i, static_cast<float>(p));
}

void Body::setMass(double mass)
{
    if (!std::isfinite(mass) || mass <= 0.0)
        throw std::invalid_argument(fmt::format("mass must be finite and positive, got {}", mass));
    m_mass = mass;
}

void Body::setCor(double cor)
{
    if (!(cor >= 0.0 && cor <= 1.0))
        throw std::invalid_argument(fmt::format("restitution must be in [0, 1], got {}", cor));
    m_cor = cor;
}

} // namespace pba
