#include "pba/force.hpp"

#include "pba/body.hpp"

namespace pba {

void Force::accumulate(const BodyStates& in, std::span<dvec3> forces) const
{
    for (std::size_t i = 0; i < in.bodies.size(); ++i) {
        const Body& body = *in.bodies[i];
        if (in.wants(i) && !body.isFixed())
            forces[i] += force(i, body, in.states[i].pos, in.states[i].vel);
    }
}

double Force::potentialEnergyShare(std::size_t index, const BodyStates& in) const
{
    return potentialEnergy(index, *in.bodies[index], in.states[index].pos);
}

double Force::totalPotentialEnergy(const BodyStates& in) const
{
    double e = 0.0;
    for (std::size_t i = 0; i < in.bodies.size(); ++i)
        e += potentialEnergyShare(i, in);
    return e;
}

} // namespace pba
