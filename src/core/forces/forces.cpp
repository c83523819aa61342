#include "pba/forces.hpp"

#include "pba/body.hpp"
#include "pba/swarm.hpp"

#include "parallel.hpp"
#include "forces/spring_force.hpp"

namespace pba {

dvec3 Gravity::force(std::size_t, const Body& body, const dvec3&, const dvec3&) const { return body.getMass() * m_g; }

void Gravity::accumulate(const BodyStates& in, Accumulators& out) const
{
    detail::addToEachMoving(in, out, [&](std::size_t i) { return in.mass(i) * m_g; });
}

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

void Drag::accumulate(const BodyStates& in, Accumulators& out) const
{
    if (m_angular == 0.0 || in.poses.empty() || out.torques.empty()) {
        detail::addToEachMoving(in, out, [&](std::size_t i) { return dragForce(m_coefficient, in.states[i].vel); });
        return;
    }
    detail::forEachIndex(in.bodies.size(), [&](std::size_t i) {
        if (in.moving(i))
            out.add(i, dragForce(m_coefficient, in.states[i].vel), -m_angular * in.poses[i].angularVelocity);
    });
}

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

void Spring::accumulate(const BodyStates& in, Accumulators& out) const
{
    if (!in.moving(m_particle))
        return;
    const State& s = in.states[m_particle];
    if (m_attachment == dvec3(0.0)) {
        out.add(m_particle, force(m_particle, *in.bodies[m_particle], s.pos, s.vel));
        return;
    }
    // Tied to a point of a turning body: the spring pulls that point, moving with v + omega x r,
    // and so turns the body too.
    const Pose& pose = in.pose(m_particle);
    const dvec3 arm = glm::mat3_cast(pose.orientation) * m_attachment;
    const dvec3 f = springForce(m_anchor, m_stiffness, m_restLength, m_damping, s.pos + arm,
                                s.vel + glm::cross(pose.angularVelocity, arm));
    out.addAt(m_particle, f, arm);
}

double Spring::potentialEnergyShare(std::size_t index, const BodyStates& in) const
{
    if (index != m_particle)
        return 0.0;
    const dvec3 arm = glm::mat3_cast(in.pose(index).orientation) * m_attachment;
    const double stretch = glm::length(in.states[index].pos + arm - m_anchor) - m_restLength;
    return 0.5 * m_stiffness * stretch * stretch;
}

double Spring::potentialEnergy(std::size_t index, const Body&, const dvec3& x) const
{
    if (index != m_particle)
        return 0.0;
    const double stretch = glm::length(x - m_anchor) - m_restLength;
    return 0.5 * m_stiffness * stretch * stretch;
}

} // namespace pba

namespace pba {

dvec3 TwoBodySpring::force(std::size_t, const Body&, const dvec3&, const dvec3&) const { return dvec3(0.0); }

void TwoBodySpring::accumulate(const BodyStates& in, Accumulators& out) const
{
    const State& a = in.states[m_a];
    const State& b = in.states[m_b];
    // b seen from a is the anchored spring's kernel with the anchor at a and b's velocity
    // relative to a: one kernel for both forms.
    const dvec3 onB = springForce(a.pos, m_stiffness, m_restLength, m_damping, b.pos, b.vel - a.vel);
    if (in.moving(m_a))
        out.add(m_a, -onB);
    if (in.moving(m_b))
        out.add(m_b, onB);
}

double TwoBodySpring::energy(const BodyStates& in) const
{
    const double stretch = glm::length(in.states[m_b].pos - in.states[m_a].pos) - m_restLength;
    return 0.5 * m_stiffness * stretch * stretch;
}

double TwoBodySpring::potentialEnergyShare(std::size_t index, const BodyStates& in) const
{
    return index == m_a || index == m_b ? 0.5 * energy(in) : 0.0;
}

double TwoBodySpring::totalPotentialEnergy(const BodyStates& in) const { return energy(in); }

void TwoBodySpring::appendCouplings(std::vector<std::pair<std::size_t, std::size_t>>& pairs) const
{
    pairs.emplace_back(m_a, m_b);
}

} // namespace pba
