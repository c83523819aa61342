#include "pba/forces.hpp"

#include "pba/body.hpp"
#include "pba/swarm.hpp"

namespace pba {

dvec3 Gravity::force(std::size_t, const Body& body, const dvec3&, const dvec3&) const { return body.getMass() * m_g; }

double Gravity::potentialEnergy(std::size_t, const Body& body, const dvec3& x) const
{
    return -body.getMass() * glm::dot(m_g, x);
}

bool Gravity::addToSwarmFields(SwarmFields& fields) const
{
    fields.gravity += Vec3<float>(m_g);
    return true;
}

dvec3 Drag::force(std::size_t, const Body&, const dvec3&, const dvec3& v) const { return dragForce(m_coefficient, v); }

bool Drag::addToSwarmFields(SwarmFields& fields) const
{
    fields.drag += float(m_coefficient);
    return true;
}

dvec3 Spring::force(std::size_t index, const Body&, const dvec3& x, const dvec3& v) const
{
    if (index != m_particle)
        return dvec3(0.0);
    return springForce(m_anchor, m_stiffness, m_restLength, m_damping, x, v);
}

double Spring::potentialEnergy(std::size_t index, const Body&, const dvec3& x) const
{
    if (index != m_particle)
        return 0.0;
    const double stretch = glm::length(x - m_anchor) - m_restLength;
    return 0.5 * m_stiffness * stretch * stretch;
}

} // namespace pba
