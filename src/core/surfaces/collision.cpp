#include "pba/collision.hpp"

#include "surfaces/collision_rules.hpp"

namespace pba {

int stepWithCollisions(CollisionResponse response, Integrator integrator, std::span<const Plane> planes,
                       double restitution, dvec3& x, dvec3& v, double dt,
                       const std::function<dvec3(const dvec3&, const dvec3&)>& accel)
{
    // The template of collision_rules.hpp, which the World inlines with its own acceleration.
    return stepWithCollisions<double>(response, integrator, planes, restitution, x, v, dt, accel);
}

} // namespace pba
