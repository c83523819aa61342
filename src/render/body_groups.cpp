#include "body_groups.hpp"

#include <algorithm>
#include <string>

#include "palette.hpp"

namespace pba::render {

namespace {

glm::vec4 colourOf(palette::Rgb rgb)
{
    const auto [r, g, b] = palette::channels(rgb);
    return {r, g, b, 1.0f};
}

/// "rope NAME", or the name alone where it already says what it is ("rope", "cloth": not "rope rope").
std::string kindAndName(const std::string& kind, const std::string& name)
{
    return name == kind ? name : kind + " " + name;
}

/// The ropes and cloths whose particles all exist, as groups (unordered).
std::vector<BodyGroup> fabricGroups(const World& world, const FabricLayout& fabric)
{
    std::vector<BodyGroup> out;
    for (const RopeLayout& rope : fabric.ropes) {
        out.push_back({BodyGroup::Kind::Rope, rope.name,
                       kindAndName("rope", rope.name) + ": " + std::to_string(rope.particles.size()) + " particles",
                       rope.particles});
    }
    for (const ClothLayout& cloth : fabric.cloths) {
        BodyGroup g{BodyGroup::Kind::Cloth, cloth.name,
                    kindAndName("cloth", cloth.name) + ": " + std::to_string(cloth.width) + " x " +
                        std::to_string(cloth.height) + " particles",
                    {}};
        for (std::size_t k = 0; k < cloth.width * cloth.height; ++k)
            g.members.push_back(cloth.first + k);
        out.push_back(std::move(g));
    }
    std::erase_if(out, [&](const BodyGroup& g) {
        return g.members.empty() ||
               std::any_of(g.members.begin(), g.members.end(), [&](std::size_t i) { return i >= world.bodyCount(); });
    });
    return out;
}

} // namespace

BodyGroups::BodyGroups(const World& world, const FabricLayout& fabric)
    : m_groupOf(world.bodyCount(), 0), m_fixed(world.bodyCount(), false)
{
    std::vector<bool> taken(world.bodyCount(), false);
    m_groups = fabricGroups(world, fabric);
    for (const BodyGroup& g : m_groups)
        for (const std::size_t i : g.members)
            taken[i] = true;
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        m_fixed[i] = world.body(i).isFixed();
        if (!taken[i])
            m_groups.push_back({BodyGroup::Kind::Body, world.body(i).getName(), world.body(i).getName(), {i}});
    }
    std::stable_sort(m_groups.begin(), m_groups.end(),
                     [](const BodyGroup& a, const BodyGroup& b) { return a.members.front() < b.members.front(); });
    for (std::size_t g = 0; g < m_groups.size(); ++g) {
        BodyGroup& group = m_groups[g];
        const bool fixedBody = !group.fabric() && m_fixed[group.members.front()];
        group.colour = colourOf(fixedBody ? palette::kFixed : palette::bodyRgb(g));
        for (const std::size_t i : group.members)
            m_groupOf[i] = g;
    }
}

glm::vec4 BodyGroups::bodyColour(std::size_t body) const
{
    return m_fixed[body] ? colourOf(palette::kFixed) : m_groups[m_groupOf[body]].colour;
}

glm::vec4 BodyGroups::swarmColour(std::size_t swarm) const { return colourOf(palette::bodyRgb(m_groups.size() + swarm)); }

double groupEnergy(const BodyGroup& group, const std::vector<double>& energies)
{
    double sum = 0.0;
    for (const std::size_t i : group.members)
        sum += energies[i];
    return sum;
}

bool groupFixed(const World& world, const BodyGroup& group)
{
    return std::all_of(group.members.begin(), group.members.end(), [&](std::size_t i) { return world.body(i).isFixed(); });
}

double movingEnergy(const World& world, const BodyGroups& groups, const std::vector<double>& energies)
{
    double sum = 0.0;
    for (const BodyGroup& group : groups.groups())
        if (!groupFixed(world, group))
            sum += groupEnergy(group, energies);
    return sum;
}

bool anyGroupFixed(const World& world, const BodyGroups& groups)
{
    return std::any_of(groups.groups().begin(), groups.groups().end(),
                       [&](const BodyGroup& group) { return groupFixed(world, group); });
}

dvec3 groupMomentum(const World& world, const BodyGroup& group)
{
    dvec3 p(0.0);
    for (const std::size_t i : group.members)
        if (!world.body(i).isFixed())
            p += world.body(i).getMass() * world.body(i).getVel();
    return p;
}

} // namespace pba::render
