#include "exact_solution.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include "pba/forces.hpp"
#include "pba/particle.hpp"
#include "pba/spring_network.hpp"

namespace pba::study {

namespace {

std::optional<double> floorHeight(const World& world)
{
    if (world.ground())
        return *world.ground();
    if (world.room())
        return world.room()->min.y;
    return std::nullopt;
}

/// The springs on `particle` (the oscillator's exact solution needs the one spring's numbers).
std::vector<const Spring*> springsOn(const World& world, std::size_t particle)
{
    struct Finder final : ForceVisitor {
        std::size_t particle = 0;
        std::vector<const Spring*> found;
        void visit(const Spring& spring) override
        {
            if (spring.particle() == particle)
                found.push_back(&spring);
        }
    } finder;
    finder.particle = particle;
    for (std::size_t i = 0; i < world.forceCount(); ++i)
        world.force(i).accept(finder);
    return finder.found;
}

} // namespace

ForceKinds forceKinds(const World& world)
{
    struct Collector final : ForceVisitor {
        std::size_t gravities = 0;
        ForceKinds kinds;
        void visit(const Gravity&) override { ++gravities; }
        void visit(const Spring& spring) override { kinds.dampedSprings = kinds.dampedSprings || spring.damping() > 0.0; }
        void visit(const TwoBodySpring& spring) override
        {
            kinds.dampedSprings = kinds.dampedSprings || spring.damping() > 0.0;
        }
        void visit(const SpringNetwork& network) override
        {
            // (ExactSolution::find asks for every particle: a scan of a cloth's springs each time
            // made a 250 x 250 sheet's sim start in 10 s.)
            kinds.dampedSprings = kinds.dampedSprings || network.damped();
        }
        void visit(const Drag&) override { kinds.drag = true; }
    } collector;
    for (std::size_t i = 0; i < world.forceCount(); ++i)
        world.force(i).accept(collector);
    collector.kinds.onlyGravity = collector.gravities == world.forceCount();
    return collector.kinds;
}

namespace {

/// Whether body i moves alone under the forces: a point (a ball meets other balls and bodies) that
/// no joint holds.
bool movesAlone(const World& world, std::size_t i)
{
    const auto* particle = dynamic_cast<const Particle*>(&world.body(i));
    if (!particle || particle->getRadius() > 0.0)
        return false;
    for (std::size_t j = 0; j < world.jointCount(); ++j) {
        const JointFrame frame = world.jointFrame(j);
        if (frame.bodyA == i || frame.bodyB == i)
            return false;
    }
    return true;
}

} // namespace

std::optional<ExactSolution> ExactSolution::find(const World& world, std::size_t particle)
{
    const Body& body = world.body(particle);
    const dvec3 g = world.gravity();
    ExactSolution exact;
    exact.m_start = body.getPos();
    if (!movesAlone(world, particle))
        return std::nullopt;
    const auto floor = floorHeight(world);
    if (floor && forceKinds(world).onlyGravity && g.x == 0.0 && g.z == 0.0 && g.y < 0.0 && body.getVel() == dvec3(0.0) &&
        body.getCor() == 1.0 && !world.room() && !world.floorHole() && body.getPos().y > *floor) {
        exact.m_kind = Kind::Bounce;
        exact.m_floor = *floor;
        exact.m_height = body.getPos().y - *floor;
        exact.m_g = -g.y;
        return exact;
    }
    if (world.planes().empty() && g == dvec3(0.0)) {
        for (const Spring* spring : springsOn(world, particle)) {
            if (spring->damping() != 0.0 || world.forceCount() != 2)
                continue;
            const dvec3 d = body.getPos() - spring->anchor();
            if (glm::length(d) == 0.0)
                return std::nullopt;
            const dvec3 u = d / glm::length(d);
            if (glm::length(glm::cross(body.getVel(), u)) > 1e-12 * (1.0 + glm::length(body.getVel())))
                return std::nullopt; // motion off the spring's line is not one-dimensional
            exact.m_kind = Kind::Oscillator;
            exact.m_anchor = spring->anchor();
            exact.m_axis = u;
            exact.m_rest = spring->restLength();
            exact.m_s0 = glm::length(d) - spring->restLength();
            exact.m_w = std::sqrt(spring->stiffness() / body.getMass());
            exact.m_v0 = glm::dot(body.getVel(), u);
            exact.m_height = std::hypot(exact.m_s0, exact.m_v0 / exact.m_w);
            if (!(exact.m_height < exact.m_rest))
                return std::nullopt; // it would pass its anchor, where the force is no longer linear
            return exact;
        }
    }
    return std::nullopt;
}

dvec3 ExactSolution::position(double t) const
{
    if (m_kind == Kind::Oscillator) {
        const double s = m_s0 * std::cos(m_w * t) + m_v0 / m_w * std::sin(m_w * t);
        return m_anchor + (m_rest + s) * m_axis;
    }
    // Time since the last apex: the motion repeats every period, apexes at 0, P, 2P, ...
    const double t0 = std::sqrt(2.0 * m_height / m_g);
    const double since = std::fmod(t + t0, 2.0 * t0) - t0;
    return {m_start.x, m_floor + m_height - 0.5 * m_g * since * since, m_start.z};
}

double ExactSolution::period() const
{
    return m_kind == Kind::Oscillator ? 2.0 * std::numbers::pi / m_w : 2.0 * std::sqrt(2.0 * m_height / m_g);
}

} // namespace pba::study
