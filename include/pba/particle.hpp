#pragma once
#include "pba/body.hpp"

namespace pba {

/// A point mass, or a small ball. Without a radius it is drawn with a small quad (scaled to 0.1,
/// rotated by pi/2 about x so it lies in the xz plane) because a dimensionless thing cannot be
/// seen; with one it is a sphere of that radius: it meets the room (and other particles) at its
/// surface, is drawn at that size, and the air drags on its cross-section.
class Particle : public Body {
public:
    Particle();
    std::unique_ptr<Body> clone() const override { return std::make_unique<Particle>(*this); }

    /// Radius in m; 0 (the default) is a point, stepped exactly as before radii existed.
    double getRadius() const { return m_radius; }
    /// Throws std::invalid_argument unless radius is finite and not negative.
    void setRadius(double radius);
    /// Coulomb friction coefficient mu against surfaces and other particles (static and kinetic
    /// alike); 0 (the default) is frictionless.
    double getFriction() const { return m_friction; }
    /// Throws std::invalid_argument unless friction is finite and not negative.
    void setFriction(double friction);

private:
    double m_radius = 0.0;   ///< m
    double m_friction = 0.0; ///< Coulomb mu, dimensionless
};

} // namespace pba
