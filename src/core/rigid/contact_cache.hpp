#pragma once
// The contact cache: every contact of the last step, by body pair, so that this step's contact
// between the same two bodies starts from the impulses its points ended with (points matched by
// their feature ids), and the narrow phase from the pair's last separating axis. Contact memory
// lives here, not in the bodies (Jolt's ContactConstraintManager keys its cache the same way).
#include <cstdint>
#include <utility>
#include <vector>

#include "rigid/contact.hpp"

namespace pba::rigid {

class ContactCache {
public:
    /// This step's contacts become the last step's; this step's list starts empty.
    void beginStep();
    std::vector<Contact>& contacts() { return m_current; }
    const std::vector<Contact>& contacts() const { return m_current; }
    /// The last step's contact between the same two bodies, or null.
    const Contact* previous(std::uint64_t key) const;
    const std::vector<Contact>& previousContacts() const { return m_previous; }
    /// Hands each point of `c` the impulses of the last step's point with the same feature id
    /// (none for a new point), and the pair's separating axis.
    void warmStart(Contact& c) const;
    /// The same, with the last step's contact between the two bodies (previous(c.key())) known.
    void warmStart(Contact& c, const Contact* old) const;
    void clear();

private:
    std::vector<Contact> m_current, m_previous;
    std::vector<std::pair<std::uint64_t, std::uint32_t>> m_previousKeys; ///< sorted
};

} // namespace pba::rigid
