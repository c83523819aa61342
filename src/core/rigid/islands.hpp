#pragma once
// Islands: the awake bodies that touch each other, directly or through others, or are joined;
// what one body does can reach only the bodies of its island within a step, so islands are
// solved apart (in parallel), and an island whose bodies have all been still for a while goes to
// sleep as one and costs nothing until something touches it (Box2D's and Jolt's islands).
#include <cstdint>
#include <span>
#include <vector>

#include "rigid/broad_phase.hpp"
#include "rigid/contact.hpp"

namespace pba::rigid {

/// A link between two bodies that binds them into one island (a joint's bodies).
struct Link {
    BodyIndex a = 0, b = 0;
};

class Islands {
public:
    /// The islands of the awake bodies (`motion`) linked by touching contacts (count > 0, both
    /// bodies movable) and by `links`; static bodies link nothing. Each island's bodies and
    /// contacts are in increasing order, and the islands in the order of their first body.
    void build(std::span<const Motion> motion, std::span<const Contact> contacts, std::span<const Link> links);

    std::size_t count() const { return m_bodyStart.size() - 1; }
    std::span<const std::uint32_t> bodies(std::size_t island) const
    {
        return {m_bodies.data() + m_bodyStart[island], m_bodyStart[island + 1] - m_bodyStart[island]};
    }
    std::span<const std::uint32_t> contacts(std::size_t island) const
    {
        return {m_contacts.data() + m_contactStart[island], m_contactStart[island + 1] - m_contactStart[island]};
    }
    std::span<const std::uint32_t> links(std::size_t island) const
    {
        return {m_links.data() + m_linkStart[island], m_linkStart[island + 1] - m_linkStart[island]};
    }
    /// The island of an awake body (npos for others).
    std::uint32_t islandOf(BodyIndex body) const { return m_islandOf[body]; }
    static constexpr std::uint32_t npos = 0xffffffffu;

private:
    std::uint32_t find(std::uint32_t i);

    std::vector<std::uint32_t> m_parent;
    std::vector<std::uint32_t> m_islandOf;
    std::vector<std::uint32_t> m_bodies, m_bodyStart;
    std::vector<std::uint32_t> m_contacts, m_contactStart;
    std::vector<std::uint32_t> m_links, m_linkStart;
};

} // namespace pba::rigid
