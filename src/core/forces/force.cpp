#include "pba/force.hpp"

#include "pba/body.hpp"
#include "pba/particle.hpp"

namespace pba {

bool BodyStates::isFixed(std::size_t i) const { return bodies[i]->isFixed(); }

double BodyStates::mass(std::size_t i) const
{
    return masses.empty() ? bodies[i]->getMass() : masses[i];
}

double BodyStates::radius(std::size_t i) const
{
    if (!radii.empty())
        return radii[i];
    const auto* particle = dynamic_cast<const Particle*>(bodies[i].get());
    return particle ? particle->getRadius() : 0.0;
}

void Force::accumulate(const BodyStates& in, Accumulators& out) const
{
    for (std::size_t i = 0; i < in.bodies.size(); ++i)
        if (in.moving(i))
            out.add(i, force(i, *in.bodies[i], in.states[i].pos, in.states[i].vel));
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
