#pragma once
// The exact solutions the integrator study measures against. Each one is recognised from the
// scene itself (its forces, surfaces and the particle's start), never from the scene's name.
#include <optional>

#include "pba/world.hpp"

namespace pba::study {

/// Which kinds of force the world has, for what a report may say of it.
struct ForceKinds {
    bool onlyGravity = true;    ///< no force but gravity
    bool dampedSprings = false; ///< a spring with damping (anchored, between two bodies, or a rope's or cloth's)
    bool drag = false;          ///< the linear `drag` force
};
ForceKinds forceKinds(const World& world);

/// The exact motion of one particle, if the scene has one we know.
class ExactSolution {
public:
    enum class Kind { Bounce, Oscillator };

    /// A point particle (no radius) that no joint holds, dropped from rest above a floor under
    /// gravity alone with e = 1 (apex h, first impact at sqrt(2h/g), period 2 sqrt(2h/g)); or one
    /// on an undamped spring without gravity or surfaces, moving along the spring and never
    /// reaching its anchor. Nothing otherwise.
    static std::optional<ExactSolution> find(const World& world, std::size_t particle);

    Kind kind() const { return m_kind; }
    dvec3 position(double t) const;
    /// Drop height above the floor (bounce) or amplitude (oscillator), m.
    double height() const { return m_height; }
    /// Bounce period 2 sqrt(2h/g), or the oscillator's 2 pi / w, s.
    double period() const;
    double gravity() const { return m_g; }

private:
    Kind m_kind = Kind::Bounce;
    dvec3 m_start{0.0};
    double m_floor = 0.0;
    double m_height = 0.0;
    double m_g = 0.0;
    // oscillator: x(t) = anchor + (L + s(t)) u, s(t) = s0 cos(w t) + (v0/w) sin(w t)
    dvec3 m_anchor{0.0};
    dvec3 m_axis{0.0};
    double m_rest = 0.0, m_s0 = 0.0, m_v0 = 0.0, m_w = 0.0;
};

} // namespace pba::study
