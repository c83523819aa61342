#pragma once
// The scene's bodies as a reader sees them: each rope and each cloth is one thing (one row of
// the panel, one line of the legend, one colour), each other body a thing of its own. Every
// group gets its colour from the palette by its place in the scene, so the drawn body, its
// legend bullet and its plot lines share one colour on every run.
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "pba/fabric.hpp"
#include "pba/world.hpp"

namespace pba::render {

struct BodyGroup {
    enum class Kind { Body, Rope, Cloth };
    Kind kind = Kind::Body;
    std::string name;                 ///< the body's, the rope's or the cloth's
    /// "rope NAME: 25 particles", "cloth NAME: 10 x 10 particles", or the body's name.
    std::string label;
    std::vector<std::size_t> members; ///< world indices, in the scene's order
    glm::vec4 colour{1.0f};
    bool fabric() const { return kind != Kind::Body; }
};

class BodyGroups {
public:
    BodyGroups() = default;
    /// The ropes and cloths of `fabric` and every other body, ordered by their first body.
    BodyGroups(const World& world, const FabricLayout& fabric);

    const std::vector<BodyGroup>& groups() const { return m_groups; }
    std::size_t size() const { return m_groups.size(); }
    const BodyGroup& operator[](std::size_t g) const { return m_groups[g]; }
    /// The group body i belongs to.
    std::size_t groupOf(std::size_t body) const { return m_groupOf[body]; }
    /// Whether body i is a particle of a rope or cloth.
    bool inFabric(std::size_t body) const { return m_groups[m_groupOf[body]].fabric(); }
    /// The colour body i is drawn in: its group's, or grey for a fixed body (a pin, an anchor).
    glm::vec4 bodyColour(std::size_t body) const;
    /// The colour of swarm s: the palette's next after the groups'.
    glm::vec4 swarmColour(std::size_t swarm) const;
    std::size_t bodyCount() const { return m_groupOf.size(); }

private:
    std::vector<BodyGroup> m_groups;
    std::vector<std::size_t> m_groupOf;
    std::vector<bool> m_fixed;
};

/// The sum of the members' energies (World::energies()) and their momentum.
double groupEnergy(const BodyGroup& group, const std::vector<double>& energies);
dvec3 groupMomentum(const World& world, const BodyGroup& group);
/// Whether every member is fixed: it never moves (its height energy never changes, its plots are
/// flat lines).
bool groupFixed(const World& world, const BodyGroup& group);
/// The energy of the groups that move: a fixed body's height energy never changes, and counted it
/// would hide the others' losses (three thousand joules of ramps beside a box's seventy).
double movingEnergy(const World& world, const BodyGroups& groups, const std::vector<double>& energies);
/// Whether some group is fixed, so that the scene's totals are of its moving bodies only.
bool anyGroupFixed(const World& world, const BodyGroups& groups);

} // namespace pba::render
