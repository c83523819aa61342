#pragma once
// The springs that act on one system of particles, gathered once for the methods that treat them
// implicitly (backward Euler's Jacobian, XPBD's constraints): every anchored spring, two-body
// spring and spring network's link with an end in the system, its ends as the system's own
// indices (0 to n - 1, the order of the system's members), an end that does not move (an anchor,
// a fixed particle) as a fixed point. Kept with the World's coupling and made anew with it.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "pba/clone_ptr.hpp"
#include "pba/force.hpp"

namespace pba::detail {

class SpringSystem {
public:
    static constexpr std::uint32_t kFixed = std::numeric_limits<std::uint32_t>::max();
    static constexpr std::size_t kAnchor = std::numeric_limits<std::size_t>::max();

    SpringSystem() = default;
    /// The springs of `forces` with an end among `members` (world indices, in the system's
    /// order), of a world of `bodyCount` bodies. A spring's end that is not a member is a fixed
    /// point: no force couples two systems (World::step refuses bodies coupled with different
    /// integrators), so such an end is fixed or an anchor.
    SpringSystem(std::span<const ClonePtr<Force>> forces, std::span<const std::size_t> members, std::size_t bodyCount);

    std::size_t size() const { return m_a.size(); }
    std::size_t bodies() const { return m_bodies; }
    /// Spring s: its first end a (a member's index), its second end b (a member's, or kFixed),
    /// and its stiffness (N/m), rest length (m) and damping (N s/m).
    std::uint32_t a(std::size_t s) const { return m_a[s]; }
    std::uint32_t b(std::size_t s) const { return m_b[s]; }
    double stiffness(std::size_t s) const { return m_stiffness[s]; }
    double restLength(std::size_t s) const { return m_rest[s]; }
    double damping(std::size_t s) const { return m_damping[s]; }
    /// Where the fixed end of spring s (b(s) == kFixed) is, after placeFixedEnds.
    const dvec3& fixedPoint(std::size_t s) const { return m_fixedPoint[m_fixedEnd[s]]; }
    /// Puts each fixed end where it is at the start of the step: an anchor's point, or the fixed
    /// body's position in `positions` (one per world body; a program may move a fixed body).
    void placeFixedEnds(std::span<const dvec3> positions);

    /// The springs at member p: incident(p)[k] is 2 s + 1 where p is spring s's second end and 2 s
    /// where it is the first, in the springs' order.
    std::span<const std::uint32_t> incident(std::size_t p) const
    {
        return {m_incident.data() + m_first[p], m_incident.data() + m_first[p + 1]};
    }
    /// Whether world force f is a spring (the system's springs are among those forces' springs).
    bool isSpring(std::size_t f) const { return f < m_isSpring.size() && m_isSpring[f] != 0; }

    /// Adds a spring between ends given as world indices (`anchor`: b is that point instead).
    /// Kept only with an end among the members.
    void addSpring(std::size_t a, std::size_t b, double k, double rest, double c, const dvec3* anchor);

    /// A spring between two members given as the system's own indices.
    struct LocalSpring {
        std::uint32_t a = 0, b = 0;
        double stiffness = 0.0, rest = 0.0, damping = 0.0;
    };
    /// This system with `extra` members after its own and `springs` among them (rigid bodies'
    /// points solved as members: the joint points of world_particle_systems.cpp).
    SpringSystem withExtraMembers(std::size_t extra, std::span<const LocalSpring> springs) const;
    /// Sets the stiffness, rest length and damping of the last springs.size() springs (made by
    /// withExtraMembers with springs of the same ends).
    void setLastSprings(std::span<const LocalSpring> springs);

private:
    void buildIncidence();

    std::size_t m_bodies = 0;
    std::vector<std::uint32_t> m_local; ///< world body -> member index (kFixed: not a member); while gathering
    std::vector<std::uint32_t> m_a, m_b, m_fixedEnd;
    std::vector<double> m_stiffness, m_rest, m_damping;
    std::vector<std::size_t> m_fixedBody; ///< per fixed end: the world body, or kAnchor
    std::vector<dvec3> m_fixedPoint;      ///< per fixed end: where it is
    std::vector<std::uint32_t> m_first, m_incident;
    std::vector<std::uint8_t> m_isSpring;
};

} // namespace pba::detail
