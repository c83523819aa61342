#include "pba/rigid_body.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "contact/narrow_phase.hpp"

namespace pba {

RigidBody::RigidBody() : RigidBody(Shape::box(dvec3(1.0)), 1.0) {}

RigidBody::RigidBody(const Shape& shape, double density) { setShape(shape, density); }

RigidBody::RigidBody(const MassProperties& properties)
{
    adoptShape(Shape::box(dvec3(1.0)));
    setMassProperties(properties);
}

void RigidBody::adoptShape(const Shape& shape)
{
    Form form{shape, contactPointsOf(shape), surfaceSamplesOf(shape), 0.0,
              std::make_shared<const contact::CollisionShape>(contact::CollisionShape::of(shape))};
    for (const dvec3& p : form.contactPoints)
        form.boundingRadius = std::max(form.boundingRadius, glm::length(p));
    if (shape.type == ShapeType::Sphere)
        form.boundingRadius = shape.radius;
    m_form = std::make_shared<const Form>(std::move(form));
    setMesh(drawMeshOf(shape));
}

void RigidBody::setShape(const Shape& shape, double density)
{
    setMassProperties(massPropertiesOf(shape, density));
    adoptShape(shape);
}

void RigidBody::setShapeWithMass(const Shape& shape, double mass)
{
    setMassProperties(massPropertiesOf(shape, 1.0).withMass(mass));
    adoptShape(shape);
}

void RigidBody::setFriction(double friction)
{
    if (!(friction >= 0.0 && std::isfinite(friction)))
        throw std::invalid_argument(fmt::format("a friction coefficient must be finite and non-negative, got {}", friction));
    m_friction = friction;
}

void RigidBody::setMassProperties(const MassProperties& properties)
{
    const dmat3& i = properties.inertia;
    // Symmetric, and positive definite by Sylvester's criterion (leading minors positive).
    const double scale = std::abs(i[0][0]) + std::abs(i[1][1]) + std::abs(i[2][2]);
    const bool symmetric = std::abs(i[0][1] - i[1][0]) <= 1e-12 * scale && std::abs(i[0][2] - i[2][0]) <= 1e-12 * scale &&
                           std::abs(i[1][2] - i[2][1]) <= 1e-12 * scale;
    const double minor2 = i[0][0] * i[1][1] - i[0][1] * i[1][0];
    if (!symmetric || !(i[0][0] > 0.0) || !(minor2 > 0.0) || !(glm::determinant(i) > 0.0) ||
        !std::isfinite(glm::determinant(i)))
        throw std::invalid_argument("an inertia tensor must be symmetric and positive definite");
    setMass(properties.mass);
    m_inertiaBody = i;
    m_inverseInertiaBody = glm::inverse(i);
}

dvec3 RigidBody::getAngularVelocity() const
{
    return angularVelocity(m_rotation.orientation, m_inverseInertiaBody, m_rotation.momentum);
}

dmat3 RigidBody::getInverseInertiaWorld() const
{
    const dmat3 r = glm::mat3_cast(m_rotation.orientation);
    return r * m_inverseInertiaBody * glm::transpose(r);
}

double RigidBody::getRotationalKineticEnergy() const
{
    return 0.5 * glm::dot(getAngularVelocity(), m_rotation.momentum);
}

void RigidBody::setOrientation(const dquat& q)
{
    const double length = glm::length(q);
    if (!(length > 0.0 && std::isfinite(length)))
        throw std::invalid_argument(
            fmt::format("an orientation must be a non-zero finite quaternion, got ({}, {}, {}, {})", q.w, q.x, q.y, q.z));
    m_rotation.orientation = q / length;
}

void RigidBody::setAngularVelocity(const dvec3& omega)
{
    const dmat3 r = glm::mat3_cast(m_rotation.orientation);
    m_rotation.momentum = r * (m_inertiaBody * (glm::transpose(r) * omega));
}

void RigidBody::setRotation(const Rotation& rotation)
{
    setOrientation(rotation.orientation);
    m_rotation.momentum = rotation.momentum;
}

} // namespace pba
