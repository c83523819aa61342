#include "collision_note.hpp"

#include <vector>

namespace pba::render {

namespace {

/// Which kinds of body the world has, as far as collisions go.
struct Kinds {
    bool freePoints = false;        ///< particles on their own, and swarms: the response applies
    /// one of those integrates with semi-implicit Euler and bounces elastically: what the note
    /// says of its bounce height is the practical's comparison, which a lossy bounce has not
    bool freeSemiImplicit = false;
    bool coupledPoints = false;     ///< particles joined by springs (ropes, cloths)
    bool rigid = false;
};

Kinds kindsOf(const World& world)
{
    Kinds k;
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        const Body& body = world.body(i);
        if (world.isRigid(i)) {
            k.rigid = true;
        } else if (body.isFixed()) {
            continue;
        } else if (world.isCoupled(i)) {
            k.coupledPoints = true;
        } else {
            k.freePoints = true;
            k.freeSemiImplicit = k.freeSemiImplicit ||
                                 (body.getIntegrator() == Integrator::SemiImplicitEuler && body.getCor() == 1.0);
        }
    }
    for (std::size_t s = 0; s < world.swarmCount(); ++s) {
        k.freePoints = true;
        k.freeSemiImplicit = k.freeSemiImplicit || (world.swarm(s).integrator() == Integrator::SemiImplicitEuler &&
                                                     world.swarm(s).restitution() == 1.0);
    }
    return k;
}

std::string ruleText(CollisionResponse response)
{
    switch (response) {
    case CollisionResponse::Exact: return "exact, each bounces at its time of impact";
    case CollisionResponse::Reflect: return "reflect, mirrored back after the step";
    case CollisionResponse::Clamp: return "clamp, put back on the surface after the step";
    }
    return "?";
}

/// What the rule does to semi-implicit Euler's bounce (the practical's comparison).
std::string semiImplicitText(CollisionResponse response)
{
    switch (response) {
    case CollisionResponse::Exact: return " (semi-implicit Euler loses a little energy at each bounce)";
    case CollisionResponse::Reflect: return " (semi-implicit Euler keeps its bounce height)";
    case CollisionResponse::Clamp: return "";
    }
    return "";
}

} // namespace

std::string collisionNote(const World& world)
{
    const Kinds k = kindsOf(world);
    const bool surfaces = !world.planes().empty();
    std::vector<std::string> parts;
    if (surfaces && k.freePoints)
        parts.push_back("particles: " + ruleText(world.collisionResponse()) +
                        (k.freeSemiImplicit ? semiImplicitText(world.collisionResponse()) : ""));
    if (surfaces && k.coupledPoints) {
        // A coupled particle has no path of its own to find a time of impact on.
        const CollisionResponse coupled = world.coupledCollisionResponse();
        parts.push_back("particles joined by springs: " + ruleText(coupled) +
                        (coupled != world.collisionResponse() ? " (exact needs a particle's own path)" : ""));
    }
    if (k.rigid)
        parts.push_back("rigid bodies: contact impulses with their restitution and friction");
    if (parts.empty())
        return "";
    std::string text = "collisions: " + parts.front();
    for (std::size_t p = 1; p < parts.size(); ++p)
        text += "; " + parts[p];
    return text;
}

} // namespace pba::render
