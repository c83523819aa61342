#include "pba/body.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace pba {

void Body::setMesh(Mesh mesh) { m_mesh = std::move(mesh); }

glm::mat4 Body::getTranslate() const
{
    glm::mat4 t(1.0f);
    t[3] = glm::vec4(glm::vec3(m_pos), 1.0f);
    return t;
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
