#pragma once
// Many two-body springs as one force: the stretch, shear and bending springs of a rope or a
// cloth. A 128 x 128 cloth has about 97,000 springs; as that many TwoBodySpring objects the
// world would ask each one in turn, through a virtual call, to add to two accumulators (and
// could not share that among cores without two springs writing one body's force at once).
// Held together, the springs are evaluated in two passes that each split among the cores:
//   1. each spring's force on its second end, from the two ends' trial states (springs are
//      independent: any order, any thread);
//   2. each body's sum over the springs that meet at it, in the springs' order, from an
//      incidence list built once (bodies are independent).
// So a body's force is the same sum in the same order whatever the thread count. The kernel
// is TwoBodySpring's (springForce with the anchor at the first end): one implementation.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "pba/force.hpp"

namespace pba {

class SpringNetwork final : public ForceBase<SpringNetwork> {
public:
    /// One spring between bodies a and b of the world: F on b = -(k (|d| - L) + c (v_b - v_a) . u) u,
    /// with d = x_b - x_a and u = d / |d|; a feels -F.
    struct Link {
        std::size_t a = 0;
        std::size_t b = 0;
        double stiffness = 0.0;
        double restLength = 0.0;
        double damping = 0.0;
    };

    /// Throws std::invalid_argument for a spring whose two ends are one body.
    explicit SpringNetwork(const std::vector<Link>& links);

    /// "spring": each of its links is one (as a scene's two-body spring is).
    std::string_view type() const override { return "spring"; }
    std::size_t size() const { return m_a.size(); }
    Link link(std::size_t s) const { return {m_a[s], m_b[s], m_stiffness[s], m_restLength[s], m_damping[s]}; }
    /// Whether any of its springs has damping.
    bool damped() const { return m_damped; }

    /// Zero: the force on one end needs the other end's trial state (see accumulate).
    dvec3 force(std::size_t index, const Body& body, const dvec3& x, const dvec3& v) const override;
    void accumulate(const BodyStates& in, Accumulators& out) const override;
    /// Half of each spring's energy to each of its ends: a body's few springs, not all of them.
    double potentialEnergyShare(std::size_t index, const BodyStates& in) const override;
    double totalPotentialEnergy(const BodyStates& in) const override;
    void appendCouplings(std::vector<std::pair<std::size_t, std::size_t>>& pairs) const override;
    /// Nothing to add, and nothing missing: it acts on its own bodies only.
    bool addToSwarmFields(SwarmFields& /*fields*/) const override { return true; }
    /// Conservative, and its damping only takes energy away.
    bool addsEnergy() const override { return false; }

private:
    double energy(std::size_t s, const BodyStates& in) const;
    /// Pass 1 over springs [begin, end): the force on each one's second end, into onSecond.
    void onSecondEnds(const State* states, dvec3* onSecond, std::size_t begin, std::size_t end) const;

    // 32-bit indices: the springs' arrays are read every force evaluation, and half their size
    // is half the memory a 97,000-spring cloth moves for them.
    std::vector<std::uint32_t> m_a, m_b;
    std::vector<double> m_stiffness, m_restLength, m_damping;
    bool m_damped = false;
    std::size_t m_lowest = 0; ///< the bodies the springs touch lie in [m_lowest, m_lowest + m_first.size() - 1)
    /// The incidence list: the springs at body m_lowest + p are m_incident[m_first[p]] up to
    /// m_incident[m_first[p + 1]], each 2 s + 1 where the body is spring s's second end (it
    /// feels +F) and 2 s where it is the first (-F).
    std::vector<std::size_t> m_first;
    std::vector<std::uint32_t> m_incident;
};

} // namespace pba
