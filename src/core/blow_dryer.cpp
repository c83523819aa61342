#include "pba/blow_dryer.hpp"

#include <type_traits>

#include "pba/swarm.hpp"
#include "pba/world.hpp"

#include "parallel.hpp"

namespace pba {

void BlowDryer::accumulate(const BodyStates& in, Accumulators& out) const
{
    // An upward axis (every built-in scene's) picks coordinates instead of projecting on it, as
    // in a swarm's loop: the same values, found with fewer multiplications.
    // Without a pull (axis_pull 0, as in every built-in scene) its arithmetic is left out.
    auto each = [&](auto axis, auto pull) {
        detail::addToEachMoving(in, out, [&](std::size_t i) {
            return blowDryerForce<decltype(axis)::value, true, double, decltype(pull)::value>(
                m_kernel, in.states[i].pos, in.states[i].vel);
        });
    };
    using Up = std::integral_constant<DryerAxis, DryerAxis::Up>;
    using Any = std::integral_constant<DryerAxis, DryerAxis::Any>;
    const bool up = m_field.axis == dvec3(0.0, 1.0, 0.0);
    if (m_kernel.pull != 0.0)
        up ? each(Up{}, std::true_type{}) : each(Any{}, std::true_type{});
    else
        up ? each(Up{}, std::false_type{}) : each(Any{}, std::false_type{});
}

bool BlowDryer::addToSwarmFields(SwarmFields& fields) const
{
    fields.dryers.push_back(m_field.as<float>());
    return true;
}

std::vector<WorldDryer> blowDryers(const World& world)
{
    struct Finder final : ForceVisitor {
        std::vector<WorldDryer> found;
        std::size_t index = 0;
        void visit(const BlowDryer& dryer) override { found.push_back({index, dryer.field()}); }
    } finder;
    for (; finder.index < world.forceCount(); ++finder.index)
        world.force(finder.index).accept(finder);
    return finder.found;
}

} // namespace pba
