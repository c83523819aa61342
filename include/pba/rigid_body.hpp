#pragma once
// A body with extent: the practical's "rigid bodies ... their density and inertia tensor". Its
// translation is Body's; it adds an orientation, the angular momentum and the inertia tensor.
#include "pba/body.hpp"
#include "pba/mass_properties.hpp"
#include "pba/rotation.hpp"

namespace pba {

class RigidBody : public Body {
public:
    /// A unit cube of 1 kg at rest, unrotated.
    RigidBody();
    /// A body with these mass properties (its mass and its inertia about its centre of mass,
    /// in its own frame; the centre is taken as the body's position).
    explicit RigidBody(const MassProperties& properties);
    std::unique_ptr<Body> clone() const override { return std::make_unique<RigidBody>(*this); }

    // ---- get methods ----
    const dquat& getOrientation() const { return m_rotation.orientation; }
    /// Angular momentum L, world frame.
    const dvec3& getAngularMomentum() const { return m_rotation.momentum; }
    /// omega = I_world^-1 L, world frame.
    dvec3 getAngularVelocity() const;
    const dmat3& getInertiaBody() const { return m_inertiaBody; }
    const dmat3& getInverseInertiaBody() const { return m_inverseInertiaBody; }
    /// R I_body^-1 R^T: the inverse inertia in the world frame at the current orientation.
    dmat3 getInverseInertiaWorld() const;
    /// 1/2 omega . L.
    double getRotationalKineticEnergy() const;
    const Rotation& getRotation() const { return m_rotation; }

    // ---- set methods ----
    /// Sets the mass (Body::setMass) and the inertia tensor together. std::invalid_argument
    /// unless the inertia is symmetric positive definite.
    void setMassProperties(const MassProperties& properties);
    /// Normalised; std::invalid_argument for a zero or non-finite quaternion.
    void setOrientation(const dquat& q);
    void setAngularMomentum(const dvec3& momentum) { m_rotation.momentum = momentum; }
    /// Sets L = I_world omega (world frame) at the current orientation.
    void setAngularVelocity(const dvec3& omega);
    /// Orientation and momentum at once (what an integrator writes back).
    void setRotation(const Rotation& rotation);

private:
    Rotation m_rotation;
    dmat3 m_inertiaBody{1.0 / 6.0};
    dmat3 m_inverseInertiaBody{6.0};
};

} // namespace pba
