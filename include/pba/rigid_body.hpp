#pragma once
// A body with extent: the practical's "rigid bodies ... their density and inertia tensor". Its
// translation is Body's; it adds an orientation, the angular momentum and the inertia tensor.
#include <memory>

#include "pba/body.hpp"
#include "pba/mass_properties.hpp"
#include "pba/rotation.hpp"
#include "pba/shape.hpp"

namespace pba {

namespace contact {
struct CollisionShape;
}

/// The method a scene's rigid body takes unless it names one.
inline constexpr Integrator kDefaultRigidIntegrator = Integrator::Splitting;

class RigidBody : public Body {
public:
    /// A unit cube of 1 kg at rest, unrotated.
    RigidBody();
    /// A body of this shape at this uniform density (kg/m^3): its mass and inertia tensor are
    /// the shape's, its mesh is drawn from it. std::invalid_argument for a bad shape or density.
    RigidBody(const Shape& shape, double density);
    /// A body with these mass properties (its mass and its inertia about its centre of mass,
    /// in its own frame; the centre is taken as the body's position), shaped as a unit cube.
    explicit RigidBody(const MassProperties& properties);
    std::unique_ptr<Body> clone() const override { return std::make_unique<RigidBody>(*this); }
    /// The shape's surface samples (a sphere's fixed in the world's orientation).
    Surface surface() const override { return {m_form->surfaceSamples, m_form->shape.type != ShapeType::Sphere}; }

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
    const Shape& getShape() const { return m_form->shape; }
    /// The shape's contact points (contactPointsOf), body frame, about the centre of mass.
    const std::vector<dvec3>& getContactPoints() const { return m_form->contactPoints; }
    /// How far the shape reaches from its centre of mass.
    double getBoundingRadius() const { return m_form->boundingRadius; }
    /// Coulomb friction coefficient (against the room its own; against another body combined
    /// with the other's, see docs/scenes.md).
    double getFriction() const { return m_friction; }
    /// The shape as the contact pipeline sees it (a mesh as its convex hull), shared by copies.
    const std::shared_ptr<const contact::CollisionShape>& getCollisionShape() const { return m_form->collision; }

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
    /// The shape and its mass properties at `density`, its contact points and its mesh.
    void setShape(const Shape& shape, double density);
    /// The shape with the given mass instead of a density.
    void setShapeWithMass(const Shape& shape, double mass);
    /// std::invalid_argument unless finite and non-negative.
    void setFriction(double friction);
private:
    void adoptShape(const Shape& shape);

    Rotation m_rotation;
    /// What the shape gives the body and never changes: shared by copies of the body (10,000
    /// copied dice read one set of corners, which stays in cache).
    struct Form {
        Shape shape;
        std::vector<dvec3> contactPoints;
        std::vector<SurfaceSample> surfaceSamples;
        double boundingRadius = 0.0;
        std::shared_ptr<const contact::CollisionShape> collision;
    };
    std::shared_ptr<const Form> m_form;
    double m_friction = 0.5;
    dmat3 m_inertiaBody{1.0 / 6.0};
    dmat3 m_inverseInertiaBody{6.0};
};

} // namespace pba
