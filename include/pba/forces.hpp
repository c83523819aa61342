#pragma once
// The basic forces. Each one's physics is a small kernel, and the class around it adapts the
// kernel to the Force interface. Drag's is a template here because a swarm's float loop (an
// installed detail header) inlines it; the spring's, used by the core alone, is in src/core.
#include "pba/force.hpp"

namespace pba {

/// Uniform gravity: F = m g, potential energy -m g.x.
class Gravity final : public ForceBase<Gravity> {
public:
    explicit Gravity(const dvec3& g) : m_g(g) {}
    std::string_view type() const override { return "gravity"; }
    dvec3 force(std::size_t index, const Body& body, const dvec3& x, const dvec3& v) const override;
    /// On all cores (each body's force the same whichever thread computes it).
    void accumulate(const BodyStates& in, Accumulators& out) const override;
    double potentialEnergy(std::size_t index, const Body& body, const dvec3& x) const override;
    bool addToSwarmFields(SwarmFields& fields) const override;
    /// Conservative: its work is its potential energy's loss.
    bool addsEnergy() const override { return false; }
    const dvec3& acceleration() const { return m_g; }
    void setAcceleration(const dvec3& g) { m_g = g; }

private:
    dvec3 m_g;
};

/// Linear drag F = -c v: the low-Reynolds-number model, which keeps the ODE linear
/// so its exact solution stays available to the tests.
template <class T>
inline Vec3<T> dragForce(T coefficient, const Vec3<T>& v)
{
    return -coefficient * v;
}

class Drag final : public ForceBase<Drag> {
public:
    /// `angular`: the rotational drag, a torque -angular omega on a turning body (N m s).
    explicit Drag(double coefficient, double angular = 0.0) : m_coefficient(coefficient), m_angular(angular) {}
    std::string_view type() const override { return "drag"; }
    dvec3 force(std::size_t index, const Body& body, const dvec3& x, const dvec3& v) const override;
    /// On all cores.
    void accumulate(const BodyStates& in, Accumulators& out) const override;
    bool addToSwarmFields(SwarmFields& fields) const override;
    /// It only takes energy away: still air.
    bool addsEnergy() const override { return false; }
    double coefficient() const { return m_coefficient; }
    double angularCoefficient() const { return m_angular; }

private:
    double m_coefficient;
    double m_angular;
};

/// A damped spring from a fixed anchor, F = -k (|d| - L) d/|d| - c (v . d/|d|) d/|d| with
/// d = x - anchor: its kernel is springForce (src/core/forces/spring_force.hpp). It ties one named
/// particle: a swarm in the same world feels nothing of it.
class Spring final : public ForceBase<Spring> {
public:
    /// `attachment`: where on the body the spring is tied, in the body's own frame (a rigid
    /// body's point; a particle's is its centre, zero).
    Spring(std::size_t particle, const dvec3& anchor, double stiffness, double restLength, double damping,
           const dvec3& attachment = dvec3(0.0))
        : m_particle(particle), m_anchor(anchor), m_stiffness(stiffness), m_restLength(restLength), m_damping(damping),
          m_attachment(attachment) {}
    std::string_view type() const override { return "spring"; }
    dvec3 force(std::size_t index, const Body& body, const dvec3& x, const dvec3& v) const override;
    /// Its one particle only, rather than asking every body of the world for a zero.
    void accumulate(const BodyStates& in, Accumulators& out) const override;
    double potentialEnergy(std::size_t index, const Body& body, const dvec3& x) const override;
    /// With the attachment where the body's pose puts it.
    double potentialEnergyShare(std::size_t index, const BodyStates& in) const override;
    /// Nothing to add, and nothing missing: a spring acts on its named particle only.
    bool addToSwarmFields(SwarmFields& /*fields*/) const override { return true; }
    /// A fixed anchor: conservative, and its damping only takes energy away.
    bool addsEnergy() const override { return false; }

    std::size_t particle() const { return m_particle; }
    const dvec3& anchor() const { return m_anchor; }
    double stiffness() const { return m_stiffness; }
    double restLength() const { return m_restLength; }
    double damping() const { return m_damping; }
    const dvec3& attachment() const { return m_attachment; }

private:
    std::size_t m_particle;
    dvec3 m_anchor;
    double m_stiffness;
    double m_restLength;
    double m_damping;
    dvec3 m_attachment;
};

/// Damped spring between two bodies a and b. With d = x_b - x_a and u = d/|d|, b feels
/// F = -(k (|d| - L) + c (v_b - v_a) . u) u and a feels -F: the damping acts along the spring on
/// the relative velocity only, so it never slows the pair's centre of mass. Potential energy
/// k (|d| - L)^2 / 2, split half to each end in the per-body read-out. The two bodies'
/// forces depend on each other's states, so the World integrates them together (couplings).
class TwoBodySpring final : public ForceBase<TwoBodySpring> {
public:
    TwoBodySpring(std::size_t a, std::size_t b, double stiffness, double restLength, double damping)
        : m_a(a), m_b(b), m_stiffness(stiffness), m_restLength(restLength), m_damping(damping) {}
    std::string_view type() const override { return "spring"; }
    /// Zero: the force on one end needs the other end's trial state (see accumulate).
    dvec3 force(std::size_t index, const Body& body, const dvec3& x, const dvec3& v) const override;
    void accumulate(const BodyStates& in, Accumulators& out) const override;
    double potentialEnergyShare(std::size_t index, const BodyStates& in) const override;
    double totalPotentialEnergy(const BodyStates& in) const override;
    void appendCouplings(std::vector<std::pair<std::size_t, std::size_t>>& pairs) const override;
    /// Nothing to add, and nothing missing: it acts on its two named bodies only.
    bool addToSwarmFields(SwarmFields& /*fields*/) const override { return true; }
    /// Conservative, and its damping only takes energy away.
    bool addsEnergy() const override { return false; }

    std::size_t first() const { return m_a; }
    std::size_t second() const { return m_b; }
    double stiffness() const { return m_stiffness; }
    double restLength() const { return m_restLength; }
    double damping() const { return m_damping; }

private:
    double energy(const BodyStates& in) const;

    std::size_t m_a;
    std::size_t m_b;
    double m_stiffness;
    double m_restLength;
    double m_damping;
};

} // namespace pba
