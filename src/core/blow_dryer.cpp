#include "pba/blow_dryer.hpp"

#include "pba/swarm.hpp"
#include "pba/world.hpp"

namespace pba {

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
